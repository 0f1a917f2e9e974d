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

use aster_fem::{AugmentedTerm, Dof};
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

/// A slave node whose multiplier equation differs from code_aster's at the
/// converged state: its integration points do not share one contact status
/// (code_aster's `mmstac`: on while Σ Nⱼ λⱼ + ρ g > 0), so code_aster's
/// equation — ∫ g Nⱼ over the points in contact, minus ∫ λ Nⱼ / ρ over the
/// others — is not the weighted gap over all the node's points solved here.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MixedNode {
    /// The node's row (index into the rows of the last pairing).
    pub row: usize,
    /// |Σ_off w Nⱼ (g + λ/ρ)| / Σ w Nⱼ: how far code_aster's equation is
    /// from holding at this state (a length).
    pub misfit: f64,
}

/// The node with the largest misfit between the two multiplier equations,
/// if any node's points have mixed statuses (`multipliers` and `value`
/// give the converged row multipliers and displacements).
pub(crate) fn worst_mixed_node(
    terms: &[AugmentedTerm],
    multipliers: &[f64],
    value: impl Fn(Dof) -> f64,
) -> Option<MixedNode> {
    // Per row: (points on, points off, Σ_off w N (g + λ/ρ), Σ w N).
    let mut acc: BTreeMap<usize, (usize, usize, f64, f64)> = BTreeMap::new();
    for t in terms {
        let g: f64 = t.row.terms.iter().map(|&(d, c)| c * value(d)).sum::<f64>() - t.row.rhs;
        let lambda: f64 = t
            .support
            .iter()
            .map(|&(r, n)| n * multipliers.get(r).copied().unwrap_or(0.0))
            .sum();
        let on = lambda + t.coef * g > 0.0;
        for &(r, n) in &t.support {
            let e = acc.entry(r).or_insert((0, 0, 0.0, 0.0));
            if on {
                e.0 += 1;
            } else {
                e.1 += 1;
                e.2 += t.weight * n * (g + lambda / t.coef);
            }
            e.3 += t.weight * n;
        }
    }
    acc.into_iter()
        .filter(|(_, (on, off, _, w))| *on > 0 && *off > 0 && *w > 0.0)
        .map(|(row, (_, _, d, w))| MixedNode {
            row,
            misfit: (d / w).abs(),
        })
        .max_by(|a, b| a.misfit.total_cmp(&b.misfit))
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_fem::{Comp, InequalityRow};

    /// A point whose penetration is `−u_DY(node) − b`, on row 0 with N = `n`.
    fn point(node: u32, b: f64, n: f64) -> AugmentedTerm {
        let d = Dof {
            node: NodeId(node),
            comp: Comp::DY,
        };
        AugmentedTerm {
            row: InequalityRow::new(vec![(d, -1.0)], b, 0),
            coef: 100.0,
            weight: 0.5,
            support: vec![(0, n)],
        }
    }

    #[test]
    fn mixed_statuses_are_found_with_code_aster_misfit() {
        let u = |d: Dof| if d.node == NodeId(1) { -0.01 } else { 0.02 };
        // Point 1 penetrates by 0.01 (on); point 2 is open by 0.02 under a
        // pressure 1 (λ + ρ g = 1 − 2 < 0: off).
        let terms = [point(1, 0.0, 0.5), point(2, 0.0, 0.5)];
        let m = worst_mixed_node(&terms, &[2.0], u).unwrap();
        assert_eq!(m.row, 0);
        // Σ_off w N (g + λ/ρ) / Σ w N = 0.25·(−0.02 + 1/100) / 0.5.
        assert!((m.misfit - 0.005).abs() < 1e-15, "{}", m.misfit);
        // Both points in contact (a larger pressure): nothing to report.
        assert_eq!(worst_mixed_node(&terms, &[10.0], u), None);
        // Both out of contact, no pressure: nothing either.
        let open = |_: Dof| 0.05;
        assert_eq!(worst_mixed_node(&terms, &[0.0], open), None);
    }
}
