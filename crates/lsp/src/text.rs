//! Open documents: their text, kept current by incremental edits, and the
//! conversion between byte offsets (what the parser's spans are) and LSP
//! positions (a line and a column counted in UTF-16 code units).
//!
//! Lines end at `\n`, `\r\n` or a lone `\r`, as for the LSP and for
//! [`aster_syntax::CodeMap`]. A column past the end of its line is clamped to
//! the line's end, and a column inside a surrogate pair or a line past the
//! end of the text to the nearest valid place, as the specification asks.

use lsp_types::{Position, Range, TextDocumentContentChangeEvent};

/// The line starts of a text, for offset ↔ position conversions.
#[derive(Clone, Debug)]
pub struct LineIndex {
    /// Byte offset of the start of each line (the first is 0).
    starts: Vec<usize>,
    len: usize,
}

impl LineIndex {
    pub fn new(text: &str) -> LineIndex {
        let bytes = text.as_bytes();
        let mut starts = vec![0];
        for (i, &b) in bytes.iter().enumerate() {
            if b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')) {
                starts.push(i + 1);
            }
        }
        LineIndex {
            starts,
            len: text.len(),
        }
    }

    /// The byte offset of an LSP position in `text` (the text this index
    /// was made from).
    pub fn offset(&self, text: &str, pos: Position) -> usize {
        let line = pos.line as usize;
        let Some(&start) = self.starts.get(line) else {
            return self.len;
        };
        let end = self.line_end(text, line);
        let mut units = 0u32;
        for (i, c) in text[start..end].char_indices() {
            if units >= pos.character {
                return start + i;
            }
            units += c.len_utf16() as u32;
            if units > pos.character {
                // Inside a surrogate pair: the character's start.
                return start + i;
            }
        }
        end
    }

    /// The end of a line's content (before its terminator).
    fn line_end(&self, text: &str, line: usize) -> usize {
        let next = self.starts.get(line + 1).copied().unwrap_or(self.len);
        let s = &text[self.starts[line]..next];
        self.starts[line] + s.trim_end_matches(['\n', '\r']).len()
    }

    /// The LSP position of a byte offset (clamped to the text; an offset
    /// inside a character counts as that character's start).
    pub fn position(&self, text: &str, offset: usize) -> Position {
        let mut offset = offset.min(self.len);
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = match self.starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = self.starts[line];
        let character: usize = text[start..offset].chars().map(char::len_utf16).sum();
        Position::new(line as u32, character as u32)
    }

    pub fn range(&self, text: &str, start: usize, end: usize) -> Range {
        Range::new(self.position(text, start), self.position(text, end))
    }
}

/// An open document.
#[derive(Clone, Debug)]
pub struct Document {
    pub text: String,
    pub version: i32,
    pub index: LineIndex,
}

impl Document {
    pub fn new(text: String, version: i32) -> Document {
        let index = LineIndex::new(&text);
        Document {
            text,
            version,
            index,
        }
    }

    /// Applies the changes of one `didChange`, in order (each range is in
    /// the text as the previous change left it).
    pub fn apply(&mut self, changes: Vec<TextDocumentContentChangeEvent>, version: i32) {
        for change in changes {
            match change.range {
                Some(range) => {
                    let start = self.index.offset(&self.text, range.start);
                    let end = self.index.offset(&self.text, range.end).max(start);
                    self.text.replace_range(start..end, &change.text);
                }
                None => self.text = change.text,
            }
            self.index = LineIndex::new(&self.text);
        }
        self.version = version;
    }

    pub fn offset(&self, pos: Position) -> usize {
        self.index.offset(&self.text, pos)
    }

    pub fn position(&self, offset: usize) -> Position {
        self.index.position(&self.text, offset)
    }

    pub fn range(&self, start: usize, end: usize) -> Range {
        self.index.range(&self.text, start, end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_columns_count_surrogate_pairs_and_accents() {
        // `é` is one UTF-16 unit (2 bytes), `𝜎` two units (4 bytes).
        let text = "a = 'é𝜎x'\nB = 1\r\nC = 2\rD";
        let idx = LineIndex::new(text);
        let x = text.find('x').unwrap();
        assert_eq!(idx.position(text, x), Position::new(0, 8));
        assert_eq!(idx.offset(text, Position::new(0, 8)), x);
        // Inside the surrogate pair of 𝜎: the character's start.
        let sigma = text.find('𝜎').unwrap();
        assert_eq!(idx.offset(text, Position::new(0, 7)), sigma);
        // Lines after \r\n and a lone \r.
        assert_eq!(
            idx.offset(text, Position::new(2, 0)),
            text.find('C').unwrap()
        );
        assert_eq!(
            idx.offset(text, Position::new(3, 0)),
            text.find('D').unwrap()
        );
        // A column past the end of a line is the line's end, not the next line.
        assert_eq!(
            idx.offset(text, Position::new(1, 99)),
            text.find("\r\n").unwrap()
        );
        // A line past the end is the end of the text.
        assert_eq!(idx.offset(text, Position::new(9, 0)), text.len());
    }

    #[test]
    fn incremental_edits_apply_in_order() {
        let mut doc = Document::new("MA = LIRE_MAILLAGE()\n".into(), 1);
        let at = |l, c| Position::new(l, c);
        doc.apply(
            vec![
                TextDocumentContentChangeEvent {
                    range: Some(Range::new(at(0, 19), at(0, 19))),
                    range_length: None,
                    text: "UNITE=20".into(),
                },
                TextDocumentContentChangeEvent {
                    range: Some(Range::new(at(0, 0), at(0, 2))),
                    range_length: None,
                    text: "mesh".into(),
                },
            ],
            2,
        );
        assert_eq!(doc.text, "mesh = LIRE_MAILLAGE(UNITE=20)\n");
        assert_eq!(doc.version, 2);
    }
}
