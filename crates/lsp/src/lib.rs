//! `aster lsp`: code_aster command files behind the Language Server
//! Protocol. The same parser, evaluator and catalog validation as `aster
//! check` give the diagnostics (with the did-you-mean and legacy rewrites as
//! quick fixes); the catalog and `aster explain` give hover, completion and
//! signature help; a tolerant token stream gives navigation and the context
//! of a position while the file is being typed and does not parse.
//!
//! Entry points: [`run_stdio`] (what `aster lsp` calls) and [`serve`] on any
//! [`lsp_server::Connection`] (tests use an in-memory one).

pub mod analysis;
pub mod context;
pub mod features;
pub mod lex;
pub mod server;
pub mod text;

pub use server::{run_stdio, serve};
