//! A pass over OBJ and MTL text before tobj sees it, for the problems tobj reports without
//! a line (or not at all, or by panicking): non-finite coordinates, out-of-range face
//! indices, colour statements with fewer than 3 numbers.

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

/// Checks every `v`/`vt`/`vn` number (as tobj parses them, in f32) and every face index.
pub(crate) fn scan_obj(text: &str) -> Result<(), ScanProblem> {
    let mut totals = [0usize; 3];
    for line in text.lines() {
        if let Some(kind) = line.split_whitespace().next().and_then(kind_of) {
            totals[kind] += 1;
        }
    }
    let mut seen = [0usize; 3];
    for (n, line) in text.lines().enumerate() {
        let problem = |message: String| ScanProblem { line: n + 1, message };
        let mut words = line.split_whitespace();
        match words.next() {
            Some("f") => {
                for word in words {
                    check_face_vertex(word, &seen, &totals).map_err(problem)?;
                }
            }
            Some(keyword) => {
                let Some(kind) = kind_of(keyword) else {
                    continue;
                };
                seen[kind] += 1;
                for word in words {
                    if word.parse::<f32>().is_ok_and(|x| !x.is_finite()) {
                        let (_, name, _) = KINDS[kind];
                        let index = seen[kind];
                        return Err(problem(format!(
                            "{name} {index} has a non-finite coordinate '{word}'"
                        )));
                    }
                }
            }
            None => {}
        }
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
        let Ok(index) = part.parse::<i64>() else {
            continue;
        }; // empty or malformed: tobj reports it
        let (_, name, plural) = KINDS[kind];
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
pub(crate) fn scan_mtl(text: &str) -> Result<(), ScanProblem> {
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if let Some(keyword @ ("Ka" | "Kd" | "Ks" | "Ke")) = words.next() {
            if words.count() < 3 {
                return Err(ScanProblem {
                    line: n + 1,
                    message: format!("{keyword} needs 3 numbers"),
                });
            }
        }
    }
    Ok(())
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
        assert!(scan_mtl("newmtl a\nKd 0.5 0.5 0.5\n").is_ok());
    }
}
