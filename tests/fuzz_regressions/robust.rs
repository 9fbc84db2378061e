//! Contact defects of the robust path (semi-definite forms, sizes far apart, flat
//! maxima): defects 1, 5, 6, 9 and 12 of `docs/reliability.md`.

use grainpack::contact::{contact_function, contact_function_fast, Stop};

/// fuzz target contact_bits: a form 2^1800 times the size of the other (beyond the
/// double range apart) put λ at ½ with `Stop::Exact`, while the swapped pair answered
/// 0. The small form is a point to the large one: λ* → 1 (for balls, λ* = R1/(R1+R2)).
#[test]
fn lambda_is_one_not_one_half_when_the_second_form_is_beyond_double_range_smaller() {
    let r = [0.3, 0.1, 0.0];
    let q1 = [
        3.75375841440235e255,
        4.669816313723274e-308,
        0.0,
        3.75375841440235e255,
        4.669816313723274e-308,
        3.753758421011899e255,
    ];
    let q2 = [
        7.291121767158173e-304,
        2.2673059898236077e-306,
        0.0,
        1.35675105885e-312,
        0.0,
        8.669768950612022e-280,
    ];
    let balls = (
        [1e300, 0.0, 0.0, 1e300, 0.0, 1e300],
        [1e-300, 0.0, 0.0, 1e-300, 0.0, 1e-300],
    );
    for (q1, q2) in [(q1, q2), balls] {
        for method in [contact_function, contact_function_fast] {
            let a = method(&r, &q1, &q2).unwrap();
            let b = method(&r.map(|x| -x), &q2, &q1).unwrap();
            assert_eq!(a.mu2, b.mu2, "{a:?} {b:?}");
            assert!(matches!(a.stop, Stop::Exact | Stop::Converged), "{a:?}");
            assert_eq!((a.lambda, b.lambda), (1.0, 0.0), "{a:?} {b:?}");
        }
    }
}

/// fuzz target contact_bits: a form with subnormal entries answered a μ² that depended
/// on the order of the pair. A flat disc whose second axis is a subnormal entry (2e-314
/// against 8.6e9, one bit once normalised) and a tiny definite form: 7.2e-18 in one order,
/// 2.9e-11 in the other (`tools/contact_exact.py`: 2.9103830456733697e-11, λ* = 1 and
/// 2e-160 by order). The entries the rank decision declared negligible still reached the
/// coefficients that do not vanish with the rank, and decided which end F tends to;
/// `exact::singular_form` now drops them (`UNRESOLVED`). The second pair, a point
/// against a flat disc whose null directions are 1e-317 and 8e-320 instead of 0,
/// answered 0.25 and 1/576.
#[test]
fn swapping_a_point_and_a_disc_with_subnormal_entries_keeps_mu2() {
    let pairs = [
        (
            [0.5, 0.0, 0.0],
            [8589934592.000002, 0.0, 0.0, 2.124066029e-314, 0.0, 0.0],
            [
                3.4223548124775e-310,
                0.0,
                0.0,
                1.7259532869260418e-307,
                0.0,
                3.13151306251402e-294,
            ],
            Some(2.910_383_045_673_369_7e-11),
        ),
        (
            [0.5000152587890625, 0.0, 1.0609978955e-314],
            [0.0, 0.0, 0.0, 2.070238e-317, 0.0, 1.2325910294356204e-308],
            [
                1.0,
                5.222099017e-315,
                4.450147717014403e-308,
                8.079e-320,
                8.087e-320,
                3.4332275390625e-5,
            ],
            None,
        ),
    ];
    for (r, q1, q2, expected) in pairs {
        for method in [contact_function, contact_function_fast] {
            let a = method(&r, &q1, &q2).unwrap();
            let b = method(&r.map(|x| -x), &q2, &q1).unwrap();
            assert_eq!(a.mu2, b.mu2, "{a:?} {b:?}");
            assert_eq!(a.lambda, 1.0 - b.lambda, "{a:?} {b:?}");
            if let Some(mu2) = expected {
                assert!((a.mu2 - mu2).abs() <= 4.0 * f64::EPSILON * mu2, "{a:?}");
            }
        }
    }
}

/// fuzz target contact_bits: λ at the wrong end. A disc 1e-110 thick (its form's third
/// eigenvalue 1.25e-221, below the rank decision's threshold) and a needle of the same
/// 1e-110 size answered the right μ² in both orders, but λ = 0 in both: the disc's
/// thickness, kept in one coefficient while the determinant was set to 0, made F's
/// limit at λ = 0 look like its maximum. `tools/contact_exact.py`: μ² =
/// 46.73004820241379, λ* = 1 and 0 by order.
#[test]
fn lambda_is_at_the_needle_end_for_a_disc_thinner_than_its_rank_threshold() {
    let r = [
        0.002588147670030594,
        0.000683593749999994,
        3.075052062085698e-304,
    ];
    let tiny = 1.2497855238365512e-221;
    let q1 = [1.0, 0.0, 0.0, 1e-8, 1.2497855238365468e-221, tiny];
    let q2 = [tiny; 6];
    for method in [contact_function, contact_function_fast] {
        let a = method(&r, &q1, &q2).unwrap();
        let b = method(&r.map(|x| -x), &q2, &q1).unwrap();
        assert_eq!(a.mu2, b.mu2, "{a:?} {b:?}");
        let mu2 = 46.730_048_202_413_79;
        assert!((a.mu2 - mu2).abs() <= 4.0 * f64::EPSILON * mu2, "{a:?}");
        assert_eq!((a.lambda, b.lambda), (1.0, 0.0), "{a:?} {b:?}");
    }
}

/// fuzz target contact_bits_2d (open defect 1 of the second round: 140 of 300 000
/// extreme random pairs). Pairs of ellipses degenerate to segments, sizes up to 1e150
/// apart, answered a μ² that depended on their order, all as a limit at an end
/// (`Stop::Exact`). The first has a segment of length 0.026 tilted by 3.5e-122 (its
/// off-diagonal entry) against one 7e-155 long across it: the limit at the first
/// form's end, (offset of r across the long segment)² / `q2_xx` = 1.1e-163, is 1e62
/// times the other end's, but in one order the first cross term of that end's rise
/// test (0 in real arithmetic, −1.8e-15 against products of 8.9 in doubles) said that
/// F did not rise from the small limit, and the small end was taken. The rise test
/// now leaves a cross term at rounding level to the next order
/// (`perram_wertheim::ends`, `CROSS_TERM_TOL`) and scales its products out of the
/// underflow; an end is taken only if F does not rise from it and the other end, when
/// neither does, has the smaller limit.
#[test]
fn swapping_two_segments_whose_rise_test_is_at_rounding_level_keeps_mu2() {
    use grainpack::contact::contact_function_2d;
    let pairs = [
        (
            [1.168163775723566e-307, 3.4262214803761265e-115],
            [
                6.8990327155894e-310,
                5.909106320800166e-126,
                0.00016787461936473998,
            ],
            [1.303754213969547e-309, 0.0, 0.0],
        ),
        (
            [3.645561014053373e-304, 5.222099096e-315],
            [0.0, 7.987e-320, 6.71677982612e-312],
            [2743.001953125, 0.0, 6.02816564297415e-310],
        ),
        (
            [3.4732829715905e-310, -7.105433710363454e-15],
            [8.087e-320, 1.186e-321, 7.291109417819143e-304],
            [6.27e-322, 0.0, 0.0],
        ),
    ];
    for (r, q1, q2) in pairs {
        let a = contact_function_2d(&r, &q1, &q2).unwrap();
        let b = contact_function_2d(&r.map(|x| -x), &q2, &q1).unwrap();
        assert_eq!(a.mu2, b.mu2, "{r:?} {q1:?} {q2:?}: {a:?} {b:?}");
    }
    // The first pair in closed form: a few roundings of a quotient and a product, so
    // 1e-14 relative covers them.
    let (r, q1, q2) = pairs[0];
    let offset = r[0] - r[1] * (q1[1] / q1[2]);
    let mu2 = (offset / q2[0].sqrt()).powi(2);
    let a = contact_function_2d(&r, &q1, &q2).unwrap();
    assert!((a.mu2 - mu2).abs() <= 1e-14 * mu2, "{a:?} against {mu2:e}");
}

/// fuzz target contact_bits_2d: two segments (along (1, 1) and along x, both of
/// `q_xx = a`) and `r` along y with |r| = R: `f(λ) = R²/a` for every λ (to 1e-98), so
/// F did not rise from either end, the first end tested was taken in both orders,
/// and λ was 0 both ways instead of mirrored. Now a flat F answers λ = ½ (in the
/// scaled variable), the same pair in either order.
#[test]
fn lambda_mirrors_for_two_segments_whose_contact_function_is_flat() {
    use grainpack::contact::contact_function_2d;
    let a = 2.5194700025415145e93;
    let r = [3.091245889688676e-5, 2.58030839329865e93];
    let q1 = [a, a, a];
    let q2 = [a, 4.3000643038131325e-307, 7.630052052720683e-305];
    let one = contact_function_2d(&r, &q1, &q2).unwrap();
    let other = contact_function_2d(&r.map(|x| -x), &q2, &q1).unwrap();
    // R²/a, two roundings.
    let mu2 = r[1] / a * r[1];
    assert!((one.mu2 - mu2).abs() <= 4.0 * f64::EPSILON * mu2, "{one:?}");
    assert_eq!(one.mu2, other.mu2);
    assert_eq!(one.lambda, 1.0 - other.lambda, "{one:?} {other:?}");
}

/// fuzz target contact_bits_2d (open defect 5 of the third round, now defect 12): a
/// nearly rank-1 form of size 7.5e20 against a segment of 1.9e-39 answered μ² =
/// 7.477080264558488e20 in one order and 7.477080264524815e20 in the other (4.5e-12
/// apart; `tools/contact_exact.py` gives the first, with λ* = 1 − 1.4e-30). `F` is flat
/// to 4.5e-12 across the middle, so ψ(½), whose sign chose the half of [0, 1] to search,
/// was rounding (−9.8e-18 against terms of order 1), and the swapped order searched the
/// half without the maximum. An unresolved ψ(½) now has both halves searched. The
/// second pair (forms of 1e-304 and 5e-322) was 1.9e-14 apart the same way.
#[test]
fn swapping_a_pair_whose_contact_function_is_flat_across_the_middle_keeps_mu2() {
    let pairs = [
        (
            [7.477080264572239e20, 7.477080264534209e20, 0.0],
            [
                7.477080264586554e20,
                7.477080264543599e20,
                0.0,
                7.477080264543605e20,
                0.0,
                7.47708026456508e20,
            ],
            [
                1.878900217323738e-39,
                2.787848324310933e-309,
                0.0,
                0.0,
                0.0,
                9.39450108661869e-40,
            ],
            7.477080264558488e20,
        ),
        (
            [3.5310009961663e-310, -7.24536890462657e-171, 0.0],
            [
                4.450419332515262e-308,
                1.35675105885e-312,
                0.0,
                6.664569048004567e-304,
                0.0,
                3.332507044968909e-304,
            ],
            [5.34e-322, 0.0, 0.0, 0.0, 0.0, 2.67e-322],
            7.876783957973734e-38,
        ),
    ];
    for (r, q1, q2, exact) in pairs {
        let one = contact_function(&r, &q1, &q2).unwrap();
        let other = contact_function(&r.map(|x: f64| -x), &q2, &q1).unwrap();
        for c in [one, other] {
            assert!((c.mu2 - exact).abs() <= 4.0 * f64::EPSILON * exact, "{c:?}");
        }
    }
}

/// fuzz target contact_bits_2d (fifth round, a regression of defect 12's fix before it
/// was committed): `F` flat to an ulp around λ = ½; with both halves searched, one order
/// found the two maxima equal and answered λ = ½, the other found them an ulp apart and
/// took the larger one's λ, 0.5000000020. Maxima within `F_TIE_TOL` are now a tie.
#[test]
fn lambda_mirrors_where_the_two_halves_maxima_are_an_ulp_apart() {
    let r = [8.814422105064095e-280, 2.0602110840840086e24, 0.0];
    let q1 = [
        1.1931846177412974e23,
        3.2111828443926037e-308,
        0.0,
        2.104900968400905e35,
        0.0,
        1.052450484201049e35,
    ];
    let q2 = [
        1.920405099359672e23,
        3.1985436717098735e-308,
        0.0,
        2.1049009684009023e35,
        0.0,
        1.0524504842014113e35,
    ];
    let one = contact_function(&r, &q1, &q2).unwrap();
    let other = contact_function(&r.map(|x: f64| -x), &q2, &q1).unwrap();
    assert_eq!(one.mu2, other.mu2);
    assert!(
        (one.lambda - (1.0 - other.lambda)).abs() <= 1e-12,
        "{one:?} {other:?}"
    );
}

/// fuzz target contact_bits: a needle of zero thickness (`q` of equal entries, along
/// `(1, 1, 1)`) with `r12` along it, or 12 ulps off it, against a form 1e-300 to 1e-35
/// of its size. The mixed coefficient of `f` is 0 in real arithmetic (or 7e-35 against
/// terms of order 10, below what double-double resolves), and came out as rounding:
/// 3.9e-31 in one order, 0 in the other. Which order `N` and `C` vanish to at an end
/// followed from it, so the pair answered μ² = 3.79e146 in one order and an overflow in
/// the other, or 2.3e179 and 1.5e-47; the third pair 1.04e-42 (`contact_exact`:
/// 1.0410273767909543e-42) and 7.3e-33. A coefficient within `64 ε²` of its terms'
/// magnitudes is now 0 in either order (`exact::COEFFICIENT_RESOLUTION`).
#[test]
fn swapping_a_needle_with_r12_along_it_keeps_mu2_where_a_coefficient_is_rounding() {
    let needle = |c: f64| [c; 6];
    let pairs = [
        (
            [3.7921287488073793e146; 3],
            needle(3.7921287488073793e146),
            [
                1.2203139442750433e-307,
                6.2e-322,
                6.79038682573856e-310,
                6.89913715756663e-310,
                1.390671161566996e-309,
                1.1119936983311136e-308,
            ],
            3.7921287488073793e146,
        ),
        (
            [
                1.5197906138816818e-47,
                1.519790613881695e-47,
                1.519790613881695e-47,
            ],
            needle(1.519790613881695e-47),
            [
                3.5743996522989874e-299,
                2.0235713373e-314,
                3.4223564433723e-310,
                2.4236617003790986e-305,
                6.03e-322,
                0.0,
            ],
            1.519790613881695e-47,
        ),
        (
            [1.0410273767909543e-42; 3],
            needle(1.0410273767909543e-42),
            [
                1.3980433222694975e-76,
                1.398043286095289e-76,
                1.398043286095289e-76,
                1.398043286095289e-76,
                1.398043286095289e-76,
                1.2003205303379468e-71,
            ],
            1.0410273767909543e-42,
        ),
    ];
    for (r, q1, q2, mu2) in pairs {
        let a = contact_function(&r, &q1, &q2).unwrap();
        let b = contact_function(&r.map(|x| -x), &q2, &q1).unwrap();
        assert_eq!((a.mu2, b.mu2), (mu2, mu2), "{a:?} {b:?}");
    }
}
