//! Spectrum files (`<spectrum filename="…"/>`, Mitsuba's `.spd`): one `wavelength value`
//! pair per line, `#` starting a comment. Read when the scene tree is built, where the
//! file resolver is, and handed on as the `value="wavelength:value, …"` list the
//! spectrum conversion reads.

use std::path::Path;

/// The `wavelength:value` list of the spectrum file `path`, or what is wrong with it.
pub(super) fn spectrum_file_as_list(path: &Path) -> Result<String, String> {
    if !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("spd")) {
        return Err(format!("'{}' is not a .spd spectrum file", path.display()));
    }
    let text = crate::input_file::read_text(path)
        .map_err(|e| format!("cannot read '{}': {e}", path.display()))?;
    let pairs = parse(&text)
        .map_err(|(line, problem)| format!("{}, line {line}: {problem}", path.display()))?;
    Ok(pairs.iter().map(|(w, v)| format!("{w}:{v}")).collect::<Vec<_>>().join(", "))
}

/// The pairs of a `.spd` text, or the line (from 1) and problem of the first bad line.
pub(super) fn parse(text: &str) -> Result<Vec<(f64, f64)>, (usize, String)> {
    let mut pairs = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let data = line.split('#').next().unwrap_or("");
        let numbers: Vec<&str> = data.split_whitespace().collect();
        let number = |token: &str| -> Result<f64, (usize, String)> {
            token.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                (i + 1, format!("'{}' is not a number", crate::excerpt::excerpt(token)))
            })
        };
        match numbers[..] {
            [] => {}
            [w, v] => pairs.push((number(w)?, number(v)?)),
            _ => {
                let count = numbers.len();
                return Err((i + 1, format!("{count} numbers, not a wavelength and a value")));
            }
        }
    }
    if pairs.is_empty() {
        return Err((1, "no wavelength and value".to_owned()));
    }
    Ok(pairs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_comments_and_bad_lines() {
        let text = "# eta of something\n400 1.5 # blue\n\n  500\t1.4\r\n600 1.3\n";
        assert_eq!(parse(text).unwrap(), [(400.0, 1.5), (500.0, 1.4), (600.0, 1.3)]);
        assert_eq!(parse("400 1\n500 x\n").unwrap_err(), (2, "'x' is not a number".to_owned()));
        assert_eq!(parse("400 1 2\n").unwrap_err().1, "3 numbers, not a wavelength and a value");
        assert_eq!(parse("# nothing\n").unwrap_err().1, "no wavelength and value");
    }
}
