//! Tables from other programs: `pack contact` case files, measured grain tables and
//! orientation (EBSD) files. A bad row is an error naming its line; nothing written
//! holds NaN or infinity where a number is expected.

use super::scene::{check_error, pack_small};
use grainpack::contact::{ContactError, Dimension, Method};
use grainpack::io::cases::{write_answers, CaseError, CaseTable, RowError};
use grainpack::io::scene::SceneError;
use grainpack::scene::Scene;
use std::path::PathBuf;

/// A folder of this process for the data files the scenes name.
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("grainpack-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("the temporary folder is writable");
    dir
}

/// The case file is read; each method answers every row, and the table written back
/// reads as CSV with finite `mu2` and `lambda` wherever a row was answered.
pub fn contact_csv(data: &[u8]) {
    let lines = data.split(|&b| b == b'\n').count() as u64 + 1;
    let in_file = |line: u64| assert!((1..=lines).contains(&line), "line {line} of {lines}");
    let table = match CaseTable::read(data) {
        Ok(t) => t,
        Err(CaseError::Csv { line, .. } | CaseError::NotANumber { line, .. }) => {
            return in_file(line)
        }
        Err(e) => return assert!(!e.to_string().is_empty()),
    };
    for method in Method::ALL {
        let answers = table.answers(method);
        assert_eq!(answers.len(), table.rows.len());
        for answer in &answers {
            match answer {
                Err(RowError::Case(CaseError::Csv { line, .. }))
                | Err(RowError::Case(CaseError::NotANumber { line, .. })) => in_file(*line),
                Err(RowError::Contact { line, source }) => {
                    in_file(*line);
                    in_plane_terms(table.dimension, source);
                }
                _ => {}
            }
        }
        let mut out = Vec::new();
        write_answers(&mut out, &table, method, &answers).expect("writing to memory");
        let mut written = csv::ReaderBuilder::new().from_reader(out.as_slice());
        let header = written.headers().expect("a header is written").clone();
        let numeric: Vec<usize> = (header.iter().enumerate())
            .filter(|(_, h)| ["mu2", "lambda"].contains(h))
            .map(|(i, _)| i)
            .collect();
        let mut count = 0;
        for record in written.records() {
            let record = record.expect("the answers read back as CSV");
            for &i in &numeric {
                let field = &record[i];
                if !field.is_empty() {
                    let x: f64 = field.parse().expect("a written number parses");
                    assert!(x.is_finite(), "{} = {field} written", &header[i]);
                }
            }
            count += 1;
        }
        assert_eq!(count, table.rows.len(), "one written row per row read");
    }
}

/// A 2D file's errors name 2D entries: `r12[0..2]`, `q[0..3]`, pivots 0 and 1.
fn in_plane_terms(dimension: Dimension, error: &ContactError) {
    if dimension != Dimension::Two {
        return;
    }
    match *error {
        ContactError::NotFinite { what, index, .. } => {
            assert!(index < if what == "r12" { 2 } else { 3 }, "{error}");
        }
        ContactError::NotPositiveDefinite { pivot, .. } => assert!(pivot < 2, "{error}"),
        _ => {}
    }
}

/// Validates `scene` (named `scene.toml` beside `file`, whose content is `data`):
/// an error in the data file names the file and a line of it.
fn check_with_file(scene: &str, file: &str, data: &[u8]) {
    let dir = scratch();
    let path = dir.join(file);
    std::fs::write(&path, data).expect("the temporary file is writable");
    let name = dir.join("scene.toml").display().to_string();
    match Scene::from_str(scene, &name) {
        Ok(s) => pack_small(&s),
        Err(SceneError::DataFile(d)) => {
            let lines = data.split(|&b| b == b'\n').count() + 1;
            assert_eq!(d.path, path.display().to_string(), "{d}");
            assert_eq!(d.file, name, "{d}");
            assert!(d.line <= lines, "{d}: {lines} lines");
        }
        Err(e) => check_error(&e, scene, &name),
    }
}

/// The measured table of a one-phase scene; the first byte picks the count, the mode,
/// the phase selected and the box: of three lengths, or two (a 2D scene, whose table
/// is of ellipses: `d` or `a1`, `a2`, `angle`).
pub fn measured_table(data: &[u8]) {
    let (choice, table) = data.split_first().unwrap_or((&0, &[]));
    let count = ["grains = 3", "target_fraction = 0.2"][usize::from(choice & 1)];
    let mode = ["", ", mode = \"draw\"", ", mode = \"exact\""][usize::from(choice >> 1 & 3) % 3];
    let phase = ["", ", phase = 0", ", phase = \"1\""][usize::from(choice >> 3 & 3) % 3];
    let size = ["[40.0, 40.0, 40.0]", "[40.0, 40.0]"][usize::from(choice >> 5 & 1)];
    let scene = format!(
        "{count}\n[box]\nsize = {size}\n[[phase]]\n\
         measured = {{ file = \"grains.csv\"{mode}{phase} }}\n"
    );
    check_with_file(&scene, "grains.csv", table);
}

/// The orientation file of a one-phase scene of spheroids (so that
/// `relative_to_shape` may be set by bit 0 of the first byte); bit 1 picks the box: of
/// three lengths, or two (a 2D scene, whose ellipses take each row's rotation about the
/// plane's normal).
pub fn orientation_file(data: &[u8]) {
    let (choice, table) = data.split_first().unwrap_or((&0, &[]));
    let relative = ["false", "true"][usize::from(choice & 1)];
    let size = ["[20.0, 20.0, 20.0]", "[20.0, 20.0]"][usize::from(choice >> 1 & 1)];
    let scene = format!(
        "grains = 4\n[box]\nsize = {size}\n[[phase]]\n\
         size = {{ distribution = \"constant\", value = 2.0 }}\n\
         aspect_ratio = {{ distribution = \"constant\", value = 1.5 }}\n\
         texture = {{ kind = \"file\", file = \"orientations.csv\", \
         relative_to_shape = {relative} }}\n"
    );
    check_with_file(&scene, "orientations.csv", table);
}
