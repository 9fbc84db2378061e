//! `centers.vtp`: one point per grain, with its shape as tensors for glyphs.

use super::xml::{write_piece, Array, Piece, Scalar, Section};
use super::{flat_ellipse, grain_id, phase_index, rotation};
use crate::contact::Dimension;
use crate::packing::PackedGrain;
use crate::scene::quaternion_to_euler;
use std::io::{self, Write};

/// `R diag(a₁^p, a₂^p, a₃^p) Rᵀ` in row-major order, for column `k` of R along
/// semi-axis `k`: `p = 1` gives the shape tensor, `p = 2` the quadratic form.
fn tensor(grain: &PackedGrain, power: i32) -> [f64; 9] {
    let r = rotation(grain.quaternion);
    let d = grain.semi_axes.map(|a| a.powi(power));
    let mut t = [0.0; 9];
    for i in 0..3 {
        for j in i..3 {
            // Mirrored, so that the tensor is exactly symmetric.
            t[3 * i + j] = (0..3).map(|k| d[k] * r[k][i] * r[k][j]).sum();
            t[3 * j + i] = t[3 * i + j];
        }
    }
    t
}

/// The shape tensor `S = R diag(a₁, a₂, a₃) Rᵀ`, row-major: its eigenvalues are the
/// semi-axes and its eigenvectors their directions, so a unit sphere mapped by `S` is
/// the grain (centred at the origin). This is what ParaView's Tensor Glyph draws.
pub fn shape_tensor(grain: &PackedGrain) -> [f64; 9] {
    tensor(grain, 1)
}

/// The quadratic form `Q = R diag(a₁², a₂², a₃²) Rᵀ = S²`, row-major: the grain is
/// `{x : (x − c)ᵀ Q⁻¹ (x − c) ≤ 1}`, as in the contact layer.
pub fn quadratic_form(grain: &PackedGrain) -> [f64; 9] {
    tensor(grain, 2)
}

/// Writes `centers.vtp` (VTK XML PolyData, arrays zlib-compressed in raw appended
/// data, float64, `io/vtk/xml.rs`): one point per grain at its centre, each a vertex
/// cell, with point data `grain_id`, `phase` (`Int32`), `semi_axes` (3 components),
/// `shape_tensor` ([`shape_tensor`], 9 components, the active tensors) and
/// `quadratic_form` ([`quadratic_form`], 9 components); with `crystals` (`crystals[i]`
/// the crystal orientation of `grains[i]`), also `crystal_quaternion` (4 components,
/// scalar first) and `euler_angles` (Bunge, degrees).
///
/// In 2D (`dimension`), each ellipse lies in the plane z = 0 with its third semi-axis 0
/// (the embedded grain flattened): the points are `(x, y, 0)`, `semi_axes` `(a1, a2, 0)`, and the
/// tensors have a zero z row and column (a Tensor Glyph draws the flat ellipse).
pub fn write_centers_vtp(
    out: &mut dyn Write,
    grains: &[PackedGrain],
    crystals: Option<&[[f64; 4]]>,
    dimension: Dimension,
) -> io::Result<()> {
    let flat: Vec<PackedGrain>;
    let grains = match dimension {
        Dimension::Two => {
            flat = grains.iter().map(flat_ellipse).collect();
            &flat[..]
        }
        Dimension::Three => grains,
    };
    let n = grains.len();
    for g in grains {
        grain_id(g)?;
        phase_index(g)?;
    }
    let point = |name, components, value: fn(&PackedGrain) -> Vec<f64>| {
        Array::new(
            Section::PointData,
            name,
            Scalar::Float64,
            components,
            move |i, b| b.extend(value(&grains[i]).iter().flat_map(|x| x.to_le_bytes())),
        )
    };
    let int = |name, value: fn(&PackedGrain) -> io::Result<i32>| {
        Array::new(Section::PointData, name, Scalar::Int32, 1, move |i, b| {
            b.extend(value(&grains[i]).unwrap_or_default().to_le_bytes())
        })
    };
    let mut arrays = vec![
        int("grain_id", grain_id),
        int("phase", phase_index),
        point("semi_axes", 3, |g| g.semi_axes.to_vec()),
        point("shape_tensor", 9, |g| shape_tensor(g).to_vec()),
        point("quadratic_form", 9, |g| quadratic_form(g).to_vec()),
    ];
    if let Some(c) = crystals {
        let q = move |i: usize| c.get(i).copied().unwrap_or([1.0, 0.0, 0.0, 0.0]);
        let values = move |i: usize, euler: bool| -> Vec<f64> {
            if euler {
                quaternion_to_euler(q(i)).map(f64::to_degrees).to_vec()
            } else {
                q(i).to_vec()
            }
        };
        for (name, components, euler) in
            [("crystal_quaternion", 4, false), ("euler_angles", 3, true)]
        {
            arrays.push(Array::new(
                Section::PointData,
                name,
                Scalar::Float64,
                components,
                move |i, b| b.extend(values(i, euler).iter().flat_map(|x| x.to_le_bytes())),
            ));
        }
    }
    let index = Scalar::index(n);
    arrays.push(point_array_centres(grains));
    arrays.push(Array::new(
        Section::Verts,
        "connectivity",
        index,
        1,
        move |i, b| index.push_index(i, b),
    ));
    arrays.push(Array::new(
        Section::Verts,
        "offsets",
        index,
        1,
        move |i, b| index.push_index(i + 1, b),
    ));
    let counts = ["NumberOfLines", "NumberOfStrips", "NumberOfPolys"].map(|k| (k, 0));
    write_piece(
        out,
        Piece {
            kind: "PolyData",
            counts: [("NumberOfPoints", n), ("NumberOfVerts", n)]
                .into_iter()
                .chain(counts)
                .collect(),
            active: vec![
                (Section::PointData, "Scalars", "grain_id"),
                (Section::PointData, "Tensors", "shape_tensor"),
            ],
            items: n,
            arrays,
        },
    )
}

/// The grains' centres as the points.
fn point_array_centres(grains: &[PackedGrain]) -> Array<'_> {
    Array::new(
        Section::Points,
        "Points",
        Scalar::Float64,
        3,
        move |i, b| b.extend(grains[i].centre.iter().flat_map(|x| x.to_le_bytes())),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sums of three products of numbers of size ≤ 4: a few ulp of 16.
    const TOL: f64 = 64.0 * f64::EPSILON;

    #[test]
    fn the_shape_tensor_maps_each_axis_to_its_semi_axis_and_squares_to_q() {
        let q = [0.8f64, 0.1, 0.4, -0.3];
        let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        let g = PackedGrain {
            id: 3,
            phase: 1,
            centre: [1.0, 2.0, 3.0],
            semi_axes: [4.0, 2.0, 0.5],
            quaternion: q.map(|x| x / norm),
        };
        let s = shape_tensor(&g);
        let q = quadratic_form(&g);
        let r = rotation(g.quaternion);
        for (axis, a) in r.iter().zip(g.semi_axes) {
            // S r_k = a_k r_k: the semi-axes are the eigenvalues.
            for i in 0..3 {
                let sr: f64 = (0..3).map(|j| s[3 * i + j] * axis[j]).sum();
                assert!((sr - a * axis[i]).abs() < TOL, "axis {axis:?}");
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                assert_eq!(s[3 * i + j], s[3 * j + i], "symmetric");
                let ss: f64 = (0..3).map(|m| s[3 * i + m] * s[3 * m + j]).sum();
                assert!((ss - q[3 * i + j]).abs() < TOL, "S² = Q at ({i}, {j})");
            }
        }
    }
}
