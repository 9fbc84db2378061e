//! How many grains a scene of drawn phases has: `grains` or `target_fraction`, each
//! checked against the densest packing of the scene's grains and the grain limit.

use super::plane::densest;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::RawScene;
use crate::scene::{mean_grain_volume, Domain, GrainCount, Phase, MAX_GRAINS};

pub(super) fn count(
    src: &Source,
    raw: &RawScene,
    domain: &Domain,
    phases: &[Phase],
) -> Result<GrainCount, SceneError> {
    let v_grain = mean_grain_volume(phases);
    let v_box = domain.volume();
    let (densest, grains) = densest(domain);
    match (&raw.grains, &raw.target_fraction) {
        (Some(_), Some(f)) => Err(src.invalid_at(
            "target_fraction",
            f,
            "give either grains or target_fraction, not both",
        )),
        (None, None) => {
            Err(src.missing("grains", 0..0, "give grains (a count) or target_fraction"))
        }
        (Some(n), None) => {
            let count = *n.get_ref();
            if count == 0 || count > MAX_GRAINS as u64 {
                return Err(src.invalid_at("grains", n, format!("must lie in [1, {MAX_GRAINS}]")));
            }
            let fraction = count as f64 * v_grain / v_box;
            if fraction > densest {
                return Err(src.invalid_at(
                    "grains",
                    n,
                    format!(
                        "that many grains fill an expected {fraction:.3} of the box, beyond the \
                         densest packing of {grains} ({densest})"
                    ),
                ));
            }
            Ok(GrainCount::Exactly(count as usize))
        }
        (None, Some(f)) => {
            let fraction = *f.get_ref();
            if !(fraction > 0.0 && fraction <= densest) {
                return Err(src.invalid_at(
                    "target_fraction",
                    f,
                    format!(
                        "must lie in (0, {densest}]: {densest} is the densest known packing of \
                         {grains}"
                    ),
                ));
            }
            let expected = fraction * v_box / v_grain;
            if expected > MAX_GRAINS as f64 {
                return Err(src.invalid_at(
                    "target_fraction",
                    f,
                    format!("needs about {expected:.3e} grains, more than the limit {MAX_GRAINS}"),
                ));
            }
            Ok(GrainCount::Fraction(fraction))
        }
    }
}
