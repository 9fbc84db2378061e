//! The Abaqus/CalculiX deck `rve.inp`: the voxel RVE as C3D8 hexahedra, written as it
//! is made (memory: one `u32` per cell for the grain sets, besides the grid).
//!
//! Numbering: cell `(i, j, k)` of `rve.vti` is element `1 + i + Nx (j + Ny k)`; node
//! `(i, j, k)`, at `(i hx, j hy, k hz)`, is `1 + i + (Nx+1)(j + (Ny+1) k)`. The three
//! reference nodes `RPX`, `RPY`, `RPZ` follow the grid's nodes.
//!
//! # Periodic constraints
//! In a periodic box, every node with an index at the far face (`i = Nx`, `j = Ny` or
//! `k = Nz`) is tied to its image at the near faces (those indices set to 0):
//! `u(node) − u(image) − Σ u(RP_d) = 0`, the sum over the directions `d` in which it
//! is at the far face. The displacement of `RP_d` is thus the jump of `u` across the
//! box along `d`: `u(RPX) = H · (Lx, 0, 0)` for a macroscopic displacement gradient
//! `H`, and the reaction force on `RPX` is the total force on the face `x = Lx`. Each
//! far node is the first (dependent) term of exactly one equation and never a term's
//! image, so the equations are independent.
//!
//! # Two dimensions
//! A 2D grid (one layer of pixels) is written as its plane: CPE4 quadrilaterals,
//! element `1 + i + Nx j` on pixel `(i, j)`, node `1 + i + (Nx+1) j` at `(i hx, j hy)`
//! (the numbers of the 3D formulas at `k = 0`), reference nodes `RPX`, `RPY`, and the
//! same equations on the two in-plane components (`super::boundary` writes both).

use super::boundary::{
    axes, last_layer, node, reference_nodes, write_equations, write_list, write_node_sets, AXES,
};
use super::damask::PLACEHOLDER_ELASTIC;
use super::names::{matrix_name, section_name};
use crate::contact::Dimension;
use crate::io::voxel::VoxelGrid;
use crate::packing::PackedGrain;
use crate::scene::{quaternion_to_euler, Elastic, RveFill, Scene};
use std::io::{self, Write};

/// File name of the deck.
pub const RVE_INP: &str = "rve.inp";
/// File name of the per-grain UMAT sections.
pub const RVE_UMAT_INP: &str = "rve_umat.inp";

/// The line between the model and the step template in `rve.inp`: a script may cut
/// the deck there and append a step of its own.
pub const STEP_MARKER: &str = "** ---- step template";

/// The strain of the template step (uniaxial along x).
pub const TEMPLATE_STRAIN: f64 = 1e-3;

/// The thickness of the plane-strain sections of a 2D deck (in the scene's length
/// unit): forces are per unit thickness.
pub const PLANE_THICKNESS: f64 = 1.0;

/// Writes `rve.inp` for `grid`: nodes, elements, an element set per grain
/// (`GRAIN_k`, grains without voxels skipped) and per phase (`PHASE<i>_<NAME>`,
/// `MATRIX`), node sets of the six faces (`X0`, `X1`, ...), twelve edges (`X0Y0`, ...)
/// and eight corners (`X0Y0Z0`, ...), the reference nodes, the periodic equations
/// (periodic box), a `*Material` and `*Solid Section` per phase from the scene's
/// elastic constants, and a static step in uniaxial strain along x. Every number is in
/// the scene's units (`[units]`, named in a comment at the top): coordinates in
/// `units.length`, moduli in `units.stress`.
///
/// A 2D grid (one layer of pixels) gives the plane-strain deck: CPE4 elements on the
/// pixels, nodes `(x, y)` numbered as the `k = 0` plane of the 3D grid, the edges
/// `X0`, `X1`, `Y0`, `Y1` and four corners, reference nodes `RPX`, `RPY`, equations
/// on the two in-plane components, sections of thickness 1 (the out-of-plane strain is
/// zero), and a step in uniaxial stress along x (`RPY` free along y).
pub fn write_abaqus_deck(out: &mut dyn Write, scene: &Scene, grid: &VoxelGrid) -> io::Result<()> {
    let [nx, ny, nz] = grid.cells;
    let h = grid.spacing();
    let size = grid.size;
    let plane = grid.dimension == Dimension::Two;
    let element = if plane { "CPE4" } else { "C3D8" };
    writeln!(out, "*Heading")?;
    let periodic = if grid.periodic {
        "periodic"
    } else {
        "not periodic"
    };
    let unit = scene.units.length.symbol();
    if plane {
        writeln!(
            out,
            "grainpack pixel RVE: {nx} x {ny} {element} elements (plane strain, thickness 1), \
             rectangle {} x {} {unit}, {periodic}",
            size[0], size[1]
        )?;
    } else {
        writeln!(
            out,
            "grainpack voxel RVE: {nx} x {ny} x {nz} {element} elements, box {} x {} x {} {unit}, \
             {periodic}",
            size[0], size[1], size[2]
        )?;
    }
    let (length, stress) = (scene.units.length.symbol(), scene.units.stress.symbol());
    writeln!(
        out,
        "** units (the scene's [units]): lengths in {length}, stresses and E in {stress}, \
         forces in {stress}*{length}^2"
    )?;
    if plane {
        writeln!(out, "** element 1 + i + Nx j is cell (i, j, 0) of rve.vti;")?;
        writeln!(out, "** node 1 + i + (Nx+1) j lies at (i hx, j hy).")?;
    } else {
        writeln!(
            out,
            "** element 1 + i + Nx (j + Ny k) is cell (i, j, k) of rve.vti;"
        )?;
        writeln!(
            out,
            "** node 1 + i + (Nx+1)(j + (Ny+1) k) lies at (i hx, j hy, k hz)."
        )?;
    }
    writeln!(out, "*Node")?;
    for k in 0..=last_layer(grid) {
        for j in 0..=ny {
            for i in 0..=nx {
                let id = node(grid, i, j, k);
                let (x, y, z) = (i as f64 * h[0], j as f64 * h[1], k as f64 * h[2]);
                if plane {
                    writeln!(out, "{id}, {x:?}, {y:?}")?;
                } else {
                    writeln!(out, "{id}, {x:?}, {y:?}, {z:?}")?;
                }
            }
        }
    }
    let rp = reference_nodes(grid);
    for (d, id) in rp.iter().enumerate() {
        let mut at = [0.0; 3];
        at[d] = size[d];
        if plane {
            writeln!(out, "{id}, {:?}, {:?}", at[0], at[1])?;
        } else {
            writeln!(out, "{id}, {:?}, {:?}, {:?}", at[0], at[1], at[2])?;
        }
    }
    writeln!(out, "*Element, type={element}")?;
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let n = |a, b, c| node(grid, i + a, j + b, k + c);
                let e = grid.index(i, j, k) + 1;
                if plane {
                    // Counter-clockwise, as Abaqus numbers a quadrilateral.
                    let [a, b, c, d] = [n(0, 0, 0), n(1, 0, 0), n(1, 1, 0), n(0, 1, 0)];
                    writeln!(out, "{e}, {a}, {b}, {c}, {d}")?;
                    continue;
                }
                writeln!(
                    out,
                    "{}, {}, {}, {}, {}, {}, {}, {}, {}",
                    e,
                    n(0, 0, 0),
                    n(1, 0, 0),
                    n(1, 1, 0),
                    n(0, 1, 0),
                    n(0, 0, 1),
                    n(1, 0, 1),
                    n(1, 1, 1),
                    n(0, 1, 1)
                )?;
            }
        }
    }
    write_grain_sets(out, grid)?;
    for (name, phase, _) in solids(scene, grid) {
        write_list(out, &format!("*Elset, elset={name}"), {
            let phase = phase as u32;
            grid.phase
                .iter()
                .enumerate()
                .filter(move |(_, &p)| p == phase)
                .map(|(e, _)| e + 1)
        })?;
    }
    write_node_sets(out, grid)?;
    let names: Vec<String> = AXES[..axes(grid)]
        .iter()
        .map(|a| format!("RP{a}"))
        .collect();
    for (name, id) in names.iter().zip(&rp) {
        writeln!(out, "*Nset, nset={name}\n{id}")?;
    }
    writeln!(out, "*Nset, nset=RP\n{}", names.join(", "))?;
    if grid.periodic {
        write_equations(out, grid, &rp)?;
    }
    for (name, _, elastic) in solids(scene, grid) {
        writeln!(out, "*Material, name={name}")?;
        writeln!(out, "*Elastic")?;
        writeln!(out, "{:?}, {:?}", elastic.young, elastic.poisson)?;
        write_section(out, grid, &name)?;
    }
    if plane {
        write_plane_step(out, [size[0], size[1]], grid.periodic)
    } else {
        write_solid_step(out, grid)
    }
}

/// `*Solid Section` of `elset` with the material of the same name; a plane-strain
/// section's data line is its thickness, 1.
fn write_section(out: &mut dyn Write, grid: &VoxelGrid, elset: &str) -> io::Result<()> {
    writeln!(out, "*Solid Section, elset={elset}, material={elset}")?;
    if grid.dimension == Dimension::Two {
        writeln!(out, "{PLANE_THICKNESS:?}")?;
    }
    Ok(())
}

/// The 3D step template: uniaxial strain along x.
fn write_solid_step(out: &mut dyn Write, grid: &VoxelGrid) -> io::Result<()> {
    let size = grid.size;
    writeln!(
        out,
        "{STEP_MARKER}: uniaxial strain {TEMPLATE_STRAIN:e} along x"
    )?;
    writeln!(out, "*Boundary")?;
    writeln!(out, "{}, 1, 3, 0.0", node(grid, 0, 0, 0))?;
    writeln!(out, "*Step")?;
    writeln!(out, "*Static")?;
    writeln!(out, "*Boundary")?;
    if grid.periodic {
        // The jump across x is the imposed strain; the lateral normal strains are free
        // (no normal force), the shears held at zero.
        writeln!(out, "RPX, 1, 1, {:?}", TEMPLATE_STRAIN * size[0])?;
        writeln!(
            out,
            "RPX, 2, 3, 0.0\nRPY, 1, 1, 0.0\nRPY, 3, 3, 0.0\nRPZ, 1, 2, 0.0"
        )?;
        // CalculiX reports no reaction at nodes tied only by equations: the force on
        // the face x = Lx is the sum of the reactions of its nodes.
        writeln!(out, "*Node Print, nset=RP\nU")?;
        writeln!(out, "*Node Print, nset=X1, totals=only\nRF")?;
    } else {
        writeln!(out, "X0, 1, 1, 0.0\nY0, 2, 2, 0.0\nZ0, 3, 3, 0.0")?;
        writeln!(out, "X1, 1, 1, {:?}", TEMPLATE_STRAIN * size[0])?;
        writeln!(out, "*Node Print, nset=X1, totals=only\nRF")?;
    }
    writeln!(out, "*End Step")
}

/// The 2D step template of a `size[0]` × `size[1]` rectangle: the normal strain along
/// x imposed, the normal stress along y free (zero), the shear held at zero; plane
/// strain (zero strain along z) by the elements. The normal stress along x over the
/// strain is the plane-strain modulus `E/(1 − ν²)` of a homogeneous RVE. Node 1, the
/// rectangle's origin corner in `rve.inp` and in the conforming mesh's `mesh.inp`, is
/// fixed; a periodic deck needs the reference nodes `RPX`, `RPY` and the node sets `RP`
/// and `X1`, a walled one `X0`, `Y0` and `X1`.
pub fn write_plane_step(out: &mut dyn Write, size: [f64; 2], periodic: bool) -> io::Result<()> {
    writeln!(
        out,
        "{STEP_MARKER}: uniaxial stress along x, strain {TEMPLATE_STRAIN:e}, plane strain"
    )?;
    writeln!(out, "*Boundary")?;
    writeln!(out, "1, 1, 2, 0.0")?;
    writeln!(out, "*Step")?;
    writeln!(out, "*Static")?;
    writeln!(out, "*Boundary")?;
    if periodic {
        writeln!(out, "RPX, 1, 1, {:?}", TEMPLATE_STRAIN * size[0])?;
        writeln!(out, "RPX, 2, 2, 0.0\nRPY, 1, 1, 0.0")?;
        writeln!(out, "*Node Print, nset=RP\nU")?;
    } else {
        writeln!(out, "X0, 1, 1, 0.0\nY0, 2, 2, 0.0")?;
        writeln!(out, "X1, 1, 1, {:?}", TEMPLATE_STRAIN * size[0])?;
    }
    writeln!(out, "*Node Print, nset=X1, totals=only\nRF")?;
    writeln!(out, "*End Step")
}

/// Writes `rve_umat.inp`: for each grain with voxels a `*Material` with `*Depvar`
/// and `*User Material` constants (phase index, Bunge Euler angles φ1, Φ, φ2 in
/// degrees) and its `*Solid Section`; to use it, replace `rve.inp`'s phase sections by
/// `*Include, input=rve_umat.inp` (and adapt `*Depvar` to the UMAT).
pub fn write_umat_sections(
    out: &mut dyn Write,
    scene: &Scene,
    grains: &[PackedGrain],
    crystals: &[[f64; 4]],
    grid: &VoxelGrid,
) -> io::Result<()> {
    let counts = material_counts(grid);
    writeln!(
        out,
        "** Per-grain UMAT sections for rve.inp, written by grainpack."
    )?;
    writeln!(
        out,
        "** Constants: phase index, Bunge Euler angles phi1, Phi, phi2 (degrees)."
    )?;
    for (g, o) in grains.iter().zip(crystals) {
        if counts[g.id as usize] == 0 {
            continue;
        }
        let [p1, p, p2] = quaternion_to_euler(*o).map(f64::to_degrees);
        let name = format!("GRAIN_{}", g.id);
        writeln!(out, "*Material, name={name}\n*Depvar\n1")?;
        writeln!(
            out,
            "*User Material, constants=4\n{}, {p1:?}, {p:?}, {p2:?}",
            g.phase
        )?;
        write_section(out, grid, &name)?;
    }
    if let Some((name, _, _)) = solids(scene, grid)
        .into_iter()
        .find(|(_, p, _)| *p == grid.phases)
    {
        writeln!(out, "*Material, name={name}\n*Depvar\n1")?;
        writeln!(
            out,
            "*User Material, constants=4\n{}, 0.0, 0.0, 0.0",
            grid.phases
        )?;
        write_section(out, grid, &name)?;
    }
    Ok(())
}

/// The element sets with material: `(name, phase number, elastic constants)` of each
/// phase with voxels, the matrix last. Validation gave every phase (and the matrix)
/// its constants when the deck is written; a missing one would be a bug, and takes
/// the DAMASK placeholder rather than writing nothing.
fn solids(scene: &Scene, grid: &VoxelGrid) -> Vec<(String, usize, Elastic)> {
    let mut present = vec![false; grid.phases + 1];
    for &p in &grid.phase {
        present[p as usize] = true;
    }
    // The placeholder is in Pa; the deck is in the scene's stress unit.
    let fallback = Elastic {
        young: scene.units.stress.from_si(PLACEHOLDER_ELASTIC.young),
        ..PLACEHOLDER_ELASTIC
    };
    let mut out: Vec<_> = scene
        .phases
        .iter()
        .enumerate()
        .filter(|(i, _)| present[*i])
        .map(|(i, p)| {
            let name = section_name(&format!("PHASE{i}_"), &p.name);
            (name, i, p.elastic.unwrap_or(fallback))
        })
        .collect();
    if grid.fill == RveFill::Matrix && present[grid.phases] {
        let name = section_name("", matrix_name(scene));
        out.push((name, grid.phases, scene.matrix.elastic.unwrap_or(fallback)));
    }
    out
}

fn material_counts(grid: &VoxelGrid) -> Vec<usize> {
    let mut counts = vec![0usize; grid.grains + 1];
    for &m in &grid.material {
        counts[m as usize] += 1;
    }
    counts
}

/// `GRAIN_k` for every grain with voxels: the cells sorted by material (a counting
/// sort, one `u32` per cell).
fn write_grain_sets(out: &mut dyn Write, grid: &VoxelGrid) -> io::Result<()> {
    let counts = material_counts(grid);
    let mut start = Vec::with_capacity(counts.len() + 1);
    start.push(0);
    for c in &counts {
        start.push(start[start.len() - 1] + c);
    }
    let mut next = start.clone();
    let mut order = vec![0u32; grid.len()];
    for (e, &m) in grid.material.iter().enumerate() {
        order[next[m as usize]] = e as u32;
        next[m as usize] += 1;
    }
    for g in 0..grid.grains {
        if counts[g] > 0 {
            let cells = order[start[g]..start[g + 1]]
                .iter()
                .map(|&e| e as usize + 1);
            write_list(out, &format!("*Elset, elset=GRAIN_{g}"), cells)?;
        }
    }
    Ok(())
}
