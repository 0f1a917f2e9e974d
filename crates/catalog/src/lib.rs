//! The command catalog of code_aster 17.
//!
//! The catalog is generated from code_aster's keyword facts by
//! `examples/gen_catalog.rs` and embedded as compact JSON, deserialised once on
//! first use. Entry points: [`catalog()`] then [`Catalog::command`]; block
//! conditions are evaluated by [`cond`]; result types and the concept type
//! hierarchy live in [`types`].

pub mod cond;
pub mod explain;
pub mod model;
pub mod types;

pub use model::*;

use std::collections::HashMap;
use std::sync::OnceLock;

static DATA: &str = include_str!("../data/catalog-v17.json");

/// All commands, by name.
pub struct Catalog {
    commands: Vec<Command>,
    by_name: HashMap<String, usize>,
    conditions: HashMap<String, Result<cond::Cond, String>>,
}

impl Catalog {
    fn load() -> Catalog {
        // The embedded data is produced by our generator and checked by the
        // tests; failing to read it is a build defect, not a user error.
        let mut commands: Vec<Command> = match serde_json::from_str(DATA) {
            Ok(c) => c,
            Err(e) => panic!("embedded catalog is corrupt: {e}"),
        };
        let by_name = commands
            .iter()
            .enumerate()
            .map(|(i, c)| (c.name.clone(), i))
            .collect();
        let mut conditions = HashMap::new();
        fn collect(entries: &[Entry], out: &mut HashMap<String, Result<cond::Cond, String>>) {
            for e in entries {
                match &e.node {
                    Node::Block(b) => {
                        out.entry(b.condition.clone())
                            .or_insert_with(|| cond::parse(&b.condition));
                        collect(&b.keywords, out);
                    }
                    Node::Factor(f) => collect(&f.keywords, out),
                    Node::Simple(_) => {}
                }
            }
        }
        for c in &commands {
            collect(&c.keywords, &mut conditions);
        }
        // Each block keeps its parsed condition: evaluating a block must
        // not cost a lookup by its source text.
        fn attach(entries: &mut [Entry], parsed: &HashMap<String, Result<cond::Cond, String>>) {
            for e in entries {
                match &mut e.node {
                    Node::Block(b) => {
                        b.parsed = parsed.get(&b.condition).cloned();
                        attach(&mut b.keywords, parsed);
                    }
                    Node::Factor(f) => attach(&mut f.keywords, parsed),
                    Node::Simple(s) => s.default_cond = s.default.as_deref().map(lits_cval),
                }
            }
        }
        for c in &mut commands {
            attach(&mut c.keywords, &conditions);
        }
        Catalog {
            commands,
            by_name,
            conditions,
        }
    }

    pub fn command(&self, name: &str) -> Option<&Command> {
        self.by_name.get(name).map(|&i| &self.commands[i])
    }

    pub fn commands(&self) -> &[Command] {
        &self.commands
    }

    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.commands.iter().map(|c| c.name.as_str())
    }

    /// The parsed form of a block condition (parsed once at load).
    pub fn condition(&self, source: &str) -> Result<&cond::Cond, &str> {
        match self.conditions.get(source) {
            Some(Ok(c)) => Ok(c),
            Some(Err(e)) => Err(e),
            None => Err("condition not in the catalog"),
        }
    }
}

/// The catalog, loaded on first use.
pub fn catalog() -> &'static Catalog {
    static CAT: OnceLock<Catalog> = OnceLock::new();
    CAT.get_or_init(Catalog::load)
}
