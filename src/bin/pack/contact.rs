//! `pack contact`: the contact function over a CSV of pairs.

use anyhow::{Context, Result};
use grainpack::contact::{Answer, Method};
use grainpack::io::atomic::write_atomically;
use grainpack::io::cases::{format_17, CaseTable};
use std::fs::File;
use std::io::{self, Write};
use std::path::Path;

/// Columns this command writes; input columns of the same name are not copied.
const RESULT_COLUMNS: [&str; 5] = ["mu2", "lambda", "stop", "overlap", "error"];

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

    let parsed: Vec<_> = (0..table.rows.len()).map(|i| table.case(i)).collect();
    let pairs: Vec<_> = parsed
        .iter()
        .flatten()
        .map(|c| (c.r12, c.q1, c.q2))
        .collect();
    let mut evaluated = method.evaluate_all(&pairs).into_iter();
    let answers: Vec<Result<Answer, String>> = parsed
        .iter()
        .map(|case| match case {
            Ok(c) => evaluated
                .next()
                .expect("one answer per parsed row")
                .map_err(|e| format!("line {}: {e}", c.line)),
            Err(e) => Err(e.to_string()),
        })
        .collect();

    let bad = answers.iter().filter(|a| a.is_err()).count();
    for message in answers.iter().filter_map(|a| a.as_ref().err()) {
        eprintln!("pack contact: {name}: {message}");
    }
    let write = |out: &mut dyn Write| write_table(out, &table, method, &answers, bad > 0);
    match output {
        Some(path) => write_atomically(path, |w| write(w))
            .with_context(|| format!("cannot write {}", path.display()))?,
        None => write(&mut io::stdout().lock()).context("cannot write to standard output")?,
    }

    if time {
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

fn write_table(
    out: &mut dyn Write,
    table: &CaseTable,
    method: Method,
    answers: &[Result<Answer, String>],
    with_error: bool,
) -> io::Result<()> {
    let keep: Vec<usize> = (0..table.headers.len())
        .filter(|&i| !RESULT_COLUMNS.contains(&&table.headers[i]))
        .collect();
    let mut writer = csv::Writer::from_writer(out);
    let mut header: Vec<&str> = keep.iter().map(|&i| &table.headers[i]).collect();
    header.extend(if method.is_decision() {
        &["overlap"][..]
    } else {
        &["mu2", "lambda", "stop"][..]
    });
    if with_error {
        header.push("error");
    }
    writer.write_record(&header)?;
    for (row, answer) in table.rows.iter().zip(answers) {
        let mut fields: Vec<String> = match row {
            Ok((_, record)) => keep
                .iter()
                .map(|&i| record.get(i).unwrap_or("").to_string())
                .collect(),
            Err(_) => vec![String::new(); keep.len()],
        };
        match answer {
            Ok(Answer::Value { mu2, lambda, stop }) => {
                fields.extend([format_17(*mu2), format_17(*lambda), format!("{stop:?}")])
            }
            Ok(Answer::Overlap(o)) => fields.push(o.to_string()),
            Err(_) => fields.extend(std::iter::repeat_n(
                String::new(),
                header.len() - keep.len() - 1,
            )),
        }
        if with_error {
            fields.push(answer.as_ref().err().cloned().unwrap_or_default());
        }
        writer.write_record(&fields)?;
    }
    writer.flush()
}
