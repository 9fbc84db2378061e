//! The voxel RVE: the fast voxeliser against the brute-force one and against an
//! independent inside test, periodic wrap, ties, threads, the per-grain report, errors.
//! The files (.vti, .png) are in `voxel_files.rs`.

mod support;

use grainpack::io::voxel::{brute_force_voxelise, grain_report, voxelise, VoxelError};
use grainpack::packing::PackedGrain;
use grainpack::scene::RveFill;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use support::voxel::*;

#[test]
fn sphere_voxel_volume_approaches_the_ball_volume() {
    // Off-grid centre, so that no symmetry makes the count exact by luck.
    let g = grain(0, [0.513, 0.471, 0.529], [0.3; 3], IDENTITY);
    let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.3f64.powi(3);
    for periodic in [false, true] {
        let dev: Vec<f64> = [8, 16, 32, 64, 128]
            .iter()
            .map(|&n| {
                let grid = voxelise(
                    &[g],
                    &domain([1.0; 3], periodic),
                    [n; 3],
                    RveFill::Matrix,
                    2,
                )
                .unwrap();
                let count = grid.material.iter().filter(|&&m| m == 0).count();
                (count as f64 * grid.voxel_volume() - ball).abs() / ball
            })
            .collect();
        // The surface error falls like 1/N on average (not monotonically).
        assert!(dev[4] < 0.005, "{dev:?}");
        assert!(dev[4] < dev[0] && dev[3] < dev[1], "{dev:?}");
    }
}

#[test]
fn fill_grains_leaves_nothing_unassigned_and_keeps_every_grain_interior() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for periodic in [true, false] {
        let size = [1.0, 1.3, 0.9];
        let grains = random_packing(&mut rng, 25, size, periodic);
        let d = domain(size, periodic);
        let full = voxelise(&grains, &d, [21, 26, 19], RveFill::Grains, 2).unwrap();
        let holes = voxelise(&grains, &d, [21, 26, 19], RveFill::Matrix, 2).unwrap();
        let n = grains.len() as u32;
        let mut inside = 0;
        for v in 0..full.len() {
            assert!(full.material[v] < n, "voxel {v} has no grain");
            let x = centre_of(&full, v);
            let t: Vec<f64> = grains.iter().map(|g| t2(g, x, size, periodic)).collect();
            // Voxels within 1e-9 of a surface are left out: rounding may put them on
            // either side, and this check rounds differently from the crate.
            match t.iter().position(|&t| t < 1.0 - 1e-9) {
                Some(g) => {
                    inside += 1;
                    assert_eq!(full.material[v], g as u32, "voxel {v}");
                    assert_eq!(holes.material[v], g as u32, "voxel {v}");
                    assert_eq!(full.phase[v], grains[g].phase as u32);
                }
                None if t.iter().all(|&t| t > 1.0 + 1e-9) => {
                    assert_eq!(holes.material[v], n, "voxel {v} is in no grain");
                    assert_eq!(holes.phase[v], 2, "the matrix is phase `phases`");
                }
                None => {}
            }
        }
        assert!(
            inside > full.len() / 10,
            "the packing is too sparse to test: {inside}"
        );
    }
}

#[test]
fn a_grain_on_a_corner_shows_in_all_eight_corners_of_a_periodic_box_only() {
    let q = [0.9, 0.1, 0.3, 0.3];
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    // Corner voxel centres are within 0.13 of the centre's images: inside the
    // inscribed sphere (0.15) of the grain.
    let g = grain(0, [0.02, 0.97, 0.01], [0.25, 0.2, 0.15], q.map(|x| x / n));
    for periodic in [true, false] {
        let grid = voxelise(
            &[g],
            &domain([1.0; 3], periodic),
            [10; 3],
            RveFill::Matrix,
            1,
        )
        .unwrap();
        let corners: Vec<u32> = (0..8)
            .map(|c| {
                let i = [c & 1, (c >> 1) & 1, (c >> 2) & 1].map(|b| b * 9);
                grid.material[grid.index(i[0], i[1], i[2])]
            })
            .collect();
        let grain_corners = corners.iter().filter(|&&m| m == 0).count();
        assert_eq!(grain_corners, if periodic { 8 } else { 1 }, "{corners:?}");
        let report = grain_report(&grid, &[g]).unwrap();
        assert_eq!(
            report.grains[0].pieces, 1,
            "wrapped across faces it is one piece"
        );
    }
}

#[test]
fn fast_voxeliser_matches_brute_force_exactly() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for case in 0..16 {
        let periodic = case % 2 == 0;
        let size = [1.0, 0.8, 1.2];
        let grains = if case < 8 {
            random_packing(&mut rng, 20, size, periodic)
        } else {
            random_grains(&mut rng, case as u32 - 5, size)
        };
        let cells = if case % 4 < 2 {
            [15, 13, 17]
        } else {
            [7, 22, 11]
        };
        for fill in [RveFill::Matrix, RveFill::Grains] {
            let d = domain(size, periodic);
            let fast = voxelise(&grains, &d, cells, fill, 2).unwrap();
            let slow = brute_force_voxelise(&grains, &d, cells, fill, 2).unwrap();
            let differ = (0..fast.len())
                .filter(|&v| fast.material[v] != slow.material[v])
                .count();
            assert_eq!(differ, 0, "case {case}, {fill:?}: {differ} voxels differ");
            assert_eq!(fast, slow);
        }
    }
}

#[test]
fn ties_go_to_the_lower_material_number() {
    // Dyadic numbers, so every t² below is exact: with 8 cells, cell 4 has its centre at
    // x = 0.5625, exactly 0.25 from both spheres (x = 0.3125 and 0.8125).
    let a = grain(0, [0.3125, 0.5, 0.5], [0.125; 3], IDENTITY);
    let b = grain(1, [0.8125, 0.5, 0.5], [0.125; 3], IDENTITY);
    let d = domain([1.0; 3], false);
    for grains in [[a, b], [b, a]] {
        let grid = voxelise(&grains, &d, [8; 3], RveFill::Grains, 2).unwrap();
        assert_eq!(
            grid,
            brute_force_voxelise(&grains, &d, [8; 3], RveFill::Grains, 2).unwrap()
        );
        let first_is_a = grains[0].centre[0] < 0.5;
        for k in 0..8 {
            for j in 0..8 {
                // The tie goes to material 0, whichever sphere that is.
                assert_eq!(grid.material[grid.index(4, j, k)], 0);
                // Cell 3 (x = 0.4375) is nearer a, cell 5 (x = 0.6875) nearer b.
                let (near_a, near_b) = if first_is_a { (0, 1) } else { (1, 0) };
                assert_eq!(grid.material[grid.index(3, j, k)], near_a);
                assert_eq!(grid.material[grid.index(5, j, k)], near_b);
            }
        }
    }
}

#[test]
fn the_result_does_not_depend_on_the_thread_count() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let grains = random_grains(&mut rng, 12, [1.0; 3]);
    let d = domain([1.0; 3], true);
    let many = voxelise(&grains, &d, [40, 30, 70], RveFill::Grains, 2).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = pool.install(|| voxelise(&grains, &d, [40, 30, 70], RveFill::Grains, 2).unwrap());
    assert_eq!(many, one);
}

#[test]
fn a_grain_cut_in_two_is_reported_as_two_pieces() {
    let g = grain(5, [0.5, 0.5, 0.5], [0.3, 0.2, 0.2], IDENTITY);
    let mut grid = voxelise(&[g], &domain([1.0; 3], true), [20; 3], RveFill::Matrix, 2).unwrap();
    assert_eq!(grain_report(&grid, &[g]).unwrap().grains[0].pieces, 1);
    // Cut the layer x = 8 out of the grain: 0.4 < x < 0.45, left of the centre.
    let matrix = grid.matrix_material();
    for k in 0..20 {
        for j in 0..20 {
            let v = grid.index(8, j, k);
            grid.material[v] = matrix;
        }
    }
    let left = (0..grid.len())
        .filter(|&v| grid.material[v] == 0 && v % 20 < 8)
        .count() as u64;
    let report = grain_report(&grid, &[g]).unwrap();
    let r = &report.grains[0];
    assert_eq!((r.pieces, r.stray_voxels), (2, left));
    assert_eq!(report.split_grains, [5]);
}

#[test]
fn report_recovers_the_shape_of_a_well_resolved_ellipsoid_even_across_faces() {
    let q = [0.8, 0.2, -0.4, 0.4];
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let q = q.map(|x| x / n);
    for centre in [[0.5, 0.5, 0.5], [0.02, 0.98, 0.5]] {
        let g = grain(0, centre, [0.3, 0.15, 0.1], q);
        let grid = voxelise(&[g], &domain([1.0; 3], true), [80; 3], RveFill::Matrix, 1).unwrap();
        let report = grain_report(&grid, &[g]).unwrap();
        let r = &report.grains[0];
        let s = r.shape.as_ref().unwrap();
        // At 80 cells the smallest semi-axis spans 8 voxels: a few per cent.
        assert!(r.volume_deviation.abs() < 0.02, "{r:?}");
        for k in 0..3 {
            let rel = (s.semi_axes[k] - r.ellipsoid_semi_axes[k]).abs() / r.ellipsoid_semi_axes[k];
            assert!(rel < 0.03, "semi-axis {k}: {r:?}");
        }
        assert!(s.major_axis_angle_deg < 2.0, "{s:?}");
        assert!(s.centroid_offset < grid.spacing()[0], "{s:?}");
        assert!((s.aspect_ratio - 3.0).abs() < 0.1, "{s:?}");
        // DREAM.3D's ratios of the triaxial grain (b/a = 1/2, c/a = 1/3, c/b = 2/3):
        // each a ratio of two semi-axes within 3 %, so within about 6 %.
        for (got, want) in [
            (s.b_over_a, 0.5),
            (s.c_over_a, 1.0 / 3.0),
            (s.c_over_b, 2.0 / 3.0),
        ] {
            assert!((got / want - 1.0).abs() < 0.06, "{got} vs {want}: {s:?}");
        }
    }
}

#[test]
fn bad_input_gives_typed_errors_that_name_the_culprit() {
    let d = domain([1.0; 3], true);
    let g = grain(42, [0.5; 3], [0.1; 3], IDENTITY);
    let err = voxelise(&[g], &d, [4, 0, 4], RveFill::Matrix, 2).unwrap_err();
    assert!(matches!(err, VoxelError::ZeroCells { axis: 1 }), "{err}");
    let err = voxelise(&[g], &d, [4; 3], RveFill::Matrix, 0).unwrap_err();
    assert!(err.to_string().contains("grain 42"), "{err}");
    let nan = PackedGrain {
        centre: [0.5, f64::NAN, 0.5],
        ..g
    };
    let err = voxelise(&[nan], &d, [4; 3], RveFill::Matrix, 2).unwrap_err();
    assert!(
        matches!(err, VoxelError::NonFiniteCentre { id: 42, .. }),
        "{err}"
    );
    let flat = PackedGrain {
        semi_axes: [0.1, 0.0, 0.1],
        ..g
    };
    let err = voxelise(&[flat], &d, [4; 3], RveFill::Matrix, 2).unwrap_err();
    assert!(matches!(err, VoxelError::Shape { id: 42, .. }), "{err}");
    let err = voxelise(&[], &d, [4; 3], RveFill::Grains, 2).unwrap_err();
    assert!(matches!(err, VoxelError::NoGrains), "{err}");
    let err = voxelise(&[g], &d, [1 << 20, 1 << 20, 4], RveFill::Matrix, 2).unwrap_err();
    assert!(matches!(err, VoxelError::TooManyCells { .. }), "{err}");
    let grid = voxelise(&[g], &d, [4; 3], RveFill::Matrix, 2).unwrap();
    let err = grain_report(&grid, &[g, g]).unwrap_err();
    assert!(
        matches!(err, VoxelError::GrainCountMismatch { grid: 1, given: 2 }),
        "{err}"
    );
}
