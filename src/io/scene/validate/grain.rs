//! A phase's grain statistics: size and aspect-ratio distributions, and orientation.

use super::axis::{direction, named_axis};
use crate::contact::{Dimension, QUATERNION_NORM_TOL};
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::{RawDistribution, RawFamily, RawKind, RawOrientation};
use crate::laws::VonMises;
use crate::laws::{Distribution, Invalid};
use crate::scene::{Axis, Orientation};
use std::f64::consts::PI;
use std::ops::Range;
use toml::Spanned;

/// `[phase.size]` or `[phase.aspect_ratio]` (at key path `key`) of a scene in
/// `dimension` (which decides what a table's `by` may be).
pub(super) fn distribution(
    src: &Source,
    key: &str,
    raw: &Spanned<RawDistribution>,
    dimension: Dimension,
) -> Result<Distribution, SceneError> {
    let r = raw.get_ref();
    if *r.distribution.get_ref() == RawFamily::Table {
        return super::table::table(src, key, raw, dimension);
    }
    if let Some((name, span)) = super::table::table_keys(r).into_iter().flatten().next() {
        return Err(src.invalid(
            format!("{key}.{name}"),
            span,
            "applies only to distribution = \"table\"",
        ));
    }
    let (family, takes): (_, &[&str]) = match *r.distribution.get_ref() {
        RawFamily::Table => unreachable!("handled above"),
        RawFamily::Constant => ("constant", &["value"]),
        RawFamily::Uniform => ("uniform", &["min", "max"]),
        RawFamily::Normal => ("normal", &["mean", "std", "min", "max"]),
        RawFamily::LogNormal => ("lognormal", &["sigma", "scale", "loc", "min", "max"]),
    };
    for (name, value) in r.params() {
        if let (Some(v), false) = (value, takes.contains(&name)) {
            return Err(src.invalid_at(
                format!("{key}.{name}"),
                v,
                format!(
                    "does not apply to distribution = \"{family}\", which takes {}",
                    takes.join(", ")
                ),
            ));
        }
    }
    let need = |name: &str| {
        r.param(name).map(|v| *v.get_ref()).ok_or_else(|| {
            src.missing(
                format!("{key}.{name}"),
                raw.span(),
                format!("distribution = \"{family}\" needs {}", takes.join(", ")),
            )
        })
    };
    let d = match *r.distribution.get_ref() {
        RawFamily::Table => unreachable!("handled above"),
        RawFamily::Constant => Distribution::Constant {
            value: need("value")?,
        },
        RawFamily::Uniform => Distribution::Uniform {
            min: need("min")?,
            max: need("max")?,
        },
        RawFamily::Normal => Distribution::Normal {
            mean: need("mean")?,
            std: need("std")?,
            min: need("min")?,
            max: need("max")?,
        },
        RawFamily::LogNormal => Distribution::LogNormal {
            sigma: need("sigma")?,
            scale: need("scale")?,
            loc: r.loc.as_ref().map_or(0.0, |v| *v.get_ref()),
            min: need("min")?,
            max: need("max")?,
        },
    };
    d.check().map_err(|Invalid { param, reason }| {
        let at = r.param(param).map_or(raw.span(), |v| v.span());
        src.invalid(format!("{key}.{param}"), at, reason)
    })?;
    Ok(d)
}

/// `[phase.orientation]` (at key path `key`) of a 3D scene (a 2D scene's is
/// `plane::orientation`).
pub(super) fn orientation(
    src: &Source,
    key: &str,
    raw: &Spanned<RawOrientation>,
) -> Result<Orientation, SceneError> {
    let o = raw.get_ref();
    let kind = *o.kind.get_ref();
    if let Some(a) = &o.angle {
        return Err(src.invalid_at(
            format!("{key}.angle"),
            a,
            "applies only in a 2D scene (box.size = [Lx, Ly]); in 3D give axis",
        ));
    }
    let given = given_keys(o);
    let (name, takes): (_, &[&str]) = match kind {
        RawKind::Random => ("random", &[]),
        RawKind::Fixed => ("fixed", &["quaternion"]),
        RawKind::Aligned => ("aligned", &["axis"]),
        RawKind::Tilt => ("tilt", &["axis", "mean", "kappa", "min", "max"]),
        RawKind::VonMises => {
            return Err(src.invalid_at(
                format!("{key}.kind"),
                &o.kind,
                "\"vonmises\" is a 2D scene's law of the angle in the plane (box.size = \
                 [Lx, Ly]); in 3D give kind = \"tilt\" with its axis",
            ))
        }
        RawKind::Fisher => (
            "fisher",
            &[
                "direction",
                "kappa",
                "spin_reference",
                "spin_kappa",
                "spin_mean",
            ],
        ),
    };
    foreign_keys(src, key, name, &given, takes, "no other key")?;
    match kind {
        RawKind::Random => Ok(Orientation::Random),
        RawKind::Fixed => {
            let q = o.quaternion.as_ref().ok_or_else(|| {
                src.missing(
                    format!("{key}.quaternion"),
                    raw.span(),
                    "kind = \"fixed\" needs quaternion = [w, x, y, z]",
                )
            })?;
            let norm = q.get_ref().iter().map(|v| v * v).sum::<f64>().sqrt();
            if !((norm - 1.0).abs() <= QUATERNION_NORM_TOL) {
                return Err(src.invalid_at(
                    format!("{key}.quaternion"),
                    q,
                    format!(
                        "must be a unit quaternion [w, x, y, z] (norm {norm}, tolerance \
                         {QUATERNION_NORM_TOL:e})"
                    ),
                ));
            }
            Ok(Orientation::Fixed {
                quaternion: q.get_ref().map(|v| v / norm),
            })
        }
        RawKind::Aligned => {
            let axis = match &o.axis {
                None => Axis::Z.unit(),
                Some(a) => direction(src, &format!("{key}.axis"), a)?,
            };
            Ok(Orientation::Aligned { axis })
        }
        RawKind::Tilt => tilt(src, key, raw, "tilt"),
        RawKind::Fisher => super::fisher::fisher(src, key, raw),
        RawKind::VonMises => unreachable!("refused above"),
    }
}

/// The keys of `kind = "tilt"` (or `"vonmises"`, a 2D scene's tilt about z: `kind`),
/// already checked to be the only ones given.
pub(super) fn tilt(
    src: &Source,
    key: &str,
    raw: &Spanned<RawOrientation>,
    kind: &str,
) -> Result<Orientation, SceneError> {
    let o = raw.get_ref();
    let axis = match &o.axis {
        None => Axis::Z,
        Some(a) => named_axis(a.get_ref()).ok_or_else(|| {
            src.invalid_at(
                format!("{key}.axis"),
                a,
                "the tilt axis must be \"x\", \"y\" or \"z\"",
            )
        })?,
    };
    let kappa = o.kappa.as_ref().ok_or_else(|| {
        src.missing(
            format!("{key}.kappa"),
            raw.span(),
            format!("kind = \"{kind}\" needs kappa (0 for uniform)"),
        )
    })?;
    let radians = |v: &Option<Spanned<f64>>| v.as_ref().map(|v| v.get_ref().to_radians());
    let mean = radians(&o.mean).unwrap_or(0.0);
    let angle = VonMises {
        mean,
        kappa: *kappa.get_ref(),
        min: radians(&o.min).unwrap_or(mean - PI),
        max: radians(&o.max).unwrap_or(mean + PI),
    };
    angle.check().map_err(|Invalid { param, reason }| {
        let at = match param {
            "mean" => o.mean.as_ref(),
            "kappa" => Some(kappa),
            "min" => o.min.as_ref().or(o.max.as_ref()),
            _ => o.max.as_ref().or(o.min.as_ref()),
        };
        src.invalid(
            format!("{key}.{param}"),
            at.map_or(raw.span(), Spanned::span),
            reason,
        )
    })?;
    Ok(Orientation::Tilt { axis, angle })
}

/// The first of the `given` keys (name, where it stands) that kind `name` does not take
/// (`takes`), as an error naming it and what the kind takes (`nothing` if none).
/// The keys an orientation table may hold, each with where it was given.
pub(super) fn given_keys(o: &RawOrientation) -> [(&'static str, Option<Range<usize>>); 11] {
    [
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
    ]
}

pub(super) fn foreign_keys(
    src: &Source,
    key: &str,
    name: &str,
    given: &[(&str, Option<Range<usize>>)],
    takes: &[&str],
    nothing: &str,
) -> Result<(), SceneError> {
    for (param, span) in given {
        if let (Some(span), false) = (span, takes.contains(param)) {
            let takes = if takes.is_empty() {
                nothing.to_owned()
            } else {
                takes.join(", ")
            };
            return Err(src.invalid(
                format!("{key}.{param}"),
                span.clone(),
                format!("does not apply to kind = \"{name}\", which takes {takes}"),
            ));
        }
    }
    Ok(())
}
