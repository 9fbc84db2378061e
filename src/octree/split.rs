//! Splitting a node into its octants (and the bucket of its large spheres), depth first,
//! the children of large nodes in parallel.

use super::boundary::Aabb;
use super::kernel::Window;
use super::scratch::Item;
use super::tree::Node;
use super::Params;
use rayon::prelude::*;

/// Most children a node can have: eight octants plus the bucket of large spheres.
const MAX_CHILDREN: usize = 9;

/// An axis is split only if it is at least this fraction of the node's longest side,
/// so cells of a non-cubic box stay within an aspect ratio of 2 (a 4:1:1 box splits
/// along x alone, then into octants): cubic-ish cells keep the loose rule meaningful.
const SPLIT_ASPECT: f64 = 0.5;

pub(super) fn leaf(start: u32, end: u32) -> Node {
    Node {
        bounds: Aabb::EMPTY,
        start,
        end,
        first_child: 0,
        child_count: 0,
    }
}

/// Working state of one build: the node array and the final sphere arrays being filled.
pub(super) struct Builder<'a, 'n> {
    pub params: &'a Params,
    pub nodes: &'n mut Vec<Node>,
    pub lanes: Window<'a>,
    pub depth: u32,
    /// Nodes of at least this many spheres have their children built in parallel.
    pub parallel_from: usize,
}

/// How a node's cell is cut: the cell, its middle, and the axes split there.
type Cut = (Aabb, [f64; 3], [bool; 3]);

/// One child of a split node before its subtree is built: its bucket, its spheres, and
/// free space of the same length.
struct Child<'a> {
    bucket: usize,
    items: &'a mut [Item],
    free: &'a mut [Item],
    codes: &'a mut [u8],
}

/// One child of a node split in parallel, with its own part of the final arrays.
struct Piece<'a> {
    node: Node,
    child: Child<'a>,
    lanes: Window<'a>,
}

impl Builder<'_, '_> {
    /// Splits node `index` (a leaf so far, covering `cell`, its spheres in `src`) if it
    /// is too full, then its children, depth first. `dst` and `codes` are free space of
    /// the same length; children find their spheres in `dst` and use `src` as free
    /// space in turn, so nothing is copied back. Leaves write their spheres out.
    pub fn split(
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
        let cut = (cell, mid, split);
        if src.len() >= self.parallel_from {
            let parts = (src, dst, codes);
            return self.split_children(first_child, (&buckets, &counts), parts, cut, depth + 1);
        }
        for (k, child) in children(&buckets, &counts, src, dst, codes).enumerate() {
            self.grow(first_child + k, child, cut, depth + 1);
        }
    }

    /// Builds the subtree of node `index`, a child of a node split by `cut`: the bucket
    /// of large spheres stays a leaf, an octant is split further.
    fn grow(&mut self, index: usize, child: Child, cut: Cut, depth: u32) {
        let (cell, mid, split) = cut;
        if child.bucket == 0 {
            self.depth = self.depth.max(depth);
            let start = self.nodes[index].start as usize;
            return self.emit(start, child.items);
        }
        let cell = child_cell(&cell, &mid, &split, child.bucket);
        self.split(index, cell, depth, child.items, child.free, child.codes);
    }

    /// Builds the subtrees of the children `first_child..` (of `buckets`, sized
    /// `counts`) in parallel, then appends their nodes in order with their indices
    /// moved to where they land.
    fn split_children(
        &mut self,
        first_child: usize,
        (buckets, counts): (&[usize], &[usize; MAX_CHILDREN]),
        (src, dst, codes): (&mut [Item], &mut [Item], &mut [u8]),
        cut: Cut,
        depth: u32,
    ) {
        let mut lanes = std::mem::replace(&mut self.lanes, Window::empty());
        let pieces: Vec<Piece> = children(buckets, counts, src, dst, codes)
            .enumerate()
            .map(|(k, child)| {
                let node = self.nodes[first_child + k];
                let whole = std::mem::replace(&mut lanes, Window::empty());
                let (head, tail) = whole.split_at(node.end as usize);
                lanes = tail;
                Piece {
                    node,
                    child,
                    lanes: head,
                }
            })
            .collect();
        let (params, parallel_from) = (self.params, self.parallel_from);
        let built: Vec<(Vec<Node>, u32)> = pieces
            .into_par_iter()
            .map(|piece| {
                let mut nodes = vec![piece.node];
                let mut builder = Builder {
                    params,
                    nodes: &mut nodes,
                    lanes: piece.lanes,
                    depth,
                    parallel_from,
                };
                builder.grow(0, piece.child, cut, depth);
                let depth = builder.depth;
                (nodes, depth)
            })
            .collect();
        for (child, (nodes, depth)) in built.into_iter().enumerate() {
            // Local node k > 0 lands at `base + k − 1`; local node 0 is the child itself.
            let base = self.nodes.len() as u32;
            let moved = |mut n: Node| {
                if !n.is_leaf() {
                    n.first_child += base - 1;
                }
                n
            };
            self.nodes[first_child + child] = moved(nodes[0]);
            self.nodes.extend(nodes[1..].iter().map(|&n| moved(n)));
            self.depth = self.depth.max(depth);
        }
    }

    /// Writes a leaf's spheres to the final arrays from position `start`.
    fn emit(&mut self, start: usize, items: &[Item]) {
        for (k, item) in items.iter().enumerate() {
            self.lanes.set(start + k, item.centre, item.radius, item.id);
        }
    }
}

/// The children of a node split into `buckets` (sized `counts`): each finds its
/// spheres in its part of `dst` (where the split put them) and uses its part of `src`
/// as free space, so nothing is copied back.
fn children<'a>(
    buckets: &'a [usize],
    counts: &'a [usize; MAX_CHILDREN],
    mut src: &'a mut [Item],
    mut dst: &'a mut [Item],
    mut codes: &'a mut [u8],
) -> impl Iterator<Item = Child<'a>> + 'a {
    buckets.iter().map(move |&b| {
        let (src_head, src_tail) = std::mem::take(&mut src).split_at_mut(counts[b]);
        let (dst_head, dst_tail) = std::mem::take(&mut dst).split_at_mut(counts[b]);
        let (codes_head, codes_tail) = std::mem::take(&mut codes).split_at_mut(counts[b]);
        (src, dst, codes) = (src_tail, dst_tail, codes_tail);
        Child {
            bucket: b,
            items: dst_head,
            free: src_head,
            codes: codes_head,
        }
    })
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
