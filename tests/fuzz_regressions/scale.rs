//! Contact defects of the common path where μ² is far from unit scale: open defect 18
//! of the sixth and seventh rounds (`docs/reliability.md`), fixed in the eighth.
//!
//! The corrector's checks of `g` (module `refine::gain`) compared products of degree up
//! to 5 in μ²'s scale, which underflowed to 0 ≤ 0 (or overflowed) where the pair's μ² is
//! far from 1: `r12` of 1e-59 or 1e59 with forms of order 1e-13 to 1e25, which the
//! common path takes as they are (every `|r12_i|` and diagonal entry within `2^±200`).
//! A `g` off by 0.4 % then passed as trusted, and its gain moved μ² by up to 1.7e-13
//! (λ by up to 4.7e-9), in one order of the pair and not the other, or at one scale of
//! `r12` and not another. The checks now work in units of `f` (`plain_g_checks`).

use grainpack::contact::{contact_function, lambda_bound, Contact, Stop, Sym3, Vec3};

/// 16 ε, `IDENTITY_TOL` of `tests/contact_properties.rs` and of the fuzz targets: the
/// bound on μ²'s symmetries (swap, `r12 × 2^k`) that these inputs broke.
const IDENTITY_TOL: f64 = 16.0 * f64::EPSILON;

/// Measured against `tools/contact_exact.py` after the fix: within 0.84 ε on every input
/// in both orders, and λ within 1e-13 of λ*; 4 ε is the common path's few ulps.
const EXACT_TOL: f64 = 4.0 * f64::EPSILON;

fn settled(c: &Contact) -> bool {
    matches!(c.stop, Stop::Converged | Stop::Exact)
}

/// The pair in both orders and with `r12 × 2^k`: μ² within [`EXACT_TOL`] of `exact`
/// in both orders, the three within [`IDENTITY_TOL`] of each other (the scaled one times
/// `4^-k`), and λ of both orders within `lambda_bound` of `lambda`.
pub(super) fn check(
    name: &str,
    answer: impl Fn(f64, bool) -> Contact,
    bound: impl Fn(bool, f64) -> f64,
    k: i32,
    exact: f64,
    lambda: f64,
) {
    let (a, b) = (answer(1.0, false), answer(1.0, true));
    let t = 2f64.powi(k);
    let c = answer(t, false);
    assert!(
        settled(&a) && settled(&b) && settled(&c),
        "{name}: {a:?} {b:?} {c:?}"
    );
    for (x, what) in [(a.mu2, "as given"), (b.mu2, "swapped")] {
        assert!(
            (x - exact).abs() <= EXACT_TOL * exact,
            "{name} {what}: {x:e} against {exact:e}"
        );
    }
    assert!(
        (a.mu2 - b.mu2).abs() <= IDENTITY_TOL * a.mu2,
        "{name}: {a:?} {b:?}"
    );
    let scaled = c.mu2 / (t * t);
    assert!(
        (scaled - a.mu2).abs() <= IDENTITY_TOL * a.mu2,
        "{name}: 2^{k}: {a:?} {c:?}"
    );
    let (ba, bb) = (bound(false, a.lambda), bound(true, b.lambda));
    assert!(
        (a.lambda - lambda).abs() <= ba,
        "{name}: {a:?}, λ* {lambda}, bound {ba:e}"
    );
    assert!(
        (b.lambda - (1.0 - lambda)).abs() <= bb,
        "{name}: {b:?}, λ* {lambda}, bound {bb:e}"
    );
}

/// fuzz target `contact_bits` (`crash-2965c544`, `-2ca1479b`, `-84c8707d`, `-8c041384`):
/// needles of `κ(Q)` 5e6 to 5e7 against forms up to 1e20 smaller; μ² of 1e-110 to 1e131.
/// Exact μ² and λ* from `tools/contact_exact.py`.
#[test]
fn swapping_or_scaling_a_needle_keeps_mu2_where_mu2_is_far_from_unit_scale() {
    let pairs: [(Vec3, Sym3, Sym3, i32, f64, f64); 4] = [
        // crash-2965c544: λ* = 0.080034228006787115
        (
            [
                6.632053699089827e-236,
                3.5525934213678002e59,
                3.1659829430095677e61,
            ],
            [
                2.9132236761663773e-05,
                5.41108926696e-312,
                1.265e-321,
                2.3283419642175885e-10,
                7.063276356055918e-304,
                1.7053025658242402e-12,
            ],
            [
                4.656614988355831e-10,
                5.468341514667297e-304,
                5.007930789753e-312,
                1.0,
                0.5,
                0.2500000079162419,
            ],
            -8,
            1.0596304342054768e131,
            0.08003422800678711,
        ),
        // crash-2ca1479b: λ* = 0.99999990284221725
        (
            [
                7.291122044702048e-304,
                -8.036283298650928e59,
                7.291122019556398e-304,
            ],
            [
                0.0003999173641204834,
                6.397087343208204e-308,
                7.98125056978806e-310,
                1.0000000000291038,
                0.5,
                0.2500002331798896,
            ],
            [
                2.252526342575774e-23,
                2.1698082811856563e-23,
                2.252526342575774e-23,
                8.804893213788078e-21,
                2.2674515922314473e-23,
                2.2651279222201366e-23,
            ],
            -8,
            6.923826272984243e125,
            0.9999999028422173,
        ),
        // crash-84c8707d: λ* = 0.94001208050228498
        (
            [
                7.291122044702048e-304,
                7.996581876159705e-59,
                3.281004908800379e-303,
            ],
            [
                0.00039672851562500005,
                5.532909939407137e-222,
                0.0,
                1.0000001192092896,
                0.5000000001164153,
                0.25000000057480065,
            ],
            [
                3.051757823158141e-05,
                5.565e-320,
                7.283052908189356e-304,
                4.656616758858119e-10,
                1.4916681476076414e-154,
                6.82121026331578e-12,
            ],
            -8,
            4.668061556850729e-110,
            0.940012080502285,
        ),
        // crash-8c041384: λ* = 0.99999592431009755
        (
            [0.0, 2.1422187447113273e-53, 6.953355807835e-310],
            [
                3.8813397022294015e-10,
                3.3083584e-317,
                5.010811313746e-312,
                1.000000312924385,
                0.5000000018044375,
                0.2500000008398757,
            ],
            [
                5.52972771901695e-10,
                3.645561009778199e-304,
                5.2227466e-315,
                1.5306383611530364e-18,
                6.297939090173151e-19,
                1.5306383611560193e-18,
            ],
            4,
            1.4848160889535272e-99,
            0.9999959243100975,
        ),
    ];
    for (r, q1, q2, k, exact, lambda) in pairs {
        let m = r.map(|x| -x);
        let answer = |t: f64, swapped: bool| {
            let scaled = r.map(|x| x * t);
            match swapped {
                false => contact_function(&scaled, &q1, &q2).unwrap(),
                true => contact_function(&m, &q2, &q1).unwrap(),
            }
        };
        let bound = |swapped: bool, l: f64| match swapped {
            false => lambda_bound(&r, &q1, &q2, l).unwrap(),
            true => lambda_bound(&m, &q2, &q1, l).unwrap(),
        };
        check(&format!("{r:?}"), answer, bound, k, exact, lambda);
    }
}
