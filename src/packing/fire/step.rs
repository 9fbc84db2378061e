//! One FIRE 2.0 step: the power check, semi-implicit Euler and the velocity mixing,
//! over the grains in parallel, sums by fixed chunks so that the threads do not change
//! a bit.

use super::Fire;
use crate::contact::dot;
use crate::packing::forces::Forces;
use crate::packing::grains::rotate_by;
use crate::packing::state::{State, GRAINS_PER_TASK};
use crate::packing::PackError;
use crate::scene::Rotation;
use rayon::prelude::*;

impl Fire {
    /// One FIRE 2.0 step: power check, semi-implicit Euler, velocity mixing.
    pub(super) fn step(
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
        scaled.resize(n, [0.0; 3]);
        let spin = &self.spin;
        let power = by_chunks(
            (scaled.par_chunks_mut(GRAINS_PER_TASK))
                .zip(forces.force.par_chunks(GRAINS_PER_TASK))
                .zip(root_mass.par_chunks(GRAINS_PER_TASK))
                .zip(self.velocity.par_chunks(GRAINS_PER_TASK)),
            |first, (((scaled, force), m), v)| {
                let mut power = 0.0;
                for (k, (s, f)) in scaled.iter_mut().zip(force).enumerate() {
                    *s = f.map(|x| x / m[k]);
                    power += dot(s, &v[k]);
                    if rotate {
                        power += dot(&torque(first + k), &spin[first + k]);
                    }
                }
                [power, 0.0]
            },
        )[0];
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
            (state.centres.par_iter_mut())
                .zip(&mut self.velocity)
                .zip(&root_mass)
                .with_min_len(GRAINS_PER_TASK)
                .for_each(|((c, v), m)| {
                    for k in 0..3 {
                        c[k] -= back * v[k] / m;
                    }
                    *v = [0.0; 3];
                });
            self.spin.iter_mut().for_each(|v| *v = [0.0; 3]);
        }
        let dt = self.dt;
        // v += dt F, then mix toward the force direction over all degrees of freedom.
        let [vv, ff] = by_chunks(
            (self.velocity.par_chunks_mut(GRAINS_PER_TASK))
                .zip(self.spin.par_chunks_mut(GRAINS_PER_TASK))
                .zip(scaled.par_chunks(GRAINS_PER_TASK)),
            |first, ((velocity, spin), scaled)| {
                let (mut vv, mut ff) = (0.0, 0.0);
                for (k, (v, f)) in velocity.iter_mut().zip(scaled).enumerate() {
                    axpy(v, dt, f);
                    vv += dot(v, v);
                    ff += dot(f, f);
                    if rotate {
                        let (t, w) = (torque(first + k), &mut spin[k]);
                        axpy(w, dt, &t);
                        vv += dot(w, w);
                        ff += dot(&t, &t);
                    }
                }
                [vv, ff]
            },
        );
        let mix = if ff > 0.0 {
            self.alpha * (vv / ff).sqrt()
        } else {
            0.0
        };
        let keep = 1.0 - self.alpha;
        let radius = &self.radius;
        let limit = |i: usize| {
            let m = root_mass[i];
            m * p.max_move * big_s * radius[i] / dt
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
/// of a mixture. Equal grains keep unit masses. `radius` gets each grain's ρ.
pub(super) fn masses(state: &State, root_mass: &mut Vec<f64>, radius: &mut Vec<f64>) {
    radius.clear();
    radius.extend(state.shapes.iter().map(|e| e.inscribed_radius()));
    let mut rho = radius.clone();
    let median = if rho.is_empty() {
        1.0
    } else {
        let k = rho.len() / 2;
        *rho.select_nth_unstable_by(k, f64::total_cmp).1
    };
    root_mass.clear();
    root_mass.extend(radius.iter().map(|r| (r / median).max(1.0)));
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

/// `f` over the grains in chunks of [`GRAINS_PER_TASK`], in parallel, and the sum of the
/// chunks' two sums in chunk order: the same whatever the threads, and for a scene of
/// one chunk the sums of one loop. `f` gets each chunk's first grain.
fn by_chunks<I: IndexedParallelIterator>(
    chunks: I,
    f: impl Fn(usize, I::Item) -> [f64; 2] + Sync + Send,
) -> [f64; 2] {
    let parts: Vec<[f64; 2]> = (chunks.enumerate())
        .map(|(c, x)| f(c * GRAINS_PER_TASK, x))
        .collect();
    parts
        .iter()
        .fold([0.0; 2], |s, p| [s[0] + p[0], s[1] + p[1]])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values whose sums round differently in every order.
    fn values(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| 1.0 / (1.0 + i as f64) * if i % 3 == 0 { -1e3 } else { 1.0 })
            .collect()
    }

    fn summed(x: &[f64]) -> [f64; 2] {
        by_chunks(x.par_chunks(GRAINS_PER_TASK), |first, c| {
            let mut s = [0.0; 2];
            for (k, v) in c.iter().enumerate() {
                s[0] += v;
                s[1] += v * (first + k) as f64;
            }
            s
        })
    }

    #[test]
    fn sums_by_chunks_do_not_depend_on_the_threads() {
        let x = values(5 * GRAINS_PER_TASK / 2);
        let on = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| summed(&x))
        };
        let one = on(1);
        assert_eq!(one.map(f64::to_bits), on(2).map(f64::to_bits));
        assert_eq!(one.map(f64::to_bits), on(3).map(f64::to_bits));
        // The chunks' sums in chunk order, each chunk's in grain order.
        let expected = x
            .chunks(GRAINS_PER_TASK)
            .enumerate()
            .fold([0.0; 2], |s, (c, part)| {
                let mut p = [0.0; 2];
                for (k, v) in part.iter().enumerate() {
                    p[0] += v;
                    p[1] += v * (c * GRAINS_PER_TASK + k) as f64;
                }
                [s[0] + p[0], s[1] + p[1]]
            });
        assert_eq!(one.map(f64::to_bits), expected.map(f64::to_bits));
    }

    #[test]
    fn one_chunk_sums_as_one_loop() {
        let x = values(GRAINS_PER_TASK);
        let mut s = 0.0;
        for v in &x {
            s += v;
        }
        assert_eq!(summed(&x)[0].to_bits(), s.to_bits());
    }
}
