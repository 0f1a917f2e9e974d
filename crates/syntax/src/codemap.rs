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

/// A 1-based line and column (column counted in characters).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct LineCol {
    pub line: usize,
    pub column: usize,
}

/// A named source text with its line index.
#[derive(Clone, Debug)]
pub struct CodeMap {
    name: String,
    source: String,
    line_starts: Vec<usize>,
}

impl CodeMap {
    pub fn new(name: impl Into<String>, source: impl Into<String>) -> CodeMap {
        let source = source.into();
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
        CodeMap {
            name: name.into(),
            source,
            line_starts,
        }
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn source(&self) -> &str {
        &self.source
    }

    /// Line and column of a byte offset (clamped to the text).
    pub fn line_col(&self, pos: usize) -> LineCol {
        let pos = pos.min(self.source.len());
        let line = match self.line_starts.binary_search(&pos) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = self.line_starts[line];
        let column = self
            .source
            .get(start..pos)
            .map(|s| s.chars().count())
            .unwrap_or(pos - start)
            + 1;
        LineCol {
            line: line + 1,
            column,
        }
    }

    /// The text of a 1-based line, without its line terminator.
    pub fn line_text(&self, line: usize) -> &str {
        let Some(&start) = self.line_starts.get(line.wrapping_sub(1)) else {
            return "";
        };
        let end = self
            .line_starts
            .get(line)
            .copied()
            .unwrap_or(self.source.len());
        self.source[start..end].trim_end_matches(['\n', '\r'])
    }

    /// The source text a span covers.
    pub fn snippet(&self, span: Span) -> &str {
        self.source
            .get(span.start as usize..span.end as usize)
            .unwrap_or("")
    }

    /// `file:line:col` of a span's start.
    pub fn location(&self, span: Span) -> String {
        let lc = self.line_col(span.start as usize);
        format!("{}:{}:{}", self.name, lc.line, lc.column)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lone_carriage_returns_end_lines() {
        let cm = CodeMap::new("f.comm", "a = 1\rb = 2\r\nc = (\r");
        assert_eq!(cm.line_col(6), LineCol { line: 2, column: 1 });
        assert_eq!(cm.line_col(13), LineCol { line: 3, column: 1 });
        assert_eq!(cm.line_text(2), "b = 2");
        assert_eq!(cm.line_text(3), "c = (");
    }

    #[test]
    fn line_col_counts_from_one() {
        let cm = CodeMap::new("f.comm", "a = 1\nbé = 2\n");
        assert_eq!(cm.line_col(0), LineCol { line: 1, column: 1 });
        assert_eq!(cm.line_col(6), LineCol { line: 2, column: 1 });
        // 'é' is two bytes but one column.
        assert_eq!(cm.line_col(9), LineCol { line: 2, column: 3 });
        assert_eq!(cm.line_text(2), "bé = 2");
        assert_eq!(cm.location(Span::new(6, 7)), "f.comm:2:1");
    }
}
