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

mod cells;
pub mod johnson_cook;
pub mod kinematic;
pub mod lemaitre;
pub mod simo_miehe;
pub mod vmis;

pub use crate::strain::{GaussState, Kinematics};
pub(crate) use cells::PlasticCells;
pub use cells::{forc_noda_deformed, forc_noda_from_stress, BehaviourState};
pub use johnson_cook::JohnsonCook;
pub use lemaitre::Lemaitre;
pub use vmis::{CurveEnd, EcroNl, Hardening, PointState, VonMises};

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
}

/// Which cells follow a plastic law or a finite-strain kinematics
/// (`COMPORTEMENT` occurrences other than ELAS in small strains); every
/// other cell is elastic in small strains.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Behaviours {
    by_cell: BTreeMap<CellId, CellBehaviour>,
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
            },
        );
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
        if self.by_cell.is_empty() && !model.has_stabilised() {
            return Vec::new();
        }
        // The stabilised HEXA8 cells are always computed here, ELAS
        // included: their forces are not K u (`crate::hexs8`).
        let elastic = CellBehaviour {
            law: None,
            kinematics: Kinematics::Small,
            viscous: None,
        };
        model
            .elements()
            .iter()
            .enumerate()
            .filter(|(_, el)| matches!(el.kind, ElementKind::Continuum { .. }))
            .filter_map(|(k, el)| match self.by_cell.get(&el.cell) {
                Some(b) => Some((k, b.clone())),
                None if model.is_stabilised(el.cell) => Some((k, elastic.clone())),
                None => None,
            })
            .collect()
    }
}
