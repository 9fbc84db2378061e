//! An ellipsoid validated and factored once, for repeated overlap tests.

use super::direct::condition_bound;
use super::ellipsoid::{Ellipsoid, ShapeError};
use super::ldl::Ldl;
use super::perram_wertheim::rank;
use super::scale::{diagonal_in_safe_range, exponent, pow2};
use super::{ContactError, Sym3};

/// An ellipsoid with what repeated contact queries need: its LDLᵀ factors, exact
/// bounding and inscribed radii (largest and smallest semi-axis), and a bound on the
/// condition number of `Q`.
///
/// Build it once per shape; [`PreparedEllipsoid::scaled`] follows a growing grain
/// without a new eigen-decomposition. Use it with
/// [`overlaps_prepared`](super::overlaps_prepared).
///
/// Semi-definite forms (a flat disc, a zero-radius needle, a point) and forms too thin
/// for the LDLᵀ rule ([`MIN_RELATIVE_PIVOT`](super::MIN_RELATIVE_PIVOT)) are built by
/// [`PreparedEllipsoid::from_quadratic_form`]: they have no factors, and
/// `overlaps_prepared` decides their pairs as [`overlaps`](super::overlaps) does.
// In this order (`repr(C)`): a relaxation's narrow phase reads the first 80 bytes of
// most shapes it meets, and the factors only of a few.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub struct PreparedEllipsoid {
    q: Sym3,
    inscribed_radius: f64,
    bounding_radius: f64,
    pub(crate) condition: f64,
    /// Whether the diagonal of `q` needs no rescaling (see
    /// [`diagonal_in_safe_range`](super::scale::diagonal_in_safe_range)).
    pub(crate) unscaled: bool,
    /// The factors of `q`; those of `I` for a form that does not factor (then
    /// `condition` is infinite and `unscaled` false, so they are never used).
    pub(crate) ldl: Ldl,
}

impl PreparedEllipsoid {
    /// Prepares any positive semi-definite form: definite ones as [`PreparedEllipsoid::new`]
    /// does, singular ones (and definite ones too thin to factor) with no factors, an
    /// inscribed radius of 0 and their largest semi-axis from an eigen-decomposition.
    ///
    /// ```
    /// use grainpack::contact::{overlaps_prepared, Ellipsoid, PreparedEllipsoid};
    /// let disc = PreparedEllipsoid::from_quadratic_form(&[1.0, 0.0, 0.0, 1.0, 0.0, 0.0]).unwrap();
    /// let ball = PreparedEllipsoid::new(&Ellipsoid::sphere(1.0).unwrap()).unwrap();
    /// assert!(overlaps_prepared(&[0.0, 0.0, 0.9], &disc, &ball).unwrap());
    /// assert!(!overlaps_prepared(&[0.0, 0.0, 1.1], &disc, &ball).unwrap());
    /// ```
    ///
    /// # Errors
    /// [`ContactError::NotFinite`] (`what = "q"`) for NaN or infinite entries;
    /// [`ContactError::NotPositiveDefinite`] for a form that is not semi-definite.
    pub fn from_quadratic_form(q: &Sym3) -> Result<Self, ContactError> {
        if let Some(index) = q.iter().position(|x| !x.is_finite()) {
            let value = q[index];
            return Err(ContactError::NotFinite {
                what: "q",
                index,
                value,
            });
        }
        if let Ok(e) = Ellipsoid::from_quadratic_form(*q) {
            if let Ok(p) = Self::new(&e) {
                return Ok(p);
            }
        }
        let top = q[0].max(q[3]).max(q[5]);
        let unit = if top > 0.0 { pow2(-exponent(top)) } else { 1.0 };
        let indefinite = || {
            let (pivot, value) = Ldl::factor(q).err().unwrap_or((2, 0.0));
            ContactError::NotPositiveDefinite {
                what: "q",
                pivot,
                value,
            }
        };
        let semi_definite = q.iter().all(|&x| x == 0.0) || top > 0.0;
        if !semi_definite || rank(&q.map(|x| x * unit)).is_none() {
            return Err(indefinite());
        }
        let m = Ellipsoid { q: *q }.matrix();
        let largest = m.symmetric_eigenvalues().max().max(0.0);
        Ok(Self {
            q: *q,
            ldl: Ldl::unchecked(&[1.0, 0.0, 0.0, 1.0, 0.0, 1.0]),
            bounding_radius: largest.sqrt(),
            inscribed_radius: 0.0,
            condition: f64::INFINITY,
            unscaled: false,
        })
    }

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
            unscaled: self.condition.is_finite() && diagonal_in_safe_range(&q),
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
