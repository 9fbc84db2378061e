//! The swap moves on small scenes: alone (energy, positions, orientations) and in the
//! loop (clean, frozen, deterministic, never less dense).

use super::swap::sweep;
use super::*;
use crate::packing::forces::Forces;
use crate::packing::neighbours::Neighbours;
use crate::packing::tests::{drawn, scattered};
use crate::packing::{pack, Job, NeighbourParams, Packing, StopReason, Tuning};
use crate::scene::{GrainSpec, Scene};
use std::sync::atomic::AtomicBool;

/// 150 frozen spheroids of aspect 1.5 with lognormal sizes, random orientations, asked
/// to fill about 0.74 of a periodic cube: more than they reach, so the loop jams.
const POLY_SPHEROIDS: &str = r#"
seed = 5
grains = 150
[box]
size = [10.4, 10.4, 10.4]
[[phase]]
size = { distribution = "lognormal", sigma = 0.25, scale = 2.0, min = 1.0, max = 4.0 }
aspect_ratio = { distribution = "constant", value = 1.5 }
"#;

/// 150 equal spheroids of aspect 1.5, frozen in random orientations, asked 0.75
/// (the loop's own tests' scene): their swaps exchange orientations between places.
const EQUAL_SPHEROIDS: &str = crate::packing::tests::DENSE_SPHEROIDS;

/// 100 equal spheres.
const EQUAL_SPHERES: &str = r#"
seed = 5
grains = 100
[box]
size = [8.3, 8.3, 8.3]
[[phase]]
size = { distribution = "constant", value = 2.0 }
"#;

/// The overlap energy of the state at scale `big_s`, from the loop's own forces.
fn energy(state: &mut State, big_s: f64) -> f64 {
    let mut neighbours = Neighbours::new(NeighbourParams::default());
    neighbours.update(state, big_s).unwrap();
    let mut forces = Forces::default();
    forces.evaluate(state, &neighbours.pairs, neighbours.builds, big_s, false);
    forces.energy
}

fn sorted_places(state: &State) -> Vec<[f64; 3]> {
    let mut places = state.centres.clone();
    places.sort_by(|a, b| a.partial_cmp(b).unwrap());
    places
}

/// A sweep keeps only swaps that lower the energy (so the total falls), moves grains
/// only onto one another's places, and turns none.
#[test]
fn a_sweep_lowers_the_energy_and_only_exchanges_places() {
    let mut state = scattered(POLY_SPHEROIDS);
    let big_s = 1.0;
    state.wrap();
    let (places, turns) = (sorted_places(&state), state.quaternions.clone());
    let before = energy(&mut state, big_s);
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let (attempts, swaps) = sweep(&mut state, big_s, &mut rng, &|| false).unwrap();
    assert!(attempts > 100, "{attempts}");
    assert!(swaps > 0, "no swap kept of {attempts}");
    let after = energy(&mut state, big_s);
    assert!(after < before, "{after} ≥ {before}");
    assert_eq!(sorted_places(&state), places);
    assert_eq!(state.quaternions, turns);
    // Sweeps again until one keeps no swap: the energy never rises.
    let mut last = after;
    for _ in 0..20 {
        let (_, swaps) = sweep(&mut state, big_s, &mut rng, &|| false).unwrap();
        let now = energy(&mut state, big_s);
        assert!(now <= last, "{now} > {last}");
        last = now;
        if swaps == 0 {
            break;
        }
    }
}

/// Equal spheres have nothing to swap: no attempt, nothing moved.
#[test]
fn equal_spheres_have_nothing_to_swap() {
    let mut state = scattered(EQUAL_SPHERES);
    state.wrap();
    let centres = state.centres.clone();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    assert_eq!(sweep(&mut state, 1.0, &mut rng, &|| false).unwrap(), (0, 0));
    assert_eq!(state.centres, centres);
}

/// The sweeps of both kinds of unjamming moves stop when told (the stop flag, the time
/// limit: `HALT_EVERY`): no attempt, nothing moved, and a sweep that was told after its
/// first block of grains attempts that block only.
#[test]
fn sweeps_stop_when_told() {
    let mut state = scattered(POLY_SPHEROIDS);
    state.wrap();
    let (centres, turns) = (state.centres.clone(), state.quaternions.clone());
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    assert_eq!(sweep(&mut state, 1.0, &mut rng, &|| true).unwrap(), (0, 0));
    let moves = monte_carlo::Moves {
        rotation: crate::scene::Rotation::Free,
        max_turn: std::f64::consts::PI,
        contact_gap: 0.0,
    };
    let mut mc = monte_carlo::MonteCarlo::new(&state, 0.5);
    let halted = mc.sweeps(&mut state, 0.5, 3, &moves, &mut rng, &|| true);
    assert_eq!(halted.unwrap(), (0, 0));
    assert_eq!((state.centres, state.quaternions), (centres, turns));
    // 2 000 grains, told to stop at the second block: at most HALT_EVERY attempts.
    let bigger = (POLY_SPHEROIDS.replace("grains = 150", "grains = 2000"))
        .replace("[10.4, 10.4, 10.4]", "[24.6, 24.6, 24.6]");
    let mut state = scattered(&bigger);
    let asked = std::cell::Cell::new(0);
    let second = || {
        asked.set(asked.get() + 1);
        asked.get() > 1
    };
    let (attempts, _) = sweep(&mut state, 1.0, &mut rng, &second).unwrap();
    assert!(attempts > 0 && attempts <= HALT_EVERY as u64, "{attempts}");
    // Asked every HALT_EVERY grains, and sooner once the attempts since have looked at
    // HALT_WORK neighbours (grains with thousands each), which then count afresh.
    let (yes, no) = (|| true, || false);
    assert!(halts(0, &mut 0, &yes) && halts(2 * HALT_EVERY, &mut 0, &yes));
    assert!(!halts(1, &mut (HALT_WORK - 1), &yes));
    let mut work = HALT_WORK;
    assert!(halts(1, &mut work, &yes) && work == 0);
    assert!(!halts(HALT_EVERY, &mut 5, &no));
}

fn pack_on(threads: usize, scene: &Scene, specs: &[GrainSpec]) -> Packing {
    let tuning = Tuning::default();
    let job = Job {
        specs,
        domain: &scene.domain,
        params: &scene.packing,
        tuning: &tuning,
        seed: scene.seed,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| pack(&job, &AtomicBool::new(false), &mut |_| {}))
        .unwrap()
}

/// In the loop (effort 2, `unjam = "swap"`): swaps are kept, the result is clean and
/// at least as dense as the first search (effort 1), the frozen orientations are
/// exactly as drawn, and one and two threads give the same grains bit for bit.
#[test]
fn swaps_in_the_loop_keep_it_clean_frozen_deterministic_and_never_less_dense() {
    let (mut scene, specs) = drawn(EQUAL_SPHEROIDS);
    let first = pack_on(1, &scene, &specs);
    scene.packing.effort = 2.0;
    scene.packing.unjam = Unjam::Swap;
    let one = pack_on(1, &scene, &specs);
    let two = pack_on(2, &scene, &specs);
    assert_eq!(one.stop, StopReason::Jammed);
    assert!(
        one.counters.swaps > 0,
        "{} {} {:?}",
        first.fraction,
        one.fraction,
        one.counters
    );
    assert_clean_frozen_denser_deterministic(&first, &one, &two, &specs);
}

/// `one` (and `two`, the same job on two threads) after unjamming moves: clean, at
/// least as dense as `first` (no moves), the frozen orientations exactly as drawn, and
/// the same on one and two threads.
fn assert_clean_frozen_denser_deterministic(
    first: &Packing,
    one: &Packing,
    two: &Packing,
    specs: &[GrainSpec],
) {
    assert!(one.verification.is_clean(), "{:?}", one.verification);
    assert!(
        one.fraction >= first.fraction,
        "{} < {}",
        one.fraction,
        first.fraction
    );
    for (g, s) in one.grains.iter().zip(specs) {
        assert_eq!(g.quaternion, s.quaternion);
    }
    assert_eq!(one.fraction, two.fraction);
    assert_eq!(one.counters.swaps, two.counters.swaps);
    for (a, b) in one.grains.iter().zip(&two.grains) {
        assert_eq!((a.centre, a.quaternion), (b.centre, b.quaternion));
    }
}

/// `unjam = "anneal"` on frozen spheroids between walls: the Monte Carlo turns no
/// frozen grain (swaps carry no orientation either), every grain stays inside the
/// walls, the result is clean, at least as dense as the first search, and the same
/// on one and two threads.
#[test]
fn annealing_keeps_frozen_grains_inside_the_walls_and_deterministic() {
    let text = POLY_SPHEROIDS.replace("[box]", "[box]\nboundary = \"reflecting\"");
    let (mut scene, specs) = drawn(&text);
    let first = pack_on(1, &scene, &specs);
    scene.packing.effort = 1.5;
    scene.packing.unjam = Unjam::Anneal;
    let one = pack_on(1, &scene, &specs);
    let two = pack_on(2, &scene, &specs);
    assert!(one.counters.swaps > 0, "{:?}", one.counters);
    assert_clean_frozen_denser_deterministic(&first, &one, &two, &specs);
}

/// The rounds per cycle follow the documented schedule: 8 with one cycle, doubled per
/// further cycle, never past `SWAP_ROUNDS`, whatever the cycle count.
#[test]
fn swap_rounds_double_with_the_cycles_up_to_the_cap() {
    let rounds: Vec<usize> = (1..=5).map(swap_rounds).collect();
    assert_eq!(
        rounds,
        [FIRST_SWAP_ROUNDS, 16, SWAP_ROUNDS, SWAP_ROUNDS, SWAP_ROUNDS]
    );
    assert_eq!(swap_rounds(u32::MAX), SWAP_ROUNDS);
}
