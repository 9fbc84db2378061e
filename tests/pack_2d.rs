//! Packing ellipses in a rectangle: the 3D loop on grains embedded in the plane
//! (`contact::Dimension`). The packings are checked by a 2D computation of their own
//! (2×2 forms, golden-section search), not by the library's contact function.

use grainpack::contact::{ellipse_angle, Dimension};
use grainpack::packing::{pack, Job, Packing, Tuning};
use grainpack::scene::{Boundary, Domain, GrainSpec, PackingParams, Rotation, Unjam};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use std::sync::atomic::AtomicBool;

/// `max over λ of λ(1−λ) rᵀ [(1−λ)A + λB]⁻¹ r` for 2×2 forms `[q00, q01, q11]`, by
/// golden-section search (f is concave on [0, 1]); 90 steps shrink the bracket to 1e-19.
fn mu2(r: [f64; 2], a: [f64; 3], b: [f64; 3]) -> f64 {
    let f = |l: f64| {
        let m = [0, 1, 2].map(|k| (1.0 - l) * a[k] + l * b[k]);
        let det = m[0] * m[2] - m[1] * m[1];
        let quad = (m[2] * r[0] * r[0] - 2.0 * m[1] * r[0] * r[1] + m[0] * r[1] * r[1]) / det;
        l * (1.0 - l) * quad
    };
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..90 {
        let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(c) > f(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    f(0.5 * (lo + hi))
}

/// The 2×2 form `R diag(a1², a2²) Rᵀ` of an ellipse at angle `t`.
fn form(a1: f64, a2: f64, t: f64) -> [f64; 3] {
    let (s, c) = t.sin_cos();
    let (p, q) = (a1 * a1, a2 * a2);
    [
        c * c * p + s * s * q,
        c * s * (p - q),
        s * s * p + c * c * q,
    ]
}

/// A pair overlaps when μ² < 1 − `MU2_TOL`: f is evaluated in double precision with a
/// 2×2 inverse of condition ≤ (a1/a2)² ≤ 4 here, relative error far below 1e-12.
const MU2_TOL: f64 = 1e-10;

/// The smallest μ² over all pairs at their minimum image, brute force.
fn min_mu2(p: &Packing, size: [f64; 2], periodic: bool) -> f64 {
    let shapes: Vec<_> = (p.grains.iter())
        .map(|g| form(g.semi_axes[0], g.semi_axes[1], ellipse_angle(g.quaternion)))
        .collect();
    let mut least = f64::INFINITY;
    for (i, gi) in p.grains.iter().enumerate() {
        for (j, gj) in p.grains.iter().enumerate().skip(i + 1) {
            let r = [0, 1].map(|k| {
                let d = gj.centre[k] - gi.centre[k];
                if periodic {
                    d - size[k] * (d / size[k]).round()
                } else {
                    d
                }
            });
            let reach = gi.semi_axes[0].max(gi.semi_axes[1]) + gj.semi_axes[0].max(gj.semi_axes[1]);
            if r[0] * r[0] + r[1] * r[1] <= reach * reach {
                least = least.min(mu2(r, shapes[i], shapes[j]));
            }
        }
    }
    least
}

/// `n` ellipses of equivalent diameters 1 and 1.4 (half each) with aspect ratios drawn
/// in `[1, max_aspect]`, random angles, in a square whose side makes `fraction`.
fn ellipses(n: usize, max_aspect: f64, fraction: f64, seed: u64) -> (Vec<GrainSpec>, f64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let specs: Vec<GrainSpec> = (0..n)
        .map(|i| {
            let d = if i % 2 == 0 { 1.0 } else { 1.4 };
            let aspect = 1.0 + (max_aspect - 1.0) * rng.random::<f64>();
            GrainSpec::ellipse(0, d, aspect, PI * rng.random::<f64>())
        })
        .collect();
    let area: f64 = specs.iter().map(GrainSpec::volume).sum();
    (specs, (area / fraction).sqrt())
}

fn pack_plane(specs: &[GrainSpec], domain: &Domain, params: &PackingParams) -> Packing {
    let job = Job {
        specs,
        domain,
        params,
        tuning: &Tuning::default(),
        seed: 3,
    };
    pack(&job, &AtomicBool::new(false), &mut |_| {}).unwrap()
}

#[test]
fn ellipses_stay_in_the_plane_and_apart() {
    for (boundary, rotation) in [
        (Boundary::Periodic, Rotation::Free),
        (Boundary::Reflecting, Rotation::None),
    ] {
        let (specs, side) = ellipses(300, 2.0, 0.80, 7);
        let domain = Domain::plane([side, side], boundary);
        let params = PackingParams {
            rotation,
            ..PackingParams::default()
        };
        let p = pack_plane(&specs, &domain, &params);
        assert!(p.verification.is_clean(), "{:?}", p.verification);
        let z = domain.plane_z();
        for g in &p.grains {
            // In the plane exactly: no force or torque of two embedded ellipses leaves it.
            assert_eq!(g.centre[2], z);
            assert_eq!((g.quaternion[1], g.quaternion[2]), (0.0, 0.0));
            assert!(g.centre[0] >= 0.0 && g.centre[0] <= side);
        }
        let periodic = boundary == Boundary::Periodic;
        let least = min_mu2(&p, [side, side], periodic);
        assert!(least >= 1.0 - MU2_TOL, "{boundary:?}: min μ² {least}");
        // The fraction reported is the area fraction of the grains as written.
        let area: f64 = p
            .grains
            .iter()
            .map(|g| PI * g.semi_axes[0] * g.semi_axes[1])
            .sum();
        let fraction = area / (side * side);
        assert!(
            (fraction - p.fraction).abs() < 1e-12 * fraction,
            "{fraction} {}",
            p.fraction
        );
        assert_eq!(
            Dimension::Two.measure(p.grains[0].semi_axes),
            PI * p.grains[0].semi_axes[0] * p.grains[0].semi_axes[1]
        );
        // Bidisperse ellipses this dense jam well above 0.75 (discs at 0.84).
        assert!(p.fraction > 0.75, "{boundary:?}: {}", p.fraction);
    }
}

#[test]
fn a_gap_is_kept_in_the_plane() {
    let (specs, side) = ellipses(200, 1.0, 0.70, 11);
    let domain = Domain::plane([side, side], Boundary::Periodic);
    let gap = 0.05;
    let params = PackingParams {
        gap,
        ..PackingParams::default()
    };
    let p = pack_plane(&specs, &domain, &params);
    assert!(p.verification.is_clean() && p.verification.min_gap >= gap);
    // Discs: surface gap ≥ gap·(r1 + r2), from the centres alone.
    let mut least = f64::INFINITY;
    for (i, a) in p.grains.iter().enumerate() {
        for b in &p.grains[i + 1..] {
            let r = [0, 1].map(|k| {
                let d = b.centre[k] - a.centre[k];
                d - side * (d / side).round()
            });
            let sum = a.semi_axes[0] + b.semi_axes[0];
            least = least.min(((r[0] * r[0] + r[1] * r[1]).sqrt() - sum) / sum);
        }
    }
    // 1e-12: the roundings of a distance of order 1.
    assert!(least >= gap - 1e-12, "{least}");
}

#[test]
fn the_plane_packing_does_not_depend_on_the_thread_count() {
    let (specs, side) = ellipses(400, 1.8, 0.82, 4);
    let domain = Domain::plane([side, side], Boundary::Periodic);
    let params = PackingParams {
        rotation: Rotation::Free,
        ..PackingParams::default()
    };
    let many = pack_plane(&specs, &domain, &params);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = pool.install(|| pack_plane(&specs, &domain, &params));
    assert_eq!(many.grains, one.grains);
    assert_eq!(many.counters.fire_steps, one.counters.fire_steps);
}

/// `unjam = "anneal"` (Monte Carlo moves, turns about the normal and swaps between
/// small compressions): the packing stays in the plane bit for bit, apart by the 2D
/// computation, the same on one and two threads, and denser than the same effort's
/// cycles without unjamming moves.
#[test]
fn annealing_stays_in_the_plane_apart_and_beats_plain_cycles() {
    let (specs, side) = ellipses(200, 1.4, 0.90, 5);
    let domain = Domain::plane([side, side], Boundary::Periodic);
    let params = |unjam| PackingParams {
        rotation: Rotation::Free,
        effort: 1.5,
        unjam,
        ..PackingParams::default()
    };
    let annealed = pack_plane(&specs, &domain, &params(Unjam::Anneal));
    let plain = pack_plane(&specs, &domain, &params(Unjam::None));
    assert!(
        annealed.verification.is_clean(),
        "{:?}",
        annealed.verification
    );
    assert!(annealed.counters.swaps > 0, "{:?}", annealed.counters);
    let z = domain.plane_z();
    for g in &annealed.grains {
        assert_eq!(g.centre[2], z);
        assert_eq!((g.quaternion[1], g.quaternion[2]), (0.0, 0.0));
    }
    let least = min_mu2(&annealed, [side, side], true);
    assert!(least >= 1.0 - MU2_TOL, "min μ² {least}");
    assert!(
        annealed.fraction > plain.fraction,
        "{} ≤ {}",
        annealed.fraction,
        plain.fraction
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = pool.install(|| pack_plane(&specs, &domain, &params(Unjam::Anneal)));
    assert_eq!(one.grains, annealed.grains);
}

/// The jamming literature's 2D scenes, timed (a benchmark, not a test: run with
/// `cargo test --release --test pack_2d -- --ignored --nocapture`).
#[test]
#[ignore]
fn literature_scenes() {
    let run = |name: &str, specs: &[GrainSpec], side: f64, params: PackingParams| {
        let domain = Domain::plane([side, side], Boundary::Periodic);
        let start = std::time::Instant::now();
        let p = pack_plane(specs, &domain, &params);
        eprintln!(
            "{name}: n {} φ {:.4} {:?} steps {} {:.2} s clean {}",
            specs.len(),
            p.fraction,
            p.stop,
            p.counters.fire_steps,
            start.elapsed().as_secs_f64(),
            p.verification.is_clean()
        );
    };
    let n = 10_000;
    let (discs, side) = ellipses(n, 1.0, 0.90, 1);
    for effort in [1.0, 2.0] {
        let params = PackingParams {
            effort,
            ..PackingParams::default()
        };
        run(
            &format!("bidisperse discs effort {effort}"),
            &discs,
            side,
            params,
        );
    }
    // Rocks and Hoy: aspect 1.3–1.4, minor axes spread over a factor 1.4.
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let rocks: Vec<GrainSpec> = (0..n)
        .map(|_| {
            let aspect = 1.3 + 0.1 * rng.random::<f64>();
            let minor = 1.0 + 0.4 * rng.random::<f64>();
            GrainSpec::ellipse(
                0,
                2.0 * minor * aspect.sqrt(),
                aspect,
                PI * rng.random::<f64>(),
            )
        })
        .collect();
    let area: f64 = rocks.iter().map(GrainSpec::volume).sum();
    for effort in [1.0, 2.0] {
        let params = PackingParams {
            effort,
            rotation: Rotation::Free,
            ..PackingParams::default()
        };
        run(
            &format!("rocks-hoy effort {effort}"),
            &rocks,
            (area / 0.95).sqrt(),
            params,
        );
    }
    let (big, side) = ellipses(100_000, 2.0, 0.75, 2);
    run("1e5 ellipses at 0.75", &big, side, PackingParams::default());
}
