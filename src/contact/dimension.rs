//! Two or three dimensions: the one place where a grain's dimension changes a formula.
//!
//! A 2D grain (an ellipse in the plane `z = const`) is packed, checked and measured as
//! the 3D grain it is the cross-section of: an ellipsoid whose third semi-axis lies along
//! `z` and whose rotation turns about `z` only. For two such grains with centres in the
//! same plane, `r12` has no `z` component and `Q(λ) = (1−λ)Q1 + λQ2` is block diagonal
//! (the `z` entry never mixes with `x`, `y`), so `r12ᵀ Q(λ)⁻¹ r12` is the 2D quadratic
//! form of the ellipses' own 2×2 blocks: the Perram–Wertheim function of the two
//! ellipsoids *is* the function of the two ellipses, for any positive `z` semi-axes. The
//! narrow phase, the broad phase and the packing loop are therefore written once; 2D
//! differs only in the measure of a grain (area `π a1 a2` instead of volume), the
//! equivalent diameter (of the circle of the same area), the exponent with which a
//! uniform scale changes the fraction (`s²`), and that every turn is about `z`.
//!
//! The third semi-axis of an embedded ellipse is its equivalent-circle radius `√(a1 a2)`
//! ([`ellipse_semi_axes`]): it lies between `a1` and `a2`, so the bounding sphere and the
//! condition number of the 3×3 form are the ellipse's own.

use super::{ellipsoid_volume, equivalent_diameter, sphere_diameter, Sym3, Vec3};
use std::f64::consts::PI;

/// Whether grains are ellipsoids in a box or ellipses in a rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Dimension {
    /// Ellipses in the plane (a box with two lengths).
    Two,
    /// Ellipsoids in space.
    #[default]
    Three,
}

/// The axis every 2D grain turns about, and the normal of the plane they lie in.
pub const PLANE_NORMAL: Vec3 = [0.0, 0.0, 1.0];

impl Dimension {
    /// 2 or 3: the power of a uniform scale `s` in a grain's measure (`s^D`).
    pub fn exponent(self) -> i32 {
        match self {
            Self::Two => 2,
            Self::Three => 3,
        }
    }

    /// The grain's measure: area `π a1 a2` in 2D (the third semi-axis is ignored),
    /// volume `4π/3 a1 a2 a3` in 3D ([`ellipsoid_volume`], bit for bit).
    pub fn measure(self, semi_axes: [f64; 3]) -> f64 {
        match self {
            Self::Two => PI * (semi_axes[0] * semi_axes[1]),
            Self::Three => ellipsoid_volume(semi_axes),
        }
    }

    /// The equivalent diameter: of the circle of the same area `2 √(a1 a2)` in 2D, of the
    /// sphere of the same volume in 3D ([`equivalent_diameter`], bit for bit).
    pub fn equivalent_diameter(self, semi_axes: [f64; 3]) -> f64 {
        match self {
            Self::Two => 2.0 * (semi_axes[0] * semi_axes[1]).sqrt(),
            Self::Three => equivalent_diameter(semi_axes),
        }
    }

    /// The diameter of the circle of area `m` (`√(4m/π)`) or the sphere of volume `m`.
    pub fn diameter_of(self, measure: f64) -> f64 {
        match self {
            Self::Two => (4.0 * measure / PI).sqrt(),
            Self::Three => sphere_diameter(measure),
        }
    }

    /// The measure of the circle or sphere of diameter `d`: `π d²/4` or `π d³/6`.
    pub fn measure_of_diameter(self, d: f64) -> f64 {
        match self {
            Self::Two => PI / 4.0 * d * d,
            Self::Three => PI / 6.0 * d.powi(3),
        }
    }

    /// The length scale `s` that changes a measure by `ratio` (`s^D = ratio`):
    /// `√ratio` or `∛ratio`.
    pub fn length_scale(self, ratio: f64) -> f64 {
        match self {
            Self::Two => ratio.sqrt(),
            Self::Three => ratio.cbrt(),
        }
    }

    /// The densest packing of ellipses or ellipsoids of one shape: `π/√12` (an affine
    /// image of the hexagonal disc packing) or 0.7707 (Donev et al., Science 2004).
    pub fn densest_fraction(self) -> f64 {
        match self {
            Self::Two => PI / 12f64.sqrt(),
            Self::Three => 0.7707,
        }
    }
}

/// The embedded semi-axes `[a1, a2, √(a1 a2)]` of the ellipse with semi-axes `a1`
/// (along the direction at its angle) and `a2`.
pub fn ellipse_semi_axes(a1: f64, a2: f64) -> [f64; 3] {
    [a1, a2, (a1 * a2).sqrt()]
}

/// The orientation of an ellipse whose first semi-axis makes angle `theta` (radians,
/// counter-clockwise from `x`) as a unit quaternion about `z`, `w ≥ 0`.
pub fn ellipse_quaternion(theta: f64) -> [f64; 4] {
    let (sin, cos) = (0.5 * theta).sin_cos();
    if cos < 0.0 {
        [-cos, 0.0, 0.0, -sin]
    } else {
        [cos, 0.0, 0.0, sin]
    }
}

/// The angle in `(−π/2, π/2]` of an ellipse's first semi-axis from `x`, for an
/// orientation `q` about `z` (an ellipse turned by π is the same ellipse).
pub fn ellipse_angle(q: [f64; 4]) -> f64 {
    let theta = 2.0 * q[3].atan2(q[0]);
    // Fold into (−π/2, π/2].
    let folded = theta - PI * (theta / PI).round();
    if folded <= -0.5 * PI {
        folded + PI
    } else {
        folded
    }
}

/// The 3×3 form `[q0, q1, 0, q2, 0, z]` of a 2×2 form `[q0, q1, q2]` (upper triangle,
/// row-major) with `z` on the third diagonal entry.
pub fn embed_form(q: [f64; 3], z: f64) -> Sym3 {
    [q[0], q[1], 0.0, q[2], 0.0, z]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_round_trip_modulo_a_half_turn() {
        for k in -20..=20 {
            let theta = 0.37 * f64::from(k);
            let back = ellipse_angle(ellipse_quaternion(theta));
            let turns = (theta - back) / PI;
            // Rounding of sin_cos and atan2: a few ε of the angle.
            assert!((turns - turns.round()).abs() < 1e-14, "{theta} -> {back}");
            assert!(back > -0.5 * PI && back <= 0.5 * PI);
        }
    }

    #[test]
    fn measures_and_diameters_agree() {
        let axes = ellipse_semi_axes(3.0, 1.0 / 3.0);
        assert_eq!(axes[2], 1.0);
        let d = Dimension::Two.equivalent_diameter(axes);
        assert!((d - 2.0).abs() < 1e-15);
        let area = Dimension::Two.measure(axes);
        assert!((Dimension::Two.diameter_of(area) - d).abs() < 1e-15);
        assert!((Dimension::Two.measure_of_diameter(d) - area).abs() < 1e-15);
        let solid = [2.0, 1.0, 0.5];
        assert_eq!(Dimension::Three.measure(solid), ellipsoid_volume(solid));
    }
}
