//! The figure end to end: written, decodable, the documented size, with a voxel
//! outline exactly when voxel samples are given.

use super::*;
use crate::contact::equivalent_diameter;
use crate::scene::aspect_ratio;
use crate::scene::Scene;

/// Two phases covering every kind of panel: a lognormal size, a constant aspect
/// ratio, a tilt law and random orientations.
const SCENE: &str = r#"
    seed = 3
    grains = 120
    [box]
    size = [50, 50, 50]
    [[phase]]
    name = "tilted"
    size = { distribution = "lognormal", sigma = 0.4, scale = 6, min = 3, max = 10 }
    aspect_ratio = { distribution = "lognormal", sigma = 0.5, scale = 2, min = 1, max = 3.5 }
    orientation = { kind = "tilt", axis = "z", kappa = 1, mean = 90, min = 0, max = 180 }
    [[phase]]
    name = "round"
    size = { distribution = "uniform", min = 4, max = 6 }
    aspect_ratio = { distribution = "constant", value = 1.5 }
"#;

/// The scene's phases and its drawn grains as packed at full size.
fn grains() -> (Vec<Phase>, Vec<PackedGrain>) {
    let scene = Scene::from_str(SCENE, "test.toml").unwrap();
    let specs = scene.sample_grains(&mut scene.rng()).unwrap();
    let packed = specs
        .iter()
        .enumerate()
        .map(|(i, s)| PackedGrain::of_spec(i as u32, s, 1.0, [0.0; 3], s.quaternion))
        .collect();
    (scene.phases, packed)
}

/// Stand-in voxel measurements: the packed values, perturbed.
fn voxel_samples(packed: &[PackedGrain]) -> Vec<VoxelSample> {
    packed
        .iter()
        .map(|g| VoxelSample {
            phase: g.phase,
            equivalent_diameter: 0.97 * equivalent_diameter(g.semi_axes),
            aspect_ratio: 1.05 * aspect_ratio(g.semi_axes),
            tilt: Some(0.3),
            shape_ratios: None,
            spin: None,
        })
        .collect()
}

/// A decoded PNG: width, height, RGB pixels.
fn decode(bytes: &[u8]) -> (u32, u32, Vec<[u8; 3]>) {
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    let pixels = buf[..info.buffer_size()]
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    (info.width, info.height, pixels)
}

/// Pixels of exactly this colour: lines are drawn in their colour, unblended, along
/// their middle.
fn count(pixels: &[[u8; 3]], c: plotters::style::RGBColor) -> usize {
    pixels.iter().filter(|p| **p == [c.0, c.1, c.2]).count()
}

#[test]
fn figure_is_written_as_a_png_of_the_documented_size() {
    let (phases, packed) = grains();
    let dir = std::env::temp_dir().join(format!("grainpack-plots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("statistics.png");
    write_statistics_png(&path, &phases, &packed, None, &[]).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let (width, height, pixels) = decode(&bytes);
    assert_eq!(
        (u64::from(width), u64::from(height)),
        statistics_png_size(2)
    );
    assert_eq!((width, height), (1800, 60 + 2 * 470));
    // Drawn, not blank: target curves, and the white background around them.
    assert!(count(&pixels, draw::TARGET) > 1000);
    assert!(count(&pixels, plotters::style::WHITE) > pixels.len() / 2);
    // Only the file is left in the directory: the temporary one was renamed.
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn voxel_outline_is_drawn_only_when_voxel_samples_are_given() {
    let (phases, packed) = grains();
    let mut without = Vec::new();
    render_statistics_png(&mut without, &phases, &packed, None, &[]).unwrap();
    let mut with = Vec::new();
    let voxel = voxel_samples(&packed);
    render_statistics_png(&mut with, &phases, &packed, Some(&voxel), &[]).unwrap();
    let (_, _, without) = decode(&without);
    let (_, _, with) = decode(&with);
    assert_eq!(count(&without, draw::VOXEL), 0);
    assert!(count(&with, draw::VOXEL) > 1000);
}

#[test]
fn phases_out_of_range_are_typed_errors() {
    let (phases, mut packed) = grains();
    let mut voxel = voxel_samples(&packed);
    voxel[5].phase = 7;
    let mut sink = Vec::new();
    match render_statistics_png(&mut sink, &phases, &packed, Some(&voxel), &[]) {
        Err(PlotError::VoxelPhase {
            index: 5,
            phase: 7,
            phases: 2,
        }) => {}
        other => panic!("{other:?}"),
    }
    packed[3].phase = 2;
    let err = render_statistics_png(&mut sink, &phases, &packed, None, &[]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "grain 3 has phase index 2, but the scene has 2 phases"
    );
    assert!(matches!(
        render_statistics_png(&mut sink, &[], &[], None, &[]),
        Err(PlotError::NoPhases)
    ));
    assert!(sink.is_empty());
}

#[test]
fn a_phase_without_grains_still_gets_its_row() {
    let (phases, packed) = grains();
    let only_first: Vec<PackedGrain> = packed.into_iter().filter(|g| g.phase == 0).collect();
    let mut png = Vec::new();
    render_statistics_png(&mut png, &phases, &only_first, None, &[]).unwrap();
    let (width, height, _) = decode(&png);
    assert_eq!(
        (u64::from(width), u64::from(height)),
        statistics_png_size(2)
    );
}

#[test]
fn unwritable_path_is_a_write_error_naming_it() {
    let (phases, packed) = grains();
    let path = std::env::temp_dir()
        .join(format!("grainpack-no-such-dir-{}", std::process::id()))
        .join("statistics.png");
    let err = write_statistics_png(&path, &phases, &packed, None, &[]).unwrap_err();
    assert!(matches!(&err, PlotError::Write { path: p, .. } if *p == path));
    assert!(err.to_string().contains("statistics.png"));
}

#[test]
fn a_texture_adds_a_line_below_its_phase_with_its_target_curve() {
    use crate::io::texture::{AngleLaw, TextureMeasure};
    let (phases, packed) = grains();
    let mut plain = Vec::new();
    render_statistics_png(&mut plain, &phases, &packed, None, &[]).unwrap();
    let measure = TextureMeasure {
        phase: 1,
        measure: "rotation angle",
        angles: vec![2.0, 2.5, 1.0],
        law: AngleLaw::Haar,
        ks_distance: AngleLaw::Haar.ks_distance(&[2.0, 2.5, 1.0]),
    };
    let mut textured = Vec::new();
    render_statistics_png(&mut textured, &phases, &packed, None, &[measure]).unwrap();
    let (w0, h0, p0) = decode(&plain);
    let (w1, h1, p1) = decode(&textured);
    assert_eq!((w0, w1, h0, h1), (1800, 1800, 60 + 2 * 470, 60 + 3 * 470));
    // One more target curve drawn, on the new line only (the last phase's extra line).
    assert!(count(&p1, draw::TARGET) > count(&p0, draw::TARGET) + 300);
    let below = p1[(w1 * h0) as usize..]
        .iter()
        .filter(|p| **p == [draw::TARGET.0, draw::TARGET.1, draw::TARGET.2])
        .count();
    assert!(below > 300, "{below}");
}
