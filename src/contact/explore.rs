use super::bernstein::Rational;
use super::scale::Prepared;
use super::sym::PencilParts;
use super::test_pairs::{random_rotation, rotate, reference_rows};
use super::*;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn kappas(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> [f64; 4] {
    let p = Prepared::new(r12, q1, q2).unwrap();
    let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
    let parts = PencilParts::new(&p.q1, &p.q2);
    let ends = [p.l1.det(), p.l2.det(), a, b];
    let (ca, cb) = super::bernstein::coefficients(&p.r, &p.q1, &p.q2, &parts, ends);
    let (x, y) = (&p.q1, &p.q2);
    let r2 = p.r.map(|v| v * v);
    let m = [
        x[3] * y[5] + x[5] * y[3],
        x[0] * y[5] + x[5] * y[0],
        x[0] * y[3] + x[3] * y[0],
    ];
    let at1 = r2[0] * m[0] + r2[1] * m[1] + r2[2] * m[2];
    let d1 = [x[3] * x[5], x[0] * x[5], x[0] * x[3]];
    let d2 = [y[3] * y[5], y[0] * y[5], y[0] * y[3]];
    let bt1 = y[0] * d1[0] + y[3] * d1[1] + y[5] * d1[2];
    let bt2 = x[0] * d2[0] + x[3] * d2[1] + x[5] * d2[2];
    let at0 = r2[0] * d1[0] + r2[1] * d1[1] + r2[2] * d1[2];
    let at2 = r2[0] * d2[0] + r2[1] * d2[1] + r2[2] * d2[2];
    let bt0 = x[0] * d1[0];
    let bt3 = y[0] * d2[0];
    let mixed = (at1 / ca[1]).max(bt1 / cb[1]).max(bt2 / cb[2]);
    let _ = (at0, at2, bt0, bt3);
    let (a1, a2) = (&parts.adj1, &parts.adj2);
    let k1 = (x[0] * a1[0] + x[3] * a1[3] + x[5] * a1[5]) / cb[0];
    let k2 = (y[0] * a2[0] + y[3] * a2[3] + y[5] * a2[5]) / cb[3];
    let ends = k1.max(k2);
    let rat = Rational::new(&p.r, &p.q1, &p.q2, &parts, [p.l1.det(), p.l2.det(), a, b]);
    let fast = contact_function_fast(r12, q1, q2).unwrap();
    let (t, s) = (fast.lambda, 1.0 - fast.lambda);
    let av = ca[0] * s * s + ca[1] * s * t + ca[2] * t * t;
    let aw = ca[0] * k1 * s * s + at1 * s * t + ca[2] * k2 * t * t;
    let bv = super::bernstein::cubic(&cb, t, s);
    let bw = super::bernstein::cubic(&[cb[0] * k1, bt1, bt2, cb[3] * k2], t, s);
    let klam = (aw / av).max(bw / bv);
    let _ = rat;
    [mixed, ends, klam, 0.0]
}

fn report(name: &str, pairs: &[(Vec3, Sym3, Sym3)]) {
    let mut worst = 0.0f64;
    let mut worst_ratio = 0.0f64;
    let mut worst_ratio_m = 0.0f64;
    let mut over = 0;
    let mut flagged = 0;
    let mut kmax = 0.0f64;
    let mut worst_l = 0.0f64;
    let mut flag_max = [0; 2];
    let mut flag_lam = [0; 2];
    for (r, q1, q2) in pairs {
        let acc = contact_function(r, q1, q2).unwrap();
        let fast = contact_function_fast(r, q1, q2).unwrap();
        let err = ((fast.mu2 - acc.mu2) / acc.mu2).abs();
        let k = kappas(r, q1, q2);
        let kk = k[0].max(k[1]);
        let kl = k[2];
        worst_l = worst_l.max(err / (f64::EPSILON * kl));
        for (j, th) in [1e-10, 1e-9].iter().enumerate() {
            flag_max[j] += usize::from(4.0 * f64::EPSILON * kk > *th);
            flag_lam[j] += usize::from(4.0 * f64::EPSILON * kl > *th);
        }
        worst = worst.max(err);
        worst_ratio = worst_ratio.max(err / (f64::EPSILON * kk));
        worst_ratio_m = worst_ratio_m.max(err / (f64::EPSILON * k[0]));
        kmax = kmax.max(kk);
        if err > 1e-10 {
            over += 1;
        }
        if f64::EPSILON * kk * 16.0 > 1e-10 {
            flagged += 1;
        }
    }
    println!(
        "{name:24} n={:5} worst={worst:.2e} err/(eps k)={worst_ratio:.2e} err/(eps kmixed)={worst_ratio_m:.2e} kmax={kmax:.2e} over1e-10={over} flagged={flagged} wl={worst_l:.2e} fmax={flag_max:?} flam={flag_lam:?}",
        pairs.len()
    );
}

fn needle(rng: &mut StdRng, aspect: f64) -> Sym3 {
    let kind = rng.random_range(0..3);
    let a = 10f64.powf(rng.random_range(-1.0..1.0));
    let axes = match kind {
        0 => [a, a / aspect, a / aspect],
        1 => [a, a, a / aspect],
        _ => [a, a / aspect.sqrt(), a / aspect],
    };
    let d = [axes[0] * axes[0], 0.0, 0.0, axes[1] * axes[1], 0.0, axes[2] * axes[2]];
    rotate(&random_rotation(rng), &([0.0; 3], d, d)).1
}

#[test]
#[ignore]
fn explore() {
    for name in ["contact_typical.csv", "contact_extreme.csv"] {
        let rows = reference_rows(name);
        let pairs: Vec<_> = rows.iter().map(|(c, _, _)| (c.r12, c.q1, c.q2)).collect();
        report(name, &pairs);
        if name == "contact_extreme.csv" {
            for k in 0..7 {
                report(&format!("cat{k}"), &pairs[k * 215..(k + 1) * 215]);
            }
        }
    }
    let mut rng = StdRng::seed_from_u64(5);
    for aspect in [1.0, 3.0, 10.0, 30.0, 100.0, 1e3, 1e4] {
        for delta in [0.0, 1e-16, 1e-13, 1e-10, 1e-7, 1e-4, 1e-2] {
            let mut pairs = vec![];
            for i in 0..200 {
                let q1 = needle(&mut rng, aspect);
                let q2 = if i % 2 == 0 {
                    q1.map(|x| x * (1.0 + delta * rng.random_range(-1.0..1.0)))
                } else {
                    let rot = nalgebra::Rotation3::from_scaled_axis(nalgebra::Vector3::from_fn(
                        |_, _| delta * rng.random_range(-1.0..1.0),
                    ));
                    rotate(&rot, &([0.0; 3], q1, q1)).1
                };
                let z = 2.0 * rng.random::<f64>() - 1.0;
                let phi = 6.28 * rng.random::<f64>();
                let rr = (1.0 - z * z).sqrt();
                let dir = [rr * phi.cos(), rr * phi.sin(), z];
                let Ok(c) = contact_function(&dir, &q1, &q2) else { continue };
                let s = (10f64.powf(rng.random_range(-1.0..1.0)) / c.mu2).sqrt();
                pairs.push((dir.map(|x| x * s), q1, q2));
            }
            report(&format!("A={aspect:e} d={delta:e}"), &pairs);
        }
    }
}

#[test]
#[ignore]
fn size_ratio() {
    let rows = reference_rows("contact_extreme.csv");
    let mut v: Vec<_> = rows[215..430].iter().map(|(c, mu2, lam)| {
        let f = contact_function_fast(&c.r12, &c.q1, &c.q2).unwrap();
        (((f.mu2 - mu2) / mu2).abs(), c.clone(), *mu2, *lam, f)
    }).collect();
    v.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (err, c, mu2, lam, f) in v.iter().take(6) {
        let p = Prepared::new(&c.r12, &c.q1, &c.q2).unwrap();
        let parts = PencilParts::new(&p.q1, &p.q2);
        let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
        let rat = Rational::new(&p.r, &p.q1, &p.q2, &parts, [p.l1.det(), p.l2.det(), a, b]);
        let refiner = super::refine::Refiner::new(&p, &parts, &rat);
        let fr = refiner.at(f.lambda).map(|v| v.f);
        let fr_ref = refiner.at(*lam).map(|v| v.f);
        let ff_ref = rat.f(*lam);
        println!("err {err:.2e} lam {} ref {} it {} | f_fast(l) {:.3e} refined(l) {:?} refined(lref) {:?} fast(lref) {:.3e}",
            f.lambda, lam, f.iterations, (rat.f(f.lambda)-mu2)/mu2, fr.map(|x| (x-mu2)/mu2), fr_ref.map(|x| (x-mu2)/mu2), (ff_ref-mu2)/mu2);
    }
}
