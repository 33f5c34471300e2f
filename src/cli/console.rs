//! Writing to the terminal without ever panicking (`print!` panics when standard output is
//! a full disk or a closed pipe): results go to standard output and a failure is an error;
//! notes go to standard error, best effort.

use anyhow::{Context, Result};
use std::fmt::Display;
use std::io::Write;

/// Writes `text` to standard output.
pub fn out(text: impl Display) -> Result<()> {
    let mut stdout = std::io::stdout().lock();
    write!(stdout, "{text}")
        .and_then(|()| stdout.flush())
        .context("cannot write to standard output")
}

/// Writes `text` and a newline to standard error; a failure there has nowhere to be told.
pub fn note(text: impl Display) {
    let _ = writeln!(std::io::stderr(), "{}", embray::excerpt::terminal_safe(&text.to_string()));
}
