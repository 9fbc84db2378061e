//! The structural invariants every tree must satisfy.

use super::validate::first_duplicate;
use super::{InvariantViolation, Octree};

impl Octree {
    /// Checks that the tree is sound, in O(n): every sphere is stored exactly once (the
    /// leaves' ranges tile the sphere arrays and no id repeats), every node's bounds
    /// contain its spheres or its children's bounds, no node is empty or deeper than
    /// [`Params::max_depth`](super::Params::max_depth), and periodic centres are wrapped.
    ///
    /// Completeness of [`Octree::pairs`] and [`Octree::neighbours`] rests on these alone.
    /// Tests call it; debug builds run it after every build.
    pub fn check_invariants(&self) -> Result<(), InvariantViolation> {
        if let Some(id) = first_duplicate(self.spheres.id.iter().copied()) {
            return Err(InvariantViolation::DuplicateId { id });
        }
        self.check_wrapped()?;
        let Some(root) = self.nodes.first() else {
            return match self.spheres.id.first() {
                None => Ok(()),
                Some(_) => Err(InvariantViolation::RangesDoNotTile { node: 0 }),
            };
        };
        if root.start != 0 || root.end as usize != self.spheres.len() {
            return Err(InvariantViolation::RangesDoNotTile { node: 0 });
        }
        let mut visited = vec![false; self.nodes.len()];
        let mut stack = vec![(0usize, 0u32)];
        while let Some((k, depth)) = stack.pop() {
            let node = &self.nodes[k];
            let id = k as u32;
            if std::mem::replace(&mut visited[k], true) {
                return Err(InvariantViolation::RangesDoNotTile { node: id });
            }
            if node.start >= node.end {
                return Err(InvariantViolation::EmptyNode { node: id });
            }
            if depth > self.params.max_depth {
                return Err(InvariantViolation::TooDeep { node: id, depth });
            }
            if node.is_leaf() {
                for s in node.range() {
                    if !node.bounds.contains(&self.spheres.aabb(s)) {
                        let sphere = self.spheres.id[s];
                        return Err(InvariantViolation::BoundsMissSphere {
                            node: id,
                            id: sphere,
                        });
                    }
                }
                continue;
            }
            let children = node.children();
            if children.start <= k || children.end > self.nodes.len() {
                return Err(InvariantViolation::RangesDoNotTile { node: id });
            }
            let mut next = node.start;
            for c in children {
                let child = &self.nodes[c];
                if child.start != next {
                    return Err(InvariantViolation::RangesDoNotTile { node: id });
                }
                next = child.end;
                if !node.bounds.contains(&child.bounds) {
                    return Err(InvariantViolation::BoundsMissChild {
                        node: id,
                        child: c as u32,
                    });
                }
                stack.push((c, depth + 1));
            }
            if next != node.end {
                return Err(InvariantViolation::RangesDoNotTile { node: id });
            }
        }
        match visited.iter().position(|&v| !v) {
            Some(k) => Err(InvariantViolation::RangesDoNotTile { node: k as u32 }),
            None => Ok(()),
        }
    }

    fn check_wrapped(&self) -> Result<(), InvariantViolation> {
        if !self.shape.is_periodic() {
            return Ok(());
        }
        for s in 0..self.spheres.len() {
            let c = self.spheres.centre(s);
            for (axis, (&value, &length)) in c.iter().zip(&self.shape.lengths).enumerate() {
                if !(0.0..length).contains(&value) {
                    return Err(InvariantViolation::NotWrapped {
                        id: self.spheres.id[s],
                        axis,
                        value,
                    });
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::{BoxShape, Octree, Params, Sphere};
    use super::InvariantViolation;

    /// A tree deep enough to have internal nodes and several leaves.
    fn tree() -> Octree {
        let spheres: Vec<Sphere> = (0..200u32)
            .map(|id| {
                let t = f64::from(id);
                let centre = [
                    (t * 0.618).fract(),
                    (t * 0.414).fract(),
                    (t * 0.732).fract(),
                ];
                Sphere {
                    id,
                    centre,
                    radius: 0.01,
                }
            })
            .collect();
        let params = Params {
            max_leaf_size: 4,
            ..Params::default()
        };
        let tree = Octree::build(&spheres, BoxShape::periodic([1.0; 3]).unwrap(), params).unwrap();
        assert!(tree.nodes.len() > 9);
        tree
    }

    #[test]
    fn a_leaf_whose_bounds_miss_a_sphere_is_caught() {
        let mut t = tree();
        let leaf = t.nodes.iter().rposition(|n| n.is_leaf()).unwrap();
        t.nodes[leaf].bounds.hi[0] = t.nodes[leaf].bounds.lo[0];
        assert!(matches!(
            t.check_invariants(),
            Err(InvariantViolation::BoundsMissSphere { .. })
        ));
    }

    #[test]
    fn a_parent_whose_bounds_miss_a_child_is_caught() {
        let mut t = tree();
        t.nodes[0].bounds.lo[1] += 0.5;
        assert!(matches!(
            t.check_invariants(),
            Err(InvariantViolation::BoundsMissChild { node: 0, .. })
        ));
    }

    #[test]
    fn a_sphere_stored_twice_is_caught() {
        let mut t = tree();
        t.spheres.id[5] = t.spheres.id[6];
        assert!(matches!(
            t.check_invariants(),
            Err(InvariantViolation::DuplicateId { .. })
        ));
    }

    #[test]
    fn children_that_skip_a_sphere_are_caught() {
        let mut t = tree();
        let c = t.nodes[0].first_child as usize;
        t.nodes[c].start += 1;
        assert!(t.check_invariants().is_err());
    }

    #[test]
    fn an_unwrapped_centre_is_caught() {
        let mut t = tree();
        t.spheres.x[3] = 1.0;
        assert!(t.check_invariants().is_err());
    }
}
