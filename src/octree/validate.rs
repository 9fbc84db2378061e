//! The checks of a build's input: the box, every sphere, unique ids.

use super::{BoxShape, OctreeError, Sphere, MAX_IMAGES_PER_AXIS};
use rayon::prelude::*;

/// Checks the box and the spheres as `build` and the brute-force references need them.
/// The spheres are checked in parallel; only when one fails are they checked again in
/// order, for the first problem.
pub(crate) fn validate_input(spheres: &[Sphere], shape: &BoxShape) -> Result<(), OctreeError> {
    shape.validate()?;
    if u32::try_from(spheres.len()).is_err() {
        return Err(OctreeError::TooManySpheres {
            count: spheres.len(),
        });
    }
    let check = |s: &Sphere| validate_sphere(s, shape);
    let parallel = spheres.len() >= PARALLEL_FROM;
    let bad = if parallel {
        let tasks = spheres.par_iter().with_min_len(CHECKS_PER_TASK);
        tasks.any(|s| check(s).is_err())
    } else {
        spheres.iter().any(|s| check(s).is_err())
    };
    if bad {
        spheres.iter().try_for_each(check)?;
    }
    // Ids in increasing order (the packing's are the grains' indices) are unique.
    let ordered = |w: &[Sphere]| w[0].id < w[1].id;
    let increasing = if parallel {
        (spheres.par_windows(2))
            .with_min_len(CHECKS_PER_TASK)
            .all(ordered)
    } else {
        spheres.windows(2).all(ordered)
    };
    if !increasing {
        if let Some(id) = first_duplicate(spheres.iter().map(|s| s.id)) {
            return Err(OctreeError::DuplicateId { id });
        }
    }
    Ok(())
}

/// Spheres one rayon task checks or gathers: a few operations each.
pub(super) const CHECKS_PER_TASK: usize = 8192;

/// Spheres from which a build checks, gathers and splits in parallel. Below it the
/// work is too short for the pool: called from outside rayon's pool (as
/// `benches/octree.rs` does), each parallel call waits for a worker to wake, which
/// made a rebuild of 10⁵ spheres about 1 ms longer.
pub(super) const PARALLEL_FROM: usize = 1 << 17;

/// One sphere's own checks, and whether it fits the periodic box.
fn validate_sphere(s: &Sphere, shape: &BoxShape) -> Result<(), OctreeError> {
    s.validate()?;
    if shape.is_periodic() {
        for (axis, &length) in shape.lengths.iter().enumerate() {
            if (2.0 * s.radius / length).ceil() > f64::from(MAX_IMAGES_PER_AXIS) {
                return Err(OctreeError::TooLargeForBox {
                    id: s.id,
                    radius: s.radius,
                    axis,
                    length,
                    max_images: MAX_IMAGES_PER_AXIS,
                });
            }
        }
    }
    Ok(())
}

/// The first id seen twice, if any: a bitmap when ids are dense enough, else a sort.
pub(crate) fn first_duplicate(ids: impl ExactSizeIterator<Item = u32> + Clone) -> Option<u32> {
    let n = ids.len();
    let max = ids.clone().max()? as usize;
    if max / 64 <= 4 * n + 64 {
        let mut seen = vec![0u64; max / 64 + 1];
        for id in ids {
            let (word, bit) = (id as usize / 64, 1u64 << (id % 64));
            if seen[word] & bit != 0 {
                return Some(id);
            }
            seen[word] |= bit;
        }
        None
    } else {
        let mut sorted: Vec<u32> = ids.collect();
        sorted.sort_unstable();
        sorted.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
    }
}
