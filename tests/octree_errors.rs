//! Bad input gives a typed error naming the sphere and the value, never a panic.

use grainpack::octree::{
    brute_force_pairs, Boundary, BoxShape, Octree, OctreeError, Params, Sphere, MAX_IMAGES_PER_AXIS,
};

fn sphere(id: u32, centre: [f64; 3], radius: f64) -> Sphere {
    Sphere { id, centre, radius }
}

fn build(spheres: &[Sphere]) -> Result<Octree, OctreeError> {
    Octree::build(
        spheres,
        BoxShape::periodic([1.0; 3]).unwrap(),
        Params::default(),
    )
}

#[test]
fn a_non_finite_centre_is_rejected_with_its_id_axis_and_value() {
    let spheres = [
        sphere(0, [0.5; 3], 0.1),
        sphere(7, [0.5, f64::INFINITY, 0.5], 0.1),
    ];
    let err = build(&spheres).unwrap_err();
    assert!(
        matches!(err, OctreeError::NonFiniteCentre { id: 7, axis: 1, value } if value.is_infinite())
    );
    assert!(err.to_string().contains("sphere 7"));
}

#[test]
fn a_zero_negative_or_non_finite_radius_is_rejected_with_its_id() {
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let err = build(&[sphere(4, [0.5; 3], bad)]).unwrap_err();
        assert!(
            matches!(err, OctreeError::InvalidRadius { id: 4, .. }),
            "{bad}: {err}"
        );
        assert!(Sphere::new(4, [0.5; 3], bad).is_err());
    }
}

#[test]
fn a_zero_negative_or_non_finite_box_length_is_rejected() {
    for bad in [0.0, -2.0, f64::NAN, f64::INFINITY] {
        let err = BoxShape::new([1.0, 1.0, bad], Boundary::Reflecting).unwrap_err();
        assert_eq!(
            err.to_string(),
            OctreeError::InvalidBoxLength {
                axis: 2,
                value: bad
            }
            .to_string()
        );
        // The fields are public: build checks again.
        let shape = BoxShape {
            lengths: [bad, 1.0, 1.0],
            boundary: Boundary::Periodic,
        };
        assert!(matches!(
            Octree::build(&[], shape, Params::default()),
            Err(OctreeError::InvalidBoxLength { axis: 0, .. })
        ));
    }
}

#[test]
fn duplicate_ids_are_rejected_dense_or_sparse() {
    let dense = [
        sphere(1, [0.1; 3], 0.1),
        sphere(2, [0.2; 3], 0.1),
        sphere(1, [0.3; 3], 0.1),
    ];
    assert_eq!(
        build(&dense).unwrap_err(),
        OctreeError::DuplicateId { id: 1 }
    );
    let sparse = [
        sphere(u32::MAX, [0.1; 3], 0.1),
        sphere(5, [0.2; 3], 0.1),
        sphere(u32::MAX, [0.3; 3], 0.1),
    ];
    assert_eq!(
        build(&sparse).unwrap_err(),
        OctreeError::DuplicateId { id: u32::MAX }
    );
}

#[test]
fn a_grain_spanning_too_many_periodic_images_is_rejected_but_walls_accept_it() {
    let radius = 0.5 * f64::from(MAX_IMAGES_PER_AXIS) + 0.1;
    let err = build(&[sphere(3, [0.5; 3], radius)]).unwrap_err();
    assert!(matches!(
        err,
        OctreeError::TooLargeForBox { id: 3, axis: 0, .. }
    ));
    let largest_allowed = 0.5 * f64::from(MAX_IMAGES_PER_AXIS);
    assert!(build(&[sphere(3, [0.5; 3], largest_allowed)]).is_ok());
    let walls = BoxShape::reflecting([1.0; 3]).unwrap();
    assert!(Octree::build(&[sphere(3, [0.5; 3], radius)], walls, Params::default()).is_ok());
}

#[test]
fn out_of_range_parameters_are_rejected() {
    let leaf = Params {
        max_leaf_size: 0,
        ..Params::default()
    };
    let loose = Params {
        loose_factor: f64::NAN,
        ..Params::default()
    };
    for params in [leaf, loose] {
        let shape = BoxShape::periodic([1.0; 3]).unwrap();
        assert!(matches!(
            Octree::build(&[], shape, params),
            Err(OctreeError::InvalidParam { .. })
        ));
    }
}

#[test]
fn brute_force_checks_its_input_too() {
    let mut out = Vec::new();
    let shape = BoxShape::periodic([1.0; 3]).unwrap();
    let err = brute_force_pairs(&[sphere(9, [0.5; 3], -1.0)], &shape, &mut out).unwrap_err();
    assert!(matches!(err, OctreeError::InvalidRadius { id: 9, .. }));
}

#[test]
fn a_failed_rebuild_leaves_an_empty_tree() {
    let mut tree = build(&[sphere(0, [0.5; 3], 0.1), sphere(1, [0.55; 3], 0.1)]).unwrap();
    assert!(tree.rebuild(&[sphere(0, [0.5; 3], f64::NAN)]).is_err());
    assert!(tree.is_empty());
    tree.check_invariants().unwrap();
    let mut pairs = Vec::new();
    tree.pairs(&mut pairs);
    assert!(pairs.is_empty());
}

#[test]
fn an_empty_scene_has_no_pairs() {
    let tree = build(&[]).unwrap();
    tree.check_invariants().unwrap();
    let mut pairs = vec![grainpack::octree::Pair {
        i: 0,
        j: 1,
        image: [0; 3],
    }];
    tree.pairs(&mut pairs);
    assert!(pairs.is_empty(), "the buffer is cleared");
}
