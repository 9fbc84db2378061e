//! The 2D pixel RVE: one layer of cells at the grains' plane. Each pixel belongs to the
//! ellipse containing its centre (an independent 2D inside test), the fast and the
//! brute-force voxelisers agree, pieces are 4-connected, the report measures areas, and
//! the plane-strain deck is a CPE4 mesh with periodic equations on two components.

mod support;

use grainpack::contact::{ellipse_quaternion, ellipse_semi_axes};
use grainpack::io::voxel::{
    brute_force_voxelise, grain_report, layer_thickness, voxelise, write_vti, VoxelError,
};
use grainpack::packing::PackedGrain;
use grainpack::scene::{Boundary, Domain, LengthUnit, RveFill};
use nalgebra::{Matrix2, Vector2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// An ellipse as the packer writes it: centre on the slab's mid-plane, embedded
/// semi-axes, a turn about z; with its angle kept for the independent test.
struct Ellipse {
    grain: PackedGrain,
    axes: [f64; 2],
    theta: f64,
}

fn plane(size: [f64; 2], periodic: bool) -> Domain {
    let boundary = if periodic {
        Boundary::Periodic
    } else {
        Boundary::Reflecting
    };
    Domain::plane(size, boundary)
}

/// Random ellipses, overlapping freely, some crossing the edges, some needles.
fn random_ellipses(rng: &mut ChaCha8Rng, n: u32, domain: &Domain) -> Vec<Ellipse> {
    let [lx, ly, _] = domain.size;
    (0..n)
        .map(|id| {
            let a1 = rng.random_range(0.03..0.25) * lx.min(ly);
            let a2 = a1
                * if id % 4 == 0 {
                    0.1
                } else {
                    rng.random_range(0.3..1.0)
                };
            let theta = rng.random_range(-PI..PI);
            let centre = [
                rng.random_range(-0.1..1.1) * lx,
                rng.random_range(-0.1..1.1) * ly,
                domain.plane_z(),
            ];
            Ellipse {
                grain: PackedGrain {
                    id,
                    phase: (id % 2) as usize,
                    centre,
                    semi_axes: ellipse_semi_axes(a1, a2),
                    quaternion: ellipse_quaternion(theta),
                },
                axes: [a1, a2],
                theta,
            }
        })
        .collect()
}

/// `dᵀ A⁻¹ d` of the ellipse at its nearest image, with `A = R(θ) diag(a²) R(θ)ᵀ` built
/// here from the angle (nalgebra's 2×2 inverse): nothing of the crate's geometry.
fn t2(e: &Ellipse, x: [f64; 2], size: [f64; 2], periodic: bool) -> f64 {
    let (s, c) = e.theta.sin_cos();
    let r = Matrix2::new(c, -s, s, c);
    let a = r
        * Matrix2::from_diagonal(&Vector2::new(e.axes[0].powi(2), e.axes[1].powi(2)))
        * r.transpose();
    let inv = a.try_inverse().unwrap();
    let k = if periodic { -2..=2 } else { 0..=0 };
    let mut best = f64::INFINITY;
    for i in k.clone() {
        for j in k.clone() {
            let d = Vector2::new(
                x[0] - e.grain.centre[0] - f64::from(i) * size[0],
                x[1] - e.grain.centre[1] - f64::from(j) * size[1],
            );
            best = best.min((d.transpose() * inv * d)[0]);
        }
    }
    best
}

#[test]
fn each_pixel_belongs_to_the_ellipse_containing_its_centre() {
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    let size = [1.0, 1.4];
    for periodic in [true, false] {
        let d = plane(size, periodic);
        let ellipses = random_ellipses(&mut rng, 30, &d);
        let grains: Vec<PackedGrain> = ellipses.iter().map(|e| e.grain).collect();
        let cells = [50, 70, 1];
        let holes = voxelise(&grains, &d, cells, RveFill::Matrix, 2).unwrap();
        let full = voxelise(&grains, &d, cells, RveFill::Grains, 2).unwrap();
        let (mut inside, mut checked) = (0, 0);
        for j in 0..cells[1] {
            for i in 0..cells[0] {
                let x = [
                    (i as f64 + 0.5) * size[0] / 50.0,
                    (j as f64 + 0.5) * size[1] / 70.0,
                ];
                let t: Vec<f64> = ellipses.iter().map(|e| t2(e, x, size, periodic)).collect();
                let mut order: Vec<usize> = (0..t.len()).collect();
                order.sort_by(|&a, &b| t[a].total_cmp(&t[b]));
                let (first, second) = (t[order[0]], t[order[1]]);
                // Pixels within 1e-9 of an edge or of a tie are left out: this test
                // rounds differently from the crate.
                if (first - 1.0).abs() < 1e-9 || second - first < 1e-9 * first {
                    continue;
                }
                checked += 1;
                let v = holes.index(i, j, 0);
                let want = if first < 1.0 { order[0] as u32 } else { 30 };
                inside += usize::from(first < 1.0);
                assert_eq!(holes.material[v], want, "matrix fill, pixel ({i}, {j})");
                assert_eq!(full.material[v], order[0] as u32, "grains fill, ({i}, {j})");
            }
        }
        // Enough of both kinds for the test to mean something.
        assert!(
            checked > 3400 && inside > 500,
            "{checked} checked, {inside} inside"
        );
    }
}

#[test]
fn plane_grids_from_the_fast_and_the_brute_force_voxeliser_are_identical() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for periodic in [true, false] {
        let d = plane([2.0, 1.5], periodic);
        let grains: Vec<PackedGrain> = random_ellipses(&mut rng, 40, &d)
            .iter()
            .map(|e| e.grain)
            .collect();
        for fill in [RveFill::Matrix, RveFill::Grains] {
            let fast = voxelise(&grains, &d, [64, 48, 1], fill, 2).unwrap();
            let slow = brute_force_voxelise(&grains, &d, [64, 48, 1], fill, 2).unwrap();
            assert_eq!(fast, slow, "periodic {periodic}, {fill:?}");
        }
    }
}

#[test]
fn a_plane_grid_is_one_layer_as_thick_as_its_pixels() {
    let d = plane([3.0, 2.0], true);
    let err = voxelise(&[], &d, [30, 20, 2], RveFill::Matrix, 1).unwrap_err();
    assert!(matches!(err, VoxelError::PlaneLayers { cells: 2 }), "{err}");
    let grid = voxelise(&[], &d, [30, 25, 1], RveFill::Matrix, 1).unwrap();
    let [hx, hy]: [f64; 2] = [0.1, 0.08];
    assert_eq!(grid.size[..2], [3.0, 2.0]);
    // √(hx hy), from the spacings as the crate computes them (3/30, 2/25).
    assert_eq!(grid.size[2], layer_thickness(3.0 / 30.0, 2.0 / 25.0));
    assert!((grid.size[2] - (hx * hy).sqrt()).abs() < 1e-15);
    let mut out = Vec::new();
    write_vti(&grid, LengthUnit::Millimetre, None, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.contains(r#"WholeExtent="0 30 0 25 0 1""#), "{text}");
}

#[test]
fn the_report_of_a_plane_grid_measures_areas_and_moment_ellipses() {
    // One ellipse, a1 = 0.3, a2 = 0.12, at 30°, well inside a periodic unit square.
    let d = plane([1.0, 1.0], true);
    let theta = PI / 6.0;
    let g = PackedGrain {
        id: 0,
        phase: 0,
        centre: [0.47, 0.52, d.plane_z()],
        semi_axes: ellipse_semi_axes(0.3, 0.12),
        quaternion: ellipse_quaternion(theta),
    };
    let area = PI * 0.3 * 0.12;
    let grid = voxelise(&[g], &d, [400, 400, 1], RveFill::Matrix, 1).unwrap();
    let report = grain_report(&grid, &[g]).unwrap();
    let r = &report.grains[0];
    // π a1 a2, the products in another order: an ulp or two.
    assert!((r.ellipsoid_volume - area).abs() < 4.0 * f64::EPSILON * area);
    // 400 pixels across: the area to well under 1 %, the boundary's error ~ perimeter·h.
    assert!(r.volume_deviation.abs() < 2e-3, "{}", r.volume_deviation);
    assert!((report.ellipsoid_fraction - area).abs() < 4.0 * f64::EPSILON * area);
    assert_eq!(r.pieces, 1);
    let shape = r.shape.as_ref().unwrap();
    // Moment ellipse: semi-axes to a few tenths of a per cent at 0.3 / 0.0025 pixels.
    let [a1, mid, a2] = shape.semi_axes;
    assert!(
        (a1 / 0.3 - 1.0).abs() < 3e-3 && (a2 / 0.12 - 1.0).abs() < 3e-3,
        "{a1} {a2}"
    );
    assert!((mid - (a1 * a2).sqrt()).abs() < 1e-15);
    let [ux, uy, uz] = shape.axes[0];
    assert_eq!(uz, 0.0);
    let angle = uy.atan2(ux);
    let off = (angle - theta) - PI * ((angle - theta) / PI).round();
    assert!(off.abs() < 2e-3, "major axis at {angle}, not {theta}");
    assert!(shape.centroid_offset < 1e-3, "{}", shape.centroid_offset);
    assert!((shape.equivalent_diameter - 2.0 * (r.voxel_volume / PI).sqrt()).abs() < 1e-15);
}
