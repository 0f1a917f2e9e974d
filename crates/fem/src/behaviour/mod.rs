//! Non-linear material behaviours of STAT_NON_LINE (`COMPORTEMENT`).
//!
//! Cells without a behaviour here are elastic (`RELATION='ELAS'`) and keep
//! the assembled elastic stiffness (K u for their internal forces). Cells
//! given a [`VonMises`] law carry a state per Gauss point ([`PointState`]:
//! stress, plastic strain, cumulated plastic strain p and the plasticity
//! indicator, code_aster's VARI V1 and V2); their internal forces ∫Bᵀσ and
//! consistent tangent ∫BᵀC B replace their elastic share of K u and K (see
//! `cells`). Small strains only (`DEFORMATION='PETIT'`).

mod cells;
pub mod vmis;

pub use cells::forc_noda_from_stress;
pub(crate) use cells::PlasticCells;
pub use vmis::{CurveEnd, Hardening, PointState, VonMises};

use crate::model::{ElementKind, Model};
use aster_mesh::CellId;
use std::collections::BTreeMap;
use std::sync::Arc;

/// Which cells follow a plastic law (`COMPORTEMENT` occurrences other than
/// ELAS); every other cell is elastic.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Behaviours {
    by_cell: BTreeMap<CellId, Arc<VonMises>>,
}

impl Behaviours {
    /// No plastic cell: linear elasticity everywhere.
    pub fn elastic() -> Behaviours {
        Behaviours::default()
    }

    /// Gives `law` to `cell` (a later assignment replaces an earlier one,
    /// as COMPORTEMENT occurrences do).
    pub fn assign(&mut self, cell: CellId, law: Arc<VonMises>) {
        self.by_cell.insert(cell, law);
    }

    /// Makes `cell` elastic again (a later `RELATION='ELAS'` occurrence).
    pub fn make_elastic(&mut self, cell: CellId) {
        self.by_cell.remove(&cell);
    }

    pub fn is_elastic(&self) -> bool {
        self.by_cell.is_empty()
    }

    pub fn law(&self, cell: CellId) -> Option<&Arc<VonMises>> {
        self.by_cell.get(&cell)
    }

    /// The plastic elements of the model (indices into `model.elements()`)
    /// with their laws. Laws on cells without a continuum element are
    /// ignored (code_aster applies COMPORTEMENT to the model's cells only:
    /// boundary and discrete cells have no such behaviour).
    pub(crate) fn elements(&self, model: &Model) -> Vec<(usize, Arc<VonMises>)> {
        if self.by_cell.is_empty() {
            return Vec::new();
        }
        model
            .elements()
            .iter()
            .enumerate()
            .filter(|(_, el)| matches!(el.kind, ElementKind::Continuum { .. }))
            .filter_map(|(k, el)| self.by_cell.get(&el.cell).map(|law| (k, law.clone())))
            .collect()
    }
}
