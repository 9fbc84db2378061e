//! What a run writes (`[output]`): which files, and the few parameters each takes.
//!
//! Every key is validated once, in `validate::output`; the writers read these typed
//! values and check nothing again. `docs/config.md` documents each key and default.

use super::Domain;
use crate::contact::Dimension;
use serde::Serialize;
use std::path::PathBuf;

/// Default subdivision level of the grain surfaces in `grains.vtu`: 320 triangles
/// per grain (see [`VtkSpec::triangles_per_grain`]).
pub const DEFAULT_VTK_RESOLUTION: u32 = 2;

/// The coarsest subdivision level accepted for `vtk_resolution`: 80 triangles per
/// grain. Level 0, the bare icosahedron, holds only 61 % of the ellipsoid's volume.
pub const MIN_VTK_RESOLUTION: u32 = 1;

/// The finest subdivision level accepted for `vtk_resolution`: 20·4⁶ = 81 920
/// triangles per grain, already far past what a screen shows of one grain.
pub const MAX_VTK_RESOLUTION: u32 = 6;

/// Cells of the voxel RVE along the box's longest edge when neither `rve_resolution`
/// nor `rve_voxel_size` is given; the other edges get proportionally many.
pub const DEFAULT_RVE_CELLS: usize = 64;

/// The most cells the voxel RVE may have along one edge.
pub const MAX_RVE_CELLS_PER_EDGE: usize = 4096;

/// The most cells the voxel RVE may have in all: 2³⁰ (1024³), about 8 GiB for its two
/// 32-bit integer fields.
pub const MAX_RVE_CELLS: u64 = 1 << 30;

/// Default element size of the conforming mesh (`mesh_size`), as a fraction of the
/// smallest grain's equivalent diameter: about three elements across the smallest
/// grain, a mesh CalculiX solves in seconds for tens of grains; its linear elements
/// leave the grains' volume 5–8 % short (BENCHMARKS.md, "Conforming mesh").
pub const DEFAULT_MESH_SIZE: f64 = 0.3;

/// Range accepted for `mesh_size`: finer than 0.05 puts 20 elements across the
/// smallest grain (millions of tetrahedra for a hundred grains); coarser than 1 does
/// not resolve the grains at all.
pub const MESH_SIZE_RANGE: (f64, f64) = (0.05, 1.0);

/// The smallest `packing.gap` a conforming mesh accepts. Between two grains the film
/// of matrix is at least `gap` × (r₁ + r₂) thick. At gap 0 (μ ≈ 1.0001) the film's
/// elements are slivers (min SICN 8e-4, issue 29) or the 3D mesh fails; gaps 0.01,
/// 0.02 and 0.05 all meshed 31 grains at φ 0.45 (BENCHMARKS.md, "Conforming mesh").
/// 0.02 is a margin above the smallest that worked, not a measured threshold.
pub const MIN_MESH_GAP: f64 = 0.02;

/// What to write, and where (`[output]`). Files are named by the writers:
/// `grains.csv`, `grains.vtu`, `centers.vtp`, `rve.vti`, the PNGs, `summary.json`.
/// The default is a 3D scene's; validation sets a 2D scene's `packing_png`.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputSpec {
    /// Output directory, relative to the current directory. Default `out`.
    pub dir: PathBuf,
    /// Write `grains.csv`. Default true.
    pub grains_csv: bool,
    /// Write `summary.json`. Default true.
    pub summary_json: bool,
    /// Write the grains' surfaces to `grains.vtu` (`vtk = true`, the default), with
    /// these parameters; `None` for `vtk = false`.
    pub vtk: Option<VtkSpec>,
    /// Write the grains' centres and shape tensors to `centers.vtp`. Default true.
    pub centers: bool,
    /// Write a voxel RVE to `rve.vti` (`rve = true`), with these parameters; `None`
    /// (the default) for no RVE.
    pub rve: Option<RveSpec>,
    /// Write PNG plots of the grain statistics against their targets. Default true.
    pub statistics_png: bool,
    /// Write `packing.png`, a picture of a 2D packing (`packing_png`). Default true in
    /// 2D; a 3D scene has none.
    pub packing_png: bool,
    /// Write DAMASK's `material.yaml` and a `load.yaml` beside `rve.vti` (`damask`,
    /// which implies `rve = true`). Default false.
    pub damask: bool,
    /// Write the Abaqus/CalculiX deck `rve.inp` beside `rve.vti` (`abaqus`, which
    /// implies `rve = true`). Default false.
    pub abaqus: bool,
    /// Write the conforming mesh `mesh.msh`, `mesh.inp` and `mesh.vtu` with gmsh
    /// (`mesh = true`), with these parameters; `None` (the default) for no mesh.
    pub mesh: Option<MeshSpec>,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            dir: PathBuf::from("out"),
            grains_csv: true,
            summary_json: true,
            vtk: Some(VtkSpec::default()),
            centers: true,
            rve: None,
            statistics_png: true,
            packing_png: false,
            damask: false,
            abaqus: false,
            mesh: None,
        }
    }
}

impl OutputSpec {
    /// Whether any file is to be written (and so the directory is needed).
    pub fn writes_anything(&self) -> bool {
        self.grains_csv
            || self.summary_json
            || self.vtk.is_some()
            || self.centers
            || self.rve.is_some()
            || self.statistics_png
            || self.packing_png
            || self.mesh.is_some()
    }
}

/// Parameters of the conforming mesh (`mesh = true`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSpec {
    /// Largest element edge as a fraction of the smallest grain's equivalent diameter
    /// (`mesh_size`, default [`DEFAULT_MESH_SIZE`]).
    pub size: f64,
    /// Element order: 1 for linear (C3D4), 2 for quadratic (C3D10) tetrahedra
    /// (`mesh_order`, default 1).
    pub order: u8,
    /// What the elements between the grains become (`mesh_fill`): the matrix (the
    /// default), or shared out among the grains as the RVE's `rve_fill = "grains"`
    /// shares its voxels (each element to the grain that must be scaled least to reach
    /// its centroid).
    pub fill: RveFill,
}

impl Default for MeshSpec {
    fn default() -> Self {
        Self {
            size: DEFAULT_MESH_SIZE,
            order: 1,
            fill: RveFill::Matrix,
        }
    }
}

/// Parameters of `grains.vtu`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VtkSpec {
    /// Subdivision level of the icosphere each grain's surface is mapped from
    /// (`vtk_resolution`), in `[MIN_VTK_RESOLUTION, MAX_VTK_RESOLUTION]`; default
    /// [`DEFAULT_VTK_RESOLUTION`].
    pub resolution: u32,
    /// Also write, in a periodic box, copies of the grains that cross a face, shifted
    /// by ±L to the far side (`periodic_images`). Default false; only a periodic box
    /// accepts true.
    pub periodic_images: bool,
}

impl Default for VtkSpec {
    fn default() -> Self {
        Self {
            resolution: DEFAULT_VTK_RESOLUTION,
            periodic_images: false,
        }
    }
}

impl VtkSpec {
    /// Triangles of one grain's surface: `20·4^resolution` (the icosahedron's 20
    /// faces, each cut into 4 per level).
    pub fn triangles_per_grain(&self) -> usize {
        20 << (2 * self.resolution)
    }

    /// Points of one grain's surface: `10·4^resolution + 2`.
    pub fn points_per_grain(&self) -> usize {
        (10 << (2 * self.resolution)) + 2
    }

    /// Vertices of one ellipse's polygon in a 2D scene: `8·2^resolution` (32 at the
    /// default, whose polygon holds `(n/2π) sin(2π/n)` = 99.4 % of the ellipse's area).
    pub fn polygon_vertices(&self) -> usize {
        8 << self.resolution
    }
}

/// Parameters of the voxel RVE `rve.vti`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RveSpec {
    /// Cells along x, y, z, each in `[1, MAX_RVE_CELLS_PER_EDGE]`, at most
    /// [`MAX_RVE_CELLS`] in all: from `rve_resolution`, from `rve_voxel_size`
    /// (`round(L/size)`, at least 1), or [`DEFAULT_RVE_CELLS`] along the longest edge
    /// and proportionally many along the others.
    pub cells: [usize; 3],
    /// What the voxels outside every grain become (`rve_fill`).
    pub fill: RveFill,
    /// Also write PNG sections of the RVE (`sections_png`). Default true.
    pub sections_png: bool,
}

impl RveSpec {
    /// Edge lengths of a voxel in a box of edges `size`: `L/N` along each axis.
    pub fn spacing(&self, size: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|i| size[i] / self.cells[i] as f64)
    }

    /// Number of cells in all.
    pub fn cell_count(&self) -> u64 {
        self.cells.iter().map(|&n| n as u64).product()
    }
}

/// What the voxels of the RVE outside every grain become (`rve_fill`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RveFill {
    /// `"grains"` (the default): every voxel belongs to a grain; the space between
    /// grains is shared out among them.
    #[default]
    Grains,
    /// `"matrix"`: voxels outside every grain belong to one matrix material.
    Matrix,
}

/// Cells along each edge of a box of edges `size` with `longest` cells along its
/// longest edge and proportionally many along the others, `round(longest·Lᵢ/L_max)`,
/// at least 1, so that voxels are as near cubes as whole numbers allow.
pub fn proportional_cells(longest: usize, size: [f64; 3]) -> [usize; 3] {
    let l_max = size.iter().copied().fold(0.0, f64::max);
    size.map(|l| ((longest as f64 * l / l_max).round() as usize).clamp(1, longest.max(1)))
}

/// [`proportional_cells`] over the box's edges: `[Nx, Ny, Nz]` in 3D; in 2D over the
/// rectangle's two, and one layer along z (`[Nx, Ny, 1]`, a pixel image).
pub fn rve_cells(longest: usize, domain: &Domain) -> [usize; 3] {
    match domain.dimension {
        Dimension::Three => proportional_cells(longest, domain.size),
        Dimension::Two => {
            let [lx, ly, _] = domain.size;
            let [nx, ny, _] = proportional_cells(longest, [lx, ly, 0.0]);
            [nx, ny, 1]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn proportional_cells_put_the_count_on_the_longest_edge_and_never_zero() {
        assert_eq!(proportional_cells(64, [10.0, 10.0, 10.0]), [64; 3]);
        assert_eq!(proportional_cells(64, [20.0, 10.0, 5.0]), [64, 32, 16]);
        // A thin slab still gets one cell across.
        assert_eq!(proportional_cells(10, [100.0, 100.0, 1.0]), [10, 10, 1]);
        // 64 · 3/7 = 27.43 rounds down, 64 · 5/7 = 45.71 up.
        assert_eq!(proportional_cells(64, [3.0, 7.0, 5.0]), [27, 64, 46]);
    }

    #[test]
    fn rve_cells_of_a_plane_are_one_layer_in_proportion_to_the_rectangle() {
        use crate::scene::Boundary;
        let plane = Domain::plane([20.0, 10.0], Boundary::Periodic);
        assert_eq!(rve_cells(64, &plane), [64, 32, 1]);
        let tall = Domain::plane([3.0, 7.0], Boundary::Reflecting);
        assert_eq!(rve_cells(64, &tall), [27, 64, 1]);
        let solid = Domain::new([3.0, 7.0, 5.0], Boundary::Periodic);
        assert_eq!(rve_cells(64, &solid), proportional_cells(64, solid.size));
    }

    #[test]
    fn spacing_times_cells_is_the_box() {
        let rve = RveSpec {
            cells: [27, 64, 46],
            fill: RveFill::Grains,
            sections_png: true,
        };
        let size = [3.0, 7.0, 5.0];
        let h = rve.spacing(size);
        for i in 0..3 {
            // One rounding in the division and one in the product: 2 ulp.
            let back = h[i] * rve.cells[i] as f64;
            assert!((back - size[i]).abs() <= 2.0 * f64::EPSILON * size[i]);
        }
        assert_eq!(rve.cell_count(), 27 * 64 * 46);
    }

    #[test]
    fn triangle_and_point_counts_follow_the_subdivision() {
        let at = |resolution| VtkSpec {
            resolution,
            periodic_images: false,
        };
        assert_eq!(at(0).triangles_per_grain(), 20);
        assert_eq!(at(0).points_per_grain(), 12);
        assert_eq!(at(2).triangles_per_grain(), 320);
        assert_eq!(at(2).points_per_grain(), 162);
        // Euler: V − E + F = 2 with E = 3F/2.
        for r in 0..=MAX_VTK_RESOLUTION {
            let (v, f) = (at(r).points_per_grain(), at(r).triangles_per_grain());
            assert_eq!(v + f - 3 * f / 2, 2);
        }
    }
}
