//! DAMASK's `material.yaml` and a `load.yaml` template, beside `rve.vti`.

use super::names::matrix_name;
use crate::contact::Dimension;
use crate::io::voxel::VoxelGrid;
use crate::packing::PackedGrain;
use crate::scene::{Elastic, Homogenization, RveFill, Scene, Units};
use std::io::{self, Write};

/// File name of DAMASK's material configuration.
pub const MATERIAL_YAML: &str = "material.yaml";
/// File name of the load case template.
pub const LOAD_YAML: &str = "load.yaml";

/// The elastic constants of a phase with neither `[phase.damask]` nor
/// `[phase.elastic]`: an isotropic placeholder (E = 200 GPa, ν = 0.3, here in Pa; every
/// writer converts it as it converts the scene's moduli: `material.yaml` in Pa, the
/// deck in the scene's `units.stress`), marked as one in the file, so that the set
/// loads and runs; replace it.
pub const PLACEHOLDER_ELASTIC: Elastic = Elastic {
    young: 200e9,
    poisson: 0.3,
};

/// Writes `material.yaml`: the scene's `homogenization` (default
/// [`Homogenization::single_crystal`]: `SX`, one constituent, `pass`), a
/// `phase` entry per scene phase (its `[phase.damask]` table as written, else an
/// isotropic Hooke phase from `[phase.elastic]` converted to Pa from the scene's
/// `units.stress`, else [`PLACEHOLDER_ELASTIC`]), the
/// matrix's when the grid has one, and the `material` list: entry `k` is grain `k` with
/// `O = crystals[k]` and the phase of `grains[k]` (printed so that it reads back to the same double), the matrix
/// last with the identity.
pub fn write_material_yaml(
    out: &mut dyn Write,
    scene: &Scene,
    grains: &[PackedGrain],
    crystals: &[[f64; 4]],
    grid: &VoxelGrid,
) -> io::Result<()> {
    let matrix = grid.fill == RveFill::Matrix;
    writeln!(out, "# DAMASK material configuration written by grainpack.")?;
    // The same text whatever the scene's units, so that one scene in MPa and µm and
    // the same in Pa and m give the same file.
    writeln!(
        out,
        "# Units: SI (Pa, m), as DAMASK reads them: [phase.elastic] converted from the \
         scene's units.stress, [phase.damask] as written."
    )?;
    writeln!(
        out,
        "# material k is grain k of grains.csv (and of rve.vti's `material`){}.",
        if matrix { ", the matrix last" } else { "" }
    )?;
    let homogenization = scene
        .homogenization
        .clone()
        .unwrap_or_else(Homogenization::single_crystal);
    let entry = flow(&homogenization.entry)?;
    let h = json(&homogenization.name);
    writeln!(out, "homogenization:")?;
    // The scene's table goes through as written, in flow style ([`flow`]).
    writeln!(out, "  {h}: {entry}")?;
    writeln!(out, "phase:")?;
    let mut names: Vec<&str> = scene.phases.iter().map(|p| p.name.as_str()).collect();
    for p in &scene.phases {
        write_phase(out, &p.name, p.damask.as_ref(), p.elastic, scene.units)?;
    }
    if matrix {
        let name = matrix_name(scene);
        write_phase(
            out,
            name,
            scene.matrix.damask.as_ref(),
            scene.matrix.elastic,
            scene.units,
        )?;
        names.push(name);
    }
    writeln!(out, "material:")?;
    for (g, o) in grains.iter().zip(crystals) {
        write_material(out, &h, names[g.phase], *o)?;
    }
    if matrix {
        write_material(out, &h, names[names.len() - 1], [1.0, 0.0, 0.0, 0.0])?;
    }
    Ok(())
}

fn write_material(
    out: &mut dyn Write,
    homogenization: &str,
    phase: &str,
    o: [f64; 4],
) -> io::Result<()> {
    writeln!(out, "  - homogenization: {homogenization}")?;
    writeln!(out, "    constituents:")?;
    writeln!(
        out,
        "      - {{phase: {}, v: 1.0, O: [{:?}, {:?}, {:?}, {:?}]}}",
        json(phase),
        o[0],
        o[1],
        o[2],
        o[3]
    )
}

fn write_phase(
    out: &mut dyn Write,
    name: &str,
    damask: Option<&toml::Table>,
    elastic: Option<Elastic>,
    units: Units,
) -> io::Result<()> {
    if let Some(table) = damask {
        // The table goes through as written, in flow style ([`flow`]).
        let text = flow(table)?;
        return writeln!(out, "  {}: {text}", json(name));
    }
    let (e, note) = match elastic {
        Some(e) => (
            Elastic {
                young: units.stress.to_si(e.young),
                ..e
            },
            "isotropic Hooke, from the scene's [phase.elastic], in Pa",
        ),
        None => (
            PLACEHOLDER_ELASTIC,
            "PLACEHOLDER: isotropic elastic E = 200 GPa, nu = 0.3; give [phase.damask] \
             (or [phase.elastic]) in the scene",
        ),
    };
    let [c11, c12, c44] = e.cubic();
    writeln!(out, "  # {note}")?;
    writeln!(out, "  {}:", json(name))?;
    writeln!(out, "    lattice: cF")?;
    writeln!(out, "    rho: 1.0")?;
    writeln!(out, "    mechanical:")?;
    writeln!(out, "      output: [F, P, O]")?;
    writeln!(
        out,
        "      elastic: {{type: Hooke, C_11: {c11:?}, C_12: {c12:?}, C_44: {c44:?}}}"
    )
}

/// `value` as a one-line YAML flow collection: JSON (which YAML 1.2 reads) with a blank
/// after every `:` and `,`. DAMASK's own YAML parser (used when DAMASK is built without
/// libfyaml, e.g. `YAML.f90` in v3.0.2) reads `"key": value` only with that blank and
/// stops with "error 705, unsupported feature" on compact JSON `{"key":value}`.
fn flow<T: serde::Serialize>(value: &T) -> io::Result<String> {
    fn write(v: &serde_json::Value, out: &mut String) {
        use serde_json::Value;
        match v {
            Value::Object(map) => {
                out.push('{');
                for (k, (key, v)) in map.iter().enumerate() {
                    if k > 0 {
                        out.push_str(", ");
                    }
                    out.push_str(&json(key));
                    out.push_str(": ");
                    write(v, out);
                }
                out.push('}');
            }
            Value::Array(items) => {
                out.push('[');
                for (k, v) in items.iter().enumerate() {
                    if k > 0 {
                        out.push_str(", ");
                    }
                    write(v, out);
                }
                out.push(']');
            }
            scalar => out.push_str(&scalar.to_string()),
        }
    }
    let value = serde_json::to_value(value).map_err(io::Error::other)?;
    let mut out = String::new();
    write(&value, &mut out);
    Ok(out)
}

/// A string as a JSON (so YAML) scalar, quoted and escaped.
fn json(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| format!("{s:?}"))
}

/// Writes `load.yaml`, a template for DAMASK's grid solver: uniaxial tension along x
/// at a strain rate of 10⁻³/s to 1 % (10 s in 20 increments), the other normal
/// stresses and the shear zero. For a 2D grid (one layer of cells along z) the load is
/// plane strain, as the plane-strain deck `rve.inp`: `F_zz` held at 1 (no rate), the
/// out-of-plane shears at zero, only `P_yy` free of load besides x; the comment says
/// how to free `F_zz` instead (generalised plane strain, `P_zz = 0`).
pub fn write_load_yaml(out: &mut dyn Write, grid: &VoxelGrid) -> io::Result<()> {
    let [nx, ny, nz] = grid.cells;
    let plane = grid.dimension == Dimension::Two;
    writeln!(
        out,
        "# DAMASK load case template written by grainpack for rve.vti ({nx} x {ny} x {nz} cells{}):",
        if plane { ", a 2D grid" } else { "" }
    )?;
    if plane {
        writeln!(
            out,
            "# uniaxial tension along x in plane strain, 1e-3/s for 10 s (1 % strain), P = 0 along y;"
        )?;
        writeln!(
            out,
            "# F_zz stays 1. For generalised plane strain, free it: dot_F zz -> x, P zz -> 0."
        )?;
    } else {
        writeln!(
            out,
            "# uniaxial tension along x, 1e-3/s for 10 s (1 % strain), P = 0 elsewhere."
        )?;
    }
    writeln!(
        out,
        "# Run: DAMASK_grid --load load.yaml --geom rve.vti --material material.yaml"
    )?;
    writeln!(out, "solver:")?;
    writeln!(out, "  mechanical: spectral_basic")?;
    writeln!(out, "loadstep:")?;
    writeln!(out, "  - boundary_conditions:")?;
    writeln!(out, "      mechanical:")?;
    if plane {
        writeln!(out, "        dot_F: [[1.0e-3, 0, 0], [0, x, 0], [0, 0, 0]]")?;
        writeln!(out, "        P: [[x, x, x], [x, 0, x], [x, x, x]]")?;
    } else {
        writeln!(out, "        dot_F: [[1.0e-3, 0, 0], [0, x, 0], [0, 0, x]]")?;
        writeln!(out, "        P: [[x, x, x], [x, 0, x], [x, x, 0]]")?;
    }
    writeln!(out, "    discretization: {{t: 10, N: 20}}")?;
    writeln!(out, "    f_out: 4")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_go_out_in_flow_style_with_blanks_after_colons_and_commas() {
        let table: toml::Table =
            toml::from_str("a = 1\nb = { c = [1.5, 2], d = \"x: y\" }\n").unwrap();
        assert_eq!(
            flow(&table).unwrap(),
            r#"{"a": 1, "b": {"c": [1.5, 2], "d": "x: y"}}"#
        );
    }
}
