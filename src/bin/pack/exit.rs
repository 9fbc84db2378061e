//! Exit codes, and the error that ends the program with one.

use std::process::ExitCode;

/// How `pack` ends; the codes are listed in `pack --help` and docs/cli.md.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exit {
    /// 0: done; for a scene, the target was reached and the packing verified.
    Success = 0,
    /// 1: an internal error, or the outputs could not be written.
    Internal = 1,
    /// 2: bad input (scene file, CSV rows, command line).
    BadInput = 2,
    /// 3: the packing stopped short of its target; its best overlap-free state is
    /// written.
    NotReached = 3,
}

impl From<Exit> for ExitCode {
    fn from(exit: Exit) -> Self {
        ExitCode::from(exit as u8)
    }
}

/// An error, with the exit code it ends the program with.
#[derive(Debug)]
pub struct Failure {
    /// The code.
    pub exit: Exit,
    /// What went wrong, with its context chain.
    pub error: anyhow::Error,
}

impl Failure {
    /// The user's input is wrong: exit code 2.
    pub fn bad_input(error: impl Into<anyhow::Error>) -> Self {
        Self {
            exit: Exit::BadInput,
            error: error.into(),
        }
    }
}

/// Any other error is internal: exit code 1.
impl From<anyhow::Error> for Failure {
    fn from(error: anyhow::Error) -> Self {
        Self {
            exit: Exit::Internal,
            error,
        }
    }
}
