//! `pack`: the grainpack command line.

mod cli;
mod contact;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    let result = match &cli.command {
        cli::Command::Contact {
            cases,
            method,
            output,
            time,
        } => contact::run(cases, *method, output.as_deref(), *time),
    };
    match result {
        Ok(0) => ExitCode::SUCCESS,
        Ok(_) => ExitCode::from(2),
        Err(e) => {
            eprintln!("pack: error: {e:#}");
            ExitCode::from(2)
        }
    }
}
