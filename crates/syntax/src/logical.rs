//! Logical line ends, marked before parsing.
//!
//! Python ends a statement at a line break that is outside brackets, strings
//! and comments and not escaped by `\`; inside brackets a line break is
//! ordinary whitespace. pest's implicit whitespace is one rule for the whole
//! grammar, so it cannot tell the two apart by itself: the grammar used to
//! push an entry on pest's stack at every bracket and let `WHITESPACE` accept
//! a line break only under such an entry. That made every choice,
//! option and repetition that can reach a bracket snapshot and rewind the
//! stack, and every skip look at it.
//!
//! Instead, this pass replaces each line break that ends a logical line by
//! [`LINE_END`] (a control byte that never appears in a command file), in a
//! copy of the same length: byte offsets, and so every span, are unchanged.
//! The grammar ends statements at [`LINE_END`] and `WHITESPACE` takes any
//! remaining line break. The AST builder reads names and literals from the
//! original text (no token ever contains a marked byte: triple-quoted
//! strings keep their line breaks).

use crate::diagnose::string_end;

/// The byte that marks the end of a logical line (ASCII "record separator").
pub const LINE_END: u8 = 0x1E;

/// Bytes the scan must look at; every other byte is skipped in a tight loop.
const SPECIAL: [bool; 256] = {
    let mut t = [false; 256];
    let special = b"#'\"([{)]}\\\n\r";
    let mut k = 0;
    while k < special.len() {
        t[special[k] as usize] = true;
        k += 1;
    }
    t
};

/// `source` with every line break that ends a logical line replaced by
/// [`LINE_END`] (both bytes of a `\r\n`). A stray closing bracket does not
/// make the depth negative, and an unterminated string ends at its line, so
/// that the parser reports those errors where they are.
pub fn mark_line_ends(source: &str) -> String {
    let mut bytes = source.as_bytes().to_vec();
    let n = bytes.len();
    let mut depth = 0usize;
    let mut i = 0;
    while i < n {
        i += bytes[i..]
            .iter()
            .position(|&b| SPECIAL[b as usize])
            .unwrap_or(n - i);
        if i >= n {
            break;
        }
        match bytes[i] {
            b'#' => {
                while i < n && !matches!(bytes[i], b'\n' | b'\r') {
                    i += 1;
                }
                continue;
            }
            b'\'' | b'"' => {
                i = string_end(&bytes, i).unwrap_or(i + 1);
                continue;
            }
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth = depth.saturating_sub(1),
            // A continuation: the line break after the backslash stays.
            b'\\' => {
                i += match (bytes.get(i + 1), bytes.get(i + 2)) {
                    (Some(b'\r'), Some(b'\n')) => 3,
                    (Some(b'\n' | b'\r'), _) => 2,
                    _ => 1,
                };
                continue;
            }
            b'\n' | b'\r' if depth == 0 => bytes[i] = LINE_END,
            _ => {}
        }
        i += 1;
    }
    // Only ASCII bytes were replaced by an ASCII byte: still UTF-8.
    String::from_utf8(bytes).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn marked(s: &str) -> String {
        mark_line_ends(s).replace('\u{1E}', "|")
    }

    #[test]
    fn only_logical_line_ends_are_marked() {
        assert_eq!(marked("a = f(1,\n  2)\nb = 3\n"), "a = f(1,\n  2)|b = 3|");
        assert_eq!(
            marked("x = 1 \\\n  + 2\r\ny = '(' # (\n"),
            "x = 1 \\\n  + 2||y = '(' # (|"
        );
        assert_eq!(
            marked("s = \"\"\"a\nb\"\"\"\nt = ')'\n"),
            "s = \"\"\"a\nb\"\"\"|t = ')'|"
        );
        assert_eq!(
            marked("x = ]\ny = 'open\nz = 1\n"),
            "x = ]|y = 'open|z = 1|"
        );
    }

    #[test]
    fn offsets_are_kept() {
        let s = "é = (1,\r\n 2)\r\n";
        assert_eq!(mark_line_ends(s).len(), s.len());
    }
}
