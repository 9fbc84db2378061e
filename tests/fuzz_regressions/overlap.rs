//! Defects of the overlap decision (`overlaps`, `overlaps_prepared`): defect 19 of
//! `docs/reliability.md`.

use grainpack::contact::{
    contact_function, embed_pair, overlaps, overlaps_2d, overlaps_prepared, PreparedEllipsoid,
    Sym2, Sym3, Vec2, Vec3,
};

/// Both entry points in both orders of the pair, as `(overlaps, overlaps_prepared)`.
fn decisions(r: &Vec3, q1: &Sym3, q2: &Sym3) -> [(bool, bool); 2] {
    let prepare = |q: &Sym3| PreparedEllipsoid::from_quadratic_form(q).unwrap();
    let (e1, e2) = (prepare(q1), prepare(q2));
    let m = r.map(|x| -x);
    [
        (
            overlaps(r, q1, q2).unwrap(),
            overlaps_prepared(r, &e1, &e2).unwrap(),
        ),
        (
            overlaps(&m, q2, q1).unwrap(),
            overlaps_prepared(&m, &e2, &e1).unwrap(),
        ),
    ]
}

/// fuzz target contact_bits_2d: a flat ellipse (semi-axes 2e-5 to 9e-3 and 1) and a
/// point-like grain (a needle or ellipse of size 1e-16 to 1e-38), `r12` along the long
/// axis, μ² = 1.00007 to 1.0001 in both orders (`contact_exact` agrees), but `overlaps`
/// answered overlap in the order whose two-sphere start is λ₀ = 1: the Newton step
/// towards λ* = 1 − 1e-22 rounds back to 1, which the iteration took for convergence,
/// and `f + g²/(2g′)` there (0.25, not μ²) decided. Now the accurate method decides.
#[test]
fn a_point_like_grain_just_outside_a_flat_ellipse_is_apart_in_both_orders() {
    let pairs: [(Vec2, Sym2, Sym2); 4] = [
        (
            [7.291122019556397e-304, 1.000047683728667],
            [
                4.929461283609271e-10,
                2.603235251791616e-188,
                1.0000000000000566,
            ],
            [
                4.857875059724969e-33,
                4.8578750597249806e-33,
                4.857875059736191e-33,
            ],
        ),
        (
            [3.054739790968597e-05, 1.0000343322753906],
            [
                7.987022399902344e-05,
                2.6032338819157537e-188,
                1.0000000000000566,
            ],
            [
                8.636168555220194e-78,
                3.38124217366107e-310,
                4.0195657312000424e-87,
            ],
        ),
        (
            [2.174196887423e-311, 1.000034332276811],
            [
                7.987022399903732e-05,
                3.338152294852615e-308,
                1.0000000000000566,
            ],
            [
                1.0410273767909543e-42,
                1.0410273767909543e-42,
                1.0410273778454435e-42,
            ],
        ),
        (
            [2.906618508884003e-121, 1.0000476874120066],
            [
                4.929461283609271e-10,
                2.603235251791616e-188,
                1.0000000000000566,
            ],
            [7.41841230137533e-68, 2.040768e-317, 1.7272337640528995e-77],
        ),
    ];
    for (r, q1, q2) in pairs {
        let m = r.map(|x| -x);
        assert!(!overlaps_2d(&r, &q1, &q2).unwrap(), "{r:?} {q1:?} {q2:?}");
        assert!(!overlaps_2d(&m, &q2, &q1).unwrap(), "{r:?} {q1:?} {q2:?}");
        let (r3, a, b) = embed_pair(&r, &q1, &q2);
        let mu2 = contact_function(&r3, &a, &b).unwrap().mu2;
        assert!(mu2 > 1.00006 && mu2 < 1.0001, "{mu2}");
        assert_eq!(decisions(&r3, &a, &b), [(false, false); 2], "μ² = {mu2}");
    }
}

/// The same in 3D, built by hand: a ball 1e-20 across beyond the rim of a flat
/// ellipsoid (semi-axes 1, 0.7 and 3e-5, whose condition number keeps the
/// separating-axis proofs from deciding and whose bounding sphere is loose) is apart at
/// μ² ≈ 1 + 4e-5 and overlaps at μ² ≈ 1 − 4e-5, in both orders, by both entry points.
#[test]
fn a_point_like_ball_at_a_flat_ellipsoids_rim_is_decided_in_both_orders() {
    let flat = [1.0, 0.0, 0.0, 1e-9, 0.0, 0.5];
    let ball = [1e-40, 0.0, 0.0, 1e-40, 0.0, 1e-40];
    for (x, overlap) in [(1.00002, false), (0.99998, true)] {
        let r = [x, 0.0, 0.0];
        let mu2 = contact_function(&r, &flat, &ball).unwrap().mu2;
        assert_eq!(mu2 < 1.0, overlap, "{mu2}");
        assert_eq!(
            decisions(&r, &flat, &ball),
            [(overlap, overlap); 2],
            "μ² = {mu2}"
        );
    }
}
