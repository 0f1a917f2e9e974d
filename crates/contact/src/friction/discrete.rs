//! The discrete penalised friction (placeholder, see module `friction`).

/// code_aster's discrete penalised friction as a fem force source.
#[derive(Clone, Debug, Default)]
pub struct DiscreteFriction;
