//! `grains.vtu`: every grain's surface as triangles, with its figures as cell data.

use super::icosphere::Icosphere;
use super::{encode, grain_id, phase_index, rotation, TRIANGLE};
use crate::contact::{ellipsoid_volume, equivalent_diameter};
use crate::packing::PackedGrain;
use crate::scene::{aspect_ratio, quaternion_to_euler};
use crate::scene::{Boundary, Domain, VtkSpec};
use std::io::{self, Write};
use vtkio::model::{
    Attribute, Attributes, Cells, DataSet, IOBuffer, UnstructuredGridPiece, VertexNumbers,
};

/// The translations of a grain's copies in `grains.vtu`: none in a walled box;
/// in a periodic box, one for each combination of faces that the grain's bounding
/// box crosses, each shifting it by ±L to the far side (+L across the face at 0, −L
/// across the face at L). A grain is shorter than the box, so it crosses at most one
/// face of each pair: 0, 1, 3 or 7 copies.
///
/// The bounding box is the ellipsoid's exact one, half-extent `√Q_ii` along axis `i`.
pub fn periodic_shifts(grain: &PackedGrain, domain: &Domain) -> Vec<[f64; 3]> {
    if domain.boundary != Boundary::Periodic {
        return Vec::new();
    }
    let r = rotation(grain.quaternion);
    let mut per_axis: [Vec<f64>; 3] = Default::default();
    for (i, shifts) in per_axis.iter_mut().enumerate() {
        let extent = (0..3)
            .map(|k| (grain.semi_axes[k] * r[k][i]).powi(2))
            .sum::<f64>()
            .sqrt();
        let (c, l) = (grain.centre[i], domain.size[i]);
        shifts.push(0.0);
        if c - extent < 0.0 {
            shifts.push(l);
        } else if c + extent > l {
            shifts.push(-l);
        }
    }
    let mut out = Vec::new();
    for &x in &per_axis[0] {
        for &y in &per_axis[1] {
            for &z in &per_axis[2] {
                if [x, y, z] != [0.0; 3] {
                    out.push([x, y, z]);
                }
            }
        }
    }
    out
}

/// The surface of `grain` shifted by `shift`, appended: its points to `points`, its
/// triangles (over those points) to `connectivity`. Point `p` of the unit sphere goes
/// to `c + shift + R diag(a) p`. R is a rotation and `a` positive, so the map keeps
/// the sphere's outward orientation.
fn push_surface(
    sphere: &Icosphere,
    grain: &PackedGrain,
    shift: [f64; 3],
    points: &mut Vec<f64>,
    connectivity: &mut Vec<u64>,
) {
    let first = (points.len() / 3) as u64;
    let r = rotation(grain.quaternion);
    let a = grain.semi_axes;
    for p in &sphere.points {
        for i in 0..3 {
            let local = a[0] * p[0] * r[0][i] + a[1] * p[1] * r[1][i] + a[2] * p[2] * r[2][i];
            points.push(grain.centre[i] + shift[i] + local);
        }
    }
    for t in &sphere.triangles {
        connectivity.extend(t.map(|i| first + u64::from(i)));
    }
}

/// Per-triangle figures of one grain, repeated over its triangles.
#[derive(Default)]
struct CellData {
    grain_id: Vec<i32>,
    phase: Vec<i32>,
    volume: Vec<f64>,
    equivalent_diameter: Vec<f64>,
    aspect_ratio: Vec<f64>,
    b_over_a: Vec<f64>,
    c_over_a: Vec<f64>,
    periodic_image: Vec<i32>,
}

/// DREAM.3D's shape ratios `[b/a, c/a]` of semi-axes sorted `a ≥ b ≥ c`, whatever
/// their order in the grain (an oblate spheroid's `a1` is its shortest).
fn shape_ratios(semi_axes: [f64; 3]) -> [f64; 2] {
    let mut s = semi_axes;
    s.sort_by(|a, b| b.total_cmp(a));
    [s[1] / s[0], s[2] / s[0]]
}

/// Writes `grains.vtu` (VTK XML UnstructuredGrid, binary base64, float64 points):
/// each grain's surface, and in a periodic box with `spec.periodic_images` its
/// [`periodic_shifts`] copies, as `20·4^resolution` triangles each. Cell data, per
/// triangle: `grain_id` and `phase` (the CSV's), `volume` `4π/3·a1·a2·a3` and
/// `equivalent_diameter` `2·(a1·a2·a3)^{1/3}` of the exact ellipsoid, `aspect_ratio`
/// `a1/a2` (first semi-axis over second: both as in the summary,
/// [`crate::run::Statistics`]), `b_over_a` and `c_over_a` (the semi-axes sorted
/// `a ≥ b ≥ c`, DREAM.3D's ratios, which describe triaxial grains), and
/// `periodic_image` (0 for the grain, 1 for a copy); with `crystals` (`crystals[i]`
/// the crystal orientation of `grains[i]`), also `crystal_quaternion` (4 components,
/// scalar first) and `euler_angles` (Bunge, degrees).
pub fn write_grains_vtu(
    out: &mut dyn Write,
    grains: &[PackedGrain],
    domain: &Domain,
    spec: &VtkSpec,
    crystals: Option<&[[f64; 4]]>,
) -> io::Result<()> {
    let sphere = Icosphere::new(spec.resolution);
    let (mut quaternions, mut eulers) = (Vec::new(), Vec::new());
    let per_grain = sphere.triangles.len();
    let mut points = Vec::new();
    let mut connectivity = Vec::new();
    let mut data = CellData::default();
    for (i, g) in grains.iter().enumerate() {
        let (id, phase) = (grain_id(g)?, phase_index(g)?);
        let mut copies = vec![[0.0; 3]];
        if spec.periodic_images {
            copies.extend(periodic_shifts(g, domain));
        }
        for (k, &shift) in copies.iter().enumerate() {
            push_surface(&sphere, g, shift, &mut points, &mut connectivity);
            let n = per_grain;
            data.grain_id.extend(std::iter::repeat_n(id, n));
            data.phase.extend(std::iter::repeat_n(phase, n));
            data.volume
                .extend(std::iter::repeat_n(ellipsoid_volume(g.semi_axes), n));
            data.equivalent_diameter
                .extend(std::iter::repeat_n(equivalent_diameter(g.semi_axes), n));
            data.aspect_ratio
                .extend(std::iter::repeat_n(aspect_ratio(g.semi_axes), n));
            let [ba, ca] = shape_ratios(g.semi_axes);
            data.b_over_a.extend(std::iter::repeat_n(ba, n));
            data.c_over_a.extend(std::iter::repeat_n(ca, n));
            data.periodic_image
                .extend(std::iter::repeat_n(i32::from(k > 0), n));
            if let Some(o) = crystals.and_then(|c| c.get(i)) {
                let e = quaternion_to_euler(*o).map(f64::to_degrees);
                for _ in 0..n {
                    quaternions.extend_from_slice(o);
                    eulers.extend_from_slice(&e);
                }
            }
        }
    }
    let cells = connectivity.len() / 3;
    let piece = UnstructuredGridPiece {
        points: IOBuffer::new(points),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity,
                offsets: (1..=cells as u64).map(|c| 3 * c).collect(),
            },
            types: vec![TRIANGLE; cells],
        },
        data: Attributes {
            point: Vec::new(),
            cell: vec![
                Attribute::scalars("grain_id", 1).with_data(data.grain_id),
                Attribute::generic("phase", 1).with_data(data.phase),
                Attribute::generic("volume", 1).with_data(data.volume),
                Attribute::generic("equivalent_diameter", 1).with_data(data.equivalent_diameter),
                Attribute::generic("aspect_ratio", 1).with_data(data.aspect_ratio),
                Attribute::generic("b_over_a", 1).with_data(data.b_over_a),
                Attribute::generic("c_over_a", 1).with_data(data.c_over_a),
                Attribute::generic("periodic_image", 1).with_data(data.periodic_image),
            ]
            .into_iter()
            .chain(
                crystals
                    .is_some()
                    .then(|| {
                        [
                            Attribute::generic("crystal_quaternion", 4).with_data(quaternions),
                            Attribute::generic("euler_angles", 3).with_data(eulers),
                        ]
                    })
                    .into_iter()
                    .flatten(),
            )
            .collect(),
        },
    };
    encode(out, DataSet::inline(piece))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grain(centre: [f64; 3], semi_axes: [f64; 3]) -> PackedGrain {
        PackedGrain {
            id: 0,
            phase: 0,
            centre,
            semi_axes,
            quaternion: [1.0, 0.0, 0.0, 0.0],
        }
    }

    const PERIODIC: Domain = Domain {
        size: [10.0, 10.0, 10.0],
        boundary: Boundary::Periodic,
    };

    #[test]
    fn a_grain_inside_the_box_has_no_copies() {
        assert!(periodic_shifts(&grain([5.0; 3], [2.0, 1.0, 1.0]), &PERIODIC).is_empty());
    }

    #[test]
    fn a_grain_across_a_corner_has_seven_copies_towards_the_box() {
        let g = grain([0.5, 9.5, 0.5], [2.0, 1.0, 1.0]);
        let shifts = periodic_shifts(&g, &PERIODIC);
        assert_eq!(shifts.len(), 7);
        for s in &shifts {
            // Each copy moves into the box: +L at the low faces, −L at the high one.
            assert!(s[0] == 0.0 || s[0] == 10.0);
            assert!(s[1] == 0.0 || s[1] == -10.0);
            assert!(s[2] == 0.0 || s[2] == 10.0);
        }
    }

    #[test]
    fn the_bounding_box_follows_the_rotation() {
        // Long axis along x: crosses the face x = 0 only.
        let along_x = grain([1.5, 5.0, 5.0], [2.0, 0.5, 0.5]);
        assert_eq!(periodic_shifts(&along_x, &PERIODIC), [[10.0, 0.0, 0.0]]);
        // Turned a quarter about z, the long axis lies along y: no face crossed.
        let h = 0.5f64.sqrt();
        let along_y = PackedGrain {
            quaternion: [h, 0.0, 0.0, h],
            ..along_x
        };
        assert!(periodic_shifts(&along_y, &PERIODIC).is_empty());
    }

    #[test]
    fn a_walled_box_has_no_copies() {
        let walls = Domain {
            boundary: Boundary::Reflecting,
            ..PERIODIC
        };
        assert!(periodic_shifts(&grain([0.5; 3], [2.0, 1.0, 1.0]), &walls).is_empty());
    }
}
