//! The growth-and-collision loop: grains grow in a box until they reach their target
//! sizes, pushed apart wherever they overlap, and the result is verified overlap-free.
//!
//! # How
//! Every grain keeps its drawn shape (and orientation, unless the scene lets grains
//! rotate); one global scale `s` multiplies all target semi-axes. The loop is the
//! compress-and-relax protocol of soft-particle jamming (O'Hern et al., *Phys. Rev. E*
//! 68, 011306, 2003), with the Perram–Wertheim contact factor μ as the measure of
//! overlap (Donev et al., *J. Comput. Phys.* 202, 737, 2005):
//! 1. grains start at random positions;
//! 2. at a trial scale `s`, the overlap energy `Σ w (1 − μ)²` of all pairs with μ < 1
//!    (at `s` inflated by [`margin`](ProtocolParams::margin)) is minimised with FIRE (`fire.rs`): each step is
//!    **broad phase** (a Verlet list of candidate pairs from the octree), **narrow
//!    phase** (the contact function of every candidate pair) and **response** (forces
//!    and torques, a damped inertial move);
//! 3. the relaxation ends *clean* as soon as every pair is apart at the true scale (μ ≥
//!    1 + [`contact_gap`](ProtocolParams::contact_gap)), or *stuck* when the energy per
//!    grain has converged to a positive plateau (jammed: the test of `jamming.rs`);
//! 4. the scale moves: the first trial is the target itself (`s = 1`, with a budget of
//!    [`stage_steps`](ProtocolParams::stage_steps)), or a scale well above it when the target lies
//!    near the jamming point estimated for the grains (`effort.rs`, `first_relaxation`: a
//!    relaxation from random positions there creeps; above it, in 3D, the first relaxation
//!    is at that band's deepest fraction, where it jams sooner; grains that do not turn jam lower
//!    than spheres of their sizes unless aligned, `frozen_share`; frozen grains a little below
//!    theirs are first pushed past it for a while, `OVERSHOOT`; the first jam of frozen slender
//!    grains is spread at twice its scale, `spreads_first`); after a stuck relaxation the state shrunk by
//!    its smallest μ is a clean state at once, and the scale is bisected between the best
//!    clean scale and the smallest stuck one until they are within `jam_resolution`
//!    (relative; a scene parameter), the target itself tried once as soon as it lies
//!    between the clean end and the midpoint (`tries_target`); with
//!    [`descent`](ProtocolParams::descent) (the default) the scale first descends from
//!    the first deep jam in short relaxations, each lower by the state's root-mean-square
//!    overlap (module `descent`). Near the jamming point relaxations slow down without
//!    end (critical slowing down), so each trial below the target has a budget of
//!    [`trial_steps`](ProtocolParams::trial_steps) steps (times `effort`, a scene parameter, when
//!    below 1), and one that runs out of it counts as jammed at that scale (below `effort = 1`, so
//!    does the target's own relaxation far above the jamming point, *deep*, after four such
//!    budgets; under a time limit, a trial has at most half the steps the time left
//!    allows, `time_limit.rs`, `timed_steps`). A first jam that is *shallow* (the target just
//!    above the jamming point: the relaxation from random positions creeps, and is cut after
//!    [`trial_steps`](ProtocolParams::trial_steps), times `effort` below 1, by the jamming test's
//!    patience) sets no bound (from `effort` 0.5 on; below, the search starts from it): the state
//!    is compressed (to `DEEP_START`, then by 2 % of scale) and relaxed again until a jam is deep,
//!    and the search starts from there, so that a start just above jamming costs and reaches about
//!    what one far above it does (`effort.rs`, `QUENCH_STEP`). With `effort` ≥ 1.5, the jammed
//!    state is then compressed again well past its jamming point and the search repeated, `⌊2
//!    (effort − 1)⌋` times (recompression cycles, see `start_cycle`), keeping the densest clean
//!    state: more effort buys density for time (with `packing.unjam = "anneal"` a cycle is a slow
//!    compression with Monte Carlo moves instead, module `unjam`);
//! 5. grains that may turn and reached the target are turned back toward their drawn
//!    orientations (`restore`, a scene parameter): [`restore_steps`](ProtocolParams::restore_steps)
//!    steps with a pull of stiffness [`restore_stiffness`](ProtocolParams::restore_stiffness)
//!    toward them, then a plain relaxation; the
//!    result is kept if it is clean.
//!
//! The margin makes a relaxation finish as soon as the true overlaps are gone, long
//! before the energy (taken at the inflated size) reaches zero. The result is checked
//! afterwards by [`verify`], an exact test of every pair whose bounding spheres meet.
//!
//! # The gap
//! With `packing.gap = g` every pair must keep μ ≥ 1 + g and every grain scaled by
//! 1 + g must stay inside the walls. The loop has no path of its own for it: its
//! shapes are the grains inflated by 1 + g (`State::new`), so a clean state of them is
//! one of the grains keeping the gap (μ scales as 1 / size). Only the volumes, and so
//! every fraction reported, are the grains' own; the grains are written at their own
//! size, and [`verify`] checks them with the gap.

mod descent;
mod effort;
mod fire;
mod forces;
mod grains;
mod jamming;
mod job;
mod neighbours;
mod snapshot;
mod start;
mod state;
mod time_limit;
mod tuning;
mod unjam;
mod verify;

pub use effort::MIN_CYCLE_EFFORT;
pub use grains::{sorted_turns, turn_angle, turn_vector, PackedGrain, StopReason};
pub use job::{Counters, Job, Outcome, PackError, Packing, Progress, Trial, Verification};
pub use tuning::{FireParams, NeighbourParams, ProtocolParams, Tuning, TuningError};
pub use verify::{verify, MIN_GAP_REACH};

use crate::scene::Rotation;
use descent::Descent;
use effort::{
    deep_patience, first_relaxation, recompression, recompression_cycles, spread_fits,
    spreads_first, start_cycle, trial_steps, tries_target, CYCLE_WINDOW, DEEP_START, QUENCH_LIMIT,
    QUENCH_MIN_EFFORT, QUENCH_STEP,
};
use fire::{Context, Fire};
use jamming::Patience;
use neighbours::Neighbours;
pub(crate) use snapshot::clean_scale;
use snapshot::{finish, keep_denser, turn_back, Snapshot};
use state::State;
use time_limit::{timed_steps, GIVE_WAY, GIVE_WAY_TARGET};

use crate::scene::GrainSpec;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

/// Packs the grains into the domain. See the module docs for the algorithm.
///
/// Deterministic for a given seed, whatever the number of threads: candidate pairs
/// come in a fixed order, each pair is evaluated on its own, and forces are summed in
/// pair order. `stop` is polled once per FIRE step; when set, the loop ends with
/// [`StopReason::Interrupted`] and returns the best overlap-free state (the interrupted
/// relaxation's own, shrunk until apart, if that is denser). `progress` is
/// called after every FIRE step's narrow phase.
pub fn pack(
    job: &Job<'_>,
    stop: &AtomicBool,
    progress: &mut dyn FnMut(&Progress),
) -> Result<Packing, PackError> {
    let Job {
        specs,
        domain,
        params,
        tuning,
        seed,
    } = *job;
    tuning.check()?;
    let started = Instant::now();
    let protocol = tuning.protocol;
    let centres = start::random_centres(specs.len(), domain, seed);
    // The loop works on the grains in the order of their starting places along a
    // space-filling curve, so that neighbours sit close in memory.
    let order = start::spatial_order(&centres, domain.size);
    let sorted: Vec<GrainSpec> = order.iter().map(|&k| specs[k]).collect();
    let mut state = State::new(&sorted, domain, params.gap).map_err(|e| match e {
        PackError::Grain { id, source } => PackError::Grain {
            id: order[id],
            source,
        },
        e => e,
    })?;
    drop(sorted);
    state.centres = order.iter().map(|&k| centres[k]).collect();
    let after = |share: f64| Some(started + Duration::from_secs_f64(params.time_limit? * share));
    let mut run = Context {
        neighbours: Neighbours::new(tuning.neighbours),
        forces: Default::default(),
        counters: Counters::default(),
        rotation: params.rotation,
        max_turn: params.max_turn,
        contact_gap: protocol.contact_gap,
        resolution: params.jam_resolution,
        stop,
        deadline: after(1.0),
        // Set again just before the loop (below).
        started,
        give_way: None,
        progress,
    };
    // The loop's relaxations, one per trial scale (`Packing::trials`).
    let mut trials = Vec::new();
    let mut fire = Fire::new(tuning.fire);
    // The best clean state (scale, centres, orientations) and the smallest stuck scale.
    let mut best: Option<Snapshot> = None;
    let mut stuck = f64::INFINITY;
    let inflated = state.fraction(1.0) * (1.0 + params.gap).powi(domain.dimension.exponent());
    let turning = params.rotation != Rotation::None && !state.round.iter().all(|&r| r);
    let first = first_relaxation(specs, domain.dimension, inflated, (params.effort, turning));
    // The overshoot's step cap (`effort::OVERSHOOT`), until it has been relaxed.
    let (mut s, mut overshoot) = (first.scale, first.steps);
    // With a time limit, cycles go on until the time is up.
    let mut cycles_left = match params.time_limit {
        Some(_) => u32::MAX,
        None => recompression_cycles(params.effort),
    };
    let depth = recompression(specs);
    // Frozen slender grains: their first jam is spread before the search (`effort`,
    // `spreads_first`), which then bisects.
    let (mut spread, mut spread_done) = (spreads_first(depth, turning, params.effort), false);
    let mut unjammer =
        unjam::Unjammer::new(params.unjam, recompression_cycles(params.effort), seed);
    // Until the first jam deep enough to search from (`effort::QUENCH_STEP`).
    let mut quenching = true;
    // The target is tried once out of turn (`tries_target`): a guess, which bounds the
    // search only if it jams on a plateau.
    let (mut target_tried, mut guess) = (false, false);
    // From the first deep jam to the first clean state: the descent (module `descent`).
    let mut descent = Descent::default();
    // Under a time limit, when the relaxations before the first clean state give way:
    // those above the target, then the target's own.
    let (mut give_way_above, give_way_target) = (after(GIVE_WAY), after(GIVE_WAY_TARGET));
    // A mean FIRE step (the final check's reserve, a timed trial's share) counts from
    // here: the setup above is no step, and on 10 000 grains it could take most of a
    // short limit's reserve after the first step.
    run.started = Instant::now();
    let reason = loop {
        let left = params.max_steps.saturating_sub(run.counters.fire_steps);
        if left == 0 {
            break StopReason::StepLimit;
        }
        run.counters.steps += 1;
        // The target's own relaxation and its compressions; later trials (a
        // recompression may go past the target: a state jammed there is as good a
        // start as any) have the trials', and under a time limit their share of it.
        let budget = if quenching {
            protocol.stage_steps
        } else {
            let timed = (run.time_left()).map_or(u64::MAX, |left| {
                timed_steps(run.started.elapsed(), left, run.counters.fire_steps)
            });
            match descent.on() {
                true => descent.budget(&protocol, params.effort, s),
                false => trial_steps(&protocol, params.effort),
            }
            .min(timed)
        };
        // Shallow relaxations from random positions creep (module `jamming`); below
        // `effort = 1` a creeping one is cut as soon as a trial's budget runs out, and
        // a deep one after `DEEP_PATIENCE` budgets.
        fire.patience = if quenching {
            Patience {
                creeping: trial_steps(&protocol, params.effort),
                any: protocol.trial_steps,
                deep: deep_patience(&protocol, params.effort),
            }
        } else {
            Patience::NONE
        };
        run.give_way = match (quenching, s > 1.0) {
            (false, _) => None,
            (true, true) => give_way_above,
            (true, false) => give_way_target,
        };
        if descent.on() {
            (fire.keep_step, fire.keep_velocity) = (true, true);
        }
        let before = run.counters.fire_steps;
        let outcome = fire.relax(
            &mut state,
            &mut run,
            s,
            s * (1.0 + protocol.margin),
            left.min(budget).min(overshoot.unwrap_or(u64::MAX)),
        )?;
        trials.push(Trial {
            scale: s,
            fraction: state.fraction(s),
            outcome,
            fire_steps: run.counters.fire_steps - before,
            energy_per_grain: run.forces.energy / state.len() as f64,
        });
        let guessed = std::mem::take(&mut guess);
        let gave_way = run.give_way.is_some_and(|d| Instant::now() >= d);
        // Each gives way once; once the target's own has, the search follows.
        if gave_way && s > 1.0 {
            give_way_above = None;
        }
        if overshoot.take().is_some() && matches!(outcome, Outcome::Stuck | Outcome::Budget) {
            s = 1.0;
            fire.keep_step = true;
            continue;
        }
        match outcome {
            Outcome::Interrupted => {
                let reason = interrupted(&run);
                keep_denser(&mut best, &mut state, &mut run, &protocol, s)?;
                break reason;
            }
            Outcome::Clean => {
                best = Some(Snapshot::of(&state, s.min(1.0)));
                descent.stop();
            }
            Outcome::Stuck | Outcome::Budget => {
                keep_denser(&mut best, &mut state, &mut run, &protocol, s)?;
                // Under a time limit, only while relaxations above the target may run.
                let room = || {
                    let ahead = give_way_above.is_some_and(|d| Instant::now() < d);
                    params.time_limit.is_none() || ahead
                };
                let fits = || spread_fits(run.neighbours.pairs.len(), domain.dimension);
                if quenching && !gave_way && std::mem::take(&mut spread) && room() && fits() {
                    (s, spread_done) = (start_cycle(s, depth), true);
                    continue;
                }
                // A shallow first jam is a poor start for the search: compress further,
                // at once to where a jam is deep, unless given way to the search.
                let shallow = quenching && !gave_way && !fire.deep;
                if shallow && s < QUENCH_LIMIT && params.effort >= QUENCH_MIN_EFFORT {
                    s = (s * (1.0 + QUENCH_STEP)).max(DEEP_START);
                    continue;
                }
                if !(guessed && outcome == Outcome::Budget) {
                    stuck = stuck.min(s);
                }
                // A state given way to a time limit is no jam to descend from.
                if quenching && !gave_way && protocol.descent && !spread_done {
                    descent.start();
                }
            }
        }
        quenching = false;
        let low = best.as_ref().map_or(0.0, |b| b.scale);
        if low >= 1.0 {
            break StopReason::TargetReached;
        }
        if stuck - low <= params.jam_resolution * low {
            if cycles_left == 0 {
                break StopReason::Jammed;
            }
            cycles_left -= 1;
            stuck = f64::INFINITY;
            descent.stop();
            // The cycles' relaxations judge with the half window.
            let half_window = (tuning.fire.window as f64 * CYCLE_WINDOW).round() as u64;
            if unjammer.anneals() {
                fire.set_window(half_window);
                // The densest clean state is annealed from below its jamming point
                // (module `unjam`), and the bisection goes on from the result.
                let loop_state = (&mut state, &mut fire, &mut run);
                let resolution = params.jam_resolution;
                let (low, above) =
                    unjammer.anneal_cycle(loop_state, &protocol, &mut best, resolution)?;
                if low >= 1.0 {
                    break StopReason::TargetReached;
                }
                (stuck, s) = (above, 0.5 * (low + above));
                continue;
            }
            s = start_cycle(low, depth);
            // Unjamming moves (`packing.unjam`, module `unjam`) at the recompressed
            // scale, before the cycle's first relaxation.
            unjammer.before_recompression(&mut state, &mut fire, &mut run, &protocol, s)?;
            fire.set_window(half_window);
            continue;
        }
        if descent.on() {
            let bounds = (protocol.margin, params.jam_resolution, low);
            let relaxed = (&run.forces, state.mean_rho2);
            if let Some(next) = descent.next_scale(s, relaxed, bounds, &mut target_tried) {
                s = next;
                continue;
            }
        }
        guess = !target_tried && tries_target(low, stuck);
        target_tried |= guess;
        s = if guess { 1.0 } else { 0.5 * (low + stuck) };
    };
    let mut snapshot = match best {
        Some(b) => b,
        None => {
            let shrunk = clean_scale(&mut state, &mut run, &protocol, s)?.min(1.0);
            Snapshot::of(&state, shrunk)
        }
    };
    // A jammed state leaves no room to turn back: only a packing that reached its
    // target is turned back.
    if params.restore && run.rotation != Rotation::None && reason == StopReason::TargetReached {
        // A recompression may have reached the target: the turn back judges with the
        // full window.
        fire.set_window(tuning.fire.window);
        let left = params.max_steps.saturating_sub(run.counters.fire_steps);
        if let Some(turned_back) =
            turn_back(&mut state, &mut fire, &mut run, &protocol, &snapshot, left)?
        {
            snapshot = turned_back;
        }
    }
    // The loop's buffers go before the check builds its own.
    let counters = run.counters;
    drop((run, fire));
    let mut packing = finish(
        specs, &order, &mut state, snapshot, reason, counters, params.gap,
    )?;
    packing.trials = trials;
    Ok(packing)
}

/// Why a relaxation stopped early: the time limit if it has run out, else the caller.
fn interrupted(run: &Context<'_>) -> StopReason {
    if run.out_of_time() {
        StopReason::TimeLimit
    } else {
        StopReason::Interrupted
    }
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_schedule;
#[cfg(test)]
mod tests_time_limit;
