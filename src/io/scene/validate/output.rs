//! `[output]` → [`OutputSpec`]: defaults filled in, the RVE's cells resolved against
//! the box, and every key that cannot take effect rejected rather than ignored.

use super::plane::not_in_2d;
use crate::contact::Dimension;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::{RawFill, RawOutput};
use crate::scene::{
    rve_cells, MeshSpec, OutputSpec, RveFill, RveSpec, VtkSpec, DEFAULT_RVE_CELLS, MAX_RVE_CELLS,
    MAX_RVE_CELLS_PER_EDGE, MAX_VTK_RESOLUTION, MESH_SIZE_RANGE, MIN_VTK_RESOLUTION,
};
use crate::scene::{Boundary, Domain};
use std::path::PathBuf;
use toml::Spanned;

/// Validates `[output]` for a scene whose box is `domain`.
pub(super) fn output(
    src: &Source,
    raw: Option<&Spanned<RawOutput>>,
    domain: &Domain,
) -> Result<OutputSpec, SceneError> {
    let plane = domain.dimension == Dimension::Two;
    let mut spec = OutputSpec {
        packing_png: plane,
        ..OutputSpec::default()
    };
    let Some(raw) = raw.map(Spanned::get_ref) else {
        return Ok(spec);
    };
    if let Some(dir) = &raw.dir {
        if dir.get_ref().trim().is_empty() {
            return Err(src.invalid_at("output.dir", dir, "must not be empty"));
        }
        spec.dir = PathBuf::from(dir.get_ref());
    }
    let flag =
        |v: &Option<Spanned<bool>>, default: bool| v.as_ref().map_or(default, |v| *v.get_ref());
    spec.grains_csv = flag(&raw.grains_csv, spec.grains_csv);
    spec.summary_json = flag(&raw.summary_json, spec.summary_json);
    spec.centers = flag(&raw.centers, spec.centers);
    spec.statistics_png = flag(&raw.statistics_png, spec.statistics_png);
    if let Some(v) = raw.packing_png.as_ref().filter(|v| *v.get_ref() && !plane) {
        return Err(src.invalid_at(
            "output.packing_png",
            v,
            "applies only to a 2D scene (a box with two lengths)",
        ));
    }
    spec.packing_png = flag(&raw.packing_png, spec.packing_png);
    spec.damask = flag(&raw.damask, false);
    spec.abaqus = flag(&raw.abaqus, false);
    spec.vtk = vtk(src, raw, domain)?;
    spec.rve = rve(src, raw, domain)?;
    spec.mesh = mesh(src, raw, plane)?;
    Ok(spec)
}

/// `mesh`, `mesh_size`, `mesh_order`, `mesh_fill`. The gap the mesh needs is checked with
/// `[packing]` (`validate::gap::meshable`).
fn mesh(src: &Source, raw: &RawOutput, plane: bool) -> Result<Option<MeshSpec>, SceneError> {
    let on = raw.mesh.as_ref().is_some_and(|v| *v.get_ref());
    if !on {
        if let Some(v) = &raw.mesh_size {
            return Err(src.invalid_at("output.mesh_size", v, "applies only with mesh = true"));
        }
        if let Some(v) = &raw.mesh_order {
            return Err(src.invalid_at("output.mesh_order", v, "applies only with mesh = true"));
        }
        if let Some(v) = &raw.mesh_fill {
            return Err(src.invalid_at("output.mesh_fill", v, "applies only with mesh = true"));
        }
        return Ok(None);
    }
    let mut spec = MeshSpec::default();
    if let Some(v) = &raw.mesh_size {
        let (lo, hi) = MESH_SIZE_RANGE;
        let h = *v.get_ref();
        if !(lo..=hi).contains(&h) {
            return Err(src.invalid_at(
                "output.mesh_size",
                v,
                format!(
                    "must lie in [{lo}, {hi}] (the largest element edge over the smallest \
                     grain's equivalent diameter)"
                ),
            ));
        }
        spec.size = h;
    }
    if let Some(v) = &raw.mesh_order {
        spec.order = match *v.get_ref() {
            1 => 1,
            2 => 2,
            _ => {
                return Err(src.invalid_at(
                    "output.mesh_order",
                    v,
                    if plane {
                        "must be 1 (linear triangles, CPE3) or 2 (quadratic, CPE6)"
                    } else {
                        "must be 1 (linear tetrahedra, C3D4) or 2 (quadratic, C3D10)"
                    },
                ))
            }
        };
    }
    if let Some(v) = &raw.mesh_fill {
        spec.fill = fill(*v.get_ref());
    }
    Ok(Some(spec))
}

/// `vtk`, `vtk_resolution`, `periodic_images`.
fn vtk(src: &Source, raw: &RawOutput, domain: &Domain) -> Result<Option<VtkSpec>, SceneError> {
    let on = raw.vtk.as_ref().is_none_or(|v| *v.get_ref());
    if !on {
        if let Some(v) = &raw.vtk_resolution {
            return Err(src.invalid_at("output.vtk_resolution", v, "applies only with vtk = true"));
        }
        if let Some(v) = &raw.periodic_images {
            return Err(src.invalid_at(
                "output.periodic_images",
                v,
                "applies only with vtk = true",
            ));
        }
        return Ok(None);
    }
    let mut spec = VtkSpec::default();
    if let Some(v) = &raw.vtk_resolution {
        let range = i64::from(MIN_VTK_RESOLUTION)..=i64::from(MAX_VTK_RESOLUTION);
        if !range.contains(v.get_ref()) {
            return Err(src.invalid_at(
                "output.vtk_resolution",
                v,
                format!(
                    "must lie in [{MIN_VTK_RESOLUTION}, {MAX_VTK_RESOLUTION}] ({})",
                    match domain.dimension {
                        Dimension::Three => "20·4^n triangles per grain",
                        Dimension::Two => "a polygon of 8·2^n points per ellipse",
                    }
                ),
            ));
        }
        spec.resolution = *v.get_ref() as u32;
    }
    if let Some(v) = &raw.periodic_images {
        if *v.get_ref() && domain.boundary != Boundary::Periodic {
            return Err(src.invalid_at(
                "output.periodic_images",
                v,
                "applies only to a periodic box (box.boundary = \"periodic\")",
            ));
        }
        spec.periodic_images = *v.get_ref();
    }
    Ok(Some(spec))
}

/// `rve`, `rve_resolution` or `rve_voxel_size`, `rve_fill`, `sections_png`.
fn rve(src: &Source, raw: &RawOutput, domain: &Domain) -> Result<Option<RveSpec>, SceneError> {
    // damask and abaqus write files beside rve.vti, on its cells.
    let implied = [
        ("output.damask", &raw.damask),
        ("output.abaqus", &raw.abaqus),
    ]
    .into_iter()
    .find_map(|(key, v)| v.as_ref().filter(|v| *v.get_ref()).map(|v| (key, v)));
    if let (Some((key, at)), Some(rve)) = (implied, raw.rve.as_ref()) {
        if !*rve.get_ref() {
            return Err(src.invalid_at(
                key,
                at,
                "writes files on the voxel RVE's cells, which rve = false turns off",
            ));
        }
    }
    let on = raw.rve.as_ref().is_some_and(|v| *v.get_ref()) || implied.is_some();
    if !on {
        let needs_rve = "applies only with rve = true";
        if let Some(v) = &raw.rve_resolution {
            return Err(src.invalid_at("output.rve_resolution", v, needs_rve));
        }
        if let Some(v) = &raw.rve_voxel_size {
            return Err(src.invalid_at("output.rve_voxel_size", v, needs_rve));
        }
        if let Some(v) = &raw.rve_fill {
            return Err(src.invalid_at("output.rve_fill", v, needs_rve));
        }
        if let Some(v) = raw.sections_png.as_ref().filter(|v| *v.get_ref()) {
            return Err(src.invalid_at("output.sections_png", v, needs_rve));
        }
        return Ok(None);
    }
    // The cells, and the key they came from (for the limit's message).
    let (cells, from) = match (&raw.rve_resolution, &raw.rve_voxel_size) {
        (Some(_), Some(h)) => {
            return Err(src.invalid_at(
                "output.rve_voxel_size",
                h,
                "give either rve_resolution or rve_voxel_size, not both",
            ))
        }
        (Some(n), None) => (
            resolution(src, n, domain)?,
            Some(("output.rve_resolution", n.span())),
        ),
        (None, Some(h)) => (
            voxel_size(src, h, domain)?,
            Some(("output.rve_voxel_size", h.span())),
        ),
        // At most DEFAULT_RVE_CELLS³, far below the limit.
        (None, None) => (rve_cells(DEFAULT_RVE_CELLS, domain), None),
    };
    let count: u64 = cells.iter().map(|&n| n as u64).product();
    if let Some((key, at)) = from.filter(|_| count > MAX_RVE_CELLS) {
        return Err(src.invalid(
            key,
            at,
            format!(
                "gives {} × {} × {} = {count} cells, more than the limit {MAX_RVE_CELLS}",
                cells[0], cells[1], cells[2]
            ),
        ));
    }
    let fill = raw
        .rve_fill
        .as_ref()
        .map_or(RveFill::Grains, |f| fill(*f.get_ref()));
    // A 2D RVE is one cell thick: it is its own section.
    let sections_png = match (&raw.sections_png, domain.dimension) {
        (Some(v), Dimension::Two) if *v.get_ref() => {
            return Err(not_in_2d(
                src,
                "output.sections_png",
                v.span(),
                "the RVE of a 2D scene is one cell thick, its own section",
            ))
        }
        (_, Dimension::Two) => false,
        (v, Dimension::Three) => v.as_ref().is_none_or(|v| *v.get_ref()),
    };
    Ok(Some(RveSpec {
        cells,
        fill,
        sections_png,
    }))
}

/// `rve_resolution = N` (N cells along the longest edge, proportionally many along
/// the others) or `[nx, ny, nz]`; `[nx, ny]` in a 2D scene (one cell along z).
fn resolution(
    src: &Source,
    raw: &Spanned<toml::Value>,
    domain: &Domain,
) -> Result<[usize; 3], SceneError> {
    let key = "output.rve_resolution";
    let limit = MAX_RVE_CELLS_PER_EDGE as i64;
    let edge = |v: &toml::Value| match v {
        toml::Value::Integer(n) if (1..=limit).contains(n) => Some(*n as usize),
        _ => None,
    };
    let (edges, shape) = match domain.dimension {
        Dimension::Three => (
            3,
            format!(
                "must be an integer or an array of three integers, each in [1, \
                 {MAX_RVE_CELLS_PER_EDGE}]"
            ),
        ),
        Dimension::Two => (
            2,
            format!(
                "must be an integer or an array of two integers [nx, ny] (a 2D scene's RVE is \
                 one cell thick), each in [1, {MAX_RVE_CELLS_PER_EDGE}]"
            ),
        ),
    };
    match raw.get_ref() {
        toml::Value::Array(items) if items.len() == edges => {
            let mut cells: Vec<usize> = items.iter().filter_map(edge).collect();
            if edges == 2 && cells.len() == 2 {
                cells.push(1);
            }
            <[usize; 3]>::try_from(cells).map_err(|_| src.invalid_at(key, raw, shape))
        }
        value => match edge(value) {
            Some(n) => Ok(rve_cells(n, domain)),
            None => Err(src.invalid_at(key, raw, shape)),
        },
    }
}

/// `rve_voxel_size = h`: `round(L/h)` cells along each edge, at least 1.
fn voxel_size(src: &Source, raw: &Spanned<f64>, domain: &Domain) -> Result<[usize; 3], SceneError> {
    let key = "output.rve_voxel_size";
    let h = *raw.get_ref();
    if !(h.is_finite() && h > 0.0) {
        return Err(src.invalid_at(key, raw, "must be positive and finite"));
    }
    // One cell along z in 2D.
    let mut cells = [1; 3];
    for (i, (&l, n)) in domain.sides().iter().zip(&mut cells).enumerate() {
        let count = (l / h).round().max(1.0);
        if count > MAX_RVE_CELLS_PER_EDGE as f64 {
            let axis = ["x", "y", "z"][i];
            return Err(src.invalid_at(
                key,
                raw,
                format!(
                    "gives {count} cells along {axis} (box side {l}), more than the limit \
                     {MAX_RVE_CELLS_PER_EDGE}"
                ),
            ));
        }
        *n = count as usize;
    }
    Ok(cells)
}

fn fill(raw: RawFill) -> RveFill {
    match raw {
        RawFill::Grains => RveFill::Grains,
        RawFill::Matrix => RveFill::Matrix,
    }
}
