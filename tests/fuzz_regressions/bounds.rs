//! Where the honest answer is a bound: λ and μ² of the robust path, each within its
//! documented bound (`contact::lambda_bound`, `contact::mu2_bound`) in both orders of
//! the pair; defects 17 and 20 of `docs/reliability.md`.

use grainpack::contact::{
    contact_function, contact_function_2d, lambda_bound, mu2_bound, Sym2, Sym3, Vec2, Vec3,
};

/// fuzz target contact_bits_2d: a needle thinner than `MIN_RELATIVE_PIVOT` (it does not
/// factor, so the robust path answers) against an ellipse, with a flat maximum: λ of the
/// two orders 1.3e-12, 5.7e-8, 1.2e-10 and 1.5e-3 apart, where `lambda_bound` was `None`
/// and only 1e-12 was allowed. It now gives the robust path's bound (5.9e-7 to 0.38),
/// and each order's λ is within it of λ* (`tools/contact_exact.py`, the last column).
#[test]
fn lambda_of_the_robust_path_is_within_its_documented_bound_in_both_orders() {
    let pairs: [(Vec2, Sym2, Sym2, f64); 4] = [
        (
            [6.183851698436469e-226, -2.220370888360308e+58],
            [
                3.5525934213782058e+59,
                3.552593421376493e+59,
                3.552593421376493e+59,
            ],
            [
                3.5525934887224885e+59,
                -3.5525932112099194e+59,
                3.5525947660658958e+59,
            ],
            0.0010455131588458502,
        ),
        (
            [1.6131943334215483e-307, 131080.1252918262],
            [2261634.50980401, 2261634.5098039214, 2261634.5098039214],
            [
                2261634.5098039214,
                0.00047679227919505875,
                3.4808654298611266e-05,
            ],
            0.047943660844176075,
        ),
        (
            [1.0000000022351743, 0.0],
            [
                1.0658661453444296e-13,
                2.6035174473080065e-188,
                1.0000000000000566,
            ],
            [1.0000000000145608, 1.0000000000143812, 1.0000002421438836],
            0.006029172551555657,
        ),
        (
            [7.041528257700769e-09, -595885180.4862745],
            [
                7.0415291131712555e-09,
                7.041529113171147e-09,
                7.041529113171147e-09,
            ],
            [
                7.041529113171147e-09,
                -7.041529113171147e-09,
                7.041529113171359e-09,
            ],
            0.3423742106427553,
        ),
    ];
    for (r, q1, q2, exact) in pairs {
        let m = r.map(|x| -x);
        let (a, b) = (
            contact_function_2d(&r, &q1, &q2).unwrap(),
            contact_function_2d(&m, &q2, &q1).unwrap(),
        );
        let embed = |r: &Vec2, q1: &Sym2, q2: &Sym2, lambda| {
            let (r, a, b) = grainpack::contact::embed_pair(r, q1, q2);
            lambda_bound(&r, &a, &b, lambda).expect("a bound on the robust path")
        };
        let (ba, bb) = (embed(&r, &q1, &q2, a.lambda), embed(&m, &q2, &q1, b.lambda));
        assert!((a.lambda - exact).abs() <= ba, "{a:?} {ba:e}");
        assert!((1.0 - b.lambda - exact).abs() <= bb, "{b:?} {bb:e}");
    }
}

/// fuzz target contact_bits: a needle of zero thickness with `r12` within 1e-12 of its
/// line, or two nearly equal needles: a coefficient of `f` cancels to 1e-23 of its
/// terms, is resolved to a few digits only, and μ² of the two orders differed by up to
/// 1.3e-8 (beyond 16 ε). Each order is within its `mu2_bound` of the other and, where
/// the forms are what the robust path takes them for, of `tools/contact_exact.py`
/// (`Some`; the last two drop a thickness below `SINGULAR_PIVOT`, where the exact μ² of
/// the doubles as given is another problem's).
#[test]
fn mu2_of_the_robust_path_is_within_its_documented_bound_where_a_coefficient_cancels() {
    let needle = |c: f64| [c; 6];
    let pairs: [(Vec3, Sym3, Sym3, Option<f64>); 6] = [
        (
            [
                3.31036971551853e-28,
                3.310369715525099e-28,
                3.310369715525099e-28,
            ],
            needle(3.310369715525099e-28),
            [
                1.4589503887937414e-307,
                6.5187710698453e-310,
                1.35675121948e-312,
                4.3304887274861445e-299,
                2.701378326042703e-305,
                1.7800590868057611e-307,
            ],
            Some(1.332447835153219e228),
        ),
        (
            [
                3.310369715518415e-28,
                3.310369715525099e-28,
                3.310369715525099e-28,
            ],
            needle(3.310369715525099e-28),
            [
                3.3037900604983914e-304,
                1.32616771162194e-309,
                2.5825e-319,
                1.002974573e-314,
                7.997e-320,
                3.189866318140662e-304,
            ],
            Some(1.3523046048614052e225),
        ),
        (
            [
                1.9305918740600452e-197,
                1.9305918745095462e-197,
                1.9305918745095462e-197,
            ],
            needle(1.9305918745095462e-197),
            [
                1.7765824092008994e-307,
                6.2e-322,
                2.652494853804e-312,
                9.844349770716241e-303,
                7.2529153e-317,
                1.73833895195875e-310,
            ],
            Some(1.136224197654894e-106),
        ),
        (
            [
                1.213625051901997e+132,
                1.2136247081528975e+132,
                1.2136247081528975e+132,
            ],
            needle(1.2136247081528975e+132),
            [
                1.2136247081552376e+132,
                1.2136247081528975e+132,
                1.2136247081528975e+132,
                1.2136247081528975e+132,
                1.2136247081528975e+132,
                1.213624718729793e+132,
            ],
            Some(3.2917821268912155e131),
        ),
        (
            [
                2.4173716651168577e+35,
                2.4173705217439246e+35,
                2.417370521746097e+35,
            ],
            [
                2.4175733458421334e+35,
                2.417370521746097e+35,
                2.417370521746097e+35,
                2.417370521746097e+35,
                2.4173705215768473e+35,
                2.417370521746097e+35,
            ],
            needle(5.5950456554376697e+141),
            None,
        ),
        (
            [
                0.000476792279410887,
                0.0004767922794117647,
                0.0004767922794117647,
            ],
            [
                0.0004767922794117647,
                0.0004767922794117647,
                0.0004767922794117647,
                0.0004767922794117647,
                0.0004767922794117647,
                0.0004767922794153174,
            ],
            [
                0.0004767922794125835,
                0.0004767922794117647,
                0.0004767922794117647,
                0.00047679227941176426,
                0.0004767922794117647,
                0.0004767922794117647,
            ],
            None,
        ),
    ];
    for (r, q1, q2, exact) in pairs {
        both_orders_within_mu2_bound(&r, &q1, &q2, exact);
    }
}

/// μ² of the pair and of its swap agree within their `mu2_bound`s (and a few ulps),
/// and each lies within its bound of `exact` (`tools/contact_exact.py`) when given.
fn both_orders_within_mu2_bound(r: &[f64; 3], q1: &[f64; 6], q2: &[f64; 6], exact: Option<f64>) {
    let ulps = 16.0 * f64::EPSILON;
    let m = r.map(|x| -x);
    let (a, b) = (
        contact_function(r, q1, q2).unwrap(),
        contact_function(&m, q2, q1).unwrap(),
    );
    let ba = mu2_bound(r, q1, q2).expect("a bound on the robust path");
    let bb = mu2_bound(&m, q2, q1).expect("a bound on the robust path");
    assert!(
        (a.mu2 - b.mu2).abs() <= (ulps + ba + bb) * a.mu2,
        "{a:?} {b:?}"
    );
    if let Some(exact) = exact {
        assert!((a.mu2 - exact).abs() <= (ulps + ba) * exact, "{a:?} {ba:e}");
        assert!((b.mu2 - exact).abs() <= (ulps + bb) * exact, "{b:?} {bb:e}");
    }
}

/// fuzz target `contact_bits` (`crash-b615f946`, open defect 18 of the seventh round):
/// two nearly equal needles along `(1, 1, 1)` of `κ(Q)` 2.7e11 and 1.6e12, beyond
/// `FORM_MAX_CONDITION`, so the robust path answers, whose coefficients cancel to 5e-8
/// of their terms: μ² of the two orders 2.9e-14 apart (3.4562907665411278e305 and
/// ...412264e305; `tools/contact_exact.py`: 3.4562907665411286e305). `mu2_bound` had
/// nothing to say about definite forms the robust path takes; it now bounds every pair
/// that path answers (here 9.3e-8).
#[test]
fn mu2_of_two_nearly_equal_needles_beyond_the_form_condition_limit_is_within_its_documented_bound()
{
    let r = [
        1.3824170279805095e306,
        1.3824172084878715e306,
        1.3824172097958654e306,
    ];
    let q1 = [
        1.3824172084878765e306,
        1.3824172084878715e306,
        1.382417208482785e306,
        1.3824172097958654e306,
        1.3824172084878765e306,
        1.3824172084878715e306,
    ];
    let q2 = [
        1.3824172084878715e306,
        1.3824172084869934e306,
        1.3824172084878715e306,
        1.3824172084878715e306,
        1.3824172084878715e306,
        1.3824172097958654e306,
    ];
    both_orders_within_mu2_bound(&r, &q1, &q2, Some(3.4562907665411286e305));
}
