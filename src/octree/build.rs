//! Building the tree: validation, loose subdivision by centre, bounds bottom-up.

use super::boundary::Aabb;
use super::kernel::Lanes;
use super::scratch::{Item, Scratch};
use super::tree::Node;
use super::{BoxShape, Octree, OctreeError, Params, Sphere, MAX_IMAGES_PER_AXIS};

/// Most children a node can have: eight octants plus the bucket of large spheres.
const MAX_CHILDREN: usize = 9;

/// An axis is split only if it is at least this fraction of the node's longest side,
/// so cells of a non-cubic box stay within an aspect ratio of 2 (a 4:1:1 box splits
/// along x alone, then into octants): cubic-ish cells keep the loose rule meaningful.
const SPLIT_ASPECT: f64 = 0.5;

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
        self.nodes.clear();
        self.spheres.resize(0);
        self.depth = 0;
        self.params.validate()?;
        validate_input(spheres, &self.shape)?;
        let n = spheres.len();
        let shape = self.shape;
        let mut scratch = std::mem::take(&mut self.scratch);
        scratch.a.clear();
        scratch.a.extend(spheres.iter().map(|s| Item {
            centre: shape.wrap(s.centre),
            radius: s.radius,
            id: s.id,
        }));
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
                lanes: &mut self.spheres,
                depth: 0,
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

/// Checks the box and the spheres as `build` and the brute-force references need them.
pub(crate) fn validate_input(spheres: &[Sphere], shape: &BoxShape) -> Result<(), OctreeError> {
    shape.validate()?;
    if u32::try_from(spheres.len()).is_err() {
        return Err(OctreeError::TooManySpheres {
            count: spheres.len(),
        });
    }
    for s in spheres {
        s.validate()?;
        if shape.is_periodic() {
            for (axis, &length) in shape.lengths.iter().enumerate() {
                if (2.0 * s.radius / length).ceil() > f64::from(MAX_IMAGES_PER_AXIS) {
                    return Err(OctreeError::TooLargeForBox {
                        id: s.id,
                        radius: s.radius,
                        axis,
                        length,
                        max_images: MAX_IMAGES_PER_AXIS,
                    });
                }
            }
        }
    }
    if let Some(id) = first_duplicate(spheres.iter().map(|s| s.id)) {
        return Err(OctreeError::DuplicateId { id });
    }
    Ok(())
}

/// The first id seen twice, if any: a bitmap when ids are dense enough, else a sort.
pub(crate) fn first_duplicate(ids: impl ExactSizeIterator<Item = u32> + Clone) -> Option<u32> {
    let n = ids.len();
    let max = ids.clone().max()? as usize;
    if max / 64 <= 4 * n + 64 {
        let mut seen = vec![0u64; max / 64 + 1];
        for id in ids {
            let (word, bit) = (id as usize / 64, 1u64 << (id % 64));
            if seen[word] & bit != 0 {
                return Some(id);
            }
            seen[word] |= bit;
        }
        None
    } else {
        let mut sorted: Vec<u32> = ids.collect();
        sorted.sort_unstable();
        sorted.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
    }
}

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

fn leaf(start: u32, end: u32) -> Node {
    Node {
        bounds: Aabb::EMPTY,
        start,
        end,
        first_child: 0,
        child_count: 0,
    }
}

/// Working state of one build: the node array and the final sphere arrays being filled.
struct Builder<'a> {
    params: &'a Params,
    nodes: &'a mut Vec<Node>,
    lanes: &'a mut Lanes,
    depth: u32,
}

impl Builder<'_> {
    /// Splits node `index` (a leaf so far, covering `cell`, its spheres in `src`) if it
    /// is too full, then its children, depth first. `dst` and `codes` are free space of
    /// the same length; children find their spheres in `dst` and use `src` as free
    /// space in turn, so nothing is copied back. Leaves write their spheres out.
    fn split(
        &mut self,
        index: usize,
        cell: Aabb,
        depth: u32,
        src: &mut [Item],
        dst: &mut [Item],
        codes: &mut [u8],
    ) {
        self.depth = self.depth.max(depth);
        let start = self.nodes[index].start as usize;
        if src.len() <= self.params.max_leaf_size || depth >= self.params.max_depth {
            return self.emit(start, src);
        }
        let extent = [0, 1, 2].map(|a| cell.hi[a] - cell.lo[a]);
        let longest = extent[0].max(extent[1]).max(extent[2]);
        let split = [0, 1, 2].map(|a| extent[a] >= SPLIT_ASPECT * longest);
        let child_side = (0..3)
            .map(|a| if split[a] { 0.5 * extent[a] } else { extent[a] })
            .fold(f64::INFINITY, f64::min);
        let max_radius = self.params.loose_factor * 0.5 * child_side;
        let mid = [0, 1, 2].map(|a| cell.lo[a] + 0.5 * extent[a]);

        // Bucket 0 keeps the large spheres; bucket 1 + octant takes the rest.
        let mut counts = [0usize; MAX_CHILDREN];
        for (item, code) in src.iter().zip(codes.iter_mut()) {
            let c = item.centre;
            let octant = (0..3).fold(0, |o, a| o | (usize::from(split[a] && c[a] >= mid[a]) << a));
            let bucket = if item.radius > max_radius {
                0
            } else {
                1 + octant
            };
            *code = bucket as u8;
            counts[bucket] += 1;
        }
        if counts[0] == src.len() {
            return self.emit(start, src); // all too large for a child: stay a leaf
        }
        let mut offsets = [0usize; MAX_CHILDREN + 1];
        for b in 0..MAX_CHILDREN {
            offsets[b + 1] = offsets[b] + counts[b];
        }
        let mut cursor = offsets;
        for (item, &code) in src.iter().zip(codes.iter()) {
            dst[cursor[code as usize]] = *item;
            cursor[code as usize] += 1;
        }

        let first_child = self.nodes.len();
        let buckets: Vec<usize> = (0..MAX_CHILDREN).filter(|&b| counts[b] > 0).collect();
        for &b in &buckets {
            self.nodes.push(leaf(
                (start + offsets[b]) as u32,
                (start + offsets[b + 1]) as u32,
            ));
        }
        self.nodes[index].first_child = first_child as u32;
        self.nodes[index].child_count = buckets.len() as u32;
        let (mut src, mut dst, mut codes) = (src, dst, codes);
        for (child, &b) in buckets.iter().enumerate() {
            let (src_head, src_tail) = std::mem::take(&mut src).split_at_mut(counts[b]);
            let (dst_head, dst_tail) = std::mem::take(&mut dst).split_at_mut(counts[b]);
            let (codes_head, codes_tail) = std::mem::take(&mut codes).split_at_mut(counts[b]);
            (src, dst, codes) = (src_tail, dst_tail, codes_tail);
            if b == 0 {
                self.depth = self.depth.max(depth + 1);
                self.emit(start + offsets[0], dst_head); // the bucket stays a leaf
            } else {
                let cell = child_cell(&cell, &mid, &split, b);
                self.split(
                    first_child + child,
                    cell,
                    depth + 1,
                    dst_head,
                    src_head,
                    codes_head,
                );
            }
        }
    }

    /// Writes a leaf's spheres to the final arrays from position `start`.
    fn emit(&mut self, start: usize, items: &[Item]) {
        for (k, item) in items.iter().enumerate() {
            self.lanes.set(start + k, item.centre, item.radius, item.id);
        }
    }
}
/// The cell of bucket `b` (1 + octant code) of `cell`; the bucket 0 keeps `cell`.
fn child_cell(cell: &Aabb, mid: &[f64; 3], split: &[bool; 3], b: usize) -> Aabb {
    let mut child = *cell;
    if b == 0 {
        return child;
    }
    for a in 0..3 {
        if split[a] {
            if (b - 1) >> a & 1 == 1 {
                child.lo[a] = mid[a];
            } else {
                child.hi[a] = mid[a];
            }
        }
    }
    child
}
