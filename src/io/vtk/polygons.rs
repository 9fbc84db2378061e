//! `grains.vtu` of a 2D scene: every ellipse as one polygon in the plane z = 0, with
//! its figures as cell data.

use super::surfaces::{f64s, placements, Placed};
use super::xml::{write_piece, Array, Piece, Scalar, Section};
use super::{grain_id, phase_index, rotation};
use crate::contact::{ellipse_angle, Dimension};
use crate::packing::PackedGrain;
use crate::scene::{aspect_ratio, quaternion_to_euler, Domain, VtkSpec};
use std::f64::consts::TAU;
use std::io::{self, Write};

/// VTK's cell type of a polygon (`VTK_POLYGON`).
const POLYGON: u8 = 7;

/// Appends the `n` vertices of `grain`'s outline shifted by `shift`, counter-clockwise
/// (the polygon's normal is +z): vertex `k` is `c + R diag(a1, a2) (cos t, sin t)`,
/// `t = 2πk/n`, on the ellipse to single precision, at z = 0.
fn push_vertices(n: usize, grain: &PackedGrain, shift: [f64; 3], bytes: &mut Vec<u8>) {
    let r = rotation(grain.quaternion);
    let [a1, a2, _] = grain.semi_axes;
    for k in 0..n {
        let (sin, cos) = (TAU * k as f64 / n as f64).sin_cos();
        for i in 0..2 {
            let local = a1 * cos * r[0][i] + a2 * sin * r[1][i];
            bytes.extend(((grain.centre[i] + shift[i] + local) as f32).to_le_bytes());
        }
        bytes.extend(0f32.to_le_bytes());
    }
}

/// A cell array of one value per polygon: `value(outline)`'s little-endian bytes.
fn cell<'a>(
    outlines: &'a [Placed],
    name: &'static str,
    scalar: Scalar,
    components: usize,
    value: impl Fn(&Placed) -> Vec<u8> + 'a,
) -> Array<'a> {
    Array::new(Section::CellData, name, scalar, components, move |k, b| {
        b.extend(value(&outlines[k]))
    })
}

/// Writes `grains.vtu` of a 2D scene: see [`write_grains_vtu`](super::write_grains_vtu).
pub(super) fn write_ellipses_vtu(
    out: &mut dyn Write,
    grains: &[PackedGrain],
    domain: &Domain,
    spec: &VtkSpec,
    crystals: Option<&[[f64; 4]]>,
) -> io::Result<()> {
    let vertices = spec.polygon_vertices();
    let outlines = placements(grains, domain, spec.periodic_images)?;
    let cells = outlines.len();
    let index = Scalar::index(cells * vertices);
    let o = &outlines;
    let grain = move |s: &Placed| &grains[s.grain];
    let float = |name, value: fn(&PackedGrain) -> f64| {
        cell(o, name, Scalar::Float64, 1, move |s| {
            value(grain(s)).to_le_bytes().to_vec()
        })
    };
    let mut arrays = vec![
        cell(o, "grain_id", Scalar::Int32, 1, move |s| {
            grain_id(grain(s))
                .unwrap_or_default()
                .to_le_bytes()
                .to_vec()
        }),
        cell(o, "phase", Scalar::Int32, 1, move |s| {
            phase_index(grain(s))
                .unwrap_or_default()
                .to_le_bytes()
                .to_vec()
        }),
        float("area", |g| Dimension::Two.measure(g.semi_axes)),
        float("equivalent_diameter", |g| {
            Dimension::Two.equivalent_diameter(g.semi_axes)
        }),
        float("aspect_ratio", |g| aspect_ratio(g.semi_axes)),
        float("angle", |g| ellipse_angle(g.quaternion).to_degrees()),
        cell(o, "periodic_image", Scalar::UInt8, 1, |s| {
            vec![u8::from(s.copy)]
        }),
    ];
    if let Some(c) = crystals {
        let q = move |s: &Placed| c.get(s.grain).copied().unwrap_or([1.0, 0.0, 0.0, 0.0]);
        arrays.push(cell(
            o,
            "crystal_quaternion",
            Scalar::Float64,
            4,
            move |s| f64s::<4, 32>(q(s)).to_vec(),
        ));
        arrays.push(cell(o, "euler_angles", Scalar::Float64, 3, move |s| {
            f64s::<3, 24>(quaternion_to_euler(q(s)).map(f64::to_degrees)).to_vec()
        }));
    }
    arrays.push(Array::new(
        Section::Points,
        "Points",
        Scalar::Float32,
        3,
        move |k, b| push_vertices(vertices, grain(&o[k]), o[k].shift, b),
    ));
    arrays.push(Array::new(
        Section::Cells,
        "connectivity",
        index,
        1,
        move |k, b| (k * vertices..(k + 1) * vertices).for_each(|v| index.push_index(v, b)),
    ));
    arrays.push(Array::new(
        Section::Cells,
        "offsets",
        index,
        1,
        move |k, b| index.push_index((k + 1) * vertices, b),
    ));
    arrays.push(Array::new(
        Section::Cells,
        "types",
        Scalar::UInt8,
        1,
        |_, b| b.push(POLYGON),
    ));
    write_piece(
        out,
        Piece {
            kind: "UnstructuredGrid",
            counts: vec![
                ("NumberOfPoints", cells * vertices),
                ("NumberOfCells", cells),
            ],
            active: vec![(Section::CellData, "Scalars", "grain_id")],
            items: cells,
            arrays,
        },
    )
}
