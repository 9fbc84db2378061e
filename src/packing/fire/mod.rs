//! FIRE, the fast inertial relaxation engine (Bitzek et al., *Phys. Rev. Lett.* 97,
//! 170201, 2006), with the corrections of FIRE 2.0 (Guénolé et al., *Comput. Mater.
//! Sci.* 175, 109584, 2020): damped dynamics that accelerate while the power `F·v` is
//! positive and stop dead when it turns negative. It minimises the overlap energy of
//! [`Forces`] at a fixed scale until the grains are apart.

use super::forces::Forces;
use super::jamming::{JamTest, Patience, Verdict};
use super::neighbours::Neighbours;
use super::state::State;
use super::{Counters, FireParams, Outcome, PackError, Progress};
use crate::contact::dot;
use crate::scene::{Boundary, Rotation};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

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
    /// When `packing.time_limit` runs out: a relaxation stops as at `stop` once the
    /// time left is what the final check needs ([`Context::time_left`]).
    pub deadline: Option<Instant>,
    /// When the loop's first FIRE step started (not the setup before it): its mean step
    /// so far sizes the final check's reserve and a timed trial's share.
    pub started: Instant,
    /// When a relaxation gives way as if out of steps ([`Outcome::Budget`]): the
    /// loop sets it, under a time limit, for the relaxations before the first clean
    /// state (`time_limit::GIVE_WAY`, `GIVE_WAY_TARGET`).
    pub give_way: Option<Instant>,
    pub progress: &'a mut dyn FnMut(&Progress),
}

/// The time the loop keeps, under a time limit, for what follows it (the interrupted
/// state shrunk until apart, the exact check of every pair, the grains written out):
/// this many FIRE steps at their mean cost. The check took 4–5 steps' time from 10⁴ to
/// 10⁶ grains (0.004, 0.089 and about 1.3 s, against steps of 0.9, 21 and 290 ms), the
/// shrink one more.
pub(crate) const FINISH_STEPS: f64 = 6.0;

/// A relaxation whose deepest pair would touch at more than this share of its scale
/// (`μ₁ / s`: it overlaps by less than 5 %) does not give way under a time limit
/// (`time_limit::GIVE_WAY`, `GIVE_WAY_TARGET`): it comes out clean within a few more steps,
/// or is kept shrunk to at least `0.95³ = 0.86` of its fraction. 10⁵ frozen ellipsoids
/// asked 0.60 and given 5 s were at 0.965 when their target's relaxation gave way, and
/// kept 0.585 from the search; going on, 0.595 (given 3 s they are at 0.85, and give
/// way). BENCHMARKS.md, "Time limits shorter than the first relaxation, again".
pub(crate) const NEARLY_APART: f64 = 0.95;

impl Context<'_> {
    /// Under a time limit, the time left to the loop: to the deadline, less
    /// [`FINISH_STEPS`] steps at the mean cost of those so far; `None` without one.
    pub fn time_left(&self) -> Option<Duration> {
        let deadline = self.deadline?;
        let now = Instant::now();
        let reserve = match self.counters.fire_steps {
            0 => Duration::ZERO,
            n => (now - self.started).mul_f64(FINISH_STEPS / n as f64),
        };
        Some(deadline.saturating_duration_since(now + reserve))
    }

    /// Whether the time limit has run out ([`Context::time_left`]).
    pub fn out_of_time(&self) -> bool {
        self.time_left().is_some_and(|left| left.is_zero())
    }

    /// Whether the loop must stop: the caller asked it to, or the time limit ran out.
    pub fn halted(&self) -> bool {
        self.stop.load(Ordering::Relaxed) || self.out_of_time()
    }
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
    /// Set before a relaxation to go on with the velocities (and FIRE's mixing) the
    /// last one ended with, as one relaxation whose scale moved; cleared by it. For
    /// the descent's segments (module `descent`).
    pub keep_velocity: bool,
    /// The square root of each grain's mass (see [`masses`]).
    root_mass: Vec<f64>,
    /// Each grain's force over its root mass.
    scaled: Vec<[f64; 3]>,
    /// Each grain's smallest semi-axis, for the step's limit: read from a dense array, not
    /// from each grain's 128-byte shape (the move is memory-bound at 10⁶ grains).
    radius: Vec<f64>,
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
            keep_velocity: false,
            patience: Patience::NONE,
            root_mass: Vec::new(),
            scaled: Vec::new(),
            radius: Vec::new(),
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
        let p = self.params;
        if !std::mem::take(&mut self.keep_velocity) || self.velocity.len() != n {
            self.velocity.clear();
            self.velocity.resize(n, [0.0; 3]);
            self.spin.clear();
            self.spin.resize(n, [0.0; 3]);
            self.alpha = p.alpha_start;
            self.positive = 0;
        }
        if !std::mem::take(&mut self.keep_step) {
            self.dt = p.dt_start;
        }
        // A contact overlapping by the margin has energy (2ρ (S − s))², ρ the smallest
        // semi-axis: the jamming test's unit.
        let margin_energy = 4.0 * (big_s - s).powi(2) * state.mean_rho2;
        let mut jam = JamTest::new(
            p.window,
            p.plateau_slope,
            margin_energy,
            run.resolution,
            self.patience,
        );
        masses(state, &mut self.root_mass, &mut self.radius);
        self.deep = false;
        for _ in 0..budget {
            if run.halted() {
                return Ok(Outcome::Interrupted);
            }
            // A state nearly apart goes on: it comes out clean soon, or is kept shrunk.
            let far = run.forces.min_mu1 < NEARLY_APART * s;
            if far && run.give_way.is_some_and(|d| Instant::now() >= d) {
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
}

mod step;

use step::masses;
