//! The other end of "the longest grain fits in the box": the smallest grains must be
//! numbers the packing can work with.

use crate::contact::Dimension;
use crate::io::scene::error::{SceneError, Source};
use crate::io::scene::raw::RawPhase;
use crate::laws::Distribution;
use crate::scene::Phase;
use toml::Spanned;

/// The smallest squared semi-axis a grain may have: `f64::MIN_POSITIVE / ε²` (4.5e-277:
/// semi-axes down to 6.7e-139). The loop shrinks the grains by the smallest μ of their
/// random start, which centres rounded to the box's ulp keep above about ε; a grain so
/// shrunk must still have a quadratic form `(s a)²` of normal doubles, or a pivot of its
/// factorisation is 0 or NaN and packing fails.
pub const MIN_SQUARED_SEMI_AXIS: f64 = f64::MIN_POSITIVE / (f64::EPSILON * f64::EPSILON);

/// Refuses a phase whose smallest grain has a squared semi-axis below
/// [`MIN_SQUARED_SEMI_AXIS`], or a volume (an area in 2D) below the normal doubles, where
/// the scene's volumes, shares and fractions become 0 (fuzz target `scene_keys`: grains of
/// 1e-300 in a box of 20 validated, then failed to pack). Names the size's lower bound
/// (or the measured table) and its value.
pub(super) fn resolved(
    src: &Source,
    key: &str,
    raw: &Spanned<RawPhase>,
    phase: &Phase,
) -> Result<(), SceneError> {
    let d = phase.size.support().0;
    let (a, measure) = (
        phase.min_semi_axis(),
        phase.dimension.measure_of_diameter(d),
    );
    if a * a >= MIN_SQUARED_SEMI_AXIS && measure >= f64::MIN_POSITIVE {
        return Ok(());
    }
    let p = raw.get_ref();
    let param = match phase.size {
        Distribution::Constant { .. } => "value",
        Distribution::Table(_) => "x",
        _ => "min",
    };
    let (name, at) = match (&p.size, &p.measured) {
        (Some(s), _) => {
            let at = match param {
                "x" => s.get_ref().x.as_ref().map(|v| v.span()),
                _ => s.get_ref().param(param).map(|v| v.span()),
            };
            (format!("{key}.size.{param}"), at.unwrap_or(s.span()))
        }
        (None, Some(m)) => (format!("{key}.measured"), m.span()),
        (None, None) => (format!("{key}.size"), raw.span()),
    };
    let what = match phase.dimension {
        Dimension::Two => "area",
        Dimension::Three => "volume",
    };
    Err(src.invalid(
        name,
        at,
        format!(
            "the smallest grains ({d:e} across, semi-axes down to {a:e}, {what} {measure:e}) \
             are below what the packing resolves in doubles: it needs semi-axes of at least \
             {:.1e} and a {what} of at least {:.1e} (the smallest normal double)",
            MIN_SQUARED_SEMI_AXIS.sqrt(),
            f64::MIN_POSITIVE
        ),
    ))
}
