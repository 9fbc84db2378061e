//! What can be wrong with a scene file, and where: file, key path, line, column, value.

use std::fmt::Write as _;
use std::ops::Range;
use std::path::PathBuf;
use thiserror::Error;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// The key path of an error that concerns the whole file (a missing top-level key).
pub const TOP_LEVEL: &str = "<top level>";

/// Why a scene file was rejected.
///
/// Every variant but [`SceneError::Read`] names the file, the line and column (1-based,
/// columns in characters) and the key path, such as `phase[1].size.sigma` (phases
/// counted from 0, in file order), so the message alone locates the mistake:
///
/// ```text
/// scene.toml:12:9: phase[0].size.sigma = -0.8: must be positive
/// ```
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene file {}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// The text is not valid TOML.
    #[error("{file}:{line}:{column}: invalid TOML: {message}")]
    Syntax {
        /// The file's name as given.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column, in characters.
        column: usize,
        /// What the TOML parser said.
        message: String,
    },
    /// The TOML does not have the shape of a scene: an unknown key, a value of the wrong
    /// type, or a missing required key.
    #[error("{file}:{line}:{column}: {key}: {message}")]
    Shape {
        /// The file's name as given.
        file: String,
        /// Key path of the offending key or table.
        key: String,
        /// 1-based line.
        line: usize,
        /// 1-based column, in characters.
        column: usize,
        /// The text at that place (the value, the key, or the table header).
        value: String,
        /// What the deserializer said (it names the expected type or keys).
        message: String,
    },
    /// A value of the right type that no scene can have: a negative size, reversed
    /// cutoffs, a fraction beyond what can be packed, a grain longer than the box...
    #[error("{file}:{line}:{column}: {key} = {value}: {reason}")]
    Value {
        /// The file's name as given.
        file: String,
        /// Key path of the offending value.
        key: String,
        /// 1-based line.
        line: usize,
        /// 1-based column, in characters.
        column: usize,
        /// The value as written, or `(missing)` for a required key that is absent (the
        /// location is then its table's).
        value: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A data file named by the scene (an orientation file, a measured grain table)
    /// cannot be read or has a bad row.
    #[error("{0}")]
    DataFile(Box<DataFileError>),
}

/// What is wrong in a data file named by the scene: the file, its line (1-based; 0 for
/// the file as a whole), the column, the value, and the scene key that named it.
#[derive(Debug, Error)]
#[error("{path}:{line}: {column} = {value}: {reason} (from {key} in {file})")]
pub struct DataFileError {
    /// The scene file's name as given.
    pub file: String,
    /// The scene key that names the data file.
    pub key: String,
    /// The data file, as resolved.
    pub path: String,
    /// 1-based line; 0 for the whole file.
    pub line: usize,
    /// The column's header (or `(file)`, `(header)`, `(row)`).
    pub column: String,
    /// The value as written.
    pub value: String,
    /// What is wrong with it.
    pub reason: String,
}

/// The text being validated and its name, to turn byte spans into error locations.
pub(crate) struct Source<'a> {
    /// The file's name as given.
    pub file: &'a str,
    /// The whole text.
    pub text: &'a str,
}

impl Source<'_> {
    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        (line, before[line_start..].chars().count() + 1)
    }

    /// The text of a span on one line, at most 60 characters.
    pub fn snippet(&self, span: &Range<usize>) -> String {
        let raw = self.text.get(span.clone()).unwrap_or("");
        let one_line = raw.split_whitespace().collect::<Vec<_>>().join(" ");
        if one_line.chars().count() > 60 {
            one_line.chars().take(59).collect::<String>() + "…"
        } else {
            one_line
        }
    }

    /// A [`SceneError::Value`] for the value at `span`.
    pub fn invalid(
        &self,
        key: impl Into<String>,
        span: Range<usize>,
        reason: impl Into<String>,
    ) -> SceneError {
        self.value_error(key.into(), &span, self.snippet(&span), reason.into())
    }

    /// A [`SceneError::Value`] for a required key that is absent from the table at
    /// `table`.
    pub fn missing(
        &self,
        key: impl Into<String>,
        table: Range<usize>,
        reason: impl Into<String>,
    ) -> SceneError {
        self.value_error(key.into(), &table, "(missing)".into(), reason.into())
    }

    /// A [`SceneError::Value`] about a value of a spanned raw field.
    pub fn invalid_at<T>(
        &self,
        key: impl Into<String>,
        at: &Spanned<T>,
        reason: impl Into<String>,
    ) -> SceneError {
        self.invalid(key, at.span(), reason)
    }

    fn value_error(
        &self,
        key: String,
        span: &Range<usize>,
        value: String,
        reason: String,
    ) -> SceneError {
        let (line, column) = self.line_column(span.start);
        SceneError::Value {
            file: self.file.to_owned(),
            key,
            line,
            column,
            value,
            reason,
        }
    }

    /// A [`SceneError::Syntax`] from the TOML parser's error.
    pub fn syntax(&self, error: &toml::de::Error) -> SceneError {
        let (line, column) = self.line_column(error.span().map_or(0, |s| s.start));
        SceneError::Syntax {
            file: self.file.to_owned(),
            line,
            column,
            message: error.message().trim().to_owned(),
        }
    }

    /// A [`SceneError::Shape`] from the deserializer's error, with the key path found
    /// by locating the error's span in the parsed document.
    pub fn shape(&self, error: &toml::de::Error, document: &DeTable<'_>) -> SceneError {
        let span = error.span().unwrap_or(0..0);
        let (line, column) = self.line_column(span.start);
        SceneError::Shape {
            file: self.file.to_owned(),
            key: key_path_at(document, &span),
            line,
            column,
            value: self.snippet(&span),
            message: error.message().trim().to_owned(),
        }
    }
}

/// The key path (`phase[1].size.sigma`) of the innermost key or value whose span
/// contains `target`; [`TOP_LEVEL`] for the empty span at the start, which is where the
/// deserializer puts errors about the document as a whole.
pub(crate) fn key_path_at(document: &DeTable<'_>, target: &Range<usize>) -> String {
    let mut path = String::new();
    if *target != (0..0) && find_in_table(document, target, &mut path) {
        path
    } else {
        TOP_LEVEL.to_owned()
    }
}

fn contains(outer: &Range<usize>, inner: &Range<usize>) -> bool {
    outer.start <= inner.start && inner.end <= outer.end
}

/// Depth first, so that a key inside a table wins over the table's header. The keys
/// of a `[table]` lie outside its header's span, so every child is searched.
fn find_in_table(table: &DeTable<'_>, target: &Range<usize>, path: &mut String) -> bool {
    for (key, value) in table {
        let len = path.len();
        let key_span = key.span();
        let key = key.get_ref();
        if !path.is_empty() {
            path.push('.');
        }
        if !key.is_empty()
            && key
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        {
            path.push_str(key);
        } else {
            let _ = write!(path, "{key:?}");
        }
        if find_in_value(value, target, path)
            || contains(&key_span, target)
            || contains(&value.span(), target)
        {
            return true;
        }
        path.truncate(len);
    }
    false
}

fn find_in_value(value: &Spanned<DeValue<'_>>, target: &Range<usize>, path: &mut String) -> bool {
    match value.get_ref() {
        DeValue::Table(table) => find_in_table(table, target, path),
        DeValue::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                let len = path.len();
                let _ = write!(path, "[{i}]");
                if find_in_value(item, target, path) || contains(&item.span(), target) {
                    return true;
                }
                path.truncate(len);
            }
            false
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_count_characters_not_bytes() {
        let text = "a = 1\nname = \"αβ\" # é\nx = 2";
        let src = Source { file: "f", text };
        let x = text.find("x =").unwrap();
        assert_eq!(src.line_column(x), (3, 1));
        let e = text.find('é').unwrap();
        assert_eq!(src.line_column(e), (2, 15));
        // An offset inside a character is moved back to its start, not a panic.
        assert_eq!(src.line_column(e + 1), (2, 15));
    }

    #[test]
    fn key_paths_follow_tables_arrays_and_inline_tables() {
        let text = "a = 1\n[[p]]\nq = 2\n[[p]]\nr = { s = [1, 2] }\n[t.u]\nv = 3\n";
        let doc = DeTable::parse(text).unwrap();
        let at = |needle: &str| {
            let i = text.find(needle).unwrap();
            key_path_at(doc.get_ref(), &(i..i + needle.len()))
        };
        assert_eq!(at("a"), "a");
        assert_eq!(at("2"), "p[0].q"); // the first "2" in the text is q's value
        assert_eq!(at("[1, 2]"), "p[1].r.s");
        assert_eq!(at("v"), "t.u.v");
        assert_eq!(at("[t.u]"), "t.u");
        assert_eq!(key_path_at(doc.get_ref(), &(0..0)), TOP_LEVEL);
    }
}
