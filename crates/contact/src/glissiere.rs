//! `GLISSIERE='OUI'`: bilateral sliding contact (links that never open).
//!
//! code_aster:
//! - discrete zones (`cfinal`, `algogl`): every paired slave node is
//!   linked from the first pairing, whatever its gap, and no link is ever
//!   released — the condition is the equality g = 0 on the normal gap;
//! - continuous zones (`mmopti`, `mmglis`, `mm_cycl_algo`): a point is
//!   linked from the start with `CONTACT_INIT='OUI'`, or with
//!   `'INTERPENETRE'` when its initial gap is at most 1e-6 ×
//!   `CONTACT_INIT_DIST` (`mmopti`): `DIST_MAXI`, or without it the
//!   shortest edge of the zone's own slave and master cells (`contSetInit`,
//!   [`crate::ResolvedZone::contact_init_threshold`]); afterwards every
//!   point found in contact when the contact loop has converged is linked
//!   for good.
//!
//! Here the continuous rows are per slave node (the weighted gap of the
//! node's integration points), so a node is linked: from the start as
//! `CONTACT_INIT` says (its weighted mean gap against that threshold),
//! then once its row is active at a converged step. code_aster links at
//! each convergence of its contact loop, also inside a step; here it
//! happens at the end of each converged increment.
//! A linked row is an [`InequalityRow::bilateral`] row of fem's solver: an
//! equality whose multiplier may take either sign.

use std::collections::BTreeSet;

use aster_fem::{InequalityRow, RowOutcome};
use aster_mesh::NodeId;

use crate::zone::ContactInit;

/// The links of one zone.
#[derive(Clone, Debug, Default)]
pub(crate) struct Glissiere {
    /// `GLISSIERE='OUI'`.
    on: bool,
    /// Discrete zone: every row is linked.
    all: bool,
    init: ContactInit,
    /// Continuous zone: the linked slave nodes.
    linked: BTreeSet<NodeId>,
    /// Whether the initial links were made (first pairing).
    started: bool,
}

impl Glissiere {
    pub(crate) fn new(on: bool, discrete: bool, init: ContactInit) -> Self {
        Glissiere {
            on,
            all: on && discrete,
            init,
            linked: BTreeSet::new(),
            started: false,
        }
    }

    pub(crate) fn is_on(&self) -> bool {
        self.on
    }

    /// At the first pairing of a continuous zone: the nodes linked from the
    /// start, given each node's weighted mean gap and the zone's
    /// `CONTACT_INIT='INTERPENETRE'` threshold `eps`
    /// ([`crate::ResolvedZone::contact_init_threshold`]).
    pub(crate) fn start(&mut self, eps: f64, gaps: &[(NodeId, f64)]) {
        if !self.on || self.all || self.started {
            return;
        }
        self.started = true;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn linked(init: ContactInit, eps: f64) -> Vec<u32> {
        let mut g = Glissiere::new(true, false, init);
        let gaps: Vec<(NodeId, f64)> = [-1e-3, 0.0, 4e-7, 6e-7, 1e-3]
            .iter()
            .enumerate()
            .map(|(i, &d)| (NodeId(i as u32), d))
            .collect();
        g.start(eps, &gaps);
        // A second start (a later pairing) changes nothing.
        g.start(1.0, &gaps);
        g.linked.iter().map(|n| n.0).collect()
    }

    #[test]
    fn initial_links_follow_mmopti() {
        // INTERPENETRE: gap ≤ eps (here 5e-7, 1e-6 × an edge of 0.5).
        assert_eq!(linked(ContactInit::Interpenetre, 5e-7), vec![0, 1, 2]);
        assert_eq!(linked(ContactInit::Oui, 5e-7), vec![0, 1, 2, 3, 4]);
        assert!(linked(ContactInit::Non, 5e-7).is_empty());
    }

    #[test]
    fn discrete_or_off_zones_keep_no_initial_list() {
        let mut off = Glissiere::new(false, false, ContactInit::Oui);
        off.start(1.0, &[(NodeId(0), 0.0)]);
        assert!(off.linked.is_empty() && !off.links(Some(NodeId(0))));
        let mut discrete = Glissiere::new(true, true, ContactInit::Non);
        discrete.start(1.0, &[(NodeId(0), 1.0)]);
        assert!(discrete.links(Some(NodeId(0))) && discrete.links(None));
    }
}
