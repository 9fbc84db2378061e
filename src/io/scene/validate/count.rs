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
            fraction_resolved(src, raw, count as f64 * v_grain, v_box, "the grains fill")?;
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

/// Refuses a box given with the grains' count (or their exact tables) that they fill a
/// fraction of below the normal doubles: the scene's fraction is then 0 in every
/// output (`box.size = [1e100, 1e100, 1e100]` with 4 grains of 1e-100: 1e-600, written
/// as `packing_fraction = 0`), and one grain against the box is finer than the packing
/// resolves (centres are rounded to the box's ulp, 1e84 there). Names `box.size`, with
/// the grains' total volume (`volume`; an area in 2D) and what they fill (`filled`: how
/// they came to).
pub(super) fn fraction_resolved(
    src: &Source,
    raw: &RawScene,
    volume: f64,
    v_box: f64,
    filled: &str,
) -> Result<(), SceneError> {
    if volume / v_box >= f64::MIN_POSITIVE {
        return Ok(());
    }
    let fraction = match v_box.is_finite() {
        true => format!("about 1e{:.0}", volume.log10() - v_box.log10()),
        false => "0 (the box's volume is beyond the double range)".to_string(),
    };
    Err(src.invalid(
        "box.size",
        raw.domain.get_ref().size.span(),
        format!(
            "{filled} {fraction} of this box, below the smallest fraction a double \
             resolves ({:.1e}): the box is too large for these grains; give a box closer \
             to their size, or target_fraction",
            f64::MIN_POSITIVE
        ),
    ))
}
