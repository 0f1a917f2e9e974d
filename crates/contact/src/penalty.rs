//! Continuous formulation, `ALGO_CONT='PENALISATION'`, as code_aster's
//! contact element computes it (`mmmvee`, `mmmtee`, `mmmvcc`, `mmmtcc` in
//! `bibfor/cont_elem`).
//!
//! - The force is **pointwise**: at each integration point p in contact,
//!   κ·wₚ·gₚ (κ = `COEF_PENA_CONT`, wₚ the point's weight, gₚ its
//!   penetration), spread on the slave and master nodes by their shape
//!   functions. One fem penalty row per point, scaled by √wₚ, gives
//!   exactly this (fem's penalty force is coef·(a·u − b)·a). A per-node
//!   weighted gap (what STANDARD enforces) would instead allow pointwise
//!   penetrations that cancel on each node: on non-matching meshes the two
//!   differ at the discretisation level (SSNP121 P: 0.35 % on LAGS_C).
//! - `LAGS_C` does not act on the displacements: it is the L² projection
//!   of the pointwise pressure onto the slave pressure functions,
//!   ∫ (λ/κ + g) Nⱼ = 0 on every point in contact and ∫ λ Nⱼ / κ = 0 on
//!   the others, i.e. M λ = Σₚ κ wₚ gₚ Nⱼ(p) with the consistent matrix
//!   M = Σₚ wₚ Nⱼ Nₖ over all points. LAGS_C = −λ.
//!
//! Difference with code_aster: its contact status of a point is
//! λₚ − κ gₚ < 0 with λₚ the interpolated LAGS_C of the previous Newton
//! iteration; here a point is in contact when it penetrates (gₚ > 0), the
//! limit of that test once LAGS_C has settled.

use std::collections::BTreeMap;

use aster_fem::InequalityRow;
use aster_mesh::{Mesh, NodeId};

use crate::pairing::ContactPair;
use crate::rows::contact_row;
use crate::surface::ResolvedZone;

/// The pressure functions of a slave point: (node, Nⱼ(p)).
fn pressure_functions(zone: &ResolvedZone, pair: &ContactPair) -> Vec<(NodeId, f64)> {
    match pair.point.cell {
        Some((ci, xi)) => {
            let c = &zone.slave[ci];
            c.nodes
                .iter()
                .copied()
                .zip(c.kind.pressure_eval(xi))
                .filter(|(_, n)| *n != 0.0)
                .collect()
        }
        None => pair.point.nodes.clone(),
    }
}

/// One penalty row per paired point, scaled by √wₚ (`None` for a point
/// that is not paired or has no term), with the row's id = the point's
/// index in `pairs`.
pub(crate) fn point_rows(
    zone: &ResolvedZone,
    pairs: &[ContactPair],
    mesh: &Mesh,
    x: &[[f64; 3]],
) -> Vec<Option<(InequalityRow, f64)>> {
    pairs
        .iter()
        .enumerate()
        .map(|(i, pair)| {
            let p = pair.pairing()?;
            let s = pair.point.weight.max(0.0).sqrt();
            if s == 0.0 {
                return None;
            }
            let row = contact_row(mesh, x, &pair.point.nodes, p, zone.space_dim, s, i);
            (!row.terms.is_empty()).then_some((row, s))
        })
        .collect()
}

/// code_aster's LAGS_C of a penalised zone: −λ with M λ = f, M the
/// consistent matrix of the slave pressure functions over every point,
/// f the pointwise forces (`forces[i]` = κ wᵢ gᵢ of point i, 0 when not in
/// contact). Nodes outside `zone.slave_nodes` (SANS_GROUP_NO) carry none.
pub(crate) fn lags_c(
    zone: &ResolvedZone,
    pairs: &[ContactPair],
    forces: &[f64],
) -> BTreeMap<NodeId, f64> {
    let free = |n: &NodeId| zone.slave_nodes.binary_search(n).is_ok();
    let mut index: BTreeMap<NodeId, usize> = BTreeMap::new();
    let mut matrix: Vec<BTreeMap<usize, f64>> = Vec::new();
    let mut rhs: Vec<f64> = Vec::new();
    for (i, pair) in pairs.iter().enumerate() {
        let functions: Vec<(usize, f64)> = pressure_functions(zone, pair)
            .into_iter()
            .filter(|(n, _)| free(n))
            .map(|(n, v)| {
                let next = index.len();
                let k = *index.entry(n).or_insert(next);
                if k == matrix.len() {
                    matrix.push(BTreeMap::new());
                    rhs.push(0.0);
                }
                (k, v)
            })
            .collect();
        let w = pair.point.weight;
        let f = forces.get(i).copied().unwrap_or(0.0);
        for &(j, nj) in &functions {
            rhs[j] += f * nj;
            for &(k, nk) in &functions {
                *matrix[j].entry(k).or_default() += w * nj * nk;
            }
        }
    }
    let lambda = conjugate_gradient(&matrix, &rhs);
    index
        .into_iter()
        .map(|(n, k)| (n, if lambda[k] == 0.0 { 0.0 } else { -lambda[k] }))
        .collect()
}

/// Solves the symmetric positive (semi-)definite system by Jacobi-
/// preconditioned conjugate gradients to round-off (a mass matrix: a few
/// tens of iterations whatever its size). Unknowns with a zero diagonal
/// stay 0.
fn conjugate_gradient(a: &[BTreeMap<usize, f64>], b: &[f64]) -> Vec<f64> {
    let n = b.len();
    let diag: Vec<f64> = (0..n)
        .map(|i| a[i].get(&i).copied().unwrap_or(0.0))
        .collect();
    let inv: Vec<f64> = diag
        .iter()
        .map(|d| if *d > 0.0 { 1.0 / d } else { 0.0 })
        .collect();
    let mul = |v: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| a[i].iter().map(|(&k, &c)| c * v[k]).sum())
            .collect()
    };
    let dot = |u: &[f64], v: &[f64]| -> f64 { u.iter().zip(v).map(|(a, b)| a * b).sum() };
    let mut x: Vec<f64> = (0..n).map(|i| b[i] * inv[i]).collect();
    let ax = mul(&x);
    let mut r: Vec<f64> = (0..n)
        .map(|i| if inv[i] > 0.0 { b[i] - ax[i] } else { 0.0 })
        .collect();
    let scale = dot(b, b).sqrt();
    if scale == 0.0 {
        return vec![0.0; n];
    }
    let mut z: Vec<f64> = (0..n).map(|i| r[i] * inv[i]).collect();
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    for _ in 0..(10 * n).max(50) {
        if dot(&r, &r).sqrt() <= 1e-15 * scale {
            break;
        }
        let ap = mul(&p);
        let pap = dot(&p, &ap);
        if pap <= 0.0 {
            break;
        }
        let alpha = rz / pap;
        for i in 0..n {
            x[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        z = (0..n).map(|i| r[i] * inv[i]).collect();
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        for i in 0..n {
            p[i] = z[i] + beta * p[i];
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conjugate_gradient_solves_a_mass_matrix() {
        // Consistent P1 mass matrix of three unit segments (4 nodes).
        let mut a = vec![BTreeMap::new(); 4];
        for e in 0..3 {
            for (i, j, v) in [(0, 0, 2.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 2.0)] {
                *a[e + i].entry(e + j).or_insert(0.0) += v / 6.0;
            }
        }
        // A uniform pressure 7: b = M·7.
        let b: Vec<f64> = (0..4).map(|i| a[i].values().sum::<f64>() * 7.0).collect();
        let x = conjugate_gradient(&a, &b);
        for v in x {
            assert!((v - 7.0).abs() < 1e-12, "{v}");
        }
    }
}
