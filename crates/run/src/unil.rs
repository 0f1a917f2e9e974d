//! `DEFI_CONTACT(FORMULATION='LIAISON_UNIL')` as a source of inequality
//! rows for the fem solver: on each node of each zone,
//! Σ COEF_MULT_c · u_c ≤ COEF_IMPO, the coefficients being functions
//! evaluated at the step's time (parameter `INST`) or at the node
//! (`X`, `Y`, `Z`).

use crate::concept::{UnilateralAlgo, UnilateralZone};
use crate::function::Function;
use aster_fem::{
    Comp, Dof, FemError, GeometryUpdate, InequalityRow, State, UnilateralMethod, UnilateralSource,
};
use aster_mesh::NodeId;

pub struct LiaisonUnil {
    pub zones: Vec<UnilateralZone>,
    pub algo: UnilateralAlgo,
}

fn eval_at(f: &Function, state: &State, node: NodeId) -> Result<f64, FemError> {
    let x = state.mesh.coord(node);
    // Every parameter the function names (a FORMULE of X, Y, Z names
    // them all; a constant none).
    f.eval_named(&[("INST", state.time), ("X", x[0]), ("Y", x[1]), ("Z", x[2])])
        .map_err(|e| FemError::Source(format!("LIAISON_UNIL coefficient: {e}")))
}

fn comp(name: &str) -> Result<Comp, FemError> {
    Comp::from_name(name)
        .ok_or_else(|| FemError::Source(format!("LIAISON_UNIL: unknown component {name}")))
}

impl LiaisonUnil {
    /// The rows at a state (the node order of the zones gives row ids).
    pub fn build_rows(&self, state: &State) -> Result<Vec<InequalityRow>, FemError> {
        let mut rows = Vec::new();
        for zone in &self.zones {
            for &node in &zone.nodes {
                let mut terms = Vec::new();
                for (c, f) in zone.comps.iter().zip(&zone.coef_mult) {
                    let a = eval_at(f, state, node)?;
                    if a != 0.0 {
                        terms.push((Dof::new(node, comp(c)?), a));
                    }
                }
                let rhs = eval_at(&zone.coef_impo, state, node)?;
                let id = rows.len();
                rows.push(InequalityRow::new(terms, rhs, id));
            }
        }
        Ok(rows)
    }
}

impl UnilateralSource for LiaisonUnil {
    fn name(&self) -> String {
        "LIAISON_UNIL".into()
    }

    fn method(&self) -> UnilateralMethod {
        match self.algo {
            UnilateralAlgo::Constraint => UnilateralMethod::ActiveSet,
            UnilateralAlgo::Penalty(coef) => UnilateralMethod::Penalty { coef },
        }
    }

    fn geometry_update(&self) -> GeometryUpdate {
        // Coefficients may depend on time: rebuild at each step.
        GeometryUpdate::EachStep
    }

    fn rows(&mut self, state: &State) -> Result<Vec<InequalityRow>, FemError> {
        self.build_rows(state)
    }
}
