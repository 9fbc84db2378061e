//! `kind = "fisher"`: the first axis by von Mises–Fisher, and the spin about it.

use super::axis::direction;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::RawOrientation;
use crate::laws::{Fisher, Invalid, VonMises};
use crate::scene::{FisherOrientation, Orientation, Spin};
use std::f64::consts::PI;
use toml::Spanned;

/// `kind = "fisher"`: `direction` (default z), `kappa`, and the spin: uniform, or
/// `spin_reference` with `spin_kappa` and `spin_mean` (degrees, default 0).
pub(super) fn fisher(
    src: &Source,
    key: &str,
    raw: &Spanned<RawOrientation>,
) -> Result<Orientation, SceneError> {
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
    Ok(Orientation::Fisher(FisherOrientation {
        mean,
        fisher,
        spin,
    }))
}
