//! What one evaluation may cost: recursion, steps, sizes.
//!
//! A command file is a program: a few bytes can ask for 10^18 loop turns
//! (`[] * 10**18` used to loop), a 10 GB string (`'a' * 10**10`) or a
//! recursion deeper than the stack. Each is bounded here and refused with a
//! located message before it is attempted:
//!
//! * [`MAX_EVAL_DEPTH`]: nested evaluation — expressions inside
//!   expressions, statements inside blocks, and calls — on one counter
//!   (the syntax tree is at most `aster_syntax::limits::MAX_DEPTH` deep,
//!   but calls nest trees inside each other);
//! * [`STEP_BUDGET`]: the work of the whole program on one budget: a turn
//!   of a `for`/`while` loop or of a comprehension, a call, and every item
//!   (or 16 bytes of text) that a bulk operation builds or copies
//!   (repetition, `range`, concatenation, padding, iteration over a
//!   container). The message names the loop or operation that ran out;
//! * [`MAX_ITEMS`] and [`MAX_STR_BYTES`]: one list, tuple, dict or string,
//!   checked before it is built ("result too large");
//! * [`MAX_INT_BITS`]: one integer (Python's integers are unbounded; a
//!   command file needs far less).
//!
//! With these, the bounded reproducers of the evaluator run in well under a
//! second and a few hundred megabytes at most. The real corpora use a tiny
//! fraction of each (checked on all 6,431 files: the same results as
//! without the limits).

/// Nested evaluation levels (expressions, statements, calls) on one stack.
pub const MAX_EVAL_DEPTH: usize = 2_500;
/// User function calls inside one another (Python's default is 1,000;
/// code_aster files recurse little).
pub const MAX_CALL_DEPTH: usize = 150;
/// Steps of the whole program (about a second of evaluation).
pub const STEP_BUDGET: u64 = 3_000_000;
/// Items of one list, tuple or dict.
pub const MAX_ITEMS: usize = STEP_BUDGET as usize;
/// Bytes of one string.
pub const MAX_STR_BYTES: usize = 16 * STEP_BUDGET as usize;
/// Bytes of text that cost one step.
pub const STR_BYTES_PER_STEP: usize = 16;
/// Bits of one integer (about 19,700 decimal digits).
pub const MAX_INT_BITS: u64 = 1 << 16;
/// Digits of an integer read from text (Python's own limit).
pub const MAX_INT_DIGITS: usize = 4_300;

/// "result too large" for `n` items (`what`: "items", "characters"…).
pub fn too_large(n: u128, limit: usize, what: &str) -> String {
    format!("result too large: {n} {what} (the limit is {limit})")
}
