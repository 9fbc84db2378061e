//! Unjamming moves between effort's recompression cycles (`packing.unjam`): ways past a
//! premature jam that the compress-and-relax protocol alone does not take.
//!
//! Once the bisection has found a jamming point and effort asks for another cycle, the
//! loop compresses the state by [`RECOMPRESSION`](super::RECOMPRESSION) and relaxes it
//! there. Before that relaxation, these moves change the state:
//! - **swaps** ([`Unjam::Swap`]): grains of similar volume but different shape, size
//!   or orientation exchange their positions wherever that lowers the overlap energy
//!   at the compressed scale — swap Monte Carlo at zero temperature (Grigera and
//!   Parisi, *Phys. Rev. E* 63, 045102, 2001; Ninarello, Berthier and Coslovich,
//!   *Phys. Rev. X* 7, 021039, 2017, where swaps reach far denser polydisperse
//!   packings than plain dynamics). Each grain keeps its own orientation, so frozen
//!   orientations stay exactly as drawn: for frozen ellipsoids a swap is the one way
//!   to put a differently oriented grain where another stood;
//! - **shaking** ([`Unjam::Shake`]): every grain is displaced at random by a fraction
//!   of its smallest semi-axis, and grains free to turn are turned at random by a
//!   small angle (never a frozen one, never past `max_turn`), then relaxed at the
//!   jamming scale: thermal noise at a fixed scale below jamming, followed by a quench.
//!
//! The moves only change the state a cycle starts from: the densest clean state of all
//! cycles is kept by the loop, so they never lower the fraction reached. They draw from
//! their own random stream ([`UNJAM_STREAM`]) and run in a fixed order, so the result
//! is the same for a seed whatever the thread count.

mod swap;

use super::fire::{Context, Fire};
use super::grains::rotate_by;
use super::state::State;
use super::{PackError, ProtocolParams};
use crate::scene::{Rotation, Unjam};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

/// The random stream of the moves (the scene's sampling uses stream 0, the starting
/// positions stream 1).
const UNJAM_STREAM: u64 = 2;

/// Sweeps of swap attempts (one attempt per grain each) before a cycle's relaxation:
/// few, since each accepted swap only settles once FIRE has relaxed around it.
pub(crate) const SWAP_SWEEPS: usize = 4;

/// Rounds of swap sweeps, each but the last followed by a relaxation of
/// [`SWAP_RELAX_STEPS`] at the recompressed scale (swap Monte Carlo alternates swaps
/// with ordinary moves).
pub(crate) const SWAP_ROUNDS: usize = 32;

/// FIRE steps of the relaxation between two rounds of swaps: a quarter of a trial's
/// default budget, about the steps a relaxation of the compressed state takes to
/// settle.
pub(crate) const SWAP_RELAX_STEPS: u64 = 250;

/// Grains swap only with grains whose volume is within this factor of theirs
/// ("similar-size" swaps): a far larger grain never fits where a small one stood, and
/// a window keeps the attempts where they may pay. 2 spans a lognormal size law of
/// σ = 0.25 over about a standard deviation either side.
pub(crate) const SWAP_VOLUME_RATIO: f64 = 2.0;

/// The standard deviation of a shake's displacement along each axis, as a share of
/// the grain's smallest semi-axis at the jamming scale; for grains free to turn, of
/// the turn angle times its largest semi-axis.
pub(crate) const SHAKE_AMPLITUDE: f64 = 0.1;

/// What the moves did, for tests and traces.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct UnjamStats {
    /// Swap attempts (pairs whose energy was compared).
    pub attempts: u64,
    /// Swaps kept.
    pub swaps: u64,
    /// Shakes done.
    pub shakes: u64,
}

/// The moves of one packing: the mode and its random stream.
pub(crate) struct Unjammer {
    mode: Unjam,
    rng: ChaCha8Rng,
    pub stats: UnjamStats,
}

impl Unjammer {
    pub fn new(mode: Unjam, seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(UNJAM_STREAM);
        Self {
            mode,
            rng,
            stats: UnjamStats::default(),
        }
    }

    /// The moves before a recompression cycle: the state is jammed near scale `low`
    /// (the best clean scale found) and is about to be relaxed at `next`.
    pub fn before_recompression(
        &mut self,
        state: &mut State,
        fire: &mut Fire,
        run: &mut Context<'_>,
        protocol: &ProtocolParams,
        low: f64,
        next: f64,
    ) -> Result<(), PackError> {
        if matches!(self.mode, Unjam::Shake | Unjam::Both) {
            self.shake(state, fire, run, protocol, low)?;
        }
        if matches!(self.mode, Unjam::Swap | Unjam::Both) {
            let big_s = next * (1.0 + protocol.margin);
            for round in 0..SWAP_ROUNDS {
                let mut kept = 0;
                for _ in 0..SWAP_SWEEPS {
                    let (attempts, swaps) = swap::sweep(state, big_s, &mut self.rng)?;
                    self.stats.attempts += attempts;
                    self.stats.swaps += swaps;
                    kept += swaps;
                    if swaps == 0 {
                        break;
                    }
                }
                if kept == 0 {
                    break;
                }
                if round + 1 < SWAP_ROUNDS {
                    // Let the packing settle around the swapped grains before the next
                    // round (the loop's own relaxation follows the last).
                    run.counters.steps += 1;
                    fire.relax(state, run, next, big_s, SWAP_RELAX_STEPS)?;
                }
            }
        }
        Ok(())
    }

    /// Displaces every grain at random (and turns those free to turn), then relaxes
    /// at scale `s` for a trial's budget.
    fn shake(
        &mut self,
        state: &mut State,
        fire: &mut Fire,
        run: &mut Context<'_>,
        protocol: &ProtocolParams,
        s: f64,
    ) -> Result<(), PackError> {
        kick(state, run.rotation, run.max_turn, s, &mut self.rng)?;
        self.stats.shakes += 1;
        run.counters.steps += 1;
        // However it ends (an interruption is seen by the loop's next relaxation), the
        // recompression follows.
        fire.relax(state, run, s, s * (1.0 + protocol.margin), protocol.trial_steps)?;
        Ok(())
    }
}

/// One random kick: centres displaced by `SHAKE_AMPLITUDE · s · ρ` along each axis (ρ
/// the smallest semi-axis), and grains that may turn under `rotation` turned by a
/// random rotation vector of `SHAKE_AMPLITUDE · ρ / b` per axis (b the largest
/// semi-axis: the same displacement at the grain's tip), its part about the allowed
/// axis only, and only where it stays within `max_turn` of the drawn orientation.
pub(crate) fn kick(
    state: &mut State,
    rotation: Rotation,
    max_turn: f64,
    s: f64,
    rng: &mut ChaCha8Rng,
) -> Result<(), PackError> {
    let mut turns = Vec::new();
    for i in 0..state.len() {
        let rho = state.shapes[i].inscribed_radius();
        let step = SHAKE_AMPLITUDE * s * rho;
        let d: [f64; 3] = std::array::from_fn(|_| step * normal(rng));
        for k in 0..3 {
            state.centres[i][k] += d[k];
        }
        if rotation == Rotation::None {
            continue;
        }
        // Drawn for every grain, so the stream does not depend on which may turn.
        let angle = SHAKE_AMPLITUDE * rho / state.shapes[i].bounding_radius();
        let theta: [f64; 3] = std::array::from_fn(|_| angle * normal(rng));
        let theta = state.allowed_torque(i, theta, rotation);
        if theta.iter().all(|&x| x == 0.0) {
            continue;
        }
        let q = rotate_by(state.quaternions[i], theta);
        if state.within_turn(i, q, max_turn) {
            turns.push((i, q));
        }
    }
    if state.domain.boundary == crate::scene::Boundary::Reflecting {
        // Walled: keep the centres inside (the walls' forces do the rest).
        state.wrap();
    }
    state.set_orientations(&turns)
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}

#[cfg(test)]
mod tests;
