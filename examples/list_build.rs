//! Times the packing loop's list build on a packed state: the octree rebuilt over the
//! grains' bounding spheres grown by the loop's skin, and every pair they meet listed.
//!
//! ```text
//! cargo run --release -- benches/scale/hundred_thousand.toml --out /tmp/h --quiet
//! cargo run --release --example list_build -- /tmp/h/grains.csv 51 40
//! ```
//!
//! Arguments: a `grains.csv` (3D), the side of its periodic cubic box, and how many
//! builds to time. Prints the pairs, a hash of the list (ids and images in list order:
//! two builds of the code that list the same pairs in the same order print the same
//! hash) and the median rebuild and walk times.

use grainpack::octree::{BoxShape, Octree, Params, Sphere};
use std::time::Instant;

/// The loop's skin as a share of the mean bounding radius (`NeighbourParams::skin`).
const SKIN: f64 = 0.6;
/// The scale the loop builds its lists at after the overshoot (`1 + margin`).
const SCALE: f64 = 1.001;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let [_, path, side, builds] = &args[..] else {
        return Err("usage: list_build GRAINS_CSV BOX_SIDE BUILDS".into());
    };
    let (side, builds): (f64, usize) = (side.parse()?, builds.parse()?);
    let mut spheres = Vec::new();
    for (k, line) in std::fs::read_to_string(path)?.lines().skip(1).enumerate() {
        let v: Vec<f64> = line.split(',').map(str::parse).collect::<Result<_, _>>()?;
        let radius = v[5].max(v[6]).max(v[7]);
        let (id, centre) = (k as u32, [v[2], v[3], v[4]]);
        spheres.push(Sphere { id, centre, radius });
    }
    let mean = spheres.iter().map(|s| s.radius).sum::<f64>() / spheres.len() as f64;
    let skin = SKIN * SCALE * mean;
    for s in &mut spheres {
        s.radius = SCALE * s.radius + 0.5 * skin;
    }
    let shape = BoxShape::periodic([side; 3])?;
    let mut tree = Octree::build(&spheres, shape, Params::default())?;
    let mut pairs = Vec::new();
    let (mut rebuild, mut walk) = (Vec::new(), Vec::new());
    for _ in 0..builds.max(1) {
        let t0 = Instant::now();
        tree.rebuild(&spheres)?;
        let t1 = Instant::now();
        tree.pairs(&mut pairs);
        rebuild.push(t1 - t0);
        walk.push(t1.elapsed());
    }
    let hash = pairs.iter().fold(0u64, |h, p| {
        let image = p.image.map(|k| k as i64);
        let key = 7 * u64::from(p.i)
            + 3 * u64::from(p.j)
            + (9 * image[0] + 3 * image[1] + image[2]) as u64;
        h.wrapping_mul(31).wrapping_add(key)
    });
    rebuild.sort();
    walk.sort();
    let ms = |d: std::time::Duration| 1e3 * d.as_secs_f64();
    println!(
        "pairs {} hash {hash:016x} rebuild median {:.2} ms walk median {:.2} ms (best {:.2})",
        pairs.len(),
        ms(rebuild[rebuild.len() / 2]),
        ms(walk[walk.len() / 2]),
        ms(walk[0]),
    );
    Ok(())
}
