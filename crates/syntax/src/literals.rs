//! Decoding of literal tokens: numbers (all Python 3 forms plus Python 2
//! `0777` and `10L`) and string literals (prefixes, quotes, escapes).
//! The grammar only delimits tokens; values are computed here.

use crate::ast::ExprKind;

/// The common literals (`12`, `2.1e11`, `.5`, `1.E-3`) without allocating:
/// decimal digits only, no `_`, no suffix, no leading `0` on an integer
/// (Python 2 octal). Anything else goes the general way.
fn plain_number(text: &str) -> Option<ExprKind> {
    let bytes = text.as_bytes();
    if bytes.iter().all(u8::is_ascii_digit) {
        if bytes.len() > 1 && bytes[0] == b'0' {
            return None;
        }
        return text.parse().ok().map(|value| ExprKind::Int { value });
    }
    let float_chars = bytes
        .iter()
        .all(|c| c.is_ascii_digit() || matches!(c, b'.' | b'e' | b'E' | b'+' | b'-'));
    if float_chars {
        return text.parse().ok().map(|value| ExprKind::Float { value });
    }
    None
}

/// The value of a number token (the grammar guarantees its shape).
pub fn number(text: &str) -> Result<ExprKind, String> {
    if let Some(kind) = plain_number(text) {
        return Ok(kind);
    }
    let clean: String = text.chars().filter(|&c| c != '_').collect();
    let (body, suffix) = match clean.chars().last() {
        Some(c @ ('j' | 'J' | 'l' | 'L')) => (&clean[..clean.len() - 1], Some(c)),
        _ => (clean.as_str(), None),
    };
    if matches!(suffix, Some('j' | 'J')) {
        let value: f64 = body
            .parse()
            .map_err(|_| format!("invalid imaginary literal `{text}`"))?;
        return Ok(ExprKind::Imag { value });
    }
    let lower = body.to_ascii_lowercase();
    let radix_int = |digits: &str, radix: u32| -> Result<ExprKind, String> {
        match i64::from_str_radix(digits, radix) {
            Ok(value) => Ok(ExprKind::Int { value }),
            Err(_) if radix == 10 => digits
                .parse()
                .map(|value| ExprKind::Float { value })
                .map_err(|_| format!("invalid integer `{text}`")),
            Err(_) => {
                // Too large for an i64: keep the magnitude as a float.
                let mut value = 0f64;
                for c in digits.chars() {
                    let d = c
                        .to_digit(radix)
                        .ok_or_else(|| format!("invalid digit `{c}` in `{text}`"))?;
                    value = value * radix as f64 + d as f64;
                }
                Ok(ExprKind::Float { value })
            }
        }
    };
    if let Some(hex) = lower.strip_prefix("0x") {
        return radix_int(hex, 16);
    }
    if let Some(oct) = lower.strip_prefix("0o") {
        return radix_int(oct, 8);
    }
    if let Some(bin) = lower.strip_prefix("0b") {
        return radix_int(bin, 2);
    }
    let is_float = lower.contains(['.', 'e']);
    if is_float {
        if matches!(suffix, Some('l' | 'L')) {
            return Err(format!("invalid long literal `{text}`"));
        }
        let value: f64 = body
            .parse()
            .map_err(|_| format!("invalid float literal `{text}`"))?;
        return Ok(ExprKind::Float { value });
    }
    // Python 2 octal: a decimal-looking literal with a leading zero.
    if body.len() > 1 && body.starts_with('0') && body.bytes().any(|b| b != b'0') {
        if body.bytes().all(|b| (b'0'..=b'7').contains(&b)) {
            return radix_int(&body[1..], 8);
        }
        return Err(format!(
            "invalid number `{text}`: leading zeros are not allowed in decimal integers"
        ));
    }
    radix_int(body, 10)
}

/// What a string token's prefix says about it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StrFlags {
    pub raw: bool,
    pub bytes: bool,
    pub fstring: bool,
}

/// Split a string token into its flags, the offset of its contents in the
/// token, and its contents (between the quotes).
pub fn split_string(token: &str) -> (StrFlags, usize, &str) {
    let prefix_len = token.find(['\'', '"']).unwrap_or(0);
    let prefix = token[..prefix_len].to_ascii_lowercase();
    let flags = StrFlags {
        raw: prefix.contains('r'),
        bytes: prefix.contains('b'),
        fstring: prefix.contains('f'),
    };
    let rest = &token[prefix_len..];
    let quote_len = if rest.starts_with("\"\"\"") || rest.starts_with("'''") {
        3
    } else {
        1
    };
    let start = prefix_len + quote_len;
    let end = token.len().saturating_sub(quote_len).max(start);
    (flags, start, &token[start..end])
}

/// Process the escapes of a (non-raw) string body. `\` followed by a newline
/// is a line continuation; unknown escapes keep their backslash (as Python does).
pub fn unescape(body: &str, bytes: bool) -> Result<Vec<u32>, String> {
    let mut out: Vec<u32> = Vec::with_capacity(body.len());
    let mut chars = body.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c as u32);
            continue;
        }
        let Some(e) = chars.next() else {
            out.push('\\' as u32);
            break;
        };
        match e {
            '\n' => {}
            '\r' => {
                if chars.peek() == Some(&'\n') {
                    chars.next();
                }
            }
            '\\' => out.push('\\' as u32),
            '\'' => out.push('\'' as u32),
            '"' => out.push('"' as u32),
            'a' => out.push(7),
            'b' => out.push(8),
            'f' => out.push(12),
            'n' => out.push(10),
            'r' => out.push(13),
            't' => out.push(9),
            'v' => out.push(11),
            '0'..='7' => {
                let mut value = e.to_digit(8).unwrap_or(0);
                for _ in 0..2 {
                    match chars.peek().and_then(|c| c.to_digit(8)) {
                        Some(d) => {
                            value = value * 8 + d;
                            chars.next();
                        }
                        None => break,
                    }
                }
                out.push(value);
            }
            'x' => out.push(hex_escape(&mut chars, 2, "\\x")?),
            'u' if !bytes => out.push(hex_escape(&mut chars, 4, "\\u")?),
            'U' if !bytes => out.push(hex_escape(&mut chars, 8, "\\U")?),
            'N' if !bytes && chars.peek() == Some(&'{') => {
                // Named characters: keep the escape verbatim (no name table).
                out.push('\\' as u32);
                out.push('N' as u32);
            }
            other => {
                out.push('\\' as u32);
                out.push(other as u32);
            }
        }
    }
    Ok(out)
}

fn hex_escape(
    chars: &mut std::iter::Peekable<std::str::Chars<'_>>,
    n: usize,
    what: &str,
) -> Result<u32, String> {
    let mut value = 0u32;
    for _ in 0..n {
        match chars.peek().and_then(|c| c.to_digit(16)) {
            Some(d) => {
                value = value.wrapping_mul(16).wrapping_add(d);
                chars.next();
            }
            None => {
                return Err(format!(
                    "truncated `{what}` escape: expected {n} hex digits"
                ))
            }
        }
    }
    Ok(value)
}

/// Code points to a Rust string; invalid code points (lone surrogates) become U+FFFD.
pub fn to_string(codes: &[u32]) -> String {
    codes
        .iter()
        .map(|&c| char::from_u32(c).unwrap_or('\u{FFFD}'))
        .collect()
}

/// Code points to bytes (a bytes literal only holds values below 256).
pub fn to_bytes(codes: &[u32]) -> Result<Vec<u8>, String> {
    codes
        .iter()
        .map(|&c| u8::try_from(c).map_err(|_| "bytes can only contain ASCII characters".into()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn num(s: &str) -> ExprKind {
        number(s).unwrap_or(ExprKind::None)
    }

    #[test]
    fn numbers_of_every_form() {
        assert_eq!(num("42"), ExprKind::Int { value: 42 });
        assert_eq!(num("1_000"), ExprKind::Int { value: 1000 });
        assert_eq!(num("0x1F"), ExprKind::Int { value: 31 });
        assert_eq!(num("0o17"), ExprKind::Int { value: 15 });
        assert_eq!(num("0777"), ExprKind::Int { value: 511 });
        assert_eq!(num("0b101"), ExprKind::Int { value: 5 });
        assert_eq!(num("10L"), ExprKind::Int { value: 10 });
        assert_eq!(num("000"), ExprKind::Int { value: 0 });
        assert_eq!(num("1."), ExprKind::Float { value: 1.0 });
        assert_eq!(num(".5"), ExprKind::Float { value: 0.5 });
        assert_eq!(num("1.E-3"), ExprKind::Float { value: 1e-3 });
        assert_eq!(num("1e+16"), ExprKind::Float { value: 1e16 });
        assert_eq!(num("2j"), ExprKind::Imag { value: 2.0 });
        assert_eq!(num("99999999999999999999"), ExprKind::Float { value: 1e20 });
        assert!(number("09").is_err());
    }

    #[test]
    fn string_prefixes_and_escapes() {
        let (flags, start, body) = split_string("rb'''a\\'b'''");
        assert!(flags.raw && flags.bytes && !flags.fstring);
        assert_eq!((start, body), (5, "a\\'b"));
        let v = unescape("a\\n\\x41\\101\\u00e9\\q\\\nz", false).unwrap_or_default();
        assert_eq!(to_string(&v), "a\nAAé\\qz");
        assert!(unescape("\\x4", false).is_err());
    }
}
