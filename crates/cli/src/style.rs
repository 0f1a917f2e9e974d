//! Colour when the output is a terminal.
//!
//! The text is styled with ANSI codes here and written through `anstream`,
//! which strips them when the stream is not a terminal (a pipe, a file, CI
//! logs) and honours `NO_COLOR` and `CLICOLOR_FORCE`. What is coloured is
//! what a reader scans for: in a diagnostic the level (`error` red,
//! `warning` yellow), the location, the gutter and the caret; in the
//! TEST_RESU listing the verdicts (`NOOK` red, `OK` green). The plain text
//! is unchanged, so scripts reading a pipe see the same bytes as before.

use anstyle::{AnsiColor, Style};
use std::io::Write;

const ERROR: Style = AnsiColor::Red.on_default().bold();
const WARNING: Style = AnsiColor::Yellow.on_default().bold();
const GUTTER: Style = AnsiColor::Blue.on_default().bold();
const BOLD: Style = Style::new().bold();
const OK: Style = AnsiColor::Green.on_default().bold();

fn paint(style: Style, text: &str) -> String {
    format!("{style}{text}{style:#}")
}

/// The level word of a headline `file:line:col: error: message` (or a
/// bare `error: message`) and its byte range in the line.
fn level_of(line: &str) -> Option<(usize, &'static str, Style)> {
    for (word, style) in [("error", ERROR), ("warning", WARNING)] {
        if line.starts_with(&format!("{word}: ")) {
            return Some((0, word, style));
        }
        if let Some(p) = line.find(&format!(": {word}: ")) {
            return Some((p + 2, word, style));
        }
    }
    None
}

/// One line of a rendered diagnostic (rustc style), styled.
fn diagnostic_line(line: &str) -> String {
    if let Some((at, word, style)) = level_of(line) {
        let (loc, rest) = line.split_at(at);
        let message = &rest[word.len()..];
        let loc = if loc.is_empty() {
            String::new()
        } else {
            paint(BOLD, loc)
        };
        return format!("{loc}{}{}", paint(style, word), paint(BOLD, message));
    }
    // The gutter: `12 | source`, `   | ^^^`, `   = help: …`.
    let digits_and_spaces = |s: &str| s.chars().all(|c| c == ' ' || c.is_ascii_digit());
    if let Some(p) = line.find(" |") {
        if digits_and_spaces(&line[..p]) {
            let (gutter, rest) = line.split_at(p + 2);
            let trimmed = rest.trim();
            let rest = if !trimmed.is_empty() && trimmed.chars().all(|c| c == '^' || c == '-') {
                let lead = rest.len() - rest.trim_start().len();
                format!("{}{}", &rest[..lead], paint(ERROR, rest.trim_start()))
            } else {
                rest.to_string()
            };
            return format!("{}{rest}", paint(GUTTER, gutter));
        }
    }
    if let Some(p) = line.find(" = ") {
        if digits_and_spaces(&line[..p]) {
            let (gutter, rest) = line.split_at(p + 3);
            let (kind, text) = rest.split_once(':').unwrap_or(("", rest));
            let kind = if kind.is_empty() {
                String::new()
            } else {
                format!("{}:", paint(BOLD, kind))
            };
            return format!("{}{kind}{text}", paint(GUTTER, gutter));
        }
    }
    line.to_string()
}

/// A rendered diagnostic (one or more, rustc style), styled line by line.
pub fn diagnostic(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 64);
    for piece in text.split_inclusive('\n') {
        let (line, nl) = match piece.strip_suffix('\n') {
            Some(l) => (l, "\n"),
            None => (piece, ""),
        };
        out.push_str(&diagnostic_line(line));
        out.push_str(nl);
    }
    out
}

/// Prints rendered diagnostics on stderr, coloured on a terminal.
pub fn eprint_diagnostic(text: &str) {
    let mut err = anstream::stderr();
    let _ = err.write_all(diagnostic(text).as_bytes());
    if !text.ends_with('\n') {
        let _ = err.write_all(b"\n");
    }
}

/// One line of the TEST_RESU listing, styled: the verdict at its start.
fn listing_line(line: &str) -> String {
    if let Some(rest) = line.strip_prefix("NOOK") {
        format!("{}{rest}", paint(ERROR, "NOOK"))
    } else if let Some(rest) = line.strip_prefix(" OK ") {
        format!(" {} {rest}", paint(OK, "OK"))
    } else {
        line.to_string()
    }
}

/// A writer for the run's listing: complete lines are styled and passed on
/// to a colour-aware stdout.
pub struct Listing<W: Write> {
    inner: W,
    pending: Vec<u8>,
}

impl Listing<anstream::Stdout> {
    /// The listing on stdout, coloured on a terminal.
    pub fn stdout() -> Self {
        Listing {
            inner: anstream::stdout(),
            pending: Vec::new(),
        }
    }
}

impl<W: Write> Listing<W> {
    /// Writes the complete lines received so far in one piece (stdout is
    /// line-buffered: one `write` for them all rather than one per line),
    /// keeping the unfinished last line.
    fn emit_lines(&mut self) -> std::io::Result<()> {
        let Some(end) = self.pending.iter().rposition(|&b| b == b'\n') else {
            return Ok(());
        };
        let mut out = String::with_capacity(end + 1);
        for line in self.pending[..end].split(|&b| b == b'\n') {
            out.push_str(&listing_line(&String::from_utf8_lossy(line)));
            out.push('\n');
        }
        self.pending.drain(..=end);
        self.inner.write_all(out.as_bytes())
    }
}

impl<W: Write> Write for Listing<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.pending.extend_from_slice(buf);
        self.emit_lines()?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        if !self.pending.is_empty() {
            let rest = std::mem::take(&mut self.pending);
            self.inner.write_all(&rest)?;
        }
        self.inner.flush()
    }
}

impl<W: Write> Drop for Listing<W> {
    fn drop(&mut self) {
        let _ = self.flush();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The codes anstream would strip, removed: the plain text is intact.
    fn strip(s: &str) -> String {
        let mut out = String::new();
        let mut chars = s.chars();
        while let Some(c) = chars.next() {
            if c == '\x1b' {
                for d in chars.by_ref() {
                    if d == 'm' {
                        break;
                    }
                }
            } else {
                out.push(c);
            }
        }
        out
    }

    const RENDERED: &str = "a.comm:8:33: error: unknown keyword GROUP_MA_ESC\n  |\n8 |     ZONE=_F(GROUP_MA_ESC=\"AB\"),\n  |             ^^^^^^^^^^^^\n  = help: did you mean `GROUP_MA_ESCL`?\n";

    #[test]
    fn a_diagnostic_keeps_its_text_and_colours_level_gutter_and_caret() {
        let styled = diagnostic(RENDERED);
        assert_eq!(strip(&styled), RENDERED);
        let lines: Vec<&str> = styled.lines().collect();
        assert!(lines[0].contains(&paint(ERROR, "error")), "{styled:?}");
        assert!(
            lines[0].starts_with(&paint(BOLD, "a.comm:8:33: ")),
            "{styled:?}"
        );
        assert!(lines[2].starts_with(&paint(GUTTER, "8 |")), "{styled:?}");
        assert!(
            lines[3].ends_with(&paint(ERROR, "^^^^^^^^^^^^")),
            "{styled:?}"
        );
        assert!(lines[4].contains(&paint(BOLD, "help")), "{styled:?}");
        // The source line itself is not touched.
        assert!(lines[2].ends_with("    ZONE=_F(GROUP_MA_ESC=\"AB\"),"));
    }

    #[test]
    fn warnings_and_bare_errors_are_coloured_too() {
        let w = diagnostic("f.comm:1:1: warning: legacy name");
        assert!(w.contains(&paint(WARNING, "warning")), "{w:?}");
        let e = diagnostic("error: cannot read x");
        assert!(e.starts_with(&paint(ERROR, "error")), "{e:?}");
        // A line that only looks like a gutter elsewhere is left alone.
        assert_eq!(diagnostic("x | y"), "x | y");
    }

    #[test]
    fn the_listing_colours_verdicts_and_passes_partial_lines_through() {
        let mut out = Vec::new();
        {
            let mut l = Listing {
                inner: &mut out,
                pending: Vec::new(),
            };
            let _ = l.write_all(b" OK   NON_REGRESSION  1.0\nNOOK  ANALYTIQUE");
            let _ = l.write_all(b"  2.0\nTEST_RESU: 1 OK, 1 NOOK");
        }
        let text = String::from_utf8_lossy(&out).to_string();
        assert_eq!(
            strip(&text),
            " OK   NON_REGRESSION  1.0\nNOOK  ANALYTIQUE  2.0\nTEST_RESU: 1 OK, 1 NOOK"
        );
        assert!(
            text.starts_with(&format!(" {} ", paint(OK, "OK"))),
            "{text:?}"
        );
        assert!(text.contains(&paint(ERROR, "NOOK")), "{text:?}");
    }

    /// The writes the listing makes to its stream.
    struct Writes(Vec<Vec<u8>>);

    impl Write for Writes {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            self.0.push(buf.to_vec());
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn the_listing_passes_a_chunk_of_lines_in_one_write() {
        let mut l = Listing {
            inner: Writes(Vec::new()),
            pending: Vec::new(),
        };
        let _ = l.write_all(b"a\n\nNOOK b\nc");
        assert_eq!(l.inner.0.len(), 1, "{:?}", l.inner.0);
        assert_eq!(
            strip(&String::from_utf8_lossy(&l.inner.0[0])),
            "a\n\nNOOK b\n"
        );
        let _ = l.write_all(b"d\n");
        let _ = l.flush();
        let writes: Vec<String> = l
            .inner
            .0
            .iter()
            .map(|w| strip(&String::from_utf8_lossy(w)))
            .collect();
        assert_eq!(writes, ["a\n\nNOOK b\n", "cd\n"]);
    }
}
