//! The broad phase of the loop: a Verlet list of candidate pairs from the octree,
//! rebuilt only when a pair may have come into reach since the last build.

use super::state::State;
use super::PackError;
use crate::octree::{Octree, Pair, Params, Sphere};

/// Candidate pairs are found for bounding spheres grown by a skin of
/// `SKIN · S · (mean bounding radius)`, and kept while no pair can have come into
/// reach: `2 · (largest displacement since) + 2 · (growth of S since) · (largest
/// bounding radius) ≤ skin`. A pair in the list costs almost nothing while its μ
/// bound keeps it out of reach (see `forces::BOUND_SLACK`), so a thick skin that
/// halves the octree builds pays: on `configs/kanapy_elongated.toml` (one thread,
/// user time of 3 runs) 0.15 took 0.86–1.09 s, 0.3 0.80–1.02 s, 0.6 0.74–0.83 s.
pub const SKIN: f64 = 0.6;

/// The candidate pairs and what is needed to know when they go stale.
#[derive(Default)]
pub(crate) struct Neighbours {
    pub pairs: Vec<Pair>,
    spheres: Vec<Sphere>,
    /// Scale the list was built for.
    built_scale: f64,
    skin: f64,
    /// Where each centre was at the build.
    anchors: Vec<[f64; 3]>,
    /// Builds so far.
    pub builds: u64,
}

impl Neighbours {
    /// Makes sure the list holds every pair whose bounding spheres at scale `scale`
    /// meet; returns whether it was rebuilt (the centres are wrapped then, and only
    /// then, since the pairs' periodic shifts refer to the centres as they are).
    pub fn update(&mut self, state: &mut State, scale: f64) -> Result<bool, PackError> {
        if !self.stale(state, scale) {
            return Ok(false);
        }
        state.wrap();
        let mean = state
            .shapes
            .iter()
            .map(|e| e.bounding_radius())
            .sum::<f64>()
            / state.len() as f64;
        self.skin = SKIN * scale * mean;
        state.spheres(scale, 0.5 * self.skin, &mut self.spheres);
        let tree = Octree::build(&self.spheres, state.box_shape, Params::default())?;
        tree.pairs(&mut self.pairs);
        // A grain shorter than the box never meets its own image.
        self.pairs.retain(|p| p.i != p.j);
        self.built_scale = scale;
        self.anchors.clone_from(&state.centres);
        self.builds += 1;
        Ok(true)
    }

    fn stale(&self, state: &State, scale: f64) -> bool {
        if self.anchors.len() != state.len() {
            return true;
        }
        let moved = state
            .centres
            .iter()
            .zip(&self.anchors)
            .map(|(a, b)| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>())
            .fold(0.0f64, f64::max)
            .sqrt();
        let grown = (scale - self.built_scale).max(0.0) * state.max_bounding_radius;
        2.0 * moved + 2.0 * grown > self.skin
    }
}

/// `c_j + shift − c_i`.
pub(crate) fn relative(centres: &[[f64; 3]], p: &Pair) -> [f64; 3] {
    let (ci, cj) = (centres[p.i as usize], centres[p.j as usize]);
    [0, 1, 2].map(|k| cj[k] + p.shift[k] - ci[k])
}
