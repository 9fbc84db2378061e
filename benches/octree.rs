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
mod cell_list;
