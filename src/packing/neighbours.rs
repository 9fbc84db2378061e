//! The broad phase of the loop: a Verlet list of candidate pairs from the octree,
//! rebuilt only when a pair may have come into reach since the last build.

use super::state::{State, GRAINS_PER_TASK};
use super::NeighbourParams;
use super::PackError;
use crate::octree::{BoxShape, Octree, Pair, Sphere};
use rayon::prelude::*;

/// The candidate pairs and what is needed to know when they go stale.
pub(crate) struct Neighbours {
    params: NeighbourParams,
    pub pairs: Vec<Pair>,
    spheres: Vec<Sphere>,
    /// Scale the list was built for.
    built_scale: f64,
    skin: f64,
    /// Where each centre was at the build.
    anchors: Vec<[f64; 3]>,
    /// Builds so far.
    pub builds: u64,
    /// The last build's tree, whose buffers the next build reuses.
    tree: Option<Octree>,
}

impl Neighbours {
    /// An empty list, stale until the first [`update`](Self::update).
    pub fn new(params: NeighbourParams) -> Self {
        Self {
            params,
            pairs: Vec::new(),
            spheres: Vec::new(),
            built_scale: 0.0,
            skin: 0.0,
            anchors: Vec::new(),
            builds: 0,
            tree: None,
        }
    }

    /// Makes sure the list holds every pair whose bounding spheres at scale `scale`
    /// meet; returns whether it was rebuilt (the centres are wrapped then, and only
    /// then, since the pairs' periodic shifts refer to the centres as they are).
    pub fn update(&mut self, state: &mut State, scale: f64) -> Result<bool, PackError> {
        if !self.stale(state, scale) {
            return Ok(false);
        }
        state.wrap();
        self.skin = self.params.skin * scale * state.mean_bounding_radius;
        state.spheres(scale, 0.5 * self.skin, &mut self.spheres);
        let tree = match self.tree.take() {
            Some(mut tree) if *tree.shape() == state.box_shape => {
                tree.rebuild(&self.spheres)?;
                tree
            }
            _ => Octree::build(&self.spheres, state.box_shape, self.params.octree)?,
        };
        tree.pairs(&mut self.pairs);
        // A grain shorter than the box never meets its own image: most lists have no
        // self-pair to drop, which a parallel look tells sooner than a serial retain.
        if self.pairs.par_iter().any(|p| p.i == p.j) {
            self.pairs.retain(|p| p.i != p.j);
        }
        self.tree = Some(tree);
        self.built_scale = scale;
        self.anchors.clone_from(&state.centres);
        self.builds += 1;
        Ok(true)
    }

    fn stale(&self, state: &State, scale: f64) -> bool {
        if self.anchors.len() != state.len() {
            return true;
        }
        // A largest element does not depend on the order it is looked for in.
        let moved = (state.centres.par_iter())
            .zip(&self.anchors)
            .with_min_len(GRAINS_PER_TASK)
            .map(|(a, b)| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>())
            .reduce(|| 0.0, f64::max)
            .sqrt();
        let grown = (scale - self.built_scale).max(0.0) * state.max_bounding_radius;
        2.0 * moved + 2.0 * grown > self.skin
    }
}

/// `c_j + shift − c_i`.
#[inline]
pub(crate) fn relative(centres: &[[f64; 3]], p: &Pair, shape: &BoxShape) -> [f64; 3] {
    let (ci, cj, shift) = (centres[p.i as usize], centres[p.j as usize], p.shift(shape));
    [0, 1, 2].map(|k| cj[k] + shift[k] - ci[k])
}
