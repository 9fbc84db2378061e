//! A phase's isotropic elastic constants (`[phase.elastic]`).

/// Isotropic linear elasticity: Young's modulus and Poisson's ratio. The stiffness is
/// positive definite exactly when `E > 0` and `−1 < ν < ½` ([`Elastic::check`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Young's modulus `E`, in the scene's stress unit ([`Units`](super::Units)).
    pub young: f64,
    /// Poisson's ratio `ν`.
    pub poisson: f64,
}

impl Elastic {
    /// Why the constants give no positive-definite stiffness, naming the key (`"E"` or
    /// `"nu"`) at fault; `None` if they do.
    pub fn check(&self) -> Option<(&'static str, &'static str)> {
        if !(self.young.is_finite() && self.young > 0.0) {
            return Some((
                "E",
                "must be positive and finite (the stiffness must be positive definite)",
            ));
        }
        if !(self.poisson > -1.0 && self.poisson < 0.5) {
            return Some((
                "nu",
                "must lie in (-1, 0.5) (the stiffness must be positive definite)",
            ));
        }
        None
    }

    /// Shear modulus `μ = E / (2(1 + ν))`.
    pub fn shear(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    /// Bulk modulus `K = E / (3(1 − 2ν))`.
    pub fn bulk(&self) -> f64 {
        self.young / (3.0 * (1.0 - 2.0 * self.poisson))
    }

    /// The cubic constants `[C11, C12, C44]` of this isotropic stiffness:
    /// `C12 = K − 2μ/3`, `C11 = C12 + 2μ`, `C44 = μ`.
    pub fn cubic(&self) -> [f64; 3] {
        let (k, mu) = (self.bulk(), self.shear());
        let c12 = k - 2.0 * mu / 3.0;
        [c12 + 2.0 * mu, c12, mu]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_constants_of_an_isotropic_solid() {
        let e = Elastic {
            young: 210.0,
            poisson: 0.3,
        };
        let [c11, c12, c44] = e.cubic();
        // Lamé: λ = Eν/((1+ν)(1−2ν)), C11 = λ + 2μ.
        let lambda = 210.0 * 0.3 / (1.3 * 0.4);
        assert!((c12 - lambda).abs() < 1e-12 * lambda);
        assert!((c11 - (lambda + 2.0 * 210.0 / 2.6)).abs() < 1e-12 * c11);
        assert!((c44 - 210.0 / 2.6).abs() < 1e-12 * c44);
        assert!(e.check().is_none());
        assert_eq!(Elastic { poisson: 0.5, ..e }.check().unwrap().0, "nu");
        assert_eq!(Elastic { young: -1.0, ..e }.check().unwrap().0, "E");
    }
}
