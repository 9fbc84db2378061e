//! The loop's clean states: the densest kept as the fallback result, put back into the
//! state when a later phase starts from it, and finally written out as packed grains
//! and checked.

use super::fire::{Context, Fire};
use super::grains::{PackedGrain, StopReason};
use super::job::{Counters, Outcome, Packing};
use super::state::State;
use super::verify::verify;
use super::PackError;
use super::ProtocolParams;
use crate::scene::{Boundary, GrainSpec};

/// Puts the state back to a snapshot's centres and orientations.
pub(super) fn restore(state: &mut State, snapshot: &Snapshot) -> Result<(), PackError> {
    state.centres.clone_from(&snapshot.centres);
    let changed: Vec<(usize, [f64; 4])> = (snapshot.quaternions.iter().enumerate())
        .filter(|&(i, q)| state.quaternions[i] != *q)
        .map(|(i, q)| (i, *q))
        .collect();
    state.set_orientations(&changed)
}

/// A clean state kept as the fallback result.
pub(super) struct Snapshot {
    pub scale: f64,
    pub centres: Vec<[f64; 3]>,
    pub quaternions: Vec<[f64; 4]>,
}

impl Snapshot {
    pub(super) fn of(state: &State, scale: f64) -> Self {
        Self {
            scale,
            centres: state.centres.clone(),
            quaternions: state.quaternions.clone(),
        }
    }
}

/// The largest scale up to `s` at which the current state is clean: every pair apart
/// with the contact gap (scaling all grains by `t` divides every μ by `t`), every
/// grain inside the walls.
pub(crate) fn clean_scale(
    state: &mut State,
    run: &mut Context<'_>,
    protocol: &ProtocolParams,
    s: f64,
) -> Result<f64, PackError> {
    let big_s = s * (1.0 + protocol.margin);
    run.neighbours.update(state, big_s)?;
    run.forces.evaluate(
        state,
        &run.neighbours.pairs,
        run.neighbours.builds,
        big_s,
        false,
    );
    let mut t = s.min(run.forces.min_mu1 / (1.0 + protocol.contact_gap));
    if state.domain.boundary == Boundary::Reflecting {
        let size = state.domain.size;
        for (c, w) in state.centres.iter().zip(&state.half_widths) {
            for k in 0..3 {
                let room = c[k].min(size[k] - c[k]).max(0.0);
                t = t.min(room / (w[k] * (1.0 + state.wall_margin)));
            }
        }
    }
    Ok(t * (1.0 - protocol.shrink_margin))
}

/// Keeps the current state, shrunk until it is clean ([`clean_scale`] from the trial
/// scale `s`), as the best if it is denser than `best`.
pub(super) fn keep_denser(
    best: &mut Option<Snapshot>,
    state: &mut State,
    run: &mut Context<'_>,
    protocol: &ProtocolParams,
    s: f64,
) -> Result<(), PackError> {
    let shrunk = clean_scale(state, run, protocol, s)?.min(1.0);
    if best.as_ref().is_none_or(|b| b.scale < shrunk) {
        *best = Some(Snapshot::of(state, shrunk));
    }
    Ok(())
}

/// Writes the snapshot out as packed grains (the grains themselves, not inflated by
/// the gap) and checks it exactly, with the `gap`.
/// `specs` are in the input's order, the state in the loop's: `order[k]` is the input
/// index of the loop's grain `k`.
pub(super) fn finish(
    specs: &[GrainSpec],
    order: &[usize],
    state: &mut State,
    snapshot: Snapshot,
    stop: StopReason,
    counters: Counters,
    gap: f64,
) -> Result<Packing, PackError> {
    let scale = snapshot.scale;
    state.centres = snapshot.centres;
    state.wrap();
    // In the input's order: the loop's grain k is input grain order[k].
    let mut place = vec![0; specs.len()];
    for (k, &input) in order.iter().enumerate() {
        place[input] = k;
    }
    let grains: Vec<PackedGrain> = (specs.iter().zip(place).enumerate())
        .map(|(id, (spec, k))| {
            let (c, q) = (state.centres[k], snapshot.quaternions[k]);
            PackedGrain::of_spec(id as u32, spec, scale, c, q)
        })
        .collect();
    let verification = verify(&grains, &state.domain, gap)?;
    let fraction = state.fraction(scale);
    Ok(Packing {
        grains,
        scale,
        fraction,
        stop,
        counters,
        trials: Vec::new(),
        verification,
    })
}

/// Turns the grains of a clean snapshot back toward their drawn orientations as far as
/// their neighbours let them: `restore_steps` FIRE steps with a pull of stiffness
/// `restore_stiffness` ([`ProtocolParams`]), then a plain relaxation at the same
/// scale. Returns the state if that ends clean (within `budget` steps in all), `None`
/// otherwise.
pub(super) fn turn_back(
    state: &mut State,
    fire: &mut Fire,
    run: &mut Context<'_>,
    protocol: &ProtocolParams,
    snapshot: &Snapshot,
    budget: u64,
) -> Result<Option<Snapshot>, PackError> {
    let (steps, big_s) = (
        protocol.restore_steps,
        snapshot.scale * (1.0 + protocol.margin),
    );
    if budget <= steps {
        return Ok(None);
    }
    restore(state, snapshot)?;
    let s = snapshot.scale;
    fire.restore = protocol.restore_stiffness;
    run.counters.steps += 1;
    let pulled = fire.relax(state, run, s, big_s, steps);
    fire.restore = 0.0;
    if pulled? == Outcome::Interrupted {
        return Ok(None);
    }
    run.counters.steps += 1;
    let left = (budget - steps).min(protocol.stage_steps);
    let settled = fire.relax(state, run, s, big_s, left)?;
    Ok((settled == Outcome::Clean).then(|| Snapshot::of(state, s)))
}
