//! `embray` command line: parse, run, print the error chain, exit with a code.

mod cli;

use clap::Parser;
use std::io::Write;

fn main() -> std::process::ExitCode {
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            // Standard error may itself be unwritable: never panic over the message.
            let _ = writeln!(std::io::stderr(), "error: {error:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
