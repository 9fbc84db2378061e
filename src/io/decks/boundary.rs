//! The deck's grid nodes, their face, edge and corner sets and the periodic equations,
//! written once for the 3D voxel mesh and the 2D pixel mesh (which is its `k = 0` plane
//! of nodes: node `(i, j)` has the number of node `(i, j, 0)`).

use crate::contact::Dimension;
use crate::io::voxel::VoxelGrid;
use std::io::{self, Write};

/// Abaqus' limit of entries per data line of a set.
const PER_LINE: usize = 16;

/// Names of the axes, as in the node sets (`X0`, `Y1`, ...) and reference nodes.
pub(super) const AXES: [&str; 3] = ["X", "Y", "Z"];

/// How many axes the mesh has: 2 (CPE4 in the plane) or 3 (C3D8).
pub(super) fn axes(grid: &VoxelGrid) -> usize {
    grid.dimension.exponent() as usize
}

/// The last node index along z: `Nz`, or 0 for the one plane of nodes of a 2D mesh.
pub(super) fn last_layer(grid: &VoxelGrid) -> usize {
    match grid.dimension {
        Dimension::Two => 0,
        Dimension::Three => grid.cells[2],
    }
}

/// Node id of grid node `(i, j, k)`: `1 + i + (Nx+1)(j + (Ny+1) k)`.
pub(super) fn node(grid: &VoxelGrid, i: usize, j: usize, k: usize) -> usize {
    let [nx, ny, _] = grid.cells;
    1 + i + (nx + 1) * (j + (ny + 1) * k)
}

/// The reference nodes `RPX`, `RPY` (and `RPZ` in 3D), numbered after the grid's nodes.
pub(super) fn reference_nodes(grid: &VoxelGrid) -> Vec<usize> {
    let [nx, ny, _] = grid.cells;
    let last = (nx + 1) * (ny + 1) * (last_layer(grid) + 1);
    (1..=axes(grid)).map(|d| last + d).collect()
}

/// Faces, edges and corners: each set fixes one or more indices at 0 or at the far
/// end, the others run over their whole range: 26 sets in 3D (`X0`, ..., `X0Y0`, ...,
/// `X0Y0Z0`, ...), 8 in 2D (the edges `X0`, `X1`, `Y0`, `Y1` and the corners).
pub(super) fn write_node_sets(out: &mut dyn Write, grid: &VoxelGrid) -> io::Result<()> {
    let d = axes(grid);
    let mut n = grid.cells;
    n[2] = last_layer(grid);
    for fixed in 1..=d {
        for mask in 0..3u32.pow(d as u32) {
            // Per axis: 0 free, 1 near face, 2 far face.
            let mut sides = [0u32; 3];
            for (a, side) in sides.iter_mut().enumerate().take(d) {
                *side = (mask / 3u32.pow(a as u32)) % 3;
            }
            if sides.iter().filter(|&&s| s != 0).count() != fixed {
                continue;
            }
            let mut name = String::new();
            let range = |a: usize| match sides[a] {
                0 => 0..=n[a],
                1 => 0..=0,
                _ => n[a]..=n[a],
            };
            for (a, axis) in AXES.iter().enumerate() {
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

/// The periodic equations, at most four terms per line: every node with an index at a
/// far face is tied to its image at the near faces, `u(node) − u(image) − Σ u(RP_d) = 0`
/// (see [`write_abaqus_deck`](super::write_abaqus_deck)), for each of the mesh's
/// displacement components.
pub(super) fn write_equations(
    out: &mut dyn Write,
    grid: &VoxelGrid,
    rp: &[usize],
) -> io::Result<()> {
    let [nx, ny, nz] = grid.cells;
    let d = axes(grid);
    writeln!(out, "*Equation")?;
    for k in 0..=last_layer(grid) {
        for j in 0..=ny {
            for i in 0..=nx {
                let far = [i == nx, j == ny, d == 3 && k == nz];
                if !far.iter().any(|&f| f) {
                    continue;
                }
                let image = node(grid, i % nx, j % ny, k % nz);
                let me = node(grid, i, j, k);
                for dof in 1..=d {
                    let mut terms = vec![(me, 1.0), (image, -1.0)];
                    terms.extend((0..d).filter(|&a| far[a]).map(|a| (rp[a], -1.0)));
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
pub(super) fn write_list(
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
