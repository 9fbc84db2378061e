//! The VTK files `pack` writes, read back without the writer's code: a plain XML
//! parser for the header, and the zlib blocks of the raw appended data decoded here.

use flate2::read::ZlibDecoder;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;
use std::collections::HashMap;
use std::io::Read;
use std::path::Path;

/// One `DataArray`: where it is (`CellData`, `Points`, ...), its attributes, and its
/// values decoded from the zlib blocks of the raw appended data.
pub struct Array {
    pub section: String,
    pub kind: String,
    pub components: usize,
    pub values: Vec<f64>,
}

/// A VTK XML file as this test reads it: the attributes of `VTKFile` and `Piece`, and
/// the arrays by name.
pub struct VtkFile {
    pub root: HashMap<String, String>,
    pub piece: HashMap<String, String>,
    pub arrays: HashMap<String, Array>,
}

impl VtkFile {
    pub fn array(&self, name: &str, section: &str, kind: &str, components: usize) -> &[f64] {
        let a = &self.arrays[name];
        assert_eq!(
            (a.section.as_str(), a.kind.as_str(), a.components),
            (section, kind, components),
            "{name}"
        );
        &a.values
    }

    pub fn count(&self, attribute: &str) -> usize {
        self.piece[attribute].parse().unwrap()
    }
}

fn attributes(e: &BytesStart) -> HashMap<String, String> {
    e.attributes()
        .map(|a| {
            let a = a.unwrap();
            let key = String::from_utf8(a.key.as_ref().to_vec()).unwrap();
            (key, a.unescape_value().unwrap().into_owned())
        })
        .collect()
}

/// One array's values from the raw appended data at `offset`: VTK's compressed layout,
/// a `UInt64` header `[blocks, block size, last block size (0 if full), compressed
/// sizes]` and then the zlib blocks.
fn decode(kind: &str, appended: &[u8], offset: usize) -> Vec<f64> {
    let at = &appended[offset..];
    let word = |j: usize| u64::from_le_bytes(at[8 * j..8 * j + 8].try_into().unwrap()) as usize;
    let (blocks, block, last) = (word(0), word(1), word(2));
    let mut data = Vec::new();
    let mut pos = 8 * (3 + blocks);
    for j in 0..blocks {
        let size = word(3 + j);
        ZlibDecoder::new(&at[pos..pos + size])
            .read_to_end(&mut data)
            .unwrap();
        pos += size;
    }
    let full_blocks = if last > 0 { blocks - 1 } else { blocks };
    assert_eq!(data.len(), full_blocks * block + last);
    let width = match kind {
        "Float64" | "Int64" => 8,
        "Float32" | "Int32" => 4,
        "UInt8" => 1,
        other => panic!("unexpected array type {other}"),
    };
    assert_eq!(data.len() % width, 0);
    data.chunks(width)
        .map(|c| match kind {
            "Float64" => f64::from_le_bytes(c.try_into().unwrap()),
            "Int64" => i64::from_le_bytes(c.try_into().unwrap()) as f64,
            "Int32" => f64::from(i32::from_le_bytes(c.try_into().unwrap())),
            "Float32" => f64::from(f32::from_le_bytes(c.try_into().unwrap())),
            _ => f64::from(c[0]),
        })
        .collect()
}

/// Reads a VTK XML file with its arrays in raw appended data: the XML up to
/// `<AppendedData encoding="raw">`, then the bytes after its `_`.
pub fn read_vtk(path: &Path) -> VtkFile {
    let bytes = std::fs::read(path).unwrap();
    let marker = b"<AppendedData encoding=\"raw\">";
    let start = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .expect("raw appended data");
    let underscore = start + bytes[start..].iter().position(|&b| b == b'_').unwrap();
    let appended = &bytes[underscore + 1..];
    let text = String::from_utf8(bytes[..start].to_vec()).unwrap();
    let mut reader = Reader::from_str(&text);
    let mut file = VtkFile {
        root: HashMap::new(),
        piece: HashMap::new(),
        arrays: HashMap::new(),
    };
    let mut section = String::new();
    loop {
        match reader.read_event() {
            Ok(Event::Start(e)) | Ok(Event::Empty(e)) => {
                let tag = String::from_utf8(e.name().as_ref().to_vec()).unwrap();
                let attrs = attributes(&e);
                match tag.as_str() {
                    "VTKFile" => file.root = attrs,
                    "Piece" => file.piece = attrs,
                    "DataArray" => {
                        assert_eq!(attrs["format"], "appended");
                        let kind = attrs["type"].clone();
                        let array = Array {
                            section: section.clone(),
                            values: decode(&kind, appended, attrs["offset"].parse().unwrap()),
                            kind,
                            components: attrs
                                .get("NumberOfComponents")
                                .map_or(1, |n| n.parse().unwrap()),
                        };
                        assert!(file.arrays.insert(attrs["Name"].clone(), array).is_none());
                    }
                    _ => section = tag,
                }
            }
            // The text stops inside the open VTKFile element.
            Ok(Event::Eof) | Err(_) => break,
            _ => {}
        }
    }
    assert_eq!(file.root["byte_order"], "LittleEndian");
    assert_eq!(file.root["header_type"], "UInt64");
    assert_eq!(file.root["compressor"], "vtkZLibDataCompressor");
    file
}
