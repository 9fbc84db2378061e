//! The count and box of a scene with exact measured tables (`mode = "exact"`): all its
//! phases exact ([`exact_scene`]), or exact ones mixed with phases whose grains are
//! drawn, from laws or from a table with replacement ([`mixed_scene`]).
//!
//! In a mixed scene the exact tables fix their grains, so they fix the grain volume: if
//! the exact phases' shares sum to `S_E` (shares normalised over all phases) and their tables hold
//! the volume `V_E`, the grains fill `V_g = V_E / S_E`, of which each drawn phase draws
//! its share `s V_g`, and each exact phase's share becomes its table's volume over
//! `V_g`. The box follows as for an all-exact scene ([`sized_box`]): `target_fraction`
//! scales the given box to `V_g / φ`; without it the box is as given. `grains = N`
//! cannot be honoured (the drawn count follows from the volumes) and is an error.

use super::plane::densest;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::RawScene;
use crate::scene::{Domain, GrainCount, Measured, MeasuredMode, Phase};

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

/// The count and box of a scene whose phases all take exactly their measured grains:
/// the shares become the tables' volumes; `grains`, if given, must equal the number of
/// rows; `target_fraction`, if given, scales the box (its proportions kept) so that the
/// grains fill that fraction; otherwise the box is as given and must hold them.
pub(super) fn exact_scene(
    src: &Source,
    raw: &RawScene,
    domain: Domain,
    phases: &mut [Phase],
) -> Result<(GrainCount, Domain), SceneError> {
    let tables: Vec<&Measured> = phases.iter().filter_map(|p| p.measured.as_ref()).collect();
    let count: usize = tables.iter().map(|m| m.grains.len()).sum();
    let volumes: Vec<f64> = tables.iter().map(|m| m.volume()).collect();
    let volume: f64 = volumes.iter().sum();
    for (p, v) in phases.iter_mut().zip(&volumes) {
        p.share = v / volume;
    }
    match (&raw.grains, &raw.target_fraction) {
        (Some(n), _) if *n.get_ref() != count as u64 => Err(src.invalid_at(
            "grains",
            n,
            format!("the measured tables (mode = \"exact\") hold {count} grains"),
        )),
        (Some(_), Some(f)) => Err(src.invalid_at(
            "target_fraction",
            f,
            "give either grains or target_fraction, not both",
        )),
        _ => Ok((
            GrainCount::Exactly(count),
            sized_box(src, raw, domain, phases, volume)?,
        )),
    }
}

/// The box of a scene whose grain volume is fixed (`volume`, by its exact tables):
/// with `target_fraction`, the given box scaled (its proportions kept) so that the
/// grains fill that fraction; otherwise the box as given, which must hold them. Either
/// way the longest grain must fit.
pub(super) fn sized_box(
    src: &Source,
    raw: &RawScene,
    domain: Domain,
    phases: &[Phase],
    volume: f64,
) -> Result<Domain, SceneError> {
    let fits = |domain: &Domain, at: std::ops::Range<usize>, key: &str| {
        let longest = phases.iter().map(Phase::max_length).fold(0.0, f64::max);
        if longest >= domain.min_side() {
            return Err(src.invalid(
                key,
                at,
                format!(
                    "the longest grain ({longest} end to end) does not fit in the \
                     box, whose shortest side is {}",
                    domain.min_side()
                ),
            ));
        }
        Ok(())
    };
    let (limit, grains) = densest(&domain);
    match &raw.target_fraction {
        Some(f) => {
            let phi = *f.get_ref();
            if !(phi > 0.0 && phi <= limit) {
                return Err(src.invalid_at(
                    "target_fraction",
                    f,
                    format!("must lie in (0, {limit}]"),
                ));
            }
            let scale = (domain.dimension).length_scale(volume / (phi * domain.volume()));
            let scaled = Domain {
                size: domain.size.map(|l| l * scale),
                ..domain
            };
            if !scaled.size.iter().all(|l| l.is_finite()) {
                // Grains of 1e103 and more (1e154 in 2D): their volume, and the box
                // scaled to it, are beyond the double range.
                return Err(src.invalid_at(
                    "target_fraction",
                    f,
                    format!(
                        "the measured grains' total volume ({volume:e}) is beyond the range \
                         of the box this would size (sides {:e}); give the table in smaller \
                         units",
                        domain.size[0] * scale
                    ),
                ));
            }
            fits(&scaled, f.span(), "target_fraction")?;
            Ok(scaled)
        }
        None => {
            let at = raw.domain.get_ref().size.span();
            fits(&domain, at.clone(), "box.size")?;
            let filled = "the measured grains fill";
            super::count::fraction_resolved(src, raw, volume, domain.volume(), filled)?;
            let phi = volume / domain.volume();
            if phi > limit {
                return Err(src.invalid(
                    "box.size",
                    at,
                    format!(
                        "the measured grains fill {phi:.3} of this box, beyond the densest \
                         packing of {grains} ({limit}); enlarge the box or give \
                         target_fraction to size it"
                    ),
                ));
            }
            Ok(domain)
        }
    }
}
