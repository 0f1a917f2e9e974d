//! Unilateral (inequality) conditions shared by `LIAISON_UNIL` and contact.
//!
//! A condition is a set of linear inequality rows `Σ aᵢ uᵢ ≤ b` over DOFs,
//! where `u` is the *total* displacement (not the increment). Sources
//! (a `LIAISON_UNIL` zone, a contact zone) produce the rows from the current
//! state; the solver enforces them, exactly with an active set on Lagrange
//! multipliers (`ALGO_CONT='CONTRAINTE'`) or approximately by penalty
//! (`'PENALISATION'`), then hands each row's outcome back to its source.
//!
//! Sign convention: a row's multiplier `λ ≥ 0` is the magnitude of the
//! reaction; the force applied by the condition on the structure is
//! `-λ a` (for `-DY ≤ 0`, a support pushing up with `+λ` in DY).

use crate::dof::{Dof, DofNumbering};
use crate::error::FemError;
use aster_mesh::{Mesh, NodeId};

/// One linear inequality `Σ coef·u(dof) ≤ rhs` on the total displacement.
#[derive(Clone, Debug, PartialEq)]
pub struct InequalityRow {
    /// `(dof, coefficient)` terms; a DOF may appear once.
    pub terms: Vec<(Dof, f64)>,
    /// Right-hand side `b`.
    pub rhs: f64,
    /// Identifier chosen by the source (e.g. the slave node), handed back in
    /// [`RowOutcome::id`].
    pub id: usize,
    /// A bilateral row (contact's `GLISSIERE='OUI'`): always enforced, as
    /// an equality `Σ aᵢ uᵢ = b`, whatever the sign of its multiplier — the
    /// link may pull as well as push and never opens. Under penalty the
    /// force is `coef·(Σ a u − b)` on both sides.
    pub bilateral: bool,
}

impl InequalityRow {
    pub fn new(terms: Vec<(Dof, f64)>, rhs: f64, id: usize) -> InequalityRow {
        InequalityRow {
            terms,
            rhs,
            id,
            bilateral: false,
        }
    }

    /// The same row made bilateral (see [`InequalityRow::bilateral`]).
    pub fn into_bilateral(mut self) -> InequalityRow {
        self.bilateral = true;
        self
    }

    /// `Σ aᵢ uᵢ - b` for a state: positive means violated (penetration).
    pub fn violation(&self, state: &State) -> f64 {
        self.terms
            .iter()
            .map(|&(d, c)| c * state.value(d).unwrap_or(0.0))
            .sum::<f64>()
            - self.rhs
    }
}

/// How the solver enforces a source's rows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum UnilateralMethod {
    /// Exact enforcement, active set on Lagrange multipliers (`CONTRAINTE`).
    ActiveSet,
    /// Penalty `λ = coef·max(0, Σ a u - b)` (`PENALISATION`, `COEF_PENA`).
    Penalty { coef: f64 },
}

/// When the solver asks the source for new rows (`REAC_GEOM`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeometryUpdate {
    /// Rows are asked once, at the first step (`REAC_GEOM='SANS'`, and
    /// LIAISON_UNIL whose rows never change).
    Once,
    /// Rows are asked at the beginning of each time step (from the last
    /// converged state).
    EachStep,
    /// Rows are asked again at each stable active set of a step, until the
    /// source returns the rows it returned last (a fixed point on the
    /// geometry; a source running code_aster's own geometric test, as
    /// contact's `GeomLoopState`, ends the loop by repeating its rows).
    EachIteration,
}

/// How a source's own loops sit with respect to Newton's iterations, for
/// code_aster's iteration count (`ITER_GLOB`, and `ITER_GLOB_MAXI`).
/// By default (discrete contact, LIAISON_UNIL) the active set is settled
/// inside one Newton iteration and new pairings are nested in the
/// iterations: the count runs over the whole increment.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OuterLoops {
    /// A new pairing starts Newton again from iteration 0 (continuous
    /// contact's `ALGO_RESO_GEOM='POINT_FIXE'`: the geometric loop is
    /// outside Newton).
    pub pairing_restarts: bool,
    /// A change of the active set starts Newton again from iteration 0
    /// (`ALGO_RESO_CONT='POINT_FIXE'`: the contact loop is outside Newton).
    pub status_restarts: bool,
}

/// The current mechanical state given to sources.
#[derive(Clone, Copy, Debug)]
pub struct State<'a> {
    pub mesh: &'a Mesh,
    pub dofs: &'a DofNumbering,
    /// Total displacement, indexed like [`DofNumbering::dofs`].
    pub displacement: &'a [f64],
    /// Time of the step being computed.
    pub time: f64,
}

impl State<'_> {
    /// Total displacement of a DOF (`None` if the DOF is not in the model).
    pub fn value(&self, dof: Dof) -> Option<f64> {
        self.dofs.index(dof).map(|i| self.displacement[i])
    }

    /// Displacement of a node as a 3-vector (missing components are 0).
    pub fn node_displacement(&self, node: NodeId) -> [f64; 3] {
        let mut u = [0.0; 3];
        if let Some(first) = self.dofs.node_first(node) {
            for (k, c) in self.dofs.node_comps(node).iter().enumerate() {
                let slot = match c {
                    crate::dof::Comp::DX => 0,
                    crate::dof::Comp::DY => 1,
                    crate::dof::Comp::DZ => 2,
                    _ => continue,
                };
                u[slot] = self.displacement[first + k];
            }
        }
        u
    }

    /// Current (deformed) coordinates of a node: initial + displacement.
    pub fn current_coord(&self, node: NodeId) -> [f64; 3] {
        let x = self.mesh.coord(node);
        let u = self.node_displacement(node);
        [x[0] + u[0], x[1] + u[1], x[2] + u[2]]
    }
}

/// What the solver reports for one row at convergence of a step.
#[derive(Clone, Debug, PartialEq)]
pub struct RowOutcome {
    /// The row's [`InequalityRow::id`].
    pub id: usize,
    /// Multiplier λ ≥ 0 (reaction magnitude along the row); 0 when inactive.
    /// A bilateral row's may be negative (the link pulls).
    pub multiplier: f64,
    /// Whether the row is enforced as an equality (in the active set, or
    /// penetrating under penalty).
    pub active: bool,
    /// `Σ aᵢ uᵢ - b` at convergence (≤ 0 up to round-off when exact).
    pub violation: f64,
}

/// A bilateral penalty term riding on a source's rows: code_aster's
/// augmented term ρ·g of the continuous `STANDARD` formulation (`mmmvee`:
/// the force at a contact point is −(λ − ρ g)·n, λ the interpolated
/// multiplier, g the pointwise penetration). While the point is in
/// contact — Σ Nⱼ λⱼ + ρ (a·u − b) > 0, code_aster's `mmstac` — it adds
/// `coef · weight · (a·u − b) · a` to the forces, whatever the sign of
/// a·u − b.
#[derive(Clone, Debug, PartialEq)]
pub struct AugmentedTerm {
    /// a·u − b: the penetration at the point.
    pub row: InequalityRow,
    /// ρ (`COEF_CONT`).
    pub coef: f64,
    /// The point's integration weight.
    pub weight: f64,
    /// The source's rows (indices into its last [`UnilateralSource::rows`]
    /// answer) whose multipliers λⱼ the point's pressure interpolates,
    /// with their weights Nⱼ.
    pub support: Vec<(usize, f64)>,
}

/// A producer of inequality rows (a LIAISON_UNIL zone, a contact zone).
pub trait UnilateralSource {
    /// Short name used in messages (e.g. `"LIAISON_UNIL"`, `"contact zone 1"`).
    fn name(&self) -> String {
        "unilateral condition".to_string()
    }

    /// How the rows are enforced.
    fn method(&self) -> UnilateralMethod {
        UnilateralMethod::ActiveSet
    }

    /// When the rows must be recomputed.
    fn geometry_update(&self) -> GeometryUpdate {
        GeometryUpdate::Once
    }

    /// Where the source's loops sit with respect to Newton's iterations.
    fn outer_loops(&self) -> OuterLoops {
        OuterLoops::default()
    }

    /// The current rows for a state (the last converged one, or the current
    /// iterate with [`GeometryUpdate::EachIteration`]).
    fn rows(&mut self, state: &State) -> Result<Vec<InequalityRow>, FemError>;

    /// Called once per converged step with the outcome of each row of the
    /// last call to [`UnilateralSource::rows`] (same order).
    fn converged(&mut self, _state: &State, _outcomes: &[RowOutcome]) -> Result<(), FemError> {
        Ok(())
    }

    /// The augmented terms that go with the rows of the last call to
    /// [`UnilateralSource::rows`] (none by default).
    fn augmented_terms(&self) -> Vec<AugmentedTerm> {
        Vec::new()
    }
}

/// A fixed list of rows, e.g. LIAISON_UNIL built by the runner.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedRows {
    pub name: String,
    pub rows: Vec<InequalityRow>,
    pub method: UnilateralMethod,
}

impl UnilateralSource for FixedRows {
    fn name(&self) -> String {
        self.name.clone()
    }
    fn method(&self) -> UnilateralMethod {
        self.method
    }
    fn rows(&mut self, _state: &State) -> Result<Vec<InequalityRow>, FemError> {
        Ok(self.rows.clone())
    }
}

/// A borrowed source: lets the caller keep the source (and read what it
/// recorded in [`UnilateralSource::converged`]) after the solve.
impl<T: UnilateralSource + ?Sized> UnilateralSource for &mut T {
    fn name(&self) -> String {
        (**self).name()
    }
    fn method(&self) -> UnilateralMethod {
        (**self).method()
    }
    fn geometry_update(&self) -> GeometryUpdate {
        (**self).geometry_update()
    }
    fn outer_loops(&self) -> OuterLoops {
        (**self).outer_loops()
    }
    fn rows(&mut self, state: &State) -> Result<Vec<InequalityRow>, FemError> {
        (**self).rows(state)
    }
    fn converged(&mut self, state: &State, outcomes: &[RowOutcome]) -> Result<(), FemError> {
        (**self).converged(state, outcomes)
    }
    fn augmented_terms(&self) -> Vec<AugmentedTerm> {
        (**self).augmented_terms()
    }
}
