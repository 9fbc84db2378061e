//! End-to-end tests of `pack contact`: the binary, its files and its exit codes.

mod support;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn pack(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pack"))
        .args(args)
        .output()
        .unwrap()
}

fn scratch(name: &str) -> PathBuf {
    support::files::scratch("cli", name)
}

const HEADER: &str = "r0,r1,r2,q1_0,q1_1,q1_2,q1_3,q1_4,q1_5,q2_0,q2_1,q2_2,q2_3,q2_4,q2_5";

fn write_cases(dir: &Path, rows: &[&str]) -> PathBuf {
    let path = dir.join("cases.csv");
    std::fs::write(&path, format!("{HEADER},label\n{}\n", rows.join("\n"))).unwrap();
    path
}

/// Two unit spheres 3 apart: μ² = (3/2)² exactly.
const SPHERES: &str = "3,0,0,1,0,0,1,0,1,1,0,0,1,0,1,a";
/// The pw85 manual's worked example (with pw85's rounding of the flat spheroid).
const PW85: &str = "0.7,-0.7,1.1,100,0,0,100,0,0.010000000000005116,25,0,0,0.25,0,0.25,b";

#[test]
fn contact_writes_inputs_and_results_with_17_digits() {
    let dir = scratch("ok");
    let cases = write_cases(&dir, &[SPHERES, PW85]);
    let out = dir.join("out.csv");
    let run = pack(&[
        "contact",
        cases.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        format!("{HEADER},label,mu2,lambda,stop")
    );
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(first[15], "a");
    assert_eq!(first[16], "2.2500000000000000e0");
    assert_eq!(first[18], "Converged");
    let second: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mu2: f64 = second[16].parse().unwrap();
    // The manual prints 3.362706040638343; our value is good to a few ulps.
    assert!(
        (mu2 - 3.362706040638343).abs() < 4.0 * f64::EPSILON * mu2,
        "{mu2}"
    );
    assert_eq!(second[16].len(), "3.3627060406383430e0".len());
}

#[test]
fn decision_methods_write_an_overlap_column() {
    let dir = scratch("decide");
    let cases = write_cases(&dir, &[SPHERES, "1,0,0,1,0,0,1,0,1,1,0,0,1,0,1,c"]);
    for method in ["overlap", "wang"] {
        let run = pack(&["contact", cases.to_str().unwrap(), "--method", method]);
        assert!(run.status.success());
        let text = String::from_utf8(run.stdout).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].ends_with(",label,overlap"), "{}", lines[0]);
        assert!(
            lines[1].ends_with(",a,false") && lines[2].ends_with(",c,true"),
            "{method}: {text}"
        );
    }
}

#[test]
fn a_bad_row_is_named_marked_and_spares_the_others() {
    let dir = scratch("bad");
    let cases = write_cases(
        &dir,
        &[
            SPHERES,
            "1,0,0,-1,0,0,1,0,1,1,0,0,1,0,1,neg",
            "1,x,0,1,0,0,1,0,1,1,0,0,1,0,1,nan",
            PW85,
        ],
    );
    let out = dir.join("out.csv");
    let run = pack(&[
        "contact",
        cases.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("line 3: q1 is not positive definite"), "{err}");
    assert!(
        err.contains("line 4: column r1: \"x\" is not a number"),
        "{err}"
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].ends_with(",mu2,lambda,stop,error"));
    assert!(lines[1].contains(",a,2.25"), "{}", lines[1]);
    assert!(
        lines[2].contains(",neg,,,,line 3: q1 is not positive definite"),
        "{}",
        lines[2]
    );
    assert!(lines[4].contains(",b,3.36270604063834"), "{}", lines[4]);
}

#[test]
fn missing_columns_or_files_fail_cleanly_and_write_nothing() {
    let dir = scratch("missing");
    let path = dir.join("short.csv");
    std::fs::write(&path, "r0,r1\n1,2\n").unwrap();
    let out = dir.join("out.csv");
    let run = pack(&[
        "contact",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains("short.csv") && err.contains("r2, q1_0"),
        "{err}"
    );
    assert!(!out.exists());
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "no stray temporary file"
    );
    let run = pack(&["contact", dir.join("absent.csv").to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("absent.csv"));
    let run = pack(&["contact", path.to_str().unwrap(), "--method", "brent"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("unknown method \"brent\""));
}

#[test]
fn time_prints_one_json_line_with_the_rounds() {
    let dir = scratch("time");
    let cases = write_cases(&dir, &[SPHERES, PW85]);
    let run = pack(&[
        "contact",
        cases.to_str().unwrap(),
        "--method",
        "fast",
        "--time",
        "-o",
        dir.join("o.csv").to_str().unwrap(),
    ]);
    assert!(run.status.success());
    let err = String::from_utf8(run.stderr).unwrap();
    let json: serde_json::Value = serde_json::from_str(err.trim()).unwrap();
    assert_eq!(json["method"], "fast");
    assert_eq!(json["cases"], 2);
    assert!(json["rounds"].as_u64().unwrap() >= 5);
    assert!(
        json["ns_per_call_min"].as_f64().unwrap() <= json["ns_per_call_median"].as_f64().unwrap()
    );
}

/// `--method batch` writes the same file as `--method accurate`, bad rows included:
/// the reference set with two bad rows among its 1000 pairs.
#[test]
fn batch_writes_what_accurate_writes() {
    let dir = scratch("batch");
    let reference = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/contact_typical.csv");
    let mut text = std::fs::read_to_string(reference).unwrap();
    let columns = text.lines().next().unwrap().split(',').count();
    let bad_row = |first: &str| {
        let mut fields = vec!["1"; columns];
        fields[0] = first;
        fields[3] = "-1";
        fields.join(",") + "\n"
    };
    text.push_str(&bad_row("1"));
    text.push_str(&bad_row("x"));
    let cases = dir.join("cases.csv");
    std::fs::write(&cases, text).unwrap();
    let mut outputs = vec![];
    for method in ["accurate", "batch"] {
        let out = dir.join(format!("{method}.csv"));
        let run = pack(&[
            "contact",
            cases.to_str().unwrap(),
            "--method",
            method,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(run.status.code(), Some(2), "{method}");
        outputs.push(std::fs::read_to_string(out).unwrap());
    }
    assert_eq!(outputs[0].lines().count(), 1003);
    assert!(outputs[0] == outputs[1], "batch and accurate differ");
}

const HEADER_2D: &str = "r0,r1,q1_0,q1_1,q1_2,q2_0,q2_1,q2_2";

/// A 2D file: ellipses, read as the 3D pair they embed as; the same columns out.
#[test]
fn contact_reads_a_2d_file_with_the_same_output_columns() {
    let dir = scratch("plane");
    let cases = dir.join("cases.csv");
    // Two unit circles 3 apart (μ² = 9/4), and a circle of radius 2 and a point at
    // (1, 1): μ² = rᵀQ⁻¹r = 2/4 at λ = 0.
    let text = format!("{HEADER_2D},label\n3,0,1,0,1,1,0,1,a\n1,1,4,0,4,0,0,0,p\n");
    std::fs::write(&cases, text).unwrap();
    for method in ["accurate", "batch", "fast", "batch-fast", "rational"] {
        let run = pack(&["contact", cases.to_str().unwrap(), "--method", method]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let text = String::from_utf8(run.stdout).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], format!("{HEADER_2D},label,mu2,lambda,stop"));
        assert_eq!(
            lines[1],
            "3,0,1,0,1,1,0,1,a,2.2500000000000000e0,5.0000000000000000e-1,Converged"
        );
        let point: Vec<&str> = lines[2].split(',').collect();
        let mu2: f64 = point[9].parse().unwrap();
        assert!(
            (mu2 - 0.5).abs() <= 4.0 * f64::EPSILON,
            "{method}: {}",
            lines[2]
        );
    }
    for method in ["overlap", "wang"] {
        let run = pack(&["contact", cases.to_str().unwrap(), "--method", method]);
        let text = String::from_utf8(run.stdout).unwrap();
        assert!(
            text.contains(",a,false\n") && text.contains(",p,true\n"),
            "{text}"
        );
    }
}

/// Bad 2D rows are named by line and by the 2D column or entry, and spare the others.
#[test]
fn a_bad_2d_row_names_the_2d_entry() {
    let dir = scratch("plane_bad");
    let cases = dir.join("cases.csv");
    let rows = [
        "3,0,1,0,1,1,0,1,a",
        "3,0,1,0,1,1,0,-1,neg",
        "3,0,1,0,1,1,0,inf,inf",
        "3,0,1,0,1,1,y,1,text",
        "3,0,1,0,0,1,0,0,parallel",
    ];
    std::fs::write(&cases, format!("{HEADER_2D},label\n{}\n", rows.join("\n"))).unwrap();
    let out = dir.join("out.csv");
    let run = pack(&[
        "contact",
        cases.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    for want in [
        "line 3: q2 is not positive definite: pivot 1",
        "line 4: q2[2] is not finite: inf",
        "line 5: column q2_1: \"y\" is not a number",
        "line 6: q1 and q2 are both singular along a common direction",
    ] {
        assert!(err.contains(want), "{want}: {err}");
    }
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(
        lines[0].ends_with(",label,mu2,lambda,stop,error"),
        "{}",
        lines[0]
    );
    assert!(lines[1].contains(",a,2.25"), "{}", lines[1]);
    assert_eq!(lines.len(), 6);
}

/// A header that is neither 2D nor 3D names what each lacks.
#[test]
fn a_2d_header_lacking_a_column_is_named() {
    let dir = scratch("plane_header");
    let cases = dir.join("cases.csv");
    std::fs::write(&cases, "r0,r1,q1_0,q1_1,q1_2,q2_0,q2_1\n1,0,1,0,1,1,0\n").unwrap();
    let run = pack(&["contact", cases.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2), "{run:?}");
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("q2_2 (ellipses)"), "{err}");
    assert!(run.stdout.is_empty());
}
