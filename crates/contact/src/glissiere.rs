//! `GLISSIERE='OUI'`: bilateral sliding contact (links that never open).
//!
//! code_aster:
//! - discrete zones (`cfinal`, `algogl`): every paired slave node is
//!   linked from the first pairing, whatever its gap, and no link is ever
//!   released — the condition is the equality g = 0 on the normal gap;
//! - continuous zones (`mmopti`, `mmglis`, `mm_cycl_algo`): a point is
//!   linked from the start with `CONTACT_INIT='OUI'`, or with
//!   `'INTERPENETRE'` when its initial gap is at most `epsint` =
//!   1e-6 × the shortest edge of the mesh (`armin`); afterwards every point
//!   found in contact when the contact loop has converged is linked for
//!   good.
//!
//! Here the continuous rows are per slave node (the weighted gap of the
//! node's integration points), so a node is linked: from the start as
//! `CONTACT_INIT` says (its weighted mean gap against `epsint`, or
//! `DIST_MAXI` when given), then once its row is active at a converged
//! step. code_aster links at each convergence of its contact loop, also
//! inside a step; here it happens at the end of each converged increment.
//! A linked row is an [`InequalityRow::bilateral`] row of fem's solver: an
//! equality whose multiplier may take either sign.

use std::collections::BTreeSet;

use aster_fem::{InequalityRow, RowOutcome};
use aster_mesh::{CellId, Mesh, NodeId};

use crate::zone::ContactInit;

/// The links of one zone.
#[derive(Clone, Debug, Default)]
pub(crate) struct Glissiere {
    /// `GLISSIERE='OUI'`.
    on: bool,
    /// Discrete zone: every row is linked.
    all: bool,
    init: ContactInit,
    /// `CONTACT_INIT='INTERPENETRE'` threshold on the initial gap.
    threshold: Option<f64>,
    /// Continuous zone: the linked slave nodes.
    linked: BTreeSet<NodeId>,
    /// Whether the initial links were made (first pairing).
    started: bool,
}

impl Glissiere {
    pub(crate) fn new(on: bool, discrete: bool, init: ContactInit, dist_maxi: Option<f64>) -> Self {
        Glissiere {
            on,
            all: on && discrete,
            init,
            threshold: dist_maxi,
            linked: BTreeSet::new(),
            started: false,
        }
    }

    pub(crate) fn is_on(&self) -> bool {
        self.on
    }

    /// At the first pairing of a continuous zone: the nodes linked from the
    /// start, given each node's weighted mean gap.
    pub(crate) fn start(&mut self, mesh: &Mesh, gaps: &[(NodeId, f64)]) {
        if !self.on || self.all || self.started {
            return;
        }
        self.started = true;
        let eps = self.threshold.unwrap_or_else(|| {
            let all: Vec<CellId> = (0..mesh.cells.len() as u32).map(CellId).collect();
            1e-6 * mesh
                .edge_length_range(&all)
                .map(|(lo, _)| lo)
                .unwrap_or(0.0)
        });
        for &(n, g) in gaps {
            let link = match self.init {
                ContactInit::Oui => true,
                ContactInit::Interpenetre => g <= eps,
                ContactInit::Non => false,
            };
            if link {
                self.linked.insert(n);
            }
        }
    }

    /// Whether the row of a carrier is linked (`node`: the slave node of a
    /// continuous row).
    pub(crate) fn links(&self, node: Option<NodeId>) -> bool {
        self.on && (self.all || node.is_some_and(|n| self.linked.contains(&n)))
    }

    /// Marks the linked rows bilateral (`node_of`: the slave node of a
    /// row id, for continuous rows).
    pub(crate) fn mark(
        &self,
        rows: &mut [InequalityRow],
        node_of: impl Fn(usize) -> Option<NodeId>,
    ) {
        if !self.on {
            return;
        }
        for r in rows {
            r.bilateral = self.links(node_of(r.id));
        }
    }

    /// A converged step: the nodes whose rows were active are linked for
    /// good (continuous zones).
    pub(crate) fn converged(
        &mut self,
        outcomes: &[RowOutcome],
        node_of: impl Fn(usize) -> Option<NodeId>,
    ) {
        if !self.on || self.all {
            return;
        }
        for o in outcomes.iter().filter(|o| o.active) {
            if let Some(n) = node_of(o.id) {
                self.linked.insert(n);
            }
        }
    }
}
