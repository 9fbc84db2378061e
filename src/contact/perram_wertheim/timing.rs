//! Where the time of `contact_function` goes, and a fixed workload for instruction
//! counts. Both are `#[ignore]`d: run them with `--ignored --nocapture`.

use super::*;
use crate::contact::test_pairs::{reference_rows, ReferencePair as Case};
use std::hint::black_box;

fn typical_cases() -> Vec<Case> {
    reference_rows("contact_typical.csv")
        .into_iter()
        .map(|(c, _, _)| c)
        .collect()
}

type Stage<'a> = (&'a str, &'a dyn Fn(&Case) -> f64);

/// Median and fastest mean time per call of each stage over 1000 passes of the typical
/// set, the stages interleaved pass by pass so that they see the same machine load.
fn time(cases: &[Case], stages: &[Stage]) {
    let mut per_call = vec![vec![]; stages.len()];
    for _ in 0..1000 {
        for (k, (_, f)) in stages.iter().enumerate() {
            let s = std::time::Instant::now();
            for c in cases {
                black_box(f(black_box(c)));
            }
            per_call[k].push(s.elapsed().as_nanos() as f64 / cases.len() as f64);
        }
    }
    for ((name, _), v) in stages.iter().zip(&mut per_call) {
        v.sort_by(f64::total_cmp);
        let (min, median) = (v[0], v[v.len() / 2]);
        println!("{name:>12}: median {median:6.1} ns, fastest {min:6.1} ns");
    }
}

/// Cumulative cost of the stages of `contact_function`: each line adds one stage.
#[test]
#[ignore]
fn split_of_the_cost() {
    let cases = typical_cases();
    let setup = |c: &Case| {
        let (l1, l2) = (Ldl::factor(&c.q1).unwrap(), Ldl::factor(&c.q2).unwrap());
        let p = Prepared::unscaled(&c.r12, &c.q1, &c.q2, l1, l2);
        let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
        let parts = PencilParts::new(&p.q1, &p.q2);
        let ends = [p.l1.det(), p.l2.det(), a, b];
        let rational = Rational::new(&p.r, &p.q1, &p.q2, &parts, ends);
        (p, parts, rational, b.sqrt() / (a.sqrt() + b.sqrt()))
    };
    time(
        &cases,
        &[
            ("prepare", &|c| {
                let (l1, l2) = (Ldl::factor(&c.q1).unwrap(), Ldl::factor(&c.q2).unwrap());
                Prepared::unscaled(&c.r12, &c.q1, &c.q2, l1, l2).r[0]
            }),
            ("+rational", &|c| {
                let (_, _, rational, t0) = setup(c);
                rational.f(t0)
            }),
            ("+predictor", &|c| {
                let (_, _, rational, t0) = setup(c);
                predict(&rational, t0, CORRECTOR_SWITCH_GAIN).unwrap().0
            }),
            ("+corrector", &|c| {
                let (p, parts, rational, t0) = setup(c);
                let refiner = Refiner::new(&p, &parts, &rational);
                let (t, _, it) = predict(&rational, t0, CORRECTOR_SWITCH_GAIN).unwrap();
                correct(&p, &refiner, t, it).unwrap().mu2
            }),
            ("accurate", &|c| {
                contact_function(&c.r12, &c.q1, &c.q2).unwrap().mu2
            }),
            ("fast", &|c| {
                contact_function_fast(&c.r12, &c.q1, &c.q2).unwrap().mu2
            }),
        ],
    );
}

/// A fixed workload for instruction counts (`valgrind --tool=callgrind`): passes of
/// the method named by `GRAINPACK_COUNT` (accurate or fast) over the typical set.
#[test]
#[ignore]
fn instruction_count_workload() {
    let cases = typical_cases();
    let passes: usize = std::env::var("GRAINPACK_PASSES").map_or(20, |v| v.parse().unwrap());
    let accurate = std::env::var("GRAINPACK_COUNT").map_or(true, |v| v == "accurate");
    let method = match accurate {
        true => contact_function,
        false => contact_function_fast,
    };
    for _ in 0..passes {
        for c in &cases {
            black_box(method(black_box(&c.r12), &c.q1, &c.q2).unwrap());
        }
    }
}

/// Per-pair time of the accurate method in lanes (whatever the target: plain arrays
/// without AVX-512) against the scalar [`contact_function`].
#[test]
#[ignore]
fn batch_against_scalar() {
    let cases = typical_cases();
    let pairs: Vec<_> = cases.iter().map(|c| (c.r12, c.q1, c.q2)).collect();
    let mut v: [Vec<f64>; 2] = Default::default();
    for _ in 0..1000 {
        let s = std::time::Instant::now();
        for (r, q1, q2) in &pairs {
            black_box(contact_function(black_box(r), q1, q2).unwrap());
        }
        v[0].push(s.elapsed().as_nanos() as f64 / pairs.len() as f64);
        let s = std::time::Instant::now();
        black_box(super::batch::in_lanes::<true>(black_box(&pairs)));
        v[1].push(s.elapsed().as_nanos() as f64 / pairs.len() as f64);
    }
    for (name, x) in ["scalar", "lanes"].iter().zip(&mut v) {
        x.sort_by(f64::total_cmp);
        println!(
            "{name:>8}: median {:6.1} ns, fastest {:6.1} ns per pair",
            x[x.len() / 2],
            x[0]
        );
    }
}

/// [`split_of_the_cost`] with each call's `r12` depending on the previous call's result
/// (through `0 · (μ² + λ)`, the same value), so that calls cannot overlap: the latency
/// of each stage. Equal to the independent times within a few ns (2026-11-27, AMD EPYC):
/// the call is bound by its chain of dependent operations, not by throughput.
#[test]
#[ignore]
fn chained_split_of_the_cost() {
    let cases = typical_cases();
    let shifted = |c: &Case, carry: f64| [c.r12[0] + carry, c.r12[1], c.r12[2]];
    let setup = |c: &Case, carry: f64| {
        let r = shifted(c, carry);
        let (l1, l2) = (Ldl::factor(&c.q1).unwrap(), Ldl::factor(&c.q2).unwrap());
        let p = Prepared::unscaled(&r, &c.q1, &c.q2, l1, l2);
        let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
        let parts = PencilParts::new(&p.q1, &p.q2);
        let ends = [p.l1.det(), p.l2.det(), a, b];
        let rational = Rational::new(&p.r, &p.q1, &p.q2, &parts, ends);
        (p, parts, rational, b.sqrt() / (a.sqrt() + b.sqrt()))
    };
    type Chained<'a> = (&'a str, &'a dyn Fn(&Case, f64) -> f64);
    let stages: [Chained; 5] = [
        ("t0", &|c, carry| setup(c, carry).3),
        ("+predictor", &|c, carry| {
            let (_, _, rational, t0) = setup(c, carry);
            predict(&rational, t0, CORRECTOR_SWITCH_GAIN).unwrap().0
        }),
        ("+corrector", &|c, carry| {
            let (p, parts, rational, t0) = setup(c, carry);
            let refiner = Refiner::new(&p, &parts, &rational);
            let (t, _, it) = predict(&rational, t0, CORRECTOR_SWITCH_GAIN).unwrap();
            let c = correct(&p, &refiner, t, it).unwrap();
            c.mu2 + c.lambda
        }),
        ("accurate", &|c, carry| {
            let c = contact_function(&shifted(c, carry), &c.q1, &c.q2).unwrap();
            c.mu2 + c.lambda
        }),
        ("fast", &|c, carry| {
            let c = contact_function_fast(&shifted(c, carry), &c.q1, &c.q2).unwrap();
            c.mu2 + c.lambda
        }),
    ];
    for (name, f) in stages {
        let mut per_call: Vec<f64> = (0..1000)
            .map(|_| {
                let s = std::time::Instant::now();
                let mut carry = 0.0;
                for c in &cases {
                    carry = f(c, carry) * 0.0;
                }
                black_box(carry);
                s.elapsed().as_nanos() as f64 / cases.len() as f64
            })
            .collect();
        per_call.sort_by(f64::total_cmp);
        println!("{name:>12}: chained, median {:6.1} ns", per_call[500]);
    }
}
