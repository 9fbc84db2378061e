//! A method's answer to every row of a case table, and the table written back with the
//! answers in new columns (what `pack contact` does).

use super::Case;
use super::{format_17, CaseError, CaseTable};
use crate::contact::{in_plane_terms, Answer, ContactError, Dimension, Method, Sym3, Vec3};
use std::io::{self, Write};
use thiserror::Error;

/// Columns the answers are written in; input columns of the same name are not copied.
pub const RESULT_COLUMNS: [&str; 5] = ["mu2", "lambda", "stop", "overlap", "error"];

/// Why a row has no answer.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RowError {
    /// The row could not be read as a pair.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// The method refused the pair.
    #[error("line {line}: {source}")]
    Contact {
        /// Line number.
        line: u64,
        /// The method's error.
        source: ContactError,
    },
}

impl CaseTable {
    /// The pairs of the rows that read as pairs, in row order (the bad rows left out).
    pub fn pairs(&self) -> Vec<(Vec3, Sym3, Sym3)> {
        (0..self.rows.len())
            .filter_map(|i| self.case(i).ok())
            .map(|c| (c.r12, c.q1, c.q2))
            .collect()
    }

    /// `method`'s answer to each row, or why the row has none; the good rows are
    /// evaluated together, so a batch method takes them eight at a time.
    pub fn answers(&self, method: Method) -> Vec<Result<Answer, RowError>> {
        let parsed: Vec<_> = (0..self.rows.len()).map(|i| self.case(i)).collect();
        let pairs: Vec<_> = (parsed.iter().flatten())
            .map(|c| (c.r12, c.q1, c.q2))
            .collect();
        let mut evaluated = method.evaluate_all(&pairs).into_iter();
        parsed
            .into_iter()
            .map(|case| {
                let c = case?;
                let answer = (evaluated.next()).expect("evaluate_all answers every pair");
                answer.map_err(|source| RowError::Contact {
                    line: c.line,
                    source: self.in_input_terms(source, &c),
                })
            })
            .collect()
    }
}

impl CaseTable {
    /// A method's error about the pair of `case`, naming the entries as the file has
    /// them (the 2×2 forms' entries in 2D, not the embedded ones).
    fn in_input_terms(&self, error: ContactError, case: &Case) -> ContactError {
        let plane = |q: &Sym3| [q[0], q[1], q[3]];
        match self.dimension {
            Dimension::Two => in_plane_terms(error, &plane(&case.q1), &plane(&case.q2)),
            Dimension::Three => error,
        }
    }
}

/// Writes `table` back as CSV with `method`'s answers: its columns (except
/// [`RESULT_COLUMNS`]), then `mu2, lambda, stop` (17 significant digits) or `overlap`,
/// and an `error` column when some row has no answer. A bad row keeps its line, empty.
pub fn write_answers(
    out: &mut dyn Write,
    table: &CaseTable,
    method: Method,
    answers: &[Result<Answer, RowError>],
) -> io::Result<()> {
    let with_error = answers.iter().any(Result::is_err);
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
            Ok((_, record)) => (keep.iter())
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
            let message = answer.as_ref().err().map(ToString::to_string);
            fields.push(message.unwrap_or_default());
        }
        writer.write_record(&fields)?;
    }
    writer.flush()
}
