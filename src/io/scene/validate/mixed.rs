//! A scene mixing phases that take exactly their measured grains with phases whose
//! grains are drawn (from laws, or from a table with replacement).
//!
//! The exact tables fix their grains, so they fix the grain volume: if the exact
//! phases' shares sum to `S_E` (shares normalised over all phases) and their tables hold
//! the volume `V_E`, the grains fill `V_g = V_E / S_E`, of which each drawn phase draws
//! its share `s V_g`, and each exact phase's share becomes its table's volume over
//! `V_g`. The box follows as for an all-exact scene ([`sized_box`]): `target_fraction`
//! scales the given box to `V_g / φ`; without it the box is as given. `grains = N`
//! cannot be honoured (the drawn count follows from the volumes) and is an error.

use super::measured::sized_box;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::RawScene;
use crate::scene::{Domain, GrainCount, MeasuredMode, Phase};

/// Whether `phase` takes exactly its measured grains.
pub(super) fn is_exact(phase: &Phase) -> bool {
    matches!(&phase.measured, Some(m) if m.mode == MeasuredMode::Exact)
}

/// The count and box of a mixed scene (some phases exact, some drawn); sets the exact
/// phases' shares to their tables' volumes over the grain volume.
pub(super) fn mixed_scene(
    src: &Source,
    raw: &RawScene,
    domain: Domain,
    phases: &mut [Phase],
) -> Result<(GrainCount, Domain), SceneError> {
    if let Some(n) = &raw.grains {
        return Err(src.invalid_at(
            "grains",
            n,
            "a scene mixing exact measured tables with drawn phases takes its grain volume \
             from the exact tables and the shares; give target_fraction (to size the box) \
             or neither, not grains",
        ));
    }
    let exact_share: f64 = phases.iter().filter(|p| is_exact(p)).map(|p| p.share).sum();
    let exact_volume: f64 = phases
        .iter()
        .filter_map(|p| p.measured.as_ref().filter(|_| is_exact(p)))
        .map(|m| m.volume())
        .sum();
    let volume = exact_volume / exact_share;
    for p in phases.iter_mut().filter(|p| is_exact(p)) {
        p.share = p.measured.as_ref().expect("exact").volume() / volume;
    }
    let domain = sized_box(src, raw, domain, phases, volume)?;
    Ok((GrainCount::Fraction(volume / domain.volume()), domain))
}
