//! Runs a command file as a program. Python-level statements are evaluated;
//! every command call is validated against the catalog (defaults filled,
//! legacy keywords mapped) and handed, as a [`CommandCall`], to a
//! [`CommandSink`]: the checker's sink only types the result, the runner's
//! sink executes it.

pub mod command;

pub use command::*;
