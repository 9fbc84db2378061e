//! Broad-phase benchmark: octree against a uniform-grid cell list and brute force.
//!
//! `cargo bench --bench octree` runs n = 1e3, 1e4, 1e5, 1e6; restrict with arguments
//! (`cargo bench --bench octree -- 1000 10000`) or `OCTREE_BENCH_SIZES=1000,10000`.
//! Scenes: random centres (overlaps allowed), lognormal radii (median 1, σ from
//! `OCTREE_BENCH_SIGMA`, default 0.3), cubic box sized for a volume fraction
//! Σ(4/3 π r³) / V = 0.6. Times are medians of repeats (and the best total, as the
//! machine may be shared); "build" is a rebuild reusing the tree's buffers, as the
//! packing loop does each step. The table is markdown; every method must find the
//! same number of pairs, or the run stops.

use grainpack::octree::{brute_force_pairs, BoxShape, Octree, Pair, Params, Sphere};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, LogNormal};
use std::time::{Duration, Instant};

const VOLUME_FRACTION: f64 = 0.6;
const DEFAULT_SIGMA: f64 = 0.3;
const DEFAULT_SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];
/// Brute force runs only up to this size (O(n²)).
const BRUTE_MAX: usize = 10_000;

fn main() {
    let sizes = sizes();
    let sigma = std::env::var("OCTREE_BENCH_SIGMA")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_SIGMA);
    println!(
        "volume fraction {VOLUME_FRACTION}, lognormal radii median 1 σ {sigma}, rayon threads {}\n",
        rayon::current_num_threads()
    );
    println!("| n | boundary | method | build ms | query ms | total ms | best total ms | pairs | sphere tests | ns/pair | ns/grain | cell list ÷ this | brute ÷ this |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for &n in &sizes {
        let (spheres, l) = scene(n, sigma, 42);
        let r_max = spheres.iter().map(|s| s.radius).fold(0.0, f64::max);
        let r_min = spheres
            .iter()
            .map(|s| s.radius)
            .fold(f64::INFINITY, f64::min);
        eprintln!(
            "n = {n}: box {l:.1}, radii {r_min:.3}..{r_max:.3} (ratio {:.1})",
            r_max / r_min
        );
        for shape in [
            BoxShape::periodic([l; 3]).unwrap(),
            BoxShape::reflecting([l; 3]).unwrap(),
        ] {
            bench_one(&spheres, shape);
        }
    }
}

fn sizes() -> Vec<usize> {
    let from_args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    if !from_args.is_empty() {
        return from_args;
    }
    match std::env::var("OCTREE_BENCH_SIZES") {
        Ok(s) => s.split(',').filter_map(|x| x.trim().parse().ok()).collect(),
        Err(_) => DEFAULT_SIZES.to_vec(),
    }
}

/// `n` spheres with lognormal radii and uniform centres in a cube of side `l` chosen
/// for the volume fraction.
fn scene(n: usize, sigma: f64, seed: u64) -> (Vec<Sphere>, f64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let dist = LogNormal::new(0.0, sigma).unwrap();
    let radii: Vec<f64> = (0..n).map(|_| dist.sample(&mut rng)).collect();
    let volume: f64 = radii
        .iter()
        .map(|r| 4.0 / 3.0 * std::f64::consts::PI * r * r * r)
        .sum();
    let l = (volume / VOLUME_FRACTION).cbrt();
    let spheres = radii
        .into_iter()
        .enumerate()
        .map(|(id, radius)| Sphere {
            id: id as u32,
            centre: [0; 3].map(|_| rng.random::<f64>() * l),
            radius,
        })
        .collect();
    (spheres, l)
}

/// The default parameters, with `OCTREE_BENCH_LEAF` and `OCTREE_BENCH_LOOSE` overriding
/// the leaf size and loose factor (for tuning the defaults).
fn tuned() -> Params {
    let env = |name: &str| std::env::var(name).ok().and_then(|s| s.parse::<f64>().ok());
    let mut params = Params::default();
    if let Some(leaf) = env("OCTREE_BENCH_LEAF") {
        params.max_leaf_size = leaf as usize;
    }
    if let Some(loose) = env("OCTREE_BENCH_LOOSE") {
        params.loose_factor = loose;
    }
    params
}

/// `OCTREE_BENCH_QUICK=1`: only the one-thread octree, 21 repeats, for tuning the
/// defaults (compare the minimum times on a shared machine).
fn quick() -> bool {
    std::env::var_os("OCTREE_BENCH_QUICK").is_some()
}

fn repeats(n: usize) -> usize {
    if quick() {
        return 21;
    }
    match n {
        0..=2_000 => 31,
        2_001..=20_000 => 11,
        20_001..=200_000 => 5,
        _ => 3,
    }
}

/// Median and minimum wall time of `reps` runs of `f`, and the last run's result.
fn timed<T>(reps: usize, mut f: impl FnMut() -> T) -> (Duration, Duration, T) {
    let mut times = Vec::with_capacity(reps);
    let mut last = None;
    for _ in 0..reps {
        let t = Instant::now();
        last = Some(std::hint::black_box(f()));
        times.push(t.elapsed());
    }
    times.sort();
    (times[reps / 2], times[0], last.unwrap())
}

struct Row {
    method: String,
    build: Duration,
    query: Duration,
    /// Fastest build + fastest query.
    best: Duration,
    pairs: usize,
    tests: u64,
}

fn bench_one(spheres: &[Sphere], shape: BoxShape) {
    let n = spheres.len();
    let reps = repeats(n);
    let mut rows = Vec::new();
    let mut out: Vec<Pair> = Vec::new();
    let rayon = format!("octree, rayon ({} threads)", rayon::current_num_threads());
    for (parallel, label) in [(false, "octree, 1 thread"), (true, rayon.as_str())] {
        let params = Params {
            parallel,
            ..tuned()
        };
        // Build once, then time rebuilds that reuse the buffers, as the packing loop does.
        let mut tree = Octree::build(spheres, shape, params).unwrap();
        let (build, build_min, ()) = timed(reps, || tree.rebuild(spheres).unwrap());
        let (query, query_min, stats) = timed(reps, || tree.pairs(&mut out));
        eprintln!(
            "  {label}: {} nodes, depth {}, {stats:?}",
            tree.node_count(),
            tree.depth()
        );
        if quick() {
            let t = (build_min + query_min).as_secs_f64() * 1e3;
            let (b, q) = (build_min.as_secs_f64() * 1e3, query_min.as_secs_f64() * 1e3);
            println!(
                "| {n} | {:?} | {label} | {b:.3} | {q:.3} | {t:.3} |",
                shape.boundary
            );
            return;
        }
        rows.push(Row {
            method: label.into(),
            build,
            query,
            best: build_min + query_min,
            pairs: out.len(),
            tests: stats.sphere_tests,
        });
    }
    let (build, build_min, cells) = timed(reps, || cell_list::CellList::build(spheres, &shape));
    let (query, query_min, tests) = timed(reps, || cells.pairs(&mut out));
    rows.push(Row {
        method: "cell list, 1 thread".into(),
        build,
        query,
        best: build_min + query_min,
        pairs: out.len(),
        tests,
    });
    if n <= BRUTE_MAX {
        let (query, best, ()) = timed(reps.min(3), || {
            brute_force_pairs(spheres, &shape, &mut out).unwrap()
        });
        let tests = (n * (n - 1) / 2) as u64;
        rows.push(Row {
            method: "brute force, 1 thread".into(),
            build: Duration::ZERO,
            query,
            best,
            pairs: out.len(),
            tests,
        });
    }
    let total = |r: &Row| (r.build + r.query).as_secs_f64();
    let cell = total(&rows[2]);
    let brute = rows.get(3).map(total);
    for r in &rows {
        assert_eq!(
            r.pairs, rows[0].pairs,
            "{} disagrees on the pair count",
            r.method
        );
        let t = total(r);
        println!(
            "| {n} | {:?} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {} | {} | {:.1} | {:.1} | {:.2} | {} |",
            shape.boundary,
            r.method,
            r.build.as_secs_f64() * 1e3,
            r.query.as_secs_f64() * 1e3,
            t * 1e3,
            r.best.as_secs_f64() * 1e3,
            r.pairs,
            r.tests,
            t * 1e9 / r.pairs.max(1) as f64,
            t * 1e9 / n as f64,
            cell / t,
            brute.map_or("–".into(), |b| format!("{:.1}", b / t)),
        );
    }
}

/// The baseline: a uniform grid of cells at least `2 r_max` wide, so intersecting
/// spheres sit in the same or adjacent cells, with the octree's pair definition.
mod cell_list {
    use grainpack::octree::{spheres_intersect, BoxShape, Pair, Sphere};

    /// Cells are `2 r_max · (1 + CELL_SLACK)` wide at least, so that rounding in the
    /// cell index can never put two touching spheres two cells apart.
    const CELL_SLACK: f64 = 1e-9;

    pub struct CellList {
        shape: BoxShape,
        dims: [usize; 3],
        /// CSR: spheres of cell `c` are `start[c]..start[c + 1]` of the arrays below.
        start: Vec<u32>,
        ids: Vec<u32>,
        centres: Vec<[f64; 3]>,
        radii: Vec<f64>,
    }

    impl CellList {
        pub fn build(spheres: &[Sphere], shape: &BoxShape) -> Self {
            let centres: Vec<[f64; 3]> = spheres.iter().map(|s| shape.wrap(s.centre)).collect();
            let r_max = spheres.iter().map(|s| s.radius).fold(0.0, f64::max);
            let (mut lo, mut hi) = ([0.0; 3], shape.lengths);
            if !shape.is_periodic() {
                for c in &centres {
                    for a in 0..3 {
                        lo[a] = f64::min(lo[a], c[a]);
                        hi[a] = f64::max(hi[a], c[a]);
                    }
                }
            }
            let want = 2.0 * r_max * (1.0 + CELL_SLACK);
            let dims = [0, 1, 2].map(|a| (((hi[a] - lo[a]) / want).floor() as usize).max(1));
            let side = [0, 1, 2].map(|a| (hi[a] - lo[a]) / dims[a] as f64);
            assert!(
                side.iter().all(|&s| s >= want),
                "box too small for a cell list"
            );
            let cell_of = |c: &[f64; 3]| {
                let i = [0, 1, 2].map(|a| (((c[a] - lo[a]) / side[a]) as usize).min(dims[a] - 1));
                (i[2] * dims[1] + i[1]) * dims[0] + i[0]
            };
            let cells: Vec<usize> = centres.iter().map(cell_of).collect();
            let mut start = vec![0u32; dims.iter().product::<usize>() + 1];
            for &c in &cells {
                start[c + 1] += 1;
            }
            for c in 1..start.len() {
                start[c] += start[c - 1];
            }
            let mut cursor = start.clone();
            let n = spheres.len();
            let (mut ids, mut sorted, mut radii) = (vec![0; n], vec![[0.0; 3]; n], vec![0.0; n]);
            for (k, &c) in cells.iter().enumerate() {
                let slot = cursor[c] as usize;
                cursor[c] += 1;
                (ids[slot], sorted[slot], radii[slot]) =
                    (spheres[k].id, centres[k], spheres[k].radius);
            }
            Self {
                shape: *shape,
                dims,
                start,
                ids,
                centres: sorted,
                radii,
            }
        }

        /// Clears `out`, fills it with the pairs, returns how many sphere pairs were tested.
        pub fn pairs(&self, out: &mut Vec<Pair>) -> u64 {
            out.clear();
            let d = self.dims;
            let mut tests = 0;
            for iz in 0..d[2] {
                for iy in 0..d[1] {
                    for ix in 0..d[0] {
                        let a = (iz * d[1] + iy) * d[0] + ix;
                        tests += self.within(a, out);
                        for o in neighbour_offsets() {
                            let Some((b, k)) = self.neighbour([ix, iy, iz], o) else {
                                continue;
                            };
                            // (a, b, k) and (b, a, −k) are the same cell pair: keep one.
                            if a < b || (a == b && positive(k)) {
                                tests += self.between(a, b, k, out);
                            }
                        }
                    }
                }
            }
            tests
        }

        /// The cell at `i + o` and the image it is taken from, if it exists.
        fn neighbour(&self, i: [usize; 3], o: [i32; 3]) -> Option<(usize, [i32; 3])> {
            let mut j = [0usize; 3];
            let mut k = [0i32; 3];
            for a in 0..3 {
                let n = self.dims[a] as i64;
                let mut x = i[a] as i64 + i64::from(o[a]);
                if x < 0 || x >= n {
                    if !self.shape.is_periodic() {
                        return None;
                    }
                    k[a] = if x < 0 { -1 } else { 1 };
                    x -= i64::from(k[a]) * n;
                }
                j[a] = x as usize;
            }
            Some(((j[2] * self.dims[1] + j[1]) * self.dims[0] + j[0], k))
        }

        fn within(&self, a: usize, out: &mut Vec<Pair>) -> u64 {
            let r = self.start[a] as usize..self.start[a + 1] as usize;
            for x in r.clone() {
                for y in x + 1..r.end {
                    let (x, y) = if self.ids[x] < self.ids[y] {
                        (x, y)
                    } else {
                        (y, x)
                    };
                    if spheres_intersect(
                        self.centres[x],
                        self.radii[x],
                        self.centres[y],
                        self.radii[y],
                        [0.0; 3],
                    ) {
                        out.push(Pair {
                            i: self.ids[x],
                            j: self.ids[y],
                            image: [0; 3],
                        });
                    }
                }
            }
            (r.len() * r.len().saturating_sub(1) / 2) as u64
        }

        fn between(&self, a: usize, b: usize, k: [i32; 3], out: &mut Vec<Pair>) -> u64 {
            let s = self.shape.shift(k);
            let image = k.map(|x| x as i8);
            let ra = self.start[a] as usize..self.start[a + 1] as usize;
            let rb = self.start[b] as usize..self.start[b + 1] as usize;
            let minus_s = s.map(|x| 0.0 - x);
            for x in ra.clone() {
                for y in rb.clone() {
                    let (ix, iy) = (self.ids[x], self.ids[y]);
                    let (cx, rx, cy, ry) = (
                        self.centres[x],
                        self.radii[x],
                        self.centres[y],
                        self.radii[y],
                    );
                    if ix <= iy {
                        if spheres_intersect(cx, rx, cy, ry, s) {
                            out.push(Pair {
                                i: ix,
                                j: iy,
                                image,
                            });
                        }
                    } else if spheres_intersect(cy, ry, cx, rx, minus_s) {
                        out.push(Pair {
                            i: iy,
                            j: ix,
                            image: image.map(|x| -x),
                        });
                    }
                }
            }
            (ra.len() * rb.len()) as u64
        }
    }

    fn neighbour_offsets() -> impl Iterator<Item = [i32; 3]> {
        (0..27)
            .map(|c| [c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1])
            .filter(|o| *o != [0; 3])
    }

    fn positive(k: [i32; 3]) -> bool {
        k[0] > 0 || (k[0] == 0 && (k[1] > 0 || (k[1] == 0 && k[2] > 0)))
    }
}
