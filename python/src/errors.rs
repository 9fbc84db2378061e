//! The module's exceptions, and error messages as the CLI prints them.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use std::error::Error;
use std::fmt::Write as _;

create_exception!(
    grainpack,
    SceneError,
    PyValueError,
    "A scene that `pack` would refuse: the message is the CLI's (`file:line:column: key = \
     value: reason`), and the attributes `file`, `line`, `column`, `key` and `value` \
     locate it (None where the error has no such part, as for a file that cannot be read)."
);

/// An error and its sources joined by ": ", as the CLI prints them (anyhow's `{:#}`).
pub fn chain(error: &dyn Error) -> String {
    let mut message = error.to_string();
    let mut source = error.source();
    while let Some(s) = source {
        let _ = write!(message, ": {s}");
        source = s.source();
    }
    message
}
