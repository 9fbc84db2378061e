//! Unit quaternions `[w, x, y, z]` (Hamilton, scalar first) as rotation matrices: the
//! one place a quaternion becomes a matrix.

use nalgebra::{Matrix3, Quaternion, UnitQuaternion};

/// The rotation matrix of `q`, normalised first (as nalgebra's `UnitQuaternion` does):
/// what an [`Ellipsoid`](super::Ellipsoid) is built with, so that anything else that
/// needs the exact form of a grain (the voxel RVE, its moments) computes the same
/// matrix bit for bit.
pub fn rotation_matrix(q: [f64; 4]) -> Matrix3<f64> {
    let [w, x, y, z] = q;
    UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z))
        .to_rotation_matrix()
        .into_inner()
}

/// Column `k` of the rotation matrix of the unit quaternion `q`, from its entries as they
/// are (`q` is taken to be of unit norm): semi-axis `k` of a grain lies along it. This
/// is what the exports and the statistics read a grain's axes with.
///
/// ```
/// use grainpack::contact::rotation_column;
/// let half = std::f64::consts::FRAC_PI_4; // a quarter turn about z
/// let x = rotation_column([half.cos(), 0.0, 0.0, half.sin()], 0);
/// assert!((x[0]).abs() < 1e-15 && (x[1] - 1.0).abs() < 1e-15);
/// ```
pub fn rotation_column(q: [f64; 4], k: usize) -> [f64; 3] {
    let [w, x, y, z] = q;
    match k {
        0 => [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + w * z),
            2.0 * (x * z - w * y),
        ],
        1 => [
            2.0 * (x * y - w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + w * x),
        ],
        _ => [
            2.0 * (x * z + w * y),
            2.0 * (y * z - w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    }
}
