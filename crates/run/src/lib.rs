//! The semantic layer: turns validated commands into a model and results.
//!
//! The evaluator (aster-eval) hands each validated [`aster_eval::CommandCall`]
//! to the [`Executor`], a [`aster_eval::CommandSink`] that keeps the concepts
//! a program creates (meshes, models, loads, functions, results, tables…) in
//! a typed store and runs each command through the mesh, fem and contact
//! crates. TEST_RESU/TEST_TABLE verdicts are printed as code_aster prints
//! them and tallied.

pub mod archive;
pub mod commands;
pub mod concept;
mod contactbridge;
pub mod defi_cont;
pub mod dyna;
pub mod elas_fo;
mod evaluate;
pub mod executor;
pub mod export;
pub mod fembridge;
pub mod field;
mod friction;
pub mod function;
pub mod journal;
mod line_search;
pub mod list;
pub mod meca_non_line;
pub mod mesh_methods;
mod meshio;
mod observation;
pub mod output;
pub mod preflight;
pub mod program;
pub mod progress;
pub mod pyfmt;
mod raised;
pub mod select;
mod shells;
pub mod solve;
pub mod support;
pub mod table;
pub mod table_read;
pub mod test_resu;
pub mod thermo_mat;
pub mod unil;
mod vtu_export;

pub use executor::{Executor, RunOptions};
