//! The plane joint element of `MODELISATION='PLAN_JOINT'` on QUAD4
//! (`MFPLQU4`: `te0201` → `nmfi2d`, `nmfisa`; `FORC_NODA`: `te0202` →
//! `nmfifi`): a cell whose face 1-2 lies on one body and face 3-4 (node 4
//! facing node 1, node 3 facing node 2) on the other, as
//! `MODI_MAILLAGE/ORIE_FISSURE` numbers it.
//!
//! At each of its two Gauss points (code_aster's `FIS2`: the weights
//! c = (1 ± 1/√3)/2 on the face's two nodes), the displacement jump in the
//! frame of face 1-2 — the normal n = (Δy, −Δx)/L (the right-hand normal
//! of 1 → 2, pointing away from the other face for a counter-clockwise
//! cell) and the tangent t = (−n_y, n_x) — is
//!
//! ```text
//! δ = B u,  δ_n = n·(c u1 + (1−c) u2 − (1−c) u3 − c u4),  δ_t likewise with t
//! ```
//!
//! and the internal forces and tangent are `Σ_g (L/2) Bᵀ σ` and
//! `Σ_g (L/2) Bᵀ (∂σ/∂δ) B` (`L` the length of face 1-2; plane, per unit
//! thickness). The traction σ (`SIGN`, `SITX`) comes from a cohesive law
//! ([`crate::cohesive`]).
//!
//! [`JointCells`] puts a set of joint cells into the non-linear solver as a
//! force source without unknowns of its own ([`crate::ForceSource`]): at
//! each Newton iterate the law is integrated from the jump at the start of
//! the increment and its increment (code_aster's `FULL_MECA`), the
//! internal variables are kept at the start of the increment and committed
//! once it has converged.

use crate::cohesive::{CohesiveLaw, Phase};
use crate::dof::{Comp, Dof};
use crate::error::FemError;
use crate::force_source::{Contribution, ForceSource, Unknown};
use crate::unilateral::State;
use aster_mesh::{CellId, NodeId};

/// The two Gauss points' weights of node 1 (code_aster's `coef`).
pub fn gauss_coefficients() -> [f64; 2] {
    let r = 3f64.sqrt() / 3.0;
    [0.5 * (1.0 + r), 0.5 * (1.0 - r)]
}

/// The jump operator and the integration weight of Gauss point `kpg`
/// (0 or 1) of a joint QUAD4 whose corners are `geom` (code_aster's
/// `nmfisa`, plane case). Rows: normal, tangential jump; columns: DX, DY
/// of nodes 1 to 4.
pub fn jump_operator(geom: &[[f64; 2]; 4], kpg: usize) -> (f64, [[f64; 8]; 2]) {
    let coef = gauss_coefficients()[kpg];
    let dx = geom[1][0] - geom[0][0];
    let dy = geom[1][1] - geom[0][1];
    let aire = (dx * dx + dy * dy).sqrt();
    let poids = aire / 2.0;
    let (co, si) = (dy, -dx);
    let norm = (co * co + si * si).sqrt();
    let (c, s) = (co / norm, si / norm);
    let w = [coef, 1.0 - coef, -(1.0 - coef), -coef];
    let mut b = [[0.0; 8]; 2];
    for (a, wa) in w.iter().enumerate() {
        b[0][2 * a] = c * wa;
        b[0][2 * a + 1] = s * wa;
        b[1][2 * a] = -s * wa;
        b[1][2 * a + 1] = c * wa;
    }
    (poids, b)
}

/// The jumps (normal, tangential) at the two Gauss points for the element
/// displacements `u` (DX, DY of nodes 1 to 4).
pub fn jumps(geom: &[[f64; 2]; 4], u: &[f64; 8]) -> [[f64; 2]; 2] {
    let mut out = [[0.0; 2]; 2];
    for (kpg, o) in out.iter_mut().enumerate() {
        let (_, b) = jump_operator(geom, kpg);
        for q in 0..2 {
            o[q] = (0..8).map(|j| b[q][j] * u[j]).sum();
        }
    }
    out
}

/// Internal forces `Σ_g w Bᵀ σ_g` (code_aster's `nmfifi`).
pub fn forces(geom: &[[f64; 2]; 4], sigma: &[[f64; 2]; 2]) -> [f64; 8] {
    let mut f = [0.0; 8];
    for (kpg, s) in sigma.iter().enumerate() {
        let (w, b) = jump_operator(geom, kpg);
        for (i, fi) in f.iter_mut().enumerate() {
            *fi += w * (b[0][i] * s[0] + b[1][i] * s[1]);
        }
    }
    f
}

/// Tangent `Σ_g w Bᵀ D_g B` (code_aster's `nmfi2d`), row-major 8×8.
pub fn tangent(geom: &[[f64; 2]; 4], d: &[[[f64; 2]; 2]; 2]) -> [[f64; 8]; 8] {
    let mut k = [[0.0; 8]; 8];
    for (kpg, dg) in d.iter().enumerate() {
        let (w, b) = jump_operator(geom, kpg);
        for i in 0..8 {
            for j in 0..8 {
                let mut v = 0.0;
                for q in 0..2 {
                    for s in 0..2 {
                        v += b[q][i] * dg[q][s] * b[s][j];
                    }
                }
                k[i][j] += w * v;
            }
        }
    }
    k
}

/// One joint cell of a [`JointCells`] source.
#[derive(Clone, Debug, PartialEq)]
pub struct JointCell {
    pub cell: CellId,
    /// Its four nodes, oriented as `ORIE_FISSURE` leaves them.
    pub nodes: [NodeId; 4],
    /// Their coordinates (x, y).
    pub geom: [[f64; 2]; 4],
    pub law: CohesiveLaw,
}

/// The state of one joint cell at its two Gauss points.
#[derive(Clone, Debug, PartialEq)]
pub struct JointPoints {
    /// (`SIGN`, `SITX`) per Gauss point.
    pub traction: [[f64; 2]; 2],
    /// The internal variables per Gauss point (the law's order).
    pub vari: [Vec<f64>; 2],
}

/// Joint cells as a force source (see the module docs).
#[derive(Clone, Debug)]
pub struct JointCells {
    cells: Vec<JointCell>,
    committed: Vec<JointPoints>,
    trial: Vec<JointPoints>,
    /// Element displacements at the start of the increment.
    start: Vec<[f64; 8]>,
    /// The converged states, one entry per converged increment (time,
    /// per cell).
    history: Vec<(f64, Vec<JointPoints>)>,
}

impl JointCells {
    pub fn new(cells: Vec<JointCell>) -> JointCells {
        let zero: Vec<JointPoints> = cells
            .iter()
            .map(|c| JointPoints {
                traction: [[0.0; 2]; 2],
                vari: [vec![0.0; c.law.n_vari()], vec![0.0; c.law.n_vari()]],
            })
            .collect();
        JointCells {
            start: vec![[0.0; 8]; cells.len()],
            committed: zero.clone(),
            trial: zero,
            cells,
            history: Vec::new(),
        }
    }

    pub fn cells(&self) -> &[JointCell] {
        &self.cells
    }

    /// The converged states, one per converged increment.
    pub fn history(&self) -> &[(f64, Vec<JointPoints>)] {
        &self.history
    }

    fn dofs(&self, state: &State, c: &JointCell) -> Result<[usize; 8], FemError> {
        let mut out = [0usize; 8];
        for (a, n) in c.nodes.iter().enumerate() {
            for (k, comp) in [Comp::DX, Comp::DY].into_iter().enumerate() {
                out[2 * a + k] = state.dofs.index(Dof::new(*n, comp)).ok_or_else(|| {
                    FemError::Model(format!(
                        "joint cell {}: node {} has no {:?} in the model",
                        state.mesh.cell_name(c.cell),
                        state
                            .mesh
                            .node_names
                            .get(n.0 as usize)
                            .cloned()
                            .unwrap_or_default(),
                        comp
                    ))
                })?;
            }
        }
        Ok(out)
    }
}

impl ForceSource for JointCells {
    fn name(&self) -> String {
        "joint elements (PLAN_JOINT)".into()
    }

    fn unknowns(&self) -> usize {
        0
    }

    /// Bᵀ D B at each Gauss point, D the cohesive laws' tangent, which is
    /// symmetric for every law of [`crate::cohesive`].
    fn symmetric_tangent(&self) -> bool {
        true
    }

    fn begin_increment(&mut self, state: &State, _own: &mut [f64]) -> Result<(), FemError> {
        for k in 0..self.cells.len() {
            let dofs = self.dofs(state, &self.cells[k])?;
            self.start[k] = dofs.map(|i| state.displacement[i]);
        }
        Ok(())
    }

    fn evaluate(&mut self, state: &State, _own: &[f64]) -> Result<Contribution, FemError> {
        let mut out = Contribution::default();
        for k in 0..self.cells.len() {
            let c = &self.cells[k];
            let dofs = self.dofs(state, c)?;
            let u = dofs.map(|i| state.displacement[i]);
            let du: [f64; 8] = std::array::from_fn(|i| u[i] - self.start[k][i]);
            let jm = jumps(&c.geom, &self.start[k]);
            let dj = jumps(&c.geom, &du);
            let mut traction = [[0.0; 2]; 2];
            let mut d = [[[0.0; 2]; 2]; 2];
            let mut vari: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
            for g in 0..2 {
                let r =
                    c.law
                        .integrate(Phase::Correction, jm[g], dj[g], &self.committed[k].vari[g]);
                traction[g] = r.traction.unwrap_or([0.0; 2]);
                vari[g] = r.vari.unwrap_or_default();
                d[g] = r.tangent;
            }
            let f = forces(&c.geom, &traction);
            let kt = tangent(&c.geom, &d);
            // The whole 8 × 8 block, zeros included: the matrix keeps one
            // pattern while the law's tangent gains and loses terms
            // (damage starting, a closed joint), so the solver's symbolic
            // analysis is made once.
            for i in 0..8 {
                out.forces.push((dofs[i], f[i]));
                for j in 0..8 {
                    out.tangent
                        .push((Unknown::Dof(dofs[i]), Unknown::Dof(dofs[j]), kt[i][j]));
                }
            }
            self.trial[k] = JointPoints { traction, vari };
        }
        Ok(out)
    }

    fn after_iteration(&mut self, _state: &State, _own: &mut [f64]) -> Result<bool, FemError> {
        Ok(true)
    }

    fn converged(&mut self, state: &State, _own: &[f64]) -> Result<(), FemError> {
        self.committed = self.trial.clone();
        self.history.push((state.time, self.committed.clone()));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A joint of length 2 along x, thickness 0.1, counter-clockwise from
    /// its lower face.
    const GEOM: [[f64; 2]; 4] = [[0.0, 0.0], [2.0, 0.0], [2.0, 0.1], [0.0, 0.1]];

    #[test]
    fn a_rigid_motion_has_no_jump_and_an_opening_is_a_positive_normal_jump() {
        let rigid = [0.3, -0.2, 0.3, -0.2, 0.3, -0.2, 0.3, -0.2];
        for j in jumps(&GEOM, &rigid) {
            assert!(j[0].abs() < 1e-15 && j[1].abs() < 1e-15);
        }
        // The upper face moved up by 1e-3 and along x by 2e-3.
        let open = [0.0, 0.0, 0.0, 0.0, 2e-3, 1e-3, 2e-3, 1e-3];
        for j in jumps(&GEOM, &open) {
            assert!((j[0] - 1e-3).abs() < 1e-15, "{j:?}");
            assert!((j[1].abs() - 2e-3).abs() < 1e-15, "{j:?}");
        }
    }

    #[test]
    fn a_uniform_traction_gives_its_resultant_on_each_face() {
        let f = forces(&GEOM, &[[5.0, 0.0], [5.0, 0.0]]);
        // Normal traction 5 on a face of length 2: 10 in all, 5 per node,
        // pulling the faces together (upper face down, lower face up).
        assert!(
            (f[1] + 5.0).abs() < 1e-12 && (f[3] + 5.0).abs() < 1e-12,
            "{f:?}"
        );
        assert!(
            (f[5] - 5.0).abs() < 1e-12 && (f[7] - 5.0).abs() < 1e-12,
            "{f:?}"
        );
    }

    #[test]
    fn the_tangent_is_the_derivative_of_the_forces_for_a_linear_law() {
        let d = [[[3.0, 0.5], [0.5, 2.0]], [[3.0, 0.5], [0.5, 2.0]]];
        let k = tangent(&GEOM, &d);
        let u = [0.1, 0.2, -0.3, 0.05, 0.7, -0.1, 0.2, 0.4];
        let j = jumps(&GEOM, &u);
        let sigma = [0, 1].map(|g| {
            [
                d[g][0][0] * j[g][0] + d[g][0][1] * j[g][1],
                d[g][1][0] * j[g][0] + d[g][1][1] * j[g][1],
            ]
        });
        let f = forces(&GEOM, &sigma);
        for i in 0..8 {
            let ku: f64 = (0..8).map(|c| k[i][c] * u[c]).sum();
            assert!((ku - f[i]).abs() < 1e-12, "{i}: {ku} vs {}", f[i]);
        }
    }
}
