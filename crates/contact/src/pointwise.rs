//! Where the continuous formulation here and code_aster's part ways.
//!
//! code_aster's continuous contact (STANDARD and PENALISATION) decides a
//! contact status at every integration point (`mmstac`: λₚ − ρ gₚ < 0); a
//! point in contact contributes ∫ μ gₚ to the equation of the nodal
//! pressures, a point out of contact ∫ μ λₚ / ρ. Here the condition is
//! one row per slave node, the weighted gap Σₚ wₚ Nⱼ(p) gₚ of its points.
//! The two are the same system when the points of every slave cell share
//! a status — all nodes of the cell in contact, or none — and whenever the
//! points are the nodes themselves (nodal integration, `INTEGRATION=
//! 'AUTO'` on linear cells). On a cell whose nodes are partly in contact
//! with integration points elsewhere (Gauss, Simpson, Newton–Cotes, and
//! AUTO on TRIA6/QUAD8 faces), code_aster's answer depends on the points'
//! statuses and on COEF_CONT: measured on ssnp154b, forma04b and ssna102g
//! (Hertz-type contact edges) the values differ by 1e-5 to several
//! percent. Such a converged step is therefore refused with the cell named
//! rather than reported.

use std::collections::{BTreeMap, BTreeSet};

use aster_fem::RowOutcome;
use aster_mesh::NodeId;

use crate::pairing::ContactPair;
use crate::surface::ResolvedZone;

/// The first slave cell integrated at points other than its nodes whose
/// nodes are partly in contact (`active`: the contact status of each slave
/// node with a row), with its nodes in and out of contact.
pub(crate) fn mixed_cell(
    zone: &ResolvedZone,
    pairs: &[ContactPair],
    outcomes: &[RowOutcome],
    node_of: impl Fn(usize) -> Option<NodeId>,
) -> Option<(usize, Vec<NodeId>, Vec<NodeId>)> {
    let active: BTreeMap<NodeId, bool> = outcomes
        .iter()
        .filter_map(|o| node_of(o.id).map(|n| (n, o.active)))
        .collect();
    let cells: BTreeSet<usize> = pairs
        .iter()
        .filter_map(|p| p.point.cell.map(|(ci, _)| ci))
        .collect();
    for ci in cells {
        let mut on = Vec::new();
        let mut off = Vec::new();
        for n in &zone.slave[ci].nodes {
            match active.get(n) {
                Some(true) => on.push(*n),
                Some(false) => off.push(*n),
                None => {}
            }
        }
        if !on.is_empty() && !off.is_empty() {
            return Some((ci, on, off));
        }
    }
    None
}
