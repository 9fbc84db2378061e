//! `unjam = "anneal"`: a recompression cycle that anneals instead of compressing
//! through. The densest clean state is shrunk by [`ANNEAL_SHRINK`] of scale, then
//! grown back in steps of [`ANNEAL_RATE`], each step preceded by [`ANNEAL_SWEEPS`]
//! sweeps of hard-particle Monte Carlo (moves, turns and swaps, `monte_carlo.rs`) and
//! followed by a relaxation that must end clean within [`ANNEAL_RELAX_STEPS`]; the
//! first step that does not marks the jamming point of the annealed packing, and the
//! loop's bisection goes on from there.
//!
//! This is a Lubachevsky–Stillinger-like slow compression (Lubachevsky and
//! Stillinger, *J. Stat. Phys.* 60, 561, 1990) with the swap moves of polydisperse
//! glass formers (Ninarello, Berthier and Coslovich, *Phys. Rev. X* 7, 021039, 2017):
//! between compressions the packing explores its configurations, so it jams where a
//! slowly compressed packing would, denser than the quench of the compress-and-relax
//! loop. On Rocks and Hoy's ellipses (1 000, aspect 1.3–1.4, minor axes over 1.4, free
//! to turn) a cycle reaches 0.8965–0.8969 (seeds 1–3) where the quench jams at 0.886
//! and swap cycles at 0.888 (BENCHMARKS.md, "Annealing").

use super::monte_carlo::{MonteCarlo, Moves};
use crate::packing::fire::{Context, Fire};
use crate::packing::state::State;
use crate::packing::Outcome;
use crate::packing::{clean_scale, PackError, ProtocolParams};
use rand_chacha::ChaCha8Rng;

/// How far below the jamming point the annealing starts, relatively in scale (3 %:
/// about 6 % of packing fraction in 2D, 9 % in 3D). The schedule was chosen on Rocks
/// and Hoy's 1 000 ellipses (seed 1, effort 1.5; start below the jamming point, sweeps
/// per step, growth per step → φ reached): 5 %, 5, 1e-3 → 0.8904; 5 %, 20, 1e-3 →
/// 0.8921; 3 %, 10, 5e-4 → 0.8927; 3 %, 40, 5e-4 → 0.8971; 3 %, 20, 2.5e-4 → 0.8978;
/// 2 %, 50, 2e-4 → 0.8993 (in twice the time). What counts is the sweeps per unit of
/// growth; a start nearer the jamming point spends them where the packing is dense
/// enough for them to matter (BENCHMARKS.md, "Annealing").
pub(crate) const ANNEAL_SHRINK: f64 = 0.03;

/// Relative growth of scale per step of the annealing (see [`ANNEAL_SHRINK`]).
pub(crate) const ANNEAL_RATE: f64 = 2.5e-4;

/// Monte Carlo sweeps before each step of growth (see [`ANNEAL_SHRINK`]): with
/// [`ANNEAL_RATE`], 80 000 sweeps per unit of relative growth, about 20 s for 1 000
/// ellipses on one core.
pub(crate) const ANNEAL_SWEEPS: usize = 20;

/// The budget of the relaxation after each step of growth: a step of [`ANNEAL_RATE`]
/// from a clean state leaves a few shallow overlaps that FIRE removes in tens of
/// steps; one that needs more marks the jamming point.
pub(crate) const ANNEAL_RELAX_STEPS: u64 = 400;

/// Anneals the clean state at scale `low` (module docs), up to the target (scale 1).
/// Returns the largest clean scale found (the state is left there) and the scale of
/// the step that did not end clean (an upper bound for the bisection; ∞ when the
/// target was reached), and counts the swaps kept.
pub(crate) fn anneal(
    state: &mut State,
    fire: &mut Fire,
    run: &mut Context<'_>,
    protocol: &ProtocolParams,
    low: f64,
    rng: &mut ChaCha8Rng,
) -> Result<(f64, f64), PackError> {
    let moves = Moves {
        rotation: run.rotation,
        max_turn: run.max_turn,
        contact_gap: protocol.contact_gap,
    };
    let mut s = low * (1.0 - ANNEAL_SHRINK);
    let mut monte_carlo = MonteCarlo::new(state, s);
    loop {
        let halt = || run.halted();
        let (_, swaps) = monte_carlo.sweeps(state, s, ANNEAL_SWEEPS, &moves, rng, &halt)?;
        run.counters.swaps += swaps;
        // Not past the target: the loop stops there.
        let next = (s * (1.0 + ANNEAL_RATE)).min(1.0);
        if next <= s {
            return Ok((s, f64::INFINITY));
        }
        run.counters.steps += 1;
        let big = next * (1.0 + protocol.margin);
        match fire.relax(state, run, next, big, ANNEAL_RELAX_STEPS)? {
            Outcome::Clean => s = next,
            Outcome::Interrupted => return Ok((s, next)),
            Outcome::Stuck | Outcome::Budget => {
                // The state left by the relaxation, shrunk until clean.
                let clean = clean_scale(state, run, protocol, next)?;
                return Ok((clean, next));
            }
        }
    }
}
