//! An ellipsoid validated and factored once, for repeated overlap tests.

use super::direct::condition_bound;
use super::ellipsoid::{Ellipsoid, ShapeError};
use super::ldl::Ldl;
use super::scale::diagonal_in_safe_range;
use super::Sym3;

/// An ellipsoid with what repeated contact queries need: its LDLᵀ factors, exact
/// bounding and inscribed radii (largest and smallest semi-axis), and a bound on the
/// condition number of `Q`.
///
/// Build it once per shape; [`PreparedEllipsoid::scaled`] follows a growing grain
/// without a new eigen-decomposition. Use it with
/// [`overlaps_prepared`](super::overlaps_prepared).
#[derive(Debug, Clone, Copy)]
pub struct PreparedEllipsoid {
    q: Sym3,
    pub(crate) ldl: Ldl,
    bounding_radius: f64,
    inscribed_radius: f64,
    pub(crate) condition: f64,
    /// Whether the diagonal of `q` needs no rescaling (see
    /// [`diagonal_in_safe_range`](super::scale::diagonal_in_safe_range)).
    pub(crate) unscaled: bool,
}

impl PreparedEllipsoid {
    /// Prepares an ellipsoid (validated by its constructor).
    pub fn new(e: &Ellipsoid) -> Result<Self, ShapeError> {
        Self::with_semi_axes(e, e.semi_axes())
    }

    /// [`PreparedEllipsoid::new`] for an ellipsoid that [`Ellipsoid::new`] built from
    /// `semi_axes`: their extremes are taken as the bounding and inscribed radii, with
    /// no eigen-decomposition (they differ from the eigenvalues of the rounded `Q` by a
    /// few `ε · cond` relative), for shapes that turn at every step.
    pub fn with_semi_axes(e: &Ellipsoid, semi_axes: [f64; 3]) -> Result<Self, ShapeError> {
        let ldl = Ldl::factor(&e.q)
            .map_err(|(pivot, value)| ShapeError::NotPositiveDefinite { pivot, value })?;
        let [a, b, c] = semi_axes;
        Ok(Self {
            q: e.q,
            ldl,
            bounding_radius: a.max(b).max(c),
            inscribed_radius: a.min(b).min(c),
            condition: condition_bound(&e.q, &ldl),
            unscaled: diagonal_in_safe_range(&e.q),
        })
    }

    /// The same shape scaled by `factor` about its centre (`Q → factor² Q`).
    ///
    /// Exact up to one rounding per stored number; the condition number is unchanged.
    pub fn scaled(&self, factor: f64) -> Self {
        let f2 = factor * factor;
        let q = self.q.map(|x| x * f2);
        Self {
            q,
            ldl: self.ldl.scaled(f2),
            bounding_radius: self.bounding_radius * factor,
            inscribed_radius: self.inscribed_radius * factor,
            condition: self.condition,
            unscaled: diagonal_in_safe_range(&q),
        }
    }

    /// The quadratic form `Q`.
    pub fn q(&self) -> &Sym3 {
        &self.q
    }

    /// The largest semi-axis.
    pub fn bounding_radius(&self) -> f64 {
        self.bounding_radius
    }

    /// The smallest semi-axis.
    pub fn inscribed_radius(&self) -> f64 {
        self.inscribed_radius
    }
}
