//! `[phase.orientation]` of a 2D scene: an ellipse's orientation is one angle, its first
//! semi-axis from x (degrees in the file, as every angle of a scene file).
//!
//! `random` (uniform), `aligned` (`angle`, default 0) and a von Mises law of the angle
//! (`kind = "vonmises"`, or `kind = "tilt"` about z, which is the same law); the 3D
//! kinds (`fixed` quaternions, `fisher` directions) and tilt axes other than z are
//! refused, each naming its key.

use super::grain::{foreign_keys, tilt};
use super::not_in_2d;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::{RawKind, RawOrientation};
use crate::scene::Orientation;
use std::ops::Range;
use toml::Spanned;

/// `[phase.orientation]` (at key path `key`) of a 2D scene.
pub(super) fn orientation(
    src: &Source,
    key: &str,
    raw: &Spanned<RawOrientation>,
) -> Result<Orientation, SceneError> {
    let o = raw.get_ref();
    let kind_at = o.kind.span();
    let (name, takes): (_, &[&str]) = match *o.kind.get_ref() {
        RawKind::Random => ("random", &[]),
        RawKind::Aligned => ("aligned", &["angle"]),
        RawKind::Tilt => ("tilt", &["axis", "mean", "kappa", "min", "max"]),
        RawKind::VonMises => ("vonmises", &["mean", "kappa", "min", "max"]),
        RawKind::Fixed => {
            return Err(not_in_2d(
                src,
                format!("{key}.kind"),
                kind_at,
                "a quaternion is a 3D orientation; give kind = \"aligned\" with angle \
                 (degrees from x)",
            ))
        }
        RawKind::Fisher => {
            return Err(not_in_2d(
                src,
                format!("{key}.kind"),
                kind_at,
                "a direction on the sphere; give kind = \"vonmises\" (a law of the angle in \
                 the plane)",
            ))
        }
    };
    if let (Some(a), "aligned") = (&o.axis, name) {
        return Err(not_in_2d(
            src,
            format!("{key}.axis"),
            a.span(),
            "an ellipse's direction is its angle; give angle (degrees from x)",
        ));
    }
    let given: [(&str, Option<Range<usize>>); 11] = [
        ("quaternion", o.quaternion.as_ref().map(Spanned::span)),
        ("axis", o.axis.as_ref().map(Spanned::span)),
        ("mean", o.mean.as_ref().map(Spanned::span)),
        ("kappa", o.kappa.as_ref().map(Spanned::span)),
        ("min", o.min.as_ref().map(Spanned::span)),
        ("max", o.max.as_ref().map(Spanned::span)),
        ("direction", o.direction.as_ref().map(Spanned::span)),
        (
            "spin_reference",
            o.spin_reference.as_ref().map(Spanned::span),
        ),
        ("spin_kappa", o.spin_kappa.as_ref().map(Spanned::span)),
        ("spin_mean", o.spin_mean.as_ref().map(Spanned::span)),
        ("angle", o.angle.as_ref().map(Spanned::span)),
    ];
    foreign_keys(src, key, name, &given, takes, "no other key")?;
    match name {
        "random" => Ok(Orientation::Random),
        "aligned" => {
            let theta = match &o.angle {
                None => 0.0,
                Some(a) if a.get_ref().is_finite() => a.get_ref().to_radians(),
                Some(a) => {
                    return Err(src.invalid_at(
                        format!("{key}.angle"),
                        a,
                        "must be a finite angle in degrees",
                    ))
                }
            };
            let (sin, cos) = theta.sin_cos();
            Ok(Orientation::Aligned {
                axis: [cos, sin, 0.0],
            })
        }
        _ => {
            if let Some(a) = o
                .axis
                .as_ref()
                .filter(|a| a.get_ref().as_str() != Some("z"))
            {
                return Err(not_in_2d(
                    src,
                    format!("{key}.axis"),
                    a.span(),
                    "grains in the plane turn about z only; omit axis or give \"z\"",
                ));
            }
            tilt(src, key, raw, name)
        }
    }
}
