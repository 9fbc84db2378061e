//! One relaxation sweep: broad phase, narrow phase, response.

use super::state::State;
use super::{Counters, PackError};
use crate::contact::{contact_geometry_fast, overlaps_prepared, PreparedEllipsoid};
use crate::io::scene::Boundary;
use crate::octree::{Octree, Pair, Params, Sphere};
use rayon::prelude::*;
use std::time::Instant;

/// Pairs are kept at least this far apart, relatively: the narrow phase works on
/// grains inflated by `1 + CONTACT_GAP`, so every pair of an overlap-free state has
/// `μ ≥ 1 + CONTACT_GAP` at the true sizes. 1e-9 is far above the error of the fast
/// contact function on the shapes of a scene (≤ 1e-12 relative for aspect ratios
/// below 100) and far below anything a user can see.
pub const CONTACT_GAP: f64 = 1e-9;

/// An overlapping pair is pushed to `1 + OVERSHOOT` times the distance `d/μ` at which it
/// would just touch. The small gap this leaves keeps the pushes of its neighbours from
/// recreating the overlap at once (pushes that stop exactly at contact make pairs
/// ping-pong for many sweeps).
pub const OVERSHOOT: f64 = 0.005;

/// What a sweep found, before its pushes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Found {
    /// Overlapping pairs (at the inflated size).
    pub overlaps: usize,
    /// Smallest μ over them (1 when there are none), at the inflated size.
    pub min_mu: f64,
}

/// The candidate pairs are found for bounding spheres grown by a skin of
/// `SKIN · s · (mean bounding radius)`, and kept while no pair can have come into reach:
/// `skin ≥ 2 · (largest displacement since) + 2 · (growth of s since) · (largest
/// bounding radius)`. 0.1 trades a few more candidate pairs for far fewer octree builds.
pub const SKIN: f64 = 0.1;

/// Buffers and the candidate list, reused from sweep to sweep.
#[derive(Default)]
pub(crate) struct Sweep {
    spheres: Vec<Sphere>,
    pairs: Vec<Pair>,
    scaled: Vec<PreparedEllipsoid>,
    hits: Vec<Option<(f64, [f64; 3])>>,
    pushes: Vec<[f64; 3]>,
    /// Inflated scale and skin the candidate list was built for.
    list_scale: f64,
    skin: f64,
    /// Distance each grain moved since the list was built.
    travelled: Vec<f64>,
    /// Whether each grain moved in the last sweep, and the scale `hits` hold for.
    moved: Vec<bool>,
    hits_scale: f64,
    before: Vec<[f64; 3]>,
}

impl Sweep {
    /// Finds the overlapping pairs at scale `s` and, if `push`, moves them apart.
    pub fn run(
        &mut self,
        state: &mut State,
        s: f64,
        push: bool,
        counters: &mut Counters,
    ) -> Result<Found, PackError> {
        let inflated = s * (1.0 + CONTACT_GAP);
        let t0 = Instant::now();
        let max_radius = state.max_bounding_radius;
        let travelled = self.travelled.iter().fold(0.0f64, |m, &d| m.max(d));
        let reach_lost = 2.0 * travelled + 2.0 * (inflated - self.list_scale).max(0.0) * max_radius;
        let rebuild = self.pairs.is_empty() && self.spheres.is_empty()
            || self.travelled.len() != state.len()
            || reach_lost > self.skin;
        if rebuild {
            // Centres are wrapped only here: between builds the pairs' shifts refer to
            // the centres as they are.
            state.confine(s);
            let mean = state
                .shapes
                .iter()
                .map(|e| e.bounding_radius())
                .sum::<f64>()
                / state.len() as f64;
            self.skin = SKIN * inflated * mean;
            state.spheres(inflated, &mut self.spheres);
            for sphere in &mut self.spheres {
                sphere.radius += 0.5 * self.skin;
            }
            let tree = Octree::build(&self.spheres, state.box_shape, Params::default())
                .map_err(|e| PackError::Domain(e.to_string()))?;
            tree.pairs(&mut self.pairs);
            self.list_scale = inflated;
            self.travelled.clear();
            self.travelled.resize(state.len(), 0.0);
            self.moved.clear();
            self.moved.resize(state.len(), true);
            self.hits.clear();
            self.hits.resize(self.pairs.len(), None);
        }
        let t1 = Instant::now();

        // Only pairs with a grain that moved can have changed, unless the scale did.
        let all = rebuild || inflated != self.hits_scale;
        self.hits_scale = inflated;
        if all {
            self.scaled.clear();
            self.scaled
                .extend(state.shapes.iter().map(|e| e.scaled(inflated)));
        }
        let (centres, shapes, scaled, moved) =
            (&state.centres, &state.shapes, &self.scaled, &self.moved);
        let tested: usize = self
            .pairs
            .par_iter()
            .zip(self.hits.par_iter_mut())
            .map(|(p, hit)| {
                let (i, j) = (p.i as usize, p.j as usize);
                if i == j || !(all || moved[i] || moved[j]) {
                    // A grain shorter than the box never meets its own image; an
                    // unmoved pair keeps its verdict.
                    return 0;
                }
                let r = relative(centres, p);
                *hit = match overlaps_prepared(&r, &scaled[i], &scaled[j]) {
                    Ok(false) => None,
                    // μ at the inflated size, from the unit-size forms.
                    _ => Some(
                        match contact_geometry_fast(&r, shapes[i].q(), shapes[j].q()) {
                            Ok(g) => (g.mu2.sqrt() / inflated, g.normal),
                            Err(_) => (0.0, [0.0; 3]),
                        },
                    ),
                };
                1
            })
            .sum();
        let t2 = Instant::now();

        let mut found = Found {
            overlaps: 0,
            min_mu: 1.0,
        };
        for (mu, _) in self.hits.iter().flatten() {
            found.overlaps += 1;
            found.min_mu = found.min_mu.min(*mu);
        }
        if push {
            self.before.clone_from(&state.centres);
            if found.overlaps > 0 {
                self.push(state, inflated);
            }
            if state.domain.boundary == Boundary::Reflecting {
                state.confine(s);
            }
            for ((m, t), (a, b)) in self
                .moved
                .iter_mut()
                .zip(&mut self.travelled)
                .zip(state.centres.iter().zip(&self.before))
            {
                let d =
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                *m = d > 0.0;
                *t += d;
            }
        }
        counters.sweeps += 1;
        counters.pairs_tested += tested as u64;
        if push {
            counters.overlaps_resolved += found.overlaps as u64;
        }
        counters.broad_phase += t1 - t0;
        counters.narrow_phase += t2 - t1;
        counters.response += t2.elapsed();
        Ok(found)
    }

    /// Moves each overlapping pair apart along its centre line, to `1 + OVERSHOOT` times
    /// the distance `d/μ` at which it would touch, split in inverse proportion to the
    /// grains' volumes; the pushes of all pairs are summed (Jacobi), in pair order.
    fn push(&mut self, state: &mut State, s: f64) {
        self.pushes.clear();
        self.pushes.resize(state.len(), [0.0; 3]);
        for (p, hit) in self.pairs.iter().zip(&self.hits) {
            let Some((mu, normal)) = *hit else { continue };
            let (i, j) = (p.i as usize, p.j as usize);
            let r = relative(&state.centres, p);
            let d = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
            let reach = s * (state.shapes[i].bounding_radius() + state.shapes[j].bounding_radius());
            let (dir, gap) = if d > 1e-12 * reach && mu > 0.0 {
                // Along the contact normal, by the overlap d (1/μ − 1) projected on it
                // (the woo DEM estimate of the penetration depth), with the overshoot.
                let along = (r[0] * normal[0] + r[1] * normal[1] + r[2] * normal[2]) / d;
                (
                    normal,
                    (d * ((1.0 + OVERSHOOT) / mu - 1.0) * along.max(0.1)).min(reach),
                )
            } else {
                // Coincident centres: any direction will do; take one fixed by the ids.
                (fallback_direction(p.i, p.j), 0.5 * reach)
            };
            let (vi, vj) = (state.volumes[i], state.volumes[j]);
            let (wi, wj) = (vj / (vi + vj), vi / (vi + vj));
            for (k, n) in dir.iter().enumerate() {
                self.pushes[i][k] -= n * gap * wi;
                self.pushes[j][k] += n * gap * wj;
            }
        }
        for (c, d) in state.centres.iter_mut().zip(&self.pushes) {
            for (x, dx) in c.iter_mut().zip(d) {
                *x += dx;
            }
        }
    }
}

/// `c_j + shift − c_i`.
fn relative(centres: &[[f64; 3]], p: &Pair) -> [f64; 3] {
    let (ci, cj) = (centres[p.i as usize], centres[p.j as usize]);
    [0, 1, 2].map(|k| cj[k] + p.shift[k] - ci[k])
}

/// A unit vector that depends only on the pair's ids (a hash), for coincident centres.
fn fallback_direction(i: u32, j: u32) -> [f64; 3] {
    let mut h = (u64::from(i) << 32 | u64::from(j)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    let mut coord = || {
        h ^= h >> 29;
        h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let v = [coord(), coord(), coord()];
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
        .sqrt()
        .max(f64::MIN_POSITIVE);
    v.map(|x| x / n)
}
