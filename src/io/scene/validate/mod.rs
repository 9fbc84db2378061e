//! Raw scene → [`Scene`]: every value checked, every default filled in, every error
//! located.

mod axis;
mod count;
mod fisher;
mod gap;
mod grain;
mod measured;
mod measured_columns;
mod mixed;
mod output;
mod plane;
mod smallest;
mod solver;
mod table;
mod texture;
mod triaxial;
mod units;

use super::error::{SceneError, Source};
use super::raw::{RawPacking, RawPhase, RawScene};
use crate::contact::Dimension;
use crate::laws::Distribution;
use crate::scene::{
    Domain, Orientation, PackingParams, Phase, PhaseTexture, Rotation, Scene, Unjam,
};
use grain::{distribution, orientation};
use plane::not_in_2d;
use serde::Deserialize;
use std::collections::HashSet;
use toml::de::{DeTable, Deserializer};
use toml::Spanned;

/// Parses, deserializes and validates a scene file's text.
pub(super) fn scene(text: &str, file: &str) -> Result<Scene, SceneError> {
    let src = Source { file, text };
    let document = DeTable::parse(text).map_err(|e| src.syntax(&e))?;
    let raw = RawScene::deserialize(Deserializer::from(document.clone()))
        .map_err(|e| src.shape(&e, document.get_ref()))?;

    let domain = plane::domain(&src, &raw.domain)?;
    if raw.phase.is_empty() {
        return Err(src.missing("phase", 0..0, "at least one [[phase]] is needed"));
    }
    let mut names = HashSet::new();
    let mut phases = Vec::with_capacity(raw.phase.len());
    let has_exact = raw.phase.iter().any(|p| {
        let mode = p
            .get_ref()
            .measured
            .as_ref()
            .and_then(|m| m.get_ref().mode.clone());
        mode.is_some_and(|m| m.get_ref() == "exact")
    });
    for (i, p) in raw.phase.iter().enumerate() {
        let phase = phase(&src, i, p, &domain, has_exact)?;
        if !names.insert(phase.name.clone()) {
            let at = p.get_ref().name.as_ref().map_or(p.span(), |n| n.span());
            return Err(src.invalid(format!("phase[{i}].name"), at, "two phases have this name"));
        }
        phases.push(phase);
    }
    let total: f64 = phases.iter().map(|p| p.share).sum();
    for p in &mut phases {
        p.share /= total;
    }

    // Exact measured tables fix the count (and the box); mixed with drawn phases, the
    // grain volume and the box (see mixed.rs).
    let exact: Vec<bool> = phases.iter().map(mixed::is_exact).collect();
    let (count, domain) = if !exact.is_empty() && exact.iter().all(|&e| e) {
        mixed::exact_scene(&src, &raw, domain, &mut phases)?
    } else if exact.iter().any(|&e| e) {
        mixed::mixed_scene(&src, &raw, domain, &mut phases)?
    } else {
        (count::count(&src, &raw, &domain, &phases)?, domain)
    };

    let units = units::units(&src, &raw)?;
    let warnings = units::warnings(&src, &raw, units, &domain);
    let output = output::output(&src, raw.output.as_ref(), &domain)?;
    let matrix = solver::matrix(&src, &raw, &output)?;
    if output.abaqus {
        let fill = output.rve.map(|r| r.fill);
        solver::solids(&src, &raw, &phases, &matrix, fill, "abaqus")?;
    }
    if let Some(mesh) = output.mesh {
        solver::solids(&src, &raw, &phases, &matrix, Some(mesh.fill), "mesh")?;
    }

    let scene = Scene {
        seed: raw.seed.as_ref().map_or(0, |s| *s.get_ref()),
        count,
        domain,
        phases,
        packing: packing(&src, raw.packing.as_ref(), domain.dimension)?,
        homogenization: solver::homogenization(&src, &raw, &output)?,
        output,
        matrix,
        units,
        warnings,
    };
    gap::fits(&src, raw.packing.as_ref(), &scene)?;
    gap::meshable(&src, &raw, &scene)?;
    Ok(scene)
}

fn phase(
    src: &Source,
    i: usize,
    raw: &Spanned<RawPhase>,
    domain: &Domain,
    scene_has_exact: bool,
) -> Result<Phase, SceneError> {
    let key = format!("phase[{i}]");
    let p = raw.get_ref();
    let name = match &p.name {
        Some(n) if n.get_ref().trim().is_empty() => {
            return Err(src.invalid_at(format!("{key}.name"), n, "must not be empty"));
        }
        Some(n) => n.get_ref().clone(),
        None => format!("phase{i}"),
    };
    let share = match &p.share {
        None => 1.0,
        Some(s) if s.get_ref().is_finite() && *s.get_ref() > 0.0 => *s.get_ref(),
        Some(s) => {
            return Err(src.invalid_at(format!("{key}.share"), s, "must be positive and finite"))
        }
    };
    plane::no_triaxial(src, &key, p, domain.dimension)?;
    let (measured, size) = match (&p.measured, &p.size) {
        (Some(_), Some(s)) => {
            return Err(src.invalid_at(
                format!("{key}.size"),
                s,
                "the sizes come from [phase.measured]; give one or the other",
            ))
        }
        (Some(m), None) => {
            let (m, size) =
                measured::measured(src, &format!("{key}.measured"), m, domain.dimension)?;
            (Some(m), size)
        }
        (None, Some(s)) => (
            None,
            distribution(src, &format!("{key}.size"), s, domain.dimension)?,
        ),
        (None, None) => {
            return Err(src.missing(
                format!("{key}.size"),
                raw.span(),
                "each phase needs size (a law) or [phase.measured] (a grain table)",
            ))
        }
    };
    if let Some(m) = &measured {
        let given = [
            (
                "aspect_ratio",
                m.has_semi_axes(),
                p.aspect_ratio.as_ref().map(Spanned::span),
            ),
            (
                "b_over_a",
                m.has_semi_axes(),
                p.b_over_a.as_ref().map(Spanned::span),
            ),
            (
                "orientation",
                m.has_orientations(),
                p.orientation.as_ref().map(Spanned::span),
            ),
            (
                "texture",
                m.has_crystals(),
                p.texture.as_ref().map(Spanned::span),
            ),
        ];
        for (name, from_table, span) in given {
            if let (true, Some(span)) = (from_table, span) {
                return Err(src.invalid(
                    format!("{key}.{name}"),
                    span,
                    "the measured table gives this for every grain; remove the key",
                ));
            }
        }
    }
    let aspect_ratio = match &p.aspect_ratio {
        None => Distribution::Constant { value: 1.0 },
        Some(a) => distribution(src, &format!("{key}.aspect_ratio"), a, domain.dimension)?,
    };
    let orientation = match &p.orientation {
        None => Orientation::Random,
        Some(o) if domain.dimension == Dimension::Two => {
            plane::orientation(src, &format!("{key}.orientation"), o)?
        }
        Some(o) => orientation(src, &format!("{key}.orientation"), o)?,
    };
    let spherical = aspect_ratio == Distribution::Constant { value: 1.0 };
    let texture = match &p.texture {
        None => PhaseTexture::default(),
        Some(t) => texture::texture(src, &format!("{key}.texture"), t, spherical)?,
    };
    let elastic = match &p.elastic {
        None => None,
        Some(e) => Some(texture::elastic(
            src,
            &format!("{key}.elastic"),
            e.get_ref(),
        )?),
    };
    let phase = Phase {
        name,
        share,
        size: size.clone(),
        aspect_ratio,
        orientation,
        texture,
        elastic,
        damask: p.damask.as_ref().map(|d| d.get_ref().clone()),
        triaxial: triaxial::triaxial(src, &key, p)?,
        measured,
        dimension: domain.dimension,
    };

    let (longest, side) = (phase.max_length(), domain.min_side());
    // A box of exact tables (all, or mixed with drawn phases) may still be scaled by
    // target_fraction: checked after that, for every phase (measured::sized_box).
    if longest >= side && !scene_has_exact {
        // Blame the size's upper bound; the message names the aspect ratios too.
        let param = match size {
            Distribution::Constant { .. } => "value",
            Distribution::Table(_) => "x",
            _ => "max",
        };
        let at = match (&p.size, &p.measured) {
            (Some(s), _) => match param {
                "x" => s.get_ref().x.as_ref().map(|v| v.span()),
                _ => s.get_ref().param(param).map(|v| v.span()),
            }
            .unwrap_or(s.span()),
            (None, Some(m)) => m.span(),
            (None, None) => raw.span(),
        };
        let (a_min, a_max) = phase.aspect_ratio.support();
        let shapes = match &phase.triaxial {
            None => format!("aspect ratios in [{a_min}, {a_max}]"),
            Some(t) => format!("shape ratios down to b/a · c/a = {}", t.min_product()),
        };
        return Err(src.invalid(
            format!("{key}.size.{param}"),
            at,
            format!(
                "the longest grain ({longest} end to end, with {shapes}) does not fit in the \
                 box, whose shortest side is {side}"
            ),
        ));
    }
    smallest::resolved(src, &key, raw, &phase)?;
    Ok(phase)
}

fn packing(
    src: &Source,
    raw: Option<&Spanned<RawPacking>>,
    dimension: Dimension,
) -> Result<PackingParams, SceneError> {
    let mut params = PackingParams::default();
    let Some(raw) = raw.map(Spanned::get_ref) else {
        return Ok(params);
    };
    if let Some(v) = &raw.max_steps {
        if *v.get_ref() == 0 {
            return Err(src.invalid_at("packing.max_steps", v, "must be at least 1"));
        }
        params.max_steps = *v.get_ref();
    }
    if let Some(v) = &raw.jam_resolution {
        if !(*v.get_ref() > 0.0 && *v.get_ref() <= 0.1) {
            return Err(src.invalid_at("packing.jam_resolution", v, "must lie in (0, 0.1]"));
        }
        params.jam_resolution = *v.get_ref();
    }
    if let Some(v) = &raw.time_limit {
        if !(v.get_ref().is_finite() && *v.get_ref() > 0.0) {
            return Err(src.invalid_at(
                "packing.time_limit",
                v,
                "must be a positive number of seconds",
            ));
        }
        params.time_limit = Some(*v.get_ref());
    }
    if let Some(v) = &raw.effort {
        if !(*v.get_ref() >= MIN_EFFORT && *v.get_ref() <= MAX_EFFORT) {
            return Err(src.invalid_at("packing.effort", v, "must lie in [0.1, 100]"));
        }
        params.effort = *v.get_ref();
    }
    if let Some(v) = &raw.rotation {
        params.rotation = match v.get_ref() {
            toml::Value::Boolean(false) => Rotation::None,
            toml::Value::Boolean(true) => Rotation::Free,
            toml::Value::String(s) if s == "axis" && dimension == Dimension::Two => {
                return Err(not_in_2d(
                    src,
                    "packing.rotation",
                    v.span(),
                    "every grain in the plane turns about z; give true (turn) or false",
                ))
            }
            toml::Value::String(s) if s == "axis" => Rotation::Axis,
            _ => {
                return Err(src.invalid_at(
                    "packing.rotation",
                    v,
                    "must be false (orientations as drawn), true (grains turn freely) or \"axis\" (grains of tilt phases turn about the tilt axis, of fisher phases about their first axis)",
                ))
            }
        };
    }
    if let Some(v) = &raw.max_turn {
        let turn = *v.get_ref();
        if !(turn > 0.0 && turn <= 180.0) {
            return Err(src.invalid_at("packing.max_turn", v, "must lie in (0, 180] degrees"));
        }
        params.max_turn = turn.to_radians();
    }
    if let Some(v) = &raw.restore {
        params.restore = *v.get_ref();
    }
    if let Some(v) = &raw.unjam {
        params.unjam = (Unjam::NAMES.iter())
            .find(|(name, _)| name == v.get_ref())
            .map(|&(_, u)| u)
            .ok_or_else(|| {
                src.invalid_at(
                    "packing.unjam",
                    v,
                    "must be \"none\", \"swap\" or \"anneal\"",
                )
            })?;
        if params.unjam != Unjam::None
            && params.effort < crate::packing::MIN_CYCLE_EFFORT
            && params.time_limit.is_none()
        {
            return Err(src.invalid_at(
                "packing.unjam",
                v,
                format!(
                    "acts between effort's recompression cycles: needs packing.effort ≥ \
                     {} (it is {})",
                    crate::packing::MIN_CYCLE_EFFORT,
                    params.effort
                ),
            ));
        }
    }
    if let Some(v) = &raw.gap {
        params.gap = gap::value(src, v)?;
    }
    Ok(params)
}

/// The range of `packing.effort`: from a tenth of the default budget per trial (100
/// FIRE steps) to a hundred times it.
const MIN_EFFORT: f64 = 0.1;
/// See [`MIN_EFFORT`].
const MAX_EFFORT: f64 = 100.0;
