//! Syntax of code_aster command files: a pest grammar (`grammar/comm.pest`)
//! read into a spanned Python AST.
//!
//! Public API: [`parse_module`] / [`parse_file`], the [`ast`] types, the
//! [`codemap`] for positions, and [`ParseError`].

pub mod ast;
pub mod codemap;

pub use codemap::{CodeMap, LineCol, Span};

/// A syntax error at one place in a file.
#[derive(Clone, Debug, PartialEq)]
pub struct ParseError {
    /// Where the error is (a zero-width span at the offending position).
    pub span: Span,
    /// What was expected / what is wrong, e.g. "expected `)`".
    pub message: String,
}

/// Parse a whole command file.
pub fn parse_module(source: &str) -> Result<ast::Module, ParseError> {
    let _ = source;
    Err(ParseError {
        span: Span::default(),
        message: "parser not implemented yet".into(),
    })
}
