//! The packed state as it is written out.

use crate::contact::dot;
use crate::scene::GrainSpec;
use std::fmt;

/// One packed grain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PackedGrain {
    /// Index in the input (and the id written out).
    pub id: u32,
    /// Index of its phase in the scene.
    pub phase: usize,
    /// Centre; inside `[0, L)` in a periodic box.
    pub centre: [f64; 3],
    /// Semi-axes as packed (target semi-axes times the scale reached).
    pub semi_axes: [f64; 3],
    /// Orientation `[w, x, y, z]` (Hamilton; semi-axis k along column k of R).
    pub quaternion: [f64; 4],
}

impl PackedGrain {
    /// Grain `id` drawn as `spec`, its shape scaled by `scale`, at `centre` with
    /// orientation `quaternion`.
    pub fn of_spec(
        id: u32,
        spec: &GrainSpec,
        scale: f64,
        centre: [f64; 3],
        quaternion: [f64; 4],
    ) -> Self {
        Self {
            id,
            phase: spec.phase,
            centre,
            semi_axes: spec.semi_axes.map(|a| a * scale),
            quaternion,
        }
    }
}

/// The rotation vector (axis times angle, the angle in `[0, π]`) of the rotation taking
/// orientation `from` to `to` (unit quaternions): from `r = to ⊗ from⁻¹`, the angle is
/// `2 atan2(|r_xyz|, |r_w|)`, accurate to a few ε even for tiny turns (unlike `acos`
/// of a dot product), and exactly 0 for `from == to`.
pub fn turn_vector(from: [f64; 4], to: [f64; 4]) -> [f64; 3] {
    let (p, q) = (from, to);
    let w = q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] * p[3];
    // Each pair of terms cancels exactly when `from == to`.
    let v = [
        (q[1] * p[0] - q[0] * p[1]) + (q[3] * p[2] - q[2] * p[3]),
        (q[2] * p[0] - q[0] * p[2]) + (q[1] * p[3] - q[3] * p[1]),
        (q[3] * p[0] - q[0] * p[3]) + (q[2] * p[1] - q[1] * p[2]),
    ];
    let sin = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if sin == 0.0 {
        return [0.0; 3];
    }
    // The shorter way round: r and −r are the same rotation.
    let k = 2.0 * sin.atan2(w.abs()) / sin * w.signum();
    v.map(|x| k * x)
}

/// The angle in radians, in `[0, π]`, of the rotation taking orientation `from` to `to`
/// (see [`turn_vector`]).
pub fn turn_angle(from: [f64; 4], to: [f64; 4]) -> f64 {
    let [x, y, z] = turn_vector(from, to);
    (x * x + y * y + z * z).sqrt()
}

/// `exp(θ/2) ⊗ q`: `q` turned by the rotation vector `θ` (in the box frame), normalised.
pub(super) fn rotate_by(q: [f64; 4], theta: [f64; 3]) -> [f64; 4] {
    let angle = dot(&theta, &theta).sqrt();
    let (sin, cos) = (0.5 * angle).sin_cos();
    // sin(θ/2)/θ, with its limit 1/2 at θ = 0.
    let k = if angle > 0.0 { sin / angle } else { 0.5 };
    let r = [cos, k * theta[0], k * theta[1], k * theta[2]];
    let p = [
        r[0] * q[0] - r[1] * q[1] - r[2] * q[2] - r[3] * q[3],
        r[0] * q[1] + r[1] * q[0] + r[2] * q[3] - r[3] * q[2],
        r[0] * q[2] - r[1] * q[3] + r[2] * q[0] + r[3] * q[1],
        r[0] * q[3] + r[1] * q[2] - r[2] * q[1] + r[3] * q[0],
    ];
    let norm = p.iter().map(|x| x * x).sum::<f64>().sqrt();
    p.map(|x| x / norm)
}

/// How far each packed grain turned from its drawn orientation (`drawn[id]`), in
/// radians, in increasing order.
pub fn sorted_turns(drawn: &[GrainSpec], grains: &[PackedGrain]) -> Vec<f64> {
    let mut turns: Vec<f64> = grains
        .iter()
        .map(|g| turn_angle(drawn[g.id as usize].quaternion, g.quaternion))
        .collect();
    turns.sort_by(f64::total_cmp);
    turns
}

/// Why the packing loop stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StopReason {
    /// Every grain reached its target size without overlap.
    TargetReached,
    /// The growth rate fell below its floor: the grains cannot grow further.
    Jammed,
    /// `packing.max_steps` steps were made.
    StepLimit,
    /// The caller asked to stop (Ctrl-C).
    Interrupted,
    /// `packing.time_limit` ran out: the densest clean state found is kept.
    TimeLimit,
}

impl StopReason {
    /// The name written to `summary.json`.
    pub fn name(self) -> &'static str {
        match self {
            StopReason::TargetReached => "target_reached",
            StopReason::Jammed => "jammed",
            StopReason::StepLimit => "step_limit",
            StopReason::Interrupted => "interrupted",
            StopReason::TimeLimit => "time_limit",
        }
    }

    /// Whether the packing met its target.
    pub fn is_success(self) -> bool {
        self == StopReason::TargetReached
    }
}

impl fmt::Display for StopReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No turn is exactly no turn, and a turn by θ (applied in the box frame, as the
    /// loop does) comes back as θ to a few ε, both ways round, small or large.
    #[test]
    fn turn_vector_recovers_the_turn_applied() {
        let n = (0.2f64 * 0.2 + 0.5 * 0.5 + 0.7 * 0.7 + 0.4 * 0.4).sqrt();
        let q = [0.2, -0.5, 0.7, 0.4].map(|x| x / n);
        assert_eq!(turn_vector(q, q), [0.0; 3]);
        assert_eq!(turn_vector(q, q.map(|x| -x)), [0.0; 3]);
        for theta in [[1e-9, 0.0, 0.0], [0.3, -0.2, 0.1], [0.0, 0.0, 3.0]] {
            let t = turn_vector(q, rotate_by(q, theta));
            for k in 0..3 {
                assert!((t[k] - theta[k]).abs() < 1e-14, "{t:?} vs {theta:?}");
            }
            let back = turn_vector(rotate_by(q, theta), q);
            assert!(
                (0..3).all(|k| (back[k] + theta[k]).abs() < 1e-14),
                "{back:?}"
            );
        }
    }
}
