//! The octree benchmark's baseline: a uniform grid of cells at least `2 r_max` wide, so
//! intersecting spheres sit in the same or adjacent cells, with the octree's pair
//! definition.

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
            (ids[slot], sorted[slot], radii[slot]) = (spheres[k].id, centres[k], spheres[k].radius);
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
