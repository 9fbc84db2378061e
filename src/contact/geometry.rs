//! Where and along which normal two ellipsoids touch once scaled by μ, and how far apart
//! they are.

use super::direct::factor_between;
use super::ldl::Ldl;
use super::perram_wertheim::{contact_function_fast_factored, lambda_and_complement, rank};
use super::prepared::PreparedEllipsoid;
use super::scale::{exponent, pow2};
use super::sym::{adjugate, det, dot, frobenius, polarised_adjugate, sym_mul};
use super::{contact_function, contact_function_fast, Contact, ContactError, Sym3, Vec3, NEAR_END};

/// Contact geometry of a pair, for collision response.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// The contact function μ² (see [`contact_function`]).
    pub mu2: f64,
    /// Its maximiser λ.
    pub lambda: f64,
    /// The point where the two ellipsoids, both scaled by μ about their centres,
    /// touch, relative to the first centre: `x₀ − c1 = (1−λ) Q1 Q(λ)⁻¹ r12`
    /// (pw85 theory, eq. 9a).
    pub point: Vec3,
    /// The common unit normal of the scaled ellipsoids at `point`, pointing from the
    /// first ellipsoid to the second: `Q(λ)⁻¹ r12`, normalised (Donev et al. 2005,
    /// eq. 18).
    pub normal: Vec3,
    /// Signed gap estimate: `d (1 − 1/μ)` along `r12`, projected on the normal
    /// (`d = |r12|`). Positive when apart, negative (a penetration depth) when
    /// overlapping.
    pub gap: f64,
}

/// The contact point, normal and gap of two ellipsoids (see [`ContactGeometry`]).
///
/// Coincident centres have no normal: `r12 = 0` is [`ContactError::CoincidentCentres`].
pub fn contact_geometry(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<ContactGeometry, ContactError> {
    geometry_from(contact_function(r12, q1, q2)?, r12, q1, q2)
}

/// [`contact_geometry`] from [`contact_function_fast`]: μ² to about `ε · cond(Q)`, for
/// collision response where speed matters more than the last digits.
pub fn contact_geometry_fast(
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<ContactGeometry, ContactError> {
    geometry_from(contact_function_fast(r12, q1, q2)?, r12, q1, q2)
}

/// [`contact_geometry_fast`] of two prepared shapes, reusing their factorisations:
/// bit for bit the same answer for shapes made by [`PreparedEllipsoid::new`] (those of
/// [`PreparedEllipsoid::scaled`] hold factors that may differ from a fresh
/// factorisation by a rounding, and so may the answer's last digits).
///
/// ```
/// use grainpack::contact::{contact_geometry_fast, contact_geometry_fast_prepared, Ellipsoid, PreparedEllipsoid};
/// let e = Ellipsoid::new([2.0, 1.0, 0.5], [0.5, 0.5, 0.5, 0.5]).unwrap();
/// let p = PreparedEllipsoid::new(&e).unwrap();
/// let r = [1.5, 0.4, -0.3];
/// assert_eq!(contact_geometry_fast_prepared(&r, &p, &p), contact_geometry_fast(&r, &e.q, &e.q));
/// ```
#[inline]
pub fn contact_geometry_fast_prepared(
    r12: &Vec3,
    e1: &PreparedEllipsoid,
    e2: &PreparedEllipsoid,
) -> Result<ContactGeometry, ContactError> {
    geometry_from(contact_fast_prepared(r12, e1, e2)?, r12, e1.q(), e2.q())
}

/// The contact function of [`contact_geometry_fast_prepared`], for a caller that wants
/// the geometry only for some answers (the packing's, of overlapping pairs: see
/// [`response_geometry`]).
#[inline]
pub(crate) fn contact_fast_prepared(
    r12: &Vec3,
    e1: &PreparedEllipsoid,
    e2: &PreparedEllipsoid,
) -> Result<Contact, ContactError> {
    let (q1, q2) = (e1.q(), e2.q());
    if e1.unscaled & e2.unscaled {
        contact_function_fast_factored(r12, q1, q2, (&e1.ldl, &e2.ldl))
    } else {
        contact_function_fast(r12, q1, q2)
    }
}

/// The geometry of a pair from its [`contact_fast_prepared`] answer `c`, for collision
/// response: [`contact_geometry_fast_prepared`]'s quantities, the normal and the point
/// from `v = adj Q(λ) r12 = det Q(λ) · Q(λ)⁻¹ r12` instead of a factorisation of
/// `Q(λ)`. Each entry of the adjugate is a 2×2 minor, so `v` errs by a few `ε κ(Q(λ))`
/// relative, and `κ(Q(λ))` is at most the larger condition number of the two forms
/// (the square of the grain's aspect ratio): about 1e-12 for an aspect ratio of 100,
/// far below what a force or a torque needs (μ² is `c`'s, untouched). A pair whose λ
/// is within [`NEAR_END`] of an end, of forms that needed rescaling, or where
/// `det Q(λ)` is not positive or the point or gap leave the double range, gets
/// [`geometry_from`]'s answer.
#[inline]
pub(crate) fn response_geometry(
    c: Contact,
    r12: &Vec3,
    e1: &PreparedEllipsoid,
    e2: &PreparedEllipsoid,
) -> Result<ContactGeometry, ContactError> {
    let (q1, q2) = (e1.q(), e2.q());
    let (lambda, m) = (c.lambda, 1.0 - c.lambda);
    if (NEAR_END..=1.0 - NEAR_END).contains(&lambda) & e1.unscaled & e2.unscaled {
        let q: Sym3 = std::array::from_fn(|k| m * q1[k] + lambda * q2[k]);
        let adj = adjugate(&q);
        let det = det(&q, &adj);
        if det > 0.0 {
            let v = sym_mul(&adj, r12);
            let point = sym_mul(q1, &v).map(|x| x * (m / det));
            if let Ok(g) = along(c, r12, point, v) {
                return Ok(g);
            }
        }
    }
    geometry_from(c, r12, q1, q2)
}

/// Smallest `|s|` whose square is formed without underflow (`2^-500`, far above the
/// subnormals); below it, or if it overflows, the normal is taken from `s` scaled to
/// its largest entry (above it the two differ only by rounding, and the plain one is
/// kept so that results stay bitwise those of earlier versions).
const NORM_IN_RANGE: f64 = 3.054936363499605e-151;

#[inline]
fn geometry_from(
    c: Contact,
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<ContactGeometry, ContactError> {
    let d = dot(r12, r12).sqrt();
    if d == 0.0 {
        return Err(ContactError::CoincidentCentres);
    }
    // Near an end, 1 − λ from the path that carries it (λ may have rounded to 1).
    let near_end = c.lambda < NEAR_END || c.lambda > 1.0 - NEAR_END;
    let (lambda, m) = if near_end {
        lambda_and_complement(r12, q1, q2)?
    } else {
        (c.lambda, 1.0 - c.lambda)
    };
    // μ² the limit of f at an end where that end's form is singular (a point, a needle,
    // or a disc the other ellipsoid reaches inside its rim): the limits there. λ is
    // then exactly 0 or 1 (or within rounding of it), and Q(λ) that form.
    let limit = match lambda {
        0.0 => limit_at_start(r12, q1, q2).map(|v| {
            let q2v = sym_mul(q2, &v);
            (std::array::from_fn(|i| r12[i] - q2v[i]), v)
        }),
        1.0 => limit_at_start(&r12.map(|x| -x), q2, q1)
            .map(|v| (sym_mul(q1, &v).map(|x| -x), v.map(|x| -x))),
        _ => None,
    };
    let (point, s) = match limit {
        Some(found) => found,
        None => {
            let (_, ldl) = factor_between(m, lambda, q1, q2)?;
            let s = ldl.solve(r12);
            // Near an end (1−λ)Q1 is formed first: Q1 s alone may overflow when 1 − λ
            // is tiny. Elsewhere as before, so that results stay bitwise the same.
            match near_end {
                true => (sym_mul(&q1.map(|x| m * x), &s), s),
                false => (sym_mul(q1, &s).map(|x| m * x), s),
            }
        }
    };
    along(c, r12, point, s)
}

/// The geometry of `c` with contact point `point` (from the first centre) and the
/// normal along `s`, a positive multiple of `Q(λ)⁻¹ r12`; an error where the point or
/// the gap leave the double range.
fn along(c: Contact, r12: &Vec3, point: Vec3, s: Vec3) -> Result<ContactGeometry, ContactError> {
    let mut norm = dot(&s, &s).sqrt();
    let mut normal = s.map(|x| x / norm);
    if !(norm.is_finite() && norm >= NORM_IN_RANGE) {
        // s beyond the range of |s|² (sizes far apart): scaled to its largest entry.
        let big = s[0].abs().max(s[1].abs()).max(s[2].abs());
        let unit = s.map(|x| x / big);
        norm = dot(&unit, &unit).sqrt();
        normal = unit.map(|x| x / norm);
    }
    // d (1 − 1/μ) r̂·n̂, with d r̂ = r12.
    let gap = (1.0 - 1.0 / c.mu2.sqrt()) * dot(r12, &normal);
    if !(gap.is_finite() && norm.is_finite() && norm > 0.0) || point.iter().any(|x| !x.is_finite())
    {
        return Err(ContactError::Overflow {
            what: "the contact geometry (the point or the gap beyond double range)",
        });
    }
    Ok(ContactGeometry {
        mu2: c.mu2,
        lambda: c.lambda,
        point,
        normal,
        gap,
    })
}

/// `v = lim λ Q(λ)⁻¹ r12` as `λ → 0⁺` for a singular `q1`, whose direction is the
/// normal's and with which the point is `r12 − Q2 v` (from `c1`; pw85's
/// `x₀ = c2 − λ Q2 Q(λ)⁻¹ r12`). With `adj Q(λ) = s² adj Q1 + st M + t² adj Q2` and
/// `det Q(λ) = s³B0 + s²t B1 + st² B2 + t³B3` (`t = λ`, `s = 1 − λ`), the terms of
/// lowest order that do not vanish with the rank of `q1` give `adj Q1 r12 / B1` (a
/// disc, rank 2), `M r12 / B2` (a needle, rank 1) and `Q2⁻¹ r12` (a point). `None` if
/// `q1` is definite (rank 3: `Q(0)` factors), not semi-definite, or the limit is not
/// finite.
fn limit_at_start(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Option<Vec3> {
    let top = q1[0].max(q1[3]).max(q1[5]);
    let rank = if top > 0.0 {
        // `rank` takes forms scaled to a largest diagonal entry in [1, 2).
        let unit = pow2(-exponent(top));
        rank(&q1.map(|x| x * unit))?
    } else if q1.iter().all(|&x| x == 0.0) {
        0
    } else {
        return None;
    };
    let v = match rank {
        2 => {
            let adj1 = adjugate(q1);
            let b1 = frobenius(&adj1, q2);
            sym_mul(&adj1, r12).map(|x| x / b1)
        }
        1 => {
            let b2 = frobenius(q1, &adjugate(q2));
            sym_mul(&polarised_adjugate(q1, q2), r12).map(|x| x / b2)
        }
        0 => Ldl::factor(q2).ok()?.solve(r12),
        _ => return None,
    };
    v.iter().all(|x| x.is_finite()).then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::test_pairs::random_pairs;

    /// `response_geometry`'s vectors against a factorisation's, relative to their size,
    /// in units of `ε κ`: the adjugate's minors and the factors each round to a few `ε κ`.
    const ADJUGATE_ROUNDING: f64 = 64.0;

    #[test]
    fn the_response_geometry_agrees_with_the_factored_one_to_the_conditioning() {
        let mut checked = 0;
        for ((r, q1, q2), kappa) in random_pairs(29, 4000) {
            let (e1, e2) = (
                PreparedEllipsoid::from_quadratic_form(&q1).unwrap(),
                PreparedEllipsoid::from_quadratic_form(&q2).unwrap(),
            );
            let Ok(c) = contact_fast_prepared(&r, &e1, &e2) else {
                continue;
            };
            let (fast, exact) = (
                response_geometry(c, &r, &e1, &e2).unwrap(),
                geometry_from(c, &r, &q1, &q2).unwrap(),
            );
            let tol = ADJUGATE_ROUNDING * f64::EPSILON * kappa;
            let off = |a: &Vec3, b: &Vec3| {
                let d: Vec3 = std::array::from_fn(|k| a[k] - b[k]);
                dot(&d, &d).sqrt()
            };
            assert_eq!((fast.mu2, fast.lambda), (exact.mu2, exact.lambda));
            assert!(
                off(&fast.normal, &exact.normal) <= tol,
                "{r:?} {q1:?} {q2:?}"
            );
            let size = dot(&r, &r).sqrt();
            assert!(off(&fast.point, &exact.point) <= tol * size, "{r:?}");
            assert!((fast.gap - exact.gap).abs() <= tol * size, "{r:?}");
            checked += 1;
        }
        assert!(checked > 3900, "{checked}");
    }
}
