//! One candidate pair: its contact factor, and the force and torques of its overlap.

use crate::contact::{
    contact_fast_prepared, contact_tracked, dot, response_geometry, ContactGeometry,
    PreparedEllipsoid, Touch,
};
use crate::octree::Pair;

/// What one overlapping pair contributes.
#[derive(Clone, Copy)]
pub(super) struct PairForce {
    /// Force on the second grain (the first gets its opposite).
    pub force: [f64; 3],
    /// Where the force acts, from the first centre; `None` for the fallback push,
    /// which turns no grain. Torques are asked of it only when grains turn.
    point: Option<[f64; 3]>,
    pub energy: f64,
    pub mu1: f64,
}

impl PairForce {
    /// The torques about the first centre and about the second (at `r` from it).
    pub fn torques(&self, r: &[f64; 3]) -> [[f64; 3]; 2] {
        let Some(point) = self.point else {
            return [[0.0; 3]; 2];
        };
        let force = self.force;
        let pj = [0, 1, 2].map(|k| point[k] - r[k]);
        [cross(&point, &force.map(|x| -x)), cross(&pj, &force)]
    }
}

/// μ₁ of one candidate pair (a lower bound, to rounding), and its force and torques
/// at scale `big_s` (`None` when it does not overlap there). `radii` are given when
/// both grains are spheres; `lambda` is where the pair's contact function starts, and
/// is left where the next evaluation should start.
#[inline(always)]
pub(super) fn pair_force(
    r: &[f64; 3],
    (ei, ej): (&PreparedEllipsoid, &PreparedEllipsoid),
    radii: Option<(f64, f64)>,
    (big_s, lambda): (f64, &mut f32),
    p: &Pair,
) -> (f64, Option<PairForce>) {
    let reach = big_s * (ei.inscribed_radius() + ej.inscribed_radius());
    let w = reach * reach;
    // The geometry only for a pair that overlaps: most of the others are tested to
    // renew their allowance, which needs μ alone.
    let found = if let Some((ri, rj)) = radii {
        sphere_geometry(r, ri, rj).map(touching)
    } else if let Some(t) =
        contact_tracked(r, ei, ej, f64::from(*lambda), (big_s * big_s, TRACK_GAIN))
    {
        *lambda = t.next as f32;
        match t.touch {
            Some(touch) => Some((t.mu2_lower, touch)),
            None => return (t.mu2_lower.sqrt(), None),
        }
    } else {
        match contact_fast_prepared(r, ei, ej) {
            Ok(c) => {
                *lambda = c.lambda as f32;
                if c.mu2.is_finite() && c.mu2.sqrt() >= big_s {
                    return (c.mu2.sqrt(), None);
                }
                response_geometry(c, r, ei, ej).ok().map(touching)
            }
            Err(_) => None,
        }
    };
    let Some((mu2, touch)) = found.filter(|(mu2, _)| mu2.is_finite()) else {
        // Coincident centres (or a pair the contact function cannot handle, which
        // the scene's validated shapes do not produce): push apart along a fixed
        // direction with the force of a full overlap.
        let n = fallback_direction(p.i, p.j);
        let force = PairForce {
            force: n.map(|x| 2.0 * reach * x),
            point: None,
            energy: w,
            mu1: 0.0,
        };
        return (0.0, Some(force));
    };
    let mu1 = mu2.sqrt();
    let mu = mu1 / big_s;
    if mu >= 1.0 {
        return (mu1, None);
    }
    let rn = dot(r, &touch.direction);
    // −∂U/∂r = 2 w (1 − μ) ∇μ, ∇μ = μ n / (r·n), for n any positive multiple of the
    // normal.
    let scale = 2.0 * w * (1.0 - mu) * mu / rn;
    let force = touch.direction.map(|x| scale * x);
    let force = PairForce {
        force,
        point: Some(touch.point),
        energy: pair_energy(reach, mu),
        mu1,
    };
    (mu1, Some(force))
}

/// A geometry's contact: its μ², its unit normal and its point.
fn touching(g: ContactGeometry) -> (f64, Touch) {
    let (direction, point) = (g.normal, g.point);
    (g.mu2, Touch { direction, point })
}

/// How close to μ² the narrow phase takes a pair's tracked `f(λ)` (module
/// `contact::track`), as the Newton model's relative gain. 1e-6 puts μ within 5e-7 of
/// its value and the normal (taken at Newton's next λ, to first order) within about
/// 1e-6, so forces agree with the maximiser's to 1e-6 of their size
/// (`forces::tests::skipping_pairs_changes_no_force`); the value is always a lower
/// bound, so a pair found apart is apart, and the final check is exact anyway. On
/// `benches/scale/hundred_thousand.toml` the maximiser's own tolerance
/// ([`GAIN_TOL`](crate::contact::GAIN_TOL), 9.2e-12) takes 1.7 evaluations of `f` a
/// tracked pair, 1e-6 1.1 (narrow phase 22 % shorter); 1e-5 and 1e-4 packed in the
/// same time within noise, in 270 and 280 FIRE steps against 275 (BENCHMARKS.md,
/// "Issue 26: contact tracked from step to step").
const TRACK_GAIN: f64 = 1e-6;

/// The overlap energy of a pair whose bodies, scaled by `big_s`, overlap with gauge
/// `μ = μ₁ / big_s < 1`: `w (1 − μ)²` with `w = reach²`, `reach = big_s (ρ_i + ρ_j)`
/// (inscribed radii). The swap moves (`unjam`) judge with the same energy.
pub(crate) fn pair_energy(reach: f64, mu: f64) -> f64 {
    reach * reach * (1.0 - mu) * (1.0 - mu)
}

/// Two spheres need no contact function: `μ = d / (R_i + R_j)`, normal `r/d`, and
/// they touch at `R_i r / (R_i + R_j)` from the first centre. `None` at `d = 0`.
fn sphere_geometry(r: &[f64; 3], ri: f64, rj: f64) -> Option<ContactGeometry> {
    let d = dot(r, r).sqrt();
    if d == 0.0 {
        return None;
    }
    let mu = d / (ri + rj);
    Some(ContactGeometry {
        mu2: mu * mu,
        lambda: ri / (ri + rj),
        point: r.map(|x| x * ri / (ri + rj)),
        normal: r.map(|x| x / d),
        gap: d - (ri + rj),
    })
}

pub(crate) fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `2^64 / φ` (odd): multiplying by it spreads consecutive ids over all 64 bits.
const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;
/// splitmix64's first mixing multiplier (Steele, Lea and Flood 2014).
const SPLITMIX_MUL: u64 = 0xBF58_476D_1CE4_E5B9;

/// A unit vector that depends only on the pair's ids (a hash), for coincident centres.
fn fallback_direction(i: u32, j: u32) -> [f64; 3] {
    let mut h = (u64::from(i) << 32 | u64::from(j)).wrapping_mul(GOLDEN_GAMMA);
    let mut coord = || {
        h ^= h >> 29;
        h = h.wrapping_mul(SPLITMIX_MUL);
        (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let v = [coord(), coord(), coord()];
    let n = dot(&v, &v).sqrt().max(f64::MIN_POSITIVE);
    v.map(|x| x / n)
}
