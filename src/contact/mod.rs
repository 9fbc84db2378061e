//! Narrow phase: do two ellipsoids overlap, and by how much?
//!
//! Every function here takes the pair in relative form: `r12 = c2 - c1` and the two
//! quadratic forms `q1`, `q2` (upper triangle of the symmetric positive-definite matrix
//! `Q = R diag(a1², a2², a3²) Rᵀ`, row-major: `q0 q1 q2 / q3 q4 / q5`, as in pw85).
//! Boxes, periodic images and ids are the caller's business. Ellipses (2×2 forms
//! `[q00, q01, q11]`) take the same functions with the suffix `_2d`, which solve the
//! embedded 3D pair (module `plane`).

mod bernstein;
mod dd;
mod dimension;
mod direct;
mod ellipsoid;
mod error;
mod geometry;
mod lanes;
mod ldl;
mod method;
mod overlap;
mod perram_wertheim;
mod plane;
mod prepared;
pub mod rational;
mod refine;
mod rotation;
mod scale;
mod sym;
#[cfg(test)]
mod test_pairs;
mod track;
pub mod wang;

pub use dimension::{
    ellipse_angle, ellipse_quaternion, ellipse_semi_axes, embed_form, Dimension, PLANE_NORMAL,
};
pub use ellipsoid::{
    ellipsoid_volume, equivalent_diameter, sphere_diameter, Ellipsoid, ShapeError,
    QUATERNION_NORM_TOL,
};
pub use error::ContactError;
pub(crate) use geometry::{contact_fast_prepared, response_geometry};
pub use geometry::{
    contact_geometry, contact_geometry_fast, contact_geometry_fast_prepared, ContactGeometry,
};
pub use ldl::MIN_RELATIVE_PIVOT;
pub use method::{Answer, Method, Timing, UnknownMethod};
pub use overlap::{overlaps, overlaps_prepared, DECISION_SAFETY};
pub use perram_wertheim::{
    contact_function, contact_function_fast, contact_functions, contact_functions_fast,
    fast_condition, lambda_bound, mu2_bound, CORRECTOR_SWITCH_GAIN, CUBIC_TERM_TOL,
    FAST_MAX_CONDITION, FAST_ROUNDING, FAST_TOL, FORM_MAX_CONDITION, GAIN_TOL, HALLEY_FINAL_GAIN,
    MAX_ITERATIONS, NEAR_END, SINGULAR_PIVOT,
};
pub use plane::{
    contact_function_2d, contact_function_fast_2d, contact_functions_2d, contact_functions_fast_2d,
    ellipse_form, embed_pair, in_plane_terms, overlaps_2d, plane_z, Sym2, Vec2,
};
pub use prepared::PreparedEllipsoid;
pub use refine::{GAIN_ROUNDING_TOL, REFINEMENT_TOL};
pub use rotation::{rotation_column, rotation_matrix};
pub(crate) use sym::dot;
pub(crate) use track::{contact_tracked, Touch};

/// A vector in 3D: `[x, y, z]`.
pub type Vec3 = [f64; 3];
/// A symmetric 3×3 matrix stored as its upper triangle, row-major:
/// `[m00, m01, m02, m11, m12, m22]`.
pub type Sym3 = [f64; 6];

/// Why an iterative routine stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Stop {
    /// The answer was found without iterating (closed form, e.g. `r12 = 0`).
    Exact,
    /// The stopping test was met: the answer is accurate to the documented tolerance.
    Converged,
    /// The iteration cap was reached before the stopping test was met. The result is the
    /// best estimate so far and must not be trusted as a decision.
    MaxIterations,
}

/// The value of the contact function and where it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// μ², the maximum of `f(λ) = λ(1−λ) r12ᵀ[(1−λ)Q1 + λQ2]⁻¹ r12` over `λ ∈ [0, 1]`.
    /// `μ² < 1`: the ellipsoids overlap; `μ² > 1`: they are apart.
    pub mu2: f64,
    /// The maximiser λ.
    pub lambda: f64,
    /// Why the solver stopped.
    pub stop: Stop,
    /// Iterations done.
    pub iterations: u32,
}
