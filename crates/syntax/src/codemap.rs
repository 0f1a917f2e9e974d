//! Source positions. Every AST node carries a [`Span`] (a byte range into the
//! source); line/column are computed on demand through a [`CodeMap`], so the
//! AST stays small and positions stay exact.

use serde::Serialize;

/// A half-open byte range `[start, end)` into one source file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Span {
    pub start: u32,
    pub end: u32,
}

/// Serialized compactly as `[start, end]` (byte offsets).
impl Serialize for Span {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        [self.start, self.end].serialize(serializer)
    }
}

impl Span {
    pub fn new(start: usize, end: usize) -> Span {
        Span {
            start: start as u32,
            end: end as u32,
        }
    }

    /// The smallest span covering both.
    pub fn merge(self, other: Span) -> Span {
        Span {
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }
}

/// A 1-based line and column (column counted in characters), in the file
/// of the [`CodeMap`] that holds the position.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct LineCol {
    pub line: usize,
    pub column: usize,
    /// Which file of the map (0 for the first).
    #[serde(skip)]
    pub file: usize,
}

/// One source text of a map: its name, text, line index and where its
/// bytes start in the map's offset space.
#[derive(Clone, Debug)]
struct SourceFile {
    name: String,
    source: String,
    line_starts: Vec<usize>,
    base: usize,
}

/// Named source texts with their line index. A map usually holds one file;
/// a study (several command files, the Python modules they import) holds
/// several, each in its own range of offsets ([`CodeMap::add_file`]), so
/// that a span alone tells the file it comes from.
#[derive(Clone, Debug)]
pub struct CodeMap {
    files: Vec<SourceFile>,
}

impl CodeMap {
    pub fn new(name: impl Into<String>, source: impl Into<String>) -> CodeMap {
        let mut map = CodeMap { files: Vec::new() };
        map.add_file(name, source);
        map
    }

    /// Adds a file after the others; returns the offset its spans start at
    /// (parse it with `parse_module_at(source, base)`).
    pub fn add_file(&mut self, name: impl Into<String>, source: impl Into<String>) -> usize {
        let source = source.into();
        // One byte of gap: a span at the end of a file is not the start of the next.
        let base = self
            .files
            .last()
            .map(|f| f.base + f.source.len() + 1)
            .unwrap_or(0);
        let mut line_starts = vec![0];
        // A line ends at `\n`, `\r\n` or a lone `\r` (old Mac files),
        // as for Python.
        let bytes = source.as_bytes();
        line_starts.extend(
            bytes
                .iter()
                .enumerate()
                .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')))
                .map(|(i, _)| i + 1),
        );
        self.files.push(SourceFile {
            name: name.into(),
            source,
            line_starts,
            base,
        });
        base
    }

    /// The name of the first file.
    pub fn name(&self) -> &str {
        &self.files[0].name
    }

    /// The text of the first file.
    pub fn source(&self) -> &str {
        &self.files[0].source
    }

    /// The file holding a global offset (the last one starting at or before it).
    fn file_at(&self, pos: usize) -> (usize, &SourceFile) {
        let i = self
            .files
            .partition_point(|f| f.base <= pos)
            .saturating_sub(1);
        (i, &self.files[i])
    }

    /// Line and column of a byte offset (clamped to its file's text).
    pub fn line_col(&self, pos: usize) -> LineCol {
        let (file, f) = self.file_at(pos);
        let pos = (pos - f.base).min(f.source.len());
        let line = match f.line_starts.binary_search(&pos) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = f.line_starts[line];
        let column = f
            .source
            .get(start..pos)
            .map(|s| s.chars().count())
            .unwrap_or(pos - start)
            + 1;
        LineCol {
            line: line + 1,
            column,
            file,
        }
    }

    /// The text of a 1-based line of the first file, without its line terminator.
    pub fn line_text(&self, line: usize) -> &str {
        self.file_line_text(0, line)
    }

    /// The text of the line a [`LineCol`] points into (in its own file).
    pub fn line_text_at(&self, lc: LineCol) -> &str {
        self.file_line_text(lc.file, lc.line)
    }

    fn file_line_text(&self, file: usize, line: usize) -> &str {
        let Some(f) = self.files.get(file) else {
            return "";
        };
        let Some(&start) = f.line_starts.get(line.wrapping_sub(1)) else {
            return "";
        };
        let end = f.line_starts.get(line).copied().unwrap_or(f.source.len());
        f.source[start..end].trim_end_matches(['\n', '\r'])
    }

    /// The source text a span covers.
    pub fn snippet(&self, span: Span) -> &str {
        let (_, f) = self.file_at(span.start as usize);
        let (start, end) = (span.start as usize, span.end as usize);
        if start < f.base || end < start {
            return "";
        }
        f.source.get(start - f.base..end - f.base).unwrap_or("")
    }

    /// The name of a file of the map (`LineCol::file`).
    pub fn file_name(&self, file: usize) -> &str {
        self.files.get(file).map_or("", |f| f.name.as_str())
    }

    /// `file:line:col` of a span's start.
    pub fn location(&self, span: Span) -> String {
        let lc = self.line_col(span.start as usize);
        format!("{}:{}:{}", self.files[lc.file].name, lc.line, lc.column)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lone_carriage_returns_end_lines() {
        let cm = CodeMap::new("f.comm", "a = 1\rb = 2\r\nc = (\r");
        assert_eq!(
            cm.line_col(6),
            LineCol {
                line: 2,
                column: 1,
                file: 0
            }
        );
        assert_eq!(
            cm.line_col(13),
            LineCol {
                line: 3,
                column: 1,
                file: 0
            }
        );
        assert_eq!(cm.line_text(2), "b = 2");
        assert_eq!(cm.line_text(3), "c = (");
    }

    #[test]
    fn line_col_counts_from_one() {
        let cm = CodeMap::new("f.comm", "a = 1\nbé = 2\n");
        let lc = |line, column| LineCol {
            line,
            column,
            file: 0,
        };
        assert_eq!(cm.line_col(0), lc(1, 1));
        assert_eq!(cm.line_col(6), lc(2, 1));
        // 'é' is two bytes but one column.
        assert_eq!(cm.line_col(9), lc(2, 3));
        assert_eq!(cm.line_text(2), "bé = 2");
        assert_eq!(cm.location(Span::new(6, 7)), "f.comm:2:1");
    }

    #[test]
    fn several_files_share_one_offset_space() {
        let mut cm = CodeMap::new("a.comm", "x = 1\n");
        let base = cm.add_file("b.com1", "y = 2\nz = 3\n");
        assert_eq!(base, 7);
        assert_eq!(cm.location(Span::new(0, 1)), "a.comm:1:1");
        assert_eq!(cm.location(Span::new(base + 6, base + 7)), "b.com1:2:1");
        let lc = cm.line_col(base + 8);
        assert_eq!((lc.line, lc.column, lc.file), (2, 3, 1));
        assert_eq!(cm.line_text_at(lc), "z = 3");
        assert_eq!(cm.snippet(Span::new(base + 4, base + 5)), "2");
        assert_eq!(cm.name(), "a.comm");
    }
}
