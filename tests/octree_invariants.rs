//! The tree stays sound through builds and rebuilds, and wrapping changes nothing.

mod support;

use grainpack::octree::{BoxShape, Octree, Params, Sphere};
use rand::Rng;
use support::octree::*;

#[test]
fn invariants_hold_for_every_scene_and_parameter_set() {
    let mut r = rng(1);
    let scenes = [
        uniform(&mut r, 300, [1.0; 3], |r| log_uniform(r, 0.002, 100.0)),
        clustered(&mut r, 300, [1.0; 3], 0.01),
        on_faces(&mut r, 300, [2.0, 1.0, 0.5], 0.05),
    ];
    for spheres in &scenes {
        for max_leaf_size in [1, 4, 48] {
            for loose_factor in [0.5, 1.0, 3.0] {
                let params = Params {
                    max_leaf_size,
                    loose_factor,
                    max_depth: 8,
                    ..Params::default()
                };
                for shape in [
                    BoxShape::periodic([2.0, 1.0, 0.5]).unwrap(),
                    BoxShape::reflecting([2.0, 1.0, 0.5]).unwrap(),
                ] {
                    let tree = Octree::build(spheres, shape, params).unwrap();
                    tree.check_invariants().unwrap();
                    assert_eq!(tree.len(), spheres.len());
                    assert!(tree.depth() <= params.max_depth);
                }
            }
        }
    }
}

#[test]
fn rebuild_reusing_buffers_equals_a_fresh_build() {
    let shape = BoxShape::periodic([1.0; 3]).unwrap();
    let mut r = rng(2);
    let first = uniform(&mut r, 500, [1.0; 3], |_| 0.03);
    let mut tree = Octree::build(&first, shape, Params::default()).unwrap();
    for n in [800, 50, 0, 500] {
        let spheres = uniform(&mut r, n, [1.0; 3], |r| log_uniform(r, 0.005, 10.0));
        tree.rebuild(&spheres).unwrap();
        tree.check_invariants().unwrap();
        let fresh = Octree::build(&spheres, shape, Params::default()).unwrap();
        let (mut a, mut b) = (Vec::new(), Vec::new());
        tree.pairs(&mut a);
        fresh.pairs(&mut b);
        assert_eq!(a, b);
        assert_matches_brute_force(&spheres, shape, Params::default());
    }
}

#[test]
fn moving_grains_by_whole_periodic_images_changes_no_pair() {
    // Dyadic centres in a box of side 1: adding whole box lengths and wrapping back is
    // exact, so the wrapped scene is bit-for-bit the original one.
    let shape = BoxShape::periodic([1.0, 2.0, 0.5]).unwrap();
    let mut r = rng(3);
    let spheres: Vec<Sphere> = (0..300)
        .map(|id| Sphere {
            id,
            centre: shape
                .lengths
                .map(|l| f64::from(r.random_range(0..1024)) / 1024.0 * l),
            radius: 0.04,
        })
        .collect();
    let moved: Vec<Sphere> = spheres
        .iter()
        .map(|s| Sphere {
            centre: [0, 1, 2]
                .map(|a| s.centre[a] + f64::from(r.random_range(-3..4)) * shape.lengths[a]),
            ..*s
        })
        .collect();
    let a = assert_matches_brute_force(&spheres, shape, Params::default());
    let b = assert_matches_brute_force(&moved, shape, Params::default());
    assert_eq!(a, b);
    let (ta, tb) = (
        Octree::build(&spheres, shape, Params::default()).unwrap(),
        Octree::build(&moved, shape, Params::default()).unwrap(),
    );
    let (mut pa, mut pb) = (Vec::new(), Vec::new());
    ta.pairs(&mut pa);
    tb.pairs(&mut pb);
    assert_eq!(sorted_keys(&pa), sorted_keys(&pb));
}

#[test]
fn input_order_does_not_change_the_pair_set() {
    let shape = BoxShape::periodic([1.0; 3]).unwrap();
    let mut r = rng(4);
    let spheres = uniform(&mut r, 400, [1.0; 3], |r| log_uniform(r, 0.01, 5.0));
    let mut reversed = spheres.clone();
    reversed.reverse();
    let (ta, tb) = (
        Octree::build(&spheres, shape, Params::default()).unwrap(),
        Octree::build(&reversed, shape, Params::default()).unwrap(),
    );
    let (mut pa, mut pb) = (Vec::new(), Vec::new());
    ta.pairs(&mut pa);
    tb.pairs(&mut pb);
    assert_eq!(sorted_keys(&pa), sorted_keys(&pb));
}
