//! Sample statistics against a target law: mean, standard deviation, the
//! Kolmogorov–Smirnov distance, and the tilt angle of an oriented grain.

use crate::io::scene::{rotation_column, Axis, VonMises};
use serde::Serialize;
use std::f64::consts::PI;

/// Mean and standard deviation of a law or of a sample.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Moments {
    /// Mean.
    pub mean: f64,
    /// Standard deviation (of a sample: of its empirical law, dividing by `n`).
    pub std: f64,
}

impl Moments {
    /// The mean and standard deviation of the empirical law of `sample` (two passes:
    /// the mean, then the mean squared deviation from it); `None` for an empty sample.
    ///
    /// ```
    /// use grainpack::io::report::stats::Moments;
    /// let m = Moments::of_sample(&[1.0, 3.0]).unwrap();
    /// assert_eq!((m.mean, m.std), (2.0, 1.0));
    /// ```
    pub fn of_sample(sample: &[f64]) -> Option<Self> {
        if sample.is_empty() {
            return None;
        }
        let n = sample.len() as f64;
        let mean = sample.iter().sum::<f64>() / n;
        let var = sample.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n;
        Some(Self {
            mean,
            std: var.sqrt(),
        })
    }
}

/// The Kolmogorov–Smirnov distance `D = sup_x |Fₙ(x) − F(x)|` between the empirical law
/// `Fₙ` of `sample` and a continuous CDF `F`; `None` for an empty sample.
///
/// With the sample sorted, `x₁ ≤ … ≤ xₙ`, the supremum is reached at a sample point or
/// just below one: `D = maxᵢ max(i/n − F(xᵢ), F(xᵢ) − (i−1)/n)`. Ties need no care: of
/// equal values, the last gives the largest `i/n` and the first the smallest `(i−1)/n`.
///
/// ```
/// use grainpack::io::report::stats::ks_distance;
/// // Uniform on [0, 1]: the worst gap is 1 − F(0.7) = 0.3, just below 1 at x = 0.7.
/// let d = ks_distance(&[0.4, 0.1, 0.7], |x| x.clamp(0.0, 1.0)).unwrap();
/// assert!((d - 0.3).abs() < 1e-15);
/// ```
pub fn ks_distance(sample: &[f64], cdf: impl Fn(f64) -> f64) -> Option<f64> {
    if sample.is_empty() {
        return None;
    }
    let mut sorted = sample.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len() as f64;
    Some(
        sorted
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let f = cdf(x);
                ((i + 1) as f64 / n - f).max(f - i as f64 / n)
            })
            .fold(0.0, f64::max),
    )
}

/// The Kolmogorov–Smirnov distance between the empirical law of `sample` and the point
/// mass at `value` (the law of a constant): the larger of the shares of the sample
/// below and above `value`. Values within `rel_tol · |value|` of it count as equal to
/// it, since a quantity recomputed from packed semi-axes carries rounding.
/// `None` for an empty sample.
///
/// ```
/// use grainpack::io::report::stats::ks_distance_to_value;
/// let d = ks_distance_to_value(&[3.0, 3.0 + 1e-15, 2.0, 3.0], 3.0, 1e-12).unwrap();
/// assert_eq!(d, 0.25); // one value in four below 3, none above
/// ```
pub fn ks_distance_to_value(sample: &[f64], value: f64, rel_tol: f64) -> Option<f64> {
    if sample.is_empty() {
        return None;
    }
    let tol = rel_tol * value.abs();
    let below = sample.iter().filter(|&&x| x < value - tol).count();
    let above = sample.iter().filter(|&&x| x > value + tol).count();
    Some(below.max(above) as f64 / sample.len() as f64)
}

/// The equivalent-sphere diameter `2 (a1 a2 a3)^{1/3}` of an ellipsoid with these
/// semi-axes: the diameter of the sphere of the same volume.
///
/// ```
/// use grainpack::io::report::stats::equivalent_diameter;
/// assert!((equivalent_diameter([4.0, 2.0, 1.0]) - 4.0).abs() < 1e-15);
/// ```
pub fn equivalent_diameter(semi_axes: [f64; 3]) -> f64 {
    2.0 * semi_axes.iter().product::<f64>().cbrt()
}

/// The aspect ratio `a1/a2` of a packed spheroid: its first semi-axis (the axis of
/// revolution) over its second (above 1 prolate, below 1 oblate).
///
/// ```
/// use grainpack::io::report::stats::aspect_ratio;
/// assert_eq!(aspect_ratio([3.0, 1.5, 1.5]), 2.0);
/// ```
pub fn aspect_ratio(semi_axes: [f64; 3]) -> f64 {
    semi_axes[0] / semi_axes[1]
}

/// The tilt angle `θ` (radians) of a grain oriented by the unit quaternion `q`, for a
/// tilt about `axis`: the angle of its first axis `e` (column 0 of the rotation) in the
/// plane normal to `axis`, from the next coordinate axis `i` in cyclic order toward the
/// one after, `j`: `θ = atan2(e_j, e_i)`. This inverts the scene's tilt orientation
/// (for `axis = z`, `e = (cos θ, sin θ, 0)`).
///
/// The angle is returned in the law's window `[mean − π, mean + π]`, where the law's
/// angles are drawn, by adding the multiple of 2π that brings it nearest the mean.
///
/// ```
/// use grainpack::io::report::stats::tilt_angle;
/// use grainpack::io::scene::{Axis, VonMises};
/// let half = 0.3f64; // a rotation by 0.6 rad about z
/// let q = [half.cos(), 0.0, 0.0, half.sin()];
/// let theta = tilt_angle(q, Axis::Z, &VonMises::new(0.0, 1.0));
/// assert!((theta - 0.6).abs() < 1e-15);
/// ```
pub fn tilt_angle(q: [f64; 4], axis: Axis, law: &VonMises) -> f64 {
    tilt_angle_of(rotation_column(q, 0), axis, law)
}

/// [`tilt_angle`] of a first axis `e` given directly (a unit vector).
pub fn tilt_angle_of(e: [f64; 3], axis: Axis, law: &VonMises) -> f64 {
    let (i, j) = ((axis.index() + 1) % 3, (axis.index() + 2) % 3);
    let theta = e[j].atan2(e[i]);
    theta + 2.0 * PI * ((law.mean - theta) / (2.0 * PI)).round()
}

/// The CDF and moments of a truncated von Mises law, tabulated once so that the CDF of
/// a whole sample costs a table look-up per value.
///
/// The window `[lo, hi]` of the law is cut into `n` cells of width `h`, at least 64 and
/// `128 (1 + √κ)/π` per radian, so a cell is at most 1/40 of the spread `1/√κ`.
/// The table holds `∫_lo^{lo + k h} ρ` for the density `ρ(θ) = e^{κ (cos(θ − mean) − 1)}`,
/// by Simpson's rule on each cell; `F(θ)` adds Simpson's rule on the part of a cell up
/// to `θ`. Simpson's error on a cell is `h⁵ ρ⁗/2880`; with `h √κ ≤ 1/40` it is below
/// 10⁻⁹ of the cell's mass, far below the sampling error of any packing.
#[derive(Debug, Clone)]
pub struct VonMisesCdf {
    law: VonMises,
    lo: f64,
    h: f64,
    /// `∫_lo^{lo + k h} ρ`, `k = 0..=n`.
    cumulative: Vec<f64>,
}

impl VonMisesCdf {
    /// Tabulates the law.
    ///
    /// ```
    /// use grainpack::io::report::stats::VonMisesCdf;
    /// use grainpack::io::scene::VonMises;
    /// use std::f64::consts::PI;
    /// let tilt = VonMisesCdf::new(&VonMises { mean: 0.5 * PI, kappa: 1.0, min: 0.0, max: PI });
    /// assert!((tilt.cdf(0.5 * PI) - 0.5).abs() < 1e-12);
    /// assert!((tilt.moments().mean - 0.5 * PI).abs() < 1e-12);
    /// ```
    pub fn new(law: &VonMises) -> Self {
        let (lo, hi) = law.window();
        let per_radian = 128.0 * (1.0 + law.kappa.sqrt()) / PI;
        let n = ((per_radian * (hi - lo)).ceil() as usize).max(64);
        let h = (hi - lo) / n as f64;
        let mut table = Self {
            law: *law,
            lo,
            h,
            cumulative: Vec::with_capacity(n + 1),
        };
        let mut sum = 0.0;
        table.cumulative.push(sum);
        for k in 0..n {
            sum += table.cell(lo + k as f64 * h, lo + (k + 1) as f64 * h);
            table.cumulative.push(sum);
        }
        table
    }

    /// The density up to a constant factor, 1 at the mean.
    fn density(&self, theta: f64) -> f64 {
        (self.law.kappa * ((theta - self.law.mean).cos() - 1.0)).exp()
    }

    /// Simpson's rule for `∫_a^b ρ`.
    fn cell(&self, a: f64, b: f64) -> f64 {
        (b - a) / 6.0 * (self.density(a) + 4.0 * self.density(0.5 * (a + b)) + self.density(b))
    }

    /// `P(Θ ≤ θ)`.
    pub fn cdf(&self, theta: f64) -> f64 {
        let n = self.cumulative.len() - 1;
        let total = self.cumulative[n];
        let t = (theta - self.lo) / self.h;
        if !(t > 0.0) {
            return 0.0;
        }
        if t >= n as f64 {
            return 1.0;
        }
        let k = t as usize;
        let node = self.lo + k as f64 * self.h;
        ((self.cumulative[k] + self.cell(node, theta)) / total).clamp(0.0, 1.0)
    }

    /// Mean and standard deviation of the law, by Simpson's rule on the same cells.
    pub fn moments(&self) -> Moments {
        let n = self.cumulative.len() - 1;
        let total = self.cumulative[n];
        let integral = |g: &dyn Fn(f64) -> f64| -> f64 {
            (0..n)
                .map(|k| {
                    let a = self.lo + k as f64 * self.h;
                    let (m, b) = (a + 0.5 * self.h, a + self.h);
                    self.h / 6.0
                        * (g(a) * self.density(a)
                            + 4.0 * g(m) * self.density(m)
                            + g(b) * self.density(b))
                })
                .sum::<f64>()
                / total
        };
        let mean = integral(&|t| t);
        let var = integral(&|t| (t - mean).powi(2));
        Moments {
            mean,
            std: var.max(0.0).sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::scene::{sample_laws, Distribution};
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    fn draw(law: &Distribution, n: usize, seed: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..n).map(|_| law.sample(&mut rng).unwrap()).collect()
    }

    /// For n draws from the law itself, `P(√n D > 1.63) ≈ 0.01` (Kolmogorov's limit
    /// law); the seed is fixed, so the test is deterministic and the bound is generous.
    #[test]
    fn ks_distance_of_a_sample_from_its_own_law_is_small() {
        let n = 5000;
        let laws = sample_laws();
        for (seed, law) in laws.iter().enumerate() {
            let d = ks_distance(&draw(law, n, seed as u64), |x| law.cdf(x)).unwrap();
            assert!(d < 1.63 / (n as f64).sqrt(), "{law:?}: D = {d}");
        }
    }

    #[test]
    fn ks_distance_of_a_shifted_sample_is_large() {
        let law = Distribution::Normal {
            mean: 7.0,
            std: 1.5,
            min: 4.0,
            max: 10.0,
        };
        let shifted: Vec<f64> = draw(&law, 2000, 9).iter().map(|x| x + 1.5).collect();
        let d = ks_distance(&shifted, |x| law.cdf(x)).unwrap();
        // A shift of one std moves the CDF by about 0.38 near the mean.
        assert!(d > 0.3, "D = {d}");
    }

    #[test]
    fn ks_distance_of_a_small_sample_is_the_hand_computed_value() {
        // Uniform [0, 1], sample 0.2, 0.5, 0.5, 0.9: the steps are at 1/4, 3/4, 1.
        // Gaps: x=0.2: 0.25−0.2 = 0.05, 0.2−0 = 0.2; x=0.5: 0.75−0.5 = 0.25,
        // 0.5−0.25 = 0.25; x=0.9: 1−0.9 = 0.1, 0.9−0.75 = 0.15. D = 0.25.
        let d = ks_distance(&[0.9, 0.5, 0.2, 0.5], |x| x.clamp(0.0, 1.0)).unwrap();
        assert!((d - 0.25).abs() < 1e-15, "{d}");
        // A single point: D = max(F(x), 1 − F(x)).
        assert_eq!(ks_distance(&[0.25], |x| x).unwrap(), 0.75);
        assert_eq!(ks_distance(&[], |x| x), None);
    }

    #[test]
    fn ks_distance_to_a_constant_counts_values_off_it() {
        assert_eq!(ks_distance_to_value(&[2.0; 5], 2.0, 0.0), Some(0.0));
        assert_eq!(
            ks_distance_to_value(&[1.0, 2.0, 2.0, 3.0, 3.0], 2.0, 1e-12),
            Some(0.4)
        );
        assert_eq!(ks_distance_to_value(&[], 2.0, 0.0), None);
    }

    #[test]
    fn moments_of_a_sample_are_those_of_its_empirical_law() {
        let m = Moments::of_sample(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]).unwrap();
        assert_eq!((m.mean, m.std), (5.0, 2.0));
        assert_eq!(Moments::of_sample(&[]), None);
    }

    /// The tilt quaternion of the scene, `rot(axis, θ) ⊗ p`, rebuilt here from the
    /// rotation columns its docs give: θ must come back, in the law's window.
    #[test]
    fn tilt_angle_inverts_the_scene_tilt_for_every_axis() {
        let law = VonMises {
            mean: 0.5 * PI,
            kappa: 1.0,
            min: 0.0,
            max: PI,
        };
        for axis in [Axis::X, Axis::Y, Axis::Z] {
            for theta in [0.0, 0.3, 1.5, 3.0] {
                let q = tilt_quaternion(axis, theta);
                let back = tilt_angle(q, axis, &law);
                // A few roundings in the quaternion and its rotation column.
                assert!((back - theta).abs() < 1e-14, "{axis:?} {theta} {back}");
            }
        }
        // Angles come back in [mean − π, mean + π].
        let q = tilt_quaternion(Axis::Z, -0.25 * PI);
        let back = tilt_angle(q, Axis::Z, &VonMises::new(PI, 1.0));
        assert!((back - 1.75 * PI).abs() < 1e-14, "{back}");
    }

    /// `rot(axis, θ) ⊗ p` with `p` the cyclic permutation taking x, y, z to the next
    /// axis, the one after and `axis` (documented in `docs/config.md`).
    fn tilt_quaternion(axis: Axis, theta: f64) -> [f64; 4] {
        let (s, c) = (0.5 * theta).sin_cos();
        let mut r = [c, 0.0, 0.0, 0.0];
        r[1 + axis.index()] = s;
        let p = match axis {
            Axis::Z => [1.0, 0.0, 0.0, 0.0],
            Axis::X => [0.5, 0.5, 0.5, 0.5],
            Axis::Y => [0.5, -0.5, -0.5, -0.5],
        };
        [
            r[0] * p[0] - r[1] * p[1] - r[2] * p[2] - r[3] * p[3],
            r[0] * p[1] + r[1] * p[0] + r[2] * p[3] - r[3] * p[2],
            r[0] * p[2] - r[1] * p[3] + r[2] * p[0] + r[3] * p[1],
            r[0] * p[3] + r[1] * p[2] - r[2] * p[1] + r[3] * p[0],
        ]
    }

    #[test]
    fn von_mises_cdf_agrees_with_the_scenes_quadrature() {
        for law in [
            VonMises {
                mean: 0.5 * PI,
                kappa: 1.0,
                min: 0.0,
                max: PI,
            },
            VonMises::new(-1.0, 300.0),
        ] {
            let table = VonMisesCdf::new(&law);
            for k in 0..=40 {
                let (lo, hi) = law.window();
                let t = lo + (hi - lo) * k as f64 / 40.0;
                // Two quadratures of a smooth density, each good to ~1e-10.
                assert!((table.cdf(t) - law.cdf(t)).abs() < 1e-9, "{law:?} at {t}");
            }
        }
    }

    #[test]
    fn von_mises_moments_match_closed_forms() {
        // κ = 0 on [0, π]: uniform, mean π/2, std π/√12.
        let m = VonMisesCdf::new(&VonMises {
            mean: 0.5 * PI,
            kappa: 0.0,
            min: 0.0,
            max: PI,
        })
        .moments();
        // Simpson is exact for polynomials of degree ≤ 3; rounding of ~1000 terms.
        assert!((m.mean - 0.5 * PI).abs() < 1e-12, "{m:?}");
        assert!((m.std - PI / 12f64.sqrt()).abs() < 1e-12, "{m:?}");
        // Large κ, untruncated: nearly normal with variance 1/κ (1 + 1/(2κ) + …); at
        // κ = 10⁴ the relative correction 1/(4κ) is 2.5e-5.
        let m = VonMisesCdf::new(&VonMises::new(0.2, 1e4)).moments();
        assert!((m.mean - 0.2).abs() < 1e-12, "{m:?}");
        assert!((m.std * 100.0 - 1.0).abs() < 5e-5, "{m:?}");
    }
}
