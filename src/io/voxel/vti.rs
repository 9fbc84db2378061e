//! VTK XML ImageData (`.vti`) with the `material` and `phase` cell arrays (and, when
//! crystal orientations are asked for, `phi1`, `Phi`, `phi2`), in metres.
//!
//! A small writer of its own rather than `vtkio`: vtkio (0.6 and 0.7) stores an image's
//! Origin and Spacing as `f32`, so `L/N` would be rounded (92/69 becomes 1.3333334 and
//! DAMASK would read a box of 92.000003), and it copies the arrays several times on the
//! way out. The format needed here is a few lines: inline binary arrays, zlib-compressed
//! in independent blocks (compressed in parallel) and base64-encoded, as VTK writes them.

use super::VoxelGrid;
use crate::io::zlib_blocks;
use crate::scene::{quaternion_to_euler, LengthUnit};
use base64::engine::general_purpose::STANDARD;
use base64::Engine;
use rayon::prelude::*;
use std::io::{self, Write};

/// Uncompressed bytes per compressed block (VTK's readers take any block size).
const BLOCK_BYTES: usize = 1 << 20;

/// Names of the orientation arrays: Bunge Euler angles in degrees, as the columns of
/// `grains.csv`.
pub const EULER_ARRAYS: [&str; 3] = ["phi1", "Phi", "phi2"];

/// Writes `grid` as VTK XML ImageData to `out` (the caller makes the file atomic), in
/// metres: `length` is the unit of `grid.size` (the scene's `units.length`), converted
/// as DAMASK expects SI.
///
/// `WholeExtent = 0 Nx 0 Ny 0 Nz` counts points, so there are `Nx Ny Nz` cells; the
/// origin is 0 and the spacing `L/N` (L in metres), printed with 17 significant digits
/// so that `N × spacing` gives `L` back. The cell arrays `material` and `phase` are
/// `Int32` (DAMASK's `GeomGrid.load` takes the `material` array; `phase` becomes an
/// initial condition there), in x-fastest order as VTK expects. With `orientations`
/// (`orientations[k]` the crystal orientation of grain `k`, a unit quaternion scalar
/// first), three more `Float64` scalar arrays [`EULER_ARRAYS`] (Bunge φ1, Φ, φ2 in
/// degrees, as in `grains.csv`, [`quaternion_to_euler`]) give each cell its material's
/// orientation, the identity (0, 0, 0) for the matrix (as its `material.yaml` entry).
/// Scalars, not one 3-component array: DAMASK's `GeomGrid.load` takes every cell array
/// other than `material` as an initial condition, and version 3.0.x reshapes each to
/// the grid's cells (a 3-component array fails there: "cannot reshape array of size
/// 3N"); 3.1.x takes scalars too.
///
/// Each array's data is alone on the line after its `<DataArray …>` tag, as DAMASK's
/// Fortran reader takes it (`VTI_readDataset_raw` in DAMASK's `src/grid/VTI.f90` reads
/// the line after the tag named `material` as the whole base64 text and skips the
/// others); XML readers do not mind the line breaks.
///
/// ```
/// use grainpack::scene::{Boundary, Domain, LengthUnit};
/// use grainpack::io::voxel::{voxelise, write_vti};
/// use grainpack::scene::RveFill;
/// let domain = Domain::new([1.0; 3], Boundary::Periodic);
/// let grid = voxelise(&[], &domain, [2, 3, 4], RveFill::Matrix, 1).unwrap();
/// let mut out = Vec::new();
/// write_vti(&grid, LengthUnit::Micrometre, None, &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains(r#"WholeExtent="0 2 0 3 0 4""#));
/// let spacing = text.split("Spacing=\"").nth(1).unwrap().split(' ').next().unwrap();
/// assert_eq!(spacing.parse::<f64>().unwrap(), 0.5e-6); // 1 µm over 2 cells, in metres
/// ```
pub fn write_vti(
    grid: &VoxelGrid,
    length: LengthUnit,
    orientations: Option<&[[f64; 4]]>,
    out: &mut dyn Write,
) -> io::Result<()> {
    let [nx, ny, nz] = grid.cells;
    let h = [0, 1, 2].map(|a| length.to_si(grid.size[a]) / grid.cells[a] as f64);
    let extent = format!("0 {nx} 0 {ny} 0 {nz}");
    writeln!(out, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        out,
        r#"<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64" compressor="vtkZLibDataCompressor">"#
    )?;
    writeln!(
        out,
        r#"  <ImageData WholeExtent="{extent}" Origin="0 0 0" Spacing="{:.16e} {:.16e} {:.16e}">"#,
        h[0], h[1], h[2]
    )?;
    writeln!(out, r#"    <Piece Extent="{extent}">"#)?;
    writeln!(out, r#"      <CellData Scalars="material">"#)?;
    for (name, values) in [("material", &grid.material), ("phase", &grid.phase)] {
        let (lo, hi) = values
            .par_iter()
            .fold(|| (u32::MAX, 0), |(lo, hi), &v| (lo.min(v), hi.max(v)))
            .reduce(|| (u32::MAX, 0), |a, b| (a.0.min(b.0), a.1.max(b.1)));
        writeln!(
            out,
            r#"        <DataArray type="Int32" Name="{name}" format="binary" RangeMin="{lo}" RangeMax="{hi}">"#
        )?;
        // Values are below i32::MAX (checked when the grid was made), so their Int32
        // bytes equal their UInt32 bytes.
        write_compressed(values, 4, |v, bytes| bytes.extend(v.to_le_bytes()), out)?;
        writeln!(out, "\n        </DataArray>")?;
    }
    if let Some(orientations) = orientations {
        let euler: Vec<[f64; 3]> = orientations
            .iter()
            .map(|&q| quaternion_to_euler(q).map(f64::to_degrees))
            .collect();
        let of = |m: &u32| euler.get(*m as usize).copied().unwrap_or([0.0; 3]);
        for (a, name) in EULER_ARRAYS.iter().enumerate() {
            writeln!(
                out,
                r#"        <DataArray type="Float64" Name="{name}" format="binary">"#
            )?;
            write_compressed(
                &grid.material,
                8,
                |m, bytes| bytes.extend(of(m)[a].to_le_bytes()),
                out,
            )?;
            writeln!(out, "\n        </DataArray>")?;
        }
    }
    writeln!(out, "      </CellData>")?;
    writeln!(out, "    </Piece>")?;
    writeln!(out, "  </ImageData>")?;
    writeln!(out, "</VTKFile>")
}

/// One array as VTK's compressed binary, on one line: base64 of the header
/// `[blocks, block size, size of a partial last block (0 if full), compressed size of
/// each block]` (UInt64), then base64 of the compressed blocks one after another. Each
/// cell's `width` bytes are made by `bytes` from its value, block by block (so a wide
/// array is never whole in memory uncompressed).
fn write_compressed<T: Sync>(
    values: &[T],
    width: usize,
    bytes: impl Fn(&T, &mut Vec<u8>) + Sync,
    out: &mut dyn Write,
) -> io::Result<()> {
    write!(out, "          ")?;
    let values_per_block = BLOCK_BYTES / width;
    let blocks: Vec<Vec<u8>> = values
        .par_chunks(values_per_block)
        .map(|chunk| {
            let mut raw = Vec::with_capacity(chunk.len() * width);
            for v in chunk {
                bytes(v, &mut raw);
            }
            zlib_blocks::compress(&raw)
        })
        .collect::<io::Result<_>>()?;
    let sizes: Vec<u64> = blocks.iter().map(|b| b.len() as u64).collect();
    let header = zlib_blocks::header(BLOCK_BYTES, values.len() * width, &sizes);
    out.write_all(STANDARD.encode(header).as_bytes())?;
    out.write_all(STANDARD.encode(blocks.concat()).as_bytes())
}
