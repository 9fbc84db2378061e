//! `grains.vtu`: every grain's surface as triangles, with its figures as cell data.

use super::icosphere::Icosphere;
use super::xml::{write_piece, Array, Piece, Scalar, Section};
use super::{grain_id, phase_index, rotation, TRIANGLE};
use crate::contact::{ellipsoid_volume, equivalent_diameter};
use crate::packing::PackedGrain;
use crate::scene::{aspect_ratio, quaternion_to_euler};
use crate::scene::{Boundary, Domain, VtkSpec};
use std::io::{self, Write};

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
    let axes = domain.sides().len();
    for (i, shifts) in per_axis.iter_mut().enumerate() {
        shifts.push(0.0);
        if i >= axes {
            continue;
        }
        let extent = (0..3)
            .map(|k| (grain.semi_axes[k] * r[k][i]).powi(2))
            .sum::<f64>()
            .sqrt();
        let (c, l) = (grain.centre[i], domain.size[i]);
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

/// One shape of `grains.vtu` (a surface in 3D, an outline in 2D): a grain (its index)
/// or a periodic copy of it, shifted.
#[derive(Clone, Copy)]
pub(super) struct Placed {
    pub grain: usize,
    pub shift: [f64; 3],
    pub copy: bool,
}

/// Each grain, followed by its periodic copies when `images` asks for them; an error
/// for a grain whose id or phase VTK cannot hold.
pub(super) fn placements(
    grains: &[PackedGrain],
    domain: &Domain,
    images: bool,
) -> io::Result<Vec<Placed>> {
    let mut placed = Vec::with_capacity(grains.len());
    for (i, g) in grains.iter().enumerate() {
        grain_id(g)?;
        phase_index(g)?;
        placed.push(Placed {
            grain: i,
            shift: [0.0; 3],
            copy: false,
        });
        if images {
            placed.extend(periodic_shifts(g, domain).into_iter().map(|shift| Placed {
                grain: i,
                shift,
                copy: true,
            }));
        }
    }
    Ok(placed)
}

/// Appends the points of `grain`'s surface shifted by `shift`: point `p` of the unit
/// sphere goes to `c + shift + R diag(a) p`. R is a rotation and `a` positive, so the
/// map keeps the sphere's outward orientation.
fn push_points(sphere: &Icosphere, grain: &PackedGrain, shift: [f64; 3], bytes: &mut Vec<u8>) {
    let r = rotation(grain.quaternion);
    let a = grain.semi_axes;
    for p in &sphere.points {
        for i in 0..3 {
            let local = a[0] * p[0] * r[0][i] + a[1] * p[1] * r[1][i] + a[2] * p[2] * r[2][i];
            // Single precision: its rounding (6e-8 of the coordinate) is far below the
            // facets' own distance from the ellipsoid (3.4 % of the volume at level 2).
            bytes.extend(((grain.centre[i] + shift[i] + local) as f32).to_le_bytes());
        }
    }
}

/// DREAM.3D's shape ratios `[b/a, c/a]` of semi-axes sorted `a ≥ b ≥ c`, whatever
/// their order in the grain (an oblate spheroid's `a1` is its shortest).
fn shape_ratios(semi_axes: [f64; 3]) -> [f64; 2] {
    let mut s = semi_axes;
    s.sort_by(|a, b| b.total_cmp(a));
    [s[1] / s[0], s[2] / s[0]]
}

/// A cell array of one value per surface, repeated over its triangles: `value(grain,
/// surface)` gives the value's little-endian bytes.
fn per_surface<'a, const N: usize>(
    name: &'static str,
    scalar: Scalar,
    components: usize,
    surfaces: &'a [Placed],
    grains: &'a [PackedGrain],
    triangles: usize,
    value: impl Fn(usize, &PackedGrain, &Placed) -> [u8; N] + 'a,
) -> Array<'a> {
    Array::new(
        Section::CellData,
        name,
        scalar,
        components,
        move |k, bytes| {
            let s = &surfaces[k];
            let v = value(s.grain, &grains[s.grain], s);
            for _ in 0..triangles {
                bytes.extend_from_slice(&v);
            }
        },
    )
}

/// The little-endian bytes of several `f64`s, one after another.
pub(super) fn f64s<const N: usize, const B: usize>(values: [f64; N]) -> [u8; B] {
    let mut out = [0; B];
    for (chunk, v) in out.chunks_exact_mut(8).zip(values) {
        chunk.copy_from_slice(&v.to_le_bytes());
    }
    out
}

/// Writes `grains.vtu` of a 3D scene: see [`write_grains_vtu`](super::write_grains_vtu).
pub(super) fn write_surfaces_vtu(
    out: &mut dyn Write,
    grains: &[PackedGrain],
    domain: &Domain,
    spec: &VtkSpec,
    crystals: Option<&[[f64; 4]]>,
) -> io::Result<()> {
    let sphere = Icosphere::new(spec.resolution);
    let (per_grain, points) = (sphere.triangles.len(), sphere.points.len());
    let surfaces = placements(grains, domain, spec.periodic_images)?;
    let cells = surfaces.len() * per_grain;
    let index = Scalar::index((surfaces.len() * points).max(3 * cells));
    let id = |g: &PackedGrain| grain_id(g).unwrap_or_default().to_le_bytes();
    let phase = |g: &PackedGrain| phase_index(g).unwrap_or_default().to_le_bytes();
    let s = &surfaces;
    let cell = |name, value: fn(&PackedGrain) -> f64| {
        per_surface(
            name,
            Scalar::Float64,
            1,
            s,
            grains,
            per_grain,
            move |_, g, _| value(g).to_le_bytes(),
        )
    };
    let mut arrays = vec![
        per_surface(
            "grain_id",
            Scalar::Int32,
            1,
            s,
            grains,
            per_grain,
            move |_, g, _| id(g),
        ),
        per_surface(
            "phase",
            Scalar::Int32,
            1,
            s,
            grains,
            per_grain,
            move |_, g, _| phase(g),
        ),
        cell("volume", |g| ellipsoid_volume(g.semi_axes)),
        cell("equivalent_diameter", |g| equivalent_diameter(g.semi_axes)),
        cell("aspect_ratio", |g| aspect_ratio(g.semi_axes)),
        cell("b_over_a", |g| shape_ratios(g.semi_axes)[0]),
        cell("c_over_a", |g| shape_ratios(g.semi_axes)[1]),
        per_surface(
            "periodic_image",
            Scalar::UInt8,
            1,
            s,
            grains,
            per_grain,
            |_, _, s| [u8::from(s.copy)],
        ),
    ];
    if let Some(c) = crystals {
        let q = move |i: usize| c.get(i).copied().unwrap_or([1.0, 0.0, 0.0, 0.0]);
        arrays.push(per_surface(
            "crystal_quaternion",
            Scalar::Float64,
            4,
            s,
            grains,
            per_grain,
            move |i, _, _| f64s::<4, 32>(q(i)),
        ));
        arrays.push(per_surface(
            "euler_angles",
            Scalar::Float64,
            3,
            s,
            grains,
            per_grain,
            move |i, _, _| f64s::<3, 24>(quaternion_to_euler(q(i)).map(f64::to_degrees)),
        ));
    }
    let sphere = &sphere;
    arrays.push(Array::new(
        Section::Points,
        "Points",
        Scalar::Float32,
        3,
        move |k, b| push_points(sphere, &grains[s[k].grain], s[k].shift, b),
    ));
    arrays.push(Array::new(
        Section::Cells,
        "connectivity",
        index,
        1,
        move |k, b| {
            for t in &sphere.triangles {
                for &v in t {
                    index.push_index(k * points + v as usize, b);
                }
            }
        },
    ));
    arrays.push(Array::new(
        Section::Cells,
        "offsets",
        index,
        1,
        move |k, b| {
            for t in 1..=per_grain {
                index.push_index(3 * (k * per_grain + t), b);
            }
        },
    ));
    arrays.push(Array::new(
        Section::Cells,
        "types",
        Scalar::UInt8,
        1,
        move |_, b| b.extend(std::iter::repeat_n(TRIANGLE, per_grain)),
    ));
    write_piece(
        out,
        Piece {
            kind: "UnstructuredGrid",
            counts: vec![
                ("NumberOfPoints", surfaces.len() * points),
                ("NumberOfCells", cells),
            ],
            active: vec![(Section::CellData, "Scalars", "grain_id")],
            items: surfaces.len(),
            arrays,
        },
    )
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

    const PERIODIC: Domain = Domain::new([10.0, 10.0, 10.0], Boundary::Periodic);

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
