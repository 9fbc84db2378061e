//! Crystal orientations: the convention, Bunge Euler angles, and the textures a phase's
//! grains are drawn from (`[phase.texture]`).
//!
//! # Convention (one for the whole crate, DAMASK's)
//! A crystal orientation is a unit quaternion `q = [q0, q1, q2, q3]`, scalar first,
//! `q0 ≥ 0`. Its rotation matrix `R(q)` (Hamilton product, the same matrix as a
//! grain's shape quaternion) has the crystal's axes `[100]`, `[010]`, `[001]` as its
//! columns, written in the sample frame (the box's x, y, z): `R` is *active*, taking
//! crystal coordinates to sample coordinates. Its transpose `Rᵀ` takes sample
//! coordinates to crystal coordinates: that passive matrix is DAMASK's orientation
//! matrix, and `q` is DAMASK's quaternion (its convention `P = −1`), so the four
//! numbers are written unchanged as DAMASK's `O`.
//!
//! Bunge Euler angles `(φ1, Φ, φ2)` (ZXZ) give `Rᵀ = Z(φ2) X(Φ) Z(φ1)`, with `Z(α)`,
//! `X(α)` the passive rotations about z and x: the sample frame turned by φ1 about z,
//! then by Φ about the new x, then by φ2 about the new z, is the crystal frame. Angles
//! are written in degrees, `φ1, φ2 ∈ [0, 360)`, `Φ ∈ [0, 180]`. The test
//! `tools/check_orientations.py` compares both conversions with `damask.Rotation`.

use super::fisher::{fisher_direction, perpendicular};
use super::orientation::{canonical, multiply};
use crate::laws::Fisher;
use rand::distr::weighted::WeightedIndex;
use rand::distr::Distribution as _;
use rand::Rng;
use std::f64::consts::PI;
use std::path::PathBuf;

/// The quaternion of Bunge Euler angles `[φ1, Φ, φ2]` in radians.
///
/// ```
/// use grainpack::scene::euler_to_quaternion;
/// // φ1 = 90° alone: the crystal's [100] lies along the sample's y.
/// let q = euler_to_quaternion([std::f64::consts::FRAC_PI_2, 0.0, 0.0]);
/// assert!((q[0] - 0.5f64.sqrt()).abs() < 1e-15 && (q[3] - 0.5f64.sqrt()).abs() < 1e-15);
/// ```
pub fn euler_to_quaternion(euler: [f64; 3]) -> [f64; 4] {
    let [p1, p, p2] = euler.map(|a| 0.5 * a);
    let (s, c) = p.sin_cos();
    let (sum, diff) = (p1 + p2, p1 - p2);
    canonical([c * sum.cos(), s * diff.cos(), s * diff.sin(), c * sum.sin()])
}

/// Bunge Euler angles `[φ1, Φ, φ2]` in radians (`φ1, φ2 ∈ [0, 2π)`, `Φ ∈ [0, π]`) of a
/// unit quaternion. At `Φ = 0` (or `π`) only `φ1 + φ2` (or `φ1 − φ2`) is defined;
/// `φ2 = 0` is returned there.
pub fn quaternion_to_euler(q: [f64; 4]) -> [f64; 3] {
    let [q0, q1, q2, q3] = canonical(q);
    // With σ = (φ1 + φ2)/2 and δ = (φ1 − φ2)/2: q0 + i q3 = cos(Φ/2) e^{iσ} and
    // q1 + i q2 = sin(Φ/2) e^{iδ}.
    let (chi, eta) = ((q0 * q0 + q3 * q3).sqrt(), (q1 * q1 + q2 * q2).sqrt());
    let big_phi = 2.0 * eta.atan2(chi);
    let (p1, p2) = if eta == 0.0 {
        (2.0 * q3.atan2(q0), 0.0)
    } else if chi == 0.0 {
        (2.0 * q2.atan2(q1), 0.0)
    } else {
        let (sigma, delta) = (q3.atan2(q0), q2.atan2(q1));
        (sigma + delta, sigma - delta)
    };
    let wrap = |a: f64| {
        let w = a.rem_euclid(2.0 * PI);
        if w >= 2.0 * PI {
            0.0
        } else {
            w
        }
    };
    [wrap(p1), big_phi, wrap(p2)]
}

/// A phase's texture (`[phase.texture]`): the law of its grains' crystal orientations.
#[derive(Debug, Clone, PartialEq)]
pub enum Texture {
    /// Uniform on SO(3) (`kind = "random"`, the default).
    Random,
    /// Every grain has this orientation (`kind = "fixed"`).
    Fixed {
        /// Unit quaternion, `q0 ≥ 0`.
        quaternion: [f64; 4],
    },
    /// A fibre (`kind = "fibre"`): the crystal direction `crystal` lies along a
    /// direction drawn from the von Mises–Fisher law about `sample` with concentration
    /// `kappa` (density ∝ `exp(κ cos θ)` on the sphere, θ the angle to `sample`), and
    /// the crystal is turned about that direction uniformly.
    Fibre {
        /// Unit crystal direction, in the crystal's Cartesian frame.
        crystal: [f64; 3],
        /// Unit sample direction.
        sample: [f64; 3],
        /// Concentration κ ≥ 0 (0: the direction is uniform on the sphere).
        kappa: f64,
    },
    /// Orientations from a file (`kind = "file"`), drawn with replacement, each with
    /// probability proportional to its weight.
    File {
        /// The file, as resolved from the scene's directory.
        path: PathBuf,
        /// Unit quaternions, `q0 ≥ 0`, one per row.
        orientations: Vec<[f64; 4]>,
        /// Positive weights, one per row (all 1 without a weight column).
        weights: Vec<f64>,
    },
}

impl Texture {
    /// The kind's name as written in a scene file.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Random => "random",
            Self::Fixed { .. } => "fixed",
            Self::Fibre { .. } => "fibre",
            Self::File { .. } => "file",
        }
    }

    /// Draws one orientation.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> [f64; 4] {
        match self {
            Self::Random => super::orientation::random_quaternion(rng),
            Self::Fixed { quaternion } => *quaternion,
            Self::Fibre {
                crystal,
                sample,
                kappa,
            } => {
                let d = fisher_direction(*sample, &Fisher { kappa: *kappa }, rng);
                let turn = axis_angle(d, 2.0 * PI * rng.random::<f64>());
                canonical(multiply(turn, shortest(*crystal, d)))
            }
            Self::File {
                orientations,
                weights,
                ..
            } => {
                // Validation guarantees at least one row and positive finite weights.
                match WeightedIndex::new(weights) {
                    Ok(w) => orientations[w.sample(rng)],
                    Err(_) => orientations[0],
                }
            }
        }
    }
}

/// A phase's crystal orientations: the texture, and whether it is relative to the
/// grain's shape.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseTexture {
    /// The law of the orientations.
    pub texture: Texture,
    /// `relative_to_shape = true`: an orientation drawn from `texture` is the crystal's
    /// orientation in the grain's own frame (its semi-axes as x, y, z), and the
    /// grain's orientation in the sample is its shape rotation (as packed) composed
    /// with it, `q = q_shape ⊗ q_drawn`, so that crystallographic and morphological
    /// texture stay together. Default false: drawn in the sample frame.
    pub relative_to_shape: bool,
}

impl Default for PhaseTexture {
    fn default() -> Self {
        Self {
            texture: Texture::Random,
            relative_to_shape: false,
        }
    }
}

impl PhaseTexture {
    /// A grain's crystal orientation in the sample frame: `drawn` (its
    /// [`GrainSpec::crystal`](super::GrainSpec::crystal)), composed with the grain's
    /// shape quaternion `shape` when the texture is relative to the shape.
    pub fn in_sample(&self, drawn: [f64; 4], shape: [f64; 4]) -> [f64; 4] {
        if self.relative_to_shape {
            canonical(multiply(shape, drawn))
        } else {
            drawn
        }
    }
}

/// The angle (radians, in `[0, π]`) of a rotation `q` about its axis: `2 acos|q0|`.
pub fn rotation_angle(q: [f64; 4]) -> f64 {
    let v = (q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    2.0 * v.atan2(q[0].abs())
}

/// The CDF of the rotation angle ω of a uniformly random rotation: `(ω − sin ω)/π`.
pub fn random_angle_cdf(omega: f64) -> f64 {
    ((omega - omega.sin()) / PI).clamp(0.0, 1.0)
}

/// The angle (radians) between the sample direction of a fibre and its crystal
/// direction `crystal` turned by `q`.
pub fn fibre_angle(q: [f64; 4], crystal: [f64; 3], sample: [f64; 3]) -> f64 {
    let d = rotate(q, crystal);
    let dot = d.iter().zip(&sample).map(|(a, b)| a * b).sum::<f64>();
    let cross = norm(cross(d, sample));
    cross.atan2(dot)
}

/// `R(q) v`.
pub fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let p = multiply(multiply(q, [0.0, v[0], v[1], v[2]]), conjugate(q));
    [p[1], p[2], p[3]]
}

fn conjugate(q: [f64; 4]) -> [f64; 4] {
    [q[0], -q[1], -q[2], -q[3]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(v: [f64; 3]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The rotation by `angle` about the unit axis `n`.
fn axis_angle(n: [f64; 3], angle: f64) -> [f64; 4] {
    let (s, c) = (0.5 * angle).sin_cos();
    [c, s * n[0], s * n[1], s * n[2]]
}

/// The shortest rotation taking the unit vector `a` to the unit vector `b`; a half
/// turn about an axis normal to `a` when `b = −a`.
fn shortest(a: [f64; 3], b: [f64; 3]) -> [f64; 4] {
    let dot: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
    let c = cross(a, b);
    let q = [1.0 + dot, c[0], c[1], c[2]];
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    // 1 + a·b loses all digits only within ~1e-8 rad of antiparallel; the half turn
    // is exact there.
    if n < 1e-8 {
        let e1 = perpendicular(a);
        return [0.0, e1[0], e1[1], e1[2]];
    }
    q.map(|v| v / n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::rotation_matrix;
    use crate::laws::ks_distance;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// Rounding of a few trigonometric evaluations and products of order 1.
    const ROUNDING: f64 = 1e-14;

    /// KS distance below which a sample of [`DRAWS`] follows its law: the 0.1 %
    /// critical value 1.95/√n.
    const DRAWS: usize = 20_000;
    fn ks_critical() -> f64 {
        1.95 / (DRAWS as f64).sqrt()
    }

    fn passive(axis: usize, a: f64) -> nalgebra::Matrix3<f64> {
        let (s, c) = a.sin_cos();
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut m = nalgebra::Matrix3::identity();
        m[(i, i)] = c;
        m[(j, j)] = c;
        m[(i, j)] = s;
        m[(j, i)] = -s;
        m
    }

    #[test]
    fn euler_angles_are_bunge_zxz_passive_and_round_trip() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..1000 {
            let e = [
                2.0 * PI * rng.random::<f64>(),
                PI * rng.random::<f64>(),
                2.0 * PI * rng.random::<f64>(),
            ];
            let q = euler_to_quaternion(e);
            assert!(q[0] >= 0.0);
            let want = passive(2, e[2]) * passive(0, e[1]) * passive(2, e[0]);
            let got = rotation_matrix(q).transpose();
            assert!((want - got).abs().max() < ROUNDING, "{e:?}");
            let back = quaternion_to_euler(q);
            for k in 0..3 {
                assert!((back[k] - e[k]).abs() < 1e-12, "{e:?} -> {back:?}");
            }
        }
        // Φ = 0: only φ1 + φ2 is defined, returned as φ1.
        let q = euler_to_quaternion([0.3, 0.0, 0.4]);
        let e = quaternion_to_euler(q);
        assert!((e[0] - 0.7).abs() < ROUNDING && e[1] == 0.0 && e[2] == 0.0);
    }

    #[test]
    fn random_rotation_angles_follow_their_so3_law() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let angles: Vec<f64> = (0..DRAWS)
            .map(|_| rotation_angle(Texture::Random.sample(&mut rng)))
            .collect();
        assert!(ks_distance(&angles, random_angle_cdf).unwrap() < ks_critical());
    }

    #[test]
    fn fibres_put_the_crystal_direction_at_the_von_mises_fisher_angle() {
        let crystal = [1.0, 1.0, 1.0].map(|v: f64| v / 3f64.sqrt());
        let sample = [0.0, 0.6, 0.8];
        for kappa in [0.0, 2.0, 50.0, 1e4] {
            let texture = Texture::Fibre {
                crystal,
                sample,
                kappa,
            };
            let mut rng = ChaCha8Rng::seed_from_u64(7);
            let angles: Vec<f64> = (0..DRAWS)
                .map(|_| fibre_angle(texture.sample(&mut rng), crystal, sample))
                .collect();
            let d = ks_distance(&angles, |t| Fisher { kappa }.angle_cdf(t)).unwrap();
            assert!(d < ks_critical(), "kappa {kappa}: KS {d}");
        }
    }

    #[test]
    fn fibres_turn_uniformly_about_the_fibre() {
        // With κ huge the direction is the sample's; the angle of the crystal's x
        // about it is then uniform in [0, 2π).
        let texture = Texture::Fibre {
            crystal: [0.0, 0.0, 1.0],
            sample: [0.0, 0.0, 1.0],
            kappa: 1e12,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let turns: Vec<f64> = (0..DRAWS)
            .map(|_| {
                let x = rotate(texture.sample(&mut rng), [1.0, 0.0, 0.0]);
                x[1].atan2(x[0]).rem_euclid(2.0 * PI)
            })
            .collect();
        let d = ks_distance(&turns, |t| (t / (2.0 * PI)).clamp(0.0, 1.0)).unwrap();
        assert!(d < ks_critical(), "KS {d}");
    }

    #[test]
    fn file_textures_draw_rows_by_weight_and_shape_relative_ones_compose() {
        let a = euler_to_quaternion([0.1, 0.2, 0.3]);
        let b = euler_to_quaternion([1.0, 2.0, 3.0]);
        let texture = Texture::File {
            path: PathBuf::from("o.csv"),
            orientations: vec![a, b],
            weights: vec![1.0, 3.0],
        };
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let hits = (0..DRAWS).filter(|_| texture.sample(&mut rng) == b).count() as f64;
        // Binomial(n, 3/4): 5 standard deviations.
        let (n, p) = (DRAWS as f64, 0.75);
        assert!((hits - n * p).abs() < 5.0 * (n * p * (1.0 - p)).sqrt());

        let shape = euler_to_quaternion([0.5, 0.6, 0.7]);
        let relative = PhaseTexture {
            texture,
            relative_to_shape: true,
        };
        let q = relative.in_sample(a, shape);
        let want = rotation_matrix(shape) * rotation_matrix(a);
        assert!((rotation_matrix(q) - want).abs().max() < ROUNDING);
        assert_eq!(PhaseTexture::default().in_sample(a, shape), a);
    }
}
