//! Swap moves at zero temperature: two grains of similar volume exchange positions
//! when that lowers the overlap energy.
//!
//! During a sweep the positions stay where they are and only their occupants change,
//! so one octree of the positions serves the whole sweep: each position is stored
//! with the largest bounding radius, and a grain's neighbours at a position are the
//! stored positions within reach of its own bounding sphere.

use super::{halts, Partners};
use crate::contact::{contact_function_fast, dot};
use crate::octree::{Neighbour, Octree, Params, Sphere};
use crate::packing::forces::pair_energy;
use crate::packing::state::State;
use crate::packing::PackError;
use crate::scene::Boundary;
use rand_chacha::ChaCha8Rng;

/// One sweep at scale `big_s` (the scale the energy is taken at): one swap attempt per
/// grain, in index order, each with a partner drawn uniformly among the grains whose
/// volume is within [`SWAP_VOLUME_RATIO`](super::SWAP_VOLUME_RATIO) of its own, kept
/// when it lowers the energy; cut short where `halt` says so (asked as [`halts`] says).
/// Returns the attempts (pairs compared) and the swaps kept.
pub(crate) fn sweep(
    state: &mut State,
    big_s: f64,
    rng: &mut ChaCha8Rng,
    halt: &dyn Fn() -> bool,
) -> Result<(u64, u64), PackError> {
    let n = state.len();
    let partners = Partners::of(&state.volumes);
    // Wrapped (periodic) or inside the box (walled): the octree's shifts refer to them.
    state.wrap();
    let places = state.centres.clone();
    let reach = big_s * state.max_bounding_radius;
    let spheres: Vec<Sphere> = (places.iter().enumerate())
        .map(|(p, &c)| Sphere {
            id: p as u32,
            centre: c,
            radius: reach,
        })
        .collect();
    let tree = Octree::build(&spheres, state.box_shape, Params::default())?;
    // Position p holds grain `occupant[p]`; grain g stands at position `place[g]`.
    let mut occupant: Vec<usize> = (0..n).collect();
    let mut place: Vec<usize> = (0..n).collect();
    let mut found = Vec::new();
    let (mut attempts, mut swaps) = (0, 0);
    let mut look = Look {
        state,
        places: &places,
        tree: &tree,
        big_s,
        found: &mut found,
        work: 0,
    };
    for i in 0..n {
        if halts(i, &mut look.work, halt) {
            break;
        }
        let j = partners.draw(look.state.volumes[i], rng);
        if j == i || look.same(i, j) {
            continue;
        }
        attempts += 1;
        let (a, b) = (place[i], place[j]);
        let skip = [a, b];
        let inf = f64::INFINITY;
        let before =
            look.energy(i, a, skip, &occupant, inf)? + look.energy(j, b, skip, &occupant, inf)?;
        // Most swaps are refused: the sums stop as soon as they reach `before` (every
        // term is positive, so the full sums would reach it too).
        let first = look.energy(i, b, skip, &occupant, before)?;
        let after = if first < before {
            first + look.energy(j, a, skip, &occupant, before - first)?
        } else {
            first
        };
        if after < before {
            occupant.swap(a, b);
            place.swap(i, j);
            look.state.centres.swap(i, j);
            swaps += 1;
        }
    }
    Ok((attempts, swaps))
}

/// What an energy lookup needs.
struct Look<'a> {
    state: &'a mut State,
    /// The positions, wrapped (the octree's shifts refer to them).
    places: &'a [[f64; 3]],
    tree: &'a Octree,
    big_s: f64,
    found: &'a mut Vec<Neighbour>,
    /// Neighbours looked at since the sweep last asked whether to stop.
    work: usize,
}

impl Look<'_> {
    /// Whether grains `i` and `j` are the same body (same semi-axes and orientation):
    /// swapping them changes nothing.
    fn same(&self, i: usize, j: usize) -> bool {
        let s = &*self.state;
        s.axes[i] == s.axes[j] && (s.round[i] || s.quaternions[i] == s.quaternions[j])
    }

    /// The overlap energy of grain `g` at position `p` with the grains at every other
    /// position but those of `skip` (the pair being swapped: their own contact is the
    /// same after the swap, the contact function being even in the centres' offset),
    /// and with the walls; ∞ as soon as the sum reaches `cap`.
    fn energy(
        &mut self,
        g: usize,
        p: usize,
        skip: [usize; 2],
        occupant: &[usize],
        cap: f64,
    ) -> Result<f64, PackError> {
        let s = &*self.state;
        let big_s = self.big_s;
        let at = self.places[p];
        let (eg, bg) = (&s.shapes[g], s.shapes[g].bounding_radius());
        self.tree.neighbours(at, big_s * bg, self.found)?;
        self.work += self.found.len();
        let mut energy = 0.0;
        for nb in self.found.iter() {
            let q = nb.id as usize;
            if skip.contains(&q) {
                continue;
            }
            let k = occupant[q];
            let ek = &s.shapes[k];
            let r: [f64; 3] = std::array::from_fn(|d| self.places[q][d] + nb.shift[d] - at[d]);
            let dist = dot(&r, &r).sqrt();
            if dist >= big_s * (bg + ek.bounding_radius()) {
                continue;
            }
            let mu1 = if s.round[g] && s.round[k] {
                dist / (s.axes[g][0] + s.axes[k][0])
            } else {
                match contact_function_fast(&r, eg.q(), ek.q()) {
                    Ok(c) if c.mu2.is_finite() => c.mu2.sqrt(),
                    // As the forces do: a full overlap.
                    _ => 0.0,
                }
            };
            let mu = mu1 / big_s;
            if mu < 1.0 {
                let reach = big_s * (eg.inscribed_radius() + ek.inscribed_radius());
                energy += pair_energy(reach, mu);
                if energy >= cap {
                    return Ok(f64::INFINITY);
                }
            }
        }
        if s.domain.boundary == Boundary::Reflecting {
            let size = s.domain.size;
            for d in 0..3 {
                let half = big_s * s.half_widths[g][d];
                let low = half - at[d];
                let high = at[d] + half - size[d];
                energy += low.max(0.0).powi(2) + high.max(0.0).powi(2);
            }
        }
        Ok(energy)
    }
}
