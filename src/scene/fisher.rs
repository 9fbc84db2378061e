//! The 3D shape-orientation law: the first axis about a mean direction by von
//! Mises–Fisher, and the spin of the grain about its first axis, uniform or von Mises
//! about a reference direction.
//!
//! The spin `ψ` of a grain whose first axis is `e` is the angle of its second axis from
//! `r⊥`, the reference direction projected on the plane normal to `e`, toward `e × r⊥`:
//! second axis `= cos ψ r⊥ + sin ψ (e × r⊥)`, third `= e × second`. So with the first
//! axis near RD (x) and the reference TD (y), `ψ = 0` puts the third axis on ND (z): a
//! pancake in the rolling plane.

use crate::laws::{Fisher, VonMises};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use rand::Rng;
use std::f64::consts::PI;

/// How a grain turns about its first axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spin {
    /// Uniform in `[−π, π)`, measured from the axis [`perpendicular`] to the first axis.
    Uniform,
    /// Von Mises `ψ` (radians) measured from the projected reference direction.
    VonMises {
        /// Unit reference direction; never parallel to the mean direction.
        reference: [f64; 3],
        /// The law of `ψ`.
        angle: VonMises,
    },
}

/// The first axis drawn by von Mises–Fisher about `mean`, then the spin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FisherOrientation {
    /// Unit mean direction of the first axis.
    pub mean: [f64; 3],
    /// The law of the angle between the first axis and `mean`.
    pub fisher: Fisher,
    /// The spin about the first axis.
    pub spin: Spin,
}

fn v(a: [f64; 3]) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

/// A unit vector normal to the unit vector `e`: `e × (the coordinate axis least
/// aligned with e)`, normalised.
pub fn perpendicular(e: [f64; 3]) -> [f64; 3] {
    let k = (0..3)
        .min_by(|&i, &j| e[i].abs().total_cmp(&e[j].abs()))
        .unwrap_or(0);
    let mut axis = [0.0; 3];
    axis[k] = 1.0;
    let p = v(e).cross(&v(axis)).normalize();
    [p.x, p.y, p.z]
}

/// A unit vector drawn from the von Mises–Fisher law about the unit vector `mean`:
/// `cos θ` from `fisher`, the azimuth uniform about `mean`.
pub(crate) fn fisher_direction<R: Rng + ?Sized>(
    mean: [f64; 3],
    fisher: &Fisher,
    rng: &mut R,
) -> [f64; 3] {
    let mu = v(mean);
    let t1 = v(perpendicular(mean));
    let t2 = mu.cross(&t1);
    let w = fisher.sample_cos_angle(rng);
    let phi = 2.0 * PI * rng.random::<f64>();
    let s = (1.0 - w * w).max(0.0).sqrt();
    let e = (mu * w + (t1 * phi.cos() + t2 * phi.sin()) * s).normalize();
    [e.x, e.y, e.z]
}

/// `r` projected on the plane normal to the unit vector `e` and normalised, or
/// [`perpendicular`]`(e)` when `r` is (numerically) along `e`.
fn projected(r: [f64; 3], e: [f64; 3]) -> Vector3<f64> {
    let (r, ev) = (v(r), v(e));
    let p = r - ev * r.dot(&ev);
    // Below 1e-8 of |r| the projection's direction is dominated by rounding of e.
    const PARALLEL: f64 = 1e-8;
    if p.norm() <= PARALLEL * r.norm() {
        v(perpendicular(e))
    } else {
        p.normalize()
    }
}

impl FisherOrientation {
    /// The reference the spin is measured from, for a grain with first axis `e`.
    fn spin_frame(&self, e: [f64; 3]) -> Vector3<f64> {
        match self.spin {
            Spin::Uniform => v(perpendicular(e)),
            Spin::VonMises { reference, .. } => projected(reference, e),
        }
    }

    /// Draws an orientation: the quaternion `[w, x, y, z]` (w ≥ 0). `None` if the spin
    /// law's rejection sampling gave up.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> Option<[f64; 4]> {
        let e = v(fisher_direction(self.mean, &self.fisher, rng));
        let psi = match self.spin {
            Spin::Uniform => 2.0 * PI * rng.random::<f64>() - PI,
            Spin::VonMises { angle, .. } => angle.sample(rng)?,
        };
        let r = self.spin_frame([e.x, e.y, e.z]);
        let second = r * psi.cos() + e.cross(&r) * psi.sin();
        let third = e.cross(&second);
        let m = Matrix3::from_columns(&[e, second, third]);
        let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
        let q = [q.w, q.i, q.j, q.k];
        Some(if q[0] < 0.0 { q.map(|c| -c) } else { q })
    }

    /// The angle (radians, `[0, π]`) between a grain's first axis `e` and the mean.
    pub fn axis_angle(&self, e: [f64; 3]) -> f64 {
        let (e, mu) = (v(e), v(self.mean));
        e.cross(&mu).norm().atan2(e.dot(&mu))
    }

    /// The spin `ψ` (radians) of a grain with first axis `e` and second axis `b`; for a
    /// von Mises spin, in the law's window `[mean − π, mean + π]`, else in `[−π, π]`.
    pub fn spin_angle(&self, e: [f64; 3], b: [f64; 3]) -> f64 {
        let r = self.spin_frame(e);
        let (ev, bv) = (v(e), v(b));
        let psi = bv.dot(&ev.cross(&r)).atan2(bv.dot(&r));
        match self.spin {
            Spin::Uniform => psi,
            Spin::VonMises { angle, .. } => {
                psi + 2.0 * PI * ((angle.mean - psi) / (2.0 * PI)).round()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::rotation_column;
    use crate::laws::{ks_distance, VonMisesCdf};
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// n = 20 000 draws: the KS distance of a correct sampler exceeds 1.95/√n ≈ 0.0138
    /// with probability 0.001, so a fixed seed fails only on a real disagreement.
    #[test]
    fn drawn_orientations_follow_the_axis_and_spin_laws() {
        let n = 20_000;
        let law = FisherOrientation {
            mean: [1.0, 0.0, 0.0],
            fisher: Fisher { kappa: 33.0 },
            spin: Spin::VonMises {
                reference: [0.0, 1.0, 0.0],
                angle: VonMises::new(0.0, 20.0),
            },
        };
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let (mut angles, mut spins) = (Vec::new(), Vec::new());
        for _ in 0..n {
            let q = law.sample(&mut rng).unwrap();
            let (e, b, c) = (
                rotation_column(q, 0),
                rotation_column(q, 1),
                rotation_column(q, 2),
            );
            // A right-handed orthonormal frame, to a few ulps.
            let ortho = v(e).dot(&v(b)).abs() + v(c).dot(&v(e).cross(&v(b))) - 1.0;
            assert!(ortho.abs() < 1e-14, "{ortho}");
            angles.push(law.axis_angle(e));
            spins.push(law.spin_angle(e, b));
        }
        let bound = 1.95 / (n as f64).sqrt();
        let d = ks_distance(&angles, |t| law.fisher.angle_cdf(t)).unwrap();
        assert!(d < bound, "axis {d}");
        let Spin::VonMises { angle, .. } = law.spin else {
            unreachable!()
        };
        let cdf = VonMisesCdf::new(&angle);
        let d = ks_distance(&spins, |t| cdf.cdf(t)).unwrap();
        assert!(d < bound, "spin {d}");
    }

    #[test]
    fn uniform_spin_is_uniform() {
        let n = 20_000;
        let law = FisherOrientation {
            mean: [0.0, 0.6, 0.8],
            fisher: Fisher { kappa: 2.0 },
            spin: Spin::Uniform,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(6);
        let spins: Vec<f64> = (0..n)
            .map(|_| {
                let q = law.sample(&mut rng).unwrap();
                law.spin_angle(rotation_column(q, 0), rotation_column(q, 1))
            })
            .collect();
        let d = ks_distance(&spins, |t| ((t + PI) / (2.0 * PI)).clamp(0.0, 1.0)).unwrap();
        assert!(d < 1.95 / (n as f64).sqrt(), "{d}");
    }
}
