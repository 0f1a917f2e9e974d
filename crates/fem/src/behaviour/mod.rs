//! Non-linear material behaviours of STAT_NON_LINE (`COMPORTEMENT`).
//!
//! Cells without a behaviour here are elastic in small strains
//! (`RELATION='ELAS'`, `DEFORMATION='PETIT'`) and keep the assembled elastic
//! stiffness (K u for their internal forces). Cells given a [`VonMises`]
//! law or a finite-strain kinematics ([`Kinematics`], `DEFORMATION`) carry
//! a state per Gauss point ([`GaussState`]); their internal forces and
//! consistent tangent replace their elastic share of K u and K (see
//! `cells`).
//!
//! - small strains (`PETIT`): von Mises with isotropic hardening
//!   ([`vmis`]), stress σ, VARI V1 = p, V2 = plasticity indicator;
//! - `PETIT_REAC`, `GREEN_LAGRANGE`, `GDEF_LOG`: the same small-strain laws
//!   (or ELAS) on the strain measure of [`crate::strain`];
//! - `SIMO_MIEHE`: multiplicative von Mises plasticity ([`simo_miehe`]);
//! - `LEMAITRE` (small strains): viscoplasticity without threshold
//!   ([`lemaitre`]), integrated over the step's duration.
//! - `VMIS_JOHN_COOK`: von Mises with Johnson–Cook rate-dependent
//!   hardening ([`johnson_cook`], `Hardening::JohnsonCook`), over the
//!   step's duration, in PETIT, PETIT_REAC or GDEF_LOG.
//! - `VMIS_CINE_LINE`: von Mises with linear kinematic (Prager) hardening
//!   ([`kinematic`], `Hardening::Kinematic`), VARI the back stress and
//!   the plasticity indicator.
//! - `ELAS_VMIS_LINE`, `ELAS_VMIS_TRAC` (small strains): Hencky's
//!   non-linear elasticity ([`hencky`]), VARI V1 = p.
//! - parameters that follow the temperature (`ELAS_FO`, `ECRO_LINE_FO`)
//!   at each Gauss point and instant, ELAS and `VMIS_ISOT_*` in small
//!   strains ([`thermo`]), the thermal strain in the behaviour.
//! - `GRILLE_ISOT_LINE`, `GRILLE_CINE_LINE` on reinforcement grids:
//!   uniaxial plasticity along the bars ([`uniaxial`], `nm1dis`, `nm1dci`),
//!   and ELAS grids under a temperature (the thermal strain along the bars).

mod cells;
pub mod hencky;
pub mod johnson_cook;
pub mod kinematic;
pub mod lemaitre;
pub mod simo_miehe;
pub mod thermo;
pub mod traction;
pub mod uniaxial;
pub mod vmis;

pub use crate::strain::{GaussState, Kinematics};
pub(crate) use cells::PlasticCells;
pub use cells::{forc_noda_deformed, forc_noda_from_stress, BehaviourState};
pub use johnson_cook::JohnsonCook;
pub use lemaitre::Lemaitre;
pub use thermo::{TempFn, ThermoHardening, ThermoMaterial};
pub use traction::{TractionCurve, TractionNappe};
pub use uniaxial::{Uniaxial, UniaxialHardening, UniaxialState};
pub use vmis::{CurveEnd, EcroNl, Hardening, LocalSearch, PointState, VonMises};

use crate::error::FemError;
use crate::model::{ElementKind, Model};
use aster_mesh::CellId;
use std::collections::BTreeMap;
use std::sync::Arc;

/// The behaviour of a cell: a plastic law (`None`: ELAS) and a kinematics.
#[derive(Clone, Debug, PartialEq)]
pub struct CellBehaviour {
    pub law: Option<Arc<VonMises>>,
    pub kinematics: Kinematics,
    /// A viscoplastic law (`LEMAITRE`, small strains) in place of `law`.
    pub viscous: Option<Arc<Lemaitre>>,
    /// Parameters that follow the temperature ([`thermo`]), small strains:
    /// in place of `law` (ELAS or a `VMIS_ISOT_*` law at each point's
    /// temperature).
    pub thermo: Option<Arc<ThermoMaterial>>,
    /// A reinforcement grid's uniaxial law ([`uniaxial`]): grid cells only.
    pub uniaxial: Option<Arc<Uniaxial>>,
    /// `ELAS_VMIS_LINE`, `ELAS_VMIS_TRAC`: `law` read as a Hencky
    /// (non-linear elastic) law, small strains ([`hencky`]).
    pub hencky: bool,
}

/// Nodal temperatures over time (`AFFE_VARC`): knots (instant, value per
/// mesh node), linear between them, constant or excluded outside.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodalHistory {
    pub knots: Vec<(f64, Arc<Vec<f64>>)>,
    pub constant_before: bool,
    pub constant_after: bool,
}

impl NodalHistory {
    /// The temperature of every mesh node at time `t`.
    pub fn at(&self, t: f64) -> Result<Vec<f64>, FemError> {
        let k = &self.knots;
        let Some(first) = k.first() else {
            return Err(FemError::Model(
                "a temperature history without values".into(),
            ));
        };
        let last = &k[k.len() - 1];
        let tol = |x: f64| 1e-12 * x.abs().max(1.0);
        if t < first.0 - tol(first.0) {
            if !self.constant_before {
                return Err(FemError::Model(format!(
                    "the temperature is asked at {t}, before its first instant {} (PROL_GAUCHE='EXCLU')",
                    first.0
                )));
            }
            return Ok(first.1.to_vec());
        }
        if t > last.0 + tol(last.0) {
            if !self.constant_after {
                return Err(FemError::Model(format!(
                    "the temperature is asked at {t}, after its last instant {} (PROL_DROITE='EXCLU')",
                    last.0
                )));
            }
            return Ok(last.1.to_vec());
        }
        if let Some((_, v)) = k.iter().find(|(x, _)| (x - t).abs() <= tol(*x)) {
            return Ok(v.to_vec());
        }
        let j = k.partition_point(|(x, _)| *x <= t).clamp(1, k.len() - 1);
        let (t0, a) = (&k[j - 1].0, &k[j - 1].1);
        let (t1, b) = (&k[j].0, &k[j].1);
        let w = (t - t0) / (t1 - t0);
        Ok(a.iter()
            .zip(b.iter())
            .map(|(x, y)| x + w * (y - x))
            .collect())
    }
}

/// Which cells follow a plastic law or a finite-strain kinematics
/// (`COMPORTEMENT` occurrences other than ELAS in small strains); every
/// other cell is elastic in small strains.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Behaviours {
    by_cell: BTreeMap<CellId, CellBehaviour>,
    /// The nodal temperatures the [`thermo`] cells read.
    temperature: Option<Arc<NodalHistory>>,
}

impl Behaviours {
    /// No plastic cell: linear elasticity everywhere.
    pub fn elastic() -> Behaviours {
        Behaviours::default()
    }

    /// Gives `law` in small strains to `cell` (a later assignment replaces
    /// an earlier one, as COMPORTEMENT occurrences do).
    pub fn assign(&mut self, cell: CellId, law: Arc<VonMises>) {
        self.assign_with(cell, Some(law), Kinematics::Small);
    }

    /// Gives `cell` a law (`None`: ELAS) under a kinematics; ELAS in small
    /// strains is the default and removes the cell.
    pub fn assign_with(
        &mut self,
        cell: CellId,
        law: Option<Arc<VonMises>>,
        kinematics: Kinematics,
    ) {
        if law.is_none() && kinematics == Kinematics::Small {
            self.by_cell.remove(&cell);
        } else {
            self.by_cell.insert(
                cell,
                CellBehaviour {
                    law,
                    kinematics,
                    viscous: None,
                    thermo: None,
                    uniaxial: None,
                    hencky: false,
                },
            );
        }
    }

    /// Gives `cell` Lemaitre's viscoplastic law in small strains.
    pub fn assign_viscous(&mut self, cell: CellId, law: Arc<Lemaitre>) {
        self.by_cell.insert(
            cell,
            CellBehaviour {
                law: None,
                kinematics: Kinematics::Small,
                viscous: Some(law),
                thermo: None,
                uniaxial: None,
                hencky: false,
            },
        );
    }

    /// Gives `cell` the Hencky law `law` (`ELAS_VMIS_*`, small strains,
    /// [`hencky`]).
    pub fn assign_hencky(&mut self, cell: CellId, law: Arc<VonMises>) {
        self.by_cell.insert(
            cell,
            CellBehaviour {
                law: Some(law),
                kinematics: Kinematics::Small,
                viscous: None,
                thermo: None,
                uniaxial: None,
                hencky: true,
            },
        );
    }

    /// Gives `cell` a temperature-dependent material in small strains
    /// (ELAS or `VMIS_ISOT_*` at each point's temperature, [`thermo`]).
    pub fn assign_thermo(&mut self, cell: CellId, material: Arc<ThermoMaterial>) {
        self.by_cell.insert(
            cell,
            CellBehaviour {
                law: material.reference_law().map(Arc::new),
                kinematics: Kinematics::Small,
                viscous: None,
                thermo: Some(material),
                uniaxial: None,
                hencky: false,
            },
        );
    }

    /// Gives a grid cell ([`ElementKind::Grid`]) a uniaxial law along its
    /// bars (`GRILLE_ISOT_LINE`, `GRILLE_CINE_LINE`, or ELAS with a
    /// thermal strain).
    pub fn assign_uniaxial(&mut self, cell: CellId, law: Arc<Uniaxial>) {
        self.by_cell.insert(
            cell,
            CellBehaviour {
                law: None,
                kinematics: Kinematics::Small,
                viscous: None,
                thermo: None,
                uniaxial: Some(law),
                hencky: false,
            },
        );
    }

    /// Whether some cell needs the temperature: a temperature-dependent
    /// material or a grid law with a dilatation coefficient.
    pub fn needs_temperature(&self) -> bool {
        self.by_cell
            .values()
            .any(|b| b.thermo.is_some() || b.uniaxial.as_ref().is_some_and(|u| u.alpha != 0.0))
    }

    /// The nodal temperatures over time the temperature-dependent cells
    /// read.
    pub fn set_temperature(&mut self, history: Arc<NodalHistory>) {
        self.temperature = Some(history);
    }

    /// The temperature history of the temperature-dependent cells.
    pub(crate) fn temperature(&self) -> Option<&Arc<NodalHistory>> {
        self.temperature.as_ref()
    }

    /// Whether a temperature history is set.
    pub fn has_temperature(&self) -> bool {
        self.temperature.is_some()
    }

    /// Whether some cell has a temperature-dependent material.
    pub fn has_thermo(&self) -> bool {
        self.by_cell.values().any(|b| b.thermo.is_some())
    }

    /// Makes `cell` elastic in small strains again (a later
    /// `RELATION='ELAS'` occurrence with `DEFORMATION='PETIT'`).
    pub fn make_elastic(&mut self, cell: CellId) {
        self.by_cell.remove(&cell);
    }

    /// Whether every cell is elastic in small strains.
    pub fn is_elastic(&self) -> bool {
        self.by_cell.is_empty()
    }

    /// The plastic law of a cell.
    pub fn law(&self, cell: CellId) -> Option<&Arc<VonMises>> {
        self.by_cell.get(&cell).and_then(|b| b.law.as_ref())
    }

    /// The kinematics of a cell (small strains when not assigned).
    pub fn kinematics(&self, cell: CellId) -> Kinematics {
        self.by_cell
            .get(&cell)
            .map(|b| b.kinematics)
            .unwrap_or_default()
    }

    /// Whether a cell follows a viscoplastic law (`LEMAITRE`).
    pub fn has_viscous(&self) -> bool {
        self.by_cell.values().any(|b| b.viscous.is_some())
    }

    /// Whether some cell has a finite-strain kinematics.
    pub fn has_finite_strains(&self) -> bool {
        self.by_cell
            .values()
            .any(|b| b.kinematics != Kinematics::Small)
    }

    /// The behaviour cells of the model (indices into `model.elements()`).
    /// Behaviours on cells without a continuum element are ignored
    /// (code_aster applies COMPORTEMENT to the model's cells only: boundary
    /// and discrete cells have no such behaviour).
    pub(crate) fn elements(&self, model: &Model) -> Vec<(usize, CellBehaviour)> {
        if self.by_cell.is_empty() && !model.has_stabilised() && !model.has_mixed() {
            return Vec::new();
        }
        // The stabilised HEXA8 cells are always computed here, ELAS
        // included: their forces are not K u (`crate::hexs8`).
        let elastic = CellBehaviour {
            law: None,
            kinematics: Kinematics::Small,
            viscous: None,
            thermo: None,
            uniaxial: None,
            hencky: false,
        };
        model
            .elements()
            .iter()
            .enumerate()
            .filter(|(_, el)| match el.kind {
                ElementKind::Continuum { .. } => true,
                // Grids with a uniaxial law.
                ElementKind::Grid { .. } => self
                    .by_cell
                    .get(&el.cell)
                    .is_some_and(|b| b.uniaxial.is_some()),
                _ => false,
            })
            .filter_map(|(k, el)| match self.by_cell.get(&el.cell) {
                Some(b) => Some((k, b.clone())),
                None if model.is_stabilised(el.cell) => Some((k, elastic.clone())),
                // So are the mixed cells (`crate::mixed_upg`): their
                // SIEF_ELGA in STAT_NON_LINE is `nifipd`'s, from the
                // strain with the swelling's volume change.
                None if model.is_mixed(el.cell) => Some((k, elastic.clone())),
                None => None,
            })
            .collect()
    }
}
