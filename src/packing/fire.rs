//! FIRE, the fast inertial relaxation engine (Bitzek et al., *Phys. Rev. Lett.* 97,
//! 170201, 2006), with the corrections of FIRE 2.0 (Guénolé et al., *Comput. Mater.
//! Sci.* 175, 109584, 2020): damped dynamics that accelerate while the power `F·v` is
//! positive and stop dead when it turns negative. It minimises the overlap energy of
//! [`Forces`] at a fixed scale until the grains are apart.

use super::forces::Forces;
use super::grains::rotate_by;
use super::jamming::{JamTest, Patience, Verdict};
use super::neighbours::Neighbours;
use super::state::{State, GRAINS_PER_TASK};
use super::{Counters, FireParams, Outcome, PackError, Progress};
use crate::contact::dot;
use crate::scene::{Boundary, Rotation};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// What a relaxation works with besides the grains: the broad and narrow phase's
/// buffers, the counters, and the caller's stop flag and progress report.
pub(crate) struct Context<'a> {
    pub neighbours: Neighbours,
    pub forces: Forces,
    pub counters: Counters,
    pub rotation: Rotation,
    /// The most a grain may turn from its drawn orientation (radians).
    pub max_turn: f64,
    /// [`ProtocolParams::contact_gap`](super::ProtocolParams::contact_gap).
    pub contact_gap: f64,
    /// The bisection's relative resolution (`packing.jam_resolution`): the jamming
    /// test's measure of an overlap that matters.
    pub resolution: f64,
    pub stop: &'a AtomicBool,
    /// When `packing.time_limit` runs out: a relaxation then stops as at `stop`.
    pub deadline: Option<Instant>,
    /// When a relaxation gives way as if out of steps ([`Outcome::Budget`]): the
    /// loop sets it, under a time limit, for the relaxations above the target before
    /// its search (`effort::GIVE_WAY`).
    pub give_way: Option<Instant>,
    pub progress: &'a mut dyn FnMut(&Progress),
}

/// The integrator's state: velocities (angular ones in length units, `ω × L`) and the
/// adaptive step.
pub(crate) struct Fire {
    params: FireParams,
    velocity: Vec<[f64; 3]>,
    spin: Vec<[f64; 3]>,
    levers: Vec<f64>,
    /// The torques each grain may follow, over their levers.
    torques: Vec<[f64; 3]>,
    /// The grains turned in a step, with their new orientations.
    turned: Vec<(usize, [f64; 4])>,
    dt: f64,
    alpha: f64,
    positive: u32,
    /// Stiffness of a pull of every grain back toward its drawn orientation: energy
    /// `restore · L² |θ|² / 2`, `L` its lever and θ its turn (rotation vector); 0 for
    /// none. While it is set, a clean state does not end a relaxation.
    pub restore: f64,
    /// Each grain's turn from its drawn orientation, while restoring.
    turns: Vec<[f64; 3]>,
    /// When a shallow relaxation counts as jammed (the jamming test's patience,
    /// module `jamming`).
    pub patience: Patience,
    /// Whether the last relaxation's last energy per grain was deep
    /// ([`DEEP`](super::jamming::DEEP) times the margin's): far above its jamming
    /// point. Meaningful after a relaxation that did not end clean.
    pub deep: bool,
    /// Set before a relaxation to start it at the step size the last one ended with
    /// instead of FIRE's start (velocities are zeroed as ever, so its first step
    /// halves that size as after any stop); cleared by it. For the target's relaxation
    /// after the overshoot (`effort::OVERSHOOT`): the same grains, 3 % smaller and
    /// about as stiff, where restarting from `dt_start` spent the first steps growing
    /// the step again (10⁵ grains: 85–89 steps at the target instead of 106–111;
    /// BENCHMARKS.md, "Issue 26: against b030b67 again").
    pub keep_step: bool,
    /// The square root of each grain's mass (see [`masses`]).
    root_mass: Vec<f64>,
    /// Each grain's force over its root mass.
    scaled: Vec<[f64; 3]>,
}

impl Fire {
    pub fn new(params: FireParams) -> Self {
        Self {
            params,
            velocity: Vec::new(),
            spin: Vec::new(),
            levers: Vec::new(),
            torques: Vec::new(),
            turned: Vec::new(),
            dt: params.dt_start,
            alpha: params.alpha_start,
            positive: 0,
            restore: 0.0,
            turns: Vec::new(),
            deep: false,
            keep_step: false,
            patience: Patience::NONE,
            root_mass: Vec::new(),
            scaled: Vec::new(),
        }
    }

    /// The current step size.
    #[cfg(test)]
    pub fn step_size(&self) -> f64 {
        self.dt
    }

    /// Sets the jamming test's window (steps) of the next relaxations.
    pub fn set_window(&mut self, window: u64) {
        self.params.window = window.max(1);
    }

    /// Relaxes the state at scale `s`, with the energy taken at `big_s ≥ s` (the
    /// margin makes the last overlaps vanish at `s` before the energy reaches zero).
    pub fn relax(
        &mut self,
        state: &mut State,
        run: &mut Context<'_>,
        s: f64,
        big_s: f64,
        budget: u64,
    ) -> Result<Outcome, PackError> {
        let rotate = run.rotation != Rotation::None;
        let turning = (run.rotation, run.max_turn);
        let n = state.len();
        self.velocity.clear();
        self.velocity.resize(n, [0.0; 3]);
        self.spin.clear();
        self.spin.resize(n, [0.0; 3]);
        let p = self.params;
        if !std::mem::take(&mut self.keep_step) {
            self.dt = p.dt_start;
        }
        self.alpha = p.alpha_start;
        self.positive = 0;
        // A contact overlapping by the margin has energy (2ρ (S − s))², ρ the smallest
        // semi-axis: the jamming test's unit.
        let mean_rho2 = state
            .shapes
            .iter()
            .map(|e| e.inscribed_radius().powi(2))
            .sum::<f64>()
            / n as f64;
        let margin_energy = 4.0 * (big_s - s).powi(2) * mean_rho2;
        let mut jam = JamTest::new(
            p.window,
            p.plateau_slope,
            margin_energy,
            run.resolution,
            self.patience,
        );
        masses(state, &mut self.root_mass);
        self.deep = false;
        for _ in 0..budget {
            if run.stop.load(Ordering::Relaxed) || run.deadline.is_some_and(|d| Instant::now() >= d)
            {
                return Ok(Outcome::Interrupted);
            }
            if run.give_way.is_some_and(|d| Instant::now() >= d) {
                return Ok(Outcome::Budget);
            }
            let Context {
                neighbours,
                forces,
                counters,
                ..
            } = run;
            let t0 = Instant::now();
            if neighbours.update(state, big_s)? {
                counters.list_builds += 1;
            }
            let t1 = Instant::now();
            forces.evaluate(state, &neighbours.pairs, neighbours.builds, big_s, rotate);
            let t2 = Instant::now();
            counters.broad_phase += t1 - t0;
            counters.narrow_phase += t2 - t1;
            counters.pairs_tested += forces.tested;
            counters.fire_steps += 1;
            let mut energy = forces.energy;
            if self.restore > 0.0 {
                // Kept for the step's pull, which needs the same turns.
                self.turns.clear();
                self.turns.extend((0..n).map(|i| state.turn(i)));
                energy += (self.turns.iter().zip(&state.shapes))
                    .map(|(t, e)| {
                        let l = big_s * e.bounding_radius();
                        0.5 * self.restore * l * l * dot(t, t)
                    })
                    .sum::<f64>();
            } else if forces.min_mu1 >= s * (1.0 + run.contact_gap) && self.inside(state, forces, s)
            {
                counters.response += t2.elapsed();
                return Ok(Outcome::Clean);
            }
            (run.progress)(&Progress {
                step: counters.fire_steps,
                scale: s,
                fraction: state.fraction(s),
                overlaps: forces.overlaps,
            });
            let overlap = (1.0 - forces.min_mu1 / s).max(0.0);
            self.deep = jam.is_deep(energy / n as f64);
            if jam.step(energy / n as f64, overlap) == Verdict::Jammed && self.restore == 0.0 {
                counters.response += t2.elapsed();
                return Ok(Outcome::Stuck);
            }
            self.step(state, forces, big_s, turning)?;
            counters.response += t2.elapsed();
        }
        Ok(Outcome::Budget)
    }

    fn inside(&self, state: &State, forces: &Forces, s: f64) -> bool {
        state.domain.boundary == Boundary::Periodic
            || forces.wall_hits == 0
            || (0..state.len()).all(|i| state.inside_walls(i, s))
    }

    /// One FIRE 2.0 step: power check, semi-implicit Euler, velocity mixing.
    fn step(
        &mut self,
        state: &mut State,
        forces: &Forces,
        big_s: f64,
        (mode, max_turn): (Rotation, f64),
    ) -> Result<(), PackError> {
        let (n, p) = (state.len(), self.params);
        let rotate = mode != Rotation::None;
        // Angular degrees of freedom in length units: ω × (S · largest semi-axis);
        // only rotating grains need them.
        self.levers.clear();
        self.torques.clear();
        if rotate {
            self.levers
                .extend(state.shapes.iter().map(|e| big_s * e.bounding_radius()));
            let kappa = self.restore;
            self.torques.extend((0..n).map(|i| {
                let l = self.levers[i];
                let mut t = forces.torque[i];
                if kappa > 0.0 {
                    axpy(&mut t, -kappa * l * l, &self.turns[i]);
                }
                let m = self.root_mass[i];
                state.allowed_torque(i, t, mode).map(|x| x / (l * m))
            }));
        }
        let (levers, torques) = (
            std::mem::take(&mut self.levers),
            std::mem::take(&mut self.torques),
        );
        let (lever, torque) = (|i: usize| levers[i], |i: usize| torques[i]);
        // FIRE in mass-weighted coordinates √m x: velocities are √m v, forces F/√m.
        let root_mass = std::mem::take(&mut self.root_mass);
        let mut scaled = std::mem::take(&mut self.scaled);
        scaled.clear();
        scaled.extend((forces.force.iter().zip(&root_mass)).map(|(f, m)| f.map(|x| x / m)));
        let mut power = 0.0;
        for (i, f) in scaled.iter().enumerate() {
            power += dot(f, &self.velocity[i]);
            if rotate {
                power += dot(&torque(i), &self.spin[i]);
            }
        }
        if power > 0.0 {
            self.positive += 1;
            if self.positive > p.n_delay {
                self.dt = (self.dt * p.dt_grow).min(p.dt_max);
                self.alpha *= p.alpha_decay;
            }
        } else {
            self.positive = 0;
            self.dt = (self.dt * p.dt_shrink).max(p.dt_min);
            self.alpha = p.alpha_start;
            // FIRE 2.0: step back half a step, and stop.
            let back = 0.5 * self.dt;
            for ((c, v), m) in state.centres.iter_mut().zip(&self.velocity).zip(&root_mass) {
                for k in 0..3 {
                    c[k] -= back * v[k] / m;
                }
            }
            self.velocity.iter_mut().for_each(|v| *v = [0.0; 3]);
            self.spin.iter_mut().for_each(|v| *v = [0.0; 3]);
        }
        let dt = self.dt;
        // v += dt F, then mix toward the force direction over all degrees of freedom.
        let (mut vv, mut ff) = (0.0, 0.0);
        for (i, &f) in scaled.iter().enumerate() {
            axpy(&mut self.velocity[i], dt, &f);
            vv += dot(&self.velocity[i], &self.velocity[i]);
            ff += dot(&f, &f);
            if rotate {
                let t = torque(i);
                axpy(&mut self.spin[i], dt, &t);
                vv += dot(&self.spin[i], &self.spin[i]);
                ff += dot(&t, &t);
            }
        }
        let mix = if ff > 0.0 {
            self.alpha * (vv / ff).sqrt()
        } else {
            0.0
        };
        let keep = 1.0 - self.alpha;
        let limit = |i: usize| {
            let m = root_mass[i];
            m * p.max_move * big_s * state.shapes[i].inscribed_radius() / dt
        };
        // v ← (1 − α) v + mix F, at most `limit` (a grain moves at most `max_move` of
        // its smallest semi-axis), then x += dt v / √m.
        let advance = |v: &mut [f64; 3], f: &[f64; 3], limit: f64| {
            *v = v.map(|x| keep * x);
            axpy(v, mix, f);
            clamp_norm(v, limit);
        };
        let mut turned = std::mem::take(&mut self.turned);
        turned.clear();
        if rotate {
            for i in 0..n {
                let m = root_mass[i];
                let limit = limit(i);
                let v = &mut self.velocity[i];
                advance(v, &scaled[i], limit);
                axpy(&mut state.centres[i], dt / m, v);
                let l = lever(i);
                let w = &mut self.spin[i];
                advance(w, &torque(i), limit);
                let angle = w.map(|x| dt * x / (l * m));
                if angle.iter().any(|&a| a != 0.0) {
                    let q = rotate_by(state.quaternions[i], angle);
                    if state.within_turn(i, q, max_turn) {
                        turned.push((i, q));
                    } else {
                        // At the limit: the grain stops turning that way.
                        *w = [0.0; 3];
                    }
                }
            }
        } else {
            // Each grain on its own: the same arithmetic in any order.
            let centres = &mut state.centres;
            (self.velocity.par_iter_mut())
                .zip(centres)
                .zip(&scaled)
                .enumerate()
                .with_min_len(GRAINS_PER_TASK)
                .for_each(|(i, ((v, c), f))| {
                    advance(v, f, limit(i));
                    axpy(c, dt / root_mass[i], v);
                });
        }
        let done = state.set_orientations(&turned);
        (self.levers, self.torques, self.turned) = (levers, torques, turned);
        (self.root_mass, self.scaled) = (root_mass, scaled);
        done
    }
}

/// Each grain's root mass `√m`: `m = max(1, (ρ/ρ̃)²)`, ρ its smallest semi-axis and ρ̃
/// the median over the grains. A grain's stiffness is about 2 per contact, and a grain
/// much larger than its neighbours has contacts in proportion to its surface, `(ρ/ρ̃)²`
/// of a typical grain's: with masses in proportion, every grain's own vibration has
/// about the same period, and FIRE's step is no longer held down by the large grains
/// of a mixture. Equal grains keep unit masses.
fn masses(state: &State, root_mass: &mut Vec<f64>) {
    let mut rho: Vec<f64> = state.shapes.iter().map(|e| e.inscribed_radius()).collect();
    let median = if rho.is_empty() {
        1.0
    } else {
        let k = rho.len() / 2;
        *rho.select_nth_unstable_by(k, f64::total_cmp).1
    };
    root_mass.clear();
    root_mass.extend((state.shapes.iter()).map(|e| (e.inscribed_radius() / median).max(1.0)));
}

/// `y += a x`.
fn axpy(y: &mut [f64; 3], a: f64, x: &[f64; 3]) {
    y.iter_mut().zip(x).for_each(|(y, x)| *y += a * x);
}

fn clamp_norm(v: &mut [f64; 3], limit: f64) {
    let norm = dot(v, v).sqrt();
    if norm > limit {
        let f = limit / norm;
        v.iter_mut().for_each(|x| *x *= f);
    }
}
