//! A pass over OBJ and MTL text before tobj sees it, for the problems tobj reports without
//! a line (or not at all, or by panicking): non-finite coordinates, out-of-range face
//! indices, MTL statements tobj cannot parse.

/// A problem with its 1-based line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ScanProblem {
    pub line: usize,
    pub message: String,
}

const KINDS: [(&str, &str, &str); 3] = [
    ("v", "vertex", "vertices"),
    ("vt", "texture coordinate", "texture coordinates"),
    ("vn", "normal", "normals"),
];

/// What the scan found that is not an error: warnings, and the `usemtl` names (with their
/// lines) so that the loader can warn about the undefined ones.
#[derive(Debug, Default)]
pub(crate) struct ObjScan {
    pub warnings: Vec<ScanProblem>,
    pub usemtl: Vec<(String, usize)>,
}

/// `text` without a leading UTF-8 byte order mark, which some Windows tools write: tobj
/// would read it as part of the first statement's keyword and drop that statement.
pub(crate) fn without_bom(mut text: String) -> String {
    if text.starts_with('\u{feff}') {
        text.drain(..'\u{feff}'.len_utf8());
    }
    text
}

/// Statements of the OBJ format that tobj reads or that embray leaves out on purpose
/// (points, lines, smoothing groups, free-form geometry, display attributes); anything else
/// is most likely a typo (`vv 1 -1 0`), whose data would be lost without a word.
const KNOWN_STATEMENTS: [&str; 36] = [
    "v",
    "vt",
    "vn",
    "vp",
    "f",
    "fo",
    "l",
    "p",
    "o",
    "g",
    "s",
    "mg",
    "usemtl",
    "mtllib",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "bevel",
    "c_interp",
    "d_interp",
    "lod",
    "usemap",
    "maplib",
    "shadow_obj",
    "trace_obj",
];

/// How many numbers each vertex statement takes (tobj's rules): `v` x y z [w | r g b],
/// `vt` u v [w], `vn` x y z.
const COUNTS: [&[usize]; 3] = [&[3, 4, 6], &[2, 3], &[3]];

/// Checks every `v`/`vt`/`vn` statement (the count and every number, as tobj parses them,
/// in f32) and every face index, so that each problem gets its line (tobj reports none);
/// faces of fewer than 3 vertices are warned about (they are dropped).
pub(crate) fn scan_obj(text: &str) -> Result<ObjScan, ScanProblem> {
    let mut totals = [0usize; 3];
    for line in text.lines() {
        if let Some(kind) = line.split_whitespace().next().and_then(kind_of) {
            totals[kind] += 1;
        }
    }
    let mut seen = [0usize; 3];
    let mut scan = ObjScan::default();
    // (line of the first, count)
    let mut unknown: Option<(usize, usize)> = None;
    for (n, line) in text.lines().enumerate() {
        let problem = |message: String| ScanProblem { line: n + 1, message };
        let mut words = line.split_whitespace();
        match words.next() {
            Some("f") => {
                let vertices: Vec<&str> = words.collect();
                for word in &vertices {
                    check_face_vertex(word, &seen, &totals).map_err(problem)?;
                }
                if vertices.len() < 3 {
                    scan.warnings.push(problem(format!(
                        "a face with {} vertices is ignored (a face needs at least 3)",
                        vertices.len()
                    )));
                }
            }
            Some("usemtl") => {
                let name = line.trim().split_once(char::is_whitespace).map(|(_, n)| n.trim());
                match name.filter(|n| !n.is_empty()) {
                    Some(name) => scan.usemtl.push((name.to_owned(), n + 1)),
                    None => return Err(problem("usemtl needs a material name".to_owned())),
                }
            }
            Some(keyword) => {
                let Some(kind) = kind_of(keyword) else {
                    if !keyword.starts_with('#') && !KNOWN_STATEMENTS.contains(&keyword) {
                        let (_, count) = unknown.get_or_insert((n + 1, 0));
                        *count += 1;
                    }
                    continue;
                };
                seen[kind] += 1;
                check_vertex(kind, seen[kind], words.collect()).map_err(problem)?;
            }
            None => {}
        }
    }
    if let Some((line, count)) = unknown {
        let first = text.lines().nth(line - 1).and_then(|l| l.split_whitespace().next());
        let message = format!(
            "{count} statement(s) of no OBJ kind are ignored, the first '{}'",
            crate::excerpt::excerpt(first.unwrap_or(""))
        );
        scan.warnings.push(ScanProblem { line, message });
    }
    Ok(scan)
}

/// One `v`/`vt`/`vn` statement's numbers (`index` counts that kind from 1).
fn check_vertex(kind: usize, index: usize, words: Vec<&str>) -> Result<(), String> {
    let (keyword, name, _) = KINDS[kind];
    for word in &words {
        match word.parse::<f32>() {
            Err(_) => {
                return Err(format!(
                    "{name} {index}: '{}' is not a number",
                    crate::excerpt::excerpt(word)
                ));
            }
            Ok(x) if !x.is_finite() => {
                return Err(format!(
                    "{name} {index} has a non-finite coordinate '{}'",
                    crate::excerpt::excerpt(word)
                ));
            }
            Ok(_) => {}
        }
    }
    let allowed = COUNTS[kind];
    if !allowed.contains(&words.len()) {
        let allowed: Vec<String> = allowed.iter().map(|c| c.to_string()).collect();
        return Err(format!(
            "{name} {index}: `{keyword}` takes {} numbers, this one has {}",
            allowed.join(" or "),
            words.len()
        ));
    }
    if kind == 0 && words.len() == 4 && words[3].parse::<f32>() == Ok(0.0) {
        return Err(format!("{name} {index} has the weight w = 0"));
    }
    Ok(())
}

fn kind_of(keyword: &str) -> Option<usize> {
    KINDS.iter().position(|(k, _, _)| *k == keyword)
}

/// One face vertex `v`, `v/vt`, `v//vn` or `v/vt/vn`; indices are 1-based, negative ones
/// count back from the last element defined so far.
fn check_face_vertex(word: &str, seen: &[usize; 3], totals: &[usize; 3]) -> Result<(), String> {
    for (kind, part) in word.split('/').enumerate().take(3) {
        let (_, name, plural) = KINDS[kind];
        if part.is_empty() && kind > 0 {
            continue; // `v//vn` and `v/vt`: the element is absent
        }
        let Ok(index) = part.parse::<i64>() else {
            return Err(format!(
                "a face's {name} index '{}' is not a whole number (or is too large)",
                crate::excerpt::excerpt(part)
            ));
        };
        if index == 0 {
            return Err(format!("a face refers to {name} 0, but OBJ indices start at 1"));
        }
        if index > 0 && index.unsigned_abs() > totals[kind] as u64 {
            return Err(format!(
                "a face refers to {name} {index}, but the file has {} {plural}",
                totals[kind]
            ));
        }
        if index < 0 && index.unsigned_abs() > seen[kind] as u64 {
            return Err(format!(
                "a face refers to {name} {index} (relative), but only {} {plural} precede it",
                seen[kind]
            ));
        }
    }
    Ok(())
}

/// tobj panics on a colour statement (`Ka`, `Kd`, `Ks`, `Ke`) with fewer than 3 values.
/// What it drops without a word comes back as warnings: statements before the first
/// `newmtl` (they belong to no material) and a material defined again (tobj keeps the last
/// definition). Exporters write both, so neither is refused.
pub(crate) fn scan_mtl(text: &str) -> Result<Vec<ScanProblem>, ScanProblem> {
    let mut warnings = Vec::new();
    let mut defined: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    let mut orphans = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let problem = |message: String| ScanProblem { line: n + 1, message };
        let line = line.trim();
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else { continue };
        let number = |w: Option<&str>| w.is_some_and(|w| w.parse::<f32>().is_ok());
        // The statements tobj parses, checked as it parses them (it fails without a line).
        match keyword {
            "Ka" | "Kd" | "Ks" | "Ke"
                if words.clone().take(3).filter(|w| w.parse::<f32>().is_ok()).count() < 3 =>
            {
                return Err(problem(format!("{keyword} needs 3 numbers")));
            }
            "Ns" | "Ni" | "d" if !number(words.next()) => {
                return Err(problem(format!("{keyword} needs a number")));
            }
            "illum" if words.next().is_none_or(|w| w.parse::<u8>().is_err()) => {
                return Err(problem("illum needs a whole number from 0 to 255".into()));
            }
            "newmtl" | "map_Ka" | "map_Kd" | "map_Ks" | "map_Bump" | "map_bump" | "map_Ns"
            | "map_ns" | "map_NS" | "bump" | "map_d"
                if words.next().is_none() =>
            {
                let what = if keyword == "newmtl" { "a material name" } else { "a file name" };
                return Err(problem(format!("{keyword} needs {what}")));
            }
            _ => {}
        }
        if keyword == "newmtl" {
            // tobj's name: the rest of the trimmed line, trimmed.
            let name = line["newmtl".len()..].trim();
            if let Some(previous) = defined.insert(name, n + 1) {
                warnings.push(problem(format!(
                    "material '{}' is defined again: this definition replaces the one at line \
                     {previous}",
                    crate::excerpt::excerpt(name)
                )));
            }
        } else if defined.is_empty() && !keyword.starts_with('#') {
            orphans.push(n + 1);
        }
    }
    if let Some(&first) = orphans.first() {
        let message = format!(
            "{} statement(s) before the first newmtl belong to no material and are ignored",
            orphans.len()
        );
        warnings.insert(0, ScanProblem { line: first, message });
    }
    Ok(warnings)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_vertex_is_numbered() {
        let err = scan_obj("v 0 0 0\n# c\nv 1 nan 0\nf 1 2 1\n").unwrap_err();
        assert_eq!(err.line, 3);
        assert_eq!(err.message, "vertex 2 has a non-finite coordinate 'nan'");
    }

    #[test]
    fn malformed_statements_get_their_line() {
        let cases = [
            ("v 0 0\n", "takes 3 or 4 or 6 numbers, this one has 2"),
            ("v 0 abc 0\n", "'abc' is not a number"),
            ("v 0 0 0 1 junk\n", "'junk' is not a number"),
            ("v 0 0 0 1 2\n", "has 5"),
            ("v 0 0 0 0\n", "w = 0"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "too large"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "'x' is not a whole number"),
            ("usemtl\n", "usemtl needs"),
        ];
        for (text, expected) in cases {
            let err = scan_obj(text).unwrap_err();
            assert!(err.message.contains(expected), "{text:?}: {}", err.message);
            assert_eq!(err.line, text.lines().count(), "{text:?}");
        }
        let huge = format!("v 0 {} 0\n", "9".repeat(100_000));
        assert!(scan_obj(&huge).unwrap_err().message.len() < 300);
    }

    #[test]
    fn short_faces_and_materials_are_noted() {
        let scan = scan_obj("v 0 0 0\nv 1 0 0\nusemtl red paint\nf 1 2\n").unwrap();
        assert_eq!(scan.warnings[0].line, 4);
        assert_eq!(scan.usemtl, [("red paint".to_owned(), 3)]);
    }

    #[test]
    fn unknown_statements_are_counted_once_and_a_bom_is_skipped() {
        let scan = scan_obj("v 0 0 0\nvv 1 -1 0\ns off\n#c\nvv 2 0 0\nxyz\n").unwrap();
        assert_eq!(scan.warnings.len(), 1, "{:?}", scan.warnings);
        assert_eq!(scan.warnings[0].line, 2);
        assert!(scan.warnings[0].message.starts_with("3 statement(s)"), "{:?}", scan.warnings);
        assert!(scan.warnings[0].message.contains("'vv'"), "{:?}", scan.warnings);
        assert_eq!(without_bom("\u{feff}v 0 0 0\n".to_owned()), "v 0 0 0\n");
        assert_eq!(without_bom("v\u{feff}".to_owned()), "v\u{feff}");
    }

    #[test]
    fn f32_overflow_is_non_finite() {
        assert!(scan_obj("v 0 0 1e39\n").is_err());
    }

    #[test]
    fn face_indices_are_checked() {
        let verts = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        assert!(scan_obj(&format!("{verts}f 1 2 3\nf -1 -2 -3\n")).is_ok());
        let err = scan_obj(&format!("{verts}f 1 2 9\n")).unwrap_err();
        assert_eq!(
            (err.line, err.message.as_str()),
            (4, "a face refers to vertex 9, but the file has 3 vertices")
        );
        assert!(scan_obj(&format!("{verts}f 1 2 0\n")).unwrap_err().message.contains("start at 1"));
        assert!(
            scan_obj(&format!("{verts}f -1 -2 -4\n")).unwrap_err().message.contains("relative")
        );
        assert!(
            scan_obj(&format!("{verts}vn 0 0 1\nf 1//1 2//1 3//2\n"))
                .unwrap_err()
                .message
                .contains("normal 2")
        );
    }

    #[test]
    fn short_colour_is_reported() {
        let err = scan_mtl("newmtl a\nKd 0.5 0.5\n").unwrap_err();
        assert_eq!((err.line, err.message.as_str()), (2, "Kd needs 3 numbers"));
        assert!(scan_mtl("newmtl a\nKd 0.5 0.5 0.5\n").unwrap().is_empty());
    }

    #[test]
    fn dropped_mtl_statements_are_warned_about() {
        let text = "# made by a tool\nKd 1 0 0\nNs 10\nnewmtl a\nKd 0 1 0\nnewmtl  a \nnewmtl b\n";
        let warnings = scan_mtl(text).unwrap();
        let lines: Vec<usize> = warnings.iter().map(|w| w.line).collect();
        assert_eq!(lines, [2, 6], "{warnings:?}");
        assert!(warnings[0].message.starts_with("2 statement(s) before the first newmtl"));
        assert!(warnings[1].message.contains("'a' is defined again"), "{warnings:?}");
        assert!(warnings[1].message.contains("line 4"), "{warnings:?}");
    }
}
