//! The 2D part of the contact report: the ellipse functions (`contact_function_2d`,
//! its fast and batch forms, `overlaps_2d`) and the algebraic test
//! `wang::separated_2d` on the 2D reference sets, with the 3D function on the
//! embedded pairs for the cost of the embedding.

use super::{row, stats, Answers, Set, HEADER, MIN_ROUNDS, MIN_SECONDS, WARM_UP_SECONDS};
use grainpack::contact::{
    contact_function, contact_function_2d, contact_function_fast_2d, contact_functions_2d,
    contact_functions_fast_2d, embed_pair, overlaps_2d, wang, Contact, ContactError, Sym2, Vec2,
};
use grainpack::io::cases::CaseTable;
use std::hint::black_box;
use std::time::Instant;

type Pair2 = (Vec2, Sym2, Sym2);

/// A 2D reference set: the pairs as given, and as a [`Set`] of embedded pairs for the
/// statistics.
fn load(name: &'static str, file: &str) -> (Vec<Pair2>, Set) {
    let path = format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let table = CaseTable::read(std::fs::File::open(path).unwrap()).unwrap();
    let col = table.column("category");
    let mut set = Set {
        name,
        pairs: vec![],
        mu2: vec![],
        category: vec![],
    };
    let mut plane = vec![];
    for i in 0..table.rows.len() {
        let c = table.case(i).unwrap();
        plane.push((
            [c.r12[0], c.r12[1]],
            [c.q1[0], c.q1[1], c.q1[3]],
            [c.q2[0], c.q2[1], c.q2[3]],
        ));
        set.pairs.push((c.r12, c.q1, c.q2));
        set.mu2.push(table.number(i, "mu2").unwrap());
        let (_, record) = table.rows[i].as_ref().unwrap();
        set.category
            .push(col.map_or("typical".into(), |k| record[k].to_string()));
    }
    (plane, set)
}

/// What is timed: one pass over the pairs, returning the answers.
enum Subject {
    One(
        &'static str,
        fn(&Vec2, &Sym2, &Sym2) -> Result<Contact, ContactError>,
    ),
    Many(
        &'static str,
        fn(&[Pair2]) -> Vec<Result<Contact, ContactError>>,
    ),
    Decision(
        &'static str,
        fn(&Vec2, &Sym2, &Sym2) -> Result<bool, ContactError>,
    ),
}

fn embedded(r: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<Contact, ContactError> {
    let (r, a, b) = embed_pair(r, q1, q2);
    contact_function(&r, &a, &b)
}

fn overlapping(r: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<bool, ContactError> {
    overlaps_2d(r, q1, q2)
}

/// An undecided pair counts as an error of the test (the `errors` column).
fn wang_overlapping(r: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<bool, ContactError> {
    match wang::separated_2d(r, q1, q2)? {
        Some(apart) => Ok(!apart),
        None => Err(ContactError::NotConverged { iterations: 0 }),
    }
}

const SUBJECTS: [Subject; 7] = [
    Subject::One("accurate 2d", contact_function_2d),
    Subject::Many("batch 2d", contact_functions_2d),
    Subject::One("fast 2d", contact_function_fast_2d),
    Subject::Many("batch-fast 2d", contact_functions_fast_2d),
    Subject::One("accurate, embedded by hand", embedded),
    Subject::Decision("overlap 2d", overlapping),
    Subject::Decision("wang 2d (undecided: errors)", wang_overlapping),
];

/// One pass of `subject` over `pairs`: μ² or the decision per pair.
fn answer(subject: &Subject, pairs: &[Pair2]) -> Answers {
    match subject {
        Subject::One(_, f) => Answers::Values(
            (pairs.iter())
                .map(|(r, a, b)| black_box(f(r, a, b)).ok().map(|c| c.mu2))
                .collect(),
        ),
        Subject::Many(_, f) => Answers::Values(
            (black_box(f(pairs)).into_iter())
                .map(|c| c.ok().map(|c| c.mu2))
                .collect(),
        ),
        Subject::Decision(_, f) => Answers::Decisions(
            (pairs.iter())
                .map(|(r, a, b)| black_box(f(r, a, b)).ok())
                .collect(),
        ),
    }
}

/// Median over rounds of the mean ns per pair of a pass, after warming up.
fn time(subject: &Subject, pairs: &[Pair2]) -> f64 {
    let start = Instant::now();
    while start.elapsed().as_secs_f64() < WARM_UP_SECONDS {
        black_box(answer(subject, black_box(pairs)));
    }
    let mut per_call = vec![];
    let start = Instant::now();
    while per_call.len() < MIN_ROUNDS || start.elapsed().as_secs_f64() < MIN_SECONDS {
        let t = Instant::now();
        black_box(answer(subject, black_box(pairs)));
        per_call.push(t.elapsed().as_nanos() as f64 / pairs.len() as f64);
    }
    per_call.sort_by(f64::total_cmp);
    per_call[per_call.len() / 2]
}

/// The 2D tables, by set and by category of the extreme set (the decisions' timings
/// include building the `Answers`, as the 3D ones do not: a few ns).
pub fn report() -> String {
    let sets = [
        load("typical 2D", "contact_plane_typical.csv"),
        load("extreme 2D", "contact_plane_extreme.csv"),
    ];
    let mut out = String::from(HEADER);
    let mut by_category = String::new();
    for (pairs, set) in &sets {
        for subject in &SUBJECTS {
            let (Subject::One(name, _) | Subject::Many(name, _) | Subject::Decision(name, _)) =
                subject;
            let decision = matches!(subject, Subject::Decision(..));
            let ns = time(subject, pairs);
            let answers = answer(subject, pairs);
            out.push_str(&row(
                name,
                set.name,
                Some(ns),
                &stats(&answers, set, |_| true),
                decision,
            ));
            if set.category.iter().any(|c| c != "typical") {
                let mut cats: Vec<&String> = set.category.iter().collect();
                cats.sort();
                cats.dedup();
                for cat in cats {
                    let s = stats(&answers, set, |i| &set.category[i] == cat);
                    by_category.push_str(&row(name, cat, None, &s, decision));
                }
            }
        }
    }
    out.push_str("\nExtreme 2D set by category:\n\n");
    out.push_str(HEADER);
    out.push_str(&by_category);
    out
}
