use super::*;
use crate::contact::test_pairs::{random_pairs, reference_rows};

/// Bitwise the same `Result` as the scalar functions, pair by pair, from the lanes
/// (whatever the target) and from [`contact_functions`] and [`contact_functions_fast`].
fn assert_same(pairs: &[(Vec3, Sym3, Sym3)]) {
    assert_lanes_same(pairs, &in_lanes::<true>(pairs), contact_function);
    assert_lanes_same(pairs, &contact_functions(pairs), contact_function);
    assert_lanes_same(pairs, &in_lanes::<false>(pairs), contact_function_fast);
    assert_lanes_same(pairs, &contact_functions_fast(pairs), contact_function_fast);
}

type Scalar = fn(&Vec3, &Sym3, &Sym3) -> Result<Contact, ContactError>;

fn assert_lanes_same(
    pairs: &[(Vec3, Sym3, Sym3)],
    batch: &[Result<Contact, ContactError>],
    scalar: Scalar,
) {
    assert_eq!(batch.len(), pairs.len());
    for (k, ((r12, q1, q2), got)) in pairs.iter().zip(batch).enumerate() {
        let want = scalar(r12, q1, q2);
        match (got, &want) {
            (Ok(g), Ok(w)) => {
                assert_eq!(g.mu2.to_bits(), w.mu2.to_bits(), "pair {k}: {g:?} vs {w:?}");
                assert_eq!(g.lambda.to_bits(), w.lambda.to_bits(), "pair {k}");
                assert_eq!((g.stop, g.iterations), (w.stop, w.iterations), "pair {k}");
            }
            // Debug, not ==: an error may carry the NaN it found.
            _ => assert_eq!(format!("{got:?}"), format!("{want:?}"), "pair {k}"),
        }
    }
}

#[test]
fn batch_equals_scalar_on_the_reference_sets() {
    for name in ["contact_typical.csv", "contact_extreme.csv"] {
        let pairs: Vec<_> = reference_rows(name)
            .into_iter()
            .map(|(c, _, _)| (c.r12, c.q1, c.q2))
            .collect();
        assert_same(&pairs);
    }
}

#[test]
fn batch_equals_scalar_on_random_pairs_and_odd_lengths() {
    let pairs: Vec<_> = random_pairs(41, 203).into_iter().map(|(p, _)| p).collect();
    assert_same(&pairs);
    assert_same(&pairs[..5]);
    assert_same(&[]);
}

/// Lanes whose pair leaves the common path go through the scalar code, next to plain
/// ones: zero offset, rescaling, not positive definite, non-finite, singular, and two
/// spheres of radii 1 and 2^-40, whose maximiser λ = 1 − 2^-40 sends the predictor to
/// its term-by-term derivatives.
#[test]
fn batch_equals_scalar_where_pairs_leave_the_common_path() {
    let unit = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0];
    let big = unit.map(|x| x * 1e200);
    let plain = ([1.5, 0.2, -0.3], unit, [2.0, 0.1, 0.0, 1.0, 0.0, 0.5]);
    let odd = [
        ([0.0; 3], unit, unit),
        ([1e150, 0.0, 0.0], big, unit),
        ([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 1.0, 0.0, 1.0], unit),
        ([f64::NAN, 0.0, 0.0], unit, unit),
        ([1.0, 0.0, 0.0], unit, [1.0, 0.0, 0.0, 1.0, 0.0, 0.0]),
        ([1.0, 0.0, 0.0], unit, unit.map(|x| x * 2f64.powi(-80))),
    ];
    for (k, pair) in odd.iter().enumerate() {
        let mut pairs = vec![plain; 16];
        pairs[k] = *pair;
        pairs[8 + 7 - k] = *pair;
        assert_same(&pairs);
    }
}
