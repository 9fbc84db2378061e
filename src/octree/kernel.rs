//! The spheres in tree order, and the innermost loops of the pair walk over them.

use super::boundary::{spheres_intersect, Aabb};
use super::Pair;
use std::ops::Range;

/// Width of the blocks the kernels test before branching, at most 32 (the bits of a
/// block's mask): a fixed trip count lets the compiler unroll and vectorise the block.
/// 16 walked the pair list of `benches/scale/hundred_thousand.toml`'s packing (1.17 M
/// pairs) in 27 ms, 8 in 32 ms, 32 and 64 as 16 (BENCHMARKS.md, "Issue 26: the list
/// build's kernel and serial parts").
const BLOCK: usize = 16;

/// The stored spheres in tree order as separate arrays (structure of arrays), so that
/// the kernels stream through them; every node owns a contiguous range.
#[derive(Debug, Clone, Default)]
pub(crate) struct Lanes {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub z: Vec<f64>,
    pub r: Vec<f64>,
    pub id: Vec<u32>,
}

impl Lanes {
    pub fn len(&self) -> usize {
        self.id.len()
    }

    /// Sets the length to `n`; new slots hold zeros until [`Window::set`].
    pub fn resize(&mut self, n: usize) {
        for v in [&mut self.x, &mut self.y, &mut self.z, &mut self.r] {
            v.resize(n, 0.0);
        }
        self.id.resize(n, 0);
    }

    /// All the spheres as a window the build fills.
    pub fn window(&mut self) -> Window<'_> {
        Window {
            x: &mut self.x,
            y: &mut self.y,
            z: &mut self.z,
            r: &mut self.r,
            id: &mut self.id,
            offset: 0,
        }
    }

    #[inline]
    pub fn centre(&self, k: usize) -> [f64; 3] {
        [self.x[k], self.y[k], self.z[k]]
    }

    #[inline]
    pub fn aabb(&self, k: usize) -> Aabb {
        Aabb::of_sphere(self.centre(k), self.r[k])
    }

    /// The spheres of `run` as a view.
    #[inline]
    pub fn view(&self, run: Range<usize>) -> View<'_> {
        View {
            x: &self.x[run.clone()],
            y: &self.y[run.clone()],
            z: &self.z[run.clone()],
            r: &self.r[run.clone()],
            id: &self.id[run],
        }
    }
}

/// The spheres of [`Lanes`] from `offset` on, as the build writes them: windows of
/// disjoint runs are filled by parallel tasks.
pub(crate) struct Window<'a> {
    x: &'a mut [f64],
    y: &'a mut [f64],
    z: &'a mut [f64],
    r: &'a mut [f64],
    id: &'a mut [u32],
    offset: usize,
}

impl<'a> Window<'a> {
    /// A window on nothing.
    pub fn empty() -> Self {
        Window {
            x: &mut [],
            y: &mut [],
            z: &mut [],
            r: &mut [],
            id: &mut [],
            offset: 0,
        }
    }

    /// Sets sphere `k` (counted in the whole lanes).
    pub fn set(&mut self, k: usize, centre: [f64; 3], radius: f64, id: u32) {
        let k = k - self.offset;
        (self.x[k], self.y[k], self.z[k]) = (centre[0], centre[1], centre[2]);
        (self.r[k], self.id[k]) = (radius, id);
    }

    /// The window before sphere `k` (counted in the whole lanes) and the one from it.
    pub fn split_at(self, k: usize) -> (Self, Self) {
        let at = k - self.offset;
        let (x, x2) = self.x.split_at_mut(at);
        let (y, y2) = self.y.split_at_mut(at);
        let (z, z2) = self.z.split_at_mut(at);
        let (r, r2) = self.r.split_at_mut(at);
        let (id, id2) = self.id.split_at_mut(at);
        let head = Window {
            x,
            y,
            z,
            r,
            id,
            offset: self.offset,
        };
        let tail = Window {
            x: x2,
            y: y2,
            z: z2,
            r: r2,
            id: id2,
            offset: k,
        };
        (head, tail)
    }
}

/// One sphere, the first of the pair tests a kernel runs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Probe {
    pub centre: [f64; 3],
    pub radius: f64,
    pub id: u32,
}

/// A run of spheres as borrowed arrays.
#[derive(Debug, Clone, Copy)]
pub(crate) struct View<'a> {
    pub x: &'a [f64],
    pub y: &'a [f64],
    pub z: &'a [f64],
    pub r: &'a [f64],
    pub id: &'a [u32],
}

impl<'a> View<'a> {
    pub fn len(&self) -> usize {
        self.id.len()
    }

    /// The view without its first `k` spheres.
    #[inline]
    pub fn tail(&self, k: usize) -> View<'a> {
        View {
            x: &self.x[k..],
            y: &self.y[k..],
            z: &self.z[k..],
            r: &self.r[k..],
            id: &self.id[k..],
        }
    }

    /// Sphere `k` of the view as the first of a pair test.
    #[inline]
    pub fn probe(&self, k: usize) -> Probe {
        Probe {
            centre: [self.x[k], self.y[k], self.z[k]],
            radius: self.r[k],
            id: self.id[k],
        }
    }

    /// Calls `f(k)` for every sphere `k` of the view whose box `c ± r` meets the closed
    /// box `[lo, hi]`, testing blocks without branches so that they vectorise.
    #[inline]
    pub fn for_each_reaching(&self, lo: [f64; 3], hi: [f64; 3], mut f: impl FnMut(usize)) {
        let reaches = |k: usize| {
            let r = self.r[k];
            let (x, y, z) = (self.x[k], self.y[k], self.z[k]);
            (x - r <= hi[0])
                & (lo[0] <= x + r)
                & (y - r <= hi[1])
                & (lo[1] <= y + r)
                & (z - r <= hi[2])
                & (lo[2] <= z + r)
        };
        self.for_each_hit(reaches, &mut f);
    }

    /// Calls `f(k)` for every sphere `k` of the view that passes `test`, in order,
    /// evaluating `test` on whole blocks of [`BLOCK`] spheres into a bit mask, without
    /// branches, so that it vectorises, and calling `f` only for the hits.
    #[inline(always)]
    fn for_each_hit(&self, test: impl Fn(usize) -> bool, mut f: impl FnMut(usize)) {
        let mut base = 0;
        while base < self.len() {
            let width = (self.len() - base).min(BLOCK);
            let mut hits = 0u32;
            if width == BLOCK {
                for k in 0..BLOCK {
                    hits |= u32::from(test(base + k)) << k;
                }
            } else {
                for k in 0..width {
                    hits |= u32::from(test(base + k)) << k;
                }
            }
            while hits != 0 {
                f(base + hits.trailing_zeros() as usize);
                hits &= hits - 1;
            }
            base += width;
        }
    }

    /// Pushes every pair of `a` with a sphere of the view that it meets without a
    /// shift, ids in order. The test is [`spheres_intersect`] with `a` first, which
    /// with a zero shift gives the same answer as with the other first
    /// (`cj − ci = −(ci − cj)` exactly, and the sum of radii commutes).
    #[inline]
    pub fn zero_shift_pairs(&self, a: Probe, out: &mut Vec<Pair>) {
        let hit = |k: usize| {
            let c = [self.x[k], self.y[k], self.z[k]];
            spheres_intersect(a.centre, a.radius, c, self.r[k], [0.0; 3])
        };
        self.for_each_hit(hit, |k| {
            let b = self.id[k];
            out.push(Pair {
                i: a.id.min(b),
                j: a.id.max(b),
                image: [0; 3],
            });
        });
    }

    /// Pushes every pair of `a` with a sphere `b` of the view moved by `s ≠ 0`. The
    /// test runs with the lower id first, as
    /// [`brute_force_pairs`](super::brute_force_pairs) does: `(a, b, s)` with
    /// `id_a > id_b` is the pair `(b, a, −s)`, and `minus_s` must be `−s` computed as
    /// `0 − s` (bit-identical to the shift of image `−k`); `image` is `k`.
    pub fn shifted_pairs(
        &self,
        a: Probe,
        (s, minus_s): ([f64; 3], [f64; 3]),
        image: [i8; 3],
        out: &mut Vec<Pair>,
    ) {
        for k in 0..self.len() {
            let (c, r, b) = ([self.x[k], self.y[k], self.z[k]], self.r[k], self.id[k]);
            if a.id <= b {
                if spheres_intersect(a.centre, a.radius, c, r, s) {
                    out.push(Pair {
                        i: a.id,
                        j: b,
                        image,
                    });
                }
            } else if spheres_intersect(c, r, a.centre, a.radius, minus_s) {
                out.push(Pair {
                    i: b,
                    j: a.id,
                    image: image.map(|x| -x),
                });
            }
        }
    }
}
