//! Warnings about MTL statements, gathered per MTL file and message: exporters write the same
//! statements into every material (Sponza's 25 materials each have `Ka`), and one line per
//! material would bury the rest of a scene's warnings.

use std::path::{Path, PathBuf};

/// The most places one gathered warning lists.
const MAX_PLACES: usize = 4;

/// A note that one statement of one material was not (fully) used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Note {
    pub line: usize,
    pub message: String,
}

impl Note {
    pub fn new(line: usize, message: impl Into<String>) -> Self {
        Note { line, message: message.into() }
    }
}

/// The notes of every MTL material mapped so far, in the order first seen.
#[derive(Debug, Default)]
pub(crate) struct MtlNotes {
    groups: Vec<Group>,
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
        match self.groups.iter_mut().find(|g| g.mtl == mtl && g.message == note.message) {
            Some(group) => group.places.push(place),
            None => self.groups.push(Group {
                mtl: mtl.to_path_buf(),
                message: note.message,
                places: vec![place],
            }),
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
}
