//! What the voxel tests share: grains, boxes, random grain sets and an independent
//! inside test.

use grainpack::contact::{overlaps, Ellipsoid};
use grainpack::io::voxel::VoxelGrid;
use grainpack::packing::PackedGrain;
use grainpack::scene::{Boundary, Domain};
use nalgebra::{Matrix3, Vector3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The identity rotation.
pub const IDENTITY: [f64; 4] = [1.0, 0.0, 0.0, 0.0];

/// A grain of phase `id % 2`.
pub fn grain(id: u32, centre: [f64; 3], semi_axes: [f64; 3], quaternion: [f64; 4]) -> PackedGrain {
    PackedGrain {
        id,
        phase: (id % 2) as usize,
        centre,
        semi_axes,
        quaternion,
    }
}

/// A periodic or walled box.
pub fn domain(size: [f64; 3], periodic: bool) -> Domain {
    let boundary = if periodic {
        Boundary::Periodic
    } else {
        Boundary::Reflecting
    };
    Domain::new(size, boundary)
}

/// A uniformly random unit quaternion.
pub fn random_quaternion(rng: &mut ChaCha8Rng) -> [f64; 4] {
    loop {
        let q: [f64; 4] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n > 0.1 && n < 1.0 {
            return q.map(|x| x / n);
        }
    }
}

/// Random grains, overlapping freely; some larger than half the box, some needles.
pub fn random_grains(rng: &mut ChaCha8Rng, n: u32, size: [f64; 3]) -> Vec<PackedGrain> {
    let l = size.iter().copied().fold(f64::INFINITY, f64::min);
    (0..n)
        .map(|id| {
            let a = rng.random_range(0.04..0.3) * l;
            let semi = match id % 5 {
                0 => [a * 3.0, a * 0.3, a * 0.3], // needle, up to 0.9 L long
                1 => [a, a, a],
                _ => [
                    a,
                    a * rng.random_range(0.5..1.0),
                    a * rng.random_range(0.3..1.0),
                ],
            };
            let c = size.map(|s| rng.random_range(-0.1..1.1) * s);
            grain(id, c, semi, random_quaternion(rng))
        })
        .collect()
}

/// Random sequential addition of up to `n` grains: no two (nor images) overlap.
pub fn random_packing(
    rng: &mut ChaCha8Rng,
    n: u32,
    size: [f64; 3],
    periodic: bool,
) -> Vec<PackedGrain> {
    let l = size.iter().copied().fold(f64::INFINITY, f64::min);
    let mut out: Vec<PackedGrain> = Vec::new();
    for _ in 0..100_000 {
        if out.len() == n as usize {
            break;
        }
        let a = rng.random_range(0.1..0.2) * l;
        let semi = [
            a,
            a * rng.random_range(0.4..1.0),
            a * rng.random_range(0.4..1.0),
        ];
        let q = random_quaternion(rng);
        let c = size.map(|s| rng.random_range(0.0..s));
        let qe = Ellipsoid::new(semi, q).unwrap().q;
        let clear = out.iter().all(|o| {
            let qo = Ellipsoid::new(o.semi_axes, o.quaternion).unwrap().q;
            let r = [0, 1, 2].map(|k| {
                let d = o.centre[k] - c[k];
                if periodic {
                    d - size[k] * (d / size[k]).round()
                } else {
                    d
                }
            });
            !overlaps(&r, &qe, &qo).unwrap()
        });
        if clear {
            out.push(grain(out.len() as u32, c, semi, q));
        }
    }
    out
}

/// `(x − c)ᵀ Q⁻¹ (x − c)` at the nearest image, from nalgebra: independent of the crate.
pub fn t2(g: &PackedGrain, x: [f64; 3], size: [f64; 3], periodic: bool) -> f64 {
    let q = Ellipsoid::new(g.semi_axes, g.quaternion).unwrap().q;
    let m = Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5]);
    let inv = m.try_inverse().unwrap();
    let mut best = f64::INFINITY;
    let k = if periodic { -1..=1 } else { 0..=0 };
    for i in k.clone() {
        for j in k.clone() {
            for l in k.clone() {
                let s = [i, j, l];
                let d = Vector3::from_fn(|a, _| x[a] - g.centre[a] - s[a] as f64 * size[a]);
                best = best.min((d.transpose() * inv * d)[0]);
            }
        }
    }
    best
}

/// Centre of cell `v`.
pub fn centre_of(grid: &VoxelGrid, v: usize) -> [f64; 3] {
    let [nx, ny, _] = grid.cells;
    let h = grid.spacing();
    let idx = [v % nx, (v / nx) % ny, v / (nx * ny)];
    [0, 1, 2].map(|a| (idx[a] as f64 + 0.5) * h[a])
}
