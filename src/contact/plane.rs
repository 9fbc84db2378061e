//! The contact function of two ellipses, by the 3D solver on the embedded pair.
//!
//! An ellipse is `{m ∈ ℝ² : (m − c)ᵀ Q⁻¹ (m − c) ≤ 1}` with `Q` a symmetric 2×2 form
//! stored as `[q00, q01, q11]` ([`Sym2`]). Each form is embedded as the 3×3 form
//! `[q00, q01, 0, q11, 0, z]` ([`embed_form`]) and `r12` as `[r0, r1, 0]`. Then
//! `Q(λ) = (1−λ)Q1 + λQ2` is block diagonal and `r12` has no `z` component, so
//! `r12ᵀ Q(λ)⁻¹ r12` is the 2D quadratic form for every λ, whatever the positive `z`
//! entries: the 3D function of the embedded pair is the ellipses' function, bit for bit
//! in exact arithmetic. Nothing is solved twice.
//!
//! **The `z` entry.** Each form gets its own, half its trace ([`plane_z`]): the mean of
//! its eigenvalues, which lies between them. So the 3×3 form has the 2×2 form's largest
//! diagonal entry and condition number, and the 3D solver sees exactly the 2D pair's
//! scale and conditioning: its power-of-two rescaling, its pivot floor
//! ([`MIN_RELATIVE_PIVOT`](super::MIN_RELATIVE_PIVOT)), its rank test for semi-definite
//! forms (relative to the largest diagonal entry) and its choice of path are those the
//! ellipses deserve. A circle embeds as a sphere, so two circles any distance apart in
//! size are two spheres to the 3D solver. A segment (rank 1) keeps a positive `z` (half
//! its only eigenvalue) and embeds as a flat disc; a point (`Q = 0`) embeds as a point.
//! One `z` shared by both forms would make the factor `(1−λ)z1 + λz2` of `det Q(λ)` and
//! of `adj Q(λ)` constant, but it cannot lie within both forms' eigenvalue ranges once
//! their sizes differ by more than `2^20` (forms by `2^40`): the smaller form would fail
//! the pivot floor, and beyond `2^46` its rank test would count it a point. With `z` per
//! form that linear factor is common to the numerator and the denominator of `f` and
//! cancels. Measured on the 2D mpmath references (`tests/contact_plane.rs`, segments,
//! points and sizes up to 1e150 apart among them): at most 4.2e-16 relative error of μ².

use super::{
    contact_function, contact_function_fast, contact_functions, contact_functions_fast, embed_form,
    overlaps, Contact, ContactError, Sym3, Vec3,
};

/// A vector in the plane: `[x, y]`.
pub type Vec2 = [f64; 2];
/// A symmetric 2×2 matrix stored as its upper triangle: `[m00, m01, m11]`.
pub type Sym2 = [f64; 3];

/// The `z` entry a 2×2 form is embedded with: half its trace, the mean of its
/// eigenvalues (see the module docs), halved before the sum so that it is finite
/// whenever the diagonal is. 0 for a point; negative only for a form with a negative
/// diagonal entry, which the solver rejects naming that entry.
#[inline(always)]
pub fn plane_z(q: &Sym2) -> f64 {
    0.5 * q[0] + 0.5 * q[2]
}

/// The embedded 3D pair of a 2D pair: `r12` with `z = 0`, each form with [`plane_z`].
#[inline(always)]
pub fn embed_pair(r12: &Vec2, q1: &Sym2, q2: &Sym2) -> (Vec3, Sym3, Sym3) {
    (
        [r12[0], r12[1], 0.0],
        embed_form(*q1, plane_z(q1)),
        embed_form(*q2, plane_z(q2)),
    )
}

/// The 2×2 form `R diag(a1², a2²) Rᵀ` of the ellipse with semi-axis `a1` at angle
/// `theta` (radians, counter-clockwise from `x`) and `a2` across it. Not validated: the
/// contact functions reject a form that is not positive semi-definite.
///
/// ```
/// use grainpack::contact::ellipse_form;
/// let q = ellipse_form(2.0, 1.0, std::f64::consts::FRAC_PI_2);
/// assert!((q[0] - 1.0).abs() < 1e-15 && q[1].abs() < 1e-15 && (q[2] - 4.0).abs() < 1e-15);
/// ```
pub fn ellipse_form(a1: f64, a2: f64, theta: f64) -> Sym2 {
    let (s, c) = theta.sin_cos();
    let (p, q) = (a1 * a1, a2 * a2);
    [
        p * c * c + q * s * s,
        (p - q) * c * s,
        p * s * s + q * c * c,
    ]
}

/// An error about the embedded pair `(r12, q1, q2)`, restated about the 2D input:
/// entry `k` of an embedded form is entry `[0, 1, _, 2][k]` of the 2×2 form, and a pivot
/// of the embedded `z` entry (only ever rejected when a diagonal entry is negative) is
/// named as the first negative diagonal entry of the 2×2 form.
pub fn in_plane_terms(error: ContactError, q1: &Sym2, q2: &Sym2) -> ContactError {
    match error {
        ContactError::NotFinite { what, index, value } if what != "r12" => {
            let index = match index {
                3 => 2,
                k => k,
            };
            ContactError::NotFinite { what, index, value }
        }
        ContactError::NotPositiveDefinite { what, pivot: 2, .. } => {
            let q = if what == "q1" { q1 } else { q2 };
            let (pivot, value) = match q[0] < 0.0 {
                true => (0, q[0]),
                false => (1, q[2]),
            };
            ContactError::NotPositiveDefinite { what, pivot, value }
        }
        e => e,
    }
}

/// The Perram–Wertheim contact function μ² of two ellipses and its maximiser λ:
/// [`contact_function`] of the embedded pair (see the module docs), a few ulps.
///
/// `μ² = max_{λ∈[0,1]} λ(1−λ) r12ᵀ[(1−λ)Q1 + λQ2]⁻¹ r12` with the 2×2 forms; `μ² < 1`
/// means overlap. Semi-definite forms (segments, points) are taken where μ² is defined,
/// and errors are [`contact_function`]'s, naming the 2D entries.
///
/// ```
/// use grainpack::contact::{contact_function_2d, ellipse_form};
/// // Two unit circles 3 apart: μ = 3/2.
/// let disc = ellipse_form(1.0, 1.0, 0.0);
/// let c = contact_function_2d(&[3.0, 0.0], &disc, &disc).unwrap();
/// assert!((c.mu2 - 2.25).abs() < 4.0 * f64::EPSILON);
/// ```
pub fn contact_function_2d(r12: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<Contact, ContactError> {
    let (r, a, b) = embed_pair(r12, q1, q2);
    contact_function(&r, &a, &b).map_err(|e| in_plane_terms(e, q1, q2))
}

/// [`contact_function_fast`] of the embedded pair: its error bound, and its hand-over
/// to the accurate method, are those of the 3D function.
pub fn contact_function_fast_2d(r12: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<Contact, ContactError> {
    let (r, a, b) = embed_pair(r12, q1, q2);
    contact_function_fast(&r, &a, &b).map_err(|e| in_plane_terms(e, q1, q2))
}

/// Whether two ellipses overlap (the sign of `μ² − 1`): [`overlaps`] of the embedded
/// pair. Touching ellipses do not overlap.
pub fn overlaps_2d(r12: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<bool, ContactError> {
    let (r, a, b) = embed_pair(r12, q1, q2);
    overlaps(&r, &a, &b).map_err(|e| in_plane_terms(e, q1, q2))
}

/// [`contact_function_2d`] of every pair, in order, eight at a time by
/// [`contact_functions`]: bitwise the same results.
pub fn contact_functions_2d(pairs: &[(Vec2, Sym2, Sym2)]) -> Vec<Result<Contact, ContactError>> {
    many(pairs, contact_functions)
}

/// [`contact_function_fast_2d`] of every pair, in order, by [`contact_functions_fast`].
pub fn contact_functions_fast_2d(
    pairs: &[(Vec2, Sym2, Sym2)],
) -> Vec<Result<Contact, ContactError>> {
    many(pairs, contact_functions_fast)
}

/// A batch function of the 3D pairs.
type Batch = fn(&[(Vec3, Sym3, Sym3)]) -> Vec<Result<Contact, ContactError>>;

fn many(pairs: &[(Vec2, Sym2, Sym2)], solve: Batch) -> Vec<Result<Contact, ContactError>> {
    let embedded: Vec<_> = pairs.iter().map(|(r, a, b)| embed_pair(r, a, b)).collect();
    let mut out = solve(&embedded);
    for (answer, (_, q1, q2)) in out.iter_mut().zip(pairs) {
        if let Err(e) = answer {
            *e = in_plane_terms(e.clone(), q1, q2);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Stop;

    /// Rounding of a few operations on μ² of order 1.
    const TOL: f64 = 8.0 * f64::EPSILON;

    #[test]
    fn circles_reduce_to_the_distance_over_the_sum_of_radii() {
        for (r1, r2, d) in [(1.0, 1.0, 3.0), (0.5, 2.0, 1.0), (1e-6, 1e3, 2e3)] {
            let c = contact_function_2d(
                &[0.0, d],
                &[r1 * r1, 0.0, r1 * r1],
                &[r2 * r2, 0.0, r2 * r2],
            )
            .unwrap();
            let want = (d / (r1 + r2)).powi(2);
            assert!((c.mu2 - want).abs() <= TOL * want, "{c:?} vs {want}");
        }
    }

    #[test]
    fn the_answer_does_not_depend_on_the_z_entry() {
        let q1 = ellipse_form(3.0, 0.2, 0.3);
        let q2 = ellipse_form(0.7, 1.5, -1.1);
        let r = [1.2, -0.4];
        let c = contact_function_2d(&r, &q1, &q2).unwrap();
        for (z1, z2) in [(1.0, 1.0), (9.0, 0.04), (0.3, 7.0)] {
            let other =
                contact_function(&[r[0], r[1], 0.0], &embed_form(q1, z1), &embed_form(q2, z2))
                    .unwrap();
            assert!((other.mu2 - c.mu2).abs() <= TOL * c.mu2, "{z1} {z2}");
        }
    }

    #[test]
    fn a_point_against_an_ellipse_is_the_ellipse_form_at_an_end() {
        let q = ellipse_form(2.0, 1.0, 0.4);
        let r = [0.5, 1.5];
        let c = contact_function_2d(&r, &[0.0; 3], &q).unwrap();
        let det = q[0] * q[2] - q[1] * q[1];
        let want = (q[2] * r[0] * r[0] - 2.0 * q[1] * r[0] * r[1] + q[0] * r[1] * r[1]) / det;
        assert!((c.mu2 - want).abs() <= TOL * want, "{c:?} vs {want}");
        assert_eq!(c.stop, Stop::Exact);
    }

    #[test]
    fn two_parallel_segments_have_no_contact_function() {
        let s = ellipse_form(1.0, 0.0, 0.5);
        let e = contact_function_2d(&[0.1, 2.0], &s, &s).unwrap_err();
        assert_eq!(e, ContactError::CommonNullDirection);
    }

    #[test]
    fn forms_near_the_top_of_the_double_range_keep_a_finite_z() {
        let q = [1e308, 0.0, 1e308];
        assert_eq!(plane_z(&q), 1e308);
        let c = contact_function_2d(&[1e154, 0.0], &q, &q).unwrap();
        assert!((c.mu2 - 0.25).abs() <= TOL, "{c:?}");
    }

    #[test]
    fn errors_name_the_2d_entries() {
        let q = ellipse_form(1.0, 1.0, 0.0);
        let bad = [1.0, 0.0, f64::NAN];
        let e = contact_function_2d(&[1.0, 0.0], &q, &bad).unwrap_err();
        assert!(
            matches!(
                e,
                ContactError::NotFinite {
                    what: "q2",
                    index: 2,
                    ..
                }
            ),
            "{e}"
        );
        let e = contact_function_2d(&[1.0, f64::INFINITY], &q, &q).unwrap_err();
        assert!(
            matches!(
                e,
                ContactError::NotFinite {
                    what: "r12",
                    index: 1,
                    ..
                }
            ),
            "{e}"
        );
        for bad in [
            [-1.0, 0.0, 1.0],
            [1.0, 0.0, -1.0],
            [-1.0, 0.0, -2.0],
            [1.0, 2.0, 1.0],
        ] {
            let e = contact_function_2d(&[1.0, 0.0], &bad, &q).unwrap_err();
            let ContactError::NotPositiveDefinite { what, pivot, .. } = e else {
                panic!("{bad:?}: {e}");
            };
            assert_eq!(what, "q1");
            assert!(pivot < 2, "{bad:?}: {e}");
            let batch = contact_functions_2d(&[([1.0, 0.0], bad, q)]);
            assert_eq!(batch[0].as_ref().unwrap_err(), &e);
        }
    }
}
