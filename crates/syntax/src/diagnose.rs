//! Better messages for syntax errors.
//!
//! pest reports the furthest position it reached and the rules it tried
//! there. For the errors people actually make that position is often far
//! from the cause (an unclosed `(` is only noticed at the end of the file)
//! or the expected set is unhelpful. So when parsing fails, this module runs
//! a small line/bracket/string scanner (the lexical layer of Python's own
//! tokenizer) and explains the failure in its terms when it can:
//! unterminated strings, unclosed/unmatched/mismatched brackets, invalid
//! characters, indentation errors, a block header without `:`, a missing
//! comma between arguments.

use crate::codemap::Span;
use crate::ParseError;

fn err(pos: usize, len: usize, message: String) -> ParseError {
    ParseError {
        span: Span::new(pos, pos + len),
        message,
    }
}

/// One logical line (physical lines joined inside brackets and after `\`).
#[derive(Debug)]
struct LogicalLine {
    /// Byte offset of the first token.
    start: usize,
    /// Byte offset just after the last token (before comment/newline).
    end: usize,
    /// The last significant character.
    last: char,
    /// The first word, e.g. `if`.
    first_word: String,
}

struct Scan {
    error: Option<ParseError>,
    lines: Vec<LogicalLine>,
}

const BLOCK_KEYWORDS: [&str; 11] = [
    "with", "if", "elif", "else", "for", "while", "def", "class", "try", "except", "finally",
];

fn closing(open: char) -> char {
    match open {
        '(' => ')',
        '[' => ']',
        _ => '}',
    }
}

/// Indentation width with tabs to the next multiple of 8 (Python 2 rule).
fn width(indent: &str) -> usize {
    indent
        .chars()
        .fold(0, |w, c| if c == '\t' { (w / 8 + 1) * 8 } else { w + 1 })
}

fn line_col(source: &str, pos: usize) -> (usize, usize) {
    // Error path only: the code map's rule for line ends (lone `\r` too).
    let lc = crate::codemap::CodeMap::new("", source).line_col(pos);
    (lc.line, lc.column)
}

fn scan(source: &str) -> Scan {
    let bytes = source.as_bytes();
    let mut lines: Vec<LogicalLine> = Vec::new();
    let mut brackets: Vec<(char, usize)> = Vec::new();
    // Each level's width with tabs to 8 columns and to 1 column: Python 3
    // refuses indentation whose order depends on the tab size (TabError).
    let mut indents: Vec<(usize, usize)> = vec![(0, 0)];
    let mut expect_indent: Option<usize> = None; // header line start, when the last line ended with `:`
    let mut i = 0;
    let mut at_line_start = true;
    let mut current: Option<LogicalLine> = None;
    let fail = |e: ParseError, lines: Vec<LogicalLine>| Scan {
        error: Some(e),
        lines,
    };
    while i < bytes.len() {
        if at_line_start && brackets.is_empty() {
            // Measure the indentation of a new logical line.
            let start = i;
            while i < bytes.len() && matches!(bytes[i], b' ' | b'\t' | b'\x0C') {
                i += 1;
            }
            match bytes.get(i) {
                None => break,
                Some(b'\n' | b'\r' | b'#') => {
                    // Blank or comment-only line: no indentation meaning.
                    while i < bytes.len() && bytes[i] != b'\n' {
                        i += 1;
                    }
                    i += 1;
                    continue;
                }
                _ => {}
            }
            let w = width(&source[start..i]);
            let alt = i - start;
            let (top, top_alt) = indents.last().copied().unwrap_or((0, 0));
            let tab_error = || {
                err(
                    start,
                    i - start,
                    "inconsistent use of tabs and spaces in indentation (TabError): indent with spaces only"
                        .into(),
                )
            };
            if (w == top) != (alt == top_alt) || (w > top) != (alt > top_alt) {
                return fail(tab_error(), lines);
            }
            if let Some(header) = expect_indent.take() {
                if w <= top {
                    let (l, _) = line_col(source, header);
                    return fail(
                        err(
                            i,
                            1,
                            format!("expected an indented block after the `:` of line {l}"),
                        ),
                        lines,
                    );
                }
                indents.push((w, alt));
            } else if w > top {
                return fail(
                    err(
                        i,
                        1,
                        "unexpected indent: this line is indented more than the block it is in"
                            .into(),
                    ),
                    lines,
                );
            } else if w < top {
                while indents.last().is_some_and(|&(t, _)| t > w) {
                    indents.pop();
                }
                if let Some(&(t, t_alt)) = indents.last() {
                    if t == w && t_alt != alt {
                        return fail(tab_error(), lines);
                    }
                }
                if indents.last().map(|l| l.0) != Some(w) {
                    return fail(
                        err(
                            i,
                            1,
                            "unindent does not match any outer indentation level".into(),
                        ),
                        lines,
                    );
                }
            }
            at_line_start = false;
        }
        let c = bytes[i];
        // Start of a token on this logical line.
        if !matches!(c, b' ' | b'\t' | b'\x0C' | b'\n' | b'\r' | b'#' | b'\\') && current.is_none()
        {
            let word: String = source[i..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            current = Some(LogicalLine {
                start: i,
                end: i,
                last: ' ',
                first_word: word,
            });
        }
        match c {
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'\\' => {
                match bytes.get(i + 1) {
                    Some(b'\n') => i += 2,
                    Some(b'\r') if bytes.get(i + 2) == Some(&b'\n') => i += 3,
                    None => i += 1,
                    _ => {
                        return fail(
                            err(
                                i,
                                1,
                                "unexpected character after line continuation character `\\`"
                                    .into(),
                            ),
                            lines,
                        )
                    }
                }
                continue;
            }
            b'\n' => {
                i += 1;
                if brackets.is_empty() {
                    if let Some(line) = current.take() {
                        if line.last == ':' && BLOCK_KEYWORDS.contains(&line.first_word.as_str()) {
                            expect_indent = Some(line.start);
                        }
                        lines.push(line);
                    }
                    at_line_start = true;
                }
                continue;
            }
            b' ' | b'\t' | b'\x0C' | b'\r' => {
                i += 1;
                continue;
            }
            _ => {}
        }
        let token_start = i;
        if c == b'\'' || c == b'"' {
            match string_end(bytes, i) {
                Ok(end) => i = end,
                Err(triple) => {
                    let msg = if triple {
                        "unterminated triple-quoted string literal: no closing quotes before the end of the file"
                    } else {
                        "unterminated string literal: the closing quote is missing on this line"
                    };
                    return fail(err(string_start(bytes, i), 1, msg.into()), lines);
                }
            }
        } else if let Some(ch) = source[i..].chars().next() {
            match ch {
                '(' | '[' | '{' => brackets.push((ch, i)),
                ')' | ']' | '}' => match brackets.pop() {
                    None => {
                        return fail(
                            err(
                                i,
                                1,
                                format!("unmatched `{ch}`: there is no opening bracket for it"),
                            ),
                            lines,
                        )
                    }
                    Some((open, at)) if closing(open) != ch => {
                        let (l, col) = line_col(source, at);
                        return fail(
                            err(
                                i,
                                1,
                                format!(
                                    "closing `{ch}` does not match the opening `{open}` of line {l}, column {col} (expected `{}`)",
                                    closing(open)
                                ),
                            ),
                            lines,
                        );
                    }
                    Some(_) => {}
                },
                c if c.is_alphanumeric() || c == '_' => {}
                c if "+-*/%<>=!&|^~@.,:;`".contains(c) => {}
                c => {
                    return fail(
                        err(
                            i,
                            c.len_utf8(),
                            format!(
                                "invalid character `{c}` (U+{:04X}) outside a string or comment",
                                c as u32
                            ),
                        ),
                        lines,
                    )
                }
            }
            i += ch.len_utf8();
        } else {
            i += 1;
        }
        if let Some(line) = current.as_mut() {
            line.end = i;
            line.last = source[token_start..i].chars().last().unwrap_or(' ');
        }
    }
    if let Some(line) = current.take() {
        lines.push(line);
    }
    if let Some(&(open, at)) = brackets.last() {
        return Scan {
            error: Some(err(
                at,
                1,
                format!(
                    "`{open}` was never closed: expected `{}` before the end of the file",
                    closing(open)
                ),
            )),
            lines,
        };
    }
    Scan { error: None, lines }
}

/// The index of a quote that starts a string, backed up over its prefix.
fn string_start(bytes: &[u8], quote: usize) -> usize {
    let mut s = quote;
    while s > 0
        && quote - s < 2
        && matches!(
            bytes[s - 1],
            b'r' | b'R' | b'b' | b'B' | b'u' | b'U' | b'f' | b'F'
        )
    {
        s -= 1;
    }
    s
}

/// End of the string whose quote is at `i`; `Err(is_triple)` if unterminated.
pub(crate) fn string_end(bytes: &[u8], i: usize) -> Result<usize, bool> {
    let q = bytes[i];
    let triple = bytes.get(i + 1) == Some(&q) && bytes.get(i + 2) == Some(&q);
    let mut j = if triple { i + 3 } else { i + 1 };
    while j < bytes.len() {
        let c = bytes[j];
        if c == b'\\' {
            j += 2;
            continue;
        }
        if triple {
            if c == q && bytes.get(j + 1) == Some(&q) && bytes.get(j + 2) == Some(&q) {
                return Ok(j + 3);
            }
        } else if c == q {
            return Ok(j + 1);
        } else if c == b'\n' {
            return Err(false);
        }
        j += 1;
    }
    Err(triple)
}

/// Replace a raw parse error by a clearer one when the scanner can explain it.
pub fn refine(source: &str, e: ParseError) -> ParseError {
    let scan = scan(source);
    if let Some(lexical) = scan.error {
        // A lexical problem before the failure point (or an unclosed bracket,
        // which is only noticed later) is the cause.
        if lexical.span.start <= e.span.start
            || lexical.message.contains("never closed")
            || lexical.message.starts_with("expected an indented block")
        {
            return lexical;
        }
    }
    let pos = e.span.start as usize;
    // The logical line of the error.
    let Some(line) = scan.lines.iter().rev().find(|l| l.start <= pos) else {
        return e;
    };
    // A block header that does not end with `:`.
    if BLOCK_KEYWORDS.contains(&line.first_word.as_str()) && line.last != ':' && pos >= line.end {
        return err(
            line.end,
            0,
            format!("expected `:` at the end of the `{}` line", line.first_word),
        );
    }
    // Two operands side by side inside brackets: a missing comma.
    let before = source[..pos.min(source.len())].trim_end();
    let prev = before.chars().last();
    let next = source.get(pos..).and_then(|s| s.chars().next());
    if inside_brackets(source, pos)
        && prev.is_some_and(|c| c.is_alphanumeric() || "_)]}'\".".contains(c))
        && next.is_some_and(|c| c.is_alphanumeric() || "_([{'\"".contains(c))
    {
        let found = crate::error::found_at(source, pos);
        return err(
            pos,
            (e.span.end - e.span.start) as usize,
            format!(
                "expected `,` or a closing bracket, found {found}: is a comma missing before it?"
            ),
        );
    }
    e
}

/// Is `pos` inside an open bracket (strings and comments skipped)?
fn inside_brackets(source: &str, pos: usize) -> bool {
    let bytes = source.as_bytes();
    let mut depth = 0i32;
    let mut i = 0;
    while i < pos.min(bytes.len()) {
        match bytes[i] {
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            b'\'' | b'"' => {
                i = string_end(bytes, i).unwrap_or(bytes.len());
                continue;
            }
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth -= 1,
            _ => {}
        }
        i += 1;
    }
    depth > 0
}

pub use crate::limits::{
    MAX_BRACKET_DEPTH, MAX_INDENT_LEVELS, MAX_KEYWORD_NESTING, MAX_PREFIX_RUN,
};

/// Byte classes of [`check_limits`]: 0 resets the unary-operator run, 1
/// (blanks) keeps it, [`LIMIT_SPECIAL`] needs the full step (comments,
/// strings, brackets, line breaks, unary operators, the separators `,` `:`
/// `;`, backquotes, a backslash, and the first letters of `lambda`, `not`,
/// `if`, `else`, `for`, `in`).
const LIMIT_SPECIAL: u8 = 2;
const LIMIT_CLASS: [u8; 256] = {
    let mut t = [0u8; 256];
    t[b' ' as usize] = 1;
    t[b'\t' as usize] = 1;
    t[0x0C] = 1;
    let special = b"#'\"([{)]}\n\r-+~,:;`\\efiln";
    let mut k = 0;
    while k < special.len() {
        t[special[k] as usize] = LIMIT_SPECIAL;
        k += 1;
    }
    t
};

fn is_ident_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_' || b >= 0x80
}

/// What a word does to the nesting estimate of [`check_limits`].
#[derive(Clone, Copy, PartialEq)]
enum Word {
    /// `lambda`: one level, and its parameters run to its `:`.
    Lambda,
    /// `for`: one level (a comprehension clause), and its targets run to `in`.
    For,
    /// `in`: ends the targets of a `for`.
    In,
    /// `not`, `if`, `elif`, `else`: one level.
    Nest,
    Other,
}

fn word(w: &[u8]) -> Word {
    match w {
        b"lambda" => Word::Lambda,
        b"for" => Word::For,
        b"in" => Word::In,
        b"not" | b"if" | b"elif" | b"else" => Word::Nest,
        _ => Word::Other,
    }
}

/// The nesting estimate of one bracket level (see [`check_limits`]).
#[derive(Clone, Copy, Default)]
struct Level {
    /// Keywords seen in the current element of this level.
    pending: usize,
    /// `lambda`s whose `:` is still to come (their commas separate parameters).
    lambda_params: usize,
    /// `for`s whose `in` is still to come (their commas separate targets).
    for_targets: usize,
}

/// The limits' state while scanning: bracket levels and their keyword
/// counts (shared by [`check_limits`] and its reference version in the tests).
struct Nesting {
    levels: Vec<Level>,
    /// The sum of `pending` over all levels, plus the backquotes of the line.
    total: usize,
}

impl Nesting {
    fn new() -> Nesting {
        Nesting {
            levels: vec![Level::default()],
            total: 0,
        }
    }
    fn top(&mut self) -> &mut Level {
        if self.levels.is_empty() {
            self.levels.push(Level::default());
        }
        let last = self.levels.len() - 1;
        &mut self.levels[last]
    }
    fn open(&mut self) {
        self.levels.push(Level::default());
    }
    fn close(&mut self) {
        if self.levels.len() > 1 {
            if let Some(l) = self.levels.pop() {
                self.total -= l.pending;
            }
        }
    }
    /// The end of an element of the current level (`,`, `:`, `;`): the
    /// expression that was nesting there is complete.
    fn end_element(&mut self) {
        let l = self.top();
        let done = l.pending;
        l.pending = 0;
        self.total -= done;
    }
    fn end_line(&mut self) {
        self.levels.truncate(1);
        self.levels[0] = Level::default();
        self.total = 0;
    }
    /// A word at `pos`; an error when the nesting goes over the limit.
    fn word(&mut self, w: Word, pos: usize, len: usize) -> Result<(), ParseError> {
        let l = self.top();
        match w {
            Word::Lambda => l.lambda_params += 1,
            Word::For => l.for_targets += 1,
            Word::In => {
                l.for_targets = l.for_targets.saturating_sub(1);
                return Ok(());
            }
            Word::Nest => {}
            Word::Other => return Ok(()),
        }
        l.pending += 1;
        self.total += 1;
        self.over(pos, len)
    }
    fn comma(&mut self) {
        let l = self.top();
        if l.lambda_params == 0 && l.for_targets == 0 {
            self.end_element();
        }
    }
    fn colon(&mut self) {
        let l = self.top();
        if l.lambda_params > 0 {
            l.lambda_params -= 1;
        } else {
            l.for_targets = 0;
            self.end_element();
        }
    }
    fn backquote(&mut self, pos: usize) -> Result<(), ParseError> {
        // Backquotes (Python 2 `repr`) can nest without brackets: each one
        // counts until the end of the logical line.
        self.total += 1;
        self.over(pos, 1)
    }
    fn over(&self, pos: usize, len: usize) -> Result<(), ParseError> {
        if self.total > MAX_KEYWORD_NESTING {
            return Err(err(
                pos,
                len,
                format!(
                    "expression too deeply nested: more than {MAX_KEYWORD_NESTING} `lambda`, `not`, `if`/`else`, `for` or backquotes inside one another"
                ),
            ));
        }
        Ok(())
    }
}

/// Nesting limits, checked in one pass over the bytes before parsing, so
/// that pathological input gets a located error instead of exhausting the
/// parser's native stack (see [`crate::limits`]): brackets, indentation
/// levels, runs of unary operators, and an estimate of the keyword nesting
/// (`lambda`, `not`, conditionals, comprehension clauses, backquotes) that
/// never under-counts what the grammar nests.
pub fn check_limits(source: &str) -> Result<(), ParseError> {
    let bytes = source.as_bytes();
    let mut depth = 0usize;
    let mut prefix_run = 0usize;
    let mut i = 0;
    let mut line_start = true;
    let mut indent_widths: Vec<usize> = Vec::new();
    let mut nesting = Nesting::new();
    while i < bytes.len() {
        if !(line_start && depth == 0) {
            // Most bytes only reset (or, for blanks, keep) the run of unary
            // operators: skip them in a tight loop, it runs every parse.
            if prefix_run == 0 {
                // No run to track (nearly always): only find the next
                // special byte.
                i += bytes[i..]
                    .iter()
                    .position(|&b| LIMIT_CLASS[b as usize] == LIMIT_SPECIAL)
                    .unwrap_or(bytes.len() - i);
            } else {
                while let Some(&b) = bytes.get(i) {
                    let class = LIMIT_CLASS[b as usize];
                    if class == LIMIT_SPECIAL {
                        break;
                    }
                    prefix_run *= class as usize;
                    i += 1;
                }
            }
            if i >= bytes.len() {
                break;
            }
        }
        let c = bytes[i];
        if line_start && depth == 0 {
            let s = i;
            while i < bytes.len() && matches!(bytes[i], b' ' | b'\t') {
                i += 1;
            }
            if i < bytes.len() && !matches!(bytes[i], b'\n' | b'\r' | b'#') {
                let w = width(&source[s..i]);
                while indent_widths.last().is_some_and(|&t| t >= w) {
                    indent_widths.pop();
                }
                if w > 0 {
                    indent_widths.push(w);
                }
                if indent_widths.len() > MAX_INDENT_LEVELS {
                    return Err(err(
                        i,
                        1,
                        format!("too many levels of indentation (more than {MAX_INDENT_LEVELS})"),
                    ));
                }
            }
            line_start = false;
            continue;
        }
        if c.is_ascii_lowercase() {
            // A word (the class table stops only at the first letters of
            // the keywords that nest): read it whole.
            let start = i;
            while i < bytes.len() && is_ident_byte(bytes[i]) {
                i += 1;
            }
            let at_word_start = start == 0 || !is_ident_byte(bytes[start - 1]);
            if at_word_start {
                nesting.word(word(&bytes[start..i]), start, i - start)?;
            }
            prefix_run = 0;
            continue;
        }
        match c {
            b'#' => {
                // A comment is whitespace: it keeps the run of unary operators.
                while i < bytes.len() && !matches!(bytes[i], b'\n' | b'\r') {
                    i += 1;
                }
                continue;
            }
            b'\'' | b'"' => {
                i = string_end(bytes, i).unwrap_or(bytes.len());
                prefix_run = 0;
                continue;
            }
            b'\\' if matches!(bytes.get(i + 1), Some(b'\n' | b'\r')) => {
                // A continuation line: whitespace too.
                i += if bytes[i + 1] == b'\r' && bytes.get(i + 2) == Some(&b'\n') {
                    3
                } else {
                    2
                };
                continue;
            }
            b'(' | b'[' | b'{' => {
                depth += 1;
                if depth > MAX_BRACKET_DEPTH {
                    return Err(err(
                        i,
                        1,
                        format!("too many nested brackets (more than {MAX_BRACKET_DEPTH})"),
                    ));
                }
                nesting.open();
            }
            b')' | b']' | b'}' => {
                depth = depth.saturating_sub(1);
                nesting.close();
            }
            b'\n' | b'\r' => {
                if depth == 0 {
                    line_start = c == b'\n';
                    nesting.end_line();
                    prefix_run = 0;
                }
                // Inside brackets a line break is whitespace.
                i += 1;
                continue;
            }
            b',' => nesting.comma(),
            b':' if bytes.get(i + 1) != Some(&b'=') => nesting.colon(),
            b';' => nesting.end_element(),
            b'`' => nesting.backquote(i)?,
            _ => {}
        }
        match c {
            b'-' | b'+' | b'~' => {
                prefix_run += 1;
                if prefix_run > MAX_PREFIX_RUN {
                    return Err(err(
                        i,
                        1,
                        format!(
                            "too many consecutive unary operators (more than {MAX_PREFIX_RUN})"
                        ),
                    ));
                }
            }
            _ => prefix_run = 0,
        }
        i += 1;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tab_width_follows_python2() {
        assert_eq!(width("\t"), 8);
        assert_eq!(width("  \t"), 8);
        assert_eq!(width("        "), 8);
        assert_eq!(width("\t "), 9);
    }

    /// The straightforward byte-by-byte version `check_limits` was before
    /// its fast path: both must agree on every input.
    fn check_limits_reference(source: &str) -> Result<(), ParseError> {
        let bytes = source.as_bytes();
        let mut depth = 0usize;
        let mut prefix_run = 0usize;
        let mut i = 0;
        let mut line_start = true;
        let mut indent_widths: Vec<usize> = Vec::new();
        let mut nesting = Nesting::new();
        while i < bytes.len() {
            let c = bytes[i];
            if line_start && depth == 0 {
                let s = i;
                while i < bytes.len() && matches!(bytes[i], b' ' | b'\t') {
                    i += 1;
                }
                if i < bytes.len() && !matches!(bytes[i], b'\n' | b'\r' | b'#') {
                    let w = width(&source[s..i]);
                    while indent_widths.last().is_some_and(|&t| t >= w) {
                        indent_widths.pop();
                    }
                    if w > 0 {
                        indent_widths.push(w);
                    }
                    if indent_widths.len() > MAX_INDENT_LEVELS {
                        return Err(err(i, 1, "indent".into()));
                    }
                }
                line_start = false;
                continue;
            }
            if is_ident_byte(c) {
                let start = i;
                while i < bytes.len() && is_ident_byte(bytes[i]) {
                    i += 1;
                }
                let w = &bytes[start..i];
                if w[0].is_ascii_lowercase() {
                    nesting.word(word(w), start, i - start)?;
                }
                prefix_run = 0;
                continue;
            }
            match c {
                b'#' => {
                    while i < bytes.len() && !matches!(bytes[i], b'\n' | b'\r') {
                        i += 1;
                    }
                    continue;
                }
                b'\'' | b'"' => {
                    i = string_end(bytes, i).unwrap_or(bytes.len());
                    prefix_run = 0;
                    continue;
                }
                b'\\' if matches!(bytes.get(i + 1), Some(b'\n' | b'\r')) => {
                    i += if bytes[i + 1] == b'\r' && bytes.get(i + 2) == Some(&b'\n') {
                        3
                    } else {
                        2
                    };
                    continue;
                }
                b'(' | b'[' | b'{' => {
                    depth += 1;
                    if depth > MAX_BRACKET_DEPTH {
                        return Err(err(i, 1, "brackets".into()));
                    }
                    nesting.open();
                }
                b')' | b']' | b'}' => {
                    depth = depth.saturating_sub(1);
                    nesting.close();
                }
                b'\n' | b'\r' => {
                    if depth == 0 {
                        line_start = c == b'\n';
                        nesting.end_line();
                        prefix_run = 0;
                    }
                    i += 1;
                    continue;
                }
                b',' => nesting.comma(),
                b':' if bytes.get(i + 1) != Some(&b'=') => nesting.colon(),
                b';' => nesting.end_element(),
                b'`' => nesting.backquote(i)?,
                _ => {}
            }
            match c {
                b'-' | b'+' | b'~' => {
                    prefix_run += 1;
                    if prefix_run > MAX_PREFIX_RUN {
                        return Err(err(i, 1, "unary".into()));
                    }
                }
                b' ' | b'\t' | 0x0C => {}
                _ => prefix_run = 0,
            }
            i += 1;
        }
        Ok(())
    }

    fn same_verdict(source: &str) {
        let fast = check_limits(source).map_err(|e| e.span);
        let reference = check_limits_reference(source).map_err(|e| e.span);
        assert_eq!(fast, reference, "{source:?}");
    }

    #[test]
    fn fast_limit_check_agrees_with_reference_at_the_limits() {
        let deep = |n: usize| format!("x = {}1{}\n", "(".repeat(n), ")".repeat(n));
        let unary = |n: usize| format!("x = {}1\ny = 2\n", "- ".repeat(n));
        let indent = |n: usize| {
            (0..n)
                .map(|k| format!("{}if a:\n", " ".repeat(k)))
                .collect::<String>()
                + &" ".repeat(n)
                + "pass\n"
        };
        for n in [
            MAX_BRACKET_DEPTH - 1,
            MAX_BRACKET_DEPTH,
            MAX_BRACKET_DEPTH + 1,
        ] {
            same_verdict(&deep(n));
        }
        for n in [MAX_PREFIX_RUN, MAX_PREFIX_RUN + 1] {
            same_verdict(&unary(n));
            same_verdict(&format!("s = '{}'\n", "-".repeat(n + 5)));
            same_verdict(&format!("# {}\nx = 1\n", "-".repeat(n + 5)));
        }
        for n in [MAX_INDENT_LEVELS, MAX_INDENT_LEVELS + 1] {
            same_verdict(&indent(n));
        }
        assert!(check_limits(&deep(MAX_BRACKET_DEPTH + 1)).is_err());
        assert!(check_limits(&unary(MAX_PREFIX_RUN + 1)).is_err());
        assert!(check_limits(&indent(MAX_INDENT_LEVELS + 1)).is_err());
    }

    proptest::proptest! {
        #[test]
        fn fast_limit_check_agrees_with_reference(
            source in "([ \t\n#'\"(\\[{)\\]}+~a=-]|\\(\\(\\(\\(|- - - -){0,400}"
        ) {
            same_verdict(&source);
        }
    }

    #[test]
    fn valid_code_has_no_lexical_error() {
        let s = scan("if x:\n    y = (1,\n  2)  # c\n\n    z = '''a\nb'''\nelse:\n\tpass\n");
        assert!(s.error.is_none(), "{:?}", s.error);
    }
}
