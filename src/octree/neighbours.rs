//! Spheres met by one query sphere.

use super::boundary::{image_range, spheres_intersect, Aabb};
use super::{Neighbour, Octree, OctreeError};

impl Octree {
    /// Clears `out` and fills it with every stored sphere that meets the query sphere
    /// (`centre`, `radius`), once per periodic image: `(id, shift)` with
    /// `|c_id + shift − centre| ≤ r_id + radius` ([`spheres_intersect`] with the query
    /// first). A radius of 0 asks which spheres contain a point.
    ///
    /// The centre need not be wrapped; shifts bring the (wrapped) stored sphere next to
    /// the centre as given. A query for a stored grain finds that grain itself with a
    /// zero shift: the caller filters it. Order: deterministic, by image then tree order.
    ///
    /// ```
    /// use grainpack::octree::{BoxShape, Octree, Params, Sphere};
    /// let shape = BoxShape::periodic([10.0; 3]).unwrap();
    /// let s = [Sphere { id: 4, centre: [9.5, 5.0, 5.0], radius: 1.0 }];
    /// let tree = Octree::build(&s, shape, Params::default()).unwrap();
    /// let mut found = Vec::new();
    /// tree.neighbours([0.2, 5.0, 5.0], 0.5, &mut found).unwrap();
    /// assert_eq!((found[0].id, found[0].shift), (4, [-10.0, 0.0, 0.0]));
    /// ```
    pub fn neighbours(
        &self,
        centre: [f64; 3],
        radius: f64,
        out: &mut Vec<Neighbour>,
    ) -> Result<(), OctreeError> {
        if !(centre.iter().all(|x| x.is_finite()) && radius.is_finite() && radius >= 0.0) {
            return Err(OctreeError::InvalidQuery { centre, radius });
        }
        out.clear();
        let Some(root) = self.nodes.first() else {
            return Ok(());
        };
        let query = Aabb::of_sphere(centre, radius);
        let images = if self.shape.is_periodic() {
            let l = self.shape.lengths;
            [0, 1, 2].map(|a| {
                image_range(
                    query.lo[a] - root.bounds.hi[a],
                    query.hi[a] - root.bounds.lo[a],
                    l[a],
                )
            })
        } else {
            [0..=0, 0..=0, 0..=0]
        };
        let mut shifts = Vec::new();
        for k0 in images[0].clone() {
            for k1 in images[1].clone() {
                for k2 in images[2].clone() {
                    shifts.push(self.shape.shift([k0, k1, k2]));
                }
            }
        }
        let max_shift = shifts.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
        let tol = self.overlap_tol(max_shift + query.magnitude());
        let mut stack = Vec::new();
        for s in shifts {
            stack.push(0);
            while let Some(k) = stack.pop() {
                let node = &self.nodes[k];
                if !query.overlaps_shifted(&node.bounds, s, tol) {
                    continue;
                }
                if node.is_leaf() {
                    for y in node.range() {
                        let (c, r) = (self.spheres.centre(y), self.spheres.r[y]);
                        if spheres_intersect(centre, radius, c, r, s) {
                            out.push(Neighbour {
                                id: self.spheres.id[y],
                                shift: s,
                            });
                        }
                    }
                } else {
                    stack.extend(node.children().rev());
                }
            }
        }
        Ok(())
    }
}
