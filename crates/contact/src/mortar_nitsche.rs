//! code_aster 17's Nitsche mortar contact of `DEFI_CONT`
//! (`ALGO_CONT='NITSCHE'`, `MECA_NON_LINE`), frictionless, in 2D on SEG2
//! and SEG3 slave faces of QUAD4/QUAD8/QUAD9/TRIA3/TRIA6 cells, as a fem
//! force source without unknowns of its own.
//!
//! As code_aster's (2025 main: `te0356`, `niElem`, `niQuantities`,
//! `niVect`, `niElemCont`, `contact_nitsche_module`,
//! `contact_algebra_module::dPi_du`, `ContactComputation::contactData`,
//! `MeshPairing::buildSlaveCellsVolu`):
//!
//! - Pairing, quadrature, normals, master points and gaps are those of the
//!   Lagrangian method (`mortar_lagrangian::pairs_of`, `mortar_point`).
//! - **The slave volume cell**: the cell other than the face itself that
//!   holds every node of a slave face (code_aster keeps it when exactly
//!   two cells do; a zone none of whose slave cells has one stops with
//!   `CONTACT1_3`, as code_aster).
//! - **Stress** (`evalStressNodes`, `evalStress`): at each node of the
//!   slave face, σ = 2μ ε + λ tr(ε) I with ε the symmetric gradient of the
//!   volume cell's total displacement on its initial coordinates and
//!   λ, μ the Lamé coefficients of the material's `ELAS` E, NU (the one
//!   material of the CHAM_MATER, whatever the behaviour); interpolated
//!   along the face with the slave's functions. In 2D ε_zz = 0 and the hoop
//!   strain is absent: the plane-strain law whatever the modelisation
//!   (C_PLAN's stress differs, AXIS misses u_r/r).
//! - **At a point** (`niElemCont`): σ_nn = (σ·n⁰)·n_s with n⁰ the slave
//!   normal on the initial coordinates and n_s the current one;
//!   γ = Σ N_a COEF_CONT / h_F; active when σ_nn + γg ≤ 0 (`CONTACT_INIT`
//!   at the first pairing as for the Lagrangian method).
//! - **Residual** (`niVect`): w [σ_nn + γg]₋ Dg[v] with Dg the
//!   derivative of the ray-traced gap (`dPi_du`): (Dζ_m, Dg) solves
//!   τ_m Dζ_m − n_s Dg = v_s − v_m + g Dn_s, Dn_s = −τ_s (n_s·Dτ_s)/|τ_s|².
//!   The variant's term θ (D σ_nn[v], ([σ_nn + γg]₋ − σ_nn)/γ) vanishes
//!   because code_aster's `dStress_n_du` is zero (and the face part of
//!   `dStress_nn_du` is commented out): `SYME='OUI'`, `VARIANTE='ROBUSTE'`
//!   and `'RAPIDE'` give the same residual, hence the same solution.
//! - **Newton**: the residual (no status criterion) and, with
//!   MECA_NON_LINE's `CONTACT/RESI_GEOM`, the displacement increment
//!   (`ResiGeom`, as for the other methods). The tangent
//!   here is w Dg⊗(γ Dg + Dσ_nn) at active points, with the exact
//!   derivative of σ_nn with respect to the volume cell's displacements
//!   (code_aster's matrix lacks it and converges linearly), normals and
//!   master points frozen: the path differs, the converged state does not.

use std::collections::HashMap;

use aster_fem::{Contribution, FemError, ForceSource, State, Unknown};
use aster_mesh::{CellType, Mesh, NodeId};

use crate::error::ContactError;
use crate::mortar_lagrangian::{
    normal_at, pairs_of, MZone, MortarLagrangian, MortarZoneDef, ResiGeom, Seg,
};
use crate::mortar_penalty::{gamma, status};
use crate::mortar_point::{dof, points, MortarPoint};
use crate::shape::dot;
use crate::source::current_positions;

/// The material of a Nitsche contact: `ELAS` E and NU.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NitscheMaterial {
    pub young: f64,
    pub poisson: f64,
}

/// The volume cell under a slave face.
#[derive(Clone, Debug)]
struct Volume {
    nodes: Vec<NodeId>,
    /// ∂N_n/∂x, ∂N_n/∂y of each of the volume's functions n (initial
    /// coordinates) at each node of the face, in the face's node order.
    grads: Vec<Vec<[f64; 2]>>,
}

/// The Nitsche mortar contact of a DEFI_CONT, as a fem force source.
#[derive(Clone, Debug)]
pub struct MortarNitsche {
    zones: Vec<MZone>,
    /// Per zone, per slave cell: its volume cell.
    volumes: Vec<Vec<Volume>>,
    lambda: f64,
    mu: f64,
    axis: bool,
    /// No pairing has been made yet (CONTACT_INIT applies).
    first_pairing: bool,
    /// MECA_NON_LINE's `CONTACT/RESI_GEOM` ([`MortarNitsche::set_resi_geom`]).
    resi_geom: ResiGeom,
}

/// The cells that hold every node of `nodes`.
fn holders(cells_of_node: &HashMap<NodeId, Vec<usize>>, nodes: &[NodeId]) -> Vec<usize> {
    let Some(first) = nodes.first().and_then(|n| cells_of_node.get(n)) else {
        return Vec::new();
    };
    first
        .iter()
        .copied()
        .filter(|c| {
            nodes[1..]
                .iter()
                .all(|n| cells_of_node.get(n).is_some_and(|v| v.contains(c)))
        })
        .collect()
}

/// ∂N/∂x of the cell's functions at reference point `xi`, on coordinates
/// `x` (`gradFuncDispVolu`).
fn gradients(ty: CellType, x: &[[f64; 3]], xi: [f64; 3]) -> Option<Vec<[f64; 2]>> {
    let s = aster_fem::shape::shape(ty, xi);
    // g(i, j) = Σ x_j ∂N/∂ξ_i
    let mut g = [[0.0f64; 2]; 2];
    for (n, p) in x.iter().enumerate() {
        for i in 0..2 {
            for j in 0..2 {
                g[i][j] += p[j] * s.dn[n][i];
            }
        }
    }
    let det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    if !(det.abs() > 0.0 && det.is_finite()) {
        return None;
    }
    let inv = [
        [g[1][1] / det, -g[0][1] / det],
        [-g[1][0] / det, g[0][0] / det],
    ];
    Some(
        s.dn.iter()
            .map(|d| {
                [
                    inv[0][0] * d[0] + inv[0][1] * d[1],
                    inv[1][0] * d[0] + inv[1][1] * d[1],
                ]
            })
            .collect(),
    )
}

impl MortarNitsche {
    /// The contact of `zones` on `mesh` (a 2D model; `axis`: AXIS weights)
    /// with the material's E and NU.
    pub fn new(
        zones: &[MortarZoneDef],
        mesh: &Mesh,
        axis: bool,
        material: NitscheMaterial,
    ) -> Result<Self, ContactError> {
        let geometry = MortarLagrangian::new(zones, mesh, axis, 2)?;
        let mut cells_of_node: HashMap<NodeId, Vec<usize>> = HashMap::new();
        for (i, c) in mesh.cells.iter().enumerate() {
            for n in &c.nodes {
                cells_of_node.entry(*n).or_default().push(i);
            }
        }
        let mut volumes = Vec::new();
        for (zi, z) in geometry.zones.iter().enumerate() {
            // code_aster maps a slave cell to the other cell when exactly
            // two cells hold its nodes, and stops (CONTACT1_3) only when
            // the map of the zone is empty.
            if !z
                .slave
                .iter()
                .any(|s| holders(&cells_of_node, &s.nodes).len() == 2)
            {
                return Err(ContactError::SlaveWithoutVolume { zone: zi + 1 });
            }
            let mut vz = Vec::new();
            for s in &z.slave {
                vz.push(volume_of(mesh, &cells_of_node, s).ok_or_else(|| {
                    let names: Vec<String> = s
                        .nodes
                        .iter()
                        .map(|n| mesh.node_name(*n))
                        .collect();
                    ContactError::Invalid {
                        keyword: "GROUP_MA_ESCL",
                        message: format!(
                            "the slave face of nodes {} of zone {} has no single QUAD4, QUAD8, QUAD9, TRIA3 or TRIA6 cell under it: the Nitsche method takes the stress of that cell",
                            names.join(", "),
                            zi + 1
                        ),
                    }
                })?);
            }
            volumes.push(vz);
        }
        let (e, nu) = (material.young, material.poisson);
        Ok(MortarNitsche {
            zones: geometry.zones,
            volumes,
            lambda: e * nu / (1.0 + nu) / (1.0 - 2.0 * nu),
            mu: 0.5 * e / (1.0 + nu),
            axis,
            first_pairing: true,
            resi_geom: ResiGeom::new(mesh),
        })
    }

    /// code_aster 17's geometric criterion, applied whatever `ALGO_CONT`
    /// (MECA_NON_LINE's `CONTACT/RESI_GEOM`, as
    /// [`MortarLagrangian::set_resi_geom`]).
    pub fn set_resi_geom(&mut self, resi_geom: f64) {
        self.resi_geom.tol = Some(resi_geom);
    }

    /// σ (xx, yy, xy) at each node of a slave face.
    fn nodal_stresses(&self, state: &State, v: &Volume) -> Vec<[f64; 3]> {
        let u: Vec<[f64; 3]> = v
            .nodes
            .iter()
            .map(|n| state.node_displacement(*n))
            .collect();
        v.grads
            .iter()
            .map(|grads| {
                // grad(i, j) = Σ ∂N_n/∂x_j u_i(n)
                let mut grad = [[0.0f64; 2]; 2];
                for (g, un) in grads.iter().zip(&u) {
                    for i in 0..2 {
                        for j in 0..2 {
                            grad[i][j] += g[j] * un[i];
                        }
                    }
                }
                let exx = grad[0][0];
                let eyy = grad[1][1];
                let exy = (grad[0][1] + grad[1][0]) / 2.0;
                let tr = exx + eyy;
                [
                    2.0 * self.mu * exx + self.lambda * tr,
                    2.0 * self.mu * eyy + self.lambda * tr,
                    2.0 * self.mu * exy,
                ]
            })
            .collect()
    }
}

/// The volume cell under slave face `s` and the gradients of its
/// functions at the face's nodes (`MeshPairing`: the other cell when
/// exactly two cells hold the face's nodes).
fn volume_of(mesh: &Mesh, cells_of_node: &HashMap<NodeId, Vec<usize>>, s: &Seg) -> Option<Volume> {
    let held = holders(cells_of_node, &s.nodes);
    if held.len() != 2 {
        return None;
    }
    let (a, b) = (&mesh.cells[held[0]], &mesh.cells[held[1]]);
    let cell = if a.ty.dim() == 2 && b.ty.dim() != 2 {
        a
    } else if b.ty.dim() == 2 && a.ty.dim() != 2 {
        b
    } else {
        return None;
    };
    if !matches!(
        cell.ty,
        CellType::QUAD4 | CellType::QUAD8 | CellType::QUAD9 | CellType::TRIA3 | CellType::TRIA6
    ) {
        return None;
    }
    let x: Vec<[f64; 3]> = cell.nodes.iter().map(|n| mesh.coord(*n)).collect();
    let refs = aster_fem::shape::reference_nodes(cell.ty);
    let grads = s
        .nodes
        .iter()
        .map(|n| {
            let k = cell.nodes.iter().position(|m| m == n)?;
            gradients(cell.ty, &x, *refs.get(k)?)
        })
        .collect::<Option<Vec<_>>>()?;
    Some(Volume {
        nodes: cell.nodes.clone(),
        grads,
    })
}

/// Dg at a point (`dPi_du`, 2D): the derivative of the ray-traced gap with
/// respect to the slave's and master's DOFs, with the slave's shape
/// derivatives `ds` at the point.
fn gap_derivative(
    state: &State,
    s: &Seg,
    m: &Seg,
    pt: &MortarPoint,
    ds: &[[f64; 2]],
) -> Vec<(usize, f64)> {
    let tm = pt.master.tangents[0];
    let ts = pt.slave.tangents[0];
    let n = pt.ns;
    let g = pt.gap;
    let tt = dot(ts, ts);
    // (τ_m, −n_s) (Dζ, Dg) = r: Dg = det(τ_m, r) / det(τ_m, −n_s).
    let det = tm[0] * (-n[1]) - (-n[0]) * tm[1];
    let solve = |r: [f64; 2]| (tm[0] * r[1] - tm[1] * r[0]) / det;
    let mut out = Vec::with_capacity(12);
    for (a, node) in s.nodes.iter().enumerate() {
        for d in 0..2 {
            let Some(i) = dof(state, *node, d) else {
                continue;
            };
            // v_s: e_d N_a; g Dn_s = −g τ_s (∂N_a/∂ξ n_d) / |τ_s|²
            let c = -g * ds[a][0] * n[d] / tt;
            let mut r = [c * ts[0], c * ts[1]];
            r[d] += pt.initial.shape[a];
            out.push((i, solve(r)));
        }
    }
    for (b, node) in m.nodes.iter().enumerate() {
        for d in 0..2 {
            let Some(i) = dof(state, *node, d) else {
                continue;
            };
            let mut r = [0.0, 0.0];
            r[d] = -pt.master.shape[b];
            out.push((i, solve(r)));
        }
    }
    out
}

impl ForceSource for MortarNitsche {
    fn name(&self) -> String {
        "DEFI_CONT (mortar Nitsche contact)".into()
    }

    fn unknowns(&self) -> usize {
        0
    }

    fn begin_increment(&mut self, state: &State, _own: &mut [f64]) -> Result<(), FemError> {
        self.resi_geom.begin(state);
        Ok(())
    }

    fn evaluate(&mut self, state: &State, _own: &[f64]) -> Result<Contribution, FemError> {
        let x = current_positions(state);
        let x0 = &state.mesh.coords;
        let mut c = Contribution::default();
        let (lambda, mu) = (self.lambda, self.mu);
        for p in pairs_of(&self.zones, &x) {
            let z = &self.zones[p.zone];
            let s = &z.slave[p.slave];
            let m = &z.master[p.master];
            let v = &self.volumes[p.zone][p.slave];
            let sp = s.positions(&x);
            let mp = m.positions(&x);
            let s0 = s.positions(x0);
            let hf = z.h[p.slave];
            let stresses = self.nodal_stresses(state, v);
            for pt in points(s, m, p.xi, &sp, &mp, &s0, self.axis)? {
                let shape = &pt.initial.shape;
                let xi = pt.initial.xi;
                let n0 = normal_at(s.kind, &s0, xi[0], s.sign).ok_or_else(|| {
                    crate::mortar_lagrangian::err(ContactError::Invalid {
                        keyword: "GROUP_MA_ESCL",
                        message: "a slave cell is degenerate (zero length)".into(),
                    })
                })?;
                let mut sig = [0.0f64; 3];
                for (na, sa) in shape.iter().zip(&stresses) {
                    for k in 0..3 {
                        sig[k] += na * sa[k];
                    }
                }
                let ns = pt.ns;
                let sn = [
                    sig[0] * n0[0] + sig[2] * n0[1],
                    sig[2] * n0[0] + sig[1] * n0[1],
                ];
                let snn = sn[0] * ns[0] + sn[1] * ns[1];
                let gam = gamma(shape, z.coef, hf);
                let (h, proj) = status(snn + gam * pt.gap, z.forced(self.first_pairing));
                if !h {
                    continue;
                }
                let w = pt.w;
                let (_, ds) = s.kind.eval(xi);
                let dg = gap_derivative(state, s, m, &pt, &ds);
                // Dσ_nn with respect to the volume cell's DOFs:
                // n_s·C:sym(e_i ⊗ ∇N_n)·n⁰, interpolated over the face.
                let mut dsnn: Vec<(usize, f64)> = Vec::with_capacity(2 * v.nodes.len());
                for (k, node) in v.nodes.iter().enumerate() {
                    for i in 0..2 {
                        let Some(dof_i) = dof(state, *node, i) else {
                            continue;
                        };
                        let mut val = 0.0;
                        for (na, grads) in shape.iter().zip(&v.grads) {
                            let gn = grads[k];
                            let gn_n0 = gn[0] * n0[0] + gn[1] * n0[1];
                            let gn_ns = gn[0] * ns[0] + gn[1] * ns[1];
                            let eps_nn = 0.5 * (ns[i] * gn_n0 + n0[i] * gn_ns);
                            val += na * (2.0 * mu * eps_nn + lambda * gn[i] * dot(ns, n0));
                        }
                        dsnn.push((dof_i, val));
                    }
                }
                for &(i, fi) in &dg {
                    // w [σ_nn + γg]₋ Dg[v]
                    c.forces.push((i, w * proj * fi));
                    for &(j, fj) in &dg {
                        c.tangent
                            .push((Unknown::Dof(i), Unknown::Dof(j), w * gam * fi * fj));
                    }
                    for &(j, fj) in &dsnn {
                        c.tangent
                            .push((Unknown::Dof(i), Unknown::Dof(j), w * fi * fj));
                    }
                }
            }
        }
        Ok(c)
    }

    fn after_iteration(&mut self, state: &State, _own: &mut [f64]) -> Result<bool, FemError> {
        self.first_pairing = false;
        Ok(self.resi_geom.accept(state))
    }

    fn converged(&mut self, _state: &State, _own: &[f64]) -> Result<(), FemError> {
        self.first_pairing = false;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradients_of_a_unit_square_are_the_reference_ones_halved() {
        let x = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
        ];
        let g = gradients(CellType::QUAD4, &x, [-1.0, -1.0, 0.0]).unwrap();
        // At node 1: N1 = (1-ξ)(1-η)/4, ∂N1/∂ξ = -(1-η)/4 = -1/2, x = 1 + ξ.
        assert!((g[0][0] + 0.5).abs() < 1e-15 && (g[0][1] + 0.5).abs() < 1e-15);
        assert!((g[1][0] - 0.5).abs() < 1e-15 && g[1][1].abs() < 1e-15);
    }
}
