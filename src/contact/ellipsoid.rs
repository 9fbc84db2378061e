//! Ellipsoids as quadratic forms, with validating constructors.

use super::rotation_matrix;
use super::{Sym3, Vec3};
use nalgebra::{Matrix3, Quaternion, SymmetricEigen, Vector3};
use std::f64::consts::PI;
use thiserror::Error;

/// How far from 1 the norm of a quaternion may be before it is rejected rather than
/// normalised: `|‖q‖ − 1| ≤ 1e-6` absorbs the rounding of quaternions printed with 7 or
/// more digits, while a quaternion of norm 2 or 0.5 (swapped or missing components) is
/// an input error.
pub const QUATERNION_NORM_TOL: f64 = 1e-6;

/// Why an ellipsoid could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ShapeError {
    /// A value is NaN or infinite.
    #[error("{what} is not finite: {value}")]
    NotFinite {
        /// The offending parameter.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A semi-axis (or radius) is zero or negative.
    #[error("semi-axis {index} must be positive, got {value}")]
    NonPositiveSemiAxis {
        /// Index 0–2 of the semi-axis.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The axis of a spheroid is the zero vector.
    #[error("the spheroid axis is the zero vector")]
    ZeroAxis,
    /// The quaternion is not of unit norm (within [`QUATERNION_NORM_TOL`]).
    #[error("quaternion must have unit norm, got norm {norm}")]
    NotUnitQuaternion {
        /// Its norm.
        norm: f64,
    },
    /// The quadratic form is not symmetric positive definite.
    #[error("quadratic form is not positive definite: pivot {pivot} of its LDLᵀ factorisation is {value}")]
    NotPositiveDefinite {
        /// Index 0–2 of the failing pivot.
        pivot: usize,
        /// Its value.
        value: f64,
    },
}

/// An ellipsoid centred at the origin: `{m : mᵀ Q⁻¹ m ≤ 1}`.
///
/// `q` is the upper triangle of `Q = R diag(a1², a2², a3²) Rᵀ`, row-major
/// (`q0 q1 q2 / q3 q4 / q5`, as in the pw85 library), where semi-axis `k` lies along
/// column `k` of the rotation `R`. Build it with a validating constructor; the centre is
/// the caller's, since contact queries take the pair in relative form.
///
/// ```
/// use grainpack::contact::Ellipsoid;
/// let e = Ellipsoid::spheroid(10.0, 0.1, [0.0, 0.0, 1.0]).unwrap();
/// assert_eq!(e.q, [100.0, 0.0, 0.0, 100.0, 0.0, 0.1 * 0.1]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    /// The quadratic form `Q`, upper triangle row-major.
    pub q: Sym3,
}

impl Ellipsoid {
    /// A sphere: `Q = r² I`.
    pub fn sphere(radius: f64) -> Result<Self, ShapeError> {
        check_semi_axis(0, radius)?;
        let r2 = radius * radius;
        Ok(Self {
            q: [r2, 0.0, 0.0, r2, 0.0, r2],
        })
    }

    /// A spheroid of revolution: `Q = a² (I − n nᵀ) + c² n nᵀ` with equatorial radius `a`,
    /// polar radius `c` and axis of revolution `n`.
    ///
    /// `axis` may have any non-zero length: it is normalised, since a direction has no
    /// length that could be wrong.
    pub fn spheroid(equatorial: f64, polar: f64, axis: Vec3) -> Result<Self, ShapeError> {
        check_semi_axis(0, equatorial)?;
        check_semi_axis(2, polar)?;
        for value in axis {
            check_finite("axis", value)?;
        }
        let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        if norm == 0.0 {
            return Err(ShapeError::ZeroAxis);
        }
        let n = axis.map(|x| x / norm);
        // Written as a² (I − nnᵀ) + c² nnᵀ rather than a² I + (c² − a²) nnᵀ: the latter
        // cancels catastrophically along the axis of a flat spheroid (pw85's `spheroid`
        // turns c = 0.1, a = 10 into Q_zz = 0.010000000000005116).
        let (a2, c2) = (equatorial * equatorial, polar * polar);
        let entry = |i: usize, j: usize| {
            let nn = n[i] * n[j];
            let delta = if i == j { 1.0 } else { 0.0 };
            a2 * (delta - nn) + c2 * nn
        };
        let q = [
            entry(0, 0),
            entry(0, 1),
            entry(0, 2),
            entry(1, 1),
            entry(1, 2),
            entry(2, 2),
        ];
        Self::from_quadratic_form(q)
    }

    /// A general ellipsoid from its semi-axes and orientation.
    ///
    /// `quaternion = [w, x, y, z]` (Hamilton convention, scalar first) gives the rotation
    /// `R`; semi-axis `k` lies along column `k` of `R`. The quaternion must have unit
    /// norm within [`QUATERNION_NORM_TOL`]; it is then normalised exactly.
    pub fn new(semi_axes: [f64; 3], quaternion: [f64; 4]) -> Result<Self, ShapeError> {
        for (index, &a) in semi_axes.iter().enumerate() {
            check_semi_axis(index, a)?;
        }
        for value in quaternion {
            check_finite("quaternion", value)?;
        }
        let [w, x, y, z] = quaternion;
        let norm = Quaternion::new(w, x, y, z).norm();
        if (norm - 1.0).abs() > QUATERNION_NORM_TOL {
            return Err(ShapeError::NotUnitQuaternion { norm });
        }
        let rot = rotation_matrix(quaternion);
        let diag = Matrix3::from_diagonal(&Vector3::from(semi_axes.map(|a| a * a)));
        let m = rot * diag * rot.transpose();
        Self::from_quadratic_form([
            m[(0, 0)],
            m[(0, 1)],
            m[(0, 2)],
            m[(1, 1)],
            m[(1, 2)],
            m[(2, 2)],
        ])
    }

    /// An ellipsoid from its quadratic form, checked finite and positive definite.
    pub fn from_quadratic_form(q: Sym3) -> Result<Self, ShapeError> {
        for value in q {
            check_finite("quadratic form", value)?;
        }
        match super::ldl::Ldl::factor(&q) {
            Ok(_) => Ok(Self { q }),
            Err((pivot, value)) => Err(ShapeError::NotPositiveDefinite { pivot, value }),
        }
    }

    /// The semi-axes in ascending order (square roots of the eigenvalues of `Q`).
    pub fn semi_axes(&self) -> [f64; 3] {
        let eigen = SymmetricEigen::new(self.matrix());
        let mut a = [0.0; 3];
        for (k, &v) in eigen.eigenvalues.iter().enumerate() {
            a[k] = v.max(0.0).sqrt();
        }
        a.sort_by(f64::total_cmp);
        a
    }

    /// Radius of the smallest sphere about the centre that contains the ellipsoid: the
    /// largest semi-axis.
    pub fn bounding_radius(&self) -> f64 {
        self.semi_axes()[2]
    }

    /// Radius of the largest sphere about the centre inside the ellipsoid: the smallest
    /// semi-axis.
    pub fn inscribed_radius(&self) -> f64 {
        self.semi_axes()[0]
    }

    /// Volume `4/3 π a1 a2 a3 = 4/3 π √det Q`.
    pub fn volume(&self) -> f64 {
        4.0 / 3.0 * PI * self.matrix().determinant().sqrt()
    }

    /// `Q` as a full 3×3 matrix.
    pub fn matrix(&self) -> Matrix3<f64> {
        let q = self.q;
        Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5])
    }
}

/// Volume `4/3 π a1 a2 a3` of the ellipsoid with these semi-axes, computed in this
/// order everywhere a grain's volume is needed, so that sums agree bit for bit.
///
/// ```
/// use grainpack::contact::ellipsoid_volume;
/// assert_eq!(ellipsoid_volume([1.0, 1.0, 1.0]), 4.0 / 3.0 * std::f64::consts::PI);
/// ```
pub fn ellipsoid_volume(semi_axes: [f64; 3]) -> f64 {
    4.0 / 3.0 * PI * semi_axes.iter().product::<f64>()
}

/// The equivalent-sphere diameter `2 (a1 a2 a3)^{1/3}` of an ellipsoid with these
/// semi-axes: the diameter of the sphere of the same volume.
///
/// ```
/// use grainpack::contact::equivalent_diameter;
/// assert!((equivalent_diameter([4.0, 2.0, 1.0]) - 4.0).abs() < 1e-15);
/// ```
pub fn equivalent_diameter(semi_axes: [f64; 3]) -> f64 {
    2.0 * semi_axes.iter().product::<f64>().cbrt()
}

/// `(6 V / π)^⅓`: the diameter of the sphere of volume `V` (a voxel set's equivalent
/// diameter, for instance).
///
/// ```
/// use grainpack::contact::sphere_diameter;
/// assert!((sphere_diameter(std::f64::consts::PI / 6.0) - 1.0).abs() < 1e-15);
/// ```
pub fn sphere_diameter(volume: f64) -> f64 {
    (6.0 * volume / PI).cbrt()
}

fn check_finite(what: &'static str, value: f64) -> Result<(), ShapeError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(ShapeError::NotFinite { what, value })
    }
}

fn check_semi_axis(index: usize, value: f64) -> Result<(), ShapeError> {
    check_finite("semi-axis", value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(ShapeError::NonPositiveSemiAxis { index, value })
    }
}
