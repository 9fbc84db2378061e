//! The solver input of a scene: `[homogenization]` and `[matrix]` (DAMASK's
//! `material.yaml`, the Abaqus deck), and the elastic constants the deck needs.

use super::texture;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::RawScene;
use crate::scene::{Homogenization, Matrix, OutputSpec, Phase, RveFill};
use toml::Spanned;

/// `[homogenization]`: only with `output.damask`; `name` a non-empty string (default
/// `SX`), `N_constituents` 1 (each material is one grain), the rest passed through.
pub(super) fn homogenization(
    src: &Source,
    raw: &RawScene,
    output: &OutputSpec,
) -> Result<Option<Homogenization>, SceneError> {
    let Some(h) = &raw.homogenization else {
        return Ok(None);
    };
    if !output.damask {
        return Err(src.invalid_at(
            "homogenization",
            h,
            "applies only to DAMASK's material.yaml (output.damask = true)",
        ));
    }
    let mut entry = h.get_ref().clone();
    let name = match entry.remove("name") {
        None => "SX".to_owned(),
        Some(toml::Value::String(s)) if !s.trim().is_empty() => s,
        Some(_) => {
            return Err(src.invalid_at(
                "homogenization.name",
                h,
                "must be a non-empty string (the name every material refers to)",
            ))
        }
    };
    match entry.get("N_constituents") {
        None => {
            entry.insert("N_constituents".into(), toml::Value::Integer(1));
        }
        Some(toml::Value::Integer(1)) => {}
        Some(_) => {
            return Err(src.invalid_at(
                "homogenization.N_constituents",
                h,
                "must be 1: each material of material.yaml is one grain",
            ))
        }
    }
    Ok(Some(Homogenization { name, entry }))
}

/// `[matrix]`: only with `rve_fill = "matrix"` or `mesh = true` (with `mesh_fill =
/// "matrix"`, its default), where there is a matrix.
pub(super) fn matrix(
    src: &Source,
    raw: &RawScene,
    output: &OutputSpec,
) -> Result<Matrix, SceneError> {
    let Some(m) = &raw.matrix else {
        return Ok(Matrix::default());
    };
    if output.rve.map(|r| r.fill) != Some(RveFill::Matrix)
        && output.mesh.map(|m| m.fill) != Some(RveFill::Matrix)
    {
        return Err(src.invalid_at(
            "matrix",
            m,
            "applies only with a voxel RVE whose gaps are a matrix (output.rve_fill = \
             \"matrix\") or a conforming mesh with a matrix (output.mesh = true, \
             mesh_fill = \"matrix\")",
        ));
    }
    let m = m.get_ref();
    Ok(Matrix {
        elastic: match &m.elastic {
            None => None,
            Some(e) => Some(texture::elastic(src, "matrix.elastic", e.get_ref())?),
        },
        damask: m.damask.as_ref().map(|d| d.get_ref().clone()),
    })
}

/// `abaqus = true` and `mesh = true` write a `*Material` per phase (and the matrix):
/// each needs its elastic constants. `switch` is the output key that asks for them.
pub(super) fn solids(
    src: &Source,
    raw: &RawScene,
    phases: &[Phase],
    matrix: &Matrix,
    fill: Option<RveFill>,
    switch: &str,
) -> Result<(), SceneError> {
    let flag = raw.output.as_ref().and_then(|o| {
        let o = o.get_ref();
        if switch == "mesh" {
            o.mesh.as_ref()
        } else {
            o.abaqus.as_ref()
        }
    });
    let at = flag.map_or(0..0, Spanned::span);
    for (i, p) in phases.iter().enumerate() {
        if p.elastic.is_none() {
            return Err(src.missing(
                format!("phase[{i}].elastic"),
                at,
                format!(
                    "output.{switch} = true writes a *Material per phase: give \
                     [phase.elastic] with E and nu"
                ),
            ));
        }
    }
    if fill == Some(RveFill::Matrix) && matrix.elastic.is_none() {
        let which = if switch == "mesh" {
            "output.mesh = true (the matrix fills the gaps between the grains)"
        } else {
            "output.abaqus = true with rve_fill = \"matrix\""
        };
        return Err(src.missing(
            "matrix.elastic",
            at,
            format!(
                "{which} writes a *Material for the matrix: give [matrix.elastic] with E \
                 and nu"
            ),
        ));
    }
    Ok(())
}
