//! `packing.gap`: its own range, and whether the grains inflated by it still fit.

use super::super::error::{SceneError, Source};
use super::super::raw::RawPacking;
use super::plane::densest;
use crate::scene::{Phase, Scene, MIN_MESH_GAP};
use toml::Spanned;

/// The gap as written: a finite number, at least 0.
pub(super) fn value(src: &Source, raw: &Spanned<f64>) -> Result<f64, SceneError> {
    let gap = *raw.get_ref();
    if !(gap.is_finite() && gap >= 0.0) {
        return Err(src.invalid_at(
            "packing.gap",
            raw,
            "must be a finite number, at least 0 (a fraction of each pair's size)",
        ));
    }
    Ok(gap)
}

/// The grains are packed inflated by `1 + gap`, so the gap is too large to mean
/// anything when the inflated grains could not be packed at all: when they would fill
/// more of the box than the densest packing of ellipsoids
/// ([`MAX_TARGET_FRACTION`](crate::scene::MAX_TARGET_FRACTION); of ellipses in 2D),
/// or when the longest of them would not fit in the box (it would meet its own
/// periodic image, or both walls).
pub(super) fn fits(
    src: &Source,
    raw: Option<&Spanned<RawPacking>>,
    scene: &Scene,
) -> Result<(), SceneError> {
    let Some(at) = raw.and_then(|r| r.get_ref().gap.as_ref()) else {
        return Ok(());
    };
    let gap = scene.packing.gap;
    let inflation = 1.0 + gap;
    let fraction = scene.expected_fraction();
    let dimension = scene.domain.dimension;
    let inflated = fraction * inflation.powi(dimension.exponent());
    let (limit, grains) = densest(&scene.domain);
    if inflated > limit {
        let largest = dimension.length_scale(limit / fraction) - 1.0;
        return Err(src.invalid_at(
            "packing.gap",
            at,
            format!(
                "the grains inflated by 1 + gap would fill {inflated:.3} of the box (the grains \
                 fill {fraction:.3}), beyond the densest packing of {grains} ({limit}): the gap \
                 can be at most {largest:.4} here"
            ),
        ));
    }
    let longest = (scene.phases.iter().map(Phase::max_length)).fold(0.0, f64::max);
    let side = scene.domain.min_side();
    if inflation * longest >= side {
        return Err(src.invalid_at(
            "packing.gap",
            at,
            format!(
                "the longest grain ({longest:.4} end to end) inflated by 1 + gap does not fit in \
                 the box, whose shortest side is {side}: the gap must be below {:.4} here",
                side / longest - 1.0
            ),
        ));
    }
    Ok(())
}

/// A conforming mesh (`output.mesh = true`) needs a film of matrix between any two
/// grains that its elements can fill: `packing.gap` at least [`MIN_MESH_GAP`].
pub(super) fn meshable(
    src: &Source,
    raw: &super::super::raw::RawScene,
    scene: &Scene,
) -> Result<(), SceneError> {
    if scene.output.mesh.is_none() || scene.packing.gap >= MIN_MESH_GAP {
        return Ok(());
    }
    let why = format!(
        "output.mesh = true needs a gap between the grains for the matrix elements: set \
         packing.gap to at least {MIN_MESH_GAP} (grains that touch, or nearly, leave slivers \
         or no mesh at all)"
    );
    match raw.packing.as_ref().and_then(|p| p.get_ref().gap.as_ref()) {
        Some(at) => Err(src.invalid_at("packing.gap", at, why)),
        None => {
            let at = raw
                .output
                .as_ref()
                .and_then(|o| o.get_ref().mesh.as_ref())
                .map_or(0..0, Spanned::span);
            Err(src.missing("packing.gap", at, why))
        }
    }
}
