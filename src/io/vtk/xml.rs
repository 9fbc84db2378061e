//! A streaming writer of VTK XML files (`.vtu`, `.vtp`) with zlib-compressed arrays in
//! raw appended data, as VTK's own writers make them by default.
//!
//! Why not `vtkio`: it builds every array whole in memory (as `f64`/`u64`), then the
//! whole file as base64 text, and it writes neither appended data nor `Int32` topology.
//! Here each array is made item by item (a grain's surface, a centre), cut into blocks
//! of [`BLOCK_BYTES`] compressed in parallel and spilled to an anonymous temporary file,
//! so memory holds a batch of blocks and one `u64` per block, whatever the file's size.
//! The file is then the XML header with each array's offset, and the spilled blocks
//! behind it.

use rayon::prelude::*;
use std::fmt::Write as _;
use std::io::{self, BufReader, BufWriter, Read, Seek, SeekFrom, Write};

use crate::io::zlib_blocks;

/// Uncompressed bytes of one compressed block. VTK's readers take any size; VTK's own
/// writers use 32 KiB. Small blocks cost a `u64` each in the header, large ones memory
/// while they are compressed ([`BATCH_BLOCKS`] at a time).
const BLOCK_BYTES: usize = 1 << 16;

/// Blocks compressed at once, in parallel.
const BATCH_BLOCKS: usize = 32;

/// The type of an array's values, as VTK names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Scalar {
    Float64,
    Float32,
    Int32,
    Int64,
    UInt8,
}

impl Scalar {
    fn name(self) -> &'static str {
        match self {
            Self::Float64 => "Float64",
            Self::Float32 => "Float32",
            Self::Int32 => "Int32",
            Self::Int64 => "Int64",
            Self::UInt8 => "UInt8",
        }
    }

    /// The signed integer type that holds every index up to `max`: `Int32` when it
    /// fits, as VTK writes topology, else `Int64`.
    pub(super) fn index(max: usize) -> Self {
        if i32::try_from(max).is_ok() {
            Self::Int32
        } else {
            Self::Int64
        }
    }

    /// Appends `v` as this integer type, little-endian.
    pub(super) fn push_index(self, v: usize, bytes: &mut Vec<u8>) {
        match self {
            Self::Int32 => bytes.extend((v as i32).to_le_bytes()),
            _ => bytes.extend((v as i64).to_le_bytes()),
        }
    }
}

/// Where an array goes in a piece, in the order VTK expects the sections.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Section {
    PointData,
    CellData,
    Points,
    /// An unstructured grid's cells (`connectivity`, `offsets`, `types`).
    Cells,
    /// Poly data's vertex cells (`connectivity`, `offsets`).
    Verts,
}

impl Section {
    fn tag(self) -> &'static str {
        match self {
            Self::PointData => "PointData",
            Self::CellData => "CellData",
            Self::Points => "Points",
            Self::Cells => "Cells",
            Self::Verts => "Verts",
        }
    }
}

/// Appends item `i`'s values of one array, little-endian, to the bytes.
pub(super) type Fill<'a> = Box<dyn FnMut(usize, &mut Vec<u8>) + 'a>;

/// One array: where it goes, its name, type and components, and how its values are
/// made item by item.
pub(super) struct Array<'a> {
    pub section: Section,
    pub name: &'static str,
    pub scalar: Scalar,
    pub components: usize,
    pub fill: Fill<'a>,
}

impl<'a> Array<'a> {
    /// An array of `scalar` with `components` values per point or cell.
    pub fn new(
        section: Section,
        name: &'static str,
        scalar: Scalar,
        components: usize,
        fill: impl FnMut(usize, &mut Vec<u8>) + 'a,
    ) -> Self {
        Self {
            section,
            name,
            scalar,
            components,
            fill: Box::new(fill),
        }
    }
}

/// What a file holds: the data set's type (`UnstructuredGrid`, `PolyData`), the
/// piece's counts (`NumberOfPoints`, ...), the active attributes of each data section
/// (`Scalars="grain_id"`), and its arrays, each made over `items` items.
pub(super) struct Piece<'a> {
    pub kind: &'static str,
    pub counts: Vec<(&'static str, usize)>,
    pub active: Vec<(Section, &'static str, &'static str)>,
    pub items: usize,
    pub arrays: Vec<Array<'a>>,
}

/// Where one array's compressed data lies in the spill file, and its header.
struct Spilled {
    header: Vec<u8>,
    bytes: u64,
}

/// Writes `piece` to `out`: the XML with every array `format="appended"` at its
/// offset, then `<AppendedData encoding="raw">`, `_`, and each array as VTK's
/// compressed layout (a `UInt64` header `[blocks, block size, size of a partial last
/// block (0 if full), compressed size of each block]`, then the blocks).
pub(super) fn write_piece(out: &mut dyn Write, mut piece: Piece) -> io::Result<()> {
    let mut spill = BufWriter::new(tempfile::tempfile()?);
    let mut spilled = Vec::with_capacity(piece.arrays.len());
    for array in &mut piece.arrays {
        spilled.push(spill_array(array, piece.items, &mut spill)?);
    }
    let mut spill = spill.into_inner().map_err(|e| e.into_error())?;
    spill.seek(SeekFrom::Start(0))?;
    out.write_all(header_xml(&piece, &spilled).as_bytes())?;
    out.write_all(b"  <AppendedData encoding=\"raw\">\n   _")?;
    let mut reader = BufReader::new(spill);
    for s in &spilled {
        out.write_all(&s.header)?;
        let copied = io::copy(&mut (&mut reader).take(s.bytes), out)?;
        if copied != s.bytes {
            return Err(io::Error::other("the spilled VTK data ended early"));
        }
    }
    out.write_all(b"\n  </AppendedData>\n</VTKFile>\n")
}

/// Makes `array`'s values over `items` items, compresses them block by block into
/// `spill`, and returns its header and compressed size.
fn spill_array(array: &mut Array, items: usize, spill: &mut dyn Write) -> io::Result<Spilled> {
    let batch = BLOCK_BYTES * BATCH_BLOCKS;
    let (mut raw, mut sizes, mut total) = (Vec::with_capacity(batch + BLOCK_BYTES), vec![], 0);
    for i in 0..items {
        (array.fill)(i, &mut raw);
        if raw.len() >= batch {
            let full = raw.len() / BLOCK_BYTES * BLOCK_BYTES;
            total += full;
            compress_blocks(&raw[..full], &mut sizes, spill)?;
            raw.drain(..full);
        }
    }
    total += raw.len();
    compress_blocks(&raw, &mut sizes, spill)?;
    Ok(Spilled {
        header: zlib_blocks::header(BLOCK_BYTES, total, &sizes),
        bytes: sizes.iter().sum(),
    })
}

/// Compresses `raw` in blocks of [`BLOCK_BYTES`] (the last may be shorter), in
/// parallel; writes them in order and appends their sizes.
fn compress_blocks(raw: &[u8], sizes: &mut Vec<u64>, out: &mut dyn Write) -> io::Result<()> {
    let blocks: Vec<Vec<u8>> = raw
        .par_chunks(BLOCK_BYTES)
        .map(zlib_blocks::compress)
        .collect::<io::Result<_>>()?;
    for b in blocks {
        out.write_all(&b)?;
        sizes.push(b.len() as u64);
    }
    Ok(())
}

/// The XML before the appended data.
fn header_xml(piece: &Piece, spilled: &[Spilled]) -> String {
    let mut x = String::from("<?xml version=\"1.0\"?>\n");
    let _ = writeln!(
        x,
        r#"<VTKFile type="{}" version="1.0" byte_order="LittleEndian" header_type="UInt64" compressor="vtkZLibDataCompressor">"#,
        piece.kind
    );
    let _ = writeln!(x, "  <{}>", piece.kind);
    let counts: Vec<String> = piece
        .counts
        .iter()
        .map(|(k, v)| format!(r#"{k}="{v}""#))
        .collect();
    let _ = writeln!(x, "    <Piece {}>", counts.join(" "));
    let mut offsets = Vec::with_capacity(spilled.len());
    let mut offset = 0;
    for s in spilled {
        offsets.push(offset);
        offset += s.header.len() as u64 + s.bytes;
    }
    let sections = [Section::PointData, Section::CellData, Section::Points]
        .into_iter()
        .chain(piece.arrays.iter().map(|a| a.section))
        .collect::<std::collections::BTreeSet<_>>();
    for section in sections {
        let active: String = piece
            .active
            .iter()
            .filter(|(s, _, _)| *s == section)
            .map(|(_, kind, name)| format!(r#" {kind}="{name}""#))
            .collect();
        let _ = writeln!(x, "      <{}{active}>", section.tag());
        for (a, offset) in piece.arrays.iter().zip(&offsets) {
            if a.section == section {
                // One component is VTK's default, and meshio reads an explicit 1 as a
                // column (n × 1) rather than a vector.
                let components = match a.components {
                    1 => String::new(),
                    n => format!(r#" NumberOfComponents="{n}""#),
                };
                let _ = writeln!(
                    x,
                    r#"        <DataArray type="{}" Name="{}"{components} format="appended" offset="{offset}"/>"#,
                    a.scalar.name(),
                    a.name,
                );
            }
        }
        let _ = writeln!(x, "      </{}>", section.tag());
    }
    let _ = writeln!(x, "    </Piece>");
    let _ = writeln!(x, "  </{}>", piece.kind);
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::read::ZlibDecoder;

    /// Reads array `k` of a file this module wrote back: its raw values.
    fn read_back(file: &[u8], k: usize) -> Vec<u8> {
        let text = String::from_utf8_lossy(file);
        let offsets: Vec<usize> = text
            .match_indices("offset=\"")
            .map(|(i, m)| {
                let rest = &text[i + m.len()..];
                rest[..rest.find('"').unwrap()].parse().unwrap()
            })
            .collect();
        let marker = b"encoding=\"raw\">";
        let tag = file
            .windows(marker.len())
            .position(|w| w == marker)
            .unwrap();
        let underscore = tag + file[tag..].iter().position(|&b| b == b'_').unwrap();
        let data = &file[underscore + 1..];
        let at = &data[offsets[k]..];
        let word = |j: usize| u64::from_le_bytes(at[8 * j..8 * j + 8].try_into().unwrap());
        let blocks = word(0) as usize;
        let mut pos = 8 * (3 + blocks);
        let mut raw = Vec::new();
        for j in 0..blocks {
            let n = word(3 + j) as usize;
            ZlibDecoder::new(&at[pos..pos + n])
                .read_to_end(&mut raw)
                .unwrap();
            pos += n;
        }
        let last = word(2) as usize;
        let full = word(1) as usize * blocks.saturating_sub(usize::from(last > 0));
        assert_eq!(raw.len(), full + last);
        raw
    }

    #[test]
    fn arrays_of_several_blocks_read_back_whole() {
        // 3 items of 50 000 f64: several blocks and a partial last one.
        let per_item = 50_000;
        let value = |i: usize, j: usize| (i * per_item + j) as f64 * 0.5;
        let piece = Piece {
            kind: "PolyData",
            counts: vec![("NumberOfPoints", 3 * per_item)],
            active: vec![(Section::PointData, "Scalars", "x")],
            items: 3,
            arrays: vec![
                Array::new(Section::PointData, "x", Scalar::Float64, 1, |i, b| {
                    b.extend((0..per_item).flat_map(|j| value(i, j).to_le_bytes()))
                }),
                Array::new(Section::PointData, "empty", Scalar::UInt8, 1, |_, _| {}),
            ],
        };
        let mut file = Vec::new();
        write_piece(&mut file, piece).unwrap();
        let raw = read_back(&file, 0);
        let values: Vec<f64> = raw
            .chunks(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(values.len(), 3 * per_item);
        assert!(values
            .iter()
            .enumerate()
            .all(|(k, &v)| v == value(k / per_item, k % per_item)));
        assert!(read_back(&file, 1).is_empty());
        let text = String::from_utf8_lossy(&file);
        assert!(text.contains(r#"<PointData Scalars="x">"#), "{text}");
        assert!(text.ends_with("</AppendedData>\n</VTKFile>\n"));
    }

    #[test]
    fn indices_take_int32_until_it_overflows() {
        assert_eq!(Scalar::index(i32::MAX as usize), Scalar::Int32);
        assert_eq!(Scalar::index(i32::MAX as usize + 1), Scalar::Int64);
        let mut b = Vec::new();
        Scalar::Int64.push_index(1 << 40, &mut b);
        Scalar::Int32.push_index(7, &mut b);
        assert_eq!(b.len(), 12);
    }
}
