//! Tests of `packing.time_limit`: the relaxations before the first clean state give
//! way, the search's trials take their share of the time left, the loop keeps time for
//! the final check, and an interrupted trial keeps its state where denser.

use super::tests::{drawn, job};
use super::tests_schedule::context;
use super::*;
use crate::scene::{GrainSpec, Scene};
use std::sync::atomic::AtomicBool;

/// Packs `scene` under time limits from `limit` on until `retry` accepts a run (`None`)
/// or has asked `tries` times for another limit (`Some(factor)`: the last one times
/// it), and returns the accepted run, which stopped at its limit. Every run is
/// overlap-free.
fn first_accepted(
    scene: &mut Scene,
    specs: &[GrainSpec],
    mut limit: f64,
    tries: usize,
    retry: impl Fn(&Packing) -> Option<f64>,
) -> Packing {
    let tuning = Tuning::default();
    let mut tried = Vec::new();
    for _ in 0..tries {
        scene.packing.time_limit = Some(limit);
        let timed = pack(
            &job(scene, specs, &tuning),
            &AtomicBool::new(false),
            &mut |_| {},
        )
        .unwrap();
        assert!(timed.verification.is_clean(), "{:?}", timed.verification);
        match retry(&timed) {
            None => {
                assert_eq!(timed.stop, StopReason::TimeLimit);
                return timed;
            }
            Some(factor) => limit *= factor,
        }
        tried.push(timed.trials);
    }
    panic!("no limit was accepted: {tried:?}");
}

/// Whether any trial after the first came out clean.
fn clean_after_first(p: &Packing) -> bool {
    p.trials[1..].iter().any(|t| t.outcome == Outcome::Clean)
}

/// Under a time limit shorter than the target's own relaxation from random positions,
/// that relaxation gives way to the search at [`time_limit::GIVE_WAY_TARGET`] of the limit
/// while its grains still overlap deeply, and the search's trials climb from it shrunk
/// until apart: the run keeps a clean trial's state, not the interrupted relaxation's
/// shrunk by its deepest overlap. 3 000 equal spheres asked 0.60 (well below their
/// jamming point: relaxed at the target). The limit starts at 0.4 of the time the
/// relaxation took alone and adapts to the machine's speed: shorter where the
/// relaxation came out clean anyway or was nearly apart when it should give way
/// ([`fire::NEARLY_APART`]) or the target was reached (a faster machine than during
/// the run without a limit), longer where the limit ran out first or the search had
/// no time for a clean trial.
#[test]
fn a_time_limit_shorter_than_the_targets_relaxation_gives_way_to_the_search() {
    let (mut scene, specs) = drawn(
        "seed = 2\ngrains = 3000\n[box]\nsize = [27.56, 27.56, 27.56]\n\
         [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n",
    );
    let started = std::time::Instant::now();
    let plain = pack(
        &job(&scene, &specs, &Tuning::default()),
        &AtomicBool::new(false),
        &mut |_| {},
    )
    .unwrap();
    let took = started.elapsed().as_secs_f64();
    let first = &plain.trials[0];
    assert!(
        first.scale == 1.0 && first.outcome == Outcome::Clean,
        "{first:?}"
    );
    let timed = first_accepted(&mut scene, &specs, 0.4 * took, 6, |timed| {
        // A machine faster than during the plain run may reach the target in time.
        if timed.stop == StopReason::TargetReached {
            return Some(0.6);
        }
        match timed.trials[0].outcome {
            Outcome::Budget if clean_after_first(timed) => None,
            Outcome::Budget => Some(1.5),
            // Nearly apart when the limit came (kept shrunk): too late; else too soon.
            Outcome::Interrupted if timed.fraction < fire::NEARLY_APART.powi(3) * 0.6 => Some(1.5),
            _ => Some(0.6),
        }
    });
    let clean = (timed.trials.iter().filter(|t| t.outcome == Outcome::Clean))
        .map(|t| t.fraction)
        .fold(0.0, f64::max);
    assert!(
        timed.fraction >= clean,
        "{}: {:?}",
        timed.fraction,
        timed.trials
    );
}

/// Under a time limit shorter than the deep start, the deep relaxation gives way to the
/// search at [`GIVE_WAY`] of it, and the search's first trials leave a clean state
/// near the jamming point instead of the deep state shrunk until apart (about 0.45
/// here). The limit starts at the time the deep start took in a run without one; the
/// machine's speed varies between runs, so a run whose deep start still ended (faster)
/// or whose search had no clean trial yet (slower) is tried again with less or more.
#[test]
fn a_time_limit_shorter_than_the_deep_start_gives_way_to_the_search() {
    // 3 000 equal spheres at 0.70: far above their jamming point, a deep start.
    let (mut scene, specs) = drawn(
        "seed = 3\ngrains = 3000\n[box]\nsize = [26.19, 26.19, 26.19]\n\
         [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n",
    );
    let started = std::time::Instant::now();
    let mut deep = None;
    let plain = pack(
        &job(&scene, &specs, &Tuning::default()),
        &AtomicBool::new(false),
        &mut |p| {
            if p.scale < 1.0 {
                deep.get_or_insert(started.elapsed());
            }
        },
    )
    .unwrap();
    let first = &plain.trials[0];
    assert!(
        first.scale > 1.0 && first.outcome == Outcome::Stuck,
        "{first:?}"
    );
    let limit = deep.unwrap().as_secs_f64();
    let timed = first_accepted(&mut scene, &specs, limit, 4, |timed| {
        assert_eq!(timed.stop, StopReason::TimeLimit);
        match timed.trials[0].outcome {
            Outcome::Stuck => Some(0.7),
            Outcome::Budget if !clean_after_first(timed) => Some(1.3),
            _ => None,
        }
    });
    let gave_way = &timed.trials[0];
    assert_eq!(gave_way.outcome, Outcome::Budget, "{:?}", timed.trials);
    assert!(gave_way.fire_steps < first.fire_steps, "{gave_way:?}");
    assert!(
        timed.fraction > 0.85 * plain.fraction,
        "{} against {}: {:?}",
        timed.fraction,
        plain.fraction,
        timed.trials
    );
}

/// Under a time limit a trial of the search takes at most half the FIRE steps the time
/// left allows at the mean cost of a step so far, and never fewer than
/// [`time_limit::TIMED_LEAST`]; before the first step, no cap.
#[test]
fn a_timed_trial_takes_its_share_of_the_steps_left() {
    use std::time::Duration;
    let secs = Duration::from_secs_f64;
    assert_eq!(timed_steps(secs(1.0), secs(4.0), 500), 1000);
    assert_eq!(timed_steps(secs(2.0), secs(1.0), 2000), 500);
    assert_eq!(
        timed_steps(secs(1.0), secs(0.01), 500),
        time_limit::TIMED_LEAST
    );
    assert_eq!(
        timed_steps(secs(1.0), Duration::ZERO, 500),
        time_limit::TIMED_LEAST
    );
    assert_eq!(timed_steps(Duration::ZERO, secs(1.0), 0), u64::MAX);
}

/// Under a time limit the loop keeps the time of [`fire::FINISH_STEPS`] of its FIRE
/// steps, at their mean cost so far, for the final check: it is out of time that much
/// before the deadline, and not before its first step.
#[test]
fn the_loop_keeps_time_for_the_final_check() {
    use std::time::{Duration, Instant};
    let (tuning, stop) = (Tuning::default(), AtomicBool::new(false));
    let mut progress = |_: &Progress| {};
    let mut run = context(&tuning, &stop, &mut progress);
    let secs = Duration::from_secs_f64;
    let now = Instant::now();
    (run.started, run.deadline) = (now.checked_sub(secs(10.0)).unwrap(), Some(now + secs(10.0)));
    assert!(run.time_left().unwrap() > secs(9.9));
    // 100 steps in 10 s: six of them, 0.6 s, kept.
    run.counters.fire_steps = 100;
    let left = run.time_left().unwrap().as_secs_f64();
    assert!(left > 9.3 && left < 9.41, "{left}");
    assert!(!run.out_of_time());
    // 6 steps in 10 s: the 10 s left are the check's.
    run.counters.fire_steps = 6;
    assert!(run.out_of_time());
    run.deadline = None;
    assert!(run.time_left().is_none() && !run.out_of_time());
}

/// A relaxation interrupted inside the search leaves its state, shrunk until apart, as
/// the result where that is denser than the densest state kept before it: 1 000 equal
/// spheres asked 0.70, stopped half way through each trial in turn, keep a clean state
/// never less dense than when stopped at that trial's start, and denser in most trials
/// (the descent's segments, whose overlaps shrink as they relax; without the shrunk
/// state kept, none would be).
#[test]
fn an_interrupted_trial_keeps_its_state_shrunk_where_denser() {
    let (scene, specs) = drawn(
        "seed = 1\ngrains = 1000\n[box]\nsize = [18.16, 18.16, 18.16]\n\
         [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n",
    );
    let tuning = Tuning::default();
    let plain = pack(
        &job(&scene, &specs, &tuning),
        &AtomicBool::new(false),
        &mut |_| {},
    )
    .unwrap();
    let stopped_at = |at: u64| {
        let stop = AtomicBool::new(false);
        let stopped = pack(&job(&scene, &specs, &tuning), &stop, &mut |p| {
            if p.step >= at {
                stop.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        })
        .unwrap();
        assert_eq!(stopped.stop, StopReason::Interrupted);
        assert!(
            stopped.verification.is_clean(),
            "{at}: {:?}",
            stopped.verification
        );
        stopped.fraction
    };
    let mut gained = 0;
    for (k, trial) in plain.trials.iter().enumerate().skip(1) {
        let start = plain.trials[..k].iter().map(|t| t.fire_steps).sum::<u64>();
        let (before, within) = (stopped_at(start), stopped_at(start + trial.fire_steps / 2));
        assert!(within >= before, "{k}: {within} < {before}");
        gained += usize::from(within > before);
    }
    let trials = plain.trials.len() - 1;
    assert!(
        2 * gained >= trials,
        "{gained} of {trials}: {:?}",
        plain.trials
    );
}
