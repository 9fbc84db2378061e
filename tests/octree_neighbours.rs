//! Neighbour queries equal brute force, exactly.

mod support;

use grainpack::octree::{
    brute_force_neighbours, BoxShape, Neighbour, Octree, OctreeError, Params, Sphere,
};
use rand::Rng;
use support::octree::*;

type Key = (u32, [u64; 3]);

fn keys(found: &[Neighbour]) -> Vec<Key> {
    let mut k: Vec<Key> = found
        .iter()
        .map(|n| (n.id, n.shift.map(f64::to_bits)))
        .collect();
    k.sort_unstable();
    let len = k.len();
    k.dedup();
    assert_eq!(k.len(), len, "a neighbour was reported twice");
    k
}

/// Runs `queries` random queries (centres in and around the box, radii from 0 up to
/// `max_radius`) and requires the tree and brute force to agree.
fn assert_queries_match(
    spheres: &[Sphere],
    shape: BoxShape,
    queries: usize,
    max_radius: f64,
    seed: u64,
) {
    let tree = Octree::build(spheres, shape, Params::default()).unwrap();
    let mut r = rng(seed);
    let (mut got, mut want) = (Vec::new(), Vec::new());
    for q in 0..queries {
        let centre = shape.lengths.map(|l| (r.random::<f64>() * 1.4 - 0.2) * l);
        let radius = if q % 5 == 0 {
            0.0
        } else {
            r.random::<f64>() * max_radius
        };
        tree.neighbours(centre, radius, &mut got).unwrap();
        brute_force_neighbours(spheres, &shape, centre, radius, &mut want).unwrap();
        assert_eq!(keys(&got), keys(&want), "query {centre:?} radius {radius}");
    }
}

#[test]
fn neighbours_equal_brute_force_in_uniform_and_polydisperse_scenes() {
    for seed in 0..4 {
        let mut r = rng(seed);
        let lengths = [1.0, 1.5, 0.8];
        let spheres = uniform(&mut r, 400, lengths, |r| log_uniform(r, 0.003, 100.0));
        for shape in [
            BoxShape::periodic(lengths).unwrap(),
            BoxShape::reflecting(lengths).unwrap(),
        ] {
            assert_queries_match(&spheres, shape, 60, 0.3, 10 + seed);
        }
    }
}

#[test]
fn neighbours_equal_brute_force_across_faces_and_in_tiny_boxes() {
    let mut r = rng(20);
    let spheres = on_faces(&mut r, 200, [1.0; 3], 0.08);
    assert_queries_match(&spheres, BoxShape::periodic([1.0; 3]).unwrap(), 60, 0.2, 21);
    let spheres = uniform(&mut r, 5, [0.5, 0.6, 0.7], |r| log_uniform(r, 0.1, 5.0));
    // Grains and query radii larger than the box: several images of each grain.
    assert_queries_match(
        &spheres,
        BoxShape::periodic([0.5, 0.6, 0.7]).unwrap(),
        60,
        1.0,
        22,
    );
}

#[test]
fn a_stored_grain_finds_itself_with_a_zero_shift() {
    let mut r = rng(30);
    let spheres = uniform(&mut r, 100, [1.0; 3], |_| 0.05);
    let tree = Octree::build(
        &spheres,
        BoxShape::periodic([1.0; 3]).unwrap(),
        Params::default(),
    )
    .unwrap();
    let mut found = Vec::new();
    for s in &spheres {
        tree.neighbours(s.centre, s.radius, &mut found).unwrap();
        assert!(found.iter().any(|n| n.id == s.id && n.shift == [0.0; 3]));
    }
}

#[test]
fn a_point_query_across_a_periodic_face_gets_the_image_shift() {
    let s = [Sphere {
        id: 3,
        centre: [0.05, 0.5, 0.95],
        radius: 0.1,
    }];
    let tree = Octree::build(&s, BoxShape::periodic([1.0; 3]).unwrap(), Params::default()).unwrap();
    let mut found = Vec::new();
    tree.neighbours([0.99, 0.5, 0.01], 0.0, &mut found).unwrap();
    assert_eq!(
        found,
        vec![Neighbour {
            id: 3,
            shift: [1.0, 0.0, -1.0]
        }]
    );
    let walls = Octree::build(
        &s,
        BoxShape::reflecting([1.0; 3]).unwrap(),
        Params::default(),
    )
    .unwrap();
    walls
        .neighbours([0.99, 0.5, 0.01], 0.0, &mut found)
        .unwrap();
    assert!(found.is_empty());
}

#[test]
fn invalid_queries_are_rejected() {
    let tree = Octree::build(
        &[],
        BoxShape::periodic([1.0; 3]).unwrap(),
        Params::default(),
    )
    .unwrap();
    let mut found = Vec::new();
    for (centre, radius) in [
        ([f64::NAN, 0.0, 0.0], 1.0),
        ([0.0; 3], -1.0),
        ([0.0; 3], f64::INFINITY),
    ] {
        assert!(matches!(
            tree.neighbours(centre, radius, &mut found),
            Err(OctreeError::InvalidQuery { .. })
        ));
    }
    tree.neighbours([0.5; 3], 1.0, &mut found).unwrap();
    assert!(found.is_empty());
}
