//! The reference voxeliser: every grain and every image that could matter, per voxel.

use super::geometry::{image_range, prepare, scaled_dist2, Lattice, REACH_SLACK};
use super::raster::MARGIN_VOXELS;
use super::{VoxelError, VoxelGrid};
use crate::packing::PackedGrain;
use crate::scene::Domain;
use crate::scene::RveFill;
use rayon::prelude::*;

/// What [`voxelise`](super::voxelise) computes, the slow and obvious way: for each voxel,
/// `t²` for every grain and every periodic image within reach, and the smallest wins
/// (ties to the lower material number). Same arguments, same errors. For tests.
///
/// "Within reach": the smallest `t` over all images is at most `u`, the smallest `t`
/// over the grains' nearest images (in `RveFill::Matrix` only `t ≤ 1` counts, so `u = 1`),
/// and an image farther than `u √Q_aa` along any axis has `t > u`.
pub fn brute_force_voxelise(
    grains: &[PackedGrain],
    domain: &Domain,
    cells: [usize; 3],
    fill: RveFill,
    phases: usize,
) -> Result<VoxelGrid, VoxelError> {
    let lat = Lattice::new(domain, cells)?;
    let forms = prepare(grains, &lat, phases)?;
    if fill == RveFill::Grains && forms.is_empty() {
        return Err(VoxelError::NoGrains);
    }
    let [nx, ny, nz] = cells;
    let matrix = forms.len() as u32;
    let material = (0..nx * ny * nz)
        .into_par_iter()
        .map(|v| {
            let x = [
                lat.coord(0, v % nx),
                lat.coord(1, (v / nx) % ny),
                lat.coord(2, v / (nx * ny)),
            ];
            let reach = match fill {
                RveFill::Matrix => 1.0,
                RveFill::Grains => forms
                    .iter()
                    .map(|f| {
                        let d = [0, 1, 2].map(|a| nearest(x[a] - f.centre[a], &lat, a));
                        scaled_dist2(&f.p, d).sqrt()
                    })
                    .fold(f64::INFINITY, f64::min),
            } * (1.0 + REACH_SLACK);
            let (mut best, mut winner) = (f64::INFINITY, matrix);
            for (g, f) in forms.iter().enumerate() {
                let k = [0, 1, 2].map(|a| {
                    let half = reach * f.half[a] + MARGIN_VOXELS * lat.h[a];
                    image_range(&lat, a, f.centre[a], half, x[a], x[a])
                });
                for kz in k[2].clone() {
                    for ky in k[1].clone() {
                        for kx in k[0].clone() {
                            let d = [
                                x[0] - lat.image(0, f.centre[0], kx),
                                x[1] - lat.image(1, f.centre[1], ky),
                                x[2] - lat.image(2, f.centre[2], kz),
                            ];
                            let t2 = scaled_dist2(&f.p, d);
                            if t2 < best {
                                (best, winner) = (t2, g as u32);
                            }
                        }
                    }
                }
            }
            if fill == RveFill::Matrix && best > 1.0 {
                matrix
            } else {
                winner
            }
        })
        .collect();
    Ok(lat.into_grid(fill, &forms, phases, material))
}

/// `d` moved by a multiple of the box edge to `[−L/2, L/2]` in a periodic box.
fn nearest(d: f64, lat: &Lattice, axis: usize) -> f64 {
    if lat.periodic {
        let l = lat.size[axis];
        d - l * (d / l).round()
    } else {
        d
    }
}
