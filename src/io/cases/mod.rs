//! Contact cases as CSV: `r0,r1,r2,q1_0,…,q1_5,q2_0,…,q2_5` (ellipsoids) or
//! `r0,r1,q1_0,q1_1,q1_2,q2_0,q2_1,q2_2` (ellipses, 2×2 forms `[q00, q01, q11]`), and
//! any extra columns. A 2D pair is read as the 3D pair it embeds as
//! ([`embed_pair`]), which every method answers as the ellipses' own.

mod answers;

pub use answers::{write_answers, RowError, RESULT_COLUMNS};

use crate::contact::{embed_pair, Dimension, Sym3, Vec3};
use std::io::Read;
use thiserror::Error;

/// The columns a case file must have, in the order they are read.
pub const INPUT_COLUMNS: [&str; 15] = [
    "r0", "r1", "r2", "q1_0", "q1_1", "q1_2", "q1_3", "q1_4", "q1_5", "q2_0", "q2_1", "q2_2",
    "q2_3", "q2_4", "q2_5",
];

/// The columns a 2D case file must have, in the order they are read.
pub const INPUT_COLUMNS_2D: [&str; 8] =
    ["r0", "r1", "q1_0", "q1_1", "q1_2", "q2_0", "q2_1", "q2_2"];

/// The columns only a 3D case file has: one of them in the header makes the file 3D.
const ONLY_3D: [&str; 7] = ["r2", "q1_3", "q1_4", "q1_5", "q2_3", "q2_4", "q2_5"];

/// One pair in relative form, with the line it came from (a 2D pair embedded).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    /// Line number in the file (the header is line 1).
    pub line: u64,
    /// `c2 − c1`.
    pub r12: Vec3,
    /// Quadratic form of the first ellipsoid.
    pub q1: Sym3,
    /// Quadratic form of the second ellipsoid.
    pub q2: Sym3,
}

/// What is wrong with a case file or one of its rows.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CaseError {
    /// The header lacks required columns.
    #[error("header lacks column(s) {0}")]
    MissingColumns(String),
    /// The CSV itself is malformed (e.g. a row with the wrong number of fields).
    #[error("line {line}: {message}")]
    Csv {
        /// Line number.
        line: u64,
        /// What the CSV reader said.
        message: String,
    },
    /// A field is not a number.
    #[error("line {line}: column {column}: {value:?} is not a number")]
    NotANumber {
        /// Line number.
        line: u64,
        /// Column name.
        column: String,
        /// The field as written.
        value: String,
    },
}

/// A case file as read: its header, its raw records and where each required column is.
#[derive(Debug, Clone)]
pub struct CaseTable {
    /// The header, as written.
    pub headers: csv::StringRecord,
    /// Each data row as written, with its line number; a row the CSV reader rejected
    /// is kept as the error, so that its neighbours are still processed.
    pub rows: Vec<Result<(u64, csv::StringRecord), CaseError>>,
    /// Ellipses (the 2D columns) or ellipsoids.
    pub dimension: Dimension,
    index: [usize; 15],
}

impl CaseTable {
    /// Reads a whole case file. Fails only if the header is unreadable or lacks a
    /// required column; bad rows are kept as errors in [`CaseTable::rows`].
    pub fn read<R: Read>(input: R) -> Result<Self, CaseError> {
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_reader(input);
        let headers = reader
            .headers()
            .map_err(|e| CaseError::Csv {
                line: 1,
                message: e.to_string(),
            })?
            .clone();
        let (dimension, index) = required_columns(&headers)?;
        let mut rows = Vec::new();
        for record in reader.records() {
            rows.push(match record {
                Ok(r) => Ok((r.position().map_or(0, |p| p.line()), r)),
                Err(e) => Err(CaseError::Csv {
                    line: e.position().map_or(0, |p| p.line()),
                    message: e.to_string(),
                }),
            });
        }
        Ok(Self {
            headers,
            rows,
            dimension,
            index,
        })
    }

    /// The position of a column by name.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.headers.iter().position(|h| h == name)
    }

    /// Parses row `i` into a case (a 2D row as the pair it embeds as).
    pub fn case(&self, i: usize) -> Result<Case, CaseError> {
        let (line, record) = self.rows[i].as_ref().map_err(Clone::clone)?;
        let names: &[&str] = match self.dimension {
            Dimension::Two => &INPUT_COLUMNS_2D,
            Dimension::Three => &INPUT_COLUMNS,
        };
        let mut values = [0.0; 15];
        for (k, name) in names.iter().enumerate() {
            values[k] = parse_number(record, self.index[k], *line, name)?;
        }
        let (r12, q1, q2) = match self.dimension {
            Dimension::Two => {
                let pick = |k: usize| [values[k], values[k + 1], values[k + 2]];
                embed_pair(&[values[0], values[1]], &pick(2), &pick(5))
            }
            Dimension::Three => {
                let (mut r12, mut q1, mut q2) = ([0.0; 3], [0.0; 6], [0.0; 6]);
                r12.copy_from_slice(&values[0..3]);
                q1.copy_from_slice(&values[3..9]);
                q2.copy_from_slice(&values[9..15]);
                (r12, q1, q2)
            }
        };
        Ok(Case {
            line: *line,
            r12,
            q1,
            q2,
        })
    }

    /// Parses column `name` of row `i` as a number (for reference columns such as
    /// `mu2`).
    pub fn number(&self, i: usize, name: &str) -> Result<f64, CaseError> {
        let (line, record) = self.rows[i].as_ref().map_err(Clone::clone)?;
        let col = self
            .column(name)
            .ok_or_else(|| CaseError::MissingColumns(name.to_string()))?;
        parse_number(record, col, *line, name)
    }
}

/// The dimension of a case file by its header, and where each input column is: 3D
/// with any 3D-only column, else 2D. A header with neither set complete names what
/// each lacks.
fn required_columns(headers: &csv::StringRecord) -> Result<(Dimension, [usize; 15]), CaseError> {
    let find = |names: &[&str]| {
        let mut index = [0; 15];
        let mut missing = Vec::new();
        for (k, name) in names.iter().enumerate() {
            match headers.iter().position(|h| h == *name) {
                Some(i) => index[k] = i,
                None => missing.push(*name),
            }
        }
        (index, missing.join(", "))
    };
    let (index, missing) = find(&INPUT_COLUMNS);
    if missing.is_empty() {
        return Ok((Dimension::Three, index));
    }
    if headers.iter().any(|h| ONLY_3D.contains(&h)) {
        return Err(CaseError::MissingColumns(missing));
    }
    match find(&INPUT_COLUMNS_2D) {
        (index, lacking) if lacking.is_empty() => Ok((Dimension::Two, index)),
        (_, lacking) => Err(CaseError::MissingColumns(format!(
            "{missing} (ellipsoids) or {lacking} (ellipses)"
        ))),
    }
}

fn parse_number(
    record: &csv::StringRecord,
    col: usize,
    line: u64,
    name: &str,
) -> Result<f64, CaseError> {
    let field = record.get(col).unwrap_or("");
    field.parse::<f64>().map_err(|_| CaseError::NotANumber {
        line,
        column: name.to_string(),
        value: field.to_string(),
    })
}

/// Formats a double with 17 significant digits, enough to read back the same double.
pub fn format_17(x: f64) -> String {
    format!("{x:.16e}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_rows_name_their_line_and_column_and_spare_their_neighbours() {
        let text = format!(
            "{},extra\n{}\n{}\n{}\n",
            INPUT_COLUMNS.join(","),
            ["1"; 16].join(","),
            ["1", "x"]
                .iter()
                .chain(["1"; 14].iter())
                .copied()
                .collect::<Vec<_>>()
                .join(","),
            ["2"; 16].join(","),
        );
        let table = CaseTable::read(text.as_bytes()).unwrap();
        assert_eq!(table.rows.len(), 3);
        assert_eq!(table.case(0).unwrap().r12, [1.0; 3]);
        let err = table.case(1).unwrap_err();
        assert_eq!(
            err,
            CaseError::NotANumber {
                line: 3,
                column: "r1".into(),
                value: "x".into()
            }
        );
        assert_eq!(table.case(2).unwrap().q2, [2.0; 6]);
    }

    #[test]
    fn missing_columns_are_all_named() {
        let err = CaseTable::read("r0,r1\n1,2\n".as_bytes()).unwrap_err();
        assert!(err.to_string().contains("r2, q1_0"), "{err}");
    }

    #[test]
    fn a_2d_file_reads_as_the_embedded_pairs_and_names_its_own_columns() {
        let text = "id,r0,r1,q1_0,q1_1,q1_2,q2_0,q2_1,q2_2\n\
                    a,3,0,1,0,1,4,0.5,1\n\
                    b,3,0,1,0,1,4,x,1\n";
        let table = CaseTable::read(text.as_bytes()).unwrap();
        assert_eq!(table.dimension, Dimension::Two);
        let case = table.case(0).unwrap();
        assert_eq!(case.r12, [3.0, 0.0, 0.0]);
        assert_eq!(
            case.q1,
            embed_pair(&[3.0, 0.0], &[1.0, 0.0, 1.0], &[1.0; 3]).1
        );
        assert_eq!(case.q2[..5], [4.0, 0.5, 0.0, 1.0, 0.0]);
        assert_eq!(
            table.case(1).unwrap_err(),
            CaseError::NotANumber {
                line: 3,
                column: "q2_1".into(),
                value: "x".into()
            }
        );
    }

    #[test]
    fn a_header_with_a_3d_column_is_read_as_3d() {
        let err = CaseTable::read("r0,r1,r2,q1_0,q1_1,q1_2,q2_0,q2_1,q2_2\n".as_bytes());
        assert!(err.unwrap_err().to_string().contains("q1_3"));
        let err = CaseTable::read("r0,r1,q1_0,q1_1,q2_0,q2_1,q2_2\n".as_bytes()).unwrap_err();
        assert!(err.to_string().contains("or q1_2 (ellipses)"), "{err}");
    }

    #[test]
    fn seventeen_digits_round_trip() {
        for x in [0.1, 1.0 / 3.0, 3.362706040638629, 1e-300, 5e-324] {
            assert_eq!(format_17(x).parse::<f64>().unwrap(), x);
        }
    }
}
