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

use super::damask::PLACEHOLDER_ELASTIC;
use super::names::{matrix_name, section_name};
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

/// Abaqus' limit of entries per data line of a set.
const PER_LINE: usize = 16;

/// Writes `rve.inp` for `grid`: nodes, elements, an element set per grain
/// (`GRAIN_k`, grains without voxels skipped) and per phase (`PHASE<i>_<NAME>`,
/// `MATRIX`), node sets of the six faces (`X0`, `X1`, ...), twelve edges (`X0Y0`, ...)
/// and eight corners (`X0Y0Z0`, ...), the reference nodes, the periodic equations
/// (periodic box), a `*Material` and `*Solid Section` per phase from the scene's
/// elastic constants, and a static step in uniaxial strain along x. Every number is in
/// the scene's units (`[units]`, named in a comment at the top): coordinates in
/// `units.length`, moduli in `units.stress`.
pub fn write_abaqus_deck(out: &mut dyn Write, scene: &Scene, grid: &VoxelGrid) -> io::Result<()> {
    let [nx, ny, nz] = grid.cells;
    let h = grid.spacing();
    let size = grid.size;
    writeln!(out, "*Heading")?;
    writeln!(
        out,
        "grainpack voxel RVE: {nx} x {ny} x {nz} C3D8 elements, box {} x {} x {} {}, {}",
        size[0],
        size[1],
        size[2],
        scene.units.length.symbol(),
        if grid.periodic {
            "periodic"
        } else {
            "not periodic"
        }
    )?;
    let (length, stress) = (scene.units.length.symbol(), scene.units.stress.symbol());
    writeln!(
        out,
        "** units (the scene's [units]): lengths in {length}, stresses and E in {stress}, \
         forces in {stress}*{length}^2"
    )?;
    writeln!(
        out,
        "** element 1 + i + Nx (j + Ny k) is cell (i, j, k) of rve.vti;"
    )?;
    writeln!(
        out,
        "** node 1 + i + (Nx+1)(j + (Ny+1) k) lies at (i hx, j hy, k hz)."
    )?;
    writeln!(out, "*Node")?;
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let id = node(grid, i, j, k);
                let (x, y, z) = (i as f64 * h[0], j as f64 * h[1], k as f64 * h[2]);
                writeln!(out, "{id}, {x:?}, {y:?}, {z:?}")?;
            }
        }
    }
    let rp = reference_nodes(grid);
    for (d, id) in rp.iter().enumerate() {
        let mut at = [0.0; 3];
        at[d] = size[d];
        writeln!(out, "{id}, {:?}, {:?}, {:?}", at[0], at[1], at[2])?;
    }
    writeln!(out, "*Element, type=C3D8")?;
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let n = |a, b, c| node(grid, i + a, j + b, k + c);
                writeln!(
                    out,
                    "{}, {}, {}, {}, {}, {}, {}, {}, {}",
                    grid.index(i, j, k) + 1,
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
    let names = ["RPX", "RPY", "RPZ"];
    for (name, id) in names.iter().zip(rp) {
        writeln!(out, "*Nset, nset={name}\n{id}")?;
    }
    writeln!(out, "*Nset, nset=RP\nRPX, RPY, RPZ")?;
    if grid.periodic {
        write_equations(out, grid, rp)?;
    }
    for (name, _, elastic) in solids(scene, grid) {
        writeln!(out, "*Material, name={name}")?;
        writeln!(out, "*Elastic")?;
        writeln!(out, "{:?}, {:?}", elastic.young, elastic.poisson)?;
        writeln!(out, "*Solid Section, elset={name}, material={name}")?;
    }
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
        writeln!(out, "*Solid Section, elset={name}, material={name}")?;
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
        writeln!(out, "*Solid Section, elset={name}, material={name}")?;
    }
    Ok(())
}

/// Node id of grid node `(i, j, k)`.
fn node(grid: &VoxelGrid, i: usize, j: usize, k: usize) -> usize {
    let [nx, ny, _] = grid.cells;
    1 + i + (nx + 1) * (j + (ny + 1) * k)
}

fn reference_nodes(grid: &VoxelGrid) -> [usize; 3] {
    let [nx, ny, nz] = grid.cells;
    let last = (nx + 1) * (ny + 1) * (nz + 1);
    [last + 1, last + 2, last + 3]
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

/// Faces, edges and corners: each of the 26 sets fixes one, two or three indices at
/// 0 or at the far end, the others run over their whole range.
fn write_node_sets(out: &mut dyn Write, grid: &VoxelGrid) -> io::Result<()> {
    let n = grid.cells;
    for fixed in 1..=3 {
        for mask in 0..27u32 {
            // Per axis: 0 free, 1 near face, 2 far face.
            let sides = [mask % 3, (mask / 3) % 3, mask / 9];
            if sides.iter().filter(|&&s| s != 0).count() != fixed {
                continue;
            }
            let mut name = String::new();
            let range = |a: usize| match sides[a] {
                0 => 0..=n[a],
                1 => 0..=0,
                _ => n[a]..=n[a],
            };
            for (a, axis) in ["X", "Y", "Z"].iter().enumerate() {
                if sides[a] != 0 {
                    name.push_str(axis);
                    name.push(if sides[a] == 1 { '0' } else { '1' });
                }
            }
            let ids = range(2).flat_map(move |k| {
                range(1).flat_map(move |j| range(0).map(move |i| node(grid, i, j, k)))
            });
            write_list(out, &format!("*Nset, nset={name}"), ids)?;
        }
    }
    Ok(())
}

/// The periodic equations (see the module's docs), at most four terms per line.
fn write_equations(out: &mut dyn Write, grid: &VoxelGrid, rp: [usize; 3]) -> io::Result<()> {
    let [nx, ny, nz] = grid.cells;
    writeln!(out, "*Equation")?;
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let far = [i == nx, j == ny, k == nz];
                if !far.iter().any(|&f| f) {
                    continue;
                }
                let image = node(grid, i % nx, j % ny, k % nz);
                let me = node(grid, i, j, k);
                for dof in 1..=3 {
                    let mut terms = vec![(me, 1.0), (image, -1.0)];
                    terms.extend((0..3).filter(|&d| far[d]).map(|d| (rp[d], -1.0)));
                    writeln!(out, "{}", terms.len())?;
                    for line in terms.chunks(4) {
                        let text: Vec<String> = line
                            .iter()
                            .map(|(n, c)| format!("{n}, {dof}, {c:?}"))
                            .collect();
                        writeln!(out, "{}", text.join(", "))?;
                    }
                }
            }
        }
    }
    Ok(())
}

/// `header`, then the ids, [`PER_LINE`] to a line.
fn write_list(
    out: &mut dyn Write,
    header: &str,
    ids: impl Iterator<Item = usize>,
) -> io::Result<()> {
    writeln!(out, "{header}")?;
    let mut on_line = 0;
    for id in ids {
        if on_line == PER_LINE {
            writeln!(out)?;
            on_line = 0;
        }
        if on_line > 0 {
            write!(out, ", ")?;
        }
        write!(out, "{id}")?;
        on_line += 1;
    }
    writeln!(out)
}
