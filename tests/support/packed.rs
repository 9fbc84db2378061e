//! An independent overlap check of a written packing, for the end-to-end tests: it
//! reads `grains.csv` and tests every pair with nalgebra and a golden-section search,
//! using nothing of grainpack (not its contact module, not its octree).

use super::files::pack_in;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use serde_json::Value;
use std::path::Path;

/// A grain read back from `grains.csv`.
#[derive(Debug, Clone)]
pub struct Grain {
    /// The `id` column.
    pub id: usize,
    /// The `phase` column.
    pub phase: usize,
    /// Centre.
    pub centre: Vector3<f64>,
    /// `[a1, a2, a3]`.
    pub semi_axes: [f64; 3],
    /// `R`, built by nalgebra from the quaternion: semi-axis k along column k.
    pub rotation: Matrix3<f64>,
    /// `Q = R diag(a²) Rᵀ`.
    pub q: Matrix3<f64>,
}

impl Grain {
    /// Bounding radius: the largest semi-axis.
    pub fn radius(&self) -> f64 {
        self.semi_axes.iter().copied().fold(0.0, f64::max)
    }

    /// `(4π/3) a1 a2 a3`.
    pub fn volume(&self) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * self.semi_axes.iter().product::<f64>()
    }
}

/// Reads `grains.csv`, checking its header, its width and unit quaternions.
pub fn read_grains(path: &Path) -> Vec<Grain> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    // The crystal orientation columns (o0..phi2) came with issue 13; tables written
    // before it (configs/measured_grains.csv) end at qz.
    let header = lines.next().unwrap_or_default();
    let shape = "id,phase,x,y,z,a1,a2,a3,qw,qx,qy,qz";
    assert!(
        header == shape || header == format!("{shape},o0,o1,o2,o3,phi1,Phi,phi2"),
        "{header}"
    );
    let width = header.split(',').count();
    lines
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(f.len(), width, "{line}");
            let v: Vec<f64> = f[2..].iter().map(|s| s.parse().unwrap()).collect();
            let quaternion = Quaternion::new(v[6], v[7], v[8], v[9]);
            // Written quaternions are unit to rounding (a few ulps).
            assert!((quaternion.norm() - 1.0).abs() < 1e-14, "{line}");
            let rotation = *UnitQuaternion::from_quaternion(quaternion)
                .to_rotation_matrix()
                .matrix();
            let semi_axes = [v[3], v[4], v[5]];
            let d = Matrix3::from_diagonal(&Vector3::from(semi_axes.map(|a| a * a)));
            Grain {
                id: f[0].parse().unwrap(),
                phase: f[1].parse().unwrap(),
                centre: Vector3::new(v[0], v[1], v[2]),
                semi_axes,
                rotation,
                q: rotation * d * rotation.transpose(),
            }
        })
        .collect()
}

/// `max over λ ∈ [0, 1] of f(λ) = λ(1−λ) rᵀ [(1−λ)Q1 + λQ2]⁻¹ r`, the
/// Perram–Wertheim contact function μ², by golden-section search: f is concave on
/// [0, 1], so the bracket keeps its maximum. 90 iterations shrink it to 0.618⁹⁰ ≈ 1e-19.
pub fn contact_mu2(r: &Vector3<f64>, q1: &Matrix3<f64>, q2: &Matrix3<f64>) -> f64 {
    let f = |l: f64| {
        let m = q1 * (1.0 - l) + q2 * l;
        let x = m.cholesky().expect("Q(λ) is positive definite").solve(r);
        l * (1.0 - l) * r.dot(&x)
    };
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (0.0, 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..90 {
        if fc > fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    fc.max(fd)
}

/// A pair is overlapping when μ² < 1 − `MU2_TOL`. f is computed in double precision
/// by a Cholesky solve of a matrix of condition at most (a_max/a_min)² ≈ 20 for these
/// scenes, so its relative error is below 1e-13; 1e-10 is a wide margin that no real
/// overlap hides in, since a true overlap of grains of size ~3 by 1e-10 relative is a
/// depth of ~1e-10, which the loop's exact check would have reported.
pub const MU2_TOL: f64 = 1e-10;

/// What the independent check found.
#[derive(Debug)]
pub struct Check {
    /// Pairs (and images) whose bounding spheres meet: `|r| ≤ R_i + R_j`.
    pub candidate_pairs: usize,
    /// Of those, μ² < 1 − MU2_TOL.
    pub overlapping_pairs: usize,
    /// Smallest μ² over the candidates (∞ if none).
    pub min_mu2: f64,
}

/// Every pair by brute force, at its minimum image; in a periodic box also the 26
/// images around that one when the box is small enough for a second image to be
/// within reach (shortest side ≤ 4 R_max), and each grain against its own images.
/// Pairs whose bounding spheres are apart are separated and skipped.
pub fn check_overlaps(grains: &[Grain], size: [f64; 3], periodic: bool) -> Check {
    let r_max = grains.iter().map(Grain::radius).fold(0.0, f64::max);
    let small = size.iter().any(|&l| l <= 4.0 * r_max);
    let mut around = vec![Vector3::zeros()];
    if periodic && small {
        for i in -1..=1 {
            for j in -1..=1 {
                for k in -1..=1 {
                    if (i, j, k) != (0, 0, 0) {
                        around.push(Vector3::new(
                            f64::from(i) * size[0],
                            f64::from(j) * size[1],
                            f64::from(k) * size[2],
                        ));
                    }
                }
            }
        }
    }
    let minimum_image = |r: Vector3<f64>| {
        if periodic {
            Vector3::from_fn(|k, _| r[k] - size[k] * (r[k] / size[k]).round())
        } else {
            r
        }
    };
    let mut check = Check {
        candidate_pairs: 0,
        overlapping_pairs: 0,
        min_mu2: f64::INFINITY,
    };
    for (i, gi) in grains.iter().enumerate() {
        for gj in &grains[i..] {
            let same = gi.id == gj.id;
            let r0 = minimum_image(gj.centre - gi.centre);
            for shift in &around {
                let r = r0 + shift;
                if (same && r == Vector3::zeros()) || r.norm() > gi.radius() + gj.radius() {
                    continue;
                }
                let mu2 = contact_mu2(&r, &gi.q, &gj.q);
                // A grain meeting its own image is always wrong; it is not a pair.
                assert!(!same || mu2 >= 1.0, "grain {} meets its image", gi.id);
                if same {
                    continue;
                }
                check.candidate_pairs += 1;
                check.min_mu2 = check.min_mu2.min(mu2);
                if mu2 < 1.0 - MU2_TOL {
                    check.overlapping_pairs += 1;
                    eprintln!("overlap: {} and {} (r = {r:?}): μ² = {mu2}", gi.id, gj.id);
                }
            }
        }
    }
    check
}

/// Extent of a grain along axis k: `√Q_kk`, the support function of the ellipsoid.
pub fn extent(g: &Grain, k: usize) -> f64 {
    g.q[(k, k)].sqrt()
}

/// Packs `scene` (a path) into `dir/out`, expecting exit code `code` (3: jammed below
/// the target, outputs written), and returns the summary, after checking that
/// the grains are triaxial-ordered and overlap-free by the independent check.
pub fn pack_and_check(dir: &Path, scene: &str, periodic: bool, code: i32) -> Value {
    let run = pack_in(dir, &[scene, "--out", "out", "--threads", "2", "--quiet"]);
    assert_eq!(
        run.status.code(),
        Some(code),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap())
            .unwrap();
    let grains = read_grains(&dir.join("out/grains.csv"));
    let size: Vec<f64> = summary["box"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let size = [size[0], size[1], size[2]];
    let check = check_overlaps(&grains, size, periodic);
    assert_eq!(check.overlapping_pairs, 0, "min μ² {}", check.min_mu2);
    assert!(check.candidate_pairs > 0);
    if !periodic {
        for g in &grains {
            for (k, &l) in size.iter().enumerate() {
                let w = extent(g, k);
                assert!(g.centre[k] - w >= 0.0 && g.centre[k] + w <= l, "{g:?}");
            }
        }
    }
    summary
}
