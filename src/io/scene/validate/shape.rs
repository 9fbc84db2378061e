//! The keys of issue 15's laws: `distribution = "table"`, the triaxial shape ratios
//! (`b_over_a` with `c_over_a` or `c_over_b`) and `kind = "fisher"` orientations.

use super::grain::{direction, distribution};
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::{RawDistribution, RawOrientation, RawPhase};
use crate::laws::{
    Distribution, Fisher, Invalid, TableBasis, TableError, TableInterpolation, TableLaw, VonMises,
};
use crate::scene::{FisherOrientation, Spin, ThirdRatio, Triaxial};
use std::f64::consts::PI;
use std::ops::Range;
use toml::Spanned;

/// The table-only keys given in a distribution, with their spans.
pub(super) fn table_keys(r: &RawDistribution) -> [Option<(&'static str, Range<usize>)>; 4] {
    [
        r.x.as_ref().map(|v| ("x", v.span())),
        r.cdf.as_ref().map(|v| ("cdf", v.span())),
        r.by.as_ref().map(|v| ("by", v.span())),
        r.interpolation
            .as_ref()
            .map(|v| ("interpolation", v.span())),
    ]
}

/// `distribution = "table"`: `x`, `cdf`, `by` (`"number"`, default, or `"volume"`),
/// `interpolation` (`"linear"`, default, or `"log"`).
pub(super) fn table(
    src: &Source,
    key: &str,
    raw: &Spanned<RawDistribution>,
) -> Result<Distribution, SceneError> {
    let r = raw.get_ref();
    if let Some((name, Some(v))) = r.params().into_iter().find(|(_, v)| v.is_some()) {
        return Err(src.invalid_at(
            format!("{key}.{name}"),
            v,
            "does not apply to distribution = \"table\", which takes x, cdf, by, interpolation \
             (its cutoffs are the table's ends)",
        ));
    }
    fn need<'a>(
        src: &Source,
        key: &str,
        raw: &Spanned<RawDistribution>,
        name: &str,
        v: &'a Option<Spanned<Vec<f64>>>,
    ) -> Result<&'a Spanned<Vec<f64>>, SceneError> {
        v.as_ref().ok_or_else(|| {
            src.missing(
                format!("{key}.{name}"),
                raw.span(),
                "distribution = \"table\" needs x = [...] and cdf = [...]",
            )
        })
    }
    let x = need(src, key, raw, "x", &r.x)?;
    let cdf = need(src, key, raw, "cdf", &r.cdf)?;
    let basis = match r.by.as_ref() {
        None => TableBasis::Number,
        Some(b) => match b.get_ref().as_str() {
            "number" => TableBasis::Number,
            "volume" => TableBasis::Volume,
            _ => {
                return Err(src.invalid_at(
                    format!("{key}.by"),
                    b,
                    "must be \"number\" (fraction of grains below x) or \"volume\" (volume \
                     fraction passing x, a sieve curve)",
                ))
            }
        },
    };
    let interpolation = match r.interpolation.as_ref() {
        None => TableInterpolation::Linear,
        Some(i) => match i.get_ref().as_str() {
            "linear" => TableInterpolation::Linear,
            "log" => TableInterpolation::Log,
            _ => {
                return Err(src.invalid_at(
                    format!("{key}.interpolation"),
                    i,
                    "must be \"linear\" (in x) or \"log\" (in ln x)",
                ))
            }
        },
    };
    let law = TableLaw::new(x.get_ref(), cdf.get_ref(), basis, interpolation).map_err(
        |TableError {
             key: which,
             index,
             reason,
         }| {
            let at = if which == "x" { x.span() } else { cdf.span() };
            let path = match index {
                Some(i) => format!("{key}.{which}[{i}]"),
                None => format!("{key}.{which}"),
            };
            src.invalid(path, at, reason)
        },
    )?;
    Ok(Distribution::Table(law))
}

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
        let law = distribution(src, &format!("{key}.{name}"), raw)?;
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

/// `kind = "fisher"`: `direction` (default z), `kappa`, and the spin: uniform, or
/// `spin_reference` with `spin_kappa` and `spin_mean` (degrees, default 0).
pub(super) fn fisher(
    src: &Source,
    key: &str,
    raw: &Spanned<RawOrientation>,
) -> Result<crate::scene::Orientation, SceneError> {
    let o = raw.get_ref();
    let mean = match &o.direction {
        None => [0.0, 0.0, 1.0],
        Some(d) => direction(src, &format!("{key}.direction"), d)?,
    };
    let kappa = o.kappa.as_ref().ok_or_else(|| {
        src.missing(
            format!("{key}.kappa"),
            raw.span(),
            "kind = \"fisher\" needs kappa (0: uniform on the sphere; the most likely angle \
             to the direction is 1/√κ rad, κ ≈ 33 for 10°)",
        )
    })?;
    let fisher = Fisher {
        kappa: *kappa.get_ref(),
    };
    fisher.check().map_err(|Invalid { param, reason }| {
        src.invalid_at(format!("{key}.{param}"), kappa, reason)
    })?;
    let spin = match &o.spin_reference {
        None => {
            for (name, v) in [("spin_kappa", &o.spin_kappa), ("spin_mean", &o.spin_mean)] {
                if let Some(v) = v {
                    return Err(src.invalid_at(
                        format!("{key}.{name}"),
                        v,
                        "needs spin_reference (without it the spin is uniform)",
                    ));
                }
            }
            Spin::Uniform
        }
        Some(r) => {
            let reference = direction(src, &format!("{key}.spin_reference"), r)?;
            let along: f64 = reference.iter().zip(&mean).map(|(a, b)| a * b).sum();
            // Within 1e-6 of parallel, the projection of the reference on the plane
            // normal to the first axis has no stable direction.
            const PARALLEL_COS: f64 = 1.0 - 1e-6;
            if along.abs() >= PARALLEL_COS {
                return Err(src.invalid_at(
                    format!("{key}.spin_reference"),
                    r,
                    "is parallel to direction: the spin is measured in the plane normal to \
                     the first axis, so the reference must not lie along it",
                ));
            }
            let kappa = o.spin_kappa.as_ref().ok_or_else(|| {
                src.missing(
                    format!("{key}.spin_kappa"),
                    raw.span(),
                    "spin_reference needs spin_kappa (0 for uniform)",
                )
            })?;
            let mean = o
                .spin_mean
                .as_ref()
                .map_or(0.0, |m| m.get_ref().to_radians());
            let angle = VonMises {
                mean,
                kappa: *kappa.get_ref(),
                min: mean - PI,
                max: mean + PI,
            };
            angle.check().map_err(|Invalid { param, reason }| {
                let at = match param {
                    "kappa" => Some(kappa),
                    _ => o.spin_mean.as_ref(),
                };
                src.invalid(
                    format!("{key}.spin_{param}"),
                    at.map_or(raw.span(), Spanned::span),
                    reason,
                )
            })?;
            Spin::VonMises { reference, angle }
        }
    };
    Ok(crate::scene::Orientation::Fisher(FisherOrientation {
        mean,
        fisher,
        spin,
    }))
}
