//! The achieved crystal texture: every grain's crystal orientation in the sample frame
//! ([`crystal_orientations`]) and, per phase, the angle that measures its texture with
//! the law that angle has under the target ([`measure_textures`]). Computed once per
//! run and read by `summary.json` ([`crate::io::report::TextureSummary`]) and by the
//! texture panels of `statistics.png`.

use crate::laws::{ks_distance, Fisher, Moments};
use crate::run::RunResult;
use crate::scene::{fibre_angle, random_angle_cdf, rotation_angle, Scene, Texture};
use std::f64::consts::PI;

/// Steps of the Simpson rule for the moments of a target law, `∫₀^π (1 − F(θ)) dθ`
/// and `∫₀^π 2θ (1 − F(θ)) dθ`: far below 1e-10 of error for these smooth CDFs.
const MOMENT_STEPS: usize = 4096;

/// Two measured angles closer than this (radians) are one value when compared with the
/// atoms of a file's law: a grain drawn from a file row and measured after taking its
/// shape rotation out again (two Hamilton products) carries a rounding of a few ε, far
/// below this; distinct rows of a file written with 17 digits lie further apart, or
/// are the same orientation for any solver.
pub const ATOM_TIE: f64 = 1e-12;

/// The KS distance a sample of `n` exceeds with probability 5 % under its law (the
/// asymptotic Kolmogorov quantile 1.358/√n; conservative for a law with atoms).
pub fn ks_critical_5pct(n: usize) -> f64 {
    1.358 / (n as f64).sqrt()
}

/// The law of a phase's texture angle under its target texture.
#[derive(Debug, Clone, PartialEq)]
pub enum AngleLaw {
    /// The rotation angle ω of a uniformly random rotation (Haar measure on SO(3)):
    /// density `(1 − cos ω)/π` on `[0, π]`, CDF `(ω − sin ω)/π`.
    Haar,
    /// The angle to a fibre drawn from the von Mises–Fisher law.
    Fisher(Fisher),
    /// All at 0 (a fixed orientation, measured as the angle from it).
    Zero,
    /// The rotation angles of a file's orientations, each with its weight: `angles`
    /// sorted, `weights` summing to 1.
    Atoms {
        /// Rotation angles, ascending (radians).
        angles: Vec<f64>,
        /// Their probabilities.
        weights: Vec<f64>,
    },
}

impl AngleLaw {
    /// The file law of `orientations` with `weights` (any positive scale).
    pub fn of_file(orientations: &[[f64; 4]], weights: &[f64]) -> Self {
        let total: f64 = weights.iter().sum();
        let mut atoms: Vec<(f64, f64)> = orientations
            .iter()
            .zip(weights)
            .map(|(&q, &w)| (rotation_angle(q), w / total))
            .collect();
        atoms.sort_by(|a, b| a.0.total_cmp(&b.0));
        Self::Atoms {
            angles: atoms.iter().map(|a| a.0).collect(),
            weights: atoms.iter().map(|a| a.1).collect(),
        }
    }

    /// `P(angle ≤ x)`.
    pub fn cdf(&self, x: f64) -> f64 {
        match self {
            Self::Haar => random_angle_cdf(x),
            Self::Fisher(f) => f.angle_cdf(x),
            Self::Zero => f64::from(x >= 0.0),
            Self::Atoms { angles, weights } => {
                let k = angles.partition_point(|&a| a <= x);
                weights[..k].iter().sum::<f64>().min(1.0)
            }
        }
    }

    /// The density at `x` (radians), for the laws that have one.
    pub fn pdf(&self, x: f64) -> Option<f64> {
        match self {
            Self::Haar => Some(if (0.0..=PI).contains(&x) {
                (1.0 - x.cos()) / PI
            } else {
                0.0
            }),
            Self::Fisher(f) => Some(f.angle_pdf(x)),
            Self::Zero | Self::Atoms { .. } => None,
        }
    }

    /// Mean and standard deviation (radians): exact sums for atoms, else from the CDF
    /// by Simpson's rule on 4096 steps.
    pub fn moments(&self) -> Moments {
        match self {
            Self::Zero => Moments {
                mean: 0.0,
                std: 0.0,
            },
            Self::Atoms { angles, weights } => {
                let mean: f64 = angles.iter().zip(weights).map(|(a, w)| a * w).sum();
                let var: f64 = angles
                    .iter()
                    .zip(weights)
                    .map(|(a, w)| w * (a - mean).powi(2))
                    .sum();
                Moments {
                    mean,
                    std: var.sqrt(),
                }
            }
            _ => {
                let survival = |x: f64| 1.0 - self.cdf(x);
                let mean = simpson(survival);
                let second = simpson(|x| 2.0 * x * survival(x));
                Moments {
                    mean,
                    std: (second - mean * mean).max(0.0).sqrt(),
                }
            }
        }
    }

    /// The Kolmogorov–Smirnov distance of `sample` from this law: `sup |Fₙ − F|`.
    /// `None` for an empty sample or the fixed law (whose spread is its maximum).
    pub fn ks_distance(&self, sample: &[f64]) -> Option<f64> {
        match self {
            Self::Zero => None,
            Self::Atoms { angles, weights } => ks_distance_to_atoms(sample, angles, weights),
            _ => ks_distance(sample, |x| self.cdf(x)),
        }
    }
}

/// `∫₀^π f` by Simpson's rule on [`MOMENT_STEPS`] steps.
fn simpson(f: impl Fn(f64) -> f64) -> f64 {
    let h = PI / MOMENT_STEPS as f64;
    let inner: f64 = (1..MOMENT_STEPS)
        .map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h))
        .sum();
    h / 3.0 * (f(0.0) + inner + f(PI))
}

/// `sup_x |Fₙ(x) − G(x)|` for the empirical CDF `Fₙ` of `sample` and the step CDF `G`
/// of `angles` (ascending) with `weights`: both are right-continuous steps, so the
/// supremum is reached at a jump of one of them, where both are evaluated after every
/// value within [`ATOM_TIE`] of it.
fn ks_distance_to_atoms(sample: &[f64], angles: &[f64], weights: &[f64]) -> Option<f64> {
    if sample.is_empty() {
        return None;
    }
    let mut s = sample.to_vec();
    s.sort_by(f64::total_cmp);
    let mut jumps: Vec<f64> = s.iter().chain(angles).copied().collect();
    jumps.sort_by(f64::total_cmp);
    let n = s.len() as f64;
    let (mut i, mut j, mut g, mut d) = (0, 0, 0.0, 0.0f64);
    let mut k = 0;
    while k < jumps.len() {
        // The cluster of jumps within ATOM_TIE of each other, ending at `x`.
        let mut x = jumps[k];
        while k + 1 < jumps.len() && jumps[k + 1] - x <= ATOM_TIE {
            k += 1;
            x = jumps[k];
        }
        k += 1;
        while i < s.len() && s[i] <= x {
            i += 1;
        }
        while j < angles.len() && angles[j] <= x {
            g += weights[j];
            j += 1;
        }
        d = d.max((i as f64 / n - g).abs());
    }
    Some(d)
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

/// One phase's texture, measured: the angle of each of its grains and the law of that
/// angle under the target.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureMeasure {
    /// Index of the phase in the scene.
    pub phase: usize,
    /// The angle measured: `"rotation angle"` (random, file), `"angle to the fibre"`
    /// (fibre) or `"angle from the fixed orientation"` (fixed).
    pub measure: &'static str,
    /// The angle of each grain of the phase, radians, in grain id order.
    pub angles: Vec<f64>,
    /// Its law under the target texture.
    pub law: AngleLaw,
    /// Kolmogorov–Smirnov distance of `angles` from `law` ([`AngleLaw::ks_distance`]).
    pub ks_distance: Option<f64>,
}

/// Each phase's texture measured on the written orientations `crystals` (grain id
/// order, from [`crystal_orientations`]). For a texture relative to the shape, the
/// shape rotation is taken out again (`q_shape⁻¹ ⊗ q`), so the law is checked where it
/// was drawn.
pub fn measure_textures(
    scene: &Scene,
    result: &RunResult,
    crystals: &[[f64; 4]],
) -> Vec<TextureMeasure> {
    scene
        .phases
        .iter()
        .enumerate()
        .map(|(p, phase)| {
            let t = &phase.texture;
            let drawn = result
                .packing
                .grains
                .iter()
                .zip(crystals)
                .filter(|(g, _)| g.phase == p)
                .map(|(g, &q)| {
                    if t.relative_to_shape {
                        multiply(conjugate(g.quaternion), q)
                    } else {
                        q
                    }
                });
            // A measured table's own crystals are the target: their rotation angles,
            // each row weighted alike (a texture key beside such a table is refused).
            let table = phase.measured.as_ref().filter(|m| m.has_crystals());
            let (measure, angles, law): (_, Vec<f64>, _) = match &t.texture {
                _ if table.is_some() => {
                    let rows: Vec<[f64; 4]> = table
                        .into_iter()
                        .flat_map(|m| m.grains.iter())
                        .filter_map(|g| g.crystal)
                        .collect();
                    let weights = vec![1.0; rows.len()];
                    (
                        "rotation angle",
                        drawn.map(rotation_angle).collect(),
                        AngleLaw::of_file(&rows, &weights),
                    )
                }
                Texture::Random => (
                    "rotation angle",
                    drawn.map(rotation_angle).collect(),
                    AngleLaw::Haar,
                ),
                Texture::Fixed { quaternion } => (
                    "angle from the fixed orientation",
                    drawn
                        .map(|q| rotation_angle(multiply(conjugate(*quaternion), q)))
                        .collect(),
                    AngleLaw::Zero,
                ),
                Texture::Fibre {
                    crystal,
                    sample,
                    kappa,
                } => (
                    "angle to the fibre",
                    drawn.map(|q| fibre_angle(q, *crystal, *sample)).collect(),
                    AngleLaw::Fisher(Fisher { kappa: *kappa }),
                ),
                Texture::File {
                    orientations,
                    weights,
                    ..
                } => (
                    "rotation angle",
                    drawn.map(rotation_angle).collect(),
                    AngleLaw::of_file(orientations, weights),
                ),
            };
            TextureMeasure {
                phase: p,
                measure,
                ks_distance: law.ks_distance(&angles),
                angles,
                law,
            }
        })
        .collect()
}

/// `q⁻¹` of a unit quaternion.
fn conjugate(q: [f64; 4]) -> [f64; 4] {
    [q[0], -q[1], -q[2], -q[3]]
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
    fn the_haar_rotation_angle_has_its_closed_form_moments() {
        // E ω = π/2 + 2/π; E ω² = π²/3 + 2 (∫ ω²(1 − cos ω)/π over [0, π]).
        let m = AngleLaw::Haar.moments();
        let mean = PI / 2.0 + 2.0 / PI;
        let std = (PI * PI / 3.0 + 2.0 - mean * mean).sqrt();
        // Simpson's error at 4096 steps: far below 1e-10 for this smooth CDF.
        assert!((m.mean - mean).abs() < 1e-10, "{m:?}");
        assert!((m.std - std).abs() < 1e-10, "{m:?}");
    }

    #[test]
    fn a_sample_of_the_atoms_themselves_has_ks_distance_zero() {
        let law = AngleLaw::Atoms {
            angles: vec![0.5, 1.0, 2.0],
            weights: vec![0.25, 0.5, 0.25],
        };
        // Rounded by less than ATOM_TIE: still the atoms.
        let sample = [1.0 + 1e-15, 0.5, 2.0, 1.0 - 1e-15];
        assert_eq!(law.ks_distance(&sample), Some(0.0));
        // Every grain on the middle atom: Fₙ jumps to 1 at 1.0, G is 0.75 there and
        // 0.25 just below it.
        assert_eq!(law.ks_distance(&[1.0, 1.0]), Some(0.25));
        assert_eq!(law.cdf(1.0), 0.75);
        let m = law.moments();
        assert!((m.mean - 1.125).abs() < 1e-15);
    }
}
