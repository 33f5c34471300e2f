//! Line numbers of byte offsets in a text, from one pass over it: a reader that notes the
//! line of every element asks once per element, and counting from the start each time (as
//! `roxmltree::Document::text_pos_at` does) made a file of n elements cost n² (a Mitsuba
//! file of 50,000 elements took 8 s to read).

/// The offsets of a text's line breaks.
pub(crate) struct LineIndex {
    newlines: Vec<usize>,
}

impl LineIndex {
    pub fn new(text: &str) -> Self {
        let newlines = text.bytes().enumerate().filter(|&(_, b)| b == b'\n').map(|(i, _)| i);
        LineIndex { newlines: newlines.collect() }
    }

    /// The line (from 1) of byte `pos`: one more than the line breaks before it, as
    /// `text_pos_at` counts.
    pub fn line_at(&self, pos: usize) -> usize {
        1 + self.newlines.partition_point(|&newline| newline < pos)
    }
}

#[cfg(test)]
mod tests {
    use super::LineIndex;

    #[test]
    fn lines_are_those_roxmltree_counts() {
        let text = "<a>\n\n<b/>\r\n<c\n x='1'/>\n</a>\n";
        let doc = roxmltree::Document::parse(text).unwrap();
        let lines = LineIndex::new(text);
        for pos in 0..=text.len() + 3 {
            let expected = doc.text_pos_at(pos).row as usize;
            assert_eq!(lines.line_at(pos), expected, "byte {pos}");
        }
        assert_eq!(LineIndex::new("").line_at(0), 1);
    }
}
