//! Draws `statistics.png` for a scene's drawn grains, unpacked (as if packed at scale 1),
//! to look at the figure without running the packing loop.
//!
//! ```sh
//! cargo run --release --example statistics_plot -- [SCENE.toml] [OUT.png] [--voxel-demo]
//! ```
//!
//! Defaults: `configs/kanapy_elongated.toml`, `/tmp/h3-statistics.png`. With
//! `--voxel-demo` the voxel outline is drawn from stand-in values (the packed ones
//! shrunk by 3 % and stretched by 5 %), only to show how the outline looks: they are not
//! voxel measurements.

use grainpack::contact::equivalent_diameter;
use grainpack::io::plots::{axis_polar_angle, write_statistics_png, VoxelSample};
use grainpack::packing::PackedGrain;
use grainpack::scene::{aspect_ratio, tilt_angle, Orientation, Scene};
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let demo = args.iter().any(|a| a == "--voxel-demo");
    let mut paths = args.iter().filter(|a| !a.starts_with("--"));
    let scene_path = PathBuf::from(
        paths
            .next()
            .map_or("configs/kanapy_elongated.toml", |s| s.as_str()),
    );
    let out = PathBuf::from(
        paths
            .next()
            .map_or("/tmp/h3-statistics.png", |s| s.as_str()),
    );

    let scene = Scene::from_path(&scene_path)?;
    let specs = scene.sample_grains(&mut scene.rng())?;
    let packed: Vec<PackedGrain> = specs
        .iter()
        .enumerate()
        .map(|(i, s)| PackedGrain::of_spec(i as u32, s, 1.0, [0.0; 3], s.quaternion))
        .collect();
    let voxel: Option<Vec<VoxelSample>> = demo.then(|| {
        packed
            .iter()
            .map(|g| VoxelSample {
                phase: g.phase,
                equivalent_diameter: 0.97 * equivalent_diameter(g.semi_axes),
                aspect_ratio: 1.05 * aspect_ratio(g.semi_axes),
                tilt: Some(match scene.phases[g.phase].orientation {
                    Orientation::Tilt { axis, angle } => tilt_angle(g.quaternion, axis, &angle),
                    _ => axis_polar_angle(g.quaternion),
                }),
                shape_ratios: None,
                spin: None,
            })
            .collect()
    });
    write_statistics_png(&out, &scene.phases, &packed, voxel.as_deref(), &[])?;
    eprintln!(
        "wrote {} ({} grains of {})",
        out.display(),
        packed.len(),
        scene_path.display()
    );
    Ok(())
}
