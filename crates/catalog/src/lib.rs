//! The command catalog of code_aster 17.
//!
//! The catalog is generated from code_aster's keyword facts by
//! `examples/gen_catalog.rs` into `data/catalog-v17.json`; the build script
//! (`build.rs`) turns that JSON into static tables of the [`model`] types, so
//! the program parses nothing and allocates nothing to use it. Entry points:
//! [`catalog()`] then [`Catalog::command`]; block conditions are evaluated
//! by [`cond`] (each block parses its condition once, on first use); result
//! types and the concept type hierarchy live in [`types`].

pub mod cond;
pub mod explain;
pub mod model;
pub mod types;

pub use model::*;

mod tables {
    use crate::model::*;
    include!(concat!(env!("OUT_DIR"), "/catalog-tables.rs"));
}

/// All commands, by name: static tables made at build time.
pub struct Catalog {
    _private: (),
}

impl Catalog {
    /// A command by name (a binary search in the static table).
    pub fn command(&self, name: &str) -> Option<&'static Command> {
        tables::BY_NAME
            .binary_search_by(|&i| tables::COMMANDS[i as usize].name.cmp(name))
            .ok()
            .map(|k| &tables::COMMANDS[tables::BY_NAME[k] as usize])
    }

    /// Every command, in catalog order.
    pub fn commands(&self) -> &'static [Command] {
        &tables::COMMANDS
    }

    /// Every command name, in catalog order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        tables::COMMANDS.iter().map(|c| c.name)
    }

    /// A block condition parsed (the parse a block keeps, see
    /// [`Block::cond`]).
    pub fn condition(&self, source: &str) -> Result<cond::Cond, String> {
        cond::parse(source)
    }
}

/// The catalog.
pub fn catalog() -> &'static Catalog {
    static CAT: Catalog = Catalog { _private: () };
    &CAT
}
