//! The loop's clean states: the densest kept as the fallback result, put back into the
//! state when a later phase starts from it, and finally written out as packed grains
//! and checked.

use super::grains::{PackedGrain, StopReason};
use super::job::{Counters, Packing};
use super::state::State;
use super::verify::verify;
use super::PackError;
use crate::scene::GrainSpec;

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
