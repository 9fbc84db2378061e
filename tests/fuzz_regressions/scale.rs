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

use grainpack::contact::{
    contact_function, contact_function_2d, embed_pair, lambda_bound, Contact, Stop, Sym2, Sym3,
    Vec2, Vec3,
};

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
fn check(
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

/// fuzz target `contact_bits_2d` (the sixth round's `crash-63e28000`, `-77551983`,
/// `-5caa08d4`, `-e382b4e3`; the seventh's `-0eefda74`, `-3c59770f`, `-633102ea`,
/// `-ba70f96c`, `-c0d91f6e`, `-d98de106`, `-fb23eefe`, `-ff9fd1d1`): needles of `κ(Q)`
/// 1e6 to 1.2e8 against round forms or forms up to 1e29 smaller, `r12` of 1e-63 to
/// 6e61; μ² of 1e-171 to 1e131. On 5 of them λ of the two orders was beyond
/// `lambda_bound` (up to 4.4e-9 apart).
#[test]
fn swapping_or_scaling_an_ellipse_keeps_mu2_and_mirrors_lambda_where_mu2_is_far_from_unit_scale() {
    let pairs: [(Vec2, Sym2, Sym2, i32, f64, f64); 12] = [
        // crash-0eefda74: λ* = 0.028311907750236695
        (
            [-1.2554960704000993e58, 1.7246359519392163e-307],
            [
                1.1367323098432628e-13,
                7.40503884775626e-304,
                7.549516564555932e-15,
            ],
            [
                0.00047679240037456003,
                0.0004767922684978005,
                0.0004767922794116398,
            ],
            7,
            1.0422811000578498e126,
            0.028311907750236693,
        ),
        // crash-3c59770f: λ* = 4.0976604947346364e-5
        (
            [8.903436910786258e-298, 5.412334063750991e-59],
            [156842099844.52127, 134255653698.25882, 156842099778.51764],
            [
                5.142915353319631e25,
                5.142912663207646e25,
                5.142912663207646e25,
            ],
            -3,
            1.0888384894409282e-136,
            4.097660494734636e-05,
        ),
        // crash-5caa08d4: λ* = 0.99997322996965663
        (
            [4.862023931356511e-63, 7.535917170267851e-62],
            [
                0.00047679244016762823,
                0.000476792279383343,
                0.00047679226486157736,
            ],
            [
                1.0387866634843204e-13,
                1.0387856152602562e-13,
                1.0387856152602562e-13,
            ],
            5,
            3.397715187092501e-113,
            0.9999732299696567,
        ),
        // crash-633102ea: λ* = 0.99980677067666647
        (
            [8.903436910786258e-298, -8.876955682420106e-62],
            [156842099844.51764, 156842086014.51764, 156842099844.51755],
            [
                0.0005572136237948759,
                8.820793539666975e-159,
                0.0004759428840057384,
            ],
            7,
            2.8477908817739843e-127,
            0.9998067706766665,
        ),
        // crash-63e28000: λ* = 2.8373413205438738e-7
        (
            [1.03449915e-316, -2.272979211195581e-59],
            [
                0.00047303730370723204,
                0.0004768073558780623,
                2096959.0048713235,
            ],
            [
                5.142915267961852e25,
                5.142912663207646e25,
                5.142912663207646e25,
            ],
            -3,
            1.983463225443901e-137,
            2.8373413205438737e-07,
        ),
        // crash-77551983: λ* = 0.99999991807358308
        (
            [8.84165e-317, -1.2260546954373286e-59],
            [
                3.5525940828785556e59,
                3.552593421376493e59,
                3.5525934213723826e59,
            ],
            [
                1.1278059737199007e45,
                1.1278055297264741e45,
                1.1278055297264741e45,
            ],
            1,
            2.272433565549061e-171,
            0.9999999180735831,
        ),
        // crash-ba70f96c: λ* = 0.077819064667382494
        (
            [1.4437875898689665e-58, 1.7246368007374311e-307],
            [
                2.2333876346531346e-23,
                7.749036984169277e-304,
                1.1015098365047232e-13,
            ],
            [
                0.00047679227931939414,
                0.00047679227163132174,
                0.0004767922794117647,
            ],
            7,
            1.1460148859169536e-105,
            0.07781906466738249,
        ),
        // crash-c0d91f6e: λ* = 0.99935726998945096
        (
            [8.949537231750435e-118, -2.042613250027363e-60],
            [156842099844.51764, 156842082948.4864, 156842100222.69733],
            [
                0.01428079052883036,
                0.00014683895142296626,
                0.00014684328891556028,
            ],
            -2,
            1.219455082290267e-124,
            0.999357269989451,
        ),
        // crash-d98de106: λ* = 0.99987744845428482
        (
            [8.903436910786258e-298, 5.412334063750991e-59],
            [156842099845.40408, 156842082948.51764, 156842099838.51764],
            [
                0.00047697365783697457,
                8.815133851876533e-280,
                3.059205482713878e-05,
            ],
            -8,
            8.667913863801361e-122,
            0.9998774484542848,
        ),
        // crash-e382b4e3: λ* = 0.0012282181806623809
        (
            [5.866889444585011e61, 4.977943665454561e-57],
            [
                0.0004768225473954258,
                0.0004767922721358071,
                0.00047682109220347277,
            ],
            [2261634.548882128, 2261634.5098039214, 2261634.5098039214],
            -7,
            8.786455425660855e124,
            0.001228218180662381,
        ),
        // crash-fb23eefe: λ* = 0.95595800546542498
        (
            [-2.786057479555272e-11, -8.396528659002198e58],
            [156842100070.52576, 156842091141.48236, 156842099888.25983],
            [
                37.51764809305725,
                3.8160374566712e-310,
                3.075597112544973e-05,
            ],
            7,
            3.645000557791563e113,
            0.955958005465425,
        ),
        // crash-ff9fd1d1: λ* = 0.1315766215599405
        (
            [-1.964789782157332e59, 3.241747631888046e-05],
            [
                1.1366249738466374e-13,
                1.779848585315472e-307,
                1.1090081765205036e-13,
            ],
            [
                0.00047679227965690194,
                0.0004767922710051664,
                0.0004767922721358071,
            ],
            7,
            2.976122716056663e129,
            0.1315766215599405,
        ),
    ];
    for (r, q1, q2, k, exact, lambda) in pairs {
        let m = r.map(|x| -x);
        let answer = |t: f64, swapped: bool| {
            let scaled = r.map(|x| x * t);
            match swapped {
                false => contact_function_2d(&scaled, &q1, &q2).unwrap(),
                true => contact_function_2d(&m, &q2, &q1).unwrap(),
            }
        };
        let bound = |swapped: bool, l: f64| {
            let (r3, a, b) = match swapped {
                false => embed_pair(&r, &q1, &q2),
                true => embed_pair(&m, &q2, &q1),
            };
            lambda_bound(&r3, &a, &b, l).unwrap()
        };
        check(&format!("{r:?}"), answer, bound, k, exact, lambda);
    }
}
