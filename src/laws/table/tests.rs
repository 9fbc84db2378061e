use super::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The KS distance of `sample` from `cdf`, written out here (not `laws::stats`, which
/// depends on this module through `Distribution`).
fn ks(mut sample: Vec<f64>, cdf: impl Fn(f64) -> f64) -> f64 {
    sample.sort_by(f64::total_cmp);
    let n = sample.len() as f64;
    sample
        .iter()
        .enumerate()
        .map(|(i, &x)| {
            let f = cdf(x);
            (f - i as f64 / n).abs().max(((i + 1) as f64 / n - f).abs())
        })
        .fold(0.0, f64::max)
}

/// Draws as `Distribution::Table` makes them: the quantile of one uniform.
fn draw(law: &TableLaw, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..N).map(|_| law.quantile(rng.random::<f64>())).collect()
}

/// Draws for the KS tests: a correct sampler's KS distance exceeds 1.95/√n ≈ 0.0138
/// with probability 0.001 (Kolmogorov's limit law), so a fixed seed fails only on a
/// real disagreement between the sampler and the CDF.
const N: usize = 20_000;

/// A Fuller curve `√(d/16)` on [2, 16] at sieve-like points.
fn fuller(basis: TableBasis, interpolation: TableInterpolation) -> TableLaw {
    let x = [2.0, 4.0, 8.0, 11.2, 16.0];
    let f: Vec<f64> = x.iter().map(|d: &f64| (d / 16.0).sqrt()).collect();
    TableLaw::new(&x, &f, basis, interpolation).unwrap()
}

fn all_tables() -> Vec<TableLaw> {
    let mut v = Vec::new();
    for b in [TableBasis::Number, TableBasis::Volume, TableBasis::Area] {
        for i in [TableInterpolation::Linear, TableInterpolation::Log] {
            v.push(fuller(b, i));
        }
    }
    v
}

#[test]
fn draws_follow_the_number_cdf() {
    for law in all_tables() {
        let ks = ks(draw(&law, 21), |x| law.cdf(x));
        assert!(ks < 1.95 / (N as f64).sqrt(), "{law:?}: {ks}");
    }
}

/// A sieve curve is a volume fraction passing: the volume-weighted CDF of the
/// number law must give back the table's own curve at every point and between; an
/// area table (2D), the area-weighted one (`d²`).
/// Exact formulas on both sides: 1e-12 allows the roundings of a few dozen powers.
#[test]
fn volume_and_area_tables_give_back_the_fraction_passing() {
    for law in all_tables()
        .into_iter()
        .filter(|l| l.basis != TableBasis::Number)
    {
        let w = law.basis.weight_power();
        let total = law.moment(w as u32);
        let (lo, _) = law.support();
        for x in [2.0, 3.0, 4.0, 6.5, 8.0, 10.0, 11.2, 15.0, 16.0] {
            // ∫_lo^x t³ n(t) dt by the exact per-interval powers.
            let p = law.p();
            let mut acc = 0.0;
            for i in 0..law.x.len() - 1 {
                let (a, b) = (law.x[i], law.x[i + 1].min(x));
                if b <= a {
                    break;
                }
                let m = law.number_cdf[i + 1] - law.number_cdf[i];
                acc += m * power_integral(p + w, a, b) / power_integral(p, law.x[i], law.x[i + 1]);
            }
            let passing = acc / total;
            assert!(
                (passing - law.given_cdf(x)).abs() < 1e-12,
                "x = {x}: {passing} vs {} (from {lo})",
                law.given_cdf(x)
            );
        }
    }
}

/// Moments against the sample's: with n = 20 000, five standard errors of the mean.
#[test]
fn moments_match_the_draws() {
    for law in all_tables() {
        let s = draw(&law, 22);
        let mean = s.iter().sum::<f64>() / N as f64;
        let (m1, m2) = (law.moment(1), law.moment(2));
        let se = (m2 - m1 * m1).sqrt() / (N as f64).sqrt();
        assert!((mean - m1).abs() < 5.0 * se, "{mean} {m1}");
    }
}

#[test]
fn quantile_inverts_the_cdf_and_pdf_is_its_derivative() {
    for law in all_tables() {
        for u in [0.0, 0.1, 0.37, 0.5, 0.9, 1.0] {
            // The quantile's power and root: a few ulps of x ≤ 16.
            assert!((law.cdf(law.quantile(u)) - u).abs() < 1e-12, "{u}");
        }
        // Central difference with h = 1e-5: error O(h²·f‴) + rounding O(ε/h) ≲ 1e-9.
        let h = 1e-5;
        for x in [2.5, 5.0, 9.0, 13.0] {
            let num = (law.cdf(x + h) - law.cdf(x - h)) / (2.0 * h);
            assert!((num - law.pdf(x)).abs() < 1e-8, "{x}: {num} {}", law.pdf(x));
        }
    }
}

#[test]
fn bad_tables_name_the_entry() {
    let t = TableInterpolation::Linear;
    let err = TableLaw::new(&[1.0, 2.0, 3.0], &[0.0, 0.6, 0.5], TableBasis::Number, t).unwrap_err();
    assert_eq!((err.key, err.index), ("cdf", Some(2)));
    let err = TableLaw::new(&[1.0, 1.0], &[0.0, 1.0], TableBasis::Number, t).unwrap_err();
    assert_eq!((err.key, err.index), ("x", Some(1)));
    let err = TableLaw::new(&[1.0, 2.0], &[0.5, 0.5], TableBasis::Volume, t).unwrap_err();
    assert_eq!(err.key, "cdf");
}

#[test]
fn empirical_law_is_the_step_cdf() {
    let e = EmpiricalLaw::new(&[3.0, 1.0, 2.0, 2.0]);
    assert_eq!(e.cdf(0.5), 0.0);
    assert_eq!(e.cdf(2.0), 0.75);
    assert_eq!(e.moment(1), 2.0);
}
