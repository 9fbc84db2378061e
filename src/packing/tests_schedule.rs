//! Tests of the jamming schedule: where the first relaxation runs, when a slow one
//! counts as jammed, and which scale the bisection tries.

use super::fire::{Context, Fire};
use super::neighbours::Neighbours;
use super::tests::{drawn, job, pack_scene, pack_with, scattered};
use super::*;
use crate::contact::Dimension;
use crate::scene::{sphere_close_packing, Rotation};
use std::sync::atomic::AtomicBool;

/// 500 equal spheres (diameter 2) in a periodic cube at 0.63, 0.979 of their estimated
/// jamming point; a scene's `seed` line goes before it.
const SPHERES_063: &str = "grains = 500\n[box]\nsize = [14.9247, 14.9247, 14.9247]\n\
                           [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n";

/// Between a clean and a stuck scale, the bisection tries the target itself where the
/// bracket holds it below its midpoint, and the midpoint otherwise.
#[test]
fn the_bisection_tries_the_target_where_its_bracket_holds_it_below_the_midpoint() {
    assert!(tries_target(0.98, 1.04));
    assert!(tries_target(0.99, 1.0404));
    assert!(tries_target(0.98, f64::INFINITY));
    assert!(!tries_target(0.98, 1.01));
    assert!(!tries_target(0.9, 0.95));
    assert!(!tries_target(1.0, 1.02));
}

/// [`SPHERES_063`] with the seeds (of 1–8) whose relaxation at the target is slowest:
/// a plateau under the floor counts as jammed only with a lasting overlap of a share
/// of the resolution (`jamming::NEAR_CLEAN`), which a relaxation on its way to clean
/// does not keep, so both still reach the target. The target (0.979 of the estimated
/// jamming point) is now first relaxed at `DEEP_START` and reached from that jam (seed
/// 4: 641 FIRE steps, seed 7: 714), in no more FIRE steps than the 5 616 and 3 892 the
/// relaxation at the target took alone.
#[test]
fn a_plateau_near_clean_is_not_called_jammed_when_it_would_reach_the_target() {
    for (seed, steps) in [(4, 5616), (7, 3892)] {
        let text = format!("seed = {seed}\n{SPHERES_063}");
        let (p, _) = pack_scene(&text, Rotation::None);

        assert!(p.verification.is_clean(), "{:?}", p.verification);
        assert_eq!(p.stop, StopReason::TargetReached, "{seed}: {}", p.fraction);
        assert!(
            p.counters.fire_steps <= steps,
            "seed {seed}: {:?}",
            p.counters
        );
    }
}

/// A target near the jamming point estimated for its grains (here 0.979 of it) is first
/// relaxed at `DEEP_START`, where a relaxation from random positions jams deep at once,
/// and reached from that jam: 832 FIRE steps, where relaxing at the target first took
/// 2 578 (BENCHMARKS.md, "Issue 27, sixth round"). Below `effort = 0.5`, and for a
/// target clearly below the jamming point (0.93 of it), or grains that turn, the first
/// trial is the target. (Relaxed at the target first, this seed was slow but not over:
/// the window test the plateau test replaced called it stuck after 1 058 steps, at
/// 0.626.)
#[test]
fn a_target_near_the_jamming_point_is_first_relaxed_deep() {
    let near = format!("seed = 5\n{SPHERES_063}");
    let (p, specs) = pack_scene(&near, Rotation::None);
    assert_eq!(p.trials[0].scale, DEEP_START);
    // Grains that turn pack denser than spheres: the estimate does not place them.
    let fraction = p.fraction;
    let first = |turning| first_relaxation(&specs, Dimension::Three, fraction, (1.0, turning));
    assert_eq!(first(false).scale, DEEP_START);
    assert_eq!(first(true).scale, 1.0);
    assert_eq!(p.stop, StopReason::TargetReached, "{}", p.fraction);
    assert!((p.fraction - 0.63).abs() < 1e-3, "{}", p.fraction);
    assert!(p.verification.is_clean(), "{:?}", p.verification);
    assert!(p.counters.fire_steps <= 1000, "{:?}", p.counters);
    let (quick, _) = pack_with(&near, |p| p.effort = 0.1);
    assert_eq!(quick.trials[0].scale, 1.0);
    let (below, _) = pack_scene(&near.replace("14.9247", "15.2"), Rotation::None);
    assert_eq!(below.trials[0].scale, 1.0);
    assert_eq!(below.stop, StopReason::TargetReached);
}

/// Below `effort = 0.5` a target far above the jamming point (500 equal spheres asked
/// 0.70) is first relaxed at the target itself, and counts as jammed at the jamming
/// test's first judgement (`effort::deep_patience`): 400 FIRE steps, where four trial
/// budgets of `effort = 0.25` let it run to its plateau at 600 (10 000 such spheres:
/// 1 000 steps, and the run took longer than at `effort = 0.5`, which starts deeper).
#[test]
fn below_effort_one_half_a_deep_target_is_jammed_at_the_first_judgement() {
    let text = "seed = 1\ngrains = 500\n[box]\nsize = [14.41, 14.41, 14.41]\n\
                boundary = \"periodic\"\n\
                [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n";
    let (p, _) = pack_with(text, |p| p.effort = 0.25);
    let first = &p.trials[0];
    assert_eq!((first.scale, first.outcome), (1.0, Outcome::Stuck));
    let judged = FireParams::default().window * jamming::MIN_WINDOWS as u64;
    assert_eq!(first.fire_steps, judged, "{:?}", &p.trials[..2]);
    assert_eq!(p.stop, StopReason::Jammed);
    assert!(p.verification.is_clean(), "{:?}", p.verification);
}

/// The first jam of frozen slender grains is spread at twice its scale before the
/// search, which then bisects (no descent): 300 frozen ellipses of aspect 5 asked 0.86
/// end denser by far than at `effort = 0.4`, which does not spread (seed 1: 0.756
/// against 0.652). A spread whose list would pass `SPREAD_MAX_PAIRS` is left out.
#[test]
fn the_first_jam_of_frozen_slender_grains_is_spread_before_the_search() {
    let text = "seed = 1\ngrains = 300\n[box]\nsize = [33.1044, 33.1044]\n\
                [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n\
                aspect_ratio = { distribution = \"constant\", value = 0.2 }\n";
    let (spread, _) = pack_scene(text, Rotation::None);
    let [jam, wide] = [&spread.trials[0], &spread.trials[1]];
    assert_eq!(wide.scale, 2.0 * jam.scale, "{:?}", &spread.trials[..3]);
    assert!(matches!(jam.outcome, Outcome::Stuck | Outcome::Budget));
    assert!(spread.verification.is_clean(), "{:?}", spread.verification);
    let (plain, _) = pack_with(text, |p| p.effort = 0.4);
    assert_ne!(plain.trials[1].scale, 2.0 * plain.trials[0].scale);
    assert!(
        spread.fraction > plain.fraction + 0.03,
        "{} {}",
        spread.fraction,
        plain.fraction
    );
    let most = effort::SPREAD_MAX_PAIRS as usize;
    assert!(spread_fits(most / 4, Dimension::Two) && !spread_fits(most / 4 + 1, Dimension::Two));
    assert!(
        spread_fits(most / 8, Dimension::Three) && !spread_fits(most / 8 + 1, Dimension::Three)
    );
}

/// Grains that do not turn jam below spheres of their sizes when their orientations
/// are spread (frozen spheroids of aspect 1.5: 0.630 against 0.6435), so a target of
/// 0.62 (0.963 of the sphere estimate) is near their jamming point and starts deep;
/// aligned ones jam as spheres do (a linear map of spheres) and start at the target, as
/// spheres asked the same do. At 0.60, a little further below their own point, the
/// turned ones are first pushed past it for a while ([`effort::OVERSHOOT`]).
#[test]
fn frozen_grains_start_deep_near_their_own_jamming_point_aligned_ones_as_spheres() {
    let text = "seed = 1\ngrains = 2000\n[box]\nsize = [30.0, 30.0, 30.0]\n\
                [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n\
                aspect_ratio = { distribution = \"constant\", value = 1.5 }\n";
    let (_, turned) = drawn(text);
    let aligned: Vec<GrainSpec> = (turned.iter())
        .map(|s| GrainSpec {
            quaternion: [1.0, 0.0, 0.0, 0.0],
            ..*s
        })
        .collect();
    let spheres: Vec<GrainSpec> = (turned.iter())
        .map(|s| GrainSpec::new(0, s.diameter, 1.0, s.quaternion, None))
        .collect();
    let first = |specs: &[GrainSpec], fraction| {
        first_relaxation(specs, Dimension::Three, fraction, (1.0, false))
    };
    let (target, deep) = (effort::First::TARGET, DEEP_START);
    assert_eq!(
        (first(&turned, 0.62).scale, first(&turned, 0.62).steps),
        (deep, None)
    );
    assert_eq!(first(&aligned, 0.62), target);
    assert_eq!(first(&spheres, 0.62), target);
    let overshoot = effort::First {
        scale: effort::OVERSHOOT,
        steps: Some(effort::OVERSHOOT_STEPS),
    };
    assert_eq!(first(&turned, 0.60), overshoot);
    assert_eq!(first(&aligned, 0.60), target);
    assert_eq!(first(&spheres, 0.60), target);
    // Clearly below their jamming point, all start at the target.
    assert_eq!(first(&turned, 0.55), target);
}

/// A target above the band of [`DEEP_START`] starts at the band's deepest fraction
/// (`DEEP_START³` times the band's upper edge), the same whatever the target, and at the
/// target itself where that is denser; the band ends there without a jump. Below
/// `effort = 0.5`, and in 2D, it starts at the target.
#[test]
fn a_target_far_above_the_jamming_point_starts_at_the_bands_deepest_fraction() {
    let spheres = vec![GrainSpec::new(0, 2.0, 1.0, [1.0, 0.0, 0.0, 0.0], None); 2000];
    let edge =
        effort::FAR_ABOVE_JAMMING * sphere_close_packing(&spheres, Dimension::Three).unwrap();
    let deepest = DEEP_START.powi(3) * edge;
    let first =
        |fraction, effort| first_relaxation(&spheres, Dimension::Three, fraction, (effort, false));
    for fraction in [edge * 1.001, 0.70, 0.72, 0.79] {
        let f = first(fraction, 1.0);
        assert_eq!(f.steps, None);
        assert!(f.scale > 1.0, "{fraction}: {f:?}");
        // Rounded up to a multiple of FIRST_SCALE_STEP.
        let reached = f.scale.powi(3) * fraction / deepest;
        let most = (1.0 + effort::FIRST_SCALE_STEP).powi(3);
        assert!((1.0..most).contains(&reached), "{fraction}: {f:?}");
        assert_eq!(f.scale % effort::FIRST_SCALE_STEP, 0.0, "{f:?}");
    }
    assert_eq!(first(edge * (1.0 - 1e-9), 1.0).scale, DEEP_START);
    assert_eq!(first(edge * (1.0 + 1e-9), 1.0).scale, DEEP_START);
    assert_eq!(first(deepest * 1.01, 1.0), effort::First::TARGET);
    assert_eq!(first(0.70, 0.1), effort::First::TARGET);
    let discs: Vec<GrainSpec> = (spheres.iter())
        .map(|s| GrainSpec::ellipse(0, s.diameter, 1.0, 0.0))
        .collect();
    assert_eq!(
        first_relaxation(&discs, Dimension::Two, 0.90, (1.0, false)),
        effort::First::TARGET
    );
}

/// Frozen spheroids asked 0.60 (0.95 of their own jamming point) relax past it for
/// [`effort::OVERSHOOT_STEPS`] and then at the target, which they reach overlap-free.
#[test]
fn frozen_grains_a_little_below_their_jamming_point_overshoot_then_reach_the_target() {
    let text = "seed = 2\ngrains = 600\n[box]\nsize = [16.1199, 16.1199, 16.1199]\n\
                [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n\
                aspect_ratio = { distribution = \"constant\", value = 1.5 }\n";
    let (p, _) = pack_scene(text, Rotation::None);
    let first = &p.trials[0];
    assert_eq!(first.scale, effort::OVERSHOOT, "{:?}", p.trials);
    assert!(first.fire_steps <= effort::OVERSHOOT_STEPS, "{first:?}");
    assert_eq!(p.trials[1].scale, 1.0, "{:?}", p.trials);
    assert_eq!(p.stop, StopReason::TargetReached, "{}", p.fraction);
    assert!((p.fraction - 0.60).abs() < 1e-3, "{}", p.fraction);
    assert!(p.verification.is_clean(), "{:?}", p.verification);
}

/// A loop's context for spheres that do not turn, with no time limit.
pub(super) fn context<'a>(
    tuning: &Tuning,
    stop: &'a AtomicBool,
    progress: &'a mut dyn FnMut(&Progress),
) -> Context<'a> {
    Context {
        neighbours: Neighbours::new(tuning.neighbours),
        forces: Default::default(),
        counters: Counters::default(),
        rotation: Rotation::None,
        max_turn: std::f64::consts::PI,
        contact_gap: 0.0,
        resolution: 1e-3,
        stop,
        deadline: None,
        started: std::time::Instant::now(),
        give_way: None,
        progress,
    }
}

/// A relaxation told to keep the step (the target's after the overshoot) starts at the
/// step size the last one ended with, once; the next starts at FIRE's own start again.
#[test]
fn a_relaxation_that_keeps_the_step_starts_where_the_last_one_ended() {
    let mut state = scattered(&format!("seed = 3\n{SPHERES_063}"));
    let tuning = Tuning::default();
    let stop = AtomicBool::new(false);
    let mut progress = |_: &Progress| {};
    let mut run = context(&tuning, &stop, &mut progress);
    let mut fire = Fire::new(tuning.fire);
    let big_s = 1.0 + tuning.protocol.margin;
    // From random places the power stays positive and the step grows.
    fire.relax(&mut state, &mut run, 1.0, big_s, 60).unwrap();
    let grown = fire.step_size();
    assert!(grown > tuning.fire.dt_start, "{grown}");
    // A relaxation with no steps left shows where it would start.
    fire.keep_step = true;
    fire.relax(&mut state, &mut run, 1.0, big_s, 0).unwrap();
    assert_eq!(fire.step_size(), grown);
    assert!(!fire.keep_step);
    fire.relax(&mut state, &mut run, 1.0, big_s, 0).unwrap();
    assert_eq!(fire.step_size(), tuning.fire.dt_start);
}

/// Rounding of a scale near 1 computed as `s − step` (a few ulps of 1).
const SCALE_ROUNDING: f64 = 1e-12;
/// Relative rounding of a difference of two scales near 1 against the step it was
/// made with: the difference loses about `ulp(1) / step` ≈ 5e-13 relative at the
/// least step (4.5e-4), allowed with room.
const STEP_ROUNDING: f64 = 1e-9;

/// With `ProtocolParams::descent` (the default) the search lowers the scale from the
/// first deep jam (module `descent`): 1 000 equal spheres asked 0.70 jam within 0.001
/// of the bisection's packing fraction in fewer FIRE steps (1 405 against 3 127, 0.6422
/// both), its first segment short at the jam's own scale, each later one lower than the
/// last by at most `descent::MAX_STEP` and at least `descent::FLOOR` resolutions, none
/// longer than `descent::SEGMENT` of a trial.
#[test]
fn the_descent_jams_as_dense_as_the_bisection_in_fewer_steps() {
    let (scene, specs) = drawn(
        "seed = 1\ngrains = 1000\n[box]\nsize = [18.16, 18.16, 18.16]\n\
         [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n",
    );
    let run = |descent| {
        let mut tuning = Tuning::default();
        tuning.protocol.descent = descent;
        pack(
            &job(&scene, &specs, &tuning),
            &AtomicBool::new(false),
            &mut |_| {},
        )
        .unwrap()
    };
    let (bisected, descended) = (run(false), run(true));
    for p in [&bisected, &descended] {
        assert_eq!(p.stop, StopReason::Jammed);
        assert!(p.verification.is_clean(), "{:?}", p.verification);
    }
    let (b, d) = (bisected.counters.fire_steps, descended.counters.fire_steps);
    assert!(d < b, "{d} steps against {b}");
    assert!(
        descended.fraction > bisected.fraction - 1e-3,
        "{} against {}",
        descended.fraction,
        bisected.fraction
    );
    let trial = ProtocolParams::default().trial_steps as f64;
    let segments = &descended.trials[1..];
    assert_eq!(segments[0].scale, descended.trials[0].scale);
    assert!(segments[0].fire_steps as f64 <= (trial * descent::SEGMENT * descent::SHORT).ceil());
    for pair in segments.windows(2) {
        let (a, b) = (pair[0].scale, pair[1].scale);
        assert!(
            b < a && b >= a * (1.0 - descent::MAX_STEP) - SCALE_ROUNDING,
            "{a} -> {b}"
        );
        let floor = descent::FLOOR * scene.packing.jam_resolution * a;
        assert!(a - b >= floor * (1.0 - STEP_ROUNDING));
    }
    assert!(segments
        .iter()
        .all(|t| t.fire_steps as f64 <= (trial * descent::SEGMENT).ceil()));
}
