//! The O(n²) references the tests hold the octree to.

use super::boundary::{image_range, is_positive_image, small_image, spheres_intersect};
use super::validate::validate_input;
use super::{BoxShape, Neighbour, OctreeError, Pair, Sphere};

/// Every intersecting pair by testing all of them: the O(n²) reference used by the
/// tests, with the same definition as [`Octree::pairs`](super::Octree::pairs) (see the
/// [module docs](super)): minimum-image periodicity extended to every image that
/// intersects, self-image pairs included, the lower id first.
///
/// For each pair it tries every image `k` with `k·L` within `r_i + r_j` of
/// `c_i − c_j` (one more on each side, to be safe from rounding) and keeps those that
/// pass [`spheres_intersect`]. Inputs are checked as by
/// [`Octree::build`](super::Octree::build). Clears `out`; the order is by input index,
/// then image.
pub fn brute_force_pairs(
    spheres: &[Sphere],
    shape: &BoxShape,
    out: &mut Vec<Pair>,
) -> Result<(), OctreeError> {
    validate_input(spheres, shape)?;
    out.clear();
    let wrapped: Vec<Sphere> = spheres
        .iter()
        .map(|s| Sphere {
            centre: shape.wrap(s.centre),
            ..*s
        })
        .collect();
    for (a, sa) in wrapped.iter().enumerate() {
        if shape.is_periodic() {
            let reach = 2.0 * sa.radius;
            for k in images(shape, [0.0; 3], reach) {
                let s = shape.shift(k);
                if is_positive_image(k)
                    && spheres_intersect(sa.centre, sa.radius, sa.centre, sa.radius, s)
                {
                    out.push(Pair {
                        i: sa.id,
                        j: sa.id,
                        image: small_image(k),
                    });
                }
            }
        }
        for sb in &wrapped[a + 1..] {
            let (si, sj) = if sa.id < sb.id { (sa, sb) } else { (sb, sa) };
            let gap = [0, 1, 2].map(|x| si.centre[x] - sj.centre[x]);
            for k in images(shape, gap, si.radius + sj.radius) {
                let s = shape.shift(k);
                if spheres_intersect(si.centre, si.radius, sj.centre, sj.radius, s) {
                    out.push(Pair {
                        i: si.id,
                        j: sj.id,
                        image: small_image(k),
                    });
                }
            }
        }
    }
    Ok(())
}

/// Every stored sphere meeting a query sphere by testing all of them: the O(n)
/// reference for [`Octree::neighbours`](super::Octree::neighbours), with the same
/// definition and checks. Clears `out`; the order is by input index, then image.
pub fn brute_force_neighbours(
    spheres: &[Sphere],
    shape: &BoxShape,
    centre: [f64; 3],
    radius: f64,
    out: &mut Vec<Neighbour>,
) -> Result<(), OctreeError> {
    validate_input(spheres, shape)?;
    if !(centre.iter().all(|x| x.is_finite()) && radius.is_finite() && radius >= 0.0) {
        return Err(OctreeError::InvalidQuery { centre, radius });
    }
    out.clear();
    for s in spheres {
        let c = shape.wrap(s.centre);
        let gap = [0, 1, 2].map(|x| centre[x] - c[x]);
        for k in images(shape, gap, radius + s.radius) {
            let shift = shape.shift(k);
            if spheres_intersect(centre, radius, c, s.radius, shift) {
                out.push(Neighbour { id: s.id, shift });
            }
        }
    }
    Ok(())
}

/// The images `k` with `k·L` possibly within `reach` of `gap` (only `k = 0` for walls).
fn images(shape: &BoxShape, gap: [f64; 3], reach: f64) -> Vec<[i32; 3]> {
    if !shape.is_periodic() {
        return vec![[0; 3]];
    }
    let l = shape.lengths;
    let r = [0, 1, 2].map(|a| image_range(gap[a] - reach, gap[a] + reach, l[a]));
    let mut out = Vec::new();
    for k0 in r[0].clone() {
        for k1 in r[1].clone() {
            for k2 in r[2].clone() {
                out.push([k0, k1, k2]);
            }
        }
    }
    out
}
