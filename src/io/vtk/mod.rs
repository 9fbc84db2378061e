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
//! Both are VTK XML files (version 1.0, little-endian, `UInt64` headers) with every
//! array in base64 binary: doubles go through unrounded, and every VTK-based reader
//! and meshio load it. They are written by `vtkio`, which expresses all of it but the
//! type of the topology arrays: it writes them as `UInt64`, relabelled `Int64` here.
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
//! let domain = Domain { size: [10.0; 3], boundary: Boundary::Periodic };
//! let mut vtu = Vec::new();
//! write_grains_vtu(&mut vtu, &[grain], &domain, &VtkSpec::default(), None)?;
//! assert!(String::from_utf8(vtu)?.contains(r#"NumberOfCells="320""#));
//! let mut vtp = Vec::new();
//! write_centers_vtp(&mut vtp, &[grain], None)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod centers;
mod icosphere;
mod surfaces;

pub use centers::{quadratic_form, shape_tensor, write_centers_vtp};
pub use icosphere::Icosphere;
pub use surfaces::{periodic_shifts, write_grains_vtu};

use crate::contact::rotation_column;
use crate::packing::PackedGrain;
use std::io::{self, Write};
use vtkio::model::{ByteOrder, CellType, DataSet, Version, Vtk};
use vtkio::xml::Compressor;

/// File name of the grain surfaces.
pub const GRAINS_VTU: &str = "grains.vtu";

/// File name of the grain centres.
pub const CENTERS_VTP: &str = "centers.vtp";

/// VTK's cell type of a triangle.
const TRIANGLE: CellType = CellType::Triangle;

/// The columns of the rotation matrix of `q`: `r[k]` is the direction of semi-axis `k`.
fn rotation(q: [f64; 4]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|k| rotation_column(q, k))
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

/// Writes `data` as an uncompressed XML VTK file with base64 binary arrays, after an
/// XML declaration and with a final newline, its topology arrays as `Int64`
/// ([`signed_topology`]).
fn encode(out: &mut dyn Write, data: DataSet) -> io::Result<()> {
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        data,
        file_path: None,
    };
    let xml = vtk
        .try_into_xml_format(Compressor::None, 0)
        .map_err(io::Error::other)?;
    let mut text = Vec::new();
    xml.write(&mut text).map_err(io::Error::other)?;
    let text = String::from_utf8(text).map_err(io::Error::other)?;
    out.write_all(b"<?xml version=\"1.0\"?>\n")?;
    out.write_all(signed_topology(&text)?.as_bytes())?;
    out.write_all(b"\n")
}

/// The topology arrays of vtkio's XML: connectivity and offsets.
const TOPOLOGY_ARRAYS: [&str; 2] = ["connectivity", "offsets"];

/// Relabels vtkio's `UInt64` connectivity and offsets arrays as `Int64`, the type VTK
/// itself writes.
///
/// This is the one thing vtkio cannot express: it always writes these arrays as
/// `UInt64`, and meshio (5.3) then returns the cells as float64 arrays, since numpy
/// promotes `uint64` with a signed integer to float64. The indices are far below 2⁶³,
/// so their little-endian bytes, and the base64 text, are the same as `Int64`: only
/// the `type` attribute changes. Each array must be found, or the file is not written
/// (a vtkio that serializes differently must fail loudly, not quietly write `UInt64`).
fn signed_topology(xml: &str) -> io::Result<String> {
    let mut text = xml.to_owned();
    for name in TOPOLOGY_ARRAYS {
        let unsigned = format!(r#"<DataArray type="UInt64" Name="{name}""#);
        if !text.contains(&unsigned) {
            return Err(io::Error::other(format!(
                "vtkio wrote no UInt64 {name} array: cannot relabel it as Int64"
            )));
        }
        text = text.replace(
            &unsigned,
            &format!(r#"<DataArray type="Int64" Name="{name}""#),
        );
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn topology_arrays_are_int64_and_nothing_else_is_relabelled() {
        let grain = PackedGrain {
            id: 0,
            phase: 0,
            centre: [1.0; 3],
            semi_axes: [1.0; 3],
            quaternion: [1.0, 0.0, 0.0, 0.0],
        };
        let mut out = Vec::new();
        write_centers_vtp(&mut out, &[grain], None).unwrap();
        let text = String::from_utf8(out).unwrap();
        for name in TOPOLOGY_ARRAYS {
            assert!(text.contains(&format!(r#"<DataArray type="Int64" Name="{name}""#)));
        }
        assert!(!text.contains(r#"<DataArray type="UInt64""#), "{text}");
        assert!(text.contains(r#"header_type="UInt64""#));
        assert!(text.starts_with("<?xml") && text.ends_with("</VTKFile>\n"));
    }

    #[test]
    fn a_serialization_without_the_expected_arrays_is_an_error() {
        let e = signed_topology("<VTKFile></VTKFile>").unwrap_err();
        assert!(e.to_string().contains("connectivity"), "{e}");
    }
}
