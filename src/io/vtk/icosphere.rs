//! The unit icosphere: the triangulated sphere every grain's surface is mapped from.

use std::collections::HashMap;

/// A triangulation of the unit sphere: the icosahedron with each triangle cut into
/// four `level` times, new points pushed out onto the sphere.
///
/// It has `10·4^level + 2` points and `20·4^level` triangles, every point on the unit
/// sphere and every triangle counter-clockwise seen from outside (its normal
/// `(p1 − p0) × (p2 − p0)` points outwards). Each edge is shared by exactly two
/// triangles, which run along it in opposite directions: the surface is closed and
/// consistently oriented.
///
/// ```
/// use grainpack::io::vtk::Icosphere;
/// let sphere = Icosphere::new(2);
/// assert_eq!((sphere.points.len(), sphere.triangles.len()), (162, 320));
/// let deficit = 1.0 - sphere.volume() / (4.0 / 3.0 * std::f64::consts::PI);
/// assert!(deficit > 0.0 && deficit < 0.04);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Icosphere {
    /// Points on the unit sphere.
    pub points: Vec<[f64; 3]>,
    /// Triangles, as indices into `points`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// The icosahedron's faces, counter-clockwise seen from outside, over the points of
/// [`icosahedron_points`] (the usual numbering, e.g. Kahler's "Creating an icosphere
/// mesh in code").
const FACES: [[u32; 3]; 20] = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
];

/// The icosahedron's 12 vertices `(±1, ±t, 0)` and their cyclic permutations, for the
/// golden ratio `t`, on the unit sphere.
fn icosahedron_points() -> Vec<[f64; 3]> {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .into_iter()
    .map(normalised)
    .collect()
}

fn normalised(p: [f64; 3]) -> [f64; 3] {
    let norm = p.iter().map(|x| x * x).sum::<f64>().sqrt();
    p.map(|x| x / norm)
}

impl Icosphere {
    /// The icosphere of subdivision level `level` (0 is the icosahedron).
    pub fn new(level: u32) -> Self {
        let mut points = icosahedron_points();
        let mut triangles = FACES.to_vec();
        for _ in 0..level {
            // Each edge's midpoint is made once and shared by its two triangles.
            let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
            let mut midpoint = |a: u32, b: u32, points: &mut Vec<[f64; 3]>| {
                *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let (p, q) = (points[a as usize], points[b as usize]);
                    points.push(normalised([0, 1, 2].map(|i| p[i] + q[i])));
                    (points.len() - 1) as u32
                })
            };
            let mut finer = Vec::with_capacity(4 * triangles.len());
            for [a, b, c] in triangles {
                let ab = midpoint(a, b, &mut points);
                let bc = midpoint(b, c, &mut points);
                let ca = midpoint(c, a, &mut points);
                finer.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
            }
            triangles = finer;
        }
        Self { points, triangles }
    }

    /// The enclosed volume, `Σ det(p0, p1, p2) / 6` over the triangles (the divergence
    /// theorem; positive because the triangles face outwards). Below the sphere's
    /// `4π/3`, since the points lie on the sphere and the flat triangles inside it.
    pub fn volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [p, q, r] = t.map(|i| self.points[i as usize]);
                det(p, q, r) / 6.0
            })
            .sum()
    }
}

/// `p · (q × r)`.
pub(super) fn det(p: [f64; 3], q: [f64; 3], r: [f64; 3]) -> f64 {
    p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0])
        + p[2] * (q[0] * r[1] - q[1] * r[0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;
    use std::f64::consts::PI;

    /// Rounding of a normalised point's length: a few ulp.
    const UNIT_TOL: f64 = 8.0 * f64::EPSILON;

    #[test]
    fn every_level_is_a_closed_consistently_oriented_sphere() {
        for level in 0..=4 {
            let s = Icosphere::new(level);
            assert_eq!(s.points.len(), 10 * 4usize.pow(level) + 2);
            assert_eq!(s.triangles.len(), 20 * 4usize.pow(level));
            for p in &s.points {
                let r = p.iter().map(|x| x * x).sum::<f64>().sqrt();
                assert!((r - 1.0).abs() < UNIT_TOL, "level {level}: |p| = {r}");
            }
            // Every directed edge once, and its reverse once: closed and oriented.
            let mut edges = HashSet::new();
            for &[a, b, c] in &s.triangles {
                for e in [(a, b), (b, c), (c, a)] {
                    assert!(edges.insert(e), "level {level}: edge {e:?} twice");
                }
            }
            for &(a, b) in &edges {
                assert!(
                    edges.contains(&(b, a)),
                    "level {level}: edge ({a}, {b}) open"
                );
            }
            // Outward: each triangle's normal points away from the centre.
            for t in &s.triangles {
                let [p, q, r] = t.map(|i| s.points[i as usize]);
                assert!(det(p, q, r) > 0.0, "level {level}: {t:?} faces inwards");
            }
        }
    }

    #[test]
    fn the_volume_approaches_the_sphere_from_below() {
        let sphere = 4.0 / 3.0 * PI;
        let mut last = 0.0;
        for level in 0..=5 {
            let v = Icosphere::new(level).volume();
            assert!(v > last && v < sphere, "level {level}: {v}");
            last = v;
        }
        // The icosahedron inscribed in the unit sphere: (5/12)(3 + √5) a³ for the edge
        // a = 4 / √(10 + 2√5).
        let a = 4.0 / (10.0 + 2.0 * 5f64.sqrt()).sqrt();
        let exact = 5.0 / 12.0 * (3.0 + 5f64.sqrt()) * a.powi(3);
        // A sum of 20 terms: a few ulp of the total.
        assert!((Icosphere::new(0).volume() - exact).abs() < 32.0 * f64::EPSILON * exact);
    }
}
