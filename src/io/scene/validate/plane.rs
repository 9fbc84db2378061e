//! `[phase.orientation]` of a 2D scene: an ellipse's orientation is one angle, its first
//! semi-axis from x (degrees in the file, as every angle of a scene file).
//!
//! `random` (uniform), `aligned` (`angle`, default 0) and a von Mises law of the angle
//! (`kind = "vonmises"`, or `kind = "tilt"` about z, which is the same law); the 3D
//! kinds (`fixed` quaternions, `fisher` directions) and tilt axes other than z are
//! refused, each naming its key. Also here: the box, whose two or three lengths make
//! the scene 2D or 3D, the densest fraction of its grains, the refusal of triaxial laws
//! and the message every 2D refusal shares.

use super::grain::{foreign_keys, given_keys, tilt};
use crate::contact::Dimension;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::{RawBoundary, RawBox, RawKind, RawOrientation, RawPhase};
use crate::scene::{Boundary, Domain, Orientation, MAX_TARGET_FRACTION};
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
    let given = given_keys(o);
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

pub(super) fn domain(src: &Source, raw: &Spanned<RawBox>) -> Result<Domain, SceneError> {
    let raw = raw.get_ref();
    let size = raw.size.get_ref();
    if !(size.len() == 2 || size.len() == 3) {
        return Err(src.invalid_at(
            "box.size",
            &raw.size,
            format!(
                "must be [Lx, Ly, Lz] (a box of ellipsoids) or [Lx, Ly] (a 2D scene: a \
                 rectangle of ellipses), not {} lengths",
                size.len()
            ),
        ));
    }
    if !size.iter().all(|l| l.is_finite() && *l > 0.0) {
        return Err(src.invalid_at(
            "box.size",
            &raw.size,
            "every side must be positive and finite",
        ));
    }
    let boundary = match raw.boundary.as_ref().map(|b| *b.get_ref()) {
        None | Some(RawBoundary::Periodic) => Boundary::Periodic,
        Some(RawBoundary::Reflecting) => Boundary::Reflecting,
    };
    Ok(match *size.as_slice() {
        [x, y] => Domain::plane([x, y], boundary),
        _ => Domain::new([size[0], size[1], size[2]], boundary),
    })
}

/// The error of a key that has no meaning in a 2D scene, saying why.
pub(super) fn not_in_2d(
    src: &Source,
    key: impl Into<String>,
    at: Range<usize>,
    why: &str,
) -> SceneError {
    src.invalid(
        key,
        at,
        format!("has no meaning in a 2D scene (box.size = [Lx, Ly]): {why}"),
    )
}

/// The densest packing of the scene's grains (ellipsoids or ellipses), as the limit of
/// `target_fraction`, and their name for messages: [`MAX_TARGET_FRACTION`] in 3D.
pub(super) fn densest(domain: &Domain) -> (f64, &'static str) {
    match domain.dimension {
        Dimension::Three => (MAX_TARGET_FRACTION, "ellipsoids"),
        Dimension::Two => (Dimension::Two.densest_fraction(), "ellipses"),
    }
}

/// The triaxial laws (`b_over_a`, `c_over_a`, `c_over_b`) of phase `key`, refused in a
/// 2D scene.
pub(super) fn no_triaxial(
    src: &Source,
    key: &str,
    p: &RawPhase,
    dimension: Dimension,
) -> Result<(), SceneError> {
    if dimension == Dimension::Three {
        return Ok(());
    }
    let triaxial = [
        ("b_over_a", &p.b_over_a),
        ("c_over_a", &p.c_over_a),
        ("c_over_b", &p.c_over_b),
    ];
    if let Some((name, Some(v))) = triaxial.into_iter().find(|(_, v)| v.is_some()) {
        return Err(not_in_2d(
            src,
            format!("{key}.{name}"),
            v.span(),
            "an ellipse has two semi-axes; give aspect_ratio (a1/a2)",
        ));
    }
    Ok(())
}
