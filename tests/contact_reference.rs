//! Accuracy of the contact methods against the mpmath references in `tests/data`
//! (made by `tools/make_contact_reference.py`, ≥ 50 correct digits): the typical and
//! extreme sets, and the degenerate one (semi-definite forms, sizes up to 1e150 apart),
//! which only the contact functions take.

use grainpack::contact::{
    contact_function, contact_function_fast, contact_functions, contact_functions_fast,
    contact_geometry, fast_condition, overlaps, overlaps_prepared, wang, Ellipsoid,
    PreparedEllipsoid, Stop, FAST_MAX_CONDITION, FAST_ROUNDING, FAST_TOL, GAIN_TOL,
};
use grainpack::io::cases::{Case, CaseTable};
use std::collections::BTreeMap;

struct Row {
    case: Case,
    mu2: f64,
    category: String,
}

fn load(name: &str) -> Vec<Row> {
    let path = format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"));
    let table = CaseTable::read(std::fs::File::open(&path).unwrap()).unwrap();
    let has_category = table.column("category").is_some();
    (0..table.rows.len())
        .map(|i| Row {
            case: table.case(i).unwrap(),
            mu2: table.number(i, "mu2").unwrap(),
            category: if has_category {
                let (_, record) = table.rows[i].as_ref().unwrap();
                record[table.column("category").unwrap()].to_string()
            } else {
                "typical".into()
            },
        })
        .collect()
}

/// Largest relative error of μ² per category.
fn max_errors(rows: &[Row], f: impl Fn(&Case) -> f64) -> BTreeMap<String, f64> {
    let mut worst = BTreeMap::new();
    for row in rows {
        let err = ((f(&row.case) - row.mu2) / row.mu2).abs();
        let w = worst.entry(row.category.clone()).or_insert(0.0f64);
        *w = w.max(err);
    }
    worst
}

/// The accurate methods' error on every row of every set: a few ulps. Measured at most
/// 3.6e-16 (1.6 ε); 1e-15 (4.5 ε) catches a corrector that stops a step early, as it
/// would near λ = 0 or 1 with the quadratic gain test alone (7.8e-15 there).
const ACCURATE_TOL: f64 = 1e-15;

/// The three reference files.
const SETS: [&str; 3] = [
    "contact_typical.csv",
    "contact_extreme.csv",
    "contact_degenerate.csv",
];

fn accurate(c: &Case) -> f64 {
    let out = contact_function(&c.r12, &c.q1, &c.q2).unwrap();
    assert_ne!(out.stop, Stop::MaxIterations, "line {}", c.line);
    out.mu2
}

#[test]
fn contact_function_is_within_1e_14_on_the_typical_set() {
    let rows = load("contact_typical.csv");
    assert_eq!(rows.len(), 1000);
    let worst = max_errors(&rows, accurate)["typical"];
    assert!(worst <= 1e-14, "max relative error {worst:e}");
}

#[test]
fn contact_function_is_within_1e_12_on_every_extreme_category() {
    let rows = load("contact_extreme.csv");
    let worst = max_errors(&rows, accurate);
    assert_eq!(worst.len(), 8, "{worst:?}");
    for (category, err) in &worst {
        assert!(*err <= 1e-12, "{category}: max relative error {err:e}");
    }
}

#[test]
fn contact_function_is_within_a_few_ulps_on_every_set() {
    for name in SETS {
        for (category, err) in max_errors(&load(name), accurate) {
            assert!(
                err <= ACCURATE_TOL,
                "{name}, {category}: max relative error {err:e}"
            );
        }
    }
}

#[test]
fn the_degenerate_set_has_its_two_categories_and_exact_ends() {
    let rows = load("contact_degenerate.csv");
    let worst = max_errors(&rows, accurate);
    assert_eq!(
        worst.keys().collect::<Vec<_>>(),
        ["huge_ratio", "semi_definite"]
    );
    // Some semi-definite pairs have their maximum at an end, in closed form.
    let exact = rows
        .iter()
        .filter(|r| {
            let c = &r.case;
            contact_function(&c.r12, &c.q1, &c.q2).unwrap().stop == Stop::Exact
        })
        .count();
    assert!(exact > 0 && exact < rows.len(), "{exact}");
}

/// `contact_function_fast` (and `contact_functions_fast`, bitwise the same) on every
/// row of every set: never an error above [`FAST_TOL`] when converged, and the
/// bound by the condition number where it answers the pair itself
/// (`κ ≤ FAST_MAX_CONDITION`): rounding `FAST_ROUNDING · ε · κ` and the truncation the
/// stopping test allows, [`GAIN_TOL`]. A pair it hands over (`κ` larger, forms not
/// definite enough to factor, sizes too far apart) has the accurate method's error.
#[test]
fn fast_methods_meet_their_stated_bound_on_every_row() {
    for name in SETS {
        let rows = load(name);
        let pairs: Vec<_> = rows
            .iter()
            .map(|r| (r.case.r12, r.case.q1, r.case.q2))
            .collect();
        let lanes = contact_functions_fast(&pairs);
        for (row, lane) in rows.iter().zip(&lanes) {
            let c = &row.case;
            let fast = contact_function_fast(&c.r12, &c.q1, &c.q2).unwrap();
            assert_eq!(lane.as_ref().unwrap(), &fast, "{name} line {}", c.line);
            assert_ne!(fast.stop, Stop::MaxIterations, "{name} line {}", c.line);
            let err = ((fast.mu2 - row.mu2) / row.mu2).abs();
            assert!(err <= FAST_TOL, "{name} line {}: {err:e}", c.line);
            let bound = match fast_condition(&c.r12, &c.q1, &c.q2) {
                Ok(k) if k <= FAST_MAX_CONDITION => FAST_ROUNDING * f64::EPSILON * k + GAIN_TOL,
                _ => ACCURATE_TOL,
            };
            assert!(
                err <= bound,
                "{name} line {} ({}): {err:e} > {bound:e}",
                c.line,
                row.category
            );
        }
    }
}

/// The double-precision method errs by about ε·cond(Q(λ*)): cond stays below 1e4
/// on the typical set (semi-axes 0.1–10), so 1e-11 bounds it with room for the
/// constant, and a regression to a sloppier stopping rule would show.
#[test]
fn fast_contact_function_is_within_1e_11_on_the_typical_set() {
    let rows = load("contact_typical.csv");
    let worst = max_errors(&rows, |c| {
        contact_function_fast(&c.r12, &c.q1, &c.q2).unwrap().mu2
    });
    assert!(worst["typical"] <= 1e-11, "{worst:?}");
}

#[test]
fn overlaps_agrees_with_the_reference_sign_away_from_tangency() {
    for name in ["contact_typical.csv", "contact_extreme.csv"] {
        for row in load(name) {
            if (row.mu2 - 1.0).abs() <= 1e-12 {
                continue;
            }
            let c = &row.case;
            let prepare =
                |q| PreparedEllipsoid::new(&Ellipsoid::from_quadratic_form(q).unwrap()).unwrap();
            let (p1, p2) = (prepare(c.q1), prepare(c.q2));
            assert_eq!(
                overlaps_prepared(&c.r12, &p1, &p2).unwrap(),
                row.mu2 < 1.0,
                "prepared: {name} line {}",
                c.line
            );
            assert_eq!(
                overlaps(&c.r12, &c.q1, &c.q2).unwrap(),
                row.mu2 < 1.0,
                "{name} line {} ({}), mu2 = {}",
                c.line,
                row.category,
                row.mu2
            );
        }
    }
}

/// `overlaps` on the degenerate set: semi-definite forms (where μ² is defined) and
/// sizes up to 1e150 apart are decided, as the reference decides them away from
/// tangency (it misjudged 16 `huge_ratio` pairs and refused the semi-definite ones
/// before), and so is `overlaps_prepared` on every row, semi-definite forms prepared by
/// [`PreparedEllipsoid::from_quadratic_form`].
#[test]
fn overlaps_decides_the_degenerate_set() {
    let mut wrong = vec![];
    let mut prepared = 0;
    for row in load("contact_degenerate.csv") {
        if (row.mu2 - 1.0).abs() <= 1e-12 {
            continue;
        }
        let c = &row.case;
        let answer = overlaps(&c.r12, &c.q1, &c.q2);
        if answer != Ok(row.mu2 < 1.0) {
            wrong.push(format!(
                "line {} ({}): {answer:?}, mu2 = {}",
                c.line, row.category, row.mu2
            ));
        }
        let prepare = |q| PreparedEllipsoid::from_quadratic_form(&q).unwrap();
        prepared += 1;
        let answer = overlaps_prepared(&c.r12, &prepare(c.q1), &prepare(c.q2));
        if answer != Ok(row.mu2 < 1.0) {
            wrong.push(format!(
                "prepared, line {} ({}): {answer:?}, mu2 = {}",
                c.line, row.category, row.mu2
            ));
        }
    }
    assert!(
        wrong.is_empty(),
        "{} wrong:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    assert!(prepared > 400, "{prepared}");
}

/// `contact_geometry` on the degenerate set: semi-definite forms give μ² as the
/// contact function does, a unit normal and a gap of the sign of `μ − 1`; where the
/// second form is definite by a margin, the point lies on it scaled by μ and the normal
/// is its outward one there. Sizes far apart (`huge_ratio`) are answered the same way,
/// also where λ* rounds to 0 or 1 (the point takes `1 − λ*` from the path that carries
/// it; these ~40 rows were refused with a typed overflow before).
#[test]
fn contact_geometry_takes_the_degenerate_set() {
    let mut refused = vec![];
    for row in load("contact_degenerate.csv") {
        let c = &row.case;
        let g = match contact_geometry(&c.r12, &c.q1, &c.q2) {
            Ok(g) => g,
            Err(e) => {
                refused.push(format!("line {} ({}): {e}", c.line, row.category));
                continue;
            }
        };
        assert_eq!(g.mu2, accurate(c), "line {}", c.line);
        let n = g.normal;
        let norm = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!(
            (norm - 1.0).abs() <= 4.0 * f64::EPSILON,
            "line {}: {n:?}",
            c.line
        );
        assert_eq!(g.gap > 0.0, g.mu2 > 1.0, "line {}: {}", c.line, g.gap);
        let q2 = nalgebra::Matrix3::new(
            c.q2[0], c.q2[1], c.q2[2], c.q2[1], c.q2[3], c.q2[4], c.q2[2], c.q2[4], c.q2[5],
        );
        // Definite by a margin (discs may factor by rounding), of moderate size.
        let eig = q2.symmetric_eigenvalues();
        if row.category != "semi_definite" || eig.min() <= 1e-6 * eig.max() {
            continue;
        }
        let chol = q2.cholesky().unwrap();
        // On the surface of the second ellipsoid scaled by μ, normal outward there.
        let x2 = nalgebra::Vector3::from(g.point) - nalgebra::Vector3::from(c.r12);
        let v = chol.solve(&x2);
        let h2 = x2.dot(&v);
        assert!(
            (h2 - g.mu2).abs() <= 1e-8 * g.mu2,
            "line {}: {h2} {}",
            c.line,
            g.mu2
        );
        let dir = -v.normalize();
        let along = dir.dot(&nalgebra::Vector3::from(n));
        assert!(along > 1.0 - 1e-8, "line {}: {along}", c.line);
    }
    assert!(
        refused.is_empty(),
        "{}:\n{}",
        refused.len(),
        refused.join("\n")
    );
}

/// Wang–Wang–Kim is fragile near tangency; away from it (|μ²−1| > 1e-3) on the
/// typical set it must agree with the reference.
#[test]
fn wang_agrees_with_the_reference_away_from_tangency_on_the_typical_set() {
    for row in load("contact_typical.csv") {
        if (row.mu2 - 1.0).abs() <= 1e-3 {
            continue;
        }
        let c = &row.case;
        assert_eq!(
            wang::separated(&c.r12, &c.q1, &c.q2).unwrap(),
            row.mu2 > 1.0,
            "line {}, mu2 = {}",
            c.line,
            row.mu2
        );
    }
}

/// `contact_functions`, eight pairs at a time, is within a few ulps on every
/// category of every set, like the accurate method: stricter than the 1e-14 (typical)
/// and 1e-12 (extreme) asked for.
#[test]
fn contact_functions_are_within_a_few_ulps_on_every_set() {
    for name in SETS {
        let rows = load(name);
        let pairs: Vec<_> = rows
            .iter()
            .map(|r| (r.case.r12, r.case.q1, r.case.q2))
            .collect();
        let values = contact_functions(&pairs);
        let mut worst = BTreeMap::new();
        for (row, value) in rows.iter().zip(&values) {
            let c = value.as_ref().unwrap();
            assert_ne!(c.stop, Stop::MaxIterations, "line {}", row.case.line);
            let err = ((c.mu2 - row.mu2) / row.mu2).abs();
            let w = worst.entry(row.category.as_str()).or_insert(0.0f64);
            *w = w.max(err);
        }
        for (category, err) in worst {
            assert!(err <= ACCURATE_TOL, "{name}, {category}: {err:e}");
        }
    }
}
