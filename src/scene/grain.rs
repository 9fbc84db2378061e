//! Drawing grains from a scene: which phase, what size, what shape, which way round.

use super::{triaxial_semi_axes, GrainCount, Orientation, Phase, Scene, MAX_GRAINS};
use crate::contact::{ellipse_quaternion, ellipse_semi_axes, Dimension, PLANE_NORMAL};
use crate::laws::MAX_DRAWS;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use thiserror::Error;

/// The ChaCha8 stream of the crystal orientations (the shapes use stream 0).
pub const CRYSTAL_STREAM: u64 = 1;

/// One grain as drawn, before packing: its target shape and orientation.
///
/// The grain is a spheroid with semi-axes `[a1, a2, a3]`, `a2 = a3`, of the same volume
/// as the sphere of diameter `d`: with aspect ratio `α = a1/a2`,
/// `a2 = a3 = (d/2) α^{−1/3}` and `a1 = α a2`, so `a1 a2 a3 = (d/2)³`. `α > 1` is prolate
/// (a needle along the first axis), `α < 1` oblate (a platelet whose normal is the
/// first axis). Semi-axis `k` lies along column `k` of the rotation of `quaternion`.
///
/// A triaxial grain (a phase with [`Triaxial`](super::Triaxial) laws) has
/// `a1 ≥ a2 ≥ a3` from its ratios `b/a`, `c/a` at the same volume
/// ([`triaxial_semi_axes`]), and `aspect_ratio = a1/a2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrainSpec {
    /// Index of the grain's phase in [`Scene::phases`].
    pub phase: usize,
    /// Target semi-axes `[a1, a2, a3]`.
    pub semi_axes: [f64; 3],
    /// Orientation `[w, x, y, z]` (Hamilton, unit norm, `w ≥ 0` for drawn ones).
    pub quaternion: [f64; 4],
    /// Equivalent-sphere diameter `d`.
    pub diameter: f64,
    /// Aspect ratio `α = a1/a2`.
    pub aspect_ratio: f64,
    /// Tilt angle `θ` in radians, for phases with a tilt orientation.
    pub tilt: Option<f64>,
    /// The unit axis the grain may turn about under [`Rotation::Axis`]: its phase's
    /// tilt axis; for a `fisher` phase its own first axis (its spin changes); `None`
    /// (it keeps its orientation) for other phases.
    ///
    /// [`Rotation::Axis`]: super::Rotation::Axis
    pub turn_axis: Option<[f64; 3]>,
    /// Crystal orientation as drawn from the phase's texture (see
    /// [`PhaseTexture::in_sample`](super::PhaseTexture::in_sample) for the grain's
    /// orientation in the sample): scalar-first unit quaternion, `q0 ≥ 0`. Identity
    /// until [`Scene::sample_crystals`] draws it.
    pub crystal: [f64; 4],
    /// An ellipsoid, or an ellipse embedded as one (see [`Dimension`]).
    pub dimension: Dimension,
}

impl GrainSpec {
    /// A grain of diameter `d` and aspect ratio `α`, oriented by `quaternion`.
    pub fn new(
        phase: usize,
        diameter: f64,
        aspect_ratio: f64,
        quaternion: [f64; 4],
        tilt: Option<f64>,
    ) -> Self {
        let a2 = 0.5 * diameter / aspect_ratio.cbrt();
        Self {
            phase,
            semi_axes: [aspect_ratio * a2, a2, a2],
            quaternion,
            diameter,
            aspect_ratio,
            tilt,
            turn_axis: None,
            crystal: [1.0, 0.0, 0.0, 0.0],
            dimension: Dimension::Three,
        }
    }

    /// An ellipse of equivalent-circle diameter `d` and aspect ratio `α = a1/a2`, its
    /// first semi-axis at angle `theta` from `x`: `a2 = (d/2) α^{−1/2}`, `a1 = α a2`
    /// (so `a1 a2 = (d/2)²`), embedded as [`ellipse_semi_axes`] turned about `z`, free
    /// to turn about `z`.
    pub fn ellipse(phase: usize, diameter: f64, aspect_ratio: f64, theta: f64) -> Self {
        let a2 = 0.5 * diameter / aspect_ratio.sqrt();
        Self {
            phase,
            semi_axes: ellipse_semi_axes(aspect_ratio * a2, a2),
            quaternion: ellipse_quaternion(theta),
            diameter,
            aspect_ratio,
            tilt: None,
            turn_axis: Some(PLANE_NORMAL),
            crystal: [1.0, 0.0, 0.0, 0.0],
            dimension: Dimension::Two,
        }
    }

    /// Target measure: volume `π d³/6`, or area `π d²/4` for an ellipse.
    pub fn volume(&self) -> f64 {
        match self.dimension {
            Dimension::Three => PI / 6.0 * self.diameter.powi(3),
            Dimension::Two => self.dimension.measure_of_diameter(self.diameter),
        }
    }
}

/// The aspect ratio `a1/a2` of a packed spheroid: its first semi-axis (the axis of
/// revolution) over its second (above 1 prolate, below 1 oblate).
///
/// ```
/// use grainpack::scene::aspect_ratio;
/// assert_eq!(aspect_ratio([3.0, 1.5, 1.5]), 2.0);
/// ```
pub fn aspect_ratio(semi_axes: [f64; 3]) -> f64 {
    semi_axes[0] / semi_axes[1]
}

/// Why grains could not be drawn from a valid scene. Each case has a probability
/// below e⁻⁵⁰ per draw, but is reported rather than looped on or ignored.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SampleError {
    /// Rejection sampling found no value inside the cutoffs.
    #[error("phase {phase} ({name}): no {quantity} inside its cutoffs after {draws} draws")]
    TooManyRejections {
        /// Phase index.
        phase: usize,
        /// Phase name.
        name: String,
        /// `"equivalent diameter"`, `"aspect ratio"`, `"shape ratio b/a"` (`c/a`, `c/b`),
        /// `"tilt angle"` or `"orientation angle"`.
        quantity: &'static str,
        /// Draws made.
        draws: usize,
    },
    /// Reaching the target fraction took more grains than the limit.
    #[error("more than {limit} grains were drawn without reaching the target fraction")]
    TooManyGrains {
        /// The limit.
        limit: usize,
    },
}

impl Phase {
    /// Draws one grain of this phase (`index` is the phase's index): diameter, then
    /// aspect ratio, then orientation.
    pub fn sample_grain<R: Rng + ?Sized>(
        &self,
        index: usize,
        rng: &mut R,
    ) -> Result<GrainSpec, SampleError> {
        let rejected = |quantity| SampleError::TooManyRejections {
            phase: index,
            name: self.name.clone(),
            quantity,
            draws: MAX_DRAWS,
        };
        if let Some(m) = &self.measured {
            return self
                .draw_measured(index, m, rng)
                .ok_or_else(|| rejected("measured grain's shape or orientation"));
        }
        let d = self
            .size
            .sample(rng)
            .ok_or_else(|| rejected("equivalent diameter"))?;
        if self.dimension == Dimension::Two {
            let alpha = (self.aspect_ratio.sample(rng)).ok_or_else(|| rejected("aspect ratio"))?;
            let (theta, tilt) = (self.orientation.sample_angle(rng))
                .ok_or_else(|| rejected("orientation angle"))?;
            return Ok(GrainSpec {
                tilt,
                ..GrainSpec::ellipse(index, d, alpha, theta)
            });
        }
        if let Some(shape) = &self.triaxial {
            let (beta, gamma) = shape.sample(rng).map_err(rejected)?;
            let (q, _) = self
                .orientation
                .sample(rng)
                .ok_or_else(|| rejected("orientation angle"))?;
            let semi_axes = triaxial_semi_axes(d, beta, gamma);
            return Ok(GrainSpec {
                semi_axes,
                aspect_ratio: 1.0 / beta,
                turn_axis: turn_axis(&self.orientation, q),
                ..GrainSpec::new(index, d, 1.0, q, None)
            });
        }
        let alpha = self
            .aspect_ratio
            .sample(rng)
            .ok_or_else(|| rejected("aspect ratio"))?;
        let (q, tilt) = self
            .orientation
            .sample(rng)
            .ok_or_else(|| rejected("tilt angle"))?;
        Ok(GrainSpec {
            turn_axis: turn_axis(&self.orientation, q),
            ..GrainSpec::new(index, d, alpha, q, tilt)
        })
    }
}

impl Scene {
    /// The grains of the phases that take exactly their measured grains: each such
    /// phase's rows in table order, phase after phase (empty for a scene without).
    fn exact_grains<R: Rng + ?Sized>(&self, rng: &mut R) -> Result<Vec<GrainSpec>, SampleError> {
        let mut grains = Vec::new();
        for (index, phase) in self.phases.iter().enumerate() {
            let Some(m) = phase.measured.as_ref().filter(|_| is_exact(phase)) else {
                continue;
            };
            for g in m.grains.iter() {
                let spec = phase.measured_grain(index, g, rng).ok_or_else(|| {
                    SampleError::TooManyRejections {
                        phase: index,
                        name: phase.name.clone(),
                        quantity: "measured grain's shape or orientation",
                        draws: MAX_DRAWS,
                    }
                })?;
                grains.push(spec);
            }
        }
        Ok(grains)
    }

    /// The scene's random generator: ChaCha8 seeded with [`Scene::seed`], whose stream
    /// is fixed by its algorithm, so a seed gives the same grains on every machine and
    /// with any number of threads.
    pub fn rng(&self) -> ChaCha8Rng {
        ChaCha8Rng::seed_from_u64(self.seed)
    }

    /// Draws the crystal orientation of every grain from its phase's texture, one
    /// after another from `rng`. Drawn after the shapes, from a stream of its own
    /// ([`Scene::crystal_rng`] in [`crate::run::run`]), so that textures do not change
    /// the grains a seed gives.
    pub fn sample_crystals<R: Rng + ?Sized>(&self, grains: &mut [GrainSpec], rng: &mut R) {
        for g in grains {
            // Drawn even where a measured table gives the crystal (kept, set by
            // `measured_grain`), so that the other grains' draws do not depend on it.
            let drawn = self.phases[g.phase].texture.texture.sample(rng);
            let measured = self.phases[g.phase].measured.as_ref();
            if !measured.is_some_and(|m| m.has_crystals()) {
                g.crystal = drawn;
            }
        }
    }

    /// The random generator of the crystal orientations: ChaCha8 seeded with `seed`
    /// (the scene's, or the run's), on stream [`CRYSTAL_STREAM`].
    pub fn crystal_rng(seed: u64) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(CRYSTAL_STREAM);
        rng
    }

    /// Draws the scene's grains, one after another from `rng`.
    ///
    /// Each grain comes from the phase furthest below its volume share (the least
    /// `volume drawn / share`, the first phase on ties), so each phase's volume stays
    /// within one grain of its share. [`GrainCount::Exactly`] stops after that many
    /// grains; [`GrainCount::Fraction`] draws until the total volume first reaches
    /// `φ·V`, then drops the last grain if the total without it is nearer `φ·V`.
    pub fn sample_grains<R: Rng + ?Sized>(
        &self,
        rng: &mut R,
    ) -> Result<Vec<GrainSpec>, SampleError> {
        // Exact tables first: all of their grains, once each. A scene of exact tables
        // only ends there; a mixed one draws its other phases up to their shares.
        let exact = self.exact_grains(rng)?;
        if self.phases.iter().all(is_exact) {
            return Ok(exact);
        }
        let done = |count: usize, volume: f64| match self.count {
            GrainCount::Exactly(n) => count >= n,
            GrainCount::Fraction(f) => volume >= f * self.domain.volume(),
        };
        // Validation bounds the expected count by MAX_GRAINS; twice that is never reached
        // by chance, but a loop without a bound is not written.
        let limit = 2 * MAX_GRAINS;
        let mut grains =
            Vec::with_capacity(self.expected_count().ceil().min(MAX_GRAINS as f64) as usize);
        let mut drawn = vec![0.0; self.phases.len()];
        for g in &exact {
            drawn[g.phase] += g.volume();
        }
        let mut total: f64 = drawn.iter().sum();
        let first_drawn = exact.len();
        grains.extend(exact);
        let p0 = self.phases.iter().position(|p| !is_exact(p)).unwrap_or(0);
        while !done(grains.len(), total) {
            if grains.len() >= limit {
                return Err(SampleError::TooManyGrains { limit });
            }
            let mut p = p0;
            for (i, phase) in self.phases.iter().enumerate() {
                if !is_exact(phase) && drawn[i] / phase.share < drawn[p] / self.phases[p].share {
                    p = i;
                }
            }
            let grain = self.phases[p].sample_grain(p, rng)?;
            drawn[p] += grain.volume();
            total += grain.volume();
            grains.push(grain);
        }
        if let GrainCount::Fraction(f) = self.count {
            // Only a drawn grain may be dropped, never one of an exact table.
            let keep = nearest_count(&grains, f * self.domain.volume());
            grains.truncate(keep.max(first_drawn + 1).min(grains.len()));
        }
        Ok(grains)
    }
}

/// The axis a grain of orientation `q` may turn about under `rotation = "axis"`: a
/// tilt phase's tilt axis (the tilt angle changes); a `fisher` phase's grain its own
/// first axis (only the spin changes, so the law of the first axis is kept).
pub(super) fn turn_axis(orientation: &Orientation, q: [f64; 4]) -> Option<[f64; 3]> {
    match orientation {
        Orientation::Tilt { axis, .. } => Some(axis.unit()),
        Orientation::Fisher(_) => Some(crate::contact::rotation_column(q, 0)),
        _ => None,
    }
}

/// Whether `phase` takes exactly its measured grains (`mode = "exact"`).
fn is_exact(phase: &Phase) -> bool {
    matches!(&phase.measured, Some(m) if m.mode == super::MeasuredMode::Exact)
}

/// Of the grains drawn until their volumes first reached `target`, how many to keep so
/// that the total lands nearest it: all, or all but the last when the total without it
/// is nearer (never none). With large grains the first grain past the target can
/// overshoot it by a lot (0.570 drawn for 0.55 asked with 8 grains of diameter 30 in a
/// box of 75), and a target that is not met then reads as "not reached".
fn nearest_count(grains: &[GrainSpec], target: f64) -> usize {
    let n = grains.len();
    if n < 2 {
        return n;
    }
    let total: f64 = grains.iter().map(GrainSpec::volume).sum();
    let without = total - grains[n - 1].volume();
    if (target - without).abs() < (total - target).abs() {
        n - 1
    } else {
        n
    }
}
