//! Hard-particle Monte Carlo at a fixed scale: each grain in turn tries a small random
//! displacement or turn, then a swap of places with a grain of similar volume, every
//! move kept only when it leaves the grain apart from all others (the exact
//! `overlaps_prepared`) and inside the walls. The step sizes adapt toward
//! [`ACCEPTANCE`].

use super::{halts, Partners};
use crate::contact::Dimension;
use crate::contact::{dot, overlaps_prepared, PreparedEllipsoid};
use crate::octree::{wrap_coordinate, Neighbour, Octree, Params, Sphere};
use crate::packing::grains::rotate_by;
use crate::packing::state::State;
use crate::packing::PackError;
use crate::scene::{Boundary, Rotation};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// What the moves may do.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Moves {
    pub rotation: Rotation,
    pub max_turn: f64,
    /// Pairs stay at μ ≥ 1 + `contact_gap` ([`ProtocolParams::contact_gap`](crate::packing::ProtocolParams::contact_gap)).
    pub contact_gap: f64,
}

/// The share of kept moves the step sizes are tuned toward after each sweep: about a
/// third, the usual choice for hard-particle Monte Carlo (large enough steps to
/// decorrelate, few enough refusals to waste little).
const ACCEPTANCE: f64 = 0.3;

/// The first displacement step, as a share of the mean inscribed radius at the
/// scale; the first turn step (radians). The steps adapt within a few sweeps.
const FIRST_STEP: f64 = 0.05;
const FIRST_TURN: f64 = 0.05;

/// The most a step size changes after one sweep (factor either way).
const MOST_ADAPT: f64 = 1.3;

type Shape = (PreparedEllipsoid, [f64; 3]);

/// The moves' adaptive step sizes and a neighbour buffer.
pub(crate) struct MonteCarlo {
    step: f64,
    turn: f64,
    found: Vec<Neighbour>,
    /// Neighbours looked at since the sweep last asked whether to stop (`halts`).
    work: usize,
}

impl MonteCarlo {
    /// Step sizes for the state at scale `s`.
    pub fn new(state: &State, s: f64) -> Self {
        let mean: f64 = state
            .shapes
            .iter()
            .map(|e| e.inscribed_radius())
            .sum::<f64>()
            / state.len() as f64;
        Self {
            step: FIRST_STEP * s * mean,
            turn: FIRST_TURN,
            found: Vec::new(),
            work: 0,
        }
    }

    /// `sweeps` sweeps of the clean state at scale `s` (it stays clean), cut short
    /// where `halt` says so (asked as [`halts`] says); returns the moves
    /// (displacements and turns) and the swaps kept.
    pub fn sweeps(
        &mut self,
        state: &mut State,
        s: f64,
        sweeps: usize,
        p: &Moves,
        rng: &mut ChaCha8Rng,
        halt: &dyn Fn() -> bool,
    ) -> Result<(u64, u64), PackError> {
        let n = state.len();
        let partners = Partners::of(&state.volumes);
        let plane = state.domain.dimension == Dimension::Two;
        let (mut swaps, mut moves) = (0u64, 0u64);
        for _ in 0..sweeps {
            let t = s * (1.0 + p.contact_gap);
            // Displacements and turns.
            state.wrap();
            let reach = t * state.max_bounding_radius + 2.0 * self.step;
            let tree = octree_of(state, reach)?;
            let (mut tried, mut kept, mut turns_tried, mut turns_kept) = (0u64, 0u64, 0u64, 0u64);
            for g in 0..n {
                if halts(g, &mut self.work, halt) {
                    return Ok((moves, swaps));
                }
                let turning = p.rotation != Rotation::None && rng.random_bool(0.5);
                let c = state.centres[g];
                if turning {
                    let axis: [f64; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
                    let mut theta =
                        state.allowed_torque(g, axis.map(|x| x * self.turn), p.rotation);
                    if plane {
                        // Turns about the plane's normal only, as the forces' torques.
                        theta[0] = 0.0;
                        theta[1] = 0.0;
                    }
                    let q = rotate_by(state.quaternions[g], theta);
                    if !state.within_turn(g, q, p.max_turn) {
                        continue;
                    }
                    let shape = state.shape_of(g, q)?;
                    turns_tried += 1;
                    if self.free(state, &tree, None, [g, g], c, &shape, t, reach)? {
                        state.set_shape(g, q, shape);
                        turns_kept += 1;
                        moves += 1;
                    }
                } else {
                    let mut d: [f64; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
                    if plane {
                        d[2] = 0.0;
                    }
                    let at: [f64; 3] = std::array::from_fn(|k| c[k] + self.step * d[k]);
                    let shape = (state.shapes[g], state.half_widths[g]);
                    tried += 1;
                    if self.free(state, &tree, None, [g, g], at, &shape, t, reach)? {
                        state.centres[g] = at;
                        kept += 1;
                        moves += 1;
                    }
                }
            }
            self.step *= adapt(kept, tried);
            self.turn = (self.turn * adapt(turns_kept, turns_tried)).min(1.0);
            // Swaps: the places stay, their occupants change.
            state.wrap();
            let reach = t * state.max_bounding_radius;
            let tree = octree_of(state, reach)?;
            let places = state.centres.clone();
            let mut occupant: Vec<usize> = (0..n).collect();
            let mut place: Vec<usize> = (0..n).collect();
            for i in 0..n {
                if halts(i, &mut self.work, halt) {
                    return Ok((moves, swaps));
                }
                let j = partners.draw(state.volumes[i], rng);
                if j == i {
                    continue;
                }
                let (a, b) = (place[i], place[j]);
                let (qi, qj) = (state.quaternions[i], state.quaternions[j]);
                let carry = p.rotation != Rotation::None
                    && state.within_turn(i, qj, p.max_turn)
                    && state.within_turn(j, qi, p.max_turn);
                // Each grain in the other's orientation when they carry it.
                let shape = |g: usize, q: [f64; 4]| {
                    if carry {
                        state.shape_of(g, q)
                    } else {
                        Ok((state.shapes[g], state.half_widths[g]))
                    }
                };
                let o = Some(&occupant[..]);
                let ei = shape(i, qj)?;
                // Most swaps fail at once: the partner's shape only when needed.
                if !self.free(state, &tree, o, [a, b], places[b], &ei, t, reach)? {
                    continue;
                }
                let ej = shape(j, qi)?;
                if self.free(state, &tree, o, [a, b], places[a], &ej, t, reach)?
                    && apart(state, places[b], &ei, places[a], &ej, t)
                {
                    occupant.swap(a, b);
                    place.swap(i, j);
                    state.centres.swap(i, j);
                    if carry {
                        state.set_shape(i, qj, ei);
                        state.set_shape(j, qi, ej);
                    }
                    swaps += 1;
                }
            }
        }
        Ok((moves, swaps))
    }

    /// Whether shape `e` at `at` is apart, at scale `t`, from the grains stored in
    /// `tree` (radius `reach`; stored sphere `p` holds grain `occupant[p]`, or `p`)
    /// but those at the places of `skip`, and inside the walls.
    #[allow(clippy::too_many_arguments)]
    fn free(
        &mut self,
        state: &State,
        tree: &Octree,
        occupant: Option<&[usize]>,
        skip: [usize; 2],
        at: [f64; 3],
        e: &Shape,
        t: f64,
        reach: f64,
    ) -> Result<bool, PackError> {
        let size = state.domain.size;
        let periodic = state.domain.boundary == Boundary::Periodic;
        let query: [f64; 3] = if periodic {
            std::array::from_fn(|k| wrap_coordinate(at[k], size[k]))
        } else {
            at
        };
        if !periodic {
            for k in 0..3 {
                let w = e.1[k] * t * (1.0 + state.wall_margin);
                if at[k] < w || at[k] > size[k] - w {
                    return Ok(false);
                }
            }
        }
        let (eg, bg) = (&e.0, e.0.bounding_radius());
        tree.neighbours(query, t * bg + reach, &mut self.found)?;
        self.work += self.found.len();
        for nb in &self.found {
            let p = nb.id as usize;
            if skip.contains(&p) {
                // Periodic images of itself are too far in any box the loop takes.
                continue;
            }
            let k = occupant.map_or(p, |o| o[p]);
            let r: [f64; 3] =
                std::array::from_fn(|d| (state.centres[k][d] + nb.shift[d] - query[d]) / t);
            let ek = &state.shapes[k];
            if dot(&r, &r).sqrt() >= bg + ek.bounding_radius() {
                continue;
            }
            if overlaps_prepared(&r, eg, ek).unwrap_or(true) {
                return Ok(false);
            }
        }
        Ok(true)
    }
}

/// The octree of the grains' centres, each with radius `reach`.
fn octree_of(state: &State, reach: f64) -> Result<Octree, PackError> {
    let spheres: Vec<Sphere> = (state.centres.iter().enumerate())
        .map(|(p, &c)| Sphere {
            id: p as u32,
            centre: c,
            radius: reach,
        })
        .collect();
    Ok(Octree::build(&spheres, state.box_shape, Params::default())?)
}

/// Whether shape `e1` at `c1` and `e2` at `c2` are apart at scale `t` (the nearest
/// periodic image).
fn apart(state: &State, c1: [f64; 3], e1: &Shape, c2: [f64; 3], e2: &Shape, t: f64) -> bool {
    let size = state.domain.size;
    let periodic = state.domain.boundary == Boundary::Periodic;
    let r: [f64; 3] = std::array::from_fn(|d| {
        let mut x = c2[d] - c1[d];
        if periodic {
            x -= size[d] * (x / size[d]).round();
        }
        x / t
    });
    !overlaps_prepared(&r, &e1.0, &e2.0).unwrap_or(true)
}

/// The factor a step size is multiplied by after a sweep with `kept` of `tried`
/// moves kept.
fn adapt(kept: u64, tried: u64) -> f64 {
    if tried == 0 {
        return 1.0;
    }
    let rate = kept as f64 / tried as f64;
    (rate / ACCEPTANCE).clamp(1.0 / MOST_ADAPT, MOST_ADAPT)
}
