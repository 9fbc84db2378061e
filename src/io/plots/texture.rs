//! The texture panel of a phase: the angle that measures its crystal texture
//! ([`TextureMeasure`]), histogram against its law under the target, with the same
//! Kolmogorov–Smirnov distance as `summary.json`'s `textures`.
//!
//! - random: the rotation angle ω against the SO(3) (Haar) density `(1 − cos ω)/π`;
//! - fibre: the angle of the fibre's crystal direction to its sample direction against
//!   the von Mises–Fisher density;
//! - fixed: the angle from the fixed orientation, against the value 0;
//! - file: the rotation angle against that of the file's rows, with their weights
//!   (drawn as a weighted histogram).

use super::panel::Panel;
use super::target::{curve, Target, CURVE_SIGMAS};
use crate::io::texture::{ks_critical_5pct, AngleLaw, TextureMeasure};
use crate::laws::Moments;
use std::f64::consts::PI;

/// Bins of the weighted histogram drawn for a file's law.
const FILE_BINS: usize = 36;

/// The panel of `m`, angles in degrees and densities per degree.
pub(super) fn texture_panel(m: &TextureMeasure) -> Panel {
    let per_degree = PI / 180.0;
    let moments = m.law.moments();
    let ks = match m.ks_distance {
        Some(d) => format!(": KS {d:.3} (5 %: {:.3})", ks_critical_5pct(m.angles.len())),
        None => String::new(),
    };
    let (title, x_label, law, target) = match &m.law {
        AngleLaw::Haar => (
            format!("crystal rotation angle{ks}"),
            "rotation angle \u{3c9} of the crystal (degrees)",
            "target SO(3) uniform, (1 \u{2212} cos \u{3c9})/\u{3c0}".to_string(),
            Target::Curve(curve(0.0, 180.0, |t| {
                m.law.pdf(t.to_radians()).unwrap_or(0.0) * per_degree
            })),
        ),
        AngleLaw::Fisher(f) => {
            let hi = if f.kappa > 0.0 {
                (CURVE_SIGMAS / f.kappa.sqrt()).min(PI)
            } else {
                PI
            };
            (
                format!("crystal fibre{ks}"),
                "angle of the fibre to its sample direction (degrees)",
                format!("target von Mises\u{2013}Fisher, \u{3ba} = {}", f.kappa),
                Target::Curve(curve(0.0, hi.to_degrees(), |t| {
                    f.angle_pdf(t.to_radians()) * per_degree
                })),
            )
        }
        AngleLaw::Zero => (
            "crystal: fixed orientation".to_string(),
            "angle from the fixed orientation (degrees)",
            "target fixed".to_string(),
            Target::Value(0.0),
        ),
        AngleLaw::Atoms { angles, weights } => (
            format!("crystal rotation angle{ks}"),
            "rotation angle \u{3c9} of the crystal (degrees)",
            format!("the file\u{2019}s {} orientations", angles.len()),
            Target::Curve(weighted_histogram(angles, weights)),
        ),
    };
    Panel {
        title,
        x_label,
        y_label: "probability density (1/degree)",
        law,
        law_moments: (m.law != AngleLaw::Zero).then(|| Moments {
            mean: moments.mean.to_degrees(),
            std: moments.std.to_degrees(),
        }),
        target,
        packed: m.angles.iter().map(|a| a.to_degrees()).collect(),
        voxel: None,
        // In the title, with its 5 % critical value.
        ks_distance: None,
    }
}

/// The density of atoms at `angles` (radians, ascending) with `weights` (summing to
/// 1), in degrees, as a step curve on [`FILE_BINS`] bins over their range.
fn weighted_histogram(angles: &[f64], weights: &[f64]) -> Vec<(f64, f64)> {
    let lo = angles.first().map_or(0.0, |a| a.to_degrees());
    let hi = angles.last().map_or(0.0, |a| a.to_degrees());
    if !(hi > lo) {
        return vec![(lo, 0.0), (hi, 0.0)];
    }
    let width = (hi - lo) / FILE_BINS as f64;
    let mut mass = [0.0; FILE_BINS];
    for (a, w) in angles.iter().zip(weights) {
        mass[(((a.to_degrees() - lo) / width) as usize).min(FILE_BINS - 1)] += w;
    }
    let mut points = vec![(lo, 0.0)];
    for (k, m) in mass.iter().enumerate() {
        let x0 = lo + k as f64 * width;
        points.push((x0, m / width));
        points.push((x0 + width, m / width));
    }
    points.push((hi, 0.0));
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The area under a step or sampled curve by the trapezoid rule.
    fn area(points: &[(f64, f64)]) -> f64 {
        points
            .windows(2)
            .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
            .sum()
    }

    #[test]
    fn target_curves_are_densities_per_degree() {
        let measure = |law| TextureMeasure {
            phase: 0,
            measure: "rotation angle",
            angles: vec![1.0, 2.0],
            law,
            ks_distance: Some(0.1),
        };
        // Trapezoid rule on 399 intervals of a smooth density: error ~1e-5.
        let Target::Curve(haar) = texture_panel(&measure(AngleLaw::Haar)).target else {
            panic!("a density")
        };
        assert!((area(&haar) - 1.0).abs() < 1e-4);
        // A step curve integrates exactly (up to rounding).
        let atoms = AngleLaw::Atoms {
            angles: vec![0.1, 0.5, 2.5],
            weights: vec![0.2, 0.3, 0.5],
        };
        let panel = texture_panel(&measure(atoms));
        let Target::Curve(file) = panel.target else {
            panic!("a density")
        };
        assert!((area(&file) - 1.0).abs() < 1e-12);
        assert!(panel.title.contains("KS 0.100"), "{}", panel.title);
    }
}
