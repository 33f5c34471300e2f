//! `embray` command line: parse, run, print the error chain, exit with a code.

mod cli;

use clap::Parser;
use std::io::Write;

fn main() -> std::process::ExitCode {
    let args = cli::Cli::parse();
    // An interrupted run removes its temporary files; without the handler it still
    // works, only an interrupt may then leave one behind.
    if let Err(error) = embray::output::remove_temp_files_on_signals() {
        let _ = writeln!(std::io::stderr(), "warning: cannot watch for interrupts: {error}");
    }
    match cli::run(args) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            // Standard error may itself be unwritable: never panic over the message.
            let _ = writeln!(std::io::stderr(), "error: {error:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
