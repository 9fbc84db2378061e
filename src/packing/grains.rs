//! The packed state as it is written out.

use crate::io::scene::GrainSpec;
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

/// The angle in radians of the rotation taking orientation `from` to `to` (unit
/// quaternions): `2 acos |⟨from, to⟩|`, in `[0, π]`.
pub fn turn_angle(from: [f64; 4], to: [f64; 4]) -> f64 {
    let dot: f64 = from.iter().zip(&to).map(|(a, b)| a * b).sum();
    2.0 * dot.abs().min(1.0).acos()
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
}

impl StopReason {
    /// The name written to `summary.json`.
    pub fn name(self) -> &'static str {
        match self {
            StopReason::TargetReached => "target_reached",
            StopReason::Jammed => "jammed",
            StopReason::StepLimit => "step_limit",
            StopReason::Interrupted => "interrupted",
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
