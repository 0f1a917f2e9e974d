//! The command catalog of code_aster 17.
//!
//! The catalog is generated from code_aster's keyword facts by
//! `examples/gen_catalog.rs` and embedded as compact JSON; the build script
//! splits it by command so that each command is deserialised on its first
//! use, and only then (see [`load`]). Entry points: [`catalog()`] then
//! [`Catalog::command`]; block conditions are evaluated by [`cond`]; result
//! types and the concept type hierarchy live in [`types`].

pub mod cond;
pub mod explain;
pub mod load;
pub mod model;
pub mod types;

pub use model::*;

use std::sync::OnceLock;

mod index {
    include!(concat!(env!("OUT_DIR"), "/catalog-index.rs"));
}

/// Every command's JSON, one after the other (spans in `index::COMMANDS`).
static BLOB: &str = include_str!(concat!(env!("OUT_DIR"), "/catalog-commands.json"));

/// All commands, by name, each read on its first use.
pub struct Catalog {
    /// One slot per command, in catalog order.
    slots: Vec<OnceLock<Command>>,
    /// Every command at once, for the callers that list them all.
    all: OnceLock<Vec<Command>>,
}

impl Default for Catalog {
    fn default() -> Self {
        Catalog::new()
    }
}

impl Catalog {
    /// A catalog of which nothing is read yet (see [`catalog()`] for the
    /// shared one).
    pub fn new() -> Catalog {
        Catalog {
            slots: index::COMMANDS.iter().map(|_| OnceLock::new()).collect(),
            all: OnceLock::new(),
        }
    }

    /// Reads command `i` of the embedded data, its block conditions parsed
    /// and its defaults prepared.
    fn read(i: usize) -> Command {
        let (name, a, b) = index::COMMANDS[i];
        // The embedded data is produced by our generator and checked by the
        // tests; failing to read it is a build defect, not a user error.
        let mut c: Command = match serde_json::from_str(&BLOB[a as usize..b as usize]) {
            Ok(c) => c,
            Err(e) => panic!("embedded catalog is corrupt at {name}: {e}"),
        };
        // Each block keeps its parsed condition: evaluating a block must
        // not cost a parse.
        fn attach(entries: &mut [Entry]) {
            for e in entries {
                match &mut e.node {
                    Node::Block(b) => {
                        b.parsed = Some(cond::parse(&b.condition));
                        attach(&mut b.keywords);
                    }
                    Node::Factor(f) => attach(&mut f.keywords),
                    Node::Simple(s) => s.default_cond = s.default.as_deref().map(lits_cval),
                }
            }
        }
        attach(&mut c.keywords);
        c
    }

    fn position(name: &str) -> Option<usize> {
        index::BY_NAME
            .binary_search_by(|&i| index::COMMANDS[i as usize].0.cmp(name))
            .ok()
            .map(|k| index::BY_NAME[k] as usize)
    }

    /// A command by name, read on its first use.
    pub fn command(&self, name: &str) -> Option<&Command> {
        let i = Self::position(name)?;
        if let Some(all) = self.all.get() {
            return all.get(i);
        }
        Some(self.slots[i].get_or_init(|| Self::read(i)))
    }

    /// Every command, in catalog order (reads them all).
    pub fn commands(&self) -> &[Command] {
        self.all.get_or_init(|| {
            (0..index::COMMANDS.len())
                .map(|i| match self.slots[i].get() {
                    Some(c) => c.clone(),
                    None => Self::read(i),
                })
                .collect()
        })
    }

    /// How many commands have been read so far (one per distinct
    /// [`Catalog::command`] name; all of them after [`Catalog::commands`]).
    pub fn read_count(&self) -> usize {
        match self.all.get() {
            Some(all) => all.len(),
            None => self.slots.iter().filter(|s| s.get().is_some()).count(),
        }
    }

    /// Every command name, in catalog order (reads nothing).
    pub fn names(&self) -> impl Iterator<Item = &str> {
        index::COMMANDS.iter().map(|c| c.0)
    }

    /// A block condition parsed (the parse the catalog keeps in
    /// [`Block::parsed`]).
    pub fn condition(&self, source: &str) -> Result<cond::Cond, String> {
        cond::parse(source)
    }
}

/// The catalog, loaded on first use.
pub fn catalog() -> &'static Catalog {
    static CAT: OnceLock<Catalog> = OnceLock::new();
    CAT.get_or_init(Catalog::new)
}
