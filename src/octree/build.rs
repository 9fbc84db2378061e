//! Building the tree: validation, loose subdivision by centre, bounds bottom-up.

use super::boundary::Aabb;
use super::kernel::Lanes;
use super::scratch::{Item, Scratch};
use super::split::{leaf, Builder};
use super::validate::{validate_input, CHECKS_PER_TASK, PARALLEL_FROM};
use super::{BoxShape, Octree, OctreeError, Params, Sphere};
use rayon::prelude::*;

impl Octree {
    /// Builds the tree over `spheres` in `shape`.
    ///
    /// Checks every input first (finite centres, positive finite radii, unique ids, a
    /// valid box and parameters, spheres not larger than
    /// [`MAX_IMAGES_PER_AXIS`](super::MAX_IMAGES_PER_AXIS) allows) and returns the first
    /// problem as a typed error naming the sphere. Periodic centres are wrapped with
    /// [`BoxShape::wrap`]. Cost O(n · depth); debug builds then run
    /// [`Octree::check_invariants`].
    pub fn build(spheres: &[Sphere], shape: BoxShape, params: Params) -> Result<Self, OctreeError> {
        let mut tree = Octree {
            shape,
            params,
            nodes: Vec::new(),
            spheres: Lanes::default(),
            depth: 0,
            scratch: Scratch::default(),
        };
        tree.rebuild(spheres)?;
        Ok(tree)
    }

    /// Builds the tree again over new spheres (any number, any ids) in the same box with
    /// the same parameters, reusing every buffer: the call the packing loop makes each
    /// step. Same checks and result as [`Octree::build`]; on error the tree is emptied.
    ///
    /// Rebuilding was measured faster than refitting the old tree; the numbers are in a
    /// note in the source (`src/octree/build.rs`).
    pub fn rebuild(&mut self, spheres: &[Sphere]) -> Result<(), OctreeError> {
        self.rebuild_splitting(spheres, PARALLEL_FROM)
    }

    /// [`Octree::rebuild`], with nodes of at least `parallel_from` spheres split in
    /// parallel: each child's subtree into a node array of its own, appended in order,
    /// so that the tree is the one a serial build makes.
    fn rebuild_splitting(
        &mut self,
        spheres: &[Sphere],
        parallel_from: usize,
    ) -> Result<(), OctreeError> {
        self.nodes.clear();
        self.spheres.resize(0);
        self.depth = 0;
        self.params.validate()?;
        validate_input(spheres, &self.shape)?;
        let n = spheres.len();
        let shape = self.shape;
        let mut scratch = std::mem::take(&mut self.scratch);
        scratch.a.clear();
        let item = |s: &Sphere| Item {
            centre: shape.wrap(s.centre),
            radius: s.radius,
            id: s.id,
        };
        if n >= PARALLEL_FROM {
            let tasks = spheres.par_iter().with_min_len(CHECKS_PER_TASK);
            scratch.a.par_extend(tasks.map(item));
        } else {
            scratch.a.extend(spheres.iter().map(item));
        }
        // Free space only: grown when needed, never cleared.
        if scratch.b.len() < n {
            scratch.b.resize(n, Item::default());
            scratch.codes.resize(n, 0);
        }
        self.spheres.resize(n);
        if n > 0 {
            let cell = root_cell(&scratch.a, &shape);
            self.nodes.push(leaf(0, n as u32));
            let mut builder = Builder {
                params: &self.params,
                nodes: &mut self.nodes,
                lanes: self.spheres.window(),
                depth: 0,
                parallel_from,
            };
            builder.split(
                0,
                cell,
                0,
                &mut scratch.a,
                &mut scratch.b,
                &mut scratch.codes,
            );
            self.depth = builder.depth;
        }
        self.scratch = scratch;
        self.compute_bounds();
        debug_assert_eq!(self.check_invariants(), Ok(()));
        Ok(())
    }

    /// Exact bounds of every node, children before parents (they come later in the
    /// array, so a reverse sweep sees them first).
    fn compute_bounds(&mut self) {
        for k in (0..self.nodes.len()).rev() {
            let node = self.nodes[k];
            let bounds = if node.is_leaf() {
                node.range()
                    .fold(Aabb::EMPTY, |b, s| b.union(&self.spheres.aabb(s)))
            } else {
                node.children()
                    .fold(Aabb::EMPTY, |b, c| b.union(&self.nodes[c].bounds))
            };
            self.nodes[k].bounds = bounds;
        }
    }
}

// Rebuild against refit. A refit keeps the topology, takes the new centres and radii
// through the stored permutation and recomputes the bounds bottom-up. Measured with
// the step pattern of the packing loop (every centre moved by up to 1% of its radius,
// every radius grown by 0.1%, 10 steps; 1e5 lognormal spheres at φ = 0.6, periodic, one
// thread; three runs on a shared 2-core AMD EPYC, mean ms per step):
//
//                  update         pair query      total
//   rebuild        4.7 / 4.9 / 7.1  41.2 / 36.0 / 44.9  45.9 / 40.9 / 52.0
//   refit          5.8 / 5.8 / 7.3  46.6 / 38.6 / 52.1  52.3 / 44.4 / 59.4
//
// Rebuilding wins: the refit saves nothing on the update (gathering every sphere from
// the caller's slice through the permutation is random access, while the partition is
// a few sequential passes over reused buffers), and its query is 7–15% slower because
// the leaves' bounds loosen as spheres drift out of their cells (a grain wrapping
// across a periodic face stretches its leaf across the whole box). So the tree is
// rebuilt every step, which also needs no rule for when a refit has decayed too far.

/// The cell of the root: the box itself, or for walls the box grown to take in any
/// centre outside it.
fn root_cell(items: &[Item], shape: &BoxShape) -> Aabb {
    let mut cell = Aabb {
        lo: [0.0; 3],
        hi: shape.lengths,
    };
    if !shape.is_periodic() {
        for s in items {
            cell = cell.union(&Aabb {
                lo: s.centre,
                hi: s.centre,
            });
        }
    }
    cell
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn children_built_in_parallel_make_the_serial_tree() {
        // Radii from 0.02 to 2 (the largest stay in their node's bucket), centres on a
        // low-discrepancy sequence; nodes of 2¹² spheres or more split in parallel, so
        // that subtrees built in parallel split in parallel again.
        let n = 98_304;
        let spheres: Vec<Sphere> = (0..n)
            .map(|id| {
                let t = f64::from(id);
                let centre = [0.618, 0.414, 0.732].map(|a: f64| 40.0 * (t * a).fract());
                let radius = 0.02 * 100f64.powf((t * 0.271).fract().powi(8));
                Sphere { id, centre, radius }
            })
            .collect();
        let shape = BoxShape::periodic([40.0; 3]).unwrap();
        let mut parallel = Octree::build(&spheres, shape, Params::default()).unwrap();
        parallel.rebuild_splitting(&spheres, 1 << 12).unwrap();
        let mut serial = parallel.clone();
        serial.rebuild_splitting(&spheres, usize::MAX).unwrap();
        assert_eq!(parallel.check_invariants(), Ok(()));
        assert_eq!(parallel.depth, serial.depth);
        assert!(parallel.nodes.len() > 1000);
        assert_eq!(
            format!("{:?}", parallel.nodes),
            format!("{:?}", serial.nodes)
        );
        assert_eq!(parallel.spheres.id, serial.spheres.id);
        assert_eq!(parallel.spheres.x, serial.spheres.x);
        assert_eq!(parallel.spheres.r, serial.spheres.r);
    }
}
