//! Quoting input in messages: at most a short excerpt, so that a 50 MB value under an unknown
//! key gives a one-line message, not a 50 MB one.

/// The most characters of a quoted value a message shows.
pub const MAX_EXCERPT_CHARS: usize = 80;

/// Characters a terminal acts on rather than shows: control characters (a newline would start
/// a forged message line, an escape colour the terminal) and the bidirectional formatting
/// ones (U+202E shows the text after it reversed).
fn acts_on_terminal(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{061c}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// `c` as it is, or escaped (`\u{1b}`) if a terminal would act on it.
fn shown(c: char) -> Vec<char> {
    if acts_on_terminal(c) { c.escape_default().collect() } else { vec![c] }
}

/// `text` itself when it is short, else its first `MAX_EXCERPT_CHARS` characters, an
/// ellipsis and how long it was. Control and bidirectional formatting characters are shown
/// escaped, so the excerpt stays on one line and reads as written.
pub fn excerpt(text: &str) -> String {
    let total = text.chars().count();
    let mut out: String = text.chars().take(MAX_EXCERPT_CHARS).flat_map(shown).collect();
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

/// `message` as a terminal should get it: every character a terminal would act on escaped
/// but its line breaks and tabs (a message quoting input that was not excerpted, a path, a
/// library's report, may hold an escape sequence or U+202E).
pub fn terminal_safe(message: &str) -> String {
    message
        .chars()
        .flat_map(|c| if matches!(c, '\n' | '\t') { vec![c] } else { shown(c) })
        .collect()
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
        assert_eq!(excerpt("a\u{202e}b"), "a\\u{202e}b");
    }

    #[test]
    fn messages_reach_the_terminal_without_escapes_or_reversals() {
        let message = "line one\n\tmtllib 'a\u{1b}[31m.mtl' \u{202e}gnp.exe";
        assert_eq!(
            terminal_safe(message),
            "line one\n\tmtllib 'a\\u{1b}[31m.mtl' \\u{202e}gnp.exe"
        );
    }

    #[test]
    fn long_message_lines_are_cut() {
        let message = format!("first\n{}\nlast", "y".repeat(1000));
        let short = shorten_message(&message, 200);
        assert!(short.len() < 300 && short.starts_with("first\n") && short.ends_with("\nlast"));
    }
}
