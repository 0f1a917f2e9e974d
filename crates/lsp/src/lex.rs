//! A tolerant tokenizer of command files. The parser (`aster-syntax`) is
//! exact but a file being typed rarely parses (`AFFE_MODELE(MAILLAGE=MA, `
//! is not Python yet): completion, hover, signature help and navigation read
//! this token stream instead, which never fails — an unterminated string
//! runs to the end of its line, an unknown character is skipped.

/// What a token is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Name,
    /// A string literal (any quotes and prefixes); `closed` says whether
    /// its closing quote was found.
    Str {
        closed: bool,
    },
    Number,
    /// `(`, `[`, `{`.
    Open,
    /// `)`, `]`, `}`.
    Close,
    Comma,
    /// `=` alone (not `==`, `<=`, `+=`…).
    Assign,
    Dot,
    /// Any other operator or punctuation (`:`, `==`, `+`, `;`…).
    Op,
    /// The end of a line outside brackets (a logical line ends).
    Newline,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Token {
    pub kind: Kind,
    pub start: usize,
    pub end: usize,
}

impl Token {
    pub fn text<'t>(&self, src: &'t str) -> &'t str {
        &src[self.start..self.end]
    }
}

fn is_name_start(c: char) -> bool {
    c == '_' || c.is_alphabetic()
}

fn is_name_char(c: char) -> bool {
    c == '_' || c.is_alphanumeric()
}

/// The content of a string token (without prefix and quotes).
pub fn str_content<'t>(src: &'t str, t: &Token) -> &'t str {
    let s = t.text(src);
    let s = s.trim_start_matches(|c: char| c.is_ascii_alphabetic());
    for q in ["'''", "\"\"\"", "'", "\""] {
        if let Some(rest) = s.strip_prefix(q) {
            return rest.strip_suffix(q).unwrap_or(rest);
        }
    }
    s
}

/// The byte range of a string token's content.
pub fn str_content_range(src: &str, t: &Token) -> (usize, usize) {
    let content = str_content(src, t);
    let s = t.text(src);
    // `content` is a slice of `s`.
    let start = t.start + (content.as_ptr() as usize - s.as_ptr() as usize);
    (start, start + content.len())
}

/// Tokenizes `src` (comments and blanks dropped).
pub fn tokens(src: &str) -> Vec<Token> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut depth = 0usize;
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        match c {
            b' ' | b'\t' | b'\x0c' => i += 1,
            b'\\' if matches!(b.get(i + 1), Some(b'\n' | b'\r')) => {
                // A continued line.
                i += 2;
                if b[i - 1] == b'\r' && b.get(i) == Some(&b'\n') {
                    i += 1;
                }
            }
            b'\n' | b'\r' => {
                if depth == 0 && out.last().is_some_and(|t: &Token| t.kind != Kind::Newline) {
                    out.push(Token {
                        kind: Kind::Newline,
                        start: i,
                        end: i + 1,
                    });
                }
                i += 1;
            }
            b'#' => {
                while i < b.len() && b[i] != b'\n' && b[i] != b'\r' {
                    i += 1;
                }
            }
            b'\'' | b'"' => i = string(b, i, i, &mut out),
            b'0'..=b'9' => {
                let start = i;
                while i < b.len()
                    && (b[i].is_ascii_alphanumeric()
                        || b[i] == b'.'
                        || b[i] == b'_'
                        || ((b[i] == b'+' || b[i] == b'-') && matches!(b[i - 1], b'e' | b'E')))
                {
                    i += 1;
                }
                out.push(Token {
                    kind: Kind::Number,
                    start,
                    end: i,
                });
            }
            b'.' if b.get(i + 1).is_some_and(u8::is_ascii_digit) => {
                let start = i;
                i += 1;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'.') {
                    i += 1;
                }
                out.push(Token {
                    kind: Kind::Number,
                    start,
                    end: i,
                });
            }
            b'(' | b'[' | b'{' => {
                depth += 1;
                out.push(Token {
                    kind: Kind::Open,
                    start: i,
                    end: i + 1,
                });
                i += 1;
            }
            b')' | b']' | b'}' => {
                depth = depth.saturating_sub(1);
                out.push(Token {
                    kind: Kind::Close,
                    start: i,
                    end: i + 1,
                });
                i += 1;
            }
            b',' => {
                out.push(Token {
                    kind: Kind::Comma,
                    start: i,
                    end: i + 1,
                });
                i += 1;
            }
            b'.' => {
                out.push(Token {
                    kind: Kind::Dot,
                    start: i,
                    end: i + 1,
                });
                i += 1;
            }
            b'=' if b.get(i + 1) != Some(&b'=') => {
                out.push(Token {
                    kind: Kind::Assign,
                    start: i,
                    end: i + 1,
                });
                i += 1;
            }
            _ if c.is_ascii() && !c.is_ascii_alphabetic() && c != b'_' => {
                // Operators: a run of operator characters (`==`, `<=`, `**=`).
                let start = i;
                i += 1;
                while i < b.len() && b"=<>!*/%&|^~-+:;@".contains(&b[i]) && b[start] != b':' {
                    i += 1;
                }
                out.push(Token {
                    kind: Kind::Op,
                    start,
                    end: i,
                });
            }
            _ => {
                let Some(ch) = src[i..].chars().next() else {
                    break;
                };
                if !is_name_start(ch) {
                    i += ch.len_utf8();
                    continue;
                }
                let start = i;
                let mut j = i;
                for (k, ch) in src[i..].char_indices() {
                    if !is_name_char(ch) {
                        break;
                    }
                    j = i + k + ch.len_utf8();
                }
                // A string prefix (`r'…'`, `f"…"`, `u'…'`, `br'…'`).
                let word = &src[start..j];
                if word.len() <= 2
                    && word.chars().all(|c| "rRbBuUfF".contains(c))
                    && matches!(b.get(j), Some(b'\'' | b'"'))
                {
                    i = string(b, start, j, &mut out);
                    continue;
                }
                out.push(Token {
                    kind: Kind::Name,
                    start,
                    end: j,
                });
                i = j;
            }
        }
    }
    out
}

/// Reads a string literal whose token starts at `start` and whose quote is
/// at `q`; returns the offset after it.
fn string(b: &[u8], start: usize, q: usize, out: &mut Vec<Token>) -> usize {
    let quote = b[q];
    let triple = b.get(q + 1) == Some(&quote) && b.get(q + 2) == Some(&quote);
    let mut i = if triple { q + 3 } else { q + 1 };
    let mut closed = false;
    while i < b.len() {
        match b[i] {
            b'\\' => i += 2,
            c if c == quote => {
                if !triple {
                    i += 1;
                    closed = true;
                    break;
                }
                if b.get(i + 1) == Some(&quote) && b.get(i + 2) == Some(&quote) {
                    i += 3;
                    closed = true;
                    break;
                }
                i += 1;
            }
            b'\n' | b'\r' if !triple => break,
            _ => i += 1,
        }
    }
    let end = i.min(b.len());
    out.push(Token {
        kind: Kind::Str { closed },
        start,
        end,
    });
    end
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<(Kind, &str)> {
        tokens(src).iter().map(|t| (t.kind, t.text(src))).collect()
    }

    #[test]
    fn tokens_of_a_command_being_typed() {
        let src = "MA = LIRE_MAILLAGE(FORMAT='MED', # c\n  UNITE=2.0e+1, NOM=r'x\n";
        let k = kinds(src);
        assert_eq!(k[0], (Kind::Name, "MA"));
        assert_eq!(k[1], (Kind::Assign, "="));
        assert_eq!(k[4], (Kind::Name, "FORMAT"));
        assert_eq!(k[6], (Kind::Str { closed: true }, "'MED'"));
        assert_eq!(k[10], (Kind::Number, "2.0e+1"));
        assert_eq!(k[14], (Kind::Str { closed: false }, "r'x"));
        // No newline token inside the open bracket.
        assert!(!k.iter().any(|(k, _)| *k == Kind::Newline));
        let t = tokens(src);
        assert_eq!(str_content(src, &t[6]), "MED");
    }

    #[test]
    fn operators_are_not_assignments() {
        let k = kinds("if a == 1 and b <= 2: c += 1\n");
        assert_eq!(
            k.iter().filter(|(k, _)| *k == Kind::Assign).count(),
            0,
            "{k:?}"
        );
    }
}
