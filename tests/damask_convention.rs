//! The crystal orientation convention against DAMASK's own `damask.Rotation`: the rows of
//! tests/data/damask_rotations.csv (tools/make_damask_reference.py) converted both ways.

use grainpack::scene::{euler_to_quaternion, quaternion_to_euler};

/// The brief's agreement with DAMASK, Euler → quaternion and back: 1e-12 (rounding of
/// a few trigonometric evaluations is ~1e-16).
const AGREEMENT: f64 = 1e-12;

fn rows() -> Vec<(String, [f64; 3], [f64; 4])> {
    let text = std::fs::read_to_string("tests/data/damask_rotations.csv").unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("kind"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let v: Vec<f64> = f[1..].iter().map(|x| x.parse().unwrap()).collect();
            (
                f[0].to_owned(),
                [v[0], v[1], v[2]],
                [v[3], v[4], v[5], v[6]],
            )
        })
        .collect()
}

#[test]
fn euler_angles_give_damasks_quaternions() {
    let rows = rows();
    assert_eq!(rows.iter().filter(|r| r.0 == "euler").count(), 500);
    for (_, e, q) in rows.iter().filter(|r| r.0 == "euler") {
        let got = euler_to_quaternion(*e);
        for k in 0..4 {
            assert!(
                (got[k] - q[k]).abs() <= AGREEMENT,
                "{e:?}: {got:?} vs {q:?}"
            );
        }
    }
}

#[test]
fn quaternions_give_damasks_euler_angles() {
    let rows = rows();
    assert_eq!(rows.iter().filter(|r| r.0 == "quaternion").count(), 500);
    for (_, e, q) in rows.iter().filter(|r| r.0 == "quaternion") {
        let got = quaternion_to_euler(*q);
        for k in 0..3 {
            assert!(
                (got[k] - e[k]).abs() <= AGREEMENT,
                "{q:?}: {got:?} vs {e:?}"
            );
        }
    }
}
