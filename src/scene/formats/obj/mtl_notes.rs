//! Warnings about MTL statements, gathered per MTL file and message: exporters write the same
//! statements into every material (Sponza's 25 materials each have `Ka`), and one line per
//! material would bury the rest of a scene's warnings.

use std::path::{Path, PathBuf};

/// The most places one gathered warning lists.
const MAX_PLACES: usize = 4;

/// The most kinds of unknown statement one MTL file is warned about by name; the rest are
/// gathered in one warning (a file of 80,000 made-up keywords made as many warnings).
const MAX_UNKNOWN_KINDS: usize = 8;

/// A note that one statement of one material was not (fully) used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Note {
    pub line: usize,
    pub message: String,
    /// A statement of no kind embray knows (`MAX_UNKNOWN_KINDS`).
    pub unknown: bool,
}

impl Note {
    pub fn new(line: usize, message: impl Into<String>) -> Self {
        Note { line, message: message.into(), unknown: false }
    }

    /// A statement `keyword` embray does not know.
    pub fn unknown(line: usize, keyword: &str) -> Self {
        let keyword = crate::excerpt::excerpt(keyword);
        Note {
            unknown: true,
            ..Note::new(line, format!("'{keyword}' is not an MTL statement embray knows"))
        }
    }
}

/// The notes of every MTL material mapped so far, in the order first seen.
#[derive(Debug, Default)]
pub(crate) struct MtlNotes {
    groups: Vec<Group>,
    /// Each group's index by file and message (a scan of the groups was n²).
    index: std::collections::HashMap<(PathBuf, String), usize>,
    /// How many kinds of unknown statement each file has a group of.
    unknown_kinds: std::collections::HashMap<PathBuf, usize>,
}

#[derive(Debug)]
struct Group {
    mtl: PathBuf,
    message: String,
    /// (material, line)
    places: Vec<(String, usize)>,
}

impl MtlNotes {
    pub fn add(&mut self, mtl: &Path, material: &str, note: Note) {
        let place = (crate::excerpt::excerpt(material), note.line);
        let mut key = (mtl.to_path_buf(), note.message);
        if note.unknown && !self.index.contains_key(&key) {
            let kinds = self.unknown_kinds.entry(mtl.to_path_buf()).or_default();
            if *kinds >= MAX_UNKNOWN_KINDS {
                key.1 = "other statements embray does not know".to_owned();
            } else {
                *kinds += 1;
            }
        }
        match self.index.get(&key) {
            Some(&group) => self.groups[group].places.push(place),
            None => {
                self.index.insert(key.clone(), self.groups.len());
                let (mtl, message) = key;
                self.groups.push(Group { mtl, message, places: vec![place] });
            }
        }
    }

    /// One warning per MTL file and message, naming the first few places.
    pub fn flush(self, warnings: &mut Vec<String>) {
        for group in self.groups {
            let mut places: Vec<String> = group
                .places
                .iter()
                .take(MAX_PLACES)
                .map(|(material, line)| format!("material '{material}', line {line}"))
                .collect();
            if group.places.len() > MAX_PLACES {
                places.push(format!("{} more", group.places.len() - MAX_PLACES));
            }
            warnings.push(format!(
                "{}: {} ({})",
                group.mtl.display(),
                group.message,
                places.join("; ")
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_message_of_one_file_is_said_once() {
        let mut notes = MtlNotes::default();
        let a = Path::new("a.mtl");
        for (i, material) in ["m0", "m1", "m2", "m3", "m4", "m5"].into_iter().enumerate() {
            notes.add(a, material, Note::new(10 * i + 2, "Ka is not used"));
        }
        notes.add(a, "m0", Note::new(3, "Tf is not used"));
        notes.add(Path::new("b.mtl"), "m0", Note::new(2, "Ka is not used"));
        let mut warnings = Vec::new();
        notes.flush(&mut warnings);
        assert_eq!(
            warnings,
            [
                "a.mtl: Ka is not used (material 'm0', line 2; material 'm1', line 12; \
                 material 'm2', line 22; material 'm3', line 32; 2 more)",
                "a.mtl: Tf is not used (material 'm0', line 3)",
                "b.mtl: Ka is not used (material 'm0', line 2)",
            ]
        );
    }

    #[test]
    fn many_kinds_of_unknown_statement_are_gathered_past_the_first_few() {
        let mut notes = MtlNotes::default();
        let a = Path::new("a.mtl");
        for i in 0..1000 {
            notes.add(a, "m0", Note::unknown(i + 2, &format!("zz{i}")));
        }
        notes.add(a, "m0", Note::unknown(5000, "zz3"));
        let mut warnings = Vec::new();
        notes.flush(&mut warnings);
        assert_eq!(warnings.len(), MAX_UNKNOWN_KINDS + 1, "{warnings:?}");
        assert_eq!(
            warnings[3],
            "a.mtl: 'zz3' is not an MTL statement embray knows (material 'm0', line 5; material 'm0', line 5000)"
        );
        assert_eq!(
            warnings[MAX_UNKNOWN_KINDS],
            "a.mtl: other statements embray does not know (material 'm0', line 10; material 'm0', \
             line 11; material 'm0', line 12; material 'm0', line 13; 988 more)"
        );
    }
}
