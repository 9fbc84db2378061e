//! The voxel RVE's files: the .vti decodes back to the grid, the PNG is whole.

mod support;

use grainpack::io::voxel::{voxelise, write_sections_png, write_vti, EULER_ARRAYS};
use grainpack::scene::{quaternion_to_euler, LengthUnit, RveFill};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use support::voxel::*;

#[test]
fn vti_decodes_to_the_grid() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let size = [1.0, 0.7, 1.1];
    let grains = random_grains(&mut rng, 9, size);
    let grid = voxelise(
        &grains,
        &domain(size, true),
        [31, 23, 37],
        RveFill::Matrix,
        2,
    )
    .unwrap();
    // Orientations for the 9 grains; the matrix (material 9) gets the identity.
    let orientations: Vec<[f64; 4]> = (0..9)
        .map(|k| {
            let t = 0.1 * k as f64;
            [t.cos(), t.sin(), 0.0, 0.0]
        })
        .collect();
    let mut out = Vec::new();
    // The box in mm; the file in m, as DAMASK reads it.
    write_vti(&grid, LengthUnit::Millimetre, Some(&orientations), &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.contains(r#"WholeExtent="0 31 0 23 0 37""#));
    let spacing: Vec<f64> = text
        .split("Spacing=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap()
        .split(' ')
        .map(|s| s.parse().unwrap())
        .collect();
    for a in 0..3 {
        assert_eq!(
            spacing[a],
            size[a] / 1e3 / grid.cells[a] as f64,
            "spacing in metres, printed exactly"
        );
    }
    let lines: Vec<&str> = text.lines().collect();
    for (name, want) in [("material", &grid.material), ("phase", &grid.phase)] {
        let bytes = array_bytes(&lines, name);
        let got: Vec<u32> = bytes
            .chunks(4)
            .map(|c| i32::from_le_bytes(c.try_into().unwrap()) as u32)
            .collect();
        assert_eq!(&got, want, "{name}");
    }
    // Each cell's Bunge angles in degrees (as grains.csv has them), the matrix's 0, as
    // three scalar arrays (DAMASK 3.0's GeomGrid.load takes only scalars).
    for (a, name) in EULER_ARRAYS.iter().enumerate() {
        let bytes = array_bytes(&lines, name);
        let got: Vec<f64> = bytes
            .chunks(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(got.len(), grid.material.len());
        for (&cell, &m) in got.iter().zip(&grid.material) {
            let want = orientations
                .get(m as usize)
                .map_or(0.0, |&q| quaternion_to_euler(q)[a].to_degrees());
            assert_eq!(cell, want, "{name} of material {m}");
        }
    }
    assert!(!text.contains("NumberOfComponents"), "scalars only");
}

/// The bytes of the cell array `name`, read the way DAMASK's Fortran reader reads it
/// (`VTI_readDataset_raw`, src/grid/VTI.f90): the whole base64 text is the line after
/// the `<DataArray … Name="name" …>` line, leading blanks skipped; the line after it
/// closes the array.
fn array_bytes(lines: &[&str], name: &str) -> Vec<u8> {
    use base64::Engine;
    use std::io::Read;
    let b64 = base64::engine::general_purpose::STANDARD;
    let at = lines
        .iter()
        .position(|l| l.contains("<DataArray") && l.contains(&format!(r#"Name="{name}""#)))
        .unwrap();
    assert!(lines[at].trim_end().ends_with('>'), "{}", lines[at]);
    assert_eq!(lines[at + 2].trim(), "</DataArray>");
    let body = lines[at + 1].trim_start();
    // The header: 3 UInt64 (32 base64 characters, no padding), then one per block.
    let head = b64.decode(&body[..32]).unwrap();
    let word = |b: &[u8], k: usize| u64::from_le_bytes(b[8 * k..8 * k + 8].try_into().unwrap());
    let blocks = word(&head, 0) as usize;
    let head_len = (3 + blocks) * 8;
    let head_chars = head_len.div_ceil(3) * 4;
    let head = b64.decode(&body[..head_chars]).unwrap();
    let data = b64.decode(&body[head_chars..]).unwrap();
    let mut bytes = Vec::new();
    let mut at = 0;
    for k in 0..blocks {
        let len = word(&head, 3 + k) as usize;
        flate2::read::ZlibDecoder::new(&data[at..at + len])
            .read_to_end(&mut bytes)
            .unwrap();
        at += len;
    }
    bytes
}

#[test]
fn sections_png_is_written_whole() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let grains = random_grains(&mut rng, 6, [1.0, 2.0, 1.5]);
    let grid = voxelise(
        &grains,
        &domain([1.0, 2.0, 1.5], true),
        [12, 24, 18],
        RveFill::Grains,
        2,
    )
    .unwrap();
    let dir = support::files::scratch("voxel", "png");
    let path = dir.join("sections.png");
    write_sections_png(&grid, &path).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let width = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let height = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert!(
        width > 2 * height,
        "three panels side by side: {width}×{height}"
    );
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "no temporary file left"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
