//! `pack`: the grainpack command line.

mod cli;
mod contact;
mod exit;
mod scene;

use cli::{Command, Invocation};
use exit::{Exit, Failure};
use std::process::ExitCode;

fn main() -> ExitCode {
    let result = match cli::parse() {
        Invocation::Scene(path, options) => scene::run(&path, &options),
        Invocation::Command(Command::Contact {
            cases,
            method,
            output,
            time,
        }) => match contact::run(&cases, method, output.as_deref(), time) {
            Ok(0) => Ok(Exit::Success),
            Ok(_bad_rows) => Ok(Exit::BadInput),
            Err(e) => Err(Failure::bad_input(e)),
        },
    };
    result
        .unwrap_or_else(|failure| {
            eprintln!("pack: error: {:#}", failure.error);
            failure.exit
        })
        .into()
}
