//! The voxel RVE's files: the .vti decodes back to the grid, the PNG is whole.

mod support;

use grainpack::io::voxel::{voxelise, write_sections_png, write_vti};
use grainpack::scene::RveFill;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use support::voxel::*;

#[test]
fn vti_decodes_to_the_grid() {
    use base64::Engine;
    use std::io::Read;
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
    let mut out = Vec::new();
    write_vti(&grid, &mut out).unwrap();
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
            size[a] / grid.cells[a] as f64,
            "spacing printed exactly"
        );
    }
    let b64 = base64::engine::general_purpose::STANDARD;
    for (name, want) in [("material", &grid.material), ("phase", &grid.phase)] {
        let tag = format!(r#"type="Int32" Name="{name}" format="binary""#);
        let body = text.split(&tag).nth(1).unwrap();
        let body = &body[body.find('>').unwrap() + 1..body.find('<').unwrap()];
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
        let got: Vec<u32> = bytes
            .chunks(4)
            .map(|c| i32::from_le_bytes(c.try_into().unwrap()) as u32)
            .collect();
        assert_eq!(&got, want, "{name}");
    }
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
