//! `pack contact`: the contact function over a CSV of pairs.

use anyhow::{Context, Result};
use grainpack::contact::Method;
use grainpack::io::atomic::write_atomically;
use grainpack::io::cases::{write_answers, CaseTable};
use std::fs::File;
use std::io::{self, Write};
use std::path::Path;

/// Runs the subcommand; returns the number of bad rows.
pub fn run(cases: &Path, method: Method, output: Option<&Path>, time: bool) -> Result<usize> {
    let name = cases.display().to_string();
    let table = if name == "-" {
        CaseTable::read(io::stdin().lock())
    } else {
        let file = File::open(cases).with_context(|| format!("cannot open {name}"))?;
        CaseTable::read(file)
    }
    .with_context(|| format!("{name}: cannot read cases"))?;

    let answers = table.answers(method);
    let bad = answers.iter().filter(|a| a.is_err()).count();
    for error in answers.iter().filter_map(|a| a.as_ref().err()) {
        eprintln!("pack contact: {name}: {error}");
    }
    let write = |out: &mut dyn Write| write_answers(out, &table, method, &answers);
    match output {
        Some(path) => write_atomically(path, |w| write(w))
            .with_context(|| format!("cannot write {}", path.display()))?,
        None => write(&mut io::stdout().lock()).context("cannot write to standard output")?,
    }

    if time {
        let pairs = table.pairs();
        let t = method.time(&pairs, 5, 0.2);
        eprintln!(
            "{}",
            serde_json::json!({
                "method": method.name(),
                "cases": pairs.len(),
                "rounds": t.rounds,
                "ns_per_call_median": t.ns_per_call_median,
                "ns_per_call_min": t.ns_per_call_min,
            })
        );
    }
    Ok(bad)
}
