//! How grains are oriented, and unit quaternions for them.
//!
//! Quaternions are `[w, x, y, z]` (Hamilton, scalar first); semi-axis `k` of a grain
//! lies along column `k` of the rotation matrix, as everywhere in the crate. The
//! grain's first axis (column 0) is its axis of revolution (see
//! [`GrainSpec`](super::GrainSpec)).

use super::fisher::FisherOrientation;
use crate::contact::{ellipse_angle, rotation_column};
use crate::laws::VonMises;
use rand::Rng;
use std::f64::consts::PI;

/// A coordinate axis of the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// The x axis.
    X,
    /// The y axis.
    Y,
    /// The z axis.
    Z,
}

impl Axis {
    /// The axis' index: 0, 1 or 2.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The unit vector along the axis.
    pub fn unit(self) -> [f64; 3] {
        let mut e = [0.0; 3];
        e[self.index()] = 1.0;
        e
    }
}

/// How a phase's grains are oriented.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Orientation {
    /// Uniform on SO(3) (Shoemake 1992).
    Random,
    /// Every grain has this unit quaternion.
    Fixed {
        /// `[w, x, y, z]`, unit norm.
        quaternion: [f64; 4],
    },
    /// Fibres: the first axis of every grain along `axis`, by the shortest rotation from
    /// x to `axis`. A 2D scene's `angle` θ is the axis `(cos θ, sin θ, 0)`, a rotation
    /// about z.
    Aligned {
        /// Unit vector.
        axis: [f64; 3],
    },
    /// The first axis lies in the plane normal to `axis`, at an angle `θ` from the next
    /// coordinate axis in cyclic order (x→y→z→x) toward the one after:
    /// for `axis = z`, first axis `= cos θ x̂ + sin θ ŷ` (kanapy's tilt angle, measured
    /// from x in the x–y plane). The third semi-axis lies along `axis`.
    Tilt {
        /// The normal of the plane of tilt.
        axis: Axis,
        /// The law of `θ` (radians).
        angle: VonMises,
    },
    /// The first axis by von Mises–Fisher about a mean direction, then a spin about it
    /// (`kind = "fisher"`, see [`FisherOrientation`]).
    Fisher(FisherOrientation),
}

impl Orientation {
    /// The kind's name as written in a scene file.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Random => "random",
            Self::Fixed { .. } => "fixed",
            Self::Aligned { .. } => "aligned",
            Self::Tilt { .. } => "tilt",
            Self::Fisher(_) => "fisher",
        }
    }

    /// Draws an orientation: the quaternion, and the tilt angle `θ` (radians) for
    /// [`Orientation::Tilt`]. `None` if the tilt (or spin) angle's rejection sampling
    /// gave up.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> Option<([f64; 4], Option<f64>)> {
        match *self {
            Self::Random => Some((random_quaternion(rng), None)),
            Self::Fixed { quaternion } => Some((quaternion, None)),
            Self::Aligned { axis } => Some((x_to(axis), None)),
            Self::Tilt { axis, angle } => {
                let theta = angle.sample(rng)?;
                Some((tilt_quaternion(axis, theta), Some(theta)))
            }
            Self::Fisher(law) => Some((law.sample(rng)?, None)),
        }
    }
}

impl Orientation {
    /// Draws a 2D grain's angle (radians, of its first semi-axis from x), and the tilt
    /// angle for [`Orientation::Tilt`] (the same angle): uniform on a half turn for
    /// `Random` (an ellipse turned by π is the same ellipse), the angle of the axis in
    /// the x–y plane for `Aligned`, a von Mises draw for `Tilt` (about z, the only
    /// tilt a 2D scene takes). A 2D scene refuses `Fisher`; a `Fixed` quaternion (about
    /// z) gives its angle. `None` if the von Mises rejection sampling gave up.
    pub fn sample_angle<R: Rng + ?Sized>(&self, rng: &mut R) -> Option<(f64, Option<f64>)> {
        match *self {
            Self::Random => Some((PI * (rng.random::<f64>() - 0.5), None)),
            Self::Fixed { quaternion } => Some((ellipse_angle(quaternion), None)),
            Self::Aligned { axis } => Some((axis[1].atan2(axis[0]), None)),
            Self::Tilt { angle, .. } => {
                let theta = angle.sample(rng)?;
                Some((theta, Some(theta)))
            }
            Self::Fisher(law) => {
                let e = rotation_column(law.sample(rng)?, 0);
                Some((e[1].atan2(e[0]), None))
            }
        }
    }
}

/// A uniformly random unit quaternion with `w ≥ 0` (Shoemake, "Uniform random
/// rotations", Graphics Gems III, 1992).
pub(crate) fn random_quaternion<R: Rng + ?Sized>(rng: &mut R) -> [f64; 4] {
    let u1: f64 = rng.random();
    let (a, b) = (
        2.0 * PI * rng.random::<f64>(),
        2.0 * PI * rng.random::<f64>(),
    );
    let (r1, r2) = ((1.0 - u1).sqrt(), u1.sqrt());
    canonical([r2 * b.cos(), r1 * a.sin(), r1 * a.cos(), r2 * b.sin()])
}

/// The rotation of the tilt orientation: `q = rot(axis, θ) ⊗ p`, where `p` takes
/// x, y, z to the next axis, the one after, and `axis` (a cyclic permutation: identity
/// for z, 120° about (1,1,1) for x, −120° for y).
pub(crate) fn tilt_quaternion(axis: Axis, theta: f64) -> [f64; 4] {
    let (s, c) = (0.5 * theta).sin_cos();
    let mut rot = [c, 0.0, 0.0, 0.0];
    rot[1 + axis.index()] = s;
    let perm = match axis {
        Axis::Z => [1.0, 0.0, 0.0, 0.0],
        Axis::X => [0.5, 0.5, 0.5, 0.5],
        Axis::Y => [0.5, -0.5, -0.5, -0.5],
    };
    canonical(multiply(rot, perm))
}

/// The shortest rotation taking x to the unit vector `n`: half-way quaternion
/// `(1 + n_x, x̂ × n)` normalised; a half turn about z when `n = −x`.
pub(crate) fn x_to(n: [f64; 3]) -> [f64; 4] {
    let q = [1.0 + n[0], 0.0, -n[2], n[1]];
    let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm == 0.0 {
        return [0.0, 0.0, 0.0, 1.0];
    }
    q.map(|v| v / norm)
}

/// The Hamilton product `a ⊗ b`.
pub(crate) fn multiply(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// `q` or `−q`, whichever has `w ≥ 0` (the same rotation).
pub(crate) fn canonical(q: [f64; 4]) -> [f64; 4] {
    if q[0] < 0.0 {
        q.map(|v| -v)
    } else {
        q
    }
}

/// The tilt angle `θ` (radians) of a grain oriented by the unit quaternion `q`, for a
/// tilt about `axis`: the angle of its first axis `e` (column 0 of the rotation) in the
/// plane normal to `axis`, from the next coordinate axis `i` in cyclic order toward the
/// one after, `j`: `θ = atan2(e_j, e_i)`. This inverts the scene's tilt orientation
/// (for `axis = z`, `e = (cos θ, sin θ, 0)`).
///
/// The angle is returned in the law's window `[mean − π, mean + π]`, where the law's
/// angles are drawn, by adding the multiple of 2π that brings it nearest the mean.
///
/// ```
/// use grainpack::scene::tilt_angle;
/// use grainpack::laws::VonMises;
/// use grainpack::scene::Axis;
/// let half = 0.3f64; // a rotation by 0.6 rad about z
/// let q = [half.cos(), 0.0, 0.0, half.sin()];
/// let theta = tilt_angle(q, Axis::Z, &VonMises::new(0.0, 1.0));
/// assert!((theta - 0.6).abs() < 1e-15);
/// ```
pub fn tilt_angle(q: [f64; 4], axis: Axis, law: &VonMises) -> f64 {
    tilt_angle_of(rotation_column(q, 0), axis, law)
}

/// [`tilt_angle`] of a first axis `e` given directly (a unit vector).
pub fn tilt_angle_of(e: [f64; 3], axis: Axis, law: &VonMises) -> f64 {
    let (i, j) = ((axis.index() + 1) % 3, (axis.index() + 2) % 3);
    let theta = e[j].atan2(e[i]);
    theta + 2.0 * PI * ((law.mean - theta) / (2.0 * PI)).round()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::FRAC_1_SQRT_2 as H;

    /// Rotation entries are sums of a few products of unit-norm components: 1e-15
    /// allows a few ulps.
    const TOL: f64 = 1e-15;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < TOL)
    }

    #[test]
    fn tilt_puts_the_first_axis_in_the_plane_at_theta_and_the_third_along_the_axis() {
        let theta: f64 = 0.7;
        let (s, c) = theta.sin_cos();
        for (axis, first, second) in [
            (Axis::Z, [c, s, 0.0], [-s, c, 0.0]),
            (Axis::X, [0.0, c, s], [0.0, -s, c]),
            (Axis::Y, [s, 0.0, c], [c, 0.0, -s]),
        ] {
            let q = tilt_quaternion(axis, theta);
            assert!(close(rotation_column(q, 0), first), "{axis:?}");
            assert!(close(rotation_column(q, 1), second), "{axis:?}");
            assert!(close(rotation_column(q, 2), axis.unit()), "{axis:?}");
        }
    }

    #[test]
    fn tilt_about_z_is_kanapys_rotation_about_z() {
        // kanapy: q = (cos θ/2, 0, 0, sin θ/2) for θ in (0, π).
        let q = tilt_quaternion(Axis::Z, 1.2);
        let want = [0.6f64.cos(), 0.0, 0.0, 0.6f64.sin()];
        assert!(q.iter().zip(&want).all(|(a, b)| (a - b).abs() < TOL));
    }

    #[test]
    fn aligned_takes_x_to_the_axis_including_the_opposite_direction() {
        for n in [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.6, 0.0, -0.8],
        ] {
            assert!(close(rotation_column(x_to(n), 0), n), "{n:?}");
        }
        // x to z is a quarter turn about −y.
        let q = x_to([0.0, 0.0, 1.0]);
        assert!((q[0] - H).abs() < TOL && (q[2] + H).abs() < TOL);
    }

    /// The first axis of uniform rotations is uniform on the sphere: each component has
    /// mean 0 and mean square 1/3. With n = 20 000 the standard errors are
    /// √(1/3n) ≈ 0.004 and √(4/45n) ≈ 0.002; 5 standard errors are allowed.
    #[test]
    fn random_quaternions_are_unit_and_uniform() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let n = 20_000;
        let (mut m1, mut m2) = ([0.0; 3], [0.0; 3]);
        for _ in 0..n {
            let q = random_quaternion(&mut rng);
            assert!((q.iter().map(|v| v * v).sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(q[0] >= 0.0);
            let a = rotation_column(q, 0);
            for i in 0..3 {
                m1[i] += a[i] / n as f64;
                m2[i] += a[i] * a[i] / n as f64;
            }
        }
        for i in 0..3 {
            assert!(m1[i].abs() < 5.0 * 0.0041, "{m1:?}");
            assert!((m2[i] - 1.0 / 3.0).abs() < 5.0 * 0.0021, "{m2:?}");
        }
    }

    /// The tilt quaternion of the scene, `rot(axis, θ) ⊗ p`, rebuilt here from the
    /// rotation columns its docs give: θ must come back, in the law's window.
    #[test]
    fn tilt_angle_inverts_the_scene_tilt_for_every_axis() {
        let law = VonMises {
            mean: 0.5 * PI,
            kappa: 1.0,
            min: 0.0,
            max: PI,
        };
        for axis in [Axis::X, Axis::Y, Axis::Z] {
            for theta in [0.0, 0.3, 1.5, 3.0] {
                let q = tilt_quaternion(axis, theta);
                let back = tilt_angle(q, axis, &law);
                // A few roundings in the quaternion and its rotation column.
                assert!((back - theta).abs() < 1e-14, "{axis:?} {theta} {back}");
            }
        }
        // Angles come back in [mean − π, mean + π].
        let q = tilt_quaternion(Axis::Z, -0.25 * PI);
        let back = tilt_angle(q, Axis::Z, &VonMises::new(PI, 1.0));
        assert!((back - 1.75 * PI).abs() < 1e-14, "{back}");
    }

    /// `rot(axis, θ) ⊗ p` with `p` the cyclic permutation taking x, y, z to the next
    /// axis, the one after and `axis` (documented in `docs/config.md`).
    fn tilt_quaternion(axis: Axis, theta: f64) -> [f64; 4] {
        let (s, c) = (0.5 * theta).sin_cos();
        let mut r = [c, 0.0, 0.0, 0.0];
        r[1 + axis.index()] = s;
        let p = match axis {
            Axis::Z => [1.0, 0.0, 0.0, 0.0],
            Axis::X => [0.5, 0.5, 0.5, 0.5],
            Axis::Y => [0.5, -0.5, -0.5, -0.5],
        };
        [
            r[0] * p[0] - r[1] * p[1] - r[2] * p[2] - r[3] * p[3],
            r[0] * p[1] + r[1] * p[0] + r[2] * p[3] - r[3] * p[2],
            r[0] * p[2] - r[1] * p[3] + r[2] * p[0] + r[3] * p[1],
            r[0] * p[3] + r[1] * p[2] - r[2] * p[1] + r[3] * p[0],
        ]
    }
}
