//! `embray` command line: parse, run, print the error chain, exit with a code.

mod cli;

use clap::{CommandFactory, FromArgMatches};
use std::io::Write;

fn main() -> std::process::ExitCode {
    embray::limits::note_memory_at_start();
    let mut command = cli::Cli::command();
    // The version names the Embree library found at run time (not the header built
    // against), which starts an Embree device: only when the version is asked for.
    if std::env::args_os().skip(1).any(|a| a == "--version" || a == "-V") {
        let line = format!(
            "{}; backends: {}",
            env!("CARGO_PKG_VERSION"),
            embray::accel::backends_description()
        );
        command = command.version(&*Box::leak(line.into_boxed_str()));
    }
    let args = match cli::Cli::from_arg_matches(&command.get_matches()) {
        Ok(args) => args,
        Err(error) => error.exit(),
    };
    // An interrupted run removes its temporary files; without the handler it still
    // works, only an interrupt may then leave one behind.
    if let Err(error) = embray::output::remove_temp_files_on_signals() {
        let _ = writeln!(std::io::stderr(), "warning: cannot watch for interrupts: {error}");
    }
    match cli::run(args) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            // Standard error may itself be unwritable: never panic over the message.
            let message = embray::excerpt::terminal_safe(&format!("{error:#}"));
            let _ = writeln!(std::io::stderr(), "error: {message}");
            std::process::ExitCode::FAILURE
        }
    }
}
