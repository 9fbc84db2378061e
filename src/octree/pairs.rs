//! All intersecting pairs: a dual-tree walk, split into tasks for rayon.

use super::boundary::{image_range, is_positive_image, small_image};
use super::{Octree, Pair};
use rayon::prelude::*;
use std::ops::Range;

/// The walk is cut into at least this many independent tasks before they run, so that
/// rayon can balance them; the cut depends on the tree only, never on the thread count,
/// which keeps the output order fixed.
const TARGET_TASKS: usize = 256;

/// Tasks walked at once between two appends to the list ([`Octree::pairs`]). With all
/// of them at once, every task's part (and its growth slack) was held beside the list
/// while it was copied: at 1.17 M grains (`benches/scale/million.toml`, 2 threads) the
/// peak was 1.48–1.56 GB, with windows of 32 tasks 1.359 GB, the broad phase 6 % shorter
/// and the packing 2 % longer (BENCHMARKS.md, "Issues 26 and 27: tried, not kept").
const WINDOW_TASKS: usize = 32;

/// Counters of one pair query (they feed the progress bar and the benchmarks).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PairStats {
    /// Node pairs whose bounds were compared.
    pub node_tests: u64,
    /// Sphere pairs on which [`spheres_intersect`](super::spheres_intersect) ran.
    pub sphere_tests: u64,
    /// Pairs reported.
    pub pairs: u64,
}

impl PairStats {
    fn add(&mut self, other: &Self) {
        self.node_tests += other.node_tests;
        self.sphere_tests += other.sphere_tests;
        self.pairs += other.pairs;
    }
}

/// A piece of the walk: all pairs within one subtree, or all pairs between two
/// subtrees with the second moved by periodic image `k`.
#[derive(Debug, Clone, Copy)]
enum Task {
    Within(u32),
    Between(u32, u32, [i32; 3]),
}

impl Octree {
    /// Clears `out` and fills it with every intersecting pair (see the
    /// [module docs](super) for the exact definition), returning the counters.
    ///
    /// Order: deterministic, the same with or without rayon and from run to run for the
    /// same input and parameters, but not sorted; sort if you need an order.
    /// Cost O(n log n + pairs) for bounded size ratios.
    pub fn pairs(&self, out: &mut Vec<Pair>) -> PairStats {
        out.clear();
        let mut stats = PairStats::default();
        if self.nodes.is_empty() {
            return stats;
        }
        let walker = self.walker();
        let tasks = walker.tasks(&mut stats);
        if self.runs_parallel() {
            // A window of tasks at a time, its parts appended in order and dropped before
            // the next: the list is built beside one window's parts, not all of them.
            for window in tasks.chunks(WINDOW_TASKS) {
                let parts: Vec<(Vec<Pair>, PairStats)> = window
                    .par_iter()
                    .map(|&task| {
                        let mut part = Vec::new();
                        let mut sink = Sink {
                            out: &mut part,
                            stats: PairStats::default(),
                        };
                        walker.run(task, &mut sink);
                        let stats = sink.stats;
                        (part, stats)
                    })
                    .collect();
                out.reserve(parts.iter().map(|(p, _)| p.len()).sum());
                for (part, s) in &parts {
                    out.extend_from_slice(part);
                    stats.add(s);
                }
            }
        } else {
            let mut sink = Sink {
                out,
                stats: PairStats::default(),
            };
            for &task in &tasks {
                walker.run(task, &mut sink);
            }
            stats.add(&sink.stats);
        }
        stats.pairs = out.len() as u64;
        stats
    }

    fn walker(&self) -> Walker<'_> {
        let mut images = Vec::new();
        let mut max_shift = 0.0_f64;
        if self.shape.is_periodic() {
            let root = self.nodes[0].bounds;
            let spans = [0, 1, 2].map(|a| {
                let reach = root.hi[a] - root.lo[a];
                image_range(-reach, reach, self.shape.lengths[a])
            });
            for k0 in spans[0].clone() {
                for k1 in spans[1].clone() {
                    for k2 in spans[2].clone() {
                        let k = [k0, k1, k2];
                        if is_positive_image(k) {
                            let s = self.shape.shift(k);
                            max_shift = max_shift.max(s[0].abs()).max(s[1].abs()).max(s[2].abs());
                            images.push(k);
                        }
                    }
                }
            }
        }
        Walker {
            tree: self,
            images,
            tol: self.overlap_tol(max_shift),
        }
    }
}

/// What the walk needs: the tree, the images to try at the root and the slack of the
/// box-overlap test.
struct Walker<'a> {
    tree: &'a Octree,
    images: Vec<[i32; 3]>,
    tol: f64,
}

impl Walker<'_> {
    /// The root tasks, cut breadth first until there are [`TARGET_TASKS`] of them or
    /// nothing left to cut.
    fn tasks(&self, stats: &mut PairStats) -> Vec<Task> {
        let mut tasks = vec![Task::Within(0)];
        tasks.extend(self.images.iter().map(|&k| Task::Between(0, 0, k)));
        let nodes = &self.tree.nodes;
        loop {
            let mut next = Vec::with_capacity(tasks.len() * 8);
            let mut cut = false;
            for &task in &tasks {
                match task {
                    Task::Within(a) if !nodes[a as usize].is_leaf() => {
                        let children = nodes[a as usize].children();
                        for c in children.clone() {
                            next.push(Task::Within(c as u32));
                            for d in c + 1..children.end {
                                next.push(Task::Between(c as u32, d as u32, [0; 3]));
                            }
                        }
                        cut = true;
                    }
                    Task::Between(a, b, k) => {
                        match self.descend(a as usize, b as usize, self.tree.shape.shift(k), stats)
                        {
                            Descend::Apart => cut = true,
                            Descend::Leaves => next.push(task),
                            Descend::First => {
                                cut = true;
                                let children = nodes[a as usize].children();
                                next.extend(children.map(|c| Task::Between(c as u32, b, k)));
                            }
                            Descend::Second => {
                                cut = true;
                                let children = nodes[b as usize].children();
                                next.extend(children.map(|c| Task::Between(a, c as u32, k)));
                            }
                        }
                    }
                    Task::Within(_) => next.push(task),
                }
            }
            tasks = next;
            if !cut || tasks.len() >= TARGET_TASKS {
                return tasks;
            }
        }
    }

    fn run(&self, task: Task, sink: &mut Sink) {
        match task {
            Task::Within(a) => self.within(a as usize, sink),
            Task::Between(a, b, k) => self.between(a as usize, b as usize, k, sink),
        }
    }

    /// Which side of a node pair to open next, if any.
    fn descend(&self, a: usize, b: usize, s: [f64; 3], stats: &mut PairStats) -> Descend {
        let nodes = &self.tree.nodes;
        let (na, nb) = (&nodes[a], &nodes[b]);
        stats.node_tests += 1;
        if !na.bounds.overlaps_shifted(&nb.bounds, s, self.tol) {
            Descend::Apart
        } else if na.is_leaf() && nb.is_leaf() {
            Descend::Leaves
        } else if nb.is_leaf() || (!na.is_leaf() && na.len() >= nb.len()) {
            Descend::First
        } else {
            Descend::Second
        }
    }

    fn within(&self, a: usize, sink: &mut Sink) {
        let node = &self.tree.nodes[a];
        if node.is_leaf() {
            self.leaf_within(node.range(), sink);
            return;
        }
        let children = node.children();
        for c in children.clone() {
            self.within(c, sink);
            for d in c + 1..children.end {
                self.between(c, d, [0; 3], sink);
            }
        }
    }

    /// All pairs of a sphere under node `a` with one under node `b` moved to image `k`.
    fn between(&self, a: usize, b: usize, k: [i32; 3], sink: &mut Sink) {
        match self.descend(a, b, self.tree.shape.shift(k), &mut sink.stats) {
            Descend::Apart => {}
            Descend::Leaves => {
                self.leaf_between(a, b, k, sink);
            }
            Descend::First => {
                for c in self.tree.nodes[a].children() {
                    self.between(c, b, k, sink);
                }
            }
            Descend::Second => {
                for c in self.tree.nodes[b].children() {
                    self.between(a, c, k, sink);
                }
            }
        }
    }

    /// All pairs inside one leaf (no shift).
    fn leaf_within(&self, r: Range<usize>, sink: &mut Sink) {
        let leaf = self.tree.spheres.view(r);
        for a in 0..leaf.len() {
            leaf.tail(a + 1).zero_shift_pairs(leaf.probe(a), sink.out);
        }
        let n = leaf.len() as u64;
        sink.stats.sphere_tests += n * n.saturating_sub(1) / 2;
    }

    /// All pairs `(x, y + s)` with `x` in leaf `a` and `y` in leaf `b`; an `x` whose
    /// box misses `b`'s bounds (shifted, with the slack) is skipped.
    fn leaf_between(&self, a: usize, b: usize, k: [i32; 3], sink: &mut Sink) {
        let t = self.tree;
        let s = t.shape.shift(k);
        let (na, nb) = (&t.nodes[a], &t.nodes[b]);
        let ys = t.spheres.view(nb.range());
        // The same sums as `Aabb::overlaps_shifted`, hoisted out of the loop.
        let lo = [0, 1, 2].map(|k| nb.bounds.lo[k] + s[k] - self.tol);
        let hi = [0, 1, 2].map(|k| nb.bounds.hi[k] + s[k] + self.tol);
        let xs = t.spheres.view(na.range());
        if s == [0.0; 3] {
            xs.for_each_reaching(lo, hi, |x| {
                sink.stats.sphere_tests += ys.len() as u64;
                ys.zero_shift_pairs(xs.probe(x), sink.out);
            });
        } else {
            // `0 − x`, not `−x`: equals `shift(−k)` bit for bit, a zero stays `+0.0`.
            let minus_s = s.map(|x| 0.0 - x);
            xs.for_each_reaching(lo, hi, |x| {
                sink.stats.sphere_tests += ys.len() as u64;
                ys.shifted_pairs(xs.probe(x), (s, minus_s), small_image(k), sink.out);
            });
        }
    }
}

/// Where a task puts its pairs and its counters.
struct Sink<'o> {
    out: &'o mut Vec<Pair>,
    stats: PairStats,
}

/// The outcome of comparing two nodes' bounds.
enum Descend {
    Apart,
    Leaves,
    First,
    Second,
}
