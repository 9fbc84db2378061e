//! The von Mises distribution of an angle, truncated to cutoffs, sampled by the method
//! of Best and Fisher (1979).

use super::distribution::Invalid;
use super::special::simpson;
use super::{MAX_DRAWS, MIN_ACCEPTED_MASS};
use rand::Rng;
use std::f64::consts::PI;

/// The largest concentration accepted. Best–Fisher loses precision beyond it (numpy
/// switches to a wrapped normal there); at `κ = 10⁶` the spread `1/√κ` is 0.06°, which
/// a fixed orientation expresses better.
pub const MAX_KAPPA: f64 = 1e6;

/// Below this concentration the density `∝ e^{κ cos θ}` differs from uniform by less
/// than `2κ = 2·10⁻⁸` relative, and Best–Fisher's `ρ` underflows to 0: draw uniformly.
const KAPPA_UNIFORM: f64 = 1e-8;

/// Below this concentration `s = (1 + ρ²)/(2ρ)` is computed from its second-order
/// expansion `1/κ + κ`, since the exact formula cancels catastrophically.
const KAPPA_SERIES: f64 = 1e-5;

/// An angle `θ` (radians) with density `∝ e^{κ cos(θ − mean)}`, drawn in
/// `[mean − π, mean + π]` and truncated to `[min, max]`.
///
/// `κ = 0` is uniform. Cutoffs outside `[mean − π, mean + π]` cut nothing there: the
/// window that can be drawn is [`VonMises::window`].
///
/// ```
/// use grainpack::laws::VonMises;
/// use std::f64::consts::PI;
/// let tilt = VonMises { mean: 0.5 * PI, kappa: 1.0, min: 0.0, max: PI };
/// assert_eq!(tilt.window(), (0.0, PI));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VonMises {
    /// The mean direction (radians).
    pub mean: f64,
    /// The concentration `κ ≥ 0` (for large `κ`, the spread is about `1/√κ` radians).
    pub kappa: f64,
    /// Lower cutoff (radians).
    pub min: f64,
    /// Upper cutoff (radians).
    pub max: f64,
}

impl VonMises {
    /// An untruncated von Mises law: cutoffs `mean ± π`.
    pub fn new(mean: f64, kappa: f64) -> Self {
        Self {
            mean,
            kappa,
            min: mean - PI,
            max: mean + PI,
        }
    }

    /// The interval the angles are drawn from: `[min, max] ∩ [mean − π, mean + π]`.
    pub fn window(&self) -> (f64, f64) {
        (self.min.max(self.mean - PI), self.max.min(self.mean + PI))
    }

    /// The unnormalised density, scaled to 1 at the mean so that it cannot overflow.
    pub(super) fn density(&self, theta: f64) -> f64 {
        (self.kappa * ((theta - self.mean).cos() - 1.0)).exp()
    }

    /// `∫ density` over `[a, b]`, on a grid fine enough to resolve the spread `1/√κ`:
    /// the normalisation of [`VonMises::pdf`] and of the accepted mass. The CDF is
    /// [`VonMisesCdf`](super::VonMisesCdf).
    pub(super) fn integral(&self, a: f64, b: f64) -> f64 {
        if b <= a {
            return 0.0;
        }
        let per_radian = 256.0 * (1.0 + self.kappa.sqrt()) / PI;
        simpson(
            |t| self.density(t),
            a,
            b,
            (per_radian * (b - a)).ceil() as usize,
        )
    }

    /// The probability that the untruncated law falls inside the cutoffs: the
    /// acceptance rate of rejection sampling.
    pub fn accepted_mass(&self) -> f64 {
        let (lo, hi) = self.window();
        self.integral(lo, hi) / self.integral(self.mean - PI, self.mean + PI)
    }

    /// Draws one angle in the window: untruncated draws are rejected until one falls
    /// inside the cutoffs, at most [`MAX_DRAWS`] times; `None` if none did.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> Option<f64> {
        for _ in 0..MAX_DRAWS {
            let theta = self.mean + best_fisher(self.kappa, rng)?;
            if (self.min..=self.max).contains(&theta) {
                return Some(theta);
            }
        }
        None
    }

    /// Checks `κ`, the cutoffs and the mass they keep, naming the first parameter that
    /// fails (angles are reported in degrees, as written in the scene file).
    pub(crate) fn check(&self) -> Result<(), Invalid> {
        for (name, value) in [
            ("mean", self.mean),
            ("kappa", self.kappa),
            ("min", self.min),
            ("max", self.max),
        ] {
            if !value.is_finite() {
                return Err(Invalid::new(name, "must be a finite number"));
            }
        }
        if !(0.0..=MAX_KAPPA).contains(&self.kappa) {
            return Err(Invalid::new(
                "kappa",
                format!("must lie in [0, {MAX_KAPPA:e}] (for a fixed angle use kind = \"fixed\")"),
            ));
        }
        if self.min >= self.max {
            return Err(Invalid::new(
                "max",
                format!(
                    "cutoffs reversed or empty: max = {}° must be above min = {}°",
                    self.max.to_degrees(),
                    self.min.to_degrees()
                ),
            ));
        }
        let mass = self.accepted_mass();
        if !(mass >= MIN_ACCEPTED_MASS) {
            let (lo, hi) = (self.mean - PI, self.mean + PI);
            return Err(Invalid::new(
                "min",
                format!(
                    "the cutoffs [{}°, {}°] keep only {mass:.3e} of the angles, which are drawn \
                     in [{}°, {}°]; at least {MIN_ACCEPTED_MASS:e} is needed",
                    self.min.to_degrees(),
                    self.max.to_degrees(),
                    lo.to_degrees(),
                    hi.to_degrees()
                ),
            ));
        }
        Ok(())
    }
}

/// One draw `δ ∈ [−π, π]` of the von Mises law with mean 0 and concentration `κ`.
///
/// Best, D. J. & Fisher, N. I. (1979), "Efficient simulation of the von Mises
/// distribution", *Applied Statistics* 28, 152–157: a wrapped-Cauchy envelope with
/// `τ = 1 + √(1 + 4κ²)`, `ρ = (τ − √(2τ))/(2κ)`, `s = (1 + ρ²)/(2ρ)`; draw
/// `z = cos(πu₁)`, `f = (1 + sz)/(s + z)`, `c = κ(s − f)`, accept if
/// `c(2 − c) > u₂` or `ln(c/u₂) + 1 ≥ c`, then `δ = ±acos f`. Its acceptance rate is
/// above 65 % for every `κ`; `None` after [`MAX_DRAWS`] rejections.
fn best_fisher<R: Rng + ?Sized>(kappa: f64, rng: &mut R) -> Option<f64> {
    if kappa < KAPPA_UNIFORM {
        return Some(PI * (2.0 * rng.random::<f64>() - 1.0));
    }
    let s = if kappa < KAPPA_SERIES {
        1.0 / kappa + kappa
    } else {
        let tau = 1.0 + (1.0 + 4.0 * kappa * kappa).sqrt();
        let rho = (tau - (2.0 * tau).sqrt()) / (2.0 * kappa);
        (1.0 + rho * rho) / (2.0 * rho)
    };
    for _ in 0..MAX_DRAWS {
        let z = (PI * rng.random::<f64>()).cos();
        let f = (1.0 + s * z) / (s + z);
        let c = kappa * (s - f);
        let u2 = rng.random::<f64>();
        if c * (2.0 - c) > u2 || (c / u2).ln() + 1.0 >= c {
            let delta = f.clamp(-1.0, 1.0).acos();
            return Some(if rng.random::<f64>() < 0.5 {
                -delta
            } else {
                delta
            });
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// `A(κ) = E[cos δ] = I₁(κ)/I₀(κ)`, by quadrature of the density.
    fn mean_resultant_length(kappa: f64) -> f64 {
        let d = |t: f64| (kappa * (t.cos() - 1.0)).exp();
        simpson(|t| t.cos() * d(t), -PI, PI, 20_000) / simpson(d, -PI, PI, 20_000)
    }

    #[test]
    fn mean_resultant_length_matches_bessel_ratio() {
        // I1(1)/I0(1) = 0.446390, I1(4)/I0(4) = 0.863523 (power series of I₀, I₁) (tables of Bessel functions).
        assert!((mean_resultant_length(1.0) - 0.446_389_966).abs() < 1e-8);
        assert!((mean_resultant_length(4.0) - 0.863_522_611).abs() < 1e-8);
    }

    /// Sample mean direction and mean resultant length against `A(κ)`, over a range of
    /// concentrations including the series and uniform branches. With n = 20 000 draws
    /// the standard error of `mean cos δ` is at most `1/√(2n)` = 0.005 and that of the
    /// angle of the mean direction about `1/(A√n)`; 5 standard errors are allowed.
    #[test]
    fn best_fisher_reproduces_mean_direction_and_concentration() {
        let n = 20_000;
        for (kappa, seed) in [
            (0.0, 1),
            (3e-6, 2),
            (0.5, 3),
            (1.0, 4),
            (4.0, 5),
            (50.0, 6),
            (1e5, 7),
        ] {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let law = VonMises::new(0.3, kappa);
            let (mut c, mut s) = (0.0, 0.0);
            for _ in 0..n {
                let t = law.sample(&mut rng).unwrap();
                assert!((law.mean - PI..=law.mean + PI).contains(&t));
                c += (t - law.mean).cos();
                s += (t - law.mean).sin();
            }
            let (c, s) = (c / n as f64, s / n as f64);
            let a = mean_resultant_length(kappa);
            let se = (1.0 / (2.0 * n as f64)).sqrt();
            assert!(
                (c - a).abs() < 5.0 * se,
                "κ={kappa}: mean cos {c}, want {a}"
            );
            if a > 0.1 {
                let angle = s.atan2(c);
                assert!(
                    angle.abs() < 5.0 / (a * (n as f64).sqrt()),
                    "κ={kappa}: {angle}"
                );
            }
        }
    }

    #[test]
    fn truncation_keeps_draws_inside_the_cutoffs_and_reports_their_mass() {
        let law = VonMises {
            mean: 0.5 * PI,
            kappa: 1.0,
            min: 0.0,
            max: PI,
        };
        // By symmetry about the mean, [0, π] keeps P(|δ| ≤ π/2) = ∫ over half the circle.
        let full = simpson(|t| (t.cos()).exp(), -PI, PI, 20_000);
        let half = simpson(|t| (t.cos()).exp(), -0.5 * PI, 0.5 * PI, 20_000);
        assert!((law.accepted_mass() - half / full).abs() < 1e-9);
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for _ in 0..5000 {
            let t = law.sample(&mut rng).unwrap();
            assert!((0.0..=PI).contains(&t), "{t}");
        }
    }

    #[test]
    fn check_rejects_bad_kappa_and_empty_windows() {
        let bad = |v: VonMises| v.check().unwrap_err().param;
        assert_eq!(bad(VonMises::new(0.0, -1.0)), "kappa");
        assert_eq!(bad(VonMises::new(0.0, 2e6)), "kappa");
        let mut v = VonMises::new(0.0, 1.0);
        (v.min, v.max) = (1.0, 0.5);
        assert_eq!(bad(v), "max");
        // Angles are drawn in [−π, π]: a window beyond it is empty.
        (v.min, v.max) = (4.0, 5.0);
        assert_eq!(bad(v), "min");
        assert!(VonMises::new(1.0, 1.0).check().is_ok());
    }
}
