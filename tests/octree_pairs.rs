//! The octree's pair set equals brute force's, exactly, on many kinds of scenes.

mod support;

use grainpack::octree::{BoxShape, Octree, Params, Sphere};
use support::octree::*;

const SEEDS: u64 = 6;

fn both_boundaries(lengths: [f64; 3]) -> [BoxShape; 2] {
    [
        BoxShape::periodic(lengths).unwrap(),
        BoxShape::reflecting(lengths).unwrap(),
    ]
}

#[test]
fn uniform_monodisperse_pairs_equal_brute_force() {
    for seed in 0..SEEDS {
        let mut r = rng(seed);
        let spheres = uniform(&mut r, 400, [1.0; 3], |_| 0.04);
        for shape in both_boundaries([1.0; 3]) {
            assert!(assert_matches_brute_force(&spheres, shape, Params::default()) > 0);
        }
    }
}

#[test]
fn polydisperse_100_to_1_pairs_equal_brute_force() {
    for seed in 0..SEEDS {
        let mut r = rng(100 + seed);
        let spheres = uniform(&mut r, 500, [1.0; 3], |r| log_uniform(r, 0.002, 100.0));
        for shape in both_boundaries([1.0; 3]) {
            assert_matches_brute_force(&spheres, shape, Params::default());
        }
    }
}

#[test]
fn few_huge_among_many_small_pairs_equal_brute_force() {
    let mut r = rng(7);
    let mut spheres = uniform(&mut r, 500, [1.0; 3], |_| 0.004);
    for (k, s) in spheres.iter_mut().take(3).enumerate() {
        s.radius = 0.4 / (k + 1) as f64; // 100:1, 50:1, 33:1
    }
    for shape in both_boundaries([1.0; 3]) {
        assert_matches_brute_force(&spheres, shape, Params::default());
    }
}

#[test]
fn clustered_pairs_equal_brute_force() {
    for seed in 0..SEEDS {
        let mut r = rng(200 + seed);
        let spheres = clustered(&mut r, 400, [2.0, 2.0, 2.0], 0.02);
        for shape in both_boundaries([2.0; 3]) {
            assert!(assert_matches_brute_force(&spheres, shape, Params::default()) > 0);
        }
    }
}

#[test]
fn spheres_on_every_face_edge_and_corner_pair_as_brute_force() {
    for seed in 0..SEEDS {
        let mut r = rng(300 + seed);
        let lengths = [1.0, 1.5, 0.75];
        let spheres = on_faces(&mut r, 300, lengths, 0.05);
        for shape in both_boundaries(lengths) {
            assert!(assert_matches_brute_force(&spheres, shape, Params::default()) > 0);
        }
    }
}

#[test]
fn non_cubic_boxes_pairs_equal_brute_force() {
    for (seed, lengths) in [[4.0, 1.0, 1.0], [1.0, 0.3, 2.0], [0.5, 0.5, 3.0]]
        .into_iter()
        .enumerate()
    {
        let mut r = rng(400 + seed as u64);
        let spheres = uniform(&mut r, 400, lengths, |r| log_uniform(r, 0.01, 5.0));
        for shape in both_boundaries(lengths) {
            assert!(assert_matches_brute_force(&spheres, shape, Params::default()) > 0);
        }
    }
}

#[test]
fn tiny_boxes_with_few_grains_pair_as_brute_force() {
    for seed in 0..40 {
        let mut r = rng(500 + seed);
        let n = 1 + (seed as usize % 5);
        let lengths = [1.0, 0.7, 1.3];
        let spheres = uniform(&mut r, n, lengths, |r| log_uniform(r, 0.1, 10.0));
        for shape in both_boundaries(lengths) {
            assert_matches_brute_force(&spheres, shape, Params::default());
        }
    }
}

#[test]
fn grains_larger_than_half_the_box_meet_every_image_and_themselves() {
    let lengths = [1.0, 1.0, 1.0];
    let shape = BoxShape::periodic(lengths).unwrap();
    let one = [Sphere {
        id: 9,
        centre: [0.3, 0.6, 0.2],
        radius: 0.6,
    }];
    // 2r = 1.2 ≥ 1: the grain meets its images across the 3 faces, and no edge image.
    let n = assert_matches_brute_force(&one, shape, Params::default());
    assert_eq!(n, 3);
    let two = [
        one[0],
        Sphere {
            id: 4,
            centre: [0.8, 0.1, 0.5],
            radius: 0.7,
        },
    ];
    // r1 + r2 = 1.3 > 1: the pair meets through several images.
    let n = assert_matches_brute_force(&two, shape, Params::default());
    assert!(
        n > 3 + 3 + 2,
        "expected several images of the pair, got {n} pairs in all"
    );
    for seed in 0..SEEDS {
        let mut r = rng(600 + seed);
        let spheres = uniform(&mut r, 30, [1.0, 0.8, 1.2], |r| log_uniform(r, 0.05, 20.0));
        for shape in both_boundaries([1.0, 0.8, 1.2]) {
            assert_matches_brute_force(&spheres, shape, Params::default());
        }
    }
}

#[test]
fn touching_spheres_count_as_a_pair() {
    // Centres on an integer lattice and radii 0.5: every neighbour touches exactly.
    let mut spheres = Vec::new();
    for x in 0..4 {
        for y in 0..4 {
            for z in 0..4 {
                let id = spheres.len() as u32;
                spheres.push(Sphere {
                    id,
                    centre: [x as f64, y as f64, z as f64],
                    radius: 0.5,
                });
            }
        }
    }
    let walls = BoxShape::reflecting([4.0; 3]).unwrap();
    assert_eq!(
        assert_matches_brute_force(&spheres, walls, Params::default()),
        3 * 3 * 16
    );
    let periodic = BoxShape::periodic([4.0; 3]).unwrap();
    assert_eq!(
        assert_matches_brute_force(&spheres, periodic, Params::default()),
        3 * 64
    );
}

#[test]
fn reflecting_boxes_report_no_shift() {
    let mut r = rng(700);
    let spheres = on_faces(&mut r, 300, [1.0; 3], 0.1);
    let tree = Octree::build(
        &spheres,
        BoxShape::reflecting([1.0; 3]).unwrap(),
        Params::default(),
    )
    .unwrap();
    let mut pairs = Vec::new();
    tree.pairs(&mut pairs);
    assert!(!pairs.is_empty());
    assert!(pairs.iter().all(|p| p.image == [0; 3] && p.i < p.j));
}

#[test]
fn coincident_centres_stop_at_max_depth_and_pair_as_brute_force() {
    let spheres: Vec<Sphere> = (0..50)
        .map(|id| Sphere {
            id,
            centre: [0.25, 0.25, 0.25],
            radius: 0.001,
        })
        .collect();
    let params = Params {
        max_leaf_size: 2,
        max_depth: 6,
        ..Params::default()
    };
    for shape in both_boundaries([1.0; 3]) {
        assert_eq!(
            assert_matches_brute_force(&spheres, shape, params),
            50 * 49 / 2
        );
    }
}

#[test]
fn every_leaf_size_and_loose_factor_gives_the_same_pairs() {
    let mut r = rng(800);
    let spheres = uniform(&mut r, 300, [1.0; 3], |r| log_uniform(r, 0.005, 20.0));
    for max_leaf_size in [1, 3, 16] {
        for loose_factor in [0.25, 1.0, 4.0] {
            let params = Params {
                max_leaf_size,
                loose_factor,
                ..Params::default()
            };
            for shape in both_boundaries([1.0; 3]) {
                assert_matches_brute_force(&spheres, shape, params);
            }
        }
    }
}

#[test]
fn parallel_and_serial_walks_give_the_same_pairs_in_the_same_order() {
    let mut r = rng(900);
    let n = grainpack::octree::PARALLEL_MIN_SPHERES + 1000;
    let spheres = uniform(&mut r, n, [1.0; 3], |r| log_uniform(r, 0.004, 4.0));
    let shape = BoxShape::periodic([1.0; 3]).unwrap();
    let serial = Octree::build(
        &spheres,
        shape,
        Params {
            parallel: false,
            ..Params::default()
        },
    )
    .unwrap();
    let parallel = Octree::build(
        &spheres,
        shape,
        Params {
            parallel: true,
            ..Params::default()
        },
    )
    .unwrap();
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let sa = serial.pairs(&mut a);
    let sb = parallel.pairs(&mut b);
    assert_eq!(a, b);
    assert_eq!(sa, sb);
}
