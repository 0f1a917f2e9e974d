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
    /// Per cell: tangent − elastic stiffness at the last update.
    tangent_corr: Vec<DMatrix<f64>>,
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
        let tangent_corr = cells
            .iter()
            .map(|c| DMatrix::zeros(c.dofs.len(), c.dofs.len()))
            .collect();
        Ok(Some(PlasticCells {
            cells,
            trial: committed.clone(),
            committed,
            tangent_corr,
        }))
    }

    /// Integrates the behaviour at every Gauss point for the total
    /// displacement `u` from the committed states, adds the cells'
    /// corrections to `fint` (which holds K u) and keeps their consistent
    /// tangents.
    pub fn update(&mut self, model: &Model, u: &[f64], fint: &mut [f64]) -> Result<(), FemError> {
        for (c, cell) in self.cells.iter().enumerate() {
            let ue = DVector::from_iterator(cell.dofs.len(), cell.dofs.iter().map(|&i| u[i]));
            let mut fe = -(&cell.k_el * &ue);
            let mut ke = -cell.k_el.clone();
            for (g, gp) in cell.gauss.iter().enumerate() {
                let eps = &gp.b * &ue;
                let (state, tangent) = integrate(
                    &cell.law,
                    &cell.elastic,
                    cell.hypothesis,
                    eps.as_slice(),
                    &self.committed[c][g],
                    false,
                )
                .map_err(|e| at_cell(model, cell.cell, g, e))?;
                add_point(cell, gp, &state, &tangent, &mut fe, &mut ke);
                self.trial[c][g] = state;
            }
            for (a, &i) in cell.dofs.iter().enumerate() {
                fint[i] += fe[a];
            }
            self.tangent_corr[c] = ke;
        }
        Ok(())
    }

    /// Sets the tangent to code_aster's prediction matrix at the committed
    /// states (elastic where the last increment was elastic, the continuum
    /// elasto-plastic tangent elsewhere).
    pub fn prediction(&mut self, model: &Model) -> Result<(), FemError> {
        for (c, cell) in self.cells.iter().enumerate() {
            let n = cell.dofs.len();
            let mut fe = DVector::zeros(n);
            let mut ke = -cell.k_el.clone();
            for (g, gp) in cell.gauss.iter().enumerate() {
                let state = self.committed[c][g];
                let eps = vec![0.0; cell.hypothesis.ncomp()];
                let (_, tangent) = integrate(
                    &cell.law,
                    &cell.elastic,
                    cell.hypothesis,
                    &eps,
                    &state,
                    true,
                )
                .map_err(|e| at_cell(model, cell.cell, g, e))?;
                add_point(cell, gp, &state, &tangent, &mut fe, &mut ke);
            }
            self.tangent_corr[c] = ke;
        }
        Ok(())
    }

    /// The full tangent: `k` (elastic, all cells) with the plastic cells'
    /// corrections.
    pub fn tangent(&self, k: &Csc) -> Csc {
        let mut t = k.clone();
        for (cell, corr) in self.cells.iter().zip(&self.tangent_corr) {
            for (b, &j) in cell.dofs.iter().enumerate() {
                for (a, &i) in cell.dofs.iter().enumerate() {
                    let v = corr[(a, b)];
                    if v != 0. {
                        t.add(i, j, v);
                    }
                }
            }
        }
        t
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

/// Adds one Gauss point's Bᵀσ w to `fe` and BᵀC B w to `ke`.
fn add_point(
    cell: &PlasticCell,
    gp: &GaussData,
    state: &PointState,
    tangent: &[[f64; 6]; 6],
    fe: &mut DVector<f64>,
    ke: &mut DMatrix<f64>,
) {
    let n = cell.hypothesis.ncomp();
    let sigma = DVector::from_column_slice(&state.stress[..n]);
    fe.gemv_tr(gp.w, &gp.b, &sigma, 1.0);
    let c = DMatrix::from_fn(n, n, |i, j| tangent[i][j]);
    let cb = c * &gp.b;
    ke.gemm_tr(gp.w, &gp.b, &cb, 1.0);
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
