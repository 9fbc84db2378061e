use thiserror::Error;

/// Why a contact query could not be answered.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ContactError {
    /// An input value is NaN or infinite.
    #[error("{what}[{index}] is not finite: {value}")]
    NotFinite {
        /// Which input: `"r12"`, `"q1"` or `"q2"`.
        what: &'static str,
        /// Index of the offending component.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A quadratic form is not symmetric positive definite (negative, indefinite or
    /// singular): its LDLᵀ factorisation met a pivot that is not strictly positive.
    #[error("{what} is not positive definite: pivot {pivot} of its LDLᵀ factorisation is {value}")]
    NotPositiveDefinite {
        /// Which input: `"q1"` or `"q2"`.
        what: &'static str,
        /// Index (0–2) of the failing pivot.
        pivot: usize,
        /// The pivot's value.
        value: f64,
    },
    /// An intermediate quantity overflowed to infinity (inputs too large to handle in
    /// double precision).
    #[error("overflow while computing {what}")]
    Overflow {
        /// The quantity that overflowed.
        what: &'static str,
    },
    /// Both quadratic forms are singular along a common direction (two coplanar flat
    /// discs, two needles, a point and anything singular): `(1−λ)Q1 + λQ2` is singular
    /// for every λ, and μ² is not defined.
    #[error(
        "q1 and q2 are both singular along a common direction: (1−λ)q1 + λq2 is singular \
         for every λ, so μ² is not defined"
    )]
    CommonNullDirection,
    /// The centres coincide, so the contact normal is undefined.
    #[error("the centres coincide: the contact normal is undefined")]
    CoincidentCentres,
    /// The iteration cap was reached before a decision could be proved.
    #[error("no decision after {iterations} iterations")]
    NotConverged {
        /// Iterations done.
        iterations: u32,
    },
}
