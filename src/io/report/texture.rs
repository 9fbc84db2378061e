//! The achieved texture of each phase against its target law, for `summary.json`.

use crate::laws::{ks_distance, Fisher};
use crate::run::RunResult;
use crate::scene::{fibre_angle, random_angle_cdf, rotation_angle, Scene, Texture};
use serde::Serialize;
use std::f64::consts::PI;

/// The CDF of a target law of an angle.
type Law = Box<dyn Fn(f64) -> f64>;

/// Steps of the Simpson rule for a target law's mean angle, `∫₀^π (1 − F(θ)) dθ`.
const MEAN_STEPS: usize = 4096;

/// One phase's crystal orientations as written, against its texture.
#[derive(Debug, Clone, Serialize)]
pub struct TextureSummary {
    /// The phase's name.
    pub phase: String,
    /// `"random"`, `"fixed"`, `"fibre"` or `"file"`.
    pub kind: &'static str,
    /// Whether the texture is in the grains' own frames (then measured there).
    pub relative_to_shape: bool,
    /// Grains of the phase.
    pub grains: usize,
    /// The angle measured: `"rotation angle"` (random: its SO(3) law has CDF
    /// `(ω − sin ω)/π`), `"angle to the fibre"` (fibre: the von Mises–Fisher law's),
    /// `"angle from the fixed orientation"` (fixed: 0), or none (file).
    pub measure: Option<&'static str>,
    /// Mean of the measured angle over the grains, degrees.
    pub mean_deg: Option<f64>,
    /// Its mean under the target law, degrees.
    pub target_mean_deg: Option<f64>,
    /// Largest measured angle, degrees.
    pub max_deg: Option<f64>,
    /// Kolmogorov–Smirnov distance of the measured angles from the target law (random,
    /// fibre).
    pub ks_distance: Option<f64>,
    /// The KS distance a sample of this size exceeds with probability 5 %: `1.358/√n`.
    pub ks_critical_5pct: Option<f64>,
    /// Rows of the orientation file (file).
    pub file_rows: Option<usize>,
}

/// Every grain's crystal orientation in the sample frame, in grain id order: its
/// drawn orientation ([`GrainSpec::crystal`](crate::scene::GrainSpec::crystal)),
/// composed with its packed shape rotation where the phase's texture is relative to
/// the shape.
pub fn crystal_orientations(scene: &Scene, result: &RunResult) -> Vec<[f64; 4]> {
    result
        .packing
        .grains
        .iter()
        .map(|g| {
            let drawn = result.specs[g.id as usize].crystal;
            scene.phases[g.phase].texture.in_sample(drawn, g.quaternion)
        })
        .collect()
}

/// The texture summary of every phase, from the written orientations `crystals`
/// (grain id order): for a texture relative to the shape, the shape rotation is taken
/// out again (`q_shape⁻¹ ⊗ q`), so the law is checked where it was drawn.
pub fn texture_summaries(
    scene: &Scene,
    result: &RunResult,
    crystals: &[[f64; 4]],
) -> Vec<TextureSummary> {
    scene
        .phases
        .iter()
        .enumerate()
        .map(|(p, phase)| {
            let t = &phase.texture;
            let drawn: Vec<[f64; 4]> = result
                .packing
                .grains
                .iter()
                .zip(crystals)
                .filter(|(g, _)| g.phase == p)
                .map(|(g, &q)| {
                    if t.relative_to_shape {
                        let s = g.quaternion;
                        multiply([s[0], -s[1], -s[2], -s[3]], q)
                    } else {
                        q
                    }
                })
                .collect();
            let n = drawn.len();
            let (measure, angles, cdf): (_, Vec<f64>, Option<Law>) = match &t.texture {
                Texture::Random => (
                    Some("rotation angle"),
                    drawn.iter().map(|&q| rotation_angle(q)).collect(),
                    Some(Box::new(random_angle_cdf)),
                ),
                Texture::Fixed { quaternion } => {
                    let inv = [
                        quaternion[0],
                        -quaternion[1],
                        -quaternion[2],
                        -quaternion[3],
                    ];
                    (
                        Some("angle from the fixed orientation"),
                        drawn
                            .iter()
                            .map(|&q| rotation_angle(multiply(inv, q)))
                            .collect(),
                        None,
                    )
                }
                Texture::Fibre {
                    crystal,
                    sample,
                    kappa,
                } => {
                    let kappa = *kappa;
                    (
                        Some("angle to the fibre"),
                        drawn
                            .iter()
                            .map(|&q| fibre_angle(q, *crystal, *sample))
                            .collect(),
                        Some(Box::new(move |x| Fisher { kappa }.angle_cdf(x))),
                    )
                }
                Texture::File { .. } => (None, Vec::new(), None),
            };
            let deg = |x: f64| x.to_degrees();
            let mean = (!angles.is_empty()).then(|| deg(angles.iter().sum::<f64>() / n as f64));
            let max = angles.iter().copied().reduce(f64::max).map(deg);
            let target_mean = match (&t.texture, &cdf) {
                (Texture::Fixed { .. }, _) => Some(0.0),
                (_, Some(f)) => Some(deg(mean_angle(f))),
                _ => None,
            };
            let ks = cdf.as_ref().and_then(|f| ks_distance(&angles, f));
            TextureSummary {
                phase: phase.name.clone(),
                kind: t.texture.kind(),
                relative_to_shape: t.relative_to_shape,
                grains: n,
                measure,
                mean_deg: mean,
                target_mean_deg: target_mean,
                max_deg: max,
                ks_distance: ks,
                ks_critical_5pct: ks.map(|_| 1.358 / (n as f64).sqrt()),
                file_rows: match &t.texture {
                    Texture::File { orientations, .. } => Some(orientations.len()),
                    _ => None,
                },
            }
        })
        .collect()
}

/// `∫₀^π (1 − F(θ)) dθ`, the mean of an angle on [0, π] with CDF `F` (Simpson).
fn mean_angle(cdf: &dyn Fn(f64) -> f64) -> f64 {
    let h = PI / MEAN_STEPS as f64;
    let f = |i: usize| 1.0 - cdf(i as f64 * h);
    let inner: f64 = (1..MEAN_STEPS)
        .map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(i))
        .sum();
    h / 3.0 * (f(0) + inner + f(MEAN_STEPS))
}

/// The Hamilton product `a ⊗ b`.
fn multiply(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mean_rotation_angle_of_so3_is_pi_half_plus_two_over_pi() {
        let m = mean_angle(&random_angle_cdf);
        // Simpson's error at 4096 steps: far below 1e-10 for this smooth CDF.
        assert!((m - (PI / 2.0 + 2.0 / PI)).abs() < 1e-10, "{m}");
    }
}
