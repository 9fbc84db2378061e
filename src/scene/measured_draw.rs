//! A phase's grains made from its measured table: the table's semi-axes and
//! orientation where it gives them, else drawn from the phase's laws.

use super::grain::turn_axis;
use super::{GrainSpec, Measured, MeasuredGrain, Orientation, Phase};
use crate::contact::{ellipse_quaternion, Dimension, PLANE_NORMAL};
use rand::Rng;

impl Phase {
    /// The grain of this phase made from measured grain `g`: its semi-axes and
    /// orientation where the table gives them, else drawn from the phase's laws (in
    /// the order of [`Phase::sample_grain`]: shape, then orientation).
    pub(crate) fn measured_grain<R: Rng + ?Sized>(
        &self,
        index: usize,
        g: &MeasuredGrain,
        rng: &mut R,
    ) -> Option<GrainSpec> {
        let mut spec = match g.semi_axes {
            Some(axes) => GrainSpec {
                semi_axes: axes,
                aspect_ratio: axes[0] / axes[1],
                ..GrainSpec::new(index, g.diameter, 1.0, [1.0, 0.0, 0.0, 0.0], None)
            },
            None => {
                // The shape law at the measured diameter.
                let mut shape_only = self.clone();
                shape_only.measured = None;
                shape_only.size = crate::laws::Distribution::Constant { value: g.diameter };
                shape_only.orientation = Orientation::Fixed {
                    quaternion: [1.0, 0.0, 0.0, 0.0],
                };
                shape_only.sample_grain(index, rng).ok()?
            }
        };
        if let Some(c) = g.crystal {
            spec.crystal = c;
        }
        if self.dimension == Dimension::Two {
            // The table's semi-axes and quaternion are already an ellipse's, about z.
            let (q, tilt) = match g.quaternion {
                Some(q) => (q, None),
                None => {
                    let (theta, tilt) = self.orientation.sample_angle(rng)?;
                    (ellipse_quaternion(theta), tilt)
                }
            };
            spec.quaternion = q;
            spec.tilt = tilt;
            spec.dimension = Dimension::Two;
            spec.turn_axis = Some(PLANE_NORMAL);
            return Some(spec);
        }
        let (q, tilt) = match g.quaternion {
            Some(q) => (q, None),
            None => self.orientation.sample(rng)?,
        };
        spec.quaternion = q;
        spec.tilt = tilt;
        spec.turn_axis = turn_axis(&self.orientation, q);
        Some(spec)
    }

    /// Draws one grain of a `draw` table: a row uniformly at random, then
    /// [`Phase::measured_grain`].
    pub(crate) fn draw_measured<R: Rng + ?Sized>(
        &self,
        index: usize,
        measured: &Measured,
        rng: &mut R,
    ) -> Option<GrainSpec> {
        let row = rng.random_range(0..measured.grains.len());
        self.measured_grain(index, &measured.grains[row], rng)
    }
}
