//! The law a panel of the statistics figure compares its values with: a density curve
//! on the law's support, or a value.

use crate::laws::{Distribution, Moments, VonMises};

/// Points on a target density curve: at 400 points a curve over a 500-pixel axis has a
/// vertex every pixel or so, and looks smooth.
const CURVE_POINTS: usize = 400;

/// Target curves are drawn within this many standard deviations of the untruncated
/// law's centre: beyond 8, a normal density is below `e⁻³²` ≈ 10⁻¹⁴ of its peak.
pub(super) const CURVE_SIGMAS: f64 = 8.0;

/// The law a panel compares its values with.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Target {
    /// A density: `(x, f(x))` from the lower cutoff to the upper, starting and ending
    /// at 0 so that truncation shows as a step.
    Curve(Vec<(f64, f64)>),
    /// A point mass (a constant or a fixed law).
    Value(f64),
}

impl Target {
    /// The smallest and largest `x` of the law.
    pub(super) fn range(&self) -> (f64, f64) {
        match self {
            Self::Curve(points) => (
                points.first().map_or(0.0, |p| p.0),
                points.last().map_or(0.0, |p| p.0),
            ),
            Self::Value(v) => (*v, *v),
        }
    }
}

/// The density curve of a law, or its value for a constant.
///
/// The curve is drawn on the support, clipped to [`CURVE_SIGMAS`] standard deviations
/// of the untruncated law about its centre so that a narrow law between wide cutoffs
/// still gets its points where its mass is.
pub(super) fn distribution_target(law: &Distribution) -> Target {
    let (min, max) = law.support();
    let (lo, hi) = match *law {
        Distribution::Constant { value } => return Target::Value(value),
        Distribution::Uniform { .. } => (min, max),
        Distribution::Normal { mean, std, .. } => (
            min.max(mean - CURVE_SIGMAS * std),
            max.min(mean + CURVE_SIGMAS * std),
        ),
        Distribution::LogNormal {
            sigma, scale, loc, ..
        } => (
            min.max(loc + scale * (-CURVE_SIGMAS * sigma).exp()),
            max.min(loc + scale * (CURVE_SIGMAS * sigma).exp()),
        ),
        Distribution::Table(_) => (min, max),
        Distribution::Empirical(ref e) => return Target::Curve(histogram_curve(&e.sorted)),
    };
    let (lo, hi) = if lo < hi { (lo, hi) } else { (min, max) };
    Target::Curve(curve(lo, hi, |x| law.pdf(x)))
}

/// Bins of the density drawn for a measured (empirical) law.
const EMPIRICAL_BINS: usize = 24;

/// The histogram density of sorted `values` as a step curve, for a measured law (its
/// point masses have no density to draw).
pub(super) fn histogram_curve(values: &[f64]) -> Vec<(f64, f64)> {
    let (lo, hi) = (values[0], values[values.len() - 1]);
    if !(hi > lo) {
        return vec![(lo, 0.0), (hi, 0.0)];
    }
    let width = (hi - lo) / EMPIRICAL_BINS as f64;
    let mut counts = [0usize; EMPIRICAL_BINS];
    for v in values {
        counts[(((v - lo) / width) as usize).min(EMPIRICAL_BINS - 1)] += 1;
    }
    let mut points = vec![(lo, 0.0)];
    for (k, c) in counts.iter().enumerate() {
        let h = *c as f64 / (values.len() as f64 * width);
        let x0 = lo + k as f64 * width;
        points.push((x0, h));
        points.push((x0 + width, h));
    }
    points.push((hi, 0.0));
    points
}

/// The window of a tilt law's curve (radians): its window, clipped to
/// [`CURVE_SIGMAS`] spreads `1/√κ` about the mean.
pub(super) fn tilt_curve_window(law: &VonMises) -> (f64, f64) {
    let (lo, hi) = law.window();
    let half = CURVE_SIGMAS / law.kappa.sqrt();
    let (clo, chi) = (lo.max(law.mean - half), hi.min(law.mean + half));
    if clo < chi {
        (clo, chi)
    } else {
        (lo, hi)
    }
}

/// `(x, f(x))` at [`CURVE_POINTS`] points on `[lo, hi]`, between `(lo, 0)` and `(hi, 0)`.
pub(super) fn curve(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
    let mut points = Vec::with_capacity(CURVE_POINTS + 2);
    points.push((lo, 0.0));
    for k in 0..CURVE_POINTS {
        let x = lo + (hi - lo) * k as f64 / (CURVE_POINTS - 1) as f64;
        points.push((x, f(x)));
    }
    points.push((hi, 0.0));
    points
}

/// The legend entry of a law: its family.
pub(super) fn law_name(law: &Distribution) -> String {
    format!("target {}", law.family())
}

/// Mean and standard deviation of a law with a density (`None` for a constant).
pub(super) fn law_moments(law: &Distribution) -> Option<Moments> {
    match law {
        Distribution::Constant { .. } => None,
        _ => Some(Moments {
            mean: law.mean(),
            std: law.std(),
        }),
    }
}
