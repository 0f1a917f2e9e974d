//! Syntax of code_aster command files: a pest grammar (`grammar/comm.pest`)
//! read into a spanned Python AST.
//!
//! Public API: [`parse_module`] / [`parse_file`], [`read_source`], the
//! [`ast`] types, the [`codemap`] for positions, [`ParseError`] and its
//! [`ParseError::render`]ing, and the canonical printer [`fmt::format_module`].

pub mod ast;
pub mod codemap;
pub mod diagnose;
pub mod dialect;
pub mod error;
pub mod fmt;
pub mod limits;
pub mod literals;
pub mod logical;
pub mod parser;
mod tree;
pub mod validate;

pub use codemap::{CodeMap, LineCol, Span};

use std::path::Path;

/// A syntax error at one place in a file.
#[derive(Clone, Debug, PartialEq)]
pub struct ParseError {
    /// Where the error is (the offending character, or a zero-width span at the end).
    pub span: Span,
    /// What was expected / what is wrong, e.g. "expected `)`, found end of file".
    pub message: String,
}

impl ParseError {
    /// `file:line:col: message`, the source line and a caret under the position.
    pub fn render(&self, map: &CodeMap) -> String {
        error::render(map, self)
    }
}

impl std::fmt::Display for ParseError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ParseError {}

/// Parse a whole command file and run the post-parse checks of [`validate`].
pub fn parse_module(source: &str) -> Result<ast::Module, ParseError> {
    parse_module_at(source, 0)
}

/// [`parse_module`] for a file a [`CodeMap`] holds at offset `base`
/// ([`CodeMap::add_file`]): every span (of the AST and of the error) is
/// shifted by `base`.
pub fn parse_module_at(source: &str, base: usize) -> Result<ast::Module, ParseError> {
    let shift = |mut e: ParseError| {
        e.span = Span::new(e.span.start as usize + base, e.span.end as usize + base);
        e
    };
    diagnose::check_limits(source).map_err(shift)?;
    let module = match parser::parse_module_unchecked_at(source, base) {
        Ok(m) => m,
        Err(e) => {
            // `refine` reads the text: it works on unshifted positions.
            let local = Span::new(
                (e.span.start as usize).saturating_sub(base),
                (e.span.end as usize).saturating_sub(base),
            );
            return Err(shift(diagnose::refine(
                source,
                ParseError {
                    span: local,
                    message: e.message,
                },
            )));
        }
    };
    validate::check(&module)?;
    Ok(module)
}

/// Read a command file: UTF-8 (an initial BOM is dropped), else Latin-1
/// (code_aster 11 files are often Latin-1).
pub fn read_source(path: &Path) -> std::io::Result<String> {
    let bytes = std::fs::read(path)?;
    Ok(decode(&bytes))
}

/// Decode file bytes as UTF-8, falling back to Latin-1 (Windows-1252).
pub fn decode(bytes: &[u8]) -> String {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(s) => s.to_string(),
        Err(_) => {
            let (text, _, _) = encoding_rs::WINDOWS_1252.decode(bytes);
            text.into_owned()
        }
    }
}

/// Read and parse a file; the error is already rendered (`file:line:col: …`).
pub fn parse_file(path: &Path) -> Result<(CodeMap, ast::Module), String> {
    let source = read_source(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let map = CodeMap::new(path.display().to_string(), source);
    match parse_module(map.source()) {
        Ok(m) => Ok((map, m)),
        Err(e) => Err(e.render(&map)),
    }
}
