//! Random pairs, rigid motions and the reference data, shared by the unit tests.

use super::{Sym3, Vec3};
use nalgebra::{Matrix3, Rotation3, Vector3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

pub(crate) type RelativePair = (Vec3, Sym3, Sym3);

pub(crate) fn sphere(radius: f64) -> Sym3 {
    let s = radius * radius;
    [s, 0.0, 0.0, s, 0.0, s]
}

pub(crate) fn random_rotation(rng: &mut StdRng) -> Rotation3<f64> {
    Rotation3::from_scaled_axis(Vector3::from_fn(|_, _| rng.random_range(-2.0..2.0)))
}

/// The pair turned by `rot`: `r → R r`, `Q → R Q Rᵀ`.
pub(crate) fn rotate(rot: &Rotation3<f64>, (r, q1, q2): &RelativePair) -> RelativePair {
    let m = rot.matrix();
    let turn = |q: &Sym3| {
        let f = m * Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5]);
        let f = f * m.transpose();
        [
            f[(0, 0)],
            f[(0, 1)],
            f[(0, 2)],
            f[(1, 1)],
            f[(1, 2)],
            f[(2, 2)],
        ]
    };
    ((m * Vector3::from(*r)).into(), turn(q1), turn(q2))
}

/// Random pairs: semi-axes log-uniform in `[0.1, 10]`, random orientations, `r12` of
/// random direction and length in `[0, 25]`, each with `κ = (a_max / a_min)²`, a bound
/// on the condition number of every `(1−λ)Q1 + λQ2`.
pub(crate) fn random_pairs(seed: u64, n: usize) -> Vec<(RelativePair, f64)> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut one = |_| {
        let a: [f64; 6] = std::array::from_fn(|_| 10f64.powf(rng.random_range(-1.0..1.0)));
        let r = [rng.random_range(0.0..25.0), 0.0, 0.0];
        let diag = |a: &[f64]| [a[0] * a[0], 0.0, 0.0, a[1] * a[1], 0.0, a[2] * a[2]];
        let (r, q1, _) = rotate(&random_rotation(&mut rng), &(r, diag(&a[..3]), sphere(1.0)));
        let q2 = rotate(&random_rotation(&mut rng), &(r, diag(&a[3..]), sphere(1.0))).1;
        let (lo, hi) = a
            .iter()
            .fold((f64::MAX, 0.0_f64), |(l, h), &x| (l.min(x), h.max(x)));
        ((r, q1, q2), (hi / lo).powi(2))
    };
    (0..n).map(&mut one).collect()
}

/// A pair of a reference file, in relative form.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ReferencePair {
    /// Line in the file (the header is line 1).
    pub line: u64,
    pub r12: Vec3,
    pub q1: Sym3,
    pub q2: Sym3,
}

/// The rows of a reference file in `tests/data` (written by
/// `tools/make_contact_reference.py`): each pair with its μ² and λ (50 correct digits,
/// rounded to doubles). The contact layer reads them itself, with the csv crate, so that
/// its tests need nothing from `io`.
pub(crate) fn reference_rows(name: &str) -> Vec<(ReferencePair, f64, f64)> {
    let path = format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"));
    let mut reader = csv::Reader::from_path(&path).unwrap();
    let header = reader.headers().unwrap().clone();
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let r = ["r0", "r1", "r2"].map(column);
    let q1 = ["q1_0", "q1_1", "q1_2", "q1_3", "q1_4", "q1_5"].map(column);
    let q2 = ["q2_0", "q2_1", "q2_2", "q2_3", "q2_4", "q2_5"].map(column);
    let (mu2, lambda) = (column("mu2"), column("lambda"));
    reader
        .records()
        .map(|row| {
            let row = row.unwrap();
            let x = |k: usize| -> f64 { row[k].parse().unwrap() };
            let pair = ReferencePair {
                line: row.position().map_or(0, |p| p.line()),
                r12: r.map(x),
                q1: q1.map(x),
                q2: q2.map(x),
            };
            (pair, x(mu2), x(lambda))
        })
        .collect()
}
