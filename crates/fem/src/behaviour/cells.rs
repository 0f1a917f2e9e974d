//! The behaviour cells of a model during STAT_NON_LINE (plastic laws and
//! finite-strain kinematics): their Gauss-point states, internal forces
//! and tangent.
//!
//! Why corrections: the assembled elastic stiffness K already holds every
//! cell, so elastic cells cost nothing more than today (f_int = K u). A
//! behaviour cell adds (f_e(u) − Kₑ uₑ) to f_int and (K_T − Kₑ) to the
//! tangent; while a small-strain plastic cell stays elastic both
//! corrections vanish. A finite-strain cell (`crate::strain`) always
//! carries them: its forces depend on the geometry.

use super::lemaitre::{self, Lemaitre};
use super::thermo::{self, ThermoMaterial};
use super::uniaxial::{Uniaxial, UniaxialState};
use super::vmis::{integrate, PointState, VonMises};
use super::{Behaviours, GaussState, Kinematics, NodalHistory};
use crate::element::{continuum_stiffness, element_dofs, model_gauss, spring_stiffness, GaussData};
use crate::error::FemError;
use crate::linalg::Csc;
use crate::material::{Elastic, Hypothesis};
use crate::mixed_upg::MixedCell;
use crate::model::{ElementKind, Model};
use crate::post::CellValues;
use crate::strain::element::{self as fs, CellSetup, Phase, PointGeom};
use aster_mesh::CellId;
use nalgebra::{DMatrix, DVector};
use std::collections::HashMap;
use std::sync::Arc;

/// A mixed cell's forces, tangent and trial states ([`PlasticCells::mixed`]).
type MixedOut = (Vec<f64>, DMatrix<f64>, Vec<GaussState>);

/// The 72 generalised hourglass stresses of a stabilised HEXA8, converged
/// and trial.
type Hourglass = ([f64; 72], [f64; 72]);

struct PlasticCell {
    cell: CellId,
    hypothesis: Hypothesis,
    elastic: Elastic,
    /// `None`: ELAS (under a finite-strain kinematics).
    law: Option<Arc<VonMises>>,
    /// `LEMAITRE` (small strains), in place of `law`.
    viscous: Option<Arc<Lemaitre>>,
    /// Parameters at each point's temperature ([`thermo`]), small
    /// strains: `law` is then only the kind of its internal variables.
    thermo: Option<Arc<ThermoMaterial>>,
    /// `law` is a Hencky law ([`super::hencky`]): integrated from the
    /// virgin state on the total strain.
    hencky: bool,
    /// The cell's mesh nodes and the shape functions at its points (the
    /// temperature at a point, [`thermo`] cells only).
    nodes: Vec<usize>,
    shape_n: Vec<Vec<f64>>,
    kinematics: Kinematics,
    dofs: Vec<usize>,
    gauss: Vec<GaussData>,
    /// The Gauss points on the initial geometry (finite strains only).
    geoms: Vec<PointGeom>,
    /// The cell's elastic stiffness (its share of the assembled K).
    k_el: DMatrix<f64>,
    /// code_aster's stabilised one-point HEXA8 of `3D_SI`
    /// ([`crate::hexs8`]): its initial node coordinates.
    stabilised: Option<[[f64; 3]; 8]>,
    /// code_aster's mixed incompressible element (`*_INCO_UPG`,
    /// [`crate::mixed_upg`]): its data; `dofs` and `k_el` are then its
    /// displacement, pressure and swelling unknowns and its elastic matrix.
    mixed: Option<Box<MixedCell>>,
    /// A reinforcement grid with a uniaxial law ([`GridCell`]); `dofs` and
    /// `k_el` are then the grid's, `shape_n` its points' shape functions.
    grid: Option<Box<GridCell>>,
}

/// A grid cell's law and points (`te0431`'s `RAPH_MECA`/`FULL_MECA`):
/// the strain row B and weight of each point, the temperature at each
/// point at the start and end of the step (when the law has an α).
struct GridCell {
    law: Arc<Uniaxial>,
    points: Vec<crate::grid::GridPoint>,
    temp_from: Vec<f64>,
    temp_to: Vec<f64>,
}

/// A grid point's state stored as a [`GaussState`]: σ in the stress' and
/// the Cauchy stress' first component, V1 in `p`, V2 in `plastic`.
fn grid_state(s: &GaussState) -> UniaxialState {
    UniaxialState {
        sigma: s.law.stress[0],
        v1: s.law.p,
        plastic: s.law.plastic,
    }
}

fn grid_gauss_state(u: &UniaxialState) -> GaussState {
    let mut g = GaussState::default();
    g.law.stress[0] = u.sigma;
    g.law.p = u.v1;
    g.law.plastic = u.plastic;
    g.cauchy[0] = u.sigma;
    g
}

impl PlasticCell {
    fn setup(&self, dt: f64) -> CellSetup<'_> {
        CellSetup {
            dt,
            hyp: self.hypothesis,
            elastic: &self.elastic,
            law: self.law.as_deref(),
            kinematics: self.kinematics,
            geoms: &self.geoms,
        }
    }

    /// Whether the cell computes its own forces and tangent (a
    /// finite-strain kinematics, or the stabilised HEXA8).
    fn finite(&self) -> bool {
        self.kinematics != Kinematics::Small
            || self.stabilised.is_some()
            || self.mixed.is_some()
            || self.grid.is_some()
    }
}

/// The converged state of the behaviour cells of an analysis
/// ([`PlasticCells::snapshot`]): what continuing it needs beyond the
/// displacement (stresses, internal variables, finite-strain and
/// hourglass states, the tangents the next prediction uses).
#[derive(Clone, Debug, PartialEq)]
pub struct BehaviourState {
    cells: Vec<CellId>,
    committed: Vec<Vec<GaussState>>,
    u_committed: Vec<Vec<f64>>,
    tangents: Vec<Vec<[[f64; 6]; 6]>>,
    finite_k: Vec<Option<DMatrix<f64>>>,
    corrected: Vec<bool>,
    hourglass: Vec<Option<[f64; 72]>>,
    thermal_start: Option<Vec<Vec<f64>>>,
}

/// The behaviour cells, their converged (committed) states and the trial
/// states of the current Newton iterate.
pub(crate) struct PlasticCells {
    cells: Vec<PlasticCell>,
    committed: Vec<Vec<GaussState>>,
    trial: Vec<Vec<GaussState>>,
    /// The element displacements of the converged state and of the last
    /// update (finite strains only).
    u_committed: Vec<Vec<f64>>,
    u_trial: Vec<Vec<f64>>,
    /// The consistent tangents of the trial states (small strains).
    tangents: Vec<Vec<[[f64; 6]; 6]>>,
    /// K_T − Kₑ of the finite-strain cells at the last update or
    /// prediction.
    finite_k: Vec<Option<DMatrix<f64>>>,
    /// The generalised hourglass stresses (`FSTAB`) of the stabilised
    /// HEXA8 cells, converged and trial (empty for the other cells).
    hourglass: Vec<Option<Box<Hourglass>>>,
    /// `MATR_RIGI_SYME='OUI'`: the finite-strain tangents are symmetrised.
    symmetrize: bool,
    /// Per cell: whether its tangent differs from its elastic stiffness
    /// (a plastic point at the last update or prediction).
    corrected: Vec<bool>,
    /// Per cell, the position in the free stiffness' values of each of its
    /// (a, b) entries (column-major; `usize::MAX`: an eliminated DOF), with
    /// the number of values they were found for.
    positions: Option<(usize, Vec<Vec<usize>>)>,
    /// The duration of the current step (the viscous laws').
    dt: f64,
    /// The nodal temperatures of the [`thermo`] cells, the temperature at
    /// each of their points at the end of the current step, and the
    /// thermal strain at each point at the first instant of the analysis
    /// (`None` until the first step sets it).
    temperature: Option<Arc<NodalHistory>>,
    temps: Vec<Vec<f64>>,
    thermal_start: Option<Vec<Vec<f64>>>,
}

impl PlasticCells {
    /// `None` when every cell is elastic in small strains.
    pub fn new(
        model: &Model,
        behaviours: &Behaviours,
        symmetrize: bool,
    ) -> Result<Option<PlasticCells>, FemError> {
        let elements = behaviours.elements(model);
        if elements.is_empty() {
            return Ok(None);
        }
        let mut cells = Vec::with_capacity(elements.len());
        for (k, behaviour) in elements {
            let el = &model.elements()[k];
            if let (ElementKind::Grid { material, section }, Some(law)) =
                (&el.kind, behaviour.uniaxial.as_ref())
            {
                cells.push(grid_cell(model, el.cell, material, section, law.clone())?);
                continue;
            }
            let ElementKind::Continuum {
                hypothesis,
                material,
            } = &el.kind
            else {
                continue;
            };
            if !material.is_isotropic() {
                return Err(FemError::Model(format!(
                    "cell {}: an orthotropic material (ELAS_ORTH) is elastic in small strains only; its behaviours and large-strain kinematics are the isotropic law's here",
                    model.cell_name(el.cell)
                )));
            }
            let gauss = model_gauss(model, el.cell, *hypothesis).map_err(|m| {
                FemError::Model(format!("cell {} is {m}", model.cell_name(el.cell)))
            })?;
            let k_el = continuum_stiffness(&gauss, material, *hypothesis);
            if behaviour.kinematics == Kinematics::SimoMiehe {
                if behaviour.law.is_none() {
                    return Err(FemError::Model(format!(
                        "cell {}: DEFORMATION='SIMO_MIEHE' needs a plastic law (VMIS_ISOT_LINE, VMIS_ISOT_TRAC), not ELAS",
                        model.cell_name(el.cell)
                    )));
                }
                if *hypothesis == Hypothesis::PlaneStress {
                    return Err(FemError::Model(format!(
                        "cell {}: DEFORMATION='SIMO_MIEHE' is not available in plane stress (C_PLAN), as in code_aster",
                        model.cell_name(el.cell)
                    )));
                }
            }
            let geoms = if behaviour.kinematics == Kinematics::Small {
                Vec::new()
            } else {
                fs::point_geoms(&gauss, *hypothesis)
            };
            let mut dofs = element_dofs(model, el.cell);
            let mut k_el = k_el;
            let mixed = if model.is_mixed(el.cell) {
                let refuse = |what: &str| {
                    Err(FemError::Model(format!(
                        "cell {}: {what} on a mixed incompressible element (_INCO_UPG) is not implemented (small strains with ELAS and the VMIS_ISOT_*/VMIS_CINE_LINE laws are)",
                        model.cell_name(el.cell)
                    )))
                };
                if behaviour.kinematics != Kinematics::Small {
                    return refuse("a large-strain kinematics (DEFORMATION other than PETIT)");
                }
                if behaviour.viscous.is_some() {
                    return refuse("LEMAITRE");
                }
                if behaviour.hencky {
                    return refuse("ELAS_VMIS_*");
                }
                let m = MixedCell::new(model, el.cell, *hypothesis).map_err(|m| {
                    FemError::Model(format!("cell {} is {m}", model.cell_name(el.cell)))
                })?;
                k_el = m.elastic_matrix(material, false);
                dofs.clone_from(&m.dofs);
                Some(Box::new(m))
            } else {
                None
            };
            let stabilised = if model.is_stabilised(el.cell) {
                stabilised_setup(model, el.cell, &behaviour)?
            } else {
                None
            };
            let (nodes, shape_n) = if behaviour.thermo.is_some() {
                if model.is_stabilised(el.cell) || model.is_reduced(el.cell) {
                    return Err(FemError::Model(format!(
                        "cell {}: a temperature-dependent material on an under-integrated cell is not implemented",
                        model.cell_name(el.cell)
                    )));
                }
                let ty = model.mesh().cell(el.cell).ty;
                let nodes = model
                    .mesh()
                    .cell(el.cell)
                    .nodes
                    .iter()
                    .map(|n| n.0 as usize)
                    .collect();
                // (A mixed cell's points are its family's: the model's
                // stiffness scheme of the cell.)
                let shape_n = model
                    .stiffness_scheme(el.cell)
                    .iter()
                    .map(|gp| crate::shape::shape(ty, gp.xi).n.to_vec())
                    .collect();
                (nodes, shape_n)
            } else {
                (Vec::new(), Vec::new())
            };
            cells.push(PlasticCell {
                cell: el.cell,
                hypothesis: *hypothesis,
                elastic: *material,
                law: behaviour.law,
                viscous: behaviour.viscous,
                hencky: behaviour.hencky,
                thermo: behaviour.thermo,
                nodes,
                shape_n,
                kinematics: behaviour.kinematics,
                dofs,
                gauss,
                geoms,
                k_el,
                stabilised,
                mixed,
                grid: None,
            });
        }
        let committed: Vec<Vec<GaussState>> = cells
            .iter()
            .map(|c| {
                let n = if c.stabilised.is_some() {
                    1
                } else if let Some(g) = &c.grid {
                    g.points.len()
                } else {
                    c.gauss.len()
                };
                vec![GaussState::default(); n]
            })
            .collect();
        let hourglass = cells
            .iter()
            .map(|c| c.stabilised.map(|_| Box::new(([0.0; 72], [0.0; 72]))))
            .collect();
        let corrected = vec![false; cells.len()];
        let cells_len = cells.len();
        let heated_grid = |c: &PlasticCell| c.grid.as_ref().is_some_and(|g| g.law.alpha != 0.0);
        if cells.iter().any(|c| c.thermo.is_some() || heated_grid(c))
            && behaviours.temperature().is_none()
        {
            return Err(FemError::Model(
                "temperature-dependent materials without a temperature history".into(),
            ));
        }
        let tangents = committed
            .iter()
            .map(|c| vec![[[0.0; 6]; 6]; c.len()])
            .collect();
        let u_committed: Vec<Vec<f64>> = cells
            .iter()
            .map(|c| {
                if c.finite() {
                    vec![0.0; c.dofs.len()]
                } else {
                    Vec::new()
                }
            })
            .collect();
        Ok(Some(PlasticCells {
            finite_k: vec![None; cells.len()],
            cells,
            tangents,
            trial: committed.clone(),
            committed,
            u_trial: u_committed.clone(),
            u_committed,
            corrected,
            positions: None,
            hourglass,
            symmetrize,
            dt: 0.0,
            temps: vec![Vec::new(); cells_len],
            temperature: behaviours.temperature().cloned(),
            thermal_start: None,
        }))
    }

    /// The converged state of every cell (to continue an analysis from
    /// it: [`restore`](Self::restore)).
    pub fn snapshot(&self) -> BehaviourState {
        BehaviourState {
            cells: self.cells.iter().map(|c| c.cell).collect(),
            committed: self.committed.clone(),
            u_committed: self.u_committed.clone(),
            tangents: self.tangents.clone(),
            finite_k: self.finite_k.clone(),
            corrected: self.corrected.clone(),
            thermal_start: self.thermal_start.clone(),
            hourglass: self
                .hourglass
                .iter()
                .map(|h| h.as_ref().map(|h| h.0))
                .collect(),
        }
    }

    /// Starts from a converged state taken by [`snapshot`](Self::snapshot)
    /// on the same cells and behaviours.
    pub fn restore(&mut self, s: &BehaviourState) -> Result<(), FemError> {
        let same = s.cells.len() == self.cells.len()
            && s.cells.iter().zip(&self.cells).all(|(a, c)| *a == c.cell)
            && s.committed
                .iter()
                .zip(&self.committed)
                .all(|(a, b)| a.len() == b.len())
            && s.u_committed
                .iter()
                .zip(&self.u_committed)
                .all(|(a, b)| a.len() == b.len())
            && s.hourglass
                .iter()
                .zip(&self.hourglass)
                .all(|(a, b)| a.is_some() == b.is_some());
        if !same {
            return Err(FemError::Model(
                "the initial state's behaviour cells are not this analysis' (another model or other COMPORTEMENT groups)".into(),
            ));
        }
        self.committed.clone_from(&s.committed);
        self.trial.clone_from(&s.committed);
        self.u_committed.clone_from(&s.u_committed);
        self.u_trial.clone_from(&s.u_committed);
        self.tangents.clone_from(&s.tangents);
        self.finite_k.clone_from(&s.finite_k);
        self.corrected.clone_from(&s.corrected);
        if s.thermal_start.is_some() {
            self.thermal_start.clone_from(&s.thermal_start);
        }
        for (h, q) in self.hourglass.iter_mut().zip(&s.hourglass) {
            if let (Some(h), Some(q)) = (h.as_mut(), q) {
                h.0 = *q;
                h.1 = *q;
            }
        }
        Ok(())
    }

    /// The duration of the step about to be solved (from the last
    /// converged instant to the target; a cut step's own).
    pub fn set_step(&mut self, dt: f64) {
        self.dt = dt;
    }

    /// The instants of the step about to be solved, for the
    /// temperature-dependent cells: the temperature at each of their
    /// points at `target` and, at the first step of the analysis (not
    /// continued from a state), the thermal strain at `from`, which the
    /// thermal strain is counted from ([`thermo`]).
    pub fn set_instants(&mut self, from: f64, target: f64) -> Result<(), FemError> {
        let Some(history) = self.temperature.clone() else {
            return Ok(());
        };
        let at_points = |cell: &PlasticCell, nodal: &[f64]| -> Vec<f64> {
            cell.shape_n
                .iter()
                .map(|n| n.iter().zip(&cell.nodes).map(|(w, &k)| w * nodal[k]).sum())
                .collect()
        };
        if self.thermal_start.is_none() {
            let nodal = history.at(from)?;
            let mut start = Vec::with_capacity(self.cells.len());
            for cell in &self.cells {
                let mut v = Vec::new();
                if let Some(m) = &cell.thermo {
                    for t in at_points(cell, &nodal) {
                        v.push(m.thermal_strain(t)?);
                    }
                }
                start.push(v);
            }
            self.thermal_start = Some(start);
        }
        if self
            .cells
            .iter()
            .any(|c| c.grid.as_ref().is_some_and(|g| g.law.alpha != 0.0))
        {
            let before = history.at(from)?;
            let after = history.at(target)?;
            for cell in self.cells.iter_mut() {
                let (t0, t1) = (at_points(cell, &before), at_points(cell, &after));
                let Some(g) = cell.grid.as_mut().filter(|g| g.law.alpha != 0.0) else {
                    continue;
                };
                if t0.iter().chain(&t1).any(|t| t.is_nan()) {
                    return Err(FemError::Model(format!(
                        "the temperature field has no value at a node of grid cell {}",
                        cell.cell.0
                    )));
                }
                g.temp_from = t0;
                g.temp_to = t1;
            }
        }
        let nodal = history.at(target)?;
        for (c, cell) in self.cells.iter().enumerate() {
            if cell.thermo.is_some() {
                self.temps[c] = at_points(cell, &nodal);
                if self.temps[c].iter().any(|t| t.is_nan()) {
                    return Err(FemError::Model(format!(
                        "the temperature field has no value at a node of cell {}",
                        cell.cell.0
                    )));
                }
            }
        }
        Ok(())
    }

    /// Whether some cell has a finite-strain kinematics.
    pub fn has_finite_strains(&self) -> bool {
        self.cells.iter().any(|c| c.finite())
    }

    /// Whether the tangent is symmetric (SIMO_MIEHE's is not, unless
    /// `MATR_RIGI_SYME='OUI'` symmetrises it).
    pub fn symmetric_tangent(&self) -> bool {
        self.symmetrize
            || !self
                .cells
                .iter()
                .any(|c| c.kinematics == Kinematics::SimoMiehe)
    }

    /// Stores K_T − Kₑ of a finite-strain cell.
    fn set_finite_tangent(&mut self, c: usize, k: DMatrix<f64>) {
        let mut corr = k - &self.cells[c].k_el;
        if self.symmetrize {
            corr = (&corr + corr.transpose()) * 0.5;
        }
        self.finite_k[c] = Some(corr);
        self.corrected[c] = true;
    }

    /// Integrates the behaviour at every Gauss point for the total
    /// displacement `u` from the committed states, adds the cells'
    /// corrections to `fint` (which holds K u) and keeps their consistent
    /// tangents (assembled only when [`Self::tangent_restricted`] asks).
    pub fn update(&mut self, model: &Model, u: &[f64], fint: &mut [f64]) -> Result<(), FemError> {
        for c in 0..self.cells.len() {
            if !self.cells[c].finite() {
                continue;
            }
            let cell = &self.cells[c];
            let ue: Vec<f64> = cell.dofs.iter().map(|&i| u[i]).collect();
            if cell.grid.is_some() {
                let (f, k, states) = self
                    .grid(c, &ue, None)
                    .map_err(|e| at_cell_finite(model, self.cells[c].cell, e))?;
                let cell = &self.cells[c];
                let ku = &cell.k_el * DVector::from_column_slice(&ue);
                for (a, &i) in cell.dofs.iter().enumerate() {
                    fint[i] += f[a] - ku[a];
                }
                self.trial[c] = states;
                self.u_trial[c] = ue;
                self.set_finite_tangent(c, k);
                continue;
            }
            if cell.mixed.is_some() {
                let (f, k, states) = self
                    .mixed(c, &ue, false)
                    .map_err(|e| at_cell_finite(model, self.cells[c].cell, e))?;
                let cell = &self.cells[c];
                let ku = &cell.k_el * DVector::from_column_slice(&ue);
                for (a, &i) in cell.dofs.iter().enumerate() {
                    fint[i] += f[a] - ku[a];
                }
                self.trial[c] = states;
                self.u_trial[c] = ue;
                self.set_finite_tangent(c, k);
                continue;
            }
            if cell.stabilised.is_some() {
                let (f, k) = self
                    .stabilised(c, &ue, Phase::Correction)
                    .map_err(|e| at_cell_finite(model, self.cells[c].cell, e))?;
                let cell = &self.cells[c];
                let ku = &cell.k_el * DVector::from_column_slice(&ue);
                for (a, &i) in cell.dofs.iter().enumerate() {
                    fint[i] += f[a] - ku[a];
                }
                self.u_trial[c] = ue;
                self.set_finite_tangent(c, k);
                continue;
            }
            let out = fs::compute(
                &cell.setup(self.dt),
                &self.u_committed[c],
                &ue,
                &self.committed[c],
                Phase::Correction,
            )
            .map_err(|e| at_cell_finite(model, cell.cell, e))?;
            let ku = &cell.k_el * DVector::from_column_slice(&ue);
            for (a, &i) in cell.dofs.iter().enumerate() {
                fint[i] += out.f[a] - ku[a];
            }
            self.trial[c] = out.states;
            self.u_trial[c] = ue;
            self.set_finite_tangent(c, out.k);
        }
        self.update_small_strain(model, u, fint)
    }

    /// The small-strain cells' part of [`Self::update`]: each cell's
    /// points integrated from its committed states (trial states, tangents,
    /// whether it is corrected), on two threads when the cells hold many
    /// Gauss points; the corrections ∫Bᵀσ − Kₑuₑ are then added to `fint`
    /// in cell order on this thread, so the sums are those of one thread.
    fn update_small_strain(
        &mut self,
        model: &Model,
        u: &[f64],
        fint: &mut [f64],
    ) -> Result<(), FemError> {
        let points: usize = self
            .cells
            .iter()
            .filter(|c| {
                !c.finite() && (c.law.is_some() || c.viscous.is_some() || c.thermo.is_some())
            })
            .map(|c| c.gauss.len())
            .sum();
        let n = self.cells.len();
        let dt = self.dt;
        let cells = &self.cells;
        let committed = &self.committed;
        let thermal = Thermal {
            temps: &self.temps,
            start: self.thermal_start.as_deref(),
        };
        let corrections = if points >= PARALLEL_POINTS && n >= 2 {
            let mid = n / 2;
            let (t1, t2) = self.trial.split_at_mut(mid);
            let (k1, k2) = self.tangents.split_at_mut(mid);
            let (c1, c2) = self.corrected.split_at_mut(mid);
            let (r1, r2) = crate::parallel::join(
                || integrate_small_cells(model, cells, committed, &thermal, 0, u, dt, t1, k1, c1),
                || integrate_small_cells(model, cells, committed, &thermal, mid, u, dt, t2, k2, c2),
            );
            let mut r1 = r1?;
            r1.extend(r2?);
            r1
        } else {
            integrate_small_cells(
                model,
                cells,
                committed,
                &thermal,
                0,
                u,
                dt,
                &mut self.trial,
                &mut self.tangents,
                &mut self.corrected,
            )?
        };
        for (c, fe) in corrections {
            for (a, &i) in self.cells[c].dofs.iter().enumerate() {
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
    /// elasto-plastic tangent elsewhere; `elastic`: the elastic material
    /// tangent, RIGI_MECA_ELAS). Finite-strain cells get their tangent at
    /// the converged geometry and stresses (geometric stiffness included).
    pub fn prediction(&mut self, model: &Model, elastic: bool) -> Result<(), FemError> {
        for c in 0..self.cells.len() {
            if !self.cells[c].finite() {
                continue;
            }
            let cell = &self.cells[c];
            if cell.grid.is_some() {
                let ue = self.u_committed[c].clone();
                let (_, k, _) = self
                    .grid(c, &ue, Some(elastic))
                    .map_err(|e| at_cell_finite(model, self.cells[c].cell, e))?;
                self.set_finite_tangent(c, k);
                continue;
            }
            if cell.mixed.is_some() {
                let ue = self.u_committed[c].clone();
                let (_, k, _) = self
                    .mixed(c, &ue, true)
                    .map_err(|e| at_cell_finite(model, self.cells[c].cell, e))?;
                if elastic {
                    let k_el = self.cells[c].k_el.clone();
                    self.set_finite_tangent(c, k_el);
                } else {
                    self.set_finite_tangent(c, k);
                }
                continue;
            }
            if cell.stabilised.is_some() {
                let ue = self.u_committed[c].clone();
                let (_, k) = self
                    .stabilised(c, &ue, Phase::Prediction { elastic })
                    .map_err(|e| at_cell_finite(model, self.cells[c].cell, e))?;
                self.set_finite_tangent(c, k);
                continue;
            }
            let out = fs::compute(
                &cell.setup(self.dt),
                &self.u_committed[c],
                &self.u_committed[c],
                &self.committed[c],
                Phase::Prediction { elastic },
            )
            .map_err(|e| at_cell_finite(model, cell.cell, e))?;
            self.set_finite_tangent(c, out.k);
        }
        for (c, cell) in self.cells.iter().enumerate() {
            if cell.finite() {
                continue;
            }
            if let Some(visc) = cell.viscous.as_deref() {
                // The viscous flow goes on over the step: code_aster's
                // RIGI_MECA_TANG at a zero increment (ELASTIQUE: the
                // elastic stiffness).
                self.corrected[c] = !elastic;
                if elastic {
                    continue;
                }
                for g in 0..cell.gauss.len() {
                    let state = self.committed[c][g].law;
                    let eps = [0.0; 6];
                    let (_, tangent) = lemaitre::integrate(
                        visc,
                        &cell.elastic,
                        cell.hypothesis,
                        &eps[..cell.hypothesis.ncomp()],
                        &state,
                        self.dt,
                        true,
                    )
                    .map_err(|e| at_cell(model, cell.cell, g, e))?;
                    self.tangents[c][g] = tangent;
                }
                continue;
            }
            if let Some(mat) = cell.thermo.as_deref() {
                // The tangent at the committed state with the parameters
                // at the step's end (nmisot's RIGI_MECA_TANG reads '+').
                self.corrected[c] = true;
                let thermal = Thermal {
                    temps: &self.temps,
                    start: self.thermal_start.as_deref(),
                };
                for g in 0..cell.gauss.len() {
                    let state = self.committed[c][g].law;
                    let (temp, th0) = thermal.at(c, g)?;
                    let eps = [0.0; 6];
                    let prev = if elastic {
                        PointState {
                            plastic: false,
                            ..state
                        }
                    } else {
                        state
                    };
                    let (_, tangent) = thermo::integrate_point(
                        mat,
                        cell.hypothesis,
                        &eps[..cell.hypothesis.ncomp()],
                        temp,
                        th0,
                        &prev,
                        true,
                    )
                    .map_err(|e| at_cell(model, cell.cell, g, e))?;
                    self.tangents[c][g] = tangent;
                }
                continue;
            }
            let Some(law) = cell.law.as_deref() else {
                continue;
            };
            if cell.hencky {
                // lcelnl's RIGI_MECA_TANG: the tangent at the converged
                // strain.
                self.corrected[c] = true;
                let ue = &self.u_committed[c];
                let n = cell.hypothesis.ncomp();
                for (g, gp) in cell.gauss.iter().enumerate() {
                    let eps = gp.strain(ue, n);
                    let el = if elastic {
                        // PREDICTION='ELASTIQUE': the elastic matrix.
                        &[0.0; 6][..n]
                    } else {
                        &eps[..n]
                    };
                    let (_, tangent) =
                        super::hencky::integrate(law, &cell.elastic, cell.hypothesis, el)
                            .map_err(|e| at_cell(model, cell.cell, g, e))?;
                    self.tangents[c][g] = tangent;
                }
                continue;
            }
            // Elastic where the last increment was elastic: no correction
            // (unless the law has its own Young's modulus).
            let own_modulus = law.elastic(&cell.elastic) != cell.elastic;
            self.corrected[c] =
                !elastic && (own_modulus || self.committed[c].iter().any(|s| s.law.plastic));
            if !self.corrected[c] {
                continue;
            }
            for g in 0..cell.gauss.len() {
                let state = self.committed[c][g].law;
                let eps = [0.0; 6];
                let (_, tangent) = integrate(
                    law,
                    &cell.elastic,
                    cell.hypothesis,
                    &eps[..cell.hypothesis.ncomp()],
                    &state,
                    true,
                    self.dt,
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
            let corr = self.correction(c);
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

    /// Cell `c`'s tangent correction K_T − Kₑ: the stored one of a
    /// finite-strain cell (its tangent at the last update or prediction,
    /// [`Self::set_finite_tangent`]), else ∫BᵀC B − Kₑ from its Gauss
    /// points' tangents.
    fn correction(&self, c: usize) -> DMatrix<f64> {
        let cell = &self.cells[c];
        match &self.finite_k[c] {
            Some(k) if cell.finite() => k.clone(),
            _ => cell_tangent(cell, &self.tangents[c]) - &cell.k_el,
        }
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
            let corr = self.correction(c);
            let n = cell.dofs.len();
            for a in 0..n {
                let v: f64 = (0..n).map(|b| corr[(a, b)] * de[b]).sum();
                out[cell.dofs[a]] += v;
            }
        }
    }

    /// The trial states become the converged ones (end of a step).
    pub fn commit(&mut self) {
        for hg in self.hourglass.iter_mut().flatten() {
            hg.0 = hg.1;
        }
        self.committed.clone_from(&self.trial);
        self.u_committed.clone_from(&self.u_trial);
    }

    /// Forces, tangent and trial states of grid cell `c` at its element
    /// displacement `ue` (`te0431` → `nmco1d`): at each point the strain
    /// increment B (uₑ − uₑ⁻), less the thermal one α (T⁺ − T⁻), integrated
    /// from the committed state; `prediction` (`Some(elastic)`): the
    /// tangent at the committed state (RIGI_MECA_TANG, RIGI_MECA_ELAS),
    /// the forces and states then unused.
    fn grid(&self, c: usize, ue: &[f64], prediction: Option<bool>) -> Result<MixedOut, FemError> {
        let cell = &self.cells[c];
        let Some(g) = cell.grid.as_deref() else {
            return Err(FemError::Model("not a grid cell".into()));
        };
        let nd = cell.dofs.len();
        let mut f = vec![0.0; nd];
        let mut k = DMatrix::zeros(nd, nd);
        let mut states = Vec::with_capacity(g.points.len());
        let u0 = &self.u_committed[c];
        for (p, pt) in g.points.iter().enumerate() {
            let prev = grid_state(&self.committed[c][p]);
            let (state, rig) = match prediction {
                Some(elastic) => (prev, g.law.prediction_tangent(&prev, elastic)),
                None => {
                    let deps: f64 =
                        pt.b.iter()
                            .zip(ue.iter().zip(u0))
                            .map(|(b, (u, u0))| b * (u - u0))
                            .sum();
                    let depsth = if g.law.alpha != 0.0 {
                        g.law.alpha * (g.temp_to[p] - g.temp_from[p])
                    } else {
                        0.0
                    };
                    g.law
                        .integrate(&prev, deps - depsth, false)
                        .map_err(|e| FemError::Model(format!("at Gauss point {}: {e}", p + 1)))?
                }
            };
            for a in 0..nd {
                if pt.b[a] == 0.0 {
                    continue;
                }
                f[a] += pt.b[a] * state.sigma * pt.w;
                let r = pt.b[a] * rig * pt.w;
                for b in 0..nd {
                    k[(a, b)] += r * pt.b[b];
                }
            }
            states.push(grid_gauss_state(&state));
        }
        Ok((f, k, states))
    }

    /// Forces, tangent and trial states of mixed cell `c` at its unknowns
    /// `ue` (`nifipd`): its law integrated at each point from the
    /// committed state on the strain whose volumetric part is the
    /// swelling's; in `prediction`, the tangent at the committed state
    /// (RIGI_MECA_TANG), the forces and states then unused.
    fn mixed(&self, c: usize, ue: &[f64], prediction: bool) -> Result<MixedOut, FemError> {
        let cell = &self.cells[c];
        let Some(m) = cell.mixed.as_deref() else {
            return Err(FemError::Model("not a mixed cell".into()));
        };
        let n = cell.hypothesis.ncomp();
        let nd = cell.dofs.len();
        let mut f = vec![0.0; nd];
        let mut k = DMatrix::zeros(nd, nd);
        let mut states = Vec::with_capacity(m.gauss.len());
        for g in 0..m.gauss.len() {
            let prev = &self.committed[c][g].law;
            let eps = m.strain(g, ue);
            let thermo = match cell.thermo.as_deref() {
                Some(mat) => {
                    let thermal = Thermal {
                        temps: &self.temps,
                        start: self.thermal_start.as_deref(),
                    };
                    Some((mat, thermal.at(c, g)?))
                }
                None => None,
            };
            let (state, tangent) = match (thermo, cell.law.as_deref()) {
                (Some((mat, (temp, th0))), _) => thermo::integrate_point(
                    mat,
                    cell.hypothesis,
                    &eps[..n],
                    temp,
                    th0,
                    prev,
                    prediction,
                )
                .map_err(|e| FemError::Model(format!("at Gauss point {}: {e}", g + 1)))?,
                (None, Some(law)) => integrate(
                    law,
                    &cell.elastic,
                    cell.hypothesis,
                    &eps[..n],
                    prev,
                    prediction,
                    self.dt,
                )
                .map_err(|e| FemError::Model(format!("at Gauss point {}: {e}", g + 1)))?,
                (None, None) => {
                    // ELAS: σ = D ε̃.
                    let d = cell.elastic.hooke(cell.hypothesis);
                    let mut c6 = [[0.0; 6]; 6];
                    let mut stress = [0.0; 6];
                    for i in 0..n {
                        for j in 0..n {
                            c6[i][j] = d[(i, j)];
                            stress[i] += d[(i, j)] * eps[j];
                        }
                    }
                    (PointState { stress, ..*prev }, c6)
                }
            };
            m.add_tangent(g, &tangent, &mut k);
            if !prediction {
                m.add_forces(g, &state.stress, ue, &mut f);
            }
            let (cauchy, sip) = m.stress(g, &state.stress, ue);
            let mut extra = [0.0; 6];
            extra[0] = sip;
            states.push(GaussState {
                law: state,
                cauchy,
                extra,
            });
        }
        Ok((f, k, states))
    }

    /// Forces (empty in prediction) and tangent of stabilised HEXA8 cell
    /// `c` at the element displacement `ue` (`nmas3d`); in correction, its
    /// trial state and hourglass stresses.
    fn stabilised(
        &mut self,
        c: usize,
        ue: &[f64],
        phase: Phase,
    ) -> Result<(Vec<f64>, DMatrix<f64>), FemError> {
        use crate::hexs8::{to_sqrt2, Geometry, Projection};
        let cell = &self.cells[c];
        let Some(x0) = cell.stabilised else {
            return Err(FemError::Model("not a stabilised HEXA8 cell".into()));
        };
        let mut geom = x0;
        if cell.kinematics == Kinematics::SmallUpdated {
            for (a, x) in geom.iter_mut().enumerate() {
                for (i, xi) in x.iter_mut().enumerate() {
                    *xi += ue[3 * a + i];
                }
            }
        }
        let g = Geometry::new(&geom)?;
        let proj = if cell.law.is_none() {
            Projection::Asqbi
        } else {
            Projection::Ads
        };
        let nu = cell.elastic.nu;
        let prev = self.committed[c][0];
        let du: Vec<f64> = ue
            .iter()
            .zip(&self.u_committed[c])
            .map(|(u, u0)| u - u0)
            .collect();
        let mut eps = prev.extra;
        if phase == Phase::Correction {
            let de = g.strain(&du);
            for k in 0..6 {
                eps[k] += de[k];
            }
        }
        let setup = fs::CellSetup {
            hyp: Hypothesis::Solid3D,
            elastic: &cell.elastic,
            law: cell.law.as_deref(),
            kinematics: cell.kinematics,
            geoms: &[],
            dt: self.dt,
        };
        let (law, tangent) = fs::behave(&setup, &eps, &prev.law, phase)?;
        let d = to_sqrt2(&tangent);
        let k = DMatrix::from_row_slice(24, 24, &g.stiffness(&d, proj, nu));
        if phase != Phase::Correction {
            return Ok((Vec::new(), k));
        }
        let Some(hg) = self.hourglass[c].as_mut() else {
            return Err(FemError::Model("a stabilised cell without FSTAB".into()));
        };
        let q = g.hourglass_stresses(&d, proj, nu, &du, &hg.0);
        let f = g.forces(&law.stress, &q, proj, nu);
        hg.1 = q;
        self.trial[c][0] = GaussState {
            law,
            cauchy: law.stress,
            extra: eps,
        };
        Ok((f, k))
    }

    /// Replaces the behaviour cells' stresses in a SIEF_ELGA field by their
    /// committed states' (Cauchy stresses) and returns their VARI_ELGA in
    /// code_aster's order: V1 = p, V2 = plasticity indicator for the von
    /// Mises laws; then, with GDEF_LOG, the six components of T (Mandel:
    /// TXX TYY TZZ √2·TXY √2·TXZ √2·TYZ; ELAS has V1 = 0 first) and, with
    /// SIMO_MIEHE, the six of the elastic strain (I − bₑ)/2.
    pub fn fields(&self, stress: &mut [CellValues]) -> Vec<CellValues> {
        let at: HashMap<CellId, usize> = stress
            .iter()
            .enumerate()
            .map(|(k, cv)| (cv.cell, k))
            .collect();
        let mut vari = Vec::with_capacity(self.cells.len());
        for (cell, states) in self.cells.iter().zip(&self.committed) {
            if cell.grid.is_some() {
                // SIEF_ELGA's SIXX along the bars, VARI V1 … V4.
                if let Some(&k) = at.get(&cell.cell) {
                    stress[k].points = states.iter().map(|s| vec![s.cauchy[0]]).collect();
                }
                vari.push(CellValues {
                    cell: cell.cell,
                    names: VARI_NAMES[..4].to_vec(),
                    points: states
                        .iter()
                        .map(|s| grid_state(s).vari().to_vec())
                        .collect(),
                });
                continue;
            }
            let n = cell.hypothesis.ncomp();
            if let Some(&k) = at.get(&cell.cell) {
                stress[k].points = states
                    .iter()
                    .map(|s| {
                        let mut v = s.cauchy[..n].to_vec();
                        if cell.mixed.is_some() {
                            // SIEF_ELGA's SIP (tr σ/3 − p).
                            v.push(s.extra[0]);
                        }
                        v
                    })
                    .collect();
            }
            let points: Vec<Vec<f64>> =
                states.iter().map(|s| internal_variables(cell, s)).collect();
            let count = points.first().map(|p| p.len()).unwrap_or(0);
            if count == 0 {
                continue;
            }
            vari.push(CellValues {
                cell: cell.cell,
                names: VARI_NAMES[..count].to_vec(),
                points,
            });
        }
        vari
    }
}

const VARI_NAMES: [&str; 14] = [
    "V1", "V2", "V3", "V4", "V5", "V6", "V7", "V8", "V9", "V10", "V11", "V12", "V13", "V14",
];

/// VARI of a point in code_aster's order (see [`PlasticCells::fields`]).
fn internal_variables(cell: &PlasticCell, s: &GaussState) -> Vec<f64> {
    let mut v = Vec::with_capacity(8);
    match &cell.law {
        // VMIS_ISOT_NL: EPSPEQ, INDIPLAS, then EPSP (tensor components;
        // V7, V8 zero in 2D, as `vmis_isot_nl_module` packs them).
        Some(law) if matches!(law.hardening, super::Hardening::NonLinear(_)) => {
            v.extend(s.law.vari());
            let n = cell.hypothesis.ncomp();
            for k in 0..6 {
                let e = s.law.plastic_strain[k];
                v.push(match k {
                    _ if k >= n => 0.0,
                    3..=5 => e / 2.0,
                    _ => e,
                });
            }
        }
        // VMIS_JOHN_COOK (nmtevp): EPSPEQ, INDIPLAS (iterations of the
        // last search), DEPSPEQ, DINSTM, DDISSM.
        Some(law) if matches!(law.hardening, super::Hardening::JohnsonCook(_)) => {
            v.push(s.law.p);
            v.extend(s.law.rate);
        }
        // VMIS_CINE_LINE (nmcine): XCINXX … XCINYZ, INDIPLAS.
        Some(law) if matches!(law.hardening, super::Hardening::Kinematic { .. }) => {
            v.extend(super::kinematic::vari(&s.law, cell.hypothesis.ncomp()));
        }
        // ELAS_VMIS_* (lcelnl): EPSPEQ, p where non-linear.
        Some(_) if cell.hencky => v.push(if s.law.plastic { s.law.p } else { 0.0 }),
        Some(_) => v.extend(s.law.vari()),
        None if cell.viscous.is_some() => v.extend(s.law.vari()),
        None if cell.kinematics == Kinematics::Logarithmic => v.push(0.0),
        None => {}
    }
    match cell.kinematics {
        Kinematics::Logarithmic => {
            let dim = cell.hypothesis.dim();
            for k in 0..6 {
                let t = if dim == 2 && k >= 4 {
                    0.0
                } else {
                    s.law.stress[k] * crate::strain::log::mandel_factor(k)
                };
                v.push(t);
            }
        }
        Kinematics::SimoMiehe => v.extend(s.extra),
        _ => {}
    }
    v
}

/// ∫Bᵀσ − Kₑuₑ of a small-strain cell (its points' trial stresses), one
/// value per cell DOF.
fn stress_correction(cell: &PlasticCell, trial: &[GaussState], ue: &[f64]) -> Vec<f64> {
    let n = cell.hypothesis.ncomp();
    let mut fe = vec![0.0; ue.len()];
    for (a, f) in fe.iter_mut().enumerate() {
        let row = cell.k_el.row(a);
        *f = -(0..ue.len()).map(|b| row[b] * ue[b]).sum::<f64>();
    }
    for (g, gp) in cell.gauss.iter().enumerate() {
        let sigma = &trial[g].law.stress;
        for (a, f) in fe.iter_mut().enumerate() {
            *f += gp.w * (0..n).map(|k| gp.b[(k, a)] * sigma[k]).sum::<f64>();
        }
    }
    fe
}

/// The temperatures of the [`thermo`] cells' points at the end of the
/// step and their thermal strains at the first instant.
struct Thermal<'a> {
    temps: &'a [Vec<f64>],
    start: Option<&'a [Vec<f64>]>,
}

impl Thermal<'_> {
    fn at(&self, c: usize, g: usize) -> Result<(f64, f64), FemError> {
        let t = self.temps.get(c).and_then(|v| v.get(g)).copied();
        let s = self
            .start
            .and_then(|s| s.get(c))
            .and_then(|v| v.get(g))
            .copied();
        match (t, s) {
            (Some(t), Some(s)) => Ok((t, s)),
            _ => Err(FemError::Model(
                "a temperature-dependent cell integrated before its step's temperatures were set"
                    .into(),
            )),
        }
    }
}

/// Number of Gauss points of small-strain behaviour cells from which their
/// integration runs on two threads (below it a thread costs more than it
/// saves).
const PARALLEL_POINTS: usize = 4096;

/// Integrates the small-strain cells `first..first + trial.len()` of
/// `cells` at the element displacements of `u` from their committed
/// states: writes their trial states, tangents and whether each is
/// corrected, and gives the corrections ∫Bᵀσ − Kₑuₑ of the corrected
/// cells (cell index, one value per cell DOF), in cell order.
#[allow(clippy::too_many_arguments)]
fn integrate_small_cells(
    model: &Model,
    cells: &[PlasticCell],
    committed: &[Vec<GaussState>],
    thermal: &Thermal,
    first: usize,
    u: &[f64],
    dt: f64,
    trial: &mut [Vec<GaussState>],
    tangents: &mut [Vec<[[f64; 6]; 6]>],
    corrected: &mut [bool],
) -> Result<Vec<(usize, Vec<f64>)>, FemError> {
    let mut out = Vec::new();
    for (j, trial) in trial.iter_mut().enumerate() {
        let c = first + j;
        let cell = &cells[c];
        if cell.finite() {
            continue;
        }
        let ue: Vec<f64> = cell.dofs.iter().map(|&i| u[i]).collect();
        if let Some(mat) = cell.thermo.as_deref() {
            let n = cell.hypothesis.ncomp();
            for (g, gp) in cell.gauss.iter().enumerate() {
                let eps = gp.strain(&ue, n);
                let (temp, th0) = thermal.at(c, g)?;
                let (state, tangent) = thermo::integrate_point(
                    mat,
                    cell.hypothesis,
                    &eps[..n],
                    temp,
                    th0,
                    &committed[c][g].law,
                    false,
                )
                .map_err(|e| at_cell(model, cell.cell, g, e))?;
                trial[g] = GaussState {
                    law: state,
                    cauchy: state.stress,
                    extra: [0.0; 6],
                };
                tangents[j][g] = tangent;
            }
            corrected[j] = true;
            out.push((c, stress_correction(cell, trial, &ue)));
            continue;
        }
        if let Some(visc) = cell.viscous.as_deref() {
            let n = cell.hypothesis.ncomp();
            for (g, gp) in cell.gauss.iter().enumerate() {
                let eps = gp.strain(&ue, n);
                let prev = &committed[c][g].law;
                let (state, tangent) = lemaitre::integrate(
                    visc,
                    &cell.elastic,
                    cell.hypothesis,
                    &eps[..n],
                    prev,
                    dt,
                    false,
                )
                .map_err(|e| at_cell(model, cell.cell, g, e))?;
                trial[g] = GaussState {
                    law: state,
                    cauchy: state.stress,
                    extra: [0.0; 6],
                };
                tangents[j][g] = tangent;
            }
            corrected[j] = true;
            out.push((c, stress_correction(cell, trial, &ue)));
            continue;
        }
        let Some(law) = cell.law.as_deref() else {
            continue;
        };
        // A cell whose points all stay elastic without plastic strain
        // has σ = D ε and tangent D: its corrections vanish (most cells
        // around a local plastic zone).
        let mut virgin = law.elastic(&cell.elastic) == cell.elastic;
        let n = cell.hypothesis.ncomp();
        for (g, gp) in cell.gauss.iter().enumerate() {
            let eps = gp.strain(&ue, n);
            if cell.hencky {
                let (state, tangent) =
                    super::hencky::integrate(law, &cell.elastic, cell.hypothesis, &eps[..n])
                        .map_err(|e| at_cell(model, cell.cell, g, e))?;
                virgin &= !state.plastic;
                trial[g] = GaussState {
                    law: state,
                    cauchy: state.stress,
                    extra: [0.0; 6],
                };
                tangents[j][g] = tangent;
                continue;
            }
            let prev = &committed[c][g].law;
            let (state, tangent) = integrate(
                law,
                &cell.elastic,
                cell.hypothesis,
                &eps[..n],
                prev,
                false,
                dt,
            )
            .map_err(|e| at_cell(model, cell.cell, g, e))?;
            virgin &= !state.plastic && state.p == 0.0;
            trial[g] = GaussState {
                law: state,
                cauchy: state.stress,
                extra: [0.0; 6],
            };
            tangents[j][g] = tangent;
        }
        corrected[j] = !virgin;
        if virgin {
            continue;
        }
        out.push((c, stress_correction(cell, trial, &ue)));
    }
    Ok(out)
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

fn at_cell_finite(model: &Model, cell: CellId, e: FemError) -> FemError {
    match e {
        FemError::Integration(m) => {
            FemError::Integration(format!("cell {}, {m}", model.cell_name(cell)))
        }
        FemError::Model(m) => FemError::Model(format!("cell {}, {m}", model.cell_name(cell))),
        other => other,
    }
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
    forc_noda_deformed(model, u, stress, &Behaviours::default())
}

/// [`forc_noda_from_stress`] where the cells of a finite-strain
/// kinematics (`behaviours`) integrate their Cauchy stresses on the
/// deformed geometry X + u, as code_aster's FORC_NODA does for any
/// DEFORMATION other than PETIT.
pub fn forc_noda_deformed(
    model: &Model,
    u: &[f64],
    stress: &[CellValues],
    behaviours: &Behaviours,
) -> Result<Vec<f64>, FemError> {
    // code_aster's FORC_NODA of the mixed cells (te0591) has pressure and
    // swelling rows: not reproduced.
    crate::mixed_upg::refuse_mixed(model, "FORC_NODA/REAC_NODA")?;
    crate::post::refuse_stabilised(model, "nodal forces (FORC_NODA, REAC_NODA)")?;
    let at: HashMap<CellId, &CellValues> = stress.iter().map(|cv| (cv.cell, cv)).collect();
    let mut f = vec![0.0; model.dofs().len()];
    for el in model.elements() {
        let dofs = element_dofs(model, el.cell);
        let fe = match &el.kind {
            ElementKind::Continuum { hypothesis, .. } => {
                let Some(cv) = at.get(&el.cell) else {
                    continue;
                };
                let g = model_gauss(model, el.cell, *hypothesis).map_err(|m| {
                    FemError::Model(format!("cell {} is {m}", model.cell_name(el.cell)))
                })?;
                if behaviours.kinematics(el.cell).deformed_geometry() {
                    let ue: Vec<f64> = dofs.iter().map(|&i| u[i]).collect();
                    let geoms = fs::point_geoms(&g, *hypothesis);
                    let fe = fs::forces_on_deformed(&geoms, *hypothesis, &ue, &cv.points)
                        .map_err(|e| at_cell_finite(model, el.cell, e))?;
                    DVector::from_vec(fe)
                } else {
                    let mut fe = DVector::zeros(dofs.len());
                    for (gp, s) in g.iter().zip(&cv.points) {
                        let sigma = DVector::from_column_slice(&s[..hypothesis.ncomp()]);
                        fe.gemv_tr(gp.w, &gp.b, &sigma, 1.0);
                    }
                    fe
                }
            }
            ElementKind::Spring { stiffness, frame } => {
                let (k, _) = spring_stiffness(model.mesh(), el.cell, stiffness, *frame);
                let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
                k * ue
            }
            // Linear elastic facets: K u.
            ElementKind::Shell {
                material,
                section,
                theory,
            } => {
                let k = crate::element::shell_stiffness(
                    model.mesh(),
                    el.cell,
                    material,
                    section,
                    *theory,
                )
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))?;
                let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
                k * ue
            }
            // Linear elastic beams: K u.
            ElementKind::Beam { material, section } => {
                let k = crate::element::beam_stiffness(model.mesh(), el.cell, material, section)
                    .map_err(|m| {
                        FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))
                    })?;
                let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
                k * ue
            }
            // Linear elastic bars: K u.
            ElementKind::Bar { material, area } => {
                let k = crate::element::bar_stiffness(model.mesh(), el.cell, material, *area)
                    .map_err(|m| {
                        FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))
                    })?;
                let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
                k * ue
            }
            // Grids: Σ Bᵀ σ w from their stored SIXX (a plastic or heated
            // grid's stress is not E B u); K u without one.
            ElementKind::Grid { section, .. } if at.contains_key(&el.cell) => {
                let sigma: Vec<f64> = at[&el.cell]
                    .points
                    .iter()
                    .map(|p| p.first().copied().unwrap_or(0.0))
                    .collect();
                let mesh = model.mesh();
                let fe = crate::grid::nodal_forces(
                    mesh.cell(el.cell).ty,
                    &crate::element::cell_coords(mesh, el.cell),
                    section,
                    &sigma,
                )
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))?;
                DVector::from_vec(fe)
            }
            ElementKind::Grid { material, section } => {
                let k = crate::element::grid_stiffness(model.mesh(), el.cell, material, section)
                    .map_err(|m| {
                        FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))
                    })?;
                let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
                k * ue
            }
            // Linear elastic COQUE_3D: K u.
            ElementKind::Coque3d { material, section } => {
                let k = crate::element::coque3d_stiffness(model.mesh(), el.cell, material, section)
                    .map_err(|m| {
                        FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))
                    })?;
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

/// The behaviour cell of a grid with a uniaxial law.
fn grid_cell(
    model: &Model,
    cell: CellId,
    material: &Elastic,
    section: &crate::grid::GridSection,
    law: Arc<Uniaxial>,
) -> Result<PlasticCell, FemError> {
    let name = model.cell_name(cell);
    law.check()
        .map_err(|m| FemError::Model(format!("grid cell {name}: {m}")))?;
    let mesh = model.mesh();
    let ty = mesh.cell(cell).ty;
    let xyz = crate::element::cell_coords(mesh, cell);
    let points = crate::grid::points(ty, &xyz, section)
        .map_err(|m| FemError::Model(format!("grid cell {name}: {m}")))?;
    let k_el = crate::grid::stiffness(ty, &xyz, section, material.e)
        .map_err(|m| FemError::Model(format!("grid cell {name}: {m}")))?;
    let nodes = mesh.cell(cell).nodes.iter().map(|n| n.0 as usize).collect();
    let shape_n = crate::grid::scheme(ty)
        .iter()
        .map(|gp| crate::shape::shape(ty, gp.xi).n.to_vec())
        .collect();
    Ok(PlasticCell {
        cell,
        hypothesis: Hypothesis::Solid3D,
        elastic: *material,
        law: None,
        viscous: None,
        thermo: None,
        hencky: false,
        nodes,
        shape_n,
        kinematics: Kinematics::Small,
        dofs: element_dofs(model, cell),
        gauss: Vec::new(),
        geoms: Vec::new(),
        k_el,
        stabilised: None,
        mixed: None,
        grid: Some(Box::new(GridCell {
            law,
            temp_from: Vec::new(),
            temp_to: Vec::new(),
            points,
        })),
    })
}

/// The initial node coordinates of a stabilised HEXA8 cell, with the
/// behaviours `nmas3d` computes (small strains, PETIT or PETIT_REAC, and
/// the von Mises laws or ELAS).
fn stabilised_setup(
    model: &Model,
    cell: CellId,
    behaviour: &super::CellBehaviour,
) -> Result<Option<[[f64; 3]; 8]>, FemError> {
    let name = model.cell_name(cell);
    if !matches!(
        behaviour.kinematics,
        Kinematics::Small | Kinematics::SmallUpdated
    ) {
        return Err(FemError::Model(format!(
            "cell {name}: the under-integrated HEXA8 of 3D_SI takes DEFORMATION='PETIT' or 'PETIT_REAC' only (code_aster's ELEMENTSSI_1), not '{}'",
            behaviour.kinematics.aster_name()
        )));
    }
    if behaviour.viscous.is_some() {
        return Err(FemError::Model(format!(
            "cell {name}: LEMAITRE on the under-integrated HEXA8 of 3D_SI is not implemented"
        )));
    }
    let mesh = model.mesh();
    let nodes = &mesh.cell(cell).nodes;
    let mut x = [[0.0; 3]; 8];
    if nodes.len() != 8 {
        return Err(FemError::Model(format!("cell {name} is not a HEXA8")));
    }
    for (a, n) in nodes.iter().enumerate() {
        x[a] = mesh.coord(*n);
    }
    Ok(Some(x))
}
