//! VTK exports of a packing, for ParaView, PyVista, meshio and the like.
//!
//! - [`GRAINS_VTU`]: every grain's surface, a closed triangulated ellipsoid whose
//!   triangles face outwards, with the grain's figures as cell data
//!   ([`write_grains_vtu`]).
//! - [`CENTERS_VTP`]: one point per grain with its semi-axes and shape tensors as point
//!   data ([`write_centers_vtp`]). In ParaView, the Tensor Glyph filter on
//!   `shape_tensor` with a sphere glyph draws every grain; ParaView's sphere has
//!   radius 0.5, so set its Scale Factor to 2 for true size.
//!
//! In a 2D scene, every ellipse is a polygon in the plane z = 0 in `grains.vtu`, and a
//! flat grain (third semi-axis 0) at `(x, y, 0)` in `centers.vtp`.
//!
//! Both are VTK XML files (version 1.0, little-endian, `UInt64` headers) with every
//! array zlib-compressed in raw appended data, as VTK itself writes them by default,
//! which every VTK-based reader and meshio load. Values go through unrounded, but for
//! `grains.vtu`'s points, which are `Float32` (their rounding is far below the facets'
//! distance from the ellipsoid). They
//! are streamed by a small writer of their own (`src/io/vtk/xml.rs`), grain by grain, so that a
//! million grains need no more memory than a thousand.
//!
//! ```
//! use grainpack::io::vtk::{write_centers_vtp, write_grains_vtu};
//! use grainpack::scene::{Boundary, Domain, VtkSpec};
//! use grainpack::packing::PackedGrain;
//! let grain = PackedGrain {
//!     id: 0,
//!     phase: 0,
//!     centre: [5.0; 3],
//!     semi_axes: [2.0, 1.0, 1.0],
//!     quaternion: [1.0, 0.0, 0.0, 0.0],
//! };
//! let domain = Domain::new([10.0; 3], Boundary::Periodic);
//! let mut vtu = Vec::new();
//! write_grains_vtu(&mut vtu, &[grain], &domain, &VtkSpec::default(), None)?;
//! assert!(String::from_utf8_lossy(&vtu).contains(r#"NumberOfCells="320""#));
//! let mut vtp = Vec::new();
//! write_centers_vtp(&mut vtp, &[grain], None, domain.dimension)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod centers;
mod icosphere;
mod polygons;
mod surfaces;
mod xml;

pub use centers::{quadratic_form, shape_tensor, write_centers_vtp};
pub use icosphere::Icosphere;
pub use surfaces::periodic_shifts;

use crate::contact::{rotation_column, Dimension};
use crate::packing::PackedGrain;
use crate::scene::{Domain, VtkSpec};
use std::io::{self, Write};

/// File name of the grain surfaces.
pub const GRAINS_VTU: &str = "grains.vtu";

/// File name of the grain centres.
pub const CENTERS_VTP: &str = "centers.vtp";

/// VTK's cell type of a triangle (`VTK_TRIANGLE`).
const TRIANGLE: u8 = 5;

/// The columns of the rotation matrix of `q`: `r[k]` is the direction of semi-axis `k`.
fn rotation(q: [f64; 4]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|k| rotation_column(q, k))
}

/// Writes `grains.vtu` (VTK XML UnstructuredGrid, arrays zlib-compressed in raw
/// appended data, `io/vtk/xml.rs`, points `Float32`): each grain's surface, and in a
/// periodic box with `spec.periodic_images` its [`periodic_shifts`] copies, as
/// `20·4^resolution` triangles each. Cell data, per triangle: `grain_id` and `phase`
/// (the CSV's, `Int32`), `volume` `4π/3·a1·a2·a3` and `equivalent_diameter`
/// `2·(a1·a2·a3)^{1/3}` of the exact ellipsoid, `aspect_ratio` `a1/a2` (first
/// semi-axis over second: both as in the summary, [`crate::run::Statistics`]),
/// `b_over_a` and `c_over_a` (the semi-axes sorted `a ≥ b ≥ c`, DREAM.3D's ratios,
/// which describe triaxial grains), and `periodic_image` (`UInt8`: 0 for the grain, 1
/// for a copy); with `crystals` (`crystals[i]` the crystal orientation of
/// `grains[i]`), also `crystal_quaternion` (4 components, scalar first) and
/// `euler_angles` (Bunge, degrees). Topology is `Int32` (`Int64` past 2³¹ − 1).
///
/// A grain's values repeat over its triangles, which zlib stores for next to nothing;
/// the surfaces are made one at a time, so memory does not grow with the file.
///
/// In a 2D scene (`domain.dimension`), each ellipse, and with `spec.periodic_images`
/// each copy across an edge it crosses, is one `VTK_POLYGON` of
/// [`VtkSpec::polygon_vertices`] points on the ellipse, counter-clockwise, in the plane
/// z = 0. Its cell data, one value per polygon: `grain_id`, `phase`, `area` `π a1 a2`,
/// `equivalent_diameter` `2√(a1 a2)` (of the circle of the same area), `aspect_ratio`,
/// `angle` (degrees, of the first semi-axis from x, in `(−90, 90]`), `periodic_image`,
/// and with `crystals` `crystal_quaternion` and `euler_angles`.
pub fn write_grains_vtu(
    out: &mut dyn Write,
    grains: &[PackedGrain],
    domain: &Domain,
    spec: &VtkSpec,
    crystals: Option<&[[f64; 4]]>,
) -> io::Result<()> {
    match domain.dimension {
        Dimension::Two => polygons::write_ellipses_vtu(out, grains, domain, spec, crystals),
        Dimension::Three => surfaces::write_surfaces_vtu(out, grains, domain, spec, crystals),
    }
}

/// A 2D grain (the ellipsoid an ellipse is embedded as) as the ellipse itself, a 3D
/// grain flat in the plane z = 0: centre `(x, y, 0)`, semi-axes `(a1, a2, 0)`.
fn flat_ellipse(grain: &PackedGrain) -> PackedGrain {
    let [x, y, _] = grain.centre;
    let [a1, a2, _] = grain.semi_axes;
    PackedGrain {
        centre: [x, y, 0.0],
        semi_axes: [a1, a2, 0.0],
        ..*grain
    }
}

/// A grain's id as VTK's `Int32`.
fn grain_id(grain: &PackedGrain) -> io::Result<i32> {
    i32::try_from(grain.id)
        .map_err(|_| io::Error::other(format!("grain id {} exceeds VTK's Int32", grain.id)))
}

/// A grain's phase index as VTK's `Int32`.
fn phase_index(grain: &PackedGrain) -> io::Result<i32> {
    i32::try_from(grain.phase).map_err(|_| {
        io::Error::other(format!(
            "grain {}: phase {} exceeds VTK's Int32",
            grain.id, grain.phase
        ))
    })
}
