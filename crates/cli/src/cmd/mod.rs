//! One module per subcommand; each `run` returns the process exit code.

pub mod check;
pub mod diag_out;
pub mod explain;
pub mod fmt;
pub mod json_out;
pub mod lsp;
pub mod mesh;
pub mod migrate;
pub mod parse;
pub mod plot;
pub mod run;
pub mod study;
