use super::*;
use crate::laws::special::simpson;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

const KANAPY_SIZE: Distribution = Distribution::LogNormal {
    sigma: 0.8,
    scale: 14.0,
    loc: 0.0,
    min: 6.0,
    max: 16.0,
};

/// The density of the truncated law, written out independently of the code under
/// test.
fn pdf(d: &Distribution, x: f64) -> f64 {
    let p = d.accepted_mass();
    match *d {
        Distribution::Uniform { min, max } => 1.0 / (max - min),
        Distribution::Normal { mean, std, .. } => normal_pdf((x - mean) / std) / (std * p),
        Distribution::LogNormal {
            sigma, scale, loc, ..
        } => normal_pdf(((x - loc) / scale).ln() / sigma) / (sigma * (x - loc) * p),
        _ => unreachable!(),
    }
}

/// Moments from the closed forms against Simpson quadrature of `xᵏ f(x)`. Both rest
/// on the erfc fit (fractional error 1.2e-7) through the accepted mass, and Simpson
/// on 4000 intervals is exact to ~1e-12 for these smooth densities, so 1e-6 relative
/// is the tolerance.
#[test]
fn closed_form_moments_agree_with_quadrature_of_the_density() {
    for d in sample_laws() {
        let (lo, hi) = d.support();
        let total = simpson(|x| pdf(&d, x), lo, hi, 4000);
        assert!(
            (total - 1.0).abs() < 1e-6,
            "{d:?}: density integrates to {total}"
        );
        for k in 1..=3 {
            let want = simpson(|x| x.powi(k as i32) * pdf(&d, x), lo, hi, 4000);
            let got = d.moment(k);
            assert!(
                ((got - want) / want).abs() < 1e-6,
                "{d:?} k={k}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn truncated_cdf_runs_from_zero_at_min_to_one_at_max() {
    for d in [
        KANAPY_SIZE,
        Distribution::Normal {
            mean: 1.0,
            std: 1.0,
            min: 0.5,
            max: 3.0,
        },
    ] {
        let (lo, hi) = d.support();
        assert!(d.cdf(lo).abs() < 1e-12);
        assert_eq!(d.cdf(hi), 1.0);
        assert!(d.cdf(0.5 * (lo + hi)) > 0.0 && d.cdf(0.5 * (lo + hi)) < 1.0);
    }
}

#[test]
fn samples_stay_inside_the_cutoffs() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..2000 {
        let x = KANAPY_SIZE.sample(&mut rng).unwrap();
        assert!((6.0..=16.0).contains(&x), "{x}");
    }
}

#[test]
fn check_names_the_offending_parameter() {
    let bad = |d: Distribution| d.check().unwrap_err().param;
    assert_eq!(
        bad(Distribution::LogNormal {
            sigma: -0.8,
            scale: 14.0,
            loc: 0.0,
            min: 6.0,
            max: 16.0
        }),
        "sigma"
    );
    assert_eq!(bad(Distribution::Uniform { min: 5.0, max: 2.0 }), "max");
    assert_eq!(bad(Distribution::Constant { value: f64::NAN }), "value");
    // Cutoffs 9 standard deviations out keep ~1e-19 of the mass.
    assert_eq!(
        bad(Distribution::Normal {
            mean: 0.0,
            std: 1.0,
            min: 9.0,
            max: 10.0
        }),
        "min"
    );
    assert!(KANAPY_SIZE.check().is_ok());
}
