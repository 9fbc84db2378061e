//! Error against run time of every contact method on the reference sets.
//!
//! `cargo bench --bench contact --features hoomd-baseline` prints the tables, rewrites
//! the contact section of `BENCHMARKS.md` (between its markers) and draws
//! `docs/contact_error_vs_time.png`.
//! Set `CONTACT_BENCH_DRY=1` to print only, `CONTACT_BENCH_SETS=2d` to run (and rewrite)
//! only the 2D part (its own section of `BENCHMARKS.md`; the plot is left as it is).

mod common;
mod contact_plane;
mod contact_report;

use contact_report::{plot, row, stats, HEADER};
use grainpack::contact::{overlaps_prepared, Answer, Method, PreparedEllipsoid, Sym3, Vec3};
use grainpack::io::cases::CaseTable;
use hoomd_geometry::{shape::Ellipsoid as HoomdEllipsoid, Convex, IntersectsAt};
use hoomd_vector::{Cartesian, Quaternion, Versor};
use nalgebra::{Matrix3, SymmetricEigen, UnitQuaternion};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

/// Pairs with |μ² − 1| at most this are too close to tangency for a yes/no answer to
/// be judged; decisions are checked on the others (as the issue asks: 1e-12).
const TANGENCY: f64 = 1e-12;
const MIN_ROUNDS: usize = 5;
const MIN_SECONDS: f64 = 0.2;
/// Untimed passes before each subject is timed, so that the first one timed does not
/// pay for the clock ramping up and cold caches (measured: +10 % on the first).
const WARM_UP_SECONDS: f64 = 0.05;

struct Set {
    name: &'static str,
    pairs: Vec<(Vec3, Sym3, Sym3)>,
    mu2: Vec<f64>,
    category: Vec<String>,
}

fn load(name: &'static str, file: &str) -> Set {
    let path = format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let table = CaseTable::read(std::fs::File::open(path).unwrap()).unwrap();
    let col = table.column("category");
    let mut set = Set {
        name,
        pairs: vec![],
        mu2: vec![],
        category: vec![],
    };
    for i in 0..table.rows.len() {
        let c = table.case(i).unwrap();
        set.pairs.push((c.r12, c.q1, c.q2));
        set.mu2.push(table.number(i, "mu2").unwrap());
        let (_, record) = table.rows[i].as_ref().unwrap();
        set.category
            .push(col.map_or("typical".into(), |k| record[k].to_string()));
    }
    set
}

/// A method under test: ours by name, or hoomd-geometry's XenoCollide overlap test.
#[derive(Clone, Copy)]
enum Subject {
    Ours(Method),
    /// `overlaps_prepared` on shapes prepared outside the timing, as hoomd's are.
    Prepared,
    Hoomd,
}

impl Subject {
    fn name(self) -> String {
        match self {
            Subject::Ours(m) => m.name().to_string(),
            Subject::Prepared => "overlap (prepared)".into(),
            Subject::Hoomd => "hoomd-geometry".into(),
        }
    }
    fn is_decision(self) -> bool {
        match self {
            Subject::Ours(m) => m.is_decision(),
            Subject::Prepared | Subject::Hoomd => true,
        }
    }
}

/// One pair in hoomd's terms: both shapes, and the second's position and orientation
/// in the frame of the first.
struct HoomdPair {
    a: Convex<HoomdEllipsoid>,
    b: Convex<HoomdEllipsoid>,
    v: Cartesian<3>,
    o: Versor,
}

/// Semi-axes and a proper rotation (columns = axes) of `Q`.
fn principal(q: &Sym3) -> ([f64; 3], Matrix3<f64>) {
    let m = Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5]);
    let eig = SymmetricEigen::new(m);
    let mut rot = eig.eigenvectors;
    if rot.determinant() < 0.0 {
        rot.set_column(2, &(-rot.column(2)));
    }
    (eig.eigenvalues.map(|v| v.sqrt()).into(), rot)
}

fn hoomd_pair(r: &Vec3, q1: &Sym3, q2: &Sym3) -> Option<HoomdPair> {
    let (a1, r1) = principal(q1);
    let (a2, r2) = principal(q2);
    let shape = |a: [f64; 3]| -> Option<Convex<HoomdEllipsoid>> {
        Some(Convex(HoomdEllipsoid::with_semi_axes([
            a[0].try_into().ok()?,
            a[1].try_into().ok()?,
            a[2].try_into().ok()?,
        ])))
    };
    let v = r1.transpose() * nalgebra::Vector3::from(*r);
    let rel = UnitQuaternion::from_matrix(&(r1.transpose() * r2));
    let o = Quaternion {
        scalar: rel.w,
        vector: [rel.i, rel.j, rel.k].into(),
    }
    .to_versor()
    .ok()?;
    Some(HoomdPair {
        a: shape(a1)?,
        b: shape(a2)?,
        v: [v[0], v[1], v[2]].into(),
        o,
    })
}

/// What a subject answered for each pair: μ² (value methods) or overlap (decisions),
/// `None` for an error.
enum Answers {
    Values(Vec<Option<f64>>),
    Decisions(Vec<Option<bool>>),
}

type PreparedPair = (Vec3, PreparedEllipsoid, PreparedEllipsoid);

/// The pairs prepared for `overlaps_prepared`; `None` where a form is not an ellipsoid
/// it takes (the semi-definite forms of the degenerate set).
fn prepare(set: &Set) -> Vec<Option<PreparedPair>> {
    // Semi-definite forms too (issue 12): they have no factors, and their pairs go to
    // `overlaps`.
    let p = |q: &Sym3| PreparedEllipsoid::from_quadratic_form(q).ok();
    set.pairs
        .iter()
        .map(|(r, q1, q2)| Some((*r, p(q1)?, p(q2)?)))
        .collect()
}

fn answer_all(
    subject: Subject,
    set: &Set,
    hoomd: &[Option<HoomdPair>],
    prepared: &[Option<PreparedPair>],
) -> Answers {
    match subject {
        Subject::Prepared => Answers::Decisions(
            prepared
                .iter()
                .map(|p| {
                    p.as_ref()
                        .and_then(|(r, a, b)| overlaps_prepared(r, a, b).ok())
                })
                .collect(),
        ),
        Subject::Ours(m) if m.is_decision() => Answers::Decisions(
            set.pairs
                .iter()
                .map(|(r, q1, q2)| match m.evaluate(r, q1, q2) {
                    Ok(Answer::Overlap(o)) => Some(o),
                    _ => None,
                })
                .collect(),
        ),
        Subject::Ours(m) => Answers::Values(
            m.evaluate_all(&set.pairs)
                .into_iter()
                .map(|answer| match answer {
                    Ok(Answer::Value { mu2, .. }) => Some(mu2),
                    _ => None,
                })
                .collect(),
        ),
        Subject::Hoomd => Answers::Decisions(
            hoomd
                .iter()
                .map(|p| p.as_ref().map(|p| p.a.intersects_at(&p.b, &p.v, &p.o)))
                .collect(),
        ),
    }
}

/// Median over rounds of the mean ns per call of `f` over `items`, after
/// [`WARM_UP_SECONDS`] of untimed passes.
fn time_each<T>(items: &[T], f: impl Fn(&T) -> bool) -> f64 {
    let start = Instant::now();
    while start.elapsed().as_secs_f64() < WARM_UP_SECONDS {
        for item in items {
            black_box(f(black_box(item)));
        }
    }
    let mut per_call = vec![];
    let start = Instant::now();
    while per_call.len() < MIN_ROUNDS || start.elapsed().as_secs_f64() < MIN_SECONDS {
        let t = Instant::now();
        for item in items {
            black_box(f(black_box(item)));
        }
        per_call.push(t.elapsed().as_nanos() as f64 / items.len() as f64);
    }
    per_call.sort_by(f64::total_cmp);
    per_call[per_call.len() / 2]
}

fn main() {
    let root = env!("CARGO_MANIFEST_DIR");
    let dry = std::env::var_os("CONTACT_BENCH_DRY").is_some();
    let machine = format!(
        "Command: `CONTACT_BENCH_SETS=2d cargo bench --bench contact --features hoomd-baseline`. Machine: {}.\n\n",
        common::machine()
    );
    let plane = format!("{machine}{}", contact_plane::report());
    print!("{plane}");
    if !dry {
        common::update_section(&format!("{root}/BENCHMARKS.md"), "contact-bench-2d", &plane);
    }
    if std::env::var("CONTACT_BENCH_SETS").as_deref() == Ok("2d") {
        return;
    }
    let sets = [
        load("typical", "contact_typical.csv"),
        load("extreme", "contact_extreme.csv"),
        load("degenerate", "contact_degenerate.csv"),
    ];
    let mut subjects: Vec<Subject> = Method::ALL.iter().map(|&m| Subject::Ours(m)).collect();
    subjects.push(Subject::Prepared);
    subjects.push(Subject::Hoomd);

    let mut report = String::new();
    let mut points: Vec<(String, &str, f64, f64)> = vec![];
    let mut by_category = String::new();
    writeln!(
        report,
        "Command: `cargo bench --bench contact --features hoomd-baseline`. Machine: {}.\n",
        common::machine()
    )
    .unwrap();
    report.push_str(HEADER);
    for set in &sets {
        let hoomd: Vec<_> = set
            .pairs
            .iter()
            .map(|(r, q1, q2)| hoomd_pair(r, q1, q2))
            .collect();
        let hoomd_ok: Vec<HoomdPair> = set
            .pairs
            .iter()
            .filter_map(|(r, q1, q2)| hoomd_pair(r, q1, q2))
            .collect();
        let prepared = prepare(set);
        let prepared_ok: Vec<PreparedPair> = prepared.iter().flatten().cloned().collect();
        let mut overlap_ns = None;
        let mut hoomd_ns = None;
        for &subject in &subjects {
            let ns = match subject {
                Subject::Ours(m) => {
                    m.time(&set.pairs, 1, WARM_UP_SECONDS);
                    m.time(&set.pairs, MIN_ROUNDS, MIN_SECONDS)
                        .ns_per_call_median
                }
                Subject::Prepared => time_each(&prepared_ok, |(r, a, b)| {
                    overlaps_prepared(r, a, b).unwrap_or(false)
                }),
                Subject::Hoomd => time_each(&hoomd_ok, |p| p.a.intersects_at(&p.b, &p.v, &p.o)),
            };
            match subject {
                Subject::Prepared => overlap_ns = Some(ns),
                Subject::Hoomd => hoomd_ns = Some(ns),
                _ => {}
            }
            let answers = answer_all(subject, set, &hoomd, &prepared);
            let all = stats(&answers, set, |_| true);
            let name = subject.name();
            report.push_str(&row(&name, set.name, Some(ns), &all, subject.is_decision()));
            if !subject.is_decision() && set.name != "degenerate" {
                points.push((name.clone(), set.name, ns, all.max));
            }
            if set.name != "typical" {
                let mut cats: Vec<&String> = set.category.iter().collect();
                cats.sort();
                cats.dedup();
                for cat in cats {
                    let s = stats(&answers, set, |i| &set.category[i] == cat);
                    by_category.push_str(&row(&name, cat, None, &s, subject.is_decision()));
                }
            }
        }
        // The degenerate set's semi-definite pairs are no ellipsoids for either.
        if let (Some(o), Some(h), false) = (overlap_ns, hoomd_ns, set.name == "degenerate") {
            writeln!(
                by_category,
                "<!-- ratio -->\nOn the {} set, `overlaps_prepared` takes {o:.0} ns per pair and hoomd-geometry's XenoCollide {h:.0} ns (both on shapes prepared beforehand): **{:.1}× faster**.\n",
                set.name,
                h / o
            )
            .unwrap();
        }
    }
    let (ratios, per_category): (Vec<&str>, Vec<&str>) = by_category
        .lines()
        .partition(|l| l.starts_with("On the ") || l.starts_with("<!--"));
    report.push_str("\nExtreme and degenerate sets by category:\n\n");
    report.push_str(HEADER);
    for l in per_category.iter().filter(|l| !l.is_empty()) {
        report.push_str(l);
        report.push('\n');
    }
    report.push('\n');
    for l in ratios.iter().filter(|l| l.starts_with("On the ")) {
        report.push_str(l);
        report.push_str("\n\n");
    }
    print!("{report}");
    if dry {
        return;
    }
    common::update_section(&format!("{root}/BENCHMARKS.md"), "contact-bench", &report);
    plot(&format!("{root}/docs/contact_error_vs_time.png"), &points);
    eprintln!("wrote BENCHMARKS.md (contact section) and docs/contact_error_vs_time.png");
}
