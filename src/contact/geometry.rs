//! Where and along which normal two ellipsoids touch once scaled by μ, and how far apart
//! they are.

use super::direct::factor_at;
use super::sym::{dot, sym_mul};
use super::{contact_function, contact_function_fast, Contact, ContactError, Sym3, Vec3};

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
    let (lambda, m) = (c.lambda, 1.0 - c.lambda);
    let (_, ldl) = factor_at(lambda, q1, q2)?;
    let s = ldl.solve(r12);
    let q1s = sym_mul(q1, &s);
    let point = q1s.map(|x| m * x);
    let norm = dot(&s, &s).sqrt();
    let normal = s.map(|x| x / norm);
    // d (1 − 1/μ) r̂·n̂, with d r̂ = r12.
    let gap = (1.0 - 1.0 / c.mu2.sqrt()) * dot(r12, &normal);
    if !(gap.is_finite() && norm.is_finite() && norm > 0.0) || point.iter().any(|x| !x.is_finite())
    {
        return Err(ContactError::Overflow {
            what: "the contact geometry",
        });
    }
    Ok(ContactGeometry {
        mu2: c.mu2,
        lambda,
        point,
        normal,
        gap,
    })
}
