//! The limits that keep every pass over a command file bounded.
//!
//! A command file is a program: a file of a few kilobytes can nest
//! expressions tens of thousands of levels deep (`1 + 1 + …`, `a.b.b…`,
//! `not not …`, `elif` chains). Every pass over the syntax tree (the
//! parser, the builder, the post-parse checks, the formatter, the JSON
//! serialiser, the evaluator, dropping the tree) recurses on that nesting,
//! so each is bounded here, in one place, with a located message instead
//! of a stack overflow:
//!
//! * **Before parsing** ([`crate::diagnose::check_limits`], one pass over
//!   the bytes): what makes the pest parser recurse — brackets
//!   ([`MAX_BRACKET_DEPTH`]), runs of unary operators ([`MAX_PREFIX_RUN`]),
//!   indentation levels ([`MAX_INDENT_LEVELS`]) and an estimate of the
//!   keyword nesting of one expression ([`MAX_KEYWORD_NESTING`]: `lambda`,
//!   `not`, conditionals, comprehension clauses, backquotes). The estimate
//!   never under-counts: a keyword counts until the element it is in ends
//!   (a `,`, `:` or `;` of its bracket level, the closing bracket, the end
//!   of the logical line).
//! * **After building** ([`crate::validate::check`], the walk that already
//!   checks Python's compile-time rules): the depth of the tree itself
//!   ([`MAX_DEPTH`]), which folding can make much deeper than the parse
//!   (`1 + 1 + …` is one flat sequence for the parser and a left-deep tree
//!   of `BinOp`s). The operator folding of the builder stops at the same
//!   depth. Every later pass (formatter, serialiser, evaluator) then works
//!   on a tree at most [`MAX_DEPTH`] deep.
//! * **Dropping** a tree never recurses deeper than a fixed bound, whatever
//!   its depth (the `Drop` of `ast::Expr` and `ast::Stmt` defers deeper
//!   nodes to a loop), so a rejected tree, or one abandoned by an error
//!   half-way through building, is freed safely.
//!
//! The real corpora (3,913 code_aster 17 and 2,518 code_aster 11 files)
//! nest at most 44 JSON objects deep (statements, expressions, arguments),
//! far below these limits.

/// Nested brackets (Python's own parser allows 200).
pub const MAX_BRACKET_DEPTH: usize = 200;
/// Indentation levels (Python allows 100).
pub const MAX_INDENT_LEVELS: usize = 100;
/// Consecutive unary operators `-`, `+`, `~`.
pub const MAX_PREFIX_RUN: usize = 100;
/// `lambda`, `not`, `if`/`else`, `for` and backquotes in one element of
/// one bracket level, summed over the open brackets.
pub const MAX_KEYWORD_NESTING: usize = 200;
/// Depth of the syntax tree: statements and expressions inside one
/// another (CPython's compiler stops at about 2,000–3,000 on the same
/// kind of input).
pub const MAX_DEPTH: usize = 1000;

/// The message of a tree deeper than [`MAX_DEPTH`].
pub fn too_deep_message() -> String {
    format!(
        "expression or block nested too deeply (more than {MAX_DEPTH} levels): split it into several statements"
    )
}
