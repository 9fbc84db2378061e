//! Triaxial shape laws: `b_over_a` with `c_over_a` or `c_over_b`.

use super::grain::distribution;
use crate::contact::Dimension;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::{RawDistribution, RawPhase};
use crate::scene::{ThirdRatio, Triaxial};
use toml::Spanned;

/// The triaxial shape laws of a phase, if it gives `b_over_a`: checked to lie in
/// `(0, 1]` and, for `c_over_a`, never above `b_over_a`.
pub(super) fn triaxial(
    src: &Source,
    key: &str,
    p: &RawPhase,
) -> Result<Option<Triaxial>, SceneError> {
    let Some(b) = &p.b_over_a else {
        for (name, v) in [("c_over_a", &p.c_over_a), ("c_over_b", &p.c_over_b)] {
            if let Some(v) = v {
                return Err(src.invalid_at(
                    format!("{key}.{name}"),
                    v,
                    "triaxial grains need b_over_a too",
                ));
            }
        }
        return Ok(None);
    };
    if let Some(a) = &p.aspect_ratio {
        return Err(src.invalid_at(
            format!("{key}.aspect_ratio"),
            a,
            "give aspect_ratio (spheroids) or b_over_a with c_over_a or c_over_b (triaxial \
             grains), not both",
        ));
    }
    let ratio = |name: &str, raw: &Spanned<RawDistribution>| {
        let law = distribution(src, &format!("{key}.{name}"), raw, Dimension::Three)?;
        let (_, max) = law.support();
        if max > 1.0 {
            return Err(src.invalid_at(
                format!("{key}.{name}"),
                raw,
                format!(
                    "can reach {max}, above 1: the semi-axes are ordered a ≥ b ≥ c, so every \
                     shape ratio lies in (0, 1]"
                ),
            ));
        }
        Ok(law)
    };
    let b_over_a = ratio("b_over_a", b)?;
    let third = match (&p.c_over_a, &p.c_over_b) {
        (Some(_), Some(cb)) => {
            return Err(src.invalid_at(
                format!("{key}.c_over_b"),
                cb,
                "give c_over_a or c_over_b, not both",
            ))
        }
        (None, None) => {
            return Err(src.missing(
                format!("{key}.c_over_a"),
                b.span(),
                "triaxial grains need c_over_a or c_over_b besides b_over_a",
            ))
        }
        (Some(ca), None) => {
            let law = ratio("c_over_a", ca)?;
            let (c_max, b_min) = (law.support().1, b_over_a.support().0);
            if c_max > b_min {
                return Err(src.invalid_at(
                    format!("{key}.c_over_a"),
                    ca,
                    format!(
                        "can reach c/a = {c_max}, above the smallest b/a = {b_min}: c/a > b/a \
                         would make c longer than b. Lower its upper cutoff, or give c_over_b"
                    ),
                ));
            }
            ThirdRatio::OverA(law)
        }
        (None, Some(cb)) => ThirdRatio::OverB(ratio("c_over_b", cb)?),
    };
    Ok(Some(Triaxial { b_over_a, third }))
}
