//! Continuous formulation, `ALGO_CONT='STANDARD'`: code_aster's augmented
//! Lagrangian term (`mmmvee`, `mmmtee`, status `mmstac`).
//!
//! code_aster's contact element applies at each integration point in
//! contact the force −(λ − ρ g)·n (λ the interpolated LAGS_C, negative in
//! compression; g the pointwise penetration; ρ = `COEF_CONT`), while the
//! multiplier equation only asks ∫ g Nⱼ = 0 per slave node. On a
//! non-matching or curved interface g is not zero pointwise at the
//! solution, and ρ g adds forces of the size ρ·g: with `COEF_CONT` equal
//! to Young's modulus (SSNP167F) they move the displacements by 3e-5.
//! The node rows carry λ; this module gives fem, per paired point, the
//! bilateral penalty term ρ·w·g that rides on them ([`AugmentedTerm`]),
//! on while the point is in contact: Σ Nⱼ λⱼ + ρ g > 0, code_aster's
//! λ − ρ g < 0 with its signs (LAGS_C = −λ here).
//!
//! Difference with code_aster: its multiplier equation of a slave node
//! leaves out the points of the node that are not in contact (and adds
//! ∫ λ Nⱼ / ρ for them); here every paired point of the node counts. The
//! two agree where a node's points share one status (all of them in a
//! closed contact, or none).

use std::collections::BTreeMap;

use aster_fem::AugmentedTerm;
use aster_mesh::{Mesh, NodeId};

use crate::pairing::ContactPair;
use crate::rows::contact_row;
use crate::surface::ResolvedZone;

/// The augmented term of every paired point with a pressure node that
/// carries a row (`node_rows`: slave node → its row index).
pub(crate) fn terms(
    zone: &ResolvedZone,
    pairs: &[ContactPair],
    node_rows: &BTreeMap<NodeId, usize>,
    coef_cont: f64,
    mesh: &Mesh,
    x: &[[f64; 3]],
) -> Vec<AugmentedTerm> {
    let mut out = Vec::new();
    for pair in pairs {
        let Some(p) = pair.pairing() else { continue };
        let functions: Vec<(NodeId, f64)> = match pair.point.cell {
            Some((ci, xi)) => {
                let c = &zone.slave[ci];
                c.nodes
                    .iter()
                    .copied()
                    .zip(c.kind.pressure_eval(xi))
                    .collect()
            }
            None => pair.point.nodes.clone(),
        };
        let support: Vec<(usize, f64)> = functions
            .iter()
            .filter(|(_, n)| *n != 0.0)
            .filter_map(|(node, n)| node_rows.get(node).map(|&r| (r, *n)))
            .collect();
        if support.is_empty() || pair.point.weight <= 0.0 {
            continue;
        }
        let row = contact_row(mesh, x, &pair.point.nodes, p, zone.space_dim, 1.0, 0);
        if row.terms.is_empty() {
            continue;
        }
        out.push(AugmentedTerm {
            row,
            coef: coef_cont,
            weight: pair.point.weight,
            support,
        });
    }
    out
}
