//! The box, its boundary, periodic images and the exact sphere predicate.

use super::OctreeError;

/// How the faces of the box behave.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Boundary {
    /// Opposite faces are glued: a grain near one face touches grains near the opposite
    /// one through the image shifted by a multiple of the box lengths.
    Periodic,
    /// The faces are walls: no images exist and every shift is zero.
    Reflecting,
}

/// An axis-aligned box `[0, Lx) × [0, Ly) × [0, Lz)` and its boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxShape {
    /// Edge lengths `[Lx, Ly, Lz]`, each positive and finite.
    pub lengths: [f64; 3],
    /// Periodic or walled.
    pub boundary: Boundary,
}

impl BoxShape {
    /// A box with the given edge lengths, checked to be positive and finite.
    ///
    /// ```
    /// use grainpack::octree::{Boundary, BoxShape};
    /// let b = BoxShape::new([2.0, 1.0, 1.0], Boundary::Periodic).unwrap();
    /// assert_eq!(b.wrap([-0.5, 1.25, 0.5]), [1.5, 0.25, 0.5]);
    /// assert!(BoxShape::new([1.0, 0.0, 1.0], Boundary::Periodic).is_err());
    /// ```
    pub fn new(lengths: [f64; 3], boundary: Boundary) -> Result<Self, OctreeError> {
        let shape = Self { lengths, boundary };
        shape.validate()?;
        Ok(shape)
    }

    /// A periodic box; see [`BoxShape::new`].
    pub fn periodic(lengths: [f64; 3]) -> Result<Self, OctreeError> {
        Self::new(lengths, Boundary::Periodic)
    }

    /// A walled box; see [`BoxShape::new`].
    pub fn reflecting(lengths: [f64; 3]) -> Result<Self, OctreeError> {
        Self::new(lengths, Boundary::Reflecting)
    }

    /// Checks that every edge length is positive and finite (the fields are public, so
    /// [`Octree::build`](super::Octree::build) checks again).
    pub fn validate(&self) -> Result<(), OctreeError> {
        for (axis, &value) in self.lengths.iter().enumerate() {
            if !(value.is_finite() && value > 0.0) {
                return Err(OctreeError::InvalidBoxLength { axis, value });
            }
        }
        Ok(())
    }

    /// True for a periodic box.
    pub fn is_periodic(&self) -> bool {
        self.boundary == Boundary::Periodic
    }

    /// The centre the broad phase works with: in a periodic box each coordinate is
    /// reduced into `[0, L)` by `x − L·floor(x/L)` (`f64::rem_euclid`), which leaves a
    /// coordinate already in `[0, L)` bit-for-bit unchanged; a tiny negative `x` that
    /// rounds to `L` maps to `0`. A walled box returns the centre unchanged.
    ///
    /// Every shift the octree reports refers to wrapped centres.
    pub fn wrap(&self, centre: [f64; 3]) -> [f64; 3] {
        if !self.is_periodic() {
            return centre;
        }
        let mut out = centre;
        for (x, &l) in out.iter_mut().zip(&self.lengths) {
            if !(0.0..l).contains(x) {
                *x = wrap_coordinate(*x, l); // slow (an fmod): only off the fast path
            }
        }
        out
    }

    /// The shift vector of periodic image `k`: `[k0·Lx, k1·Ly, k2·Lz]`, computed exactly
    /// this way everywhere so that equal images give bit-identical shifts.
    pub fn shift(&self, image: [i32; 3]) -> [f64; 3] {
        [
            f64::from(image[0]) * self.lengths[0],
            f64::from(image[1]) * self.lengths[1],
            f64::from(image[2]) * self.lengths[2],
        ]
    }
}

/// `x` moved into `[0, l)` by a multiple of `l`: `x − l·floor(x/l)` (`f64::rem_euclid`),
/// which leaves `x` in `[0, l)` bit-for-bit unchanged; a tiny negative `x` whose
/// remainder rounds to `l` itself maps to `0`. The one periodic wrap of the crate.
///
/// ```
/// use grainpack::octree::wrap_coordinate;
/// assert_eq!(wrap_coordinate(-1e-20, 2.0), 0.0);
/// assert_eq!(wrap_coordinate(2.5, 2.0), 0.5);
/// ```
pub fn wrap_coordinate(x: f64, l: f64) -> f64 {
    let w = x.rem_euclid(l);
    if w >= l {
        0.0
    } else {
        w
    }
}

/// Whether sphere `j`, moved by `shift`, meets sphere `i`: with
/// `r_ij = (c_j + shift) − c_i`, the test is `|r_ij|² ≤ (r_i + r_j)²`. Touching counts.
///
/// This is the one predicate of the broad phase: the octree and
/// [`brute_force_pairs`](super::brute_force_pairs) both evaluate it, always with the
/// lower id as `i`, so their floating-point results agree bit for bit.
///
/// ```
/// use grainpack::octree::spheres_intersect;
/// assert!(spheres_intersect([0.0; 3], 1.0, [2.0, 0.0, 0.0], 1.0, [0.0; 3])); // touching
/// assert!(spheres_intersect([0.05, 0.0, 0.0], 0.1, [9.9, 0.0, 0.0], 0.1, [-10.0, 0.0, 0.0]));
/// ```
#[inline]
pub fn spheres_intersect(ci: [f64; 3], ri: f64, cj: [f64; 3], rj: f64, shift: [f64; 3]) -> bool {
    let dx = (cj[0] + shift[0]) - ci[0];
    let dy = (cj[1] + shift[1]) - ci[1];
    let dz = (cj[2] + shift[2]) - ci[2];
    let reach = ri + rj;
    dx * dx + dy * dy + dz * dz <= reach * reach
}

/// Whether image `k` is in the half of the lattice that the octree searches:
/// lexicographically positive (`k0 > 0`, or `k0 = 0, k1 > 0`, or `k0 = k1 = 0, k2 > 0`).
/// Exactly one of `k` and `−k` is, for `k ≠ 0`.
pub(crate) fn is_positive_image(k: [i32; 3]) -> bool {
    k[0] > 0 || (k[0] == 0 && (k[1] > 0 || (k[1] == 0 && k[2] > 0)))
}

/// Image `k` as a [`Pair`](super::Pair) stores it. The images tried are bounded by
/// [`MAX_IMAGES_PER_AXIS`](super::MAX_IMAGES_PER_AXIS) (checked when a tree is built
/// and by the brute-force reference's validation), far inside `i8`.
#[inline]
pub(crate) fn small_image(k: [i32; 3]) -> [i8; 3] {
    k.map(|x| x as i8)
}

/// The integers `k` for which `k·l` may lie in `[lo, hi]`: `floor(lo/l) ..= ceil(hi/l)`.
///
/// Rounding the quotients cannot drop a `k` (`floor` of the rounded `lo/l` never exceeds
/// `ceil` of the exact one), and any `k` left out has `k·l` a whole `l` outside
/// `[lo, hi]`, far beyond what rounding in [`spheres_intersect`] could accept.
pub(crate) fn image_range(lo: f64, hi: f64, l: f64) -> std::ops::RangeInclusive<i32> {
    // `as` saturates; the sizes are bounded by `MAX_IMAGES_PER_AXIS` at build time.
    (lo / l).floor() as i32..=(hi / l).ceil() as i32
}

/// Slack added to every box-overlap test, in units of `f64::EPSILON · M`, where `M` is
/// the largest coordinate magnitude in play (root bounds plus the largest shift).
///
/// Why this is enough: [`spheres_intersect`] rounds `(c_j + s) − c_i` by at most
/// `2ε·M` per axis and `|r_ij|² ≤ (r_i + r_j)²` by at most `3ε` relatively, node bounds
/// are rounded `c ± r` (half an ulp of `M`) and the overlap test rounds `lo + s` once
/// more; the sum is below `8ε·M` since every radius is below `M`. Twice that is used.
pub(crate) const OVERLAP_TOL_ULPS: f64 = 16.0;

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Aabb {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

impl Aabb {
    /// The empty box, the identity of [`Aabb::union`].
    pub const EMPTY: Self = Self {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    /// The bounding box of a sphere, `c ± r` rounded to nearest.
    #[inline]
    pub fn of_sphere(c: [f64; 3], r: f64) -> Self {
        Self {
            lo: [c[0] - r, c[1] - r, c[2] - r],
            hi: [c[0] + r, c[1] + r, c[2] + r],
        }
    }

    /// The smallest box containing both.
    #[inline]
    pub fn union(&self, other: &Self) -> Self {
        let mut out = *self;
        for a in 0..3 {
            out.lo[a] = out.lo[a].min(other.lo[a]);
            out.hi[a] = out.hi[a].max(other.hi[a]);
        }
        out
    }

    /// Whether `other` lies inside `self` (closed boxes, exact comparison).
    pub fn contains(&self, other: &Self) -> bool {
        (0..3).all(|a| self.lo[a] <= other.lo[a] && other.hi[a] <= self.hi[a])
    }

    /// Whether `self` and `other + shift` may overlap, allowing `tol` of slack per axis:
    /// false only if they are apart by more than `tol` along some axis. (All six tests
    /// run, joined by `&`: no branches to mispredict.)
    #[inline]
    pub fn overlaps_shifted(&self, other: &Self, shift: [f64; 3], tol: f64) -> bool {
        let overlap = |a: usize| {
            (self.lo[a] <= other.hi[a] + shift[a] + tol)
                & (other.lo[a] + shift[a] - tol <= self.hi[a])
        };
        overlap(0) & overlap(1) & overlap(2)
    }

    /// The largest coordinate magnitude, `max |lo|, |hi|` over the axes.
    pub fn magnitude(&self) -> f64 {
        (0..3).fold(0.0_f64, |m, a| {
            m.max(self.lo[a].abs()).max(self.hi[a].abs())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_leaves_centres_inside_the_box_bit_for_bit() {
        let b = BoxShape::periodic([1.0, 3.0, 0.7]).unwrap();
        for c in [
            [0.0, 0.0, 0.0],
            [0.999_999, 2.999_999, 0.699_999],
            [0.1, 0.2, 0.3],
        ] {
            assert_eq!(b.wrap(c), c);
        }
    }

    #[test]
    fn wrap_maps_every_centre_into_the_half_open_box() {
        let b = BoxShape::periodic([1.0, 3.0, 0.7]).unwrap();
        for c in [[1.0, 3.0, 0.7], [-1e-300, -1e-17, -5.2], [17.25, -3.0, 1.4]] {
            let w = b.wrap(c);
            for a in 0..3 {
                assert!((0.0..b.lengths[a]).contains(&w[a]), "{c:?} -> {w:?}");
            }
        }
        assert_eq!(b.wrap([-1e-17, 3.0, 0.35 - 0.7]), [0.0, 0.0, 0.35]);
    }

    #[test]
    fn walls_never_wrap() {
        let b = BoxShape::reflecting([1.0; 3]).unwrap();
        assert_eq!(b.wrap([-2.0, 5.0, 0.5]), [-2.0, 5.0, 0.5]);
    }

    #[test]
    fn exactly_one_of_an_image_and_its_opposite_is_positive() {
        for k0 in -2..=2 {
            for k1 in -2..=2 {
                for k2 in -2..=2 {
                    let (k, minus_k) = ([k0, k1, k2], [-k0, -k1, -k2]);
                    let count =
                        usize::from(is_positive_image(k)) + usize::from(is_positive_image(minus_k));
                    assert_eq!(count, usize::from(k != [0; 3]), "{k:?}");
                }
            }
        }
    }

    #[test]
    fn image_range_covers_every_multiple_in_the_interval() {
        for (lo, hi, l) in [
            (-0.3, 0.3, 1.0),
            (-2.0, 2.0, 1.0),
            (0.5, 0.7, 0.25),
            (-1e-17, 1e-17, 1.0),
        ] {
            let range = image_range(lo, hi, l);
            for k in -20..=20 {
                let x = f64::from(k) * l;
                if lo <= x && x <= hi {
                    assert!(
                        range.contains(&k),
                        "{k} missing from {range:?} for [{lo}, {hi}] / {l}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_zero_shift_test_does_not_depend_on_which_sphere_comes_first() {
        let (a, b) = ([0.1, 0.7, 0.3], [0.35, 0.52, 0.41]);
        for r in [0.1, 0.17, 0.2, 0.25] {
            assert_eq!(
                spheres_intersect(a, r, b, 0.05, [0.0; 3]),
                spheres_intersect(b, 0.05, a, r, [0.0; 3])
            );
        }
    }
}
