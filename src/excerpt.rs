//! Quoting input in messages: at most a short excerpt, so that a 50 MB value under an unknown
//! key gives a one-line message, not a 50 MB one.

/// The most characters of a quoted value a message shows.
pub const MAX_EXCERPT_CHARS: usize = 80;

/// `text` itself when it is short, else its first `MAX_EXCERPT_CHARS` characters, an
/// ellipsis and how long it was. Control characters are shown escaped, so the excerpt stays
/// on one line.
pub fn excerpt(text: &str) -> String {
    let total = text.chars().count();
    let mut out: String = text
        .chars()
        .take(MAX_EXCERPT_CHARS)
        .flat_map(|c| if c.is_control() { c.escape_default().collect::<Vec<_>>() } else { vec![c] })
        .collect();
    if total > MAX_EXCERPT_CHARS {
        out += &format!("… ({total} characters)");
    }
    out
}

/// `value` as written, but a number whose decimal form is long (1e300 prints 301 digits)
/// in scientific notation.
pub fn short_number(value: String) -> String {
    match value.parse::<f64>() {
        Ok(number) if value.len() > 24 => format!("{number:e}"),
        _ => value,
    }
}

/// `message` with every line longer than `max_line` characters cut to an excerpt: for
/// messages that another library wrote and that may quote the input (toml, tobj, roxmltree).
pub fn shorten_message(message: &str, max_line: usize) -> String {
    message
        .lines()
        .map(|line| {
            if line.chars().count() <= max_line {
                line.to_owned()
            } else {
                let head: String = line.chars().take(max_line).collect();
                format!("{head}… (line of {} characters cut)", line.chars().count())
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_values_are_cut_and_short_ones_kept() {
        assert_eq!(excerpt("abc"), "abc");
        let long = "x".repeat(50_000_000 / 1000);
        let shown = excerpt(&long);
        assert!(shown.chars().count() < MAX_EXCERPT_CHARS + 40, "{shown}");
        assert!(shown.ends_with("(50000 characters)"));
        assert_eq!(excerpt("a\nb"), "a\\nb");
    }

    #[test]
    fn long_message_lines_are_cut() {
        let message = format!("first\n{}\nlast", "y".repeat(1000));
        let short = shorten_message(&message, 200);
        assert!(short.len() < 300 && short.starts_with("first\n") && short.ends_with("\nlast"));
    }
}
