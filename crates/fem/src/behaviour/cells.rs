//! The plastic cells of a model during STAT_NON_LINE: their Gauss-point
//! states, internal forces and tangent.
//!
//! Why corrections: the assembled elastic stiffness K already holds every
//! cell, so elastic cells cost nothing more than today (f_int = K u). A
//! plastic cell adds (∫Bᵀσ − Kₑ uₑ) to f_int and (∫BᵀC B − Kₑ) to the
//! tangent; while it stays elastic both corrections vanish.

use super::vmis::{integrate, PointState, VonMises};
use super::Behaviours;
use crate::element::{
    continuum_gauss, continuum_stiffness, element_dofs, spring_stiffness, GaussData,
};
use crate::error::FemError;
use crate::linalg::Csc;
use crate::material::{Elastic, Hypothesis};
use crate::model::{ElementKind, Model};
use crate::post::CellValues;
use aster_mesh::CellId;
use nalgebra::{DMatrix, DVector};
use std::collections::HashMap;
use std::sync::Arc;

struct PlasticCell {
    cell: CellId,
    hypothesis: Hypothesis,
    elastic: Elastic,
    law: Arc<VonMises>,
    dofs: Vec<usize>,
    gauss: Vec<GaussData>,
    /// The cell's elastic stiffness (its share of the assembled K).
    k_el: DMatrix<f64>,
}

/// The plastic cells, their converged (committed) states and the trial
/// states of the current Newton iterate.
pub(crate) struct PlasticCells {
    cells: Vec<PlasticCell>,
    committed: Vec<Vec<PointState>>,
    trial: Vec<Vec<PointState>>,
    /// The consistent tangents of the trial states.
    tangents: Vec<Vec<[[f64; 6]; 6]>>,
    /// Per cell: whether its tangent differs from its elastic stiffness
    /// (a plastic point at the last update or prediction).
    corrected: Vec<bool>,
    /// Per cell, the position in the free stiffness' values of each of its
    /// (a, b) entries (column-major; `usize::MAX`: an eliminated DOF), with
    /// the number of values they were found for.
    positions: Option<(usize, Vec<Vec<usize>>)>,
}

impl PlasticCells {
    /// `None` when every cell is elastic.
    pub fn new(model: &Model, behaviours: &Behaviours) -> Result<Option<PlasticCells>, FemError> {
        let elements = behaviours.elements(model);
        if elements.is_empty() {
            return Ok(None);
        }
        let mut cells = Vec::with_capacity(elements.len());
        for (k, law) in elements {
            let el = &model.elements()[k];
            let ElementKind::Continuum {
                hypothesis,
                material,
            } = &el.kind
            else {
                continue;
            };
            let gauss = continuum_gauss(model.mesh(), el.cell, *hypothesis).map_err(|m| {
                FemError::Model(format!("cell {} is {m}", model.cell_name(el.cell)))
            })?;
            let k_el = continuum_stiffness(&gauss, material, *hypothesis);
            cells.push(PlasticCell {
                cell: el.cell,
                hypothesis: *hypothesis,
                elastic: *material,
                law,
                dofs: element_dofs(model, el.cell),
                gauss,
                k_el,
            });
        }
        let committed: Vec<Vec<PointState>> = cells
            .iter()
            .map(|c| vec![PointState::default(); c.gauss.len()])
            .collect();
        let corrected = vec![false; cells.len()];
        let tangents = committed
            .iter()
            .map(|c| vec![[[0.0; 6]; 6]; c.len()])
            .collect();
        Ok(Some(PlasticCells {
            cells,
            tangents,
            trial: committed.clone(),
            committed,
            corrected,
            positions: None,
        }))
    }

    /// Integrates the behaviour at every Gauss point for the total
    /// displacement `u` from the committed states, adds the cells'
    /// corrections to `fint` (which holds K u) and keeps their consistent
    /// tangents (assembled only when [`Self::tangent_restricted`] asks).
    pub fn update(&mut self, model: &Model, u: &[f64], fint: &mut [f64]) -> Result<(), FemError> {
        for (c, cell) in self.cells.iter().enumerate() {
            let ue: Vec<f64> = cell.dofs.iter().map(|&i| u[i]).collect();
            // A cell whose points all stay elastic without plastic strain
            // has σ = D ε and tangent D: its corrections vanish (most cells
            // around a local plastic zone).
            let mut virgin = true;
            let n = cell.hypothesis.ncomp();
            for (g, gp) in cell.gauss.iter().enumerate() {
                let mut eps = [0.0; 6];
                for (k, e) in eps.iter_mut().enumerate().take(n) {
                    *e = (0..ue.len()).map(|a| gp.b[(k, a)] * ue[a]).sum();
                }
                let prev = &self.committed[c][g];
                let (state, tangent) = integrate(
                    &cell.law,
                    &cell.elastic,
                    cell.hypothesis,
                    &eps[..n],
                    prev,
                    false,
                )
                .map_err(|e| at_cell(model, cell.cell, g, e))?;
                virgin &= !state.plastic && state.p == 0.0;
                self.trial[c][g] = state;
                self.tangents[c][g] = tangent;
            }
            self.corrected[c] = !virgin;
            if virgin {
                continue;
            }
            // ∫Bᵀσ − Kₑuₑ.
            let mut fe = vec![0.0; ue.len()];
            for (a, f) in fe.iter_mut().enumerate() {
                let row = cell.k_el.row(a);
                *f = -(0..ue.len()).map(|b| row[b] * ue[b]).sum::<f64>();
            }
            for (g, gp) in cell.gauss.iter().enumerate() {
                let sigma = &self.trial[c][g].stress;
                for (a, f) in fe.iter_mut().enumerate() {
                    *f += gp.w * (0..n).map(|k| gp.b[(k, a)] * sigma[k]).sum::<f64>();
                }
            }
            for (a, &i) in cell.dofs.iter().enumerate() {
                fint[i] += fe[a];
            }
        }
        Ok(())
    }

    /// Whether the last update or prediction left every cell on its
    /// elastic stiffness (the tangent is then the elastic K).
    pub fn tangent_is_elastic(&self) -> bool {
        !self.corrected.iter().any(|&c| c)
    }

    /// Sets the tangents to code_aster's prediction matrix at the committed
    /// states (elastic where the last increment was elastic, the continuum
    /// elasto-plastic tangent elsewhere).
    pub fn prediction(&mut self, model: &Model) -> Result<(), FemError> {
        for (c, cell) in self.cells.iter().enumerate() {
            // Elastic where the last increment was elastic: no correction.
            self.corrected[c] = self.committed[c].iter().any(|s| s.plastic);
            if !self.corrected[c] {
                continue;
            }
            for g in 0..cell.gauss.len() {
                let state = self.committed[c][g];
                let eps = [0.0; 6];
                let (_, tangent) = integrate(
                    &cell.law,
                    &cell.elastic,
                    cell.hypothesis,
                    &eps[..cell.hypothesis.ncomp()],
                    &state,
                    true,
                )
                .map_err(|e| at_cell(model, cell.cell, g, e))?;
                self.tangents[c][g] = tangent;
            }
        }
        Ok(())
    }

    /// The tangent on the free DOFs: `kff` (the elastic stiffness of all
    /// cells restricted by `map`, DOF → free index or `usize::MAX`) with the
    /// plastic cells' corrections ∫BᵀC B − Kₑ at the last update or
    /// prediction.
    pub fn tangent_restricted(&mut self, kff: &Csc, map: &[usize]) -> Csc {
        // Where each cell's (a, b) entry sits in kff's values (the pattern
        // is fixed for the analysis): found once, instead of a search per
        // entry at every reassembly.
        let stale = self
            .positions
            .as_ref()
            .is_none_or(|(nnz, _)| *nnz != kff.values.len());
        if stale {
            let at = |i: usize, j: usize| -> usize {
                match (map.get(i), map.get(j)) {
                    (Some(&fi), Some(&fj)) if fi != usize::MAX && fj != usize::MAX => {
                        kff.position(fi, fj).unwrap_or(usize::MAX)
                    }
                    _ => usize::MAX,
                }
            };
            let positions = self
                .cells
                .iter()
                .map(|cell| {
                    let mut p = Vec::with_capacity(cell.dofs.len() * cell.dofs.len());
                    for &j in &cell.dofs {
                        for &i in &cell.dofs {
                            p.push(at(i, j));
                        }
                    }
                    p
                })
                .collect();
            self.positions = Some((kff.values.len(), positions));
        }
        let mut t = kff.clone();
        let Some((_, positions)) = &self.positions else {
            return t;
        };
        for (c, cell) in self.cells.iter().enumerate() {
            if !self.corrected[c] {
                continue;
            }
            let corr = cell_tangent(cell, &self.tangents[c]) - &cell.k_el;
            let n = cell.dofs.len();
            for b in 0..n {
                for a in 0..n {
                    let p = positions[c][b * n + a];
                    if p != usize::MAX {
                        t.values[p] += corr[(a, b)];
                    }
                }
            }
        }
        t
    }

    /// Adds to `out` (one value per DOF of the model) the plastic cells'
    /// tangent corrections (∫BᵀC B − Kₑ at the last update or prediction)
    /// times `du`: with K·du, the tangent times `du` over every DOF,
    /// eliminated ones included (the prediction's coupling of an imposed
    /// increment, code_aster's `nmprta`).
    pub fn add_tangent_correction_times(&self, du: &[f64], out: &mut [f64]) {
        for (c, cell) in self.cells.iter().enumerate() {
            if !self.corrected[c] {
                continue;
            }
            let de: Vec<f64> = cell.dofs.iter().map(|&i| du[i]).collect();
            if de.iter().all(|&v| v == 0.0) {
                continue;
            }
            let corr = cell_tangent(cell, &self.tangents[c]) - &cell.k_el;
            let n = cell.dofs.len();
            for a in 0..n {
                let v: f64 = (0..n).map(|b| corr[(a, b)] * de[b]).sum();
                out[cell.dofs[a]] += v;
            }
        }
    }

    /// The trial states become the converged ones (end of a step).
    pub fn commit(&mut self) {
        self.committed.clone_from(&self.trial);
    }

    /// Replaces the plastic cells' stresses in a SIEF_ELGA field by their
    /// committed states' and returns VARI_ELGA (V1 = p, V2 = indicator) for
    /// them.
    pub fn fields(&self, stress: &mut [CellValues]) -> Vec<CellValues> {
        let at: HashMap<CellId, usize> = stress
            .iter()
            .enumerate()
            .map(|(k, cv)| (cv.cell, k))
            .collect();
        let mut vari = Vec::with_capacity(self.cells.len());
        for (cell, states) in self.cells.iter().zip(&self.committed) {
            let n = cell.hypothesis.ncomp();
            if let Some(&k) = at.get(&cell.cell) {
                stress[k].points = states.iter().map(|s| s.stress[..n].to_vec()).collect();
            }
            vari.push(CellValues {
                cell: cell.cell,
                names: vec!["V1", "V2"],
                points: states.iter().map(|s| s.vari().to_vec()).collect(),
            });
        }
        vari
    }
}

/// ∫BᵀC B of a cell for the tangents C of its points: the points' wCB
/// blocks are stacked so that one product Bᵀ(wCB) does the sum.
fn cell_tangent(cell: &PlasticCell, tangents: &[[[f64; 6]; 6]]) -> DMatrix<f64> {
    let n = cell.hypothesis.ncomp();
    let nd = cell.dofs.len();
    let np = cell.gauss.len();
    let mut bt = DMatrix::<f64>::zeros(nd, n * np);
    let mut wcb = DMatrix::<f64>::zeros(n * np, nd);
    for (g, gp) in cell.gauss.iter().enumerate() {
        let c = &tangents[g];
        for a in 0..nd {
            for k in 0..n {
                bt[(a, g * n + k)] = gp.b[(k, a)];
                wcb[(g * n + k, a)] = gp.w * (0..n).map(|l| c[k][l] * gp.b[(l, a)]).sum::<f64>();
            }
        }
    }
    bt * wcb
}

fn at_cell(model: &Model, cell: CellId, point: usize, e: FemError) -> FemError {
    FemError::Model(format!(
        "cell {}, Gauss point {}: {e}",
        model.cell_name(cell),
        point + 1
    ))
}

/// FORC_NODA from stored Gauss-point stresses (Σ∫Bᵀσ, and the springs'
/// forces from `u`): the nodal forces of a plastic result, whose stresses
/// are not D B u. Cells missing from `stress` count as unstressed.
pub fn forc_noda_from_stress(
    model: &Model,
    u: &[f64],
    stress: &[CellValues],
) -> Result<Vec<f64>, FemError> {
    let at: HashMap<CellId, &CellValues> = stress.iter().map(|cv| (cv.cell, cv)).collect();
    let mut f = vec![0.0; model.dofs().len()];
    for el in model.elements() {
        let dofs = element_dofs(model, el.cell);
        let fe = match &el.kind {
            ElementKind::Continuum { hypothesis, .. } => {
                let Some(cv) = at.get(&el.cell) else {
                    continue;
                };
                let g = continuum_gauss(model.mesh(), el.cell, *hypothesis).map_err(|m| {
                    FemError::Model(format!("cell {} is {m}", model.cell_name(el.cell)))
                })?;
                let mut fe = DVector::zeros(dofs.len());
                for (gp, s) in g.iter().zip(&cv.points) {
                    let sigma = DVector::from_column_slice(&s[..hypothesis.ncomp()]);
                    fe.gemv_tr(gp.w, &gp.b, &sigma, 1.0);
                }
                fe
            }
            ElementKind::Spring { stiffness, frame } => {
                let (k, _) = spring_stiffness(model.mesh(), el.cell, stiffness, *frame);
                let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
                k * ue
            }
            ElementKind::Boundary => continue,
        };
        for (a, &i) in dofs.iter().enumerate() {
            f[i] += fe[a];
        }
    }
    Ok(f)
}
