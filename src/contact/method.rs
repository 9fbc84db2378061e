//! The contact methods by name, for the command line, tests and benchmarks.

use super::{
    contact_function, contact_function_fast, contact_functions, contact_functions_fast, overlaps,
    rational::contact_function_rational, wang, Contact, ContactError, Stop, Sym3, Vec3,
};
use std::fmt;
use std::str::FromStr;

/// A way of answering the contact question for a pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// [`contact_function`]: Halley on the rational form in double, then Newton on a
    /// residual refined in double-double.
    Accurate,
    /// [`contact_functions`]: the accurate method for eight pairs at a time in vector
    /// lanes, bitwise the same values. Its time is per pair.
    Batch,
    /// [`contact_function_fast`]: the Halley predictor only.
    Fast,
    /// [`contact_functions_fast`]: the fast method eight pairs at a time, bitwise the
    /// same values. Its time is per pair.
    BatchFast,
    /// [`contact_function_rational`]: root of the degree-6 numerator of f′.
    Rational,
    /// [`overlaps`]: the yes/no decision with early exits.
    Overlap,
    /// [`wang::separated`]: the Wang–Wang–Kim algebraic separation test (yes/no).
    Wang,
}

/// What a method answers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Answer {
    /// The contact function, its maximiser and why the solver stopped.
    Value {
        /// μ².
        mu2: f64,
        /// λ.
        lambda: f64,
        /// Why the solver stopped.
        stop: Stop,
    },
    /// Whether the pair overlaps.
    Overlap(bool),
}

impl Method {
    /// Every method, in the order reports list them.
    pub const ALL: [Method; 7] = [
        Method::Accurate,
        Method::Batch,
        Method::Fast,
        Method::BatchFast,
        Method::Rational,
        Method::Overlap,
        Method::Wang,
    ];

    /// The method's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Accurate => "accurate",
            Method::Batch => "batch",
            Method::Fast => "fast",
            Method::BatchFast => "batch-fast",
            Method::Rational => "rational",
            Method::Overlap => "overlap",
            Method::Wang => "wang",
        }
    }

    /// Whether the method answers yes/no rather than μ².
    pub fn is_decision(self) -> bool {
        matches!(self, Method::Overlap | Method::Wang)
    }

    /// Answers the contact question for one pair (the batch methods: as the method whose
    /// values they give).
    #[inline]
    pub fn evaluate(self, r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<Answer, ContactError> {
        Ok(match self {
            Method::Accurate | Method::Batch => value(contact_function(r12, q1, q2)?),
            Method::Fast | Method::BatchFast => value(contact_function_fast(r12, q1, q2)?),
            Method::Rational => value(contact_function_rational(r12, q1, q2)?),
            Method::Overlap => Answer::Overlap(overlaps(r12, q1, q2)?),
            Method::Wang => Answer::Overlap(!wang::separated(r12, q1, q2)?),
        })
    }

    /// Answers the contact question for every pair, in order: the batch methods eight
    /// at a time, the others one by one.
    pub fn evaluate_all(self, pairs: &[(Vec3, Sym3, Sym3)]) -> Vec<Result<Answer, ContactError>> {
        let values = |all: Vec<Result<Contact, ContactError>>| {
            all.into_iter().map(|c| c.map(value)).collect()
        };
        match self {
            Method::Batch => values(contact_functions(pairs)),
            Method::BatchFast => values(contact_functions_fast(pairs)),
            _ => pairs
                .iter()
                .map(|(r12, q1, q2)| self.evaluate(r12, q1, q2))
                .collect(),
        }
    }
}

fn value(c: Contact) -> Answer {
    Answer::Value {
        mu2: c.mu2,
        lambda: c.lambda,
        stop: c.stop,
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown method name.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "unknown method {0:?}: expected one of accurate, batch, fast, batch-fast, rational, overlap, wang"
)]
pub struct UnknownMethod(pub String);

impl FromStr for Method {
    type Err = UnknownMethod;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownMethod(s.to_string()))
    }
}

/// Run time of a method over a set of pairs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Passes made over the whole set.
    pub rounds: usize,
    /// Median over rounds of the mean time per call, in nanoseconds.
    pub ns_per_call_median: f64,
    /// Fastest round's mean time per call, in nanoseconds.
    pub ns_per_call_min: f64,
}

impl Method {
    /// Times the method over `pairs`: whole passes over the set, repeated until at
    /// least `min_rounds` passes and `min_seconds` have elapsed. Only the calls are
    /// timed; errors are answers like any other (their cost counts). For
    /// the batch methods a pass is one call on the whole set, and "per call" is per pair.
    pub fn time(self, pairs: &[(Vec3, Sym3, Sym3)], min_rounds: usize, min_seconds: f64) -> Timing {
        use std::hint::black_box;
        use std::time::Instant;
        let mut per_call = Vec::new();
        let start = Instant::now();
        let n = pairs.len().max(1) as f64;
        while per_call.len() < min_rounds || start.elapsed().as_secs_f64() < min_seconds {
            let t = Instant::now();
            if self == Method::Batch {
                black_box(contact_functions(black_box(pairs)));
            } else if self == Method::BatchFast {
                black_box(contact_functions_fast(black_box(pairs)));
            } else {
                for (r, q1, q2) in pairs {
                    let _ = black_box(self.evaluate(black_box(r), black_box(q1), black_box(q2)));
                }
            }
            per_call.push(t.elapsed().as_nanos() as f64 / n);
        }
        per_call.sort_by(f64::total_cmp);
        Timing {
            rounds: per_call.len(),
            ns_per_call_median: per_call[per_call.len() / 2],
            ns_per_call_min: per_call[0],
        }
    }
}
