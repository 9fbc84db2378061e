//! Forces and torques against finite differences of the energy.

use super::chunk::round_down;
use super::*;
use crate::contact::dot;
use crate::packing::grains::rotate_by;
use crate::scene::{Domain, GrainSpec};

/// Central differences of an energy that is smooth near the test point: step
/// 1e-6 of the lengths involved gives an error of about 1e-12 (truncation) +
/// 1e-10 (rounding of E ≈ 1 over 2e-6), so 1e-6 relative is a safe bound.
const FD_STEP: f64 = 1e-6;
const FD_TOL: f64 = 1e-6;

fn grain(axes: [f64; 3], q: [f64; 4]) -> GrainSpec {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    GrainSpec {
        phase: 0,
        semi_axes: axes,
        quaternion: q.map(|x| x / n),
        diameter: 2.0 * axes.iter().product::<f64>().cbrt(),
        aspect_ratio: axes[0] / axes[1],
        tilt: None,
        turn_axis: None,
        crystal: [1.0, 0.0, 0.0, 0.0],
        dimension: crate::contact::Dimension::Three,
    }
}

fn two_grains(domain: &Domain) -> State {
    let specs = [
        grain([3.0, 1.0, 0.7], [0.9, 0.2, -0.3, 0.1]),
        grain([2.0, 1.5, 0.5], [0.4, -0.5, 0.6, 0.3]),
    ];
    let mut state = State::new(&specs, domain, 0.0).unwrap();
    state.centres = vec![[10.0, 10.0, 10.0], [11.2, 10.5, 9.8]];
    state
}

const PAIR: [Pair; 1] = [Pair {
    i: 0,
    j: 1,
    image: [0; 3],
}];

fn energy(state: &State, big_s: f64) -> f64 {
    let mut f = Forces::default();
    f.evaluate(state, &PAIR, 1, big_s, true);
    f.energy
}

#[test]
fn forces_and_torques_are_minus_the_gradient_of_the_energy() {
    let domain = Domain::new([30.0; 3], Boundary::Periodic);
    let mut state = two_grains(&domain);
    let big_s = 1.1;
    let mut f = Forces::default();
    f.evaluate(&state, &PAIR, 1, big_s, true);
    assert_eq!(f.overlaps, 1, "the test pair must overlap");
    assert!(f.energy > 0.0);
    let scale = f.force[1].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for g in 0..2 {
        for k in 0..3 {
            let c = state.centres[g][k];
            state.centres[g][k] = c + FD_STEP;
            let up = energy(&state, big_s);
            state.centres[g][k] = c - FD_STEP;
            let down = energy(&state, big_s);
            state.centres[g][k] = c;
            let numeric = -(up - down) / (2.0 * FD_STEP);
            assert!(
                (numeric - f.force[g][k]).abs() <= FD_TOL * scale,
                "force on {g} along {k}: {} vs {numeric}",
                f.force[g][k]
            );

            let q = state.quaternions[g];
            let mut axis = [0.0; 3];
            axis[k] = FD_STEP;
            state.set_orientations(&[(g, rotate_by(q, axis))]).unwrap();
            let up = energy(&state, big_s);
            axis[k] = -FD_STEP;
            state.set_orientations(&[(g, rotate_by(q, axis))]).unwrap();
            let down = energy(&state, big_s);
            state.set_orientations(&[(g, q)]).unwrap();
            let numeric = -(up - down) / (2.0 * FD_STEP);
            assert!(
                (numeric - f.torque[g][k]).abs() <= FD_TOL * scale * 3.0,
                "torque on {g} about {k}: {} vs {numeric}",
                f.torque[g][k]
            );
        }
    }
    // Newton's third law: the forces cancel.
    for k in 0..3 {
        assert_eq!(f.force[0][k], -f.force[1][k]);
    }
}

#[test]
fn wall_forces_and_torques_are_minus_the_gradient_of_the_energy() {
    let domain = Domain::new([4.0, 30.0, 30.0], Boundary::Reflecting);
    let mut state = two_grains(&domain);
    // Grain 0 pokes through the low x wall only.
    state.centres = vec![[1.5, 10.0, 10.0], [2.0, 20.0, 20.0]];
    let pairs: [Pair; 0] = [];
    let big_s = 1.0;
    let wall_energy = |state: &State| {
        let mut f = Forces::default();
        f.evaluate(state, &pairs, 1, big_s, true);
        f.energy
    };
    let mut f = Forces::default();
    f.evaluate(&state, &pairs, 1, big_s, true);
    assert!(f.wall_hits >= 1 && f.energy > 0.0);
    let scale = f.force[0][0].abs();
    for k in 0..3 {
        let c = state.centres[0][k];
        state.centres[0][k] = c + FD_STEP;
        let up = wall_energy(&state);
        state.centres[0][k] = c - FD_STEP;
        let down = wall_energy(&state);
        state.centres[0][k] = c;
        let numeric = -(up - down) / (2.0 * FD_STEP);
        assert!((numeric - f.force[0][k]).abs() <= FD_TOL * scale);

        let q = state.quaternions[0];
        let mut axis = [0.0; 3];
        axis[k] = FD_STEP;
        state.set_orientations(&[(0, rotate_by(q, axis))]).unwrap();
        let up = wall_energy(&state);
        axis[k] = -FD_STEP;
        state.set_orientations(&[(0, rotate_by(q, axis))]).unwrap();
        let down = wall_energy(&state);
        state.set_orientations(&[(0, q)]).unwrap();
        let numeric = -(up - down) / (2.0 * FD_STEP);
        assert!(
            (numeric - f.torque[0][k]).abs() <= FD_TOL * scale * 3.0,
            "wall torque about {k}: {} vs {numeric}",
            f.torque[0][k]
        );
    }
}

#[test]
fn two_spheres_feel_twice_their_overlap() {
    let domain = Domain::new([30.0; 3], Boundary::Periodic);
    let specs = [
        grain([1.0; 3], [1.0, 0.0, 0.0, 0.0]),
        grain([2.0; 3], [1.0, 0.0, 0.0, 0.0]),
    ];
    let mut state = State::new(&specs, &domain, 0.0).unwrap();
    state.centres = vec![[5.0, 5.0, 5.0], [7.5, 5.0, 5.0]];
    let mut f = Forces::default();
    f.evaluate(&state, &PAIR, 1, 1.0, false);
    // σ = 3, d = 2.5: force 2 (σ − d) = 1 along +x on the second sphere; the
    // fast contact function is good to ~1e-15 on spheres.
    assert!((f.force[1][0] - 1.0).abs() < 1e-12, "{:?}", f.force[1]);
    assert!(f.force[1][1].abs() < 1e-12 && f.force[1][2].abs() < 1e-12);
    assert!((f.energy - 0.25).abs() < 1e-12);
}

/// The bound behind skipping pairs while grains move and turn: a pair at μ₁ = m, whose
/// offset then changes by `d` and whose grains turn by δ_i, δ_j, has
/// `μ₁ ≥ (m − d/ρ) / (1 + (δ_i a_i + δ_j a_j)/ρ)` (ρ the sum of the smallest
/// semi-axes, a the largest). Checked with the accurate contact function on random
/// shapes, offsets, moves and turns, including turns of a radian; the bound is often
/// nearly tight for a pure move, so rounding is allowed for (1e-12 relative). So is the
/// bounding spheres' `μ₁ ≥ (|r| − d)/(b_i + b_j)` (b the largest semi-axes), whatever
/// the turns, which the narrow phase takes where it is the larger.
#[test]
fn a_pairs_contact_factor_stays_above_its_move_and_turn_bound() {
    use crate::contact::{contact_function, Ellipsoid};
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
    let unit = |rng: &mut rand_chacha::ChaCha8Rng| {
        let q: [f64; 4] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        q.map(|x| x / n)
    };
    let (mut tight, mut spheres_larger) = (0, 0);
    for _ in 0..2000 {
        let axes: [[f64; 3]; 2] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.random_range(0.2..3.0)));
        let (qi, qj) = (unit(&mut rng), unit(&mut rng));
        let r: [f64; 3] = std::array::from_fn(|_| rng.random_range(-6.0..6.0));
        let mu = |qi: [f64; 4], qj: [f64; 4], r: &[f64; 3]| {
            let (ei, ej) = (
                Ellipsoid::new(axes[0], qi).unwrap(),
                Ellipsoid::new(axes[1], qj).unwrap(),
            );
            contact_function(r, &ei.q, &ej.q).unwrap().mu2.sqrt()
        };
        let m = mu(qi, qj, &r);
        let big = rng.random_bool(0.5);
        let size = if big { 1.0 } else { 0.05 };
        let turn: [[f64; 3]; 2] =
            std::array::from_fn(|_| std::array::from_fn(|_| size * rng.random_range(-1.0..1.0)));
        let shift: [f64; 3] = std::array::from_fn(|_| size * rng.random_range(-1.0..1.0));
        let (qi2, qj2) = (rotate_by(qi, turn[0]), rotate_by(qj, turn[1]));
        let r2: [f64; 3] = std::array::from_fn(|k| r[k] + shift[k]);
        let norm = |v: &[f64; 3]| dot(v, v).sqrt();
        let amin = |a: &[f64; 3]| a[0].min(a[1]).min(a[2]);
        let amax = |a: &[f64; 3]| a[0].max(a[1]).max(a[2]);
        let rho = amin(&axes[0]) + amin(&axes[1]);
        let swept = norm(&turn[0]) * amax(&axes[0]) + norm(&turn[1]) * amax(&axes[1]);
        let bound = (m - norm(&shift) / rho) / (1.0 + swept / rho);
        let now = mu(qi2, qj2, &r2);
        assert!(now >= bound * (1.0 - 1e-12), "μ₁ {now} below bound {bound}");
        tight += usize::from(now < 1.2 * bound);
        let spheres = (norm(&r) - norm(&shift)) / (amax(&axes[0]) + amax(&axes[1]));
        assert!(now >= spheres * (1.0 - 1e-12), "μ₁ {now} below {spheres}");
        spheres_larger += usize::from(spheres > bound);
    }
    // The bounds are not vacuous: the first is within 20 % for some pairs, and the
    // spheres' is the larger for some.
    assert!(tight > 0 && spheres_larger > 0, "{tight} {spheres_larger}");
}

/// How far a tracked pair's force may stray from the maximiser's: its normal is taken
/// at λ* to first order in the last Newton step δ, so it errs by `O(δ²)`, about
/// `TRACK_GAIN` (`pair.rs`) (measured here: 8.7e-7 for forces, 9.5e-7 for torques,
/// relative to the largest; 1.5e-4 and 5.4e-4 with the normal at λ itself).
const TRACKED_FORCE_TOL: f64 = 1e-5;
/// The energy is second order in λ's error: within `TRACK_GAIN` of μ² (measured 3e-7).
const TRACKED_ENERGY_TOL: f64 = 2e-6;

/// The largest difference of two fields of vectors, relative to the largest of `b`.
fn deviation(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    let norm = |v: &[f64; 3]| dot(v, v).sqrt();
    let top = b.iter().map(norm).fold(0.0, f64::max);
    let off = a
        .iter()
        .zip(b)
        .map(|(x, y)| norm(&std::array::from_fn(|k| x[k] - y[k])));
    off.fold(0.0, f64::max) / top.max(f64::MIN_POSITIVE)
}

/// The skip test (allowances in `f32` against each grain's motion) never skips a pair
/// that overlaps: over many small moves and turns of a crowd within one list build,
/// the same pairs overlap as in a fresh evaluation that tests every pair, with the
/// same forces, torques and energy to the tracking's tolerance, and pairs are skipped
/// at all.
#[test]
fn skipping_pairs_changes_no_force() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
    let domain = Domain::new([6.0; 3], Boundary::Periodic);
    let specs: Vec<GrainSpec> = (0..40)
        .map(|_| {
            let axes = [rng.random_range(0.4..0.8), 0.4, rng.random_range(0.3..0.4)];
            grain(axes, std::array::from_fn(|_| rng.random_range(-1.0..1.0)))
        })
        .collect();
    let mut state = State::new(&specs, &domain, 0.0).unwrap();
    state.centres = (0..40)
        .map(|_| std::array::from_fn(|_| rng.random_range(1.0..5.0)))
        .collect();
    let pairs: Vec<Pair> = (0..40u32)
        .flat_map(|i| {
            (i + 1..40).map(move |j| Pair {
                i,
                j,
                image: [0; 3],
            })
        })
        .collect();
    let mut kept = Forces::default();
    let (mut skipped, mut overlapping) = (0, 0);
    for step in 0..60 {
        let big_s = if step < 30 { 0.9 } else { 0.95 };
        kept.evaluate(&state, &pairs, 1, big_s, true);
        let mut fresh = Forces::default();
        fresh.evaluate(&state, &pairs, 1, big_s, true);
        // A fresh evaluation starts every pair's λ anew, so the two agree to the
        // tracking's tolerance, not bit for bit; a pair skipped wrongly would lose a
        // whole force, or change the count.
        assert_eq!(kept.overlaps, fresh.overlaps, "step {step}");
        assert!(
            deviation(&kept.force, &fresh.force) <= TRACKED_FORCE_TOL,
            "step {step}"
        );
        assert!(
            deviation(&kept.torque, &fresh.torque) <= TRACKED_FORCE_TOL,
            "step {step}"
        );
        let energy = (kept.energy - fresh.energy).abs();
        assert!(energy <= TRACKED_ENERGY_TOL * fresh.energy, "step {step}");
        skipped += fresh.tested - kept.tested;
        overlapping += kept.overlaps;
        for c in &mut state.centres {
            c.iter_mut()
                .for_each(|x| *x += rng.random_range(-0.01..0.01));
        }
        let turned: Vec<(usize, [f64; 4])> = (0..40)
            .map(|i| {
                let angle = std::array::from_fn(|_| rng.random_range(-0.01..0.01));
                (i, rotate_by(state.quaternions[i], angle))
            })
            .collect();
        state.set_orientations(&turned).unwrap();
    }
    assert!(
        skipped > 0 && overlapping > 0,
        "{skipped} skipped, {overlapping} overlapping"
    );
}

#[test]
fn allowances_round_down() {
    for x in [0.1, -0.1, 1.0 / 3.0, 1e-30, -7e12, 123.456_789] {
        assert!(f64::from(round_down(x)) <= x, "{x}");
        assert!(
            (f64::from(round_down(x)) - x).abs() <= x.abs() * 1.2e-7,
            "{x}"
        );
    }
}
