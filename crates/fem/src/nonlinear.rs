//! The incremental static solver (`STAT_NON_LINE`, and `MECA_STATIQUE` as a
//! single linear step).
//!
//! Per time step: the eliminated values and loads at t are applied, then
//! Newton iterations solve
//!
//! ```text
//! [ K_ff  Aᵀ ] [Δu] = [ f_ext − f_int(u) − penalty(u) ]
//! [ A     0  ] [λ ]   [ d − A u                        ]
//! ```
//!
//! where the rows of A are the dualised conditions (DDL_IMPO, LIAISON_DDL)
//! and the active inequality rows; λ are total multipliers (reactions).
//! The active set is updated after each solve (primal-dual active set:
//! a row enters when violated, leaves when its multiplier is negative); the
//! step has converged when the active set is stable and the residual
//! criteria hold.
//!
//! Residual criteria (as code_aster's):
//! - `RESI_GLOB_MAXI` = ‖r‖∞ over the non-eliminated DOFs, with
//!   r = f_ext − f_int − Aᵀλ − penalty forces;
//! - `RESI_GLOB_RELA` = ‖r‖∞ / ‖f_ext + reactions‖∞ where the reactions are
//!   −Aᵀλ − penalty forces on free DOFs and f_int − f_ext on eliminated DOFs
//!   (so the reference is the load actually carried, supports included).
//!   When that reference vanishes (no load at all) the step is converged
//!   when ‖r‖∞ ≤ 1e-6 × (largest |Kᵢᵢ| × largest |u|) or is 0.

use crate::assembly::{assemble_stiffness, restrict};
use crate::behaviour::{Behaviours, PlasticCells};
use crate::error::FemError;
use crate::force_source::{self, ForceSource, ForceStep};
use crate::held;
use crate::linalg::{self, Csc, SolveFailure};
use crate::loads::Loads;
use crate::model::Model;
use crate::post::{self, CellValues};
use crate::solver_constrained::{self, KktSolver, MatrixKey};
use crate::unilateral::{
    AugmentedTerm, GeometryUpdate, InequalityRow, OuterLoops, RowOutcome, State, UnilateralMethod,
    UnilateralSource,
};

/// `NEWTON(PREDICTION=…)`: the matrix of the first iteration of a step.
/// `Tangente` (and `DeplCalcule`, `Extrapole`, which only change the first
/// iterate in code_aster) uses the tangent at the converged state,
/// `Elastique` the elastic stiffness. All give the same steps for linear
/// elasticity.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Prediction {
    #[default]
    Tangente,
    Elastique,
    DeplCalcule,
    Extrapole,
}

/// `NEWTON(MATRICE=…)`: the matrix of the Newton iterations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MatrixKind {
    /// `TANGENTE`: the consistent tangent, reassembled every `REAC_ITER`
    /// iterations.
    #[default]
    Tangente,
    /// `ELASTIQUE`: the elastic stiffness throughout (more iterations,
    /// never reassembled).
    Elastique,
}

/// `NEWTON` keywords.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions {
    pub prediction: Prediction,
    /// `REAC_ITER`: reassemble the tangent every n iterations (0: keep the
    /// prediction's matrix for the whole step). The elastic tangent is
    /// constant, so this only matters with a plastic behaviour.
    pub reac_iter: usize,
    pub matrix: MatrixKind,
    /// `MATR_RIGI_SYME='OUI'`: a non-symmetric tangent (SIMO_MIEHE) is
    /// replaced by its symmetric part (K + Kᵀ)/2.
    pub symmetrize: bool,
    /// `RECH_LINEAIRE`: a line search along each Newton correction after
    /// the prediction ([`crate::line_search`]).
    pub line_search: Option<crate::line_search::LineSearch>,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            prediction: Prediction::Tangente,
            reac_iter: 1,
            matrix: MatrixKind::Tangente,
            symmetrize: false,
            line_search: None,
        }
    }
}

/// `CONVERGENCE` keywords.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Convergence {
    /// `RESI_GLOB_RELA` (default 1e-6 when neither criterion is given).
    pub resi_glob_rela: Option<f64>,
    /// `RESI_GLOB_MAXI`.
    pub resi_glob_maxi: Option<f64>,
    /// `ITER_GLOB_MAXI` (default 10): at most that many residual checks
    /// per step, the prediction's included (code_aster's `nmconv`).
    pub iter_glob_maxi: usize,
    /// `VERIF='AU_MOINS_UN'`: with both residual criteria given, either
    /// one met is convergence (default `'TOUT'`: both).
    pub at_least_one: bool,
}

impl Default for Convergence {
    fn default() -> Self {
        Convergence {
            resi_glob_rela: Some(1e-6),
            resi_glob_maxi: None,
            iter_glob_maxi: 10,
            at_least_one: false,
        }
    }
}

/// An initial state (`ETAT_INIT`): total displacement per DOF index.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InitialState {
    pub time: Option<f64>,
    pub displacement: Vec<f64>,
    /// The behaviour cells' converged state at that displacement (an
    /// analysis continued from its last step, [`NonLinearResult::final_state`]).
    pub behaviour: Option<std::rc::Rc<crate::behaviour::BehaviourState>>,
    /// The force sources' own unknowns at that state (same sources).
    pub own_unknowns: Option<Vec<Vec<f64>>>,
}

/// One stored step of a result.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub nume_ordre: usize,
    pub time: f64,
    /// DEPL, per DOF index of the model's numbering.
    pub displacement: Vec<f64>,
    /// SIEF_ELGA.
    pub stress: Vec<CellValues>,
    /// VARI_ELGA: internal variables (none for ELAS: empty per cell).
    pub internal_variables: Vec<CellValues>,
    /// Multipliers of the dualised rows, in the order of
    /// [`Loads::equality_rows`]; the reaction on the structure is −λ·row.
    pub multipliers: Vec<f64>,
    /// Outcome of each unilateral source's rows (same order as the sources).
    pub unilateral: Vec<Vec<RowOutcome>>,
    /// Linear solves of the step, active-set changes included (0 for the
    /// initial state).
    pub iterations: usize,
    /// Newton iterations proper, as code_aster counts them against
    /// ITER_GLOB_MAXI (its `ITER_GLOB`): over the whole geometric loop,
    /// active-set changes excluded, except that a source whose loops are
    /// outside Newton ([`OuterLoops`]) restarts the count with each new
    /// pass (0 for the initial state).
    pub newton_iterations: usize,
    pub resi_glob_rela: f64,
    pub resi_glob_maxi: f64,
    /// RESI_GLOB_RELA after each Newton iteration of the step (code_aster's
    /// convergence table; empty for the initial state).
    pub residual_history: Vec<f64>,
    /// VITE and ACCE of a dynamic analysis (see [`IncrementTerms`]), per
    /// DOF index; `None` in statics.
    pub motion: Option<Motion>,
    /// The own unknowns of each force source (same order as
    /// [`StaticNonLinear::forces`]) at the step.
    pub own_unknowns: Vec<Vec<f64>>,
}

/// Velocity and acceleration per DOF index.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    pub velocity: Vec<f64>,
    pub acceleration: Vec<f64>,
}

/// What a time integrator (`dynamics`) adds to every increment of the
/// Newton loop: a matrix added to the stiffness (constant during the
/// increment) and a force affine in the displacement,
/// `matrix·(u − uₙ) − offset` (inertia and damping), uₙ the converged
/// displacement the increment starts from. STAT_NON_LINE has none;
/// DYNA_NON_LINE runs the same loop with one.
///
/// The force is taken on the increment u − uₙ, as code_aster accumulates
/// the acceleration from the Newton corrections: `matrix·u − offset'`
/// would subtract two terms of size M uₙ/(βΔt²) and leave their round-off
/// (an acceleration noise of ulp(uₙ)/(βΔt²), 0.4 mm/s² per ulp on SDNV103E)
/// in every residual.
pub trait IncrementTerms {
    /// Starts the increment `from` → `to` from the last converged
    /// displacement `u`. Returns whether [`matrix`](Self::matrix) changed
    /// since the previous increment (its factorisation is then redone).
    fn begin(&mut self, from: f64, to: f64, u: &[f64]) -> Result<bool, FemError>;
    /// The matrix over all DOFs, in the stiffness pattern.
    fn matrix(&self) -> &Csc;
    /// The constant part of the force (moved to the external forces).
    fn offset(&self) -> &[f64];
    /// The part of the force that moves with the iterate `u`:
    /// `matrix·(u − uₙ)`.
    fn force(&self, u: &[f64]) -> Vec<f64>;
    /// The largest inertia force code_aster adds to the residual's
    /// reference (`RESI_GLOB_RELA`) at the iterate `u`.
    fn reference(&self, u: &[f64]) -> f64;
    /// Whether [`converged`](Self::converged) needs the internal forces
    /// (multi-step schemes).
    fn needs_internal_forces(&self) -> bool;
    /// The increment converged at `u` (external forces at `to`, internal
    /// forces when asked for).
    fn converged(&mut self, to: f64, u: &[f64], fext: &[f64], fint: Option<&[f64]>);
    /// The last converged state's velocity and acceleration.
    fn motion(&self) -> Motion;
    /// Whether the mass holds every free DOF, so that a rigid-body mode
    /// not held by conditions is no error (an impacting body).
    fn mass_holds(&self) -> bool;
    /// Whether the integrator keeps an energy balance (`ENERGIE`): then
    /// [`balance`](Self::balance) is called after each converged increment.
    fn wants_balance(&self) -> bool {
        false
    }
    /// The forces of the increment just converged (after
    /// [`converged`](Self::converged)), for the energy balance.
    fn balance(&mut self, _to: f64, _forces: &ConvergedForces) {}
    /// The energy balance's rows so far (empty without one).
    fn energy_rows(&self) -> Vec<crate::energy_balance::EnergyRow> {
        Vec::new()
    }
}

/// The forces of a converged increment, per DOF index, for the energy
/// balance ([`IncrementTerms::balance`]).
pub struct ConvergedForces<'a> {
    /// The loads at the increment's end.
    pub loads: &'a [f64],
    /// Internal forces (B^Tσ, springs), without inertia nor damping.
    pub internal: &'a [f64],
    /// Contact and unilateral forces, on the internal-force side.
    pub links: &'a [f64],
    /// Reactions of the dualised rows on the structure (−Σ λ·row).
    pub reactions: &'a [f64],
    /// DOFs eliminated by conditions (their reactions follow from the
    /// equilibrium).
    pub eliminated: &'a [usize],
}

/// A result: the stored steps (the first is the initial state).
#[derive(Clone, Debug, PartialEq)]
pub struct NonLinearResult {
    pub steps: Vec<Step>,
    /// Every increment tried, in order — failed ones and the pieces of cut
    /// ones included (the `INFO=2` convergence table).
    pub attempts: Vec<Attempt>,
    /// The energy balance of a dynamic analysis with `ENERGIE` (code_aster's
    /// `PARA_CALC` rows: the initial state, then every converged
    /// increment, pieces of cut ones included); empty otherwise.
    pub energy: Vec<crate::energy_balance::EnergyRow>,
    /// The time of the last step and the behaviour cells' state there
    /// (`None` without behaviour cells), to continue the analysis from it.
    pub final_state: Option<(f64, std::rc::Rc<crate::behaviour::BehaviourState>)>,
}

/// One increment tried by STAT_NON_LINE (a whole step or a piece of a cut
/// one).
#[derive(Clone, Debug, PartialEq)]
pub struct Attempt {
    /// From this time…
    pub from: f64,
    /// …to this one.
    pub to: f64,
    /// Cutting level: 0 for an increment of the list, 1 for a piece of a
    /// cut one, and so on.
    pub level: usize,
    /// Newton iterations done (code_aster's count).
    pub iterations: usize,
    /// RESI_GLOB_RELA after each Newton iteration.
    pub residuals: Vec<f64>,
    /// `None` when it converged; the reason it failed otherwise.
    pub failure: Option<String>,
    /// Whether the failure made the increment be cut (else it stopped the
    /// analysis).
    pub cut: bool,
}

impl NonLinearResult {
    /// The step stored at a time (within a relative precision).
    pub fn at_time(&self, t: f64, precision: f64) -> Option<&Step> {
        self.steps
            .iter()
            .find(|s| (s.time - t).abs() <= precision * t.abs().max(1e-300) || s.time == t)
    }

    pub fn by_order(&self, nume_ordre: usize) -> Option<&Step> {
        self.steps.iter().find(|s| s.nume_ordre == nume_ordre)
    }

    pub fn last(&self) -> Option<&Step> {
        self.steps.last()
    }
}

/// `MECA_STATIQUE`: a linear static solve at each instant (default the
/// single instant 0), stored with NUME_ORDRE 1, 2, … Unilateral sources are
/// not allowed (code_aster's MECA_STATIQUE has none).
pub fn meca_statique(
    model: &Model,
    loads: &Loads,
    instants: &[f64],
) -> Result<NonLinearResult, FemError> {
    if model.has_stabilised() {
        return Err(FemError::Model(
            "the under-integrated HEXA8 of 3D_SI (code_aster's MECA_HEXS8) is computed by the non-linear operators only: its linear stiffness (te0392) is not reproduced".into(),
        ));
    }
    let mut s = StaticNonLinear {
        instants: instants.to_vec(),
        first_order: 1,
        // Independent linear solves: nothing to cut.
        subdivision: None,
        ..Default::default()
    };
    s.run(model, loads, true)
}

/// `STAT_NON_LINE`.
pub struct StaticNonLinear<'s> {
    /// The time list (`INCREMENT/LIST_INST`).
    pub instants: Vec<f64>,
    /// `INST_INIT` (default: initial state's time, else the first instant).
    pub init_time: Option<f64>,
    /// `INST_FIN` (default: the last instant).
    pub final_time: Option<f64>,
    pub initial: Option<InitialState>,
    pub newton: NewtonOptions,
    pub convergence: Convergence,
    pub sources: Vec<Box<dyn UnilateralSource + 's>>,
    /// Force sources with their own unknowns (contact with friction),
    /// solved by a generalised Newton method ([`crate::force_source`]).
    pub forces: Vec<Box<dyn ForceSource + 's>>,
    /// Bound on active-set updates per step.
    pub active_set_max_iter: usize,
    /// NUME_ORDRE of the first stored step (the initial state).
    pub first_order: usize,
    /// `COMPORTEMENT`: the plastic cells (default: all elastic).
    pub behaviours: Behaviours,
    /// Step cutting when an increment fails (`None`: ACTION='ARRET', fail).
    pub subdivision: Option<Subdivision>,
    /// Inertia and damping of a dynamic analysis (`None`: statics).
    pub dynamics: Option<Box<dyn IncrementTerms + 's>>,
    /// Why a cut increment would not reproduce the reference (`Some`: an
    /// increment that fails is not cut, the analysis stops with
    /// [`FemError::CutNotReproduced`]): where the answer depends on which
    /// increments are cut and the iterates that decide it are not exactly
    /// code_aster's.
    pub cut_refused: Option<String>,
    /// `ECHEC/EVENEMENT='INTERPENETRATION'` with `ACTION='ADAPT_COEF_PENA'`:
    /// each converged increment is offered to the force sources, which may
    /// raise their penalty and have it redone ([`ForceSource::adapt_penalty`]).
    pub penalty_adaptation: Option<crate::force_source::PenaltyAdaptation>,
}

/// `DEFI_LIST_INST/ECHEC=_F(ACTION='DECOUPE')`: a failed increment
/// (Newton or active set not converging, a poor solve) is cut into
/// `pieces` equal ones, at most `max_level` times in a row, never below
/// `min_step`; beyond that the analysis stops with
/// [`FemError::StepCutting`]. Elastic steps are cut too: with contact a
/// smaller increment changes the pairing and the active set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Subdivision {
    /// `SUBD_PAS` (default 4).
    pub pieces: usize,
    /// `SUBD_NIVEAU` (default 3).
    pub max_level: usize,
    /// `SUBD_PAS_MINI`.
    pub min_step: f64,
}

impl Default for Subdivision {
    fn default() -> Self {
        Subdivision {
            pieces: 4,
            max_level: 3,
            min_step: 0.0,
        }
    }
}

impl Default for StaticNonLinear<'_> {
    fn default() -> Self {
        StaticNonLinear {
            instants: Vec::new(),
            init_time: None,
            final_time: None,
            initial: None,
            newton: NewtonOptions::default(),
            convergence: Convergence::default(),
            sources: Vec::new(),
            forces: Vec::new(),
            active_set_max_iter: 100,
            first_order: 0,
            behaviours: Behaviours::default(),
            subdivision: Some(Subdivision::default()),
            cut_refused: None,
            penalty_adaptation: None,
            dynamics: None,
        }
    }
}

/// Time precision when comparing instants.
const TIME_EPS: f64 = 1e-9;

#[derive(Clone)]
struct SourceRows {
    rows: Vec<InequalityRow>,
    /// Rows as (dof index, coef).
    idx: Vec<Vec<(usize, f64)>>,
    active: Vec<bool>,
    method: UnilateralMethod,
    update: GeometryUpdate,
    outer: OuterLoops,
    /// The source's augmented terms (`UnilateralSource::augmented_terms`).
    aug: Vec<AugRow>,
    /// Penalty rows: the gaps carried from iteration to iteration by the
    /// Newton corrections (`None`: taken from the iterate on next use).
    tracked: Option<Vec<f64>>,
}

/// Where the augmented terms' tangent goes: the free-unknown map and the
/// triplets it adds to.
type AugmentedMatrix<'a> = (&'a [usize], &'a mut Vec<(usize, usize, f64)>);

/// An augmented term in DOF indices, with its contact status.
#[derive(Clone)]
struct AugRow {
    idx: Vec<(usize, f64)>,
    rhs: f64,
    /// coef · weight: the stiffness of the term.
    stiffness: f64,
    coef: f64,
    support: Vec<(usize, f64)>,
    on: bool,
}

impl SourceRows {
    /// The gaps of the penalty rows, as code_aster's discrete penalty
    /// (`cfjein`) carries them: taken from the geometry once (a new pairing,
    /// a new step), then updated by each Newton correction δ alone,
    /// g ← g + a·δ (code_aster's JEUITE − A·DDEPLA). Recomputing a·u − b on
    /// the total displacement instead rounds the gap at ε·|u|, which the
    /// penalty multiplies by E_N: with E_N = 1e10 the residual then stalls
    /// near 1e-8 and a tight RESI_GLOB_MAXI is never met (ssnv104d).
    fn penalty_gaps(&mut self, u: &[f64]) -> &[f64] {
        if self.tracked.is_none() {
            let g = self
                .rows
                .iter()
                .zip(&self.idx)
                .map(|(row, idx)| gap(idx, row.rhs, u))
                .collect();
            self.tracked = Some(g);
        }
        self.tracked.as_deref().unwrap_or(&[])
    }

    /// Carries the tracked penalty gaps over a Newton correction `delta`
    /// (per DOF index; eliminated DOFs do not move within a step).
    fn advance_penalty_gaps(&mut self, delta: &[f64]) {
        if let Some(g) = self.tracked.as_mut() {
            for (g, idx) in g.iter_mut().zip(&self.idx) {
                *g += idx.iter().map(|&(i, c)| c * delta[i]).sum::<f64>();
            }
        }
    }

    /// The active flags of the rows and the augmented terms, for the
    /// cycling test.
    fn state(&self) -> Vec<bool> {
        self.active
            .iter()
            .copied()
            .chain(self.aug.iter().map(|a| a.on))
            .collect()
    }

    /// Adds the penalty forces (and, with `matrix`, their stiffness on the
    /// free unknowns `map`) of the augmented terms that are on.
    fn add_augmented(&self, u: &[f64], force: &mut [f64], matrix: Option<AugmentedMatrix<'_>>) {
        let mut matrix = matrix;
        for a in self.aug.iter().filter(|a| a.on) {
            let g = gap(&a.idx, a.rhs, u);
            for &(i, ci) in &a.idx {
                force[i] += a.stiffness * ci * g;
                if let Some((map, extra)) = matrix.as_mut() {
                    if map[i] == usize::MAX {
                        continue;
                    }
                    for &(j, cj) in &a.idx {
                        if map[j] != usize::MAX {
                            extra.push((map[i], map[j], a.stiffness * ci * cj));
                        }
                    }
                }
            }
        }
    }
}

impl StaticNonLinear<'_> {
    /// Runs the analysis.
    pub fn solve(&mut self, model: &Model, loads: &Loads) -> Result<NonLinearResult, FemError> {
        crate::newton_timing::begin_solve();
        let r = self.run(model, loads, false);
        crate::newton_timing::end_solve("non-linear solve");
        r
    }

    /// `linear`: every instant is an independent linear solve from a zero
    /// state and no initial state is stored (`MECA_STATIQUE`).
    fn run(
        &mut self,
        model: &Model,
        loads: &Loads,
        linear: bool,
    ) -> Result<NonLinearResult, FemError> {
        loads.validate(model)?;
        let nd = model.dofs().len();
        let (t0, times) = if linear {
            if self.instants.is_empty() {
                (0.0, vec![0.0])
            } else {
                (f64::NAN, self.instants.clone())
            }
        } else {
            self.schedule()?
        };
        let mut u = match &self.initial {
            Some(init) => {
                if init.displacement.len() != nd {
                    return Err(FemError::Model(format!(
                        "initial state has {} displacement values, the model has {nd} degrees of freedom",
                        init.displacement.len()
                    )));
                }
                init.displacement.clone()
            }
            None => vec![0.0; nd],
        };
        let mut plastic = if linear {
            None
        } else {
            PlasticCells::new(model, &self.behaviours, self.newton.symmetrize)?
        };
        let restored = match (
            &mut plastic,
            self.initial.as_ref().and_then(|i| i.behaviour.as_ref()),
        ) {
            (Some(pc), Some(state)) => {
                pc.restore(state)?;
                true
            }
            _ => false,
        };
        if plastic.is_some() && !restored && u.iter().any(|&v| v != 0.0) {
            return Err(FemError::Model(
                "an initial state (ETAT_INIT) with a plastic behaviour needs its stresses and internal variables; only a displacement was given: start from the undeformed state or use ELAS".into(),
            ));
        }
        let k = assemble_stiffness(model)?;
        let kdiag_max = k.diagonal().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // Eliminated DOFs (the set is fixed; values depend on t).
        let elim0 = loads.eliminated(model, times.first().copied().unwrap_or(t0))?;
        let mut map = vec![0usize; nd];
        let mut nfree = 0;
        for (i, m) in map.iter_mut().enumerate() {
            if elim0.contains_key(&i) {
                *m = usize::MAX;
            } else {
                *m = nfree;
                nfree += 1;
            }
        }
        let kff = restrict(&k, &map, nfree);
        let free_dof: Vec<usize> = (0..nd).filter(|&i| map[i] != usize::MAX).collect();
        let free_coords: Vec<[f64; 3]> = free_dof
            .iter()
            .map(|&i| model.mesh().coord(model.dofs().dof(i).node))
            .collect();
        // Factorisations kept across iterations and steps.
        let mut kkt = KktSolver::default();
        if !self.forces.is_empty() && !self.sources.is_empty() {
            return Err(FemError::Model(format!(
                "{} and {} cannot be solved together (a force source with its own unknowns beside inequality rows)",
                self.forces[0].name(),
                self.sources[0].name()
            )));
        }
        let mut own: Vec<Vec<f64>> = self
            .forces
            .iter()
            .map(|f| vec![0.0; f.unknowns()])
            .collect();
        if let Some(o) = self.initial.as_ref().and_then(|i| i.own_unknowns.as_ref()) {
            if o.len() != own.len() || o.iter().zip(&own).any(|(a, b)| a.len() != b.len()) {
                return Err(FemError::Model(
                    "the initial state's contact unknowns are not this analysis' (another contact definition)".into(),
                ));
            }
            own.clone_from(o);
        }

        let mut steps = Vec::with_capacity(times.len() + 1);
        if !linear {
            let (stress, internal_variables) = step_fields(model, loads, plastic.as_ref(), &u, t0)?;
            steps.push(Step {
                nume_ordre: self.first_order,
                time: t0,
                stress,
                internal_variables,
                multipliers: vec![
                    0.0;
                    loads.equality_rows(model, t0).map(|r| r.len()).unwrap_or(0)
                ],
                unilateral: vec![Vec::new(); self.sources.len()],
                displacement: u.clone(),
                iterations: 0,
                newton_iterations: 0,
                resi_glob_rela: 0.0,
                resi_glob_maxi: 0.0,
                residual_history: Vec::new(),
                motion: self.dynamics.as_ref().map(|d| d.motion()),
                own_unknowns: own.clone(),
            });
        }
        // Dynamics: K + the integrator's matrix, rebuilt when it changes
        // (a new time step), and its restriction to the free DOFs.
        let mut k_dyn: Option<Csc> = None;
        let mass_holds = self.dynamics.as_ref().is_some_and(|d| d.mass_holds());

        let mut attempts: Vec<Attempt> = Vec::new();
        let mut history = LoadHistory::default();
        let mut srcs: Vec<Option<SourceRows>> = (0..self.sources.len()).map(|_| None).collect();
        let mut checked_held = false;
        let mut t_prev = t0;
        for &t in times.iter() {
            if linear {
                u.iter_mut().for_each(|v| *v = 0.0);
            }
            // The increment to t, cut into pieces when it fails
            // (`subdivision`: DEFI_LIST_INST/ECHEC, code_aster's default
            // DECOUPE, SUBD_PAS=4, SUBD_NIVEAU=3); `pending` holds the
            // instants still to reach, the next on top, with their level.
            let mut pending: Vec<(f64, usize)> = vec![(t, 0)];
            let mut from = t_prev;
            let mut converged = false;
            while let Some(&(target, level)) = pending.last() {
                let saved = (u.clone(), srcs.clone(), own.clone());
                if let Some(pc) = plastic.as_mut() {
                    pc.set_step(target - from);
                    pc.set_instants(from, target)?;
                }
                // Force sources start the increment from the last converged
                // state (before the new imposed values).
                for (f, o) in self.forces.iter_mut().zip(own.iter_mut()) {
                    let state = State {
                        mesh: model.mesh(),
                        dofs: model.dofs(),
                        displacement: &u,
                        time: target,
                    };
                    crate::newton_timing::timed(crate::newton_timing::Phase::Contact, || {
                        f.begin_increment(&state, o)
                    })?;
                }
                if let Some(d) = self.dynamics.as_mut() {
                    // The predictor starts from the converged state (before
                    // the imposed values of `target` are set).
                    if d.begin(from, target, &u)? || k_dyn.is_none() {
                        let mut ke = k.clone();
                        for (v, a) in ke.values.iter_mut().zip(&d.matrix().values) {
                            *v += a;
                        }
                        k_dyn = Some(restrict(&ke, &map, nfree));
                        kkt = KktSolver::default();
                    }
                }
                let elim = loads.eliminated(model, target)?;
                for (&i, &v) in &elim {
                    u[i] = v;
                }
                let fext_loads = loads.external_forces(model, target)?;
                let fext = match &self.dynamics {
                    Some(d) => fext_loads
                        .iter()
                        .zip(d.offset())
                        .map(|(a, b)| a + b)
                        .collect(),
                    None => fext_loads.clone(),
                };
                let eq = loads.equality_rows(model, target)?;
                // Rows of the sources, from the last converged state.
                for (s, src) in self.sources.iter_mut().enumerate() {
                    let need = match (&srcs[s], src.geometry_update()) {
                        (None, _) => true,
                        (Some(_), GeometryUpdate::Once) => false,
                        _ => true,
                    };
                    if need {
                        let state = State {
                            mesh: model.mesh(),
                            dofs: model.dofs(),
                            displacement: &u,
                            time: target,
                        };
                        let _t = crate::newton_timing::phase(crate::newton_timing::Phase::Contact);
                        let rows = src.rows(&state)?;
                        let prev_active = srcs[s].as_ref().map(|r| r.active.clone());
                        srcs[s] = Some(make_rows(
                            model,
                            rows,
                            src.augmented_terms(),
                            (src.method(), src.geometry_update(), src.outer_loops()),
                            prev_active,
                            &u,
                        )?);
                    }
                }
                // Force sources (friction) may hold what nothing else does:
                // a singular system is then reported by the factorisation.
                if !checked_held && !mass_holds && self.forces.is_empty() {
                    checked_held = true;
                    let mut ground: Vec<Vec<(usize, f64)>> =
                        elim.keys().map(|&i| vec![(i, 1.0)]).collect();
                    ground.extend(eq.iter().map(|r| r.terms.clone()));
                    for s in srcs.iter().flatten() {
                        ground.extend(s.idx.iter().cloned());
                    }
                    let free = held::free_dofs(model, &ground);
                    if !free.is_empty() {
                        return Err(FemError::Singular { free_dofs: free });
                    }
                }
                // The internal forces are K u (+ the plastic cells), the
                // integrator's force added apart (`IncrementTerms::force`);
                // the solves use K + its matrix.
                let (k_used, kff_used) = match &k_dyn {
                    Some(kef) => (&k, kef),
                    None => (&k, &kff),
                };
                let ctx = StepContext {
                    model,
                    k: k_used,
                    kff: kff_used,
                    map: &map,
                    nfree,
                    kdiag_max,
                    convergence: self.convergence,
                    newton: self.newton,
                    active_set_max_iter: self.active_set_max_iter,
                    coords: &free_coords,
                    free_dof: &free_dof,
                    linear,
                    first: attempts.is_empty(),
                    dynamics: self.dynamics.as_deref(),
                };
                let mut log = AttemptLog::default();
                // The force sources' forces at convergence (energy balance).
                let mut source_forces: Option<Vec<f64>> = None;
                let attempt = if self.forces.is_empty() {
                    newton_step(
                        &ctx,
                        &mut history,
                        &mut log,
                        &saved.0,
                        &elim,
                        &fext,
                        &eq,
                        &mut srcs,
                        &mut self.sources,
                        &mut u,
                        target,
                        &mut plastic,
                        &mut kkt,
                    )
                } else {
                    let fctx = ForceStep {
                        model,
                        k: &k,
                        kff: kff_used,
                        map: &map,
                        nfree,
                        kdiag_max,
                        newton: self.newton,
                        resi_glob_rela: self.convergence.resi_glob_rela,
                        resi_glob_maxi: self.convergence.resi_glob_maxi,
                        iter_glob_maxi: self.convergence.iter_glob_maxi,
                        loops_max: self.active_set_max_iter,
                        dynamics: self.dynamics.as_deref(),
                        coords: &free_coords,
                        free_dof: &free_dof,
                        mass_holds,
                    };
                    force_source::newton_step(
                        &fctx,
                        &fext,
                        &eq,
                        &mut self.forces,
                        &mut own,
                        &mut u,
                        &saved.0,
                        &elim,
                        target,
                        &mut plastic,
                        &mut kkt,
                    )
                    .map(|(solves, lam, rela, maxi, history, its, forces)| {
                        source_forces = Some(forces);
                        (solves, (lam, Vec::new()), rela, maxi, history, its)
                    })
                };

                attempts.push(Attempt {
                    from,
                    to: target,
                    level,
                    iterations: log.iterations,
                    residuals: log.residuals,
                    failure: attempt.as_ref().err().map(|e| e.to_string()),
                    cut: false,
                });
                // code_aster's event INTERPENETRATION (`nmevin`, on the
                // converged increment) and its action ADAPT_COEF_PENA
                // (`nmadcp`): the penalty doubled, the increment redone.
                let attempt = match (attempt, self.penalty_adaptation) {
                    (Ok(outcome), Some(adaptation)) => {
                        let mut redo = None;
                        for f in self.forces.iter_mut() {
                            let state = State {
                                mesh: model.mesh(),
                                dofs: model.dofs(),
                                displacement: &u,
                                time: target,
                            };
                            match f.adapt_penalty(&state, adaptation)? {
                                crate::force_source::PenaltyVerdict::Accepted => {}
                                crate::force_source::PenaltyVerdict::Raised { penetration } => {
                                    redo = Some(penetration);
                                }
                                crate::force_source::PenaltyVerdict::Capped { penetration } => {
                                    return Err(FemError::Source(format!(
                                        "{}: at time {target} the penetration {penetration:.3e} exceeds PENE_MAXI = {:e} with the penalty at COEF_MAXI = {:e} (DEFI_LIST_INST/ECHEC, EVENEMENT='INTERPENETRATION', ACTION='ADAPT_COEF_PENA': the action failed, as code_aster's MECANONLINE10_44)",
                                        f.name(),
                                        adaptation.pene_maxi,
                                        adaptation.coef_maxi
                                    )));
                                }
                            }
                        }
                        if let Some(penetration) = redo {
                            crate::progress::emit(crate::progress::Event::Redo {
                                from,
                                to: target,
                                penetration,
                            });
                            (u, srcs, own) = saved;
                            continue;
                        }
                        Ok(outcome)
                    }
                    (a, _) => a,
                };
                match attempt {
                    Ok(outcome) => {
                        pending.pop();
                        from = target;
                        if let Some(pc) = &mut plastic {
                            pc.commit();
                        }
                        if let Some(d) = self.dynamics.as_mut() {
                            let fint = if d.needs_internal_forces() {
                                Some(internal_forces(model, &k, &mut plastic, &u)?)
                            } else {
                                None
                            };
                            d.converged(target, &u, &fext_loads, fint.as_deref());
                        }
                        // Each converged increment (a piece of a cut one
                        // too) is reported to the sources: contact's
                        // geometric loop measures from its start.
                        for (f, o) in self.forces.iter_mut().zip(&own) {
                            let state = State {
                                mesh: model.mesh(),
                                dofs: model.dofs(),
                                displacement: &u,
                                time: target,
                            };
                            f.converged(&state, o)?;
                        }
                        let outcomes = report_outcomes(
                            model,
                            &mut self.sources,
                            &srcs,
                            &u,
                            target,
                            &outcome.1 .1,
                        )?;
                        if let Some(d) = self.dynamics.as_mut().filter(|d| d.wants_balance()) {
                            let internal = internal_forces(model, &k, &mut plastic, &u)?;
                            let links = link_forces(&u, source_forces.take(), &srcs, &outcomes);
                            let mut reactions = vec![0.0; u.len()];
                            for (row, l) in eq.iter().zip(&outcome.1 .0) {
                                for &(i, c) in &row.terms {
                                    reactions[i] -= c * l;
                                }
                            }
                            let eliminated: Vec<usize> = elim.keys().copied().collect();
                            d.balance(
                                target,
                                &ConvergedForces {
                                    loads: &fext_loads,
                                    internal: &internal,
                                    links: &links,
                                    reactions: &reactions,
                                    eliminated: &eliminated,
                                },
                            );
                        }
                        // Every converged increment is a step of the
                        // result, the pieces of a cut one too: code_aster
                        // inserts them in its list of instants and archives
                        // them (`dinuar`), so they shift the NUME_ORDRE of
                        // the steps after them.
                        let (
                            iterations,
                            lambdas,
                            resi_rela,
                            resi_maxi,
                            residual_history,
                            newton_iterations,
                        ) = outcome;
                        let (stress, internal_variables) =
                            step_fields(model, loads, plastic.as_ref(), &u, target)?;
                        steps.push(Step {
                            nume_ordre: self.first_order + steps.len(),
                            time: target,
                            displacement: u.clone(),
                            stress,
                            internal_variables,
                            multipliers: lambdas.0,
                            unilateral: outcomes,
                            iterations,
                            newton_iterations,
                            resi_glob_rela: resi_rela,
                            resi_glob_maxi: resi_maxi,
                            residual_history,
                            motion: self.dynamics.as_ref().map(|d| d.motion()),
                            own_unknowns: own.clone(),
                        });
                        crate::progress::emit(crate::progress::Event::Converged {
                            time: target,
                            iterations: newton_iterations,
                        });
                        converged = true;
                    }
                    Err(e) => {
                        // DEFI_LIST_INST/ECHEC (EVENEMENT='ERREUR'): a
                        // failed increment — elastic, plastic or contact —
                        // is redone from the last converged state in
                        // SUBD_PAS pieces, at most SUBD_NIVEAU levels deep,
                        // never below SUBD_PAS_MINI.
                        let cuttable = matches!(
                            e,
                            FemError::NoConvergence { .. }
                                | FemError::ActiveSet { .. }
                                | FemError::PoorSolve { .. }
                                | FemError::SourceLoop(_)
                                | FemError::Integration(_)
                        );
                        let Some(sd) = self.subdivision.filter(|_| cuttable) else {
                            return Err(e);
                        };
                        if let Some(reason) = &self.cut_refused {
                            return Err(FemError::CutNotReproduced {
                                from,
                                to: target,
                                reason: reason.clone(),
                                cause: Box::new(e),
                            });
                        }
                        let piece = (target - from) / sd.pieces.max(2) as f64;
                        let limit = if level >= sd.max_level {
                            Some(format!("SUBD_NIVEAU = {} reached", sd.max_level))
                        } else if piece < sd.min_step {
                            Some(format!(
                                "a piece of {piece:e} would be below SUBD_PAS_MINI = {:e}",
                                sd.min_step
                            ))
                        } else {
                            None
                        };
                        if let Some(limit) = limit {
                            if level == 0 && sd.max_level == 0 {
                                return Err(e);
                            }
                            return Err(FemError::StepCutting {
                                from,
                                to: target,
                                levels: level,
                                pieces: sd.pieces,
                                smallest: target - from,
                                limit,
                                cause: Box::new(e),
                            });
                        }
                        if let Some(a) = attempts.last_mut() {
                            a.cut = true;
                        }
                        (u, srcs, own) = saved;
                        pending.pop();
                        let pieces = sd.pieces.max(2);
                        crate::progress::emit(crate::progress::Event::Cut {
                            from,
                            to: target,
                            pieces,
                        });
                        for k in (1..=pieces).rev() {
                            let at = if k == pieces {
                                target
                            } else {
                                from + (target - from) * k as f64 / pieces as f64
                            };
                            pending.push((at, level + 1));
                        }
                    }
                }
            }
            t_prev = t;
            // The pending loop only empties on a converged piece reaching t
            // (a failure returns or pushes its pieces).
            debug_assert!(converged, "no increment computed to time {t}");
        }
        let final_state = plastic.as_ref().and_then(|pc| {
            steps
                .last()
                .map(|st| (st.time, std::rc::Rc::new(pc.snapshot())))
        });
        Ok(NonLinearResult {
            steps,
            attempts,
            energy: Vec::new(),
            final_state,
        })
    }

    /// Initial time and the instants to compute.
    pub(crate) fn schedule(&self) -> Result<(f64, Vec<f64>), FemError> {
        if self.instants.is_empty() {
            return Err(FemError::Model(
                "STAT_NON_LINE needs a list of instants (INCREMENT/LIST_INST)".into(),
            ));
        }
        if let Some(w) = self
            .instants
            .windows(2)
            .find(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
        {
            return Err(FemError::Model(format!(
                "the list of instants must increase strictly ({} is followed by {})",
                w[0], w[1]
            )));
        }
        let t0 = self
            .init_time
            .or(self.initial.as_ref().and_then(|i| i.time))
            .unwrap_or(self.instants[0]);
        let tf = self.final_time.unwrap_or(f64::INFINITY);
        let eps = TIME_EPS * self.instants.iter().fold(1.0f64, |m, t| m.max(t.abs()));
        let times: Vec<f64> = self
            .instants
            .iter()
            .copied()
            .filter(|&t| t > t0 + eps && t <= tf + eps)
            .collect();
        if times.is_empty() {
            return Err(FemError::Model(format!(
                "no instant to compute after INST_INIT = {t0}{}",
                if tf.is_finite() {
                    format!(" up to INST_FIN = {tf}")
                } else {
                    String::new()
                }
            )));
        }
        Ok((t0, times))
    }
}

struct StepContext<'a> {
    model: &'a Model,
    k: &'a Csc,
    kff: &'a Csc,
    map: &'a [usize],
    nfree: usize,
    kdiag_max: f64,
    convergence: Convergence,
    newton: NewtonOptions,
    active_set_max_iter: usize,
    /// Coordinates of the free unknowns (for the fill-reducing ordering).
    coords: &'a [[f64; 3]],
    /// The DOF index of each free unknown.
    free_dof: &'a [usize],
    /// A time integrator's terms (their matrix is already in `k`, `kff`
    /// and their offset in the external forces).
    dynamics: Option<&'a dyn IncrementTerms>,
    /// MECA_STATIQUE: one linear solve is the answer (code_aster checks no
    /// residual there).
    linear: bool,
    /// The first increment of the analysis (code_aster's `nume_inst = 1`).
    first: bool,
}

/// code_aster's swap of convergence criteria (`nmcore_swap`): when the
/// load (applied forces + support reactions) falls to 1e-6 of the smallest
/// load met so far, RESI_GLOB_RELA means nothing and is replaced by
/// RESI_GLOB_MAXI ≤ the maximum residual at the last convergence (never at
/// the first increment).
#[derive(Clone, Copy, Debug, Default)]
struct LoadHistory {
    /// `load_mini`: the reference at the first iteration, then the
    /// smallest reference of a converged iteration without the swap.
    load_mini: Option<f64>,
    /// RESI_GLOB_MAXI at the last convergence.
    last_resi_maxi: Option<f64>,
}

/// Whether the eliminated DOFs `elim`, the `pinned` free unknowns and the
/// equality `relations` (terms over free unknowns; `free_dof` gives each
/// one's DOF) hold the model: what [`KktSolver::solve`] asks before it
/// factorises the stiffness without the pinned unknowns.
pub(crate) fn held_by_rows(
    model: &Model,
    elim: &std::collections::HashMap<usize, f64>,
    free_dof: &[usize],
    pinned: &[usize],
    relations: &solver_constrained::Relations,
) -> bool {
    let mut ground: Vec<Vec<(usize, f64)>> = elim.keys().map(|&i| vec![(i, 1.0)]).collect();
    ground.extend(pinned.iter().map(|&f| vec![(free_dof[f], 1.0)]));
    ground.extend(
        relations
            .iter()
            .map(|t| t.iter().map(|&(f, c)| (free_dof[f], c)).collect()),
    );
    held::free_dofs(model, &ground).is_empty()
}

/// Systems without constraint rows of at least this many unknowns keep the
/// bordered path ([`linalg::solve_with`]), whose nested-dissection
/// Cholesky is split over two threads.
const SCHUR_MAX_UNROWED: usize = 20_000;

type StepOutcome = (usize, (Vec<f64>, Vec<Vec<f64>>), f64, f64, Vec<f64>, usize);

/// What a Newton attempt did, kept whether it converges or not.
#[derive(Default)]
struct AttemptLog {
    iterations: usize,
    residuals: Vec<f64>,
}

/// Newton + active-set iterations of one step. Returns (iterations,
/// (equality multipliers, per-source row multipliers), resi_rela, resi_maxi).
#[allow(clippy::too_many_arguments)]
fn newton_step(
    ctx: &StepContext,
    loads_seen: &mut LoadHistory,
    log: &mut AttemptLog,
    start: &[f64],
    elim: &std::collections::HashMap<usize, f64>,
    fext: &[f64],
    eq: &[crate::loads::EqualityRow],
    srcs: &mut [Option<SourceRows>],
    sources: &mut [Box<dyn UnilateralSource + '_>],
    u: &mut [f64],
    t: f64,
    plastic: &mut Option<PlasticCells>,
    kkt: &mut KktSolver,
) -> Result<StepOutcome, FemError> {
    let StepContext {
        model,
        k,
        kff,
        map,
        nfree,
        kdiag_max,
        convergence,
        newton,
        active_set_max_iter,
        coords,
        free_dof,
        linear,
        first,
        dynamics,
    } = *ctx;
    // With a mass on every free DOF a body need not be held by conditions.
    let mass_holds = dynamics.is_some_and(|d| d.mass_holds());
    // code_aster numbers the Newton iterations of a step from 0 (the
    // prediction) and fails the step at the first one with iterat + 1 ≥
    // ITER_GLOB_MAXI that has not converged (`nmconv`: `itemax`): at most
    // ITER_GLOB_MAXI residual checks, prediction included (SDNV103J, whose
    // ITER_GLOB_MAXI = 5 forces the cuts, is reproduced to 2e-11 with this
    // count and missed by 2 % with one more). The passes of the geometric
    // loop (REAC_GEOM) do not restart the count: the loop is nested in the
    // Newton iterations. Measured on ssnv506c: its step 0.15 → 0.2 takes 14
    // + 3 + 1 iterations over three pairings here; counting them together
    // fails it with ITER_GLOB_MAXI = 15, code_aster cuts it in four
    // (DECOUPE) and the ten TEST_TABLE values then agree to 1e-11, while
    // per-pairing counts keep the full step and miss the value at 0.2 by
    // 2.7 %. The iterations that only change the active set are not Newton
    // iterations (code_aster settles the contact inside one).
    let max_iterations = convergence.iter_glob_maxi.max(1);
    let mut settled = 0usize;
    // The penalty gaps are taken again from this attempt's starting state.
    for sr in srcs.iter_mut().flatten() {
        sr.tracked = None;
    }
    // The internal forces at the current iterate, once computed (the
    // residual of one iteration is the right-hand side of the next).
    let mut fint_now: Option<Vec<f64>> = None;
    // The matrix of the plastic iterations (`None`: the elastic K_ff).
    let mut tangent: Option<Csc> = None;
    let mut tangent_key = MatrixKey::Elastic;
    let trace = std::env::var_os("ASTER_FEM_TRACE").is_some();
    let mut residuals: Vec<f64> = Vec::new();
    // With plastic cells, as code_aster: the active set is settled on the
    // linearised problem of each Newton iteration (same iterate, internal
    // forces and tangent); `outer` counts the Newton iterations proper,
    // `base` holds the iterate and its internal forces while the set moves.
    let mut outer = 0usize;
    let mut new_outer = true;
    // The Newton iteration the last pairing started at (for traces).
    let mut pairing_start = 0usize;
    let mut base: Option<(Vec<f64>, Vec<f64>)> = None;
    // The multipliers of the last solve (the line search moves them by ρ
    // times their increment).
    let mut prev_lam: Option<Vec<f64>> = None;
    {
        let nd = u.len();
        let mut history: Vec<Vec<Vec<bool>>> = Vec::new();
        let mut newton_iter = 0usize;
        let mut set_changes = 0usize;
        // code_aster's count of contact loops (`mmbouc 'Cont'`) of a
        // source whose contact loop is outside Newton (POINT_FIXE): the
        // status evaluations at a converged Newton since the last pairing.
        let mut contact_loops = 0usize;
        // Geometric re-pairings of the increment (progress reports).
        let mut pairings = 0usize;
        let name = |i: usize| -> String {
            if i < nfree {
                let dof = map.iter().position(|&m| m == i).unwrap_or(0);
                model.dofs().dof(dof).describe(model.mesh())
            } else {
                format!("Lagrange multiplier #{}", i - nfree + 1)
            }
        };
        loop {
            // Rows in the system: equalities, then active rows of exact sources.
            let mut rows: Vec<(Vec<(usize, f64)>, f64)> = Vec::new();
            for r in eq {
                rows.push((r.terms.clone(), r.rhs));
            }
            let mut row_of: Vec<Vec<Option<usize>>> = Vec::new();
            // Penalty terms added to the matrix (free indices).
            let mut pen_extra: Vec<(usize, usize, f64)> = Vec::new();
            let mut pen_force = vec![0.0; nd];
            for sr in srcs.iter_mut().flatten() {
                let mut ro = vec![None; sr.rows.len()];
                let gaps: Vec<f64> = match sr.method {
                    UnilateralMethod::Penalty { .. } => sr.penalty_gaps(u).to_vec(),
                    UnilateralMethod::ActiveSet => Vec::new(),
                };
                for (r, row) in sr.rows.iter().enumerate() {
                    if !sr.active[r] {
                        continue;
                    }
                    match sr.method {
                        UnilateralMethod::ActiveSet => {
                            ro[r] = Some(rows.len());
                            rows.push((sr.idx[r].clone(), row.rhs));
                        }
                        UnilateralMethod::Penalty { coef } => {
                            let g = gaps[r];
                            for &(i, ci) in &sr.idx[r] {
                                pen_force[i] += coef * ci * g;
                                if map[i] == usize::MAX {
                                    continue;
                                }
                                for &(j, cj) in &sr.idx[r] {
                                    if map[j] != usize::MAX {
                                        pen_extra.push((map[i], map[j], coef * ci * cj));
                                    }
                                }
                            }
                        }
                    }
                }
                sr.add_augmented(u, &mut pen_force, Some((map, &mut pen_extra)));
                row_of.push(ro);
            }
            let m_rows = rows.len();
            let kept = kept_rows(model, &rows, eq.len(), map, u)?;
            let nk = kept.len();
            // A state where the active conditions leave a rigid-body mode
            // free is reported (instead of factorising a singular matrix).
            if !mass_holds {
                let mut ground: Vec<Vec<(usize, f64)>> =
                    elim.keys().map(|&i| vec![(i, 1.0)]).collect();
                ground.extend(kept.iter().map(|&r| rows[r].0.clone()));
                for sr in srcs.iter().flatten() {
                    if let UnilateralMethod::Penalty { .. } = sr.method {
                        for (r, on) in sr.active.iter().enumerate() {
                            if *on {
                                ground.push(sr.idx[r].clone());
                            }
                        }
                    }
                    ground.extend(sr.aug.iter().filter(|a| a.on).map(|a| a.idx.clone()));
                }
                let free = held::free_dofs(model, &ground);
                if !free.is_empty() {
                    return Err(FemError::Singular { free_dofs: free });
                }
            }
            // The prediction (code_aster's `nmprta`, PREDICTION='TANGENTE'
            // or 'ELASTIQUE'): the increment of the eliminated DOFs
            // (AFFE_CHAR_CINE) is spread through the body by the
            // prediction's tangent solve — the residual is taken at the
            // start of the increment and the imposed increment enters as
            // −K_T Δū — rather than internal forces computed on the state
            // where only the eliminated DOFs moved (whose neighbouring cells
            // would yield in that kinked trial state). Dualised conditions
            // (DDL_IMPO) enter the same solve through their rows, so both
            // ways of imposing give the same iterates. Elastic models are
            // linear: K u is the same either way.
            let predict = plastic.is_some()
                && fint_now.is_none()
                && newton_iter == 0
                && imposed_moved(u, start, elim.keys().copied());
            let mut fint = match fint_now.take() {
                Some(f) => f,
                None if predict => {
                    let u0 = before_imposed(u, start, elim.keys().copied());
                    step_forces(model, k, dynamics, plastic, &u0)?
                }
                None => step_forces(model, k, dynamics, plastic, u)?,
            };
            if let Some(pc) = plastic.as_mut() {
                if new_outer && choose_tangent(&mut tangent, pc, model, kff, map, newton, outer)? {
                    tangent_key = match tangent {
                        Some(_) => kkt.new_tangent(pc.symmetric_tangent()),
                        None => MatrixKey::Elastic,
                    };
                }
                if predict {
                    add_imposed_lift(
                        k,
                        pc,
                        tangent.is_some(),
                        u,
                        start,
                        elim.keys().copied(),
                        &mut fint,
                    );
                }
                base = Some((u.to_vec(), fint.clone()));
            }
            let matrix = tangent.as_ref().unwrap_or(kff);
            // Right-hand side.
            let mut b = vec![0.0; nfree + nk];
            for i in 0..nd {
                if map[i] != usize::MAX {
                    b[map[i]] = fext[i] - fint[i] - pen_force[i];
                }
            }
            for (k, &r) in kept.iter().enumerate() {
                let (terms, rhs) = &rows[r];
                b[nfree + k] = rhs - terms.iter().map(|&(i, c)| c * u[i]).sum::<f64>();
            }
            // The rows over free unknowns, for the Schur-complement solve
            // (large systems without rows keep the bordered path: its
            // nested-dissection Cholesky is split over two threads).
            let free_rows: Vec<Vec<(usize, f64)>> = kept
                .iter()
                .map(|&r| {
                    rows[r]
                        .0
                        .iter()
                        .filter(|(i, _)| map[*i] != usize::MAX)
                        .map(|&(i, c)| (map[i], c))
                        .collect()
                })
                .collect();
            let reduced = if nk == 0 && nfree >= SCHUR_MAX_UNROWED {
                None
            } else {
                let krows: Vec<solver_constrained::Row> = kept
                    .iter()
                    .zip(&free_rows)
                    .enumerate()
                    .map(|(k, (&r, t))| solver_constrained::Row {
                        terms: t,
                        d: b[nfree + k],
                        equality: r < eq.len(),
                    })
                    .collect();
                let held_by = |pinned: &[usize], relations: &solver_constrained::Relations| {
                    mass_holds || held_by_rows(model, elim, free_dof, pinned, relations)
                };
                kkt.solve(
                    tangent_key,
                    matrix,
                    &pen_extra,
                    &krows,
                    &b[..nfree],
                    Some(coords),
                    &held_by,
                )
                .ok()
                .flatten()
            };
            let sol = match reduced {
                Some(sol) => sol,
                None => {
                    let mut extra = pen_extra.clone();
                    for (k, t) in free_rows.iter().enumerate() {
                        for &(i, c) in t {
                            extra.push((nfree + k, i, c));
                            extra.push((i, nfree + k, c));
                        }
                    }
                    let a =
                        crate::newton_timing::timed(crate::newton_timing::Phase::Assembly, || {
                            matrix.with_extra(nfree + nk, extra)
                        });
                    let symmetric = plastic.as_ref().is_none_or(|pc| pc.symmetric_tangent());
                    let spd = nk == 0 && symmetric;
                    linalg::solve_with(&a, &b, nfree, spd, Some(coords)).map_err(|f| match f {
                        SolveFailure::Singular { index } => {
                            let mut ground: Vec<Vec<(usize, f64)>> =
                                elim.keys().map(|&i| vec![(i, 1.0)]).collect();
                            ground.extend(kept.iter().map(|&r| rows[r].0.clone()));
                            let free = held::free_dofs(model, &ground);
                            if !free.is_empty() {
                                FemError::Singular { free_dofs: free }
                            } else {
                                FemError::Singular {
                                    free_dofs: index.map(|i| vec![name(i)]).unwrap_or_default(),
                                }
                            }
                        }
                        other => linalg::failure_to_error(other, name),
                    })?
                }
            };
            let mut delta = vec![0.0; nd];
            for i in 0..nd {
                if map[i] != usize::MAX {
                    delta[i] = sol.x[map[i]];
                }
            }
            let mut lam_rows = vec![0.0; m_rows];
            for (k, &r) in kept.iter().enumerate() {
                lam_rows[r] = sol.x[nfree + k];
            }
            // RECH_LINEAIRE after the prediction (code_aster's `nmdepl`:
            // not at iteration 0): the correction scaled by ρ, the
            // multipliers moved by ρ times their increment as code_aster's
            // DEPPLU (its Lagrange unknowns are in the increment).
            let searched = match newton.line_search {
                Some(ls) if newton_iter > 0 && !linear => {
                    if srcs.iter().any(|s| s.is_some()) {
                        return Err(FemError::Model(
                            "RECH_LINEAIRE with unilateral conditions or discrete contact is not supported".into(),
                        ));
                    }
                    let rho = line_search(
                        &ls, model, k, dynamics, plastic, map, fext, &b, &delta, u, t, trace,
                    )?;
                    if let Some(prev) = prev_lam.as_ref().filter(|p| p.len() == m_rows) {
                        for (l, p) in lam_rows.iter_mut().zip(prev) {
                            *l = p + rho * (*l - p);
                        }
                    }
                    Some(rho)
                }
                _ => None,
            };
            if let Some(rho) = searched {
                for d in delta.iter_mut() {
                    *d *= rho;
                }
            }
            for i in 0..nd {
                u[i] += delta[i];
            }
            for sr in srcs.iter_mut().flatten() {
                sr.advance_penalty_gaps(&delta);
            }
            prev_lam = Some(lam_rows.clone());
            newton_iter += 1;
            crate::newton_timing::count_iteration();
            // Residual at the new iterate.
            let fint = step_forces(model, k, dynamics, plastic, u)?;
            let mut reac = vec![0.0; nd];
            for (r, (terms, _)) in rows.iter().enumerate() {
                for &(i, c) in terms {
                    reac[i] -= c * lam_rows[r];
                }
            }
            let mut pen_new = vec![0.0; nd];
            for sr in srcs.iter_mut().flatten() {
                if let UnilateralMethod::Penalty { coef } = sr.method {
                    let gaps = sr.penalty_gaps(u).to_vec();
                    for r in 0..sr.rows.len() {
                        if sr.active[r] {
                            let g = gaps[r];
                            for &(i, ci) in &sr.idx[r] {
                                pen_new[i] += coef * ci * g;
                            }
                        }
                    }
                }
                sr.add_augmented(u, &mut pen_new, None);
            }
            let mut resi_maxi = 0.0f64;
            let mut reference = 0.0f64;
            // Dynamics: code_aster's reference counts the inertia and
            // damping forces with the external ones (not with the internal
            // forces), and the inertia force of the velocity.
            let dyn_u = dynamics.map(|d| d.force(u));
            let dyn_at = |i: usize| dyn_u.as_ref().map_or(0.0, |f| f[i]);
            for i in 0..nd {
                if map[i] == usize::MAX {
                    reference = reference.max((fint[i] - dyn_at(i)).abs());
                } else {
                    let r = fext[i] - fint[i] + reac[i] - pen_new[i];
                    if trace && r.abs() > resi_maxi {
                        eprintln!("[newton] max residual {r:.3e} at {} fint {:.3e} pen {:.3e} reac {:.3e}", model.dofs().dof(i).describe(model.mesh()), fint[i], pen_new[i], reac[i]);
                    }
                    resi_maxi = resi_maxi.max(r.abs());
                    reference = reference.max((fext[i] - dyn_at(i) + reac[i] - pen_new[i]).abs());
                }
            }
            if let Some(d) = dynamics {
                reference = reference.max(d.reference(u));
            }
            let resi_rela = if reference > 0. {
                resi_maxi / reference
            } else {
                0.0
            };
            if first && newton_iter == 1 && loads_seen.load_mini.is_none() {
                loads_seen.load_mini = Some(reference);
            }
            let swapped = !first
                && convergence.resi_glob_rela.is_some()
                && loads_seen.load_mini.is_some_and(|m| reference <= 1e-6 * m)
                && loads_seen.last_resi_maxi.is_some();
            let converged_resi = if linear {
                // MECA_STATIQUE: the solve is the answer (its accuracy is
                // checked by the solver); a residual against a load that is
                // zero up to round-off means nothing. A solve that leaves
                // the equilibrium unmet (redundant conditions whose
                // reactions blow up, ssls503c) is not an answer.
                let umax = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                if reference > 0. && resi_rela > 1e-6 && resi_maxi > 1e-6 * kdiag_max * umax {
                    return Err(FemError::Model(format!(
                        "the linear solve leaves the equilibrium unmet (RESI_GLOB_RELA = {resi_rela:.3e}, RESI_GLOB_MAXI = {resi_maxi:.3e}): the stiffness with its kinematic conditions is singular or the conditions are redundant"
                    )));
                }
                true
            } else if swapped {
                resi_maxi <= loads_seen.last_resi_maxi.unwrap_or(0.0)
            } else if reference > 0. {
                let rela_ok = convergence
                    .resi_glob_rela
                    .is_none_or(|tol| resi_rela <= tol);
                let maxi_ok = convergence
                    .resi_glob_maxi
                    .is_none_or(|tol| resi_maxi <= tol);
                let both_given =
                    convergence.resi_glob_rela.is_some() && convergence.resi_glob_maxi.is_some();
                if convergence.at_least_one && both_given {
                    rela_ok || maxi_ok
                } else {
                    rela_ok && maxi_ok
                }
            } else {
                let umax = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                resi_maxi <= 1e-6 * kdiag_max * umax || resi_maxi == 0.
            };
            if converged_resi {
                if !swapped {
                    loads_seen.load_mini =
                        Some(loads_seen.load_mini.map_or(reference, |m| m.min(reference)));
                }
                loads_seen.last_resi_maxi = Some(resi_maxi);
            }
            fint_now = Some(fint);
            residuals.push(resi_rela);
            log.residuals.push(resi_rela);
            // Multipliers per source row (exact sources).
            let mut src_lam: Vec<Vec<f64>> = Vec::new();
            let mut changed = false;
            let force_scale = reference.max(1e-300);
            let mut si = 0;
            // Rows leaving the active set: (source, row, score); the most
            // negative score leaves first.
            let mut releases: Vec<(usize, usize, f64)> = Vec::new();
            // A source whose contact loop is outside Newton (POINT_FIXE)
            // starts Newton's count again when its active set changes.
            let mut restart = false;
            // A status of a source with its contact loop outside Newton
            // changed (its rows or its augmented points).
            let mut loop_status_changed = false;
            for (s_no, sr) in srcs.iter_mut().enumerate() {
                let Some(sr) = sr else {
                    src_lam.push(Vec::new());
                    continue;
                };
                let ro = &row_of[si];
                si += 1;
                let mut lam = vec![0.0; sr.rows.len()];
                let length = length_scale(model, u);
                let penetration_tol = gap_tolerance(model, u);
                let tracked = sr.tracked.clone();
                for r in 0..sr.rows.len() {
                    let g = match (sr.method, &tracked) {
                        (UnilateralMethod::Penalty { .. }, Some(t)) => t[r],
                        _ => gap(&sr.idx[r], sr.rows[r].rhs, u),
                    };
                    let now = match sr.method {
                        UnilateralMethod::ActiveSet => {
                            if let Some(k) = ro[r] {
                                lam[r] = lam_rows[k];
                            }
                            if sr.rows[r].bilateral {
                                true
                            } else if sr.active[r] {
                                lam[r] >= -1e-10 * force_scale
                            } else {
                                g > penetration_tol
                            }
                        }
                        // code_aster's status (`compute_ineq_conditions_vector`):
                        // in contact while the gap −g < r8prem, so a row
                        // the penalty brought back to g = 0 stays active
                        // (with `g > 0` it would be released and
                        // re-penetrate: a cycle); bilateral rows always are.
                        UnilateralMethod::Penalty { .. } => {
                            g > -f64::EPSILON || sr.rows[r].bilateral
                        }
                    };
                    if now != sr.active[r] {
                        changed = true;
                        restart |= sr.outer.status_restarts;
                        loop_status_changed |= sr.outer.status_restarts;
                        if !now {
                            let score = match sr.method {
                                UnilateralMethod::ActiveSet => lam[r] / force_scale,
                                UnilateralMethod::Penalty { .. } => g / length,
                            };
                            releases.push((s_no, r, score));
                        }
                        sr.active[r] = now;
                    }
                }
                // Augmented terms: code_aster's status of a point,
                // Σ Nⱼ λⱼ + ρ g > 0 with the multipliers just computed.
                for a in sr.aug.iter_mut() {
                    let pressure: f64 = a
                        .support
                        .iter()
                        .map(|&(r, n)| n * lam.get(r).copied().unwrap_or(0.0))
                        .sum();
                    let now = pressure + a.coef * gap(&a.idx, a.rhs, u) > 0.0;
                    if now != a.on {
                        a.on = now;
                        changed = true;
                        loop_status_changed |= sr.outer.status_restarts;
                    }
                }
                src_lam.push(lam);
            }
            // code_aster's flip rule for a contact loop outside Newton
            // (ALGO_RESO_CONT='POINT_FIXE'): see [`flip_ends_contact_loop`].
            // The new statuses are kept for what follows.
            if changed && loop_status_changed && converged_resi {
                contact_loops += 1;
                let loops = srcs
                    .iter()
                    .flatten()
                    .zip(&src_lam)
                    .filter(|(sr, _)| sr.outer.status_restarts)
                    .map(|(_, lam)| lam.as_slice());
                if flip_ends_contact_loop(contact_loops, loops) {
                    changed = false;
                }
            } else if converged_resi && !changed {
                contact_loops += 1;
            }
            // Releasing every row in tension at once may leave the model
            // unheld (a body resting on its supports): then release only the
            // most negative one.
            if releases.len() > 1 && !mass_holds {
                let mut ground: Vec<Vec<(usize, f64)>> =
                    elim.keys().map(|&i| vec![(i, 1.0)]).collect();
                ground.extend(eq.iter().map(|r| r.terms.clone()));
                for sr in srcs.iter().flatten() {
                    for (r, on) in sr.active.iter().enumerate() {
                        if *on {
                            ground.push(sr.idx[r].clone());
                        }
                    }
                }
                if !held::free_dofs(model, &ground).is_empty() {
                    let keep = releases
                        .iter()
                        .enumerate()
                        .min_by(|a, b| a.1 .2.total_cmp(&b.1 .2))
                        .map(|(k, _)| k)
                        .unwrap_or(0);
                    for (k, &(s_no, r, _)) in releases.iter().enumerate() {
                        if k != keep {
                            if let Some(sr) = srcs[s_no].as_mut() {
                                sr.active[r] = true;
                            }
                        }
                    }
                }
            }
            crate::progress::emit(crate::progress::Event::Iteration(
                crate::progress::Iteration {
                    time: t,
                    newton: settled + usize::from(!changed),
                    resi_glob_rela: resi_rela,
                    resi_glob_maxi: resi_maxi,
                    contact_iterations: set_changes,
                    pairings,
                    active_set_changed: changed,
                },
            ));
            // Geometry update at each iteration: re-ask the rows at the
            // current iterate; new rows mean another pass.
            if trace {
                eprintln!(
                    "[newton] t={t} solve {newton_iter} iteration {outer} (pairing from {pairing_start}) resi_rela {resi_rela:.3e} active set {}",
                    if changed { "changed" } else { "settled" }
                );
            }
            if restart {
                settled = 0;
            }
            if !changed {
                settled += 1;
            }
            log.iterations = settled;
            if !changed && plastic.is_some() {
                // A Newton iteration with a settled active set: the next
                // one linearises at this iterate.
                outer += 1;
                new_outer = true;
                history.clear();
                set_changes = 0;
            }
            if !changed {
                // A new pairing on the current geometry once Newton has
                // converged with the current one (at once when elastic: a
                // stable active set is a converged solve then).
                if plastic.is_none() || converged_resi {
                    let (new_rows, restarts) = refresh_geometry_rows(model, sources, srcs, u, t)?;
                    changed = new_rows;
                    // A geometric loop outside Newton (POINT_FIXE) starts
                    // Newton's count again with the new pairing.
                    if restarts {
                        settled = 0;
                        log.iterations = 0;
                    }
                }
                if changed {
                    contact_loops = 0;
                    pairing_start = outer;
                    pairings += 1;
                    // New rows: the active sets seen with the previous
                    // ones say nothing about cycling with these.
                    history.clear();
                    set_changes += 1;
                    if set_changes > active_set_max_iter {
                        return Err(FemError::ActiveSet {
                            time: t,
                            message: format!(
                                "the geometry update (REAC_GEOM) does not settle after {active_set_max_iter} passes"
                            ),
                        });
                    }
                    continue;
                }
                if converged_resi {
                    let eq_lam = lam_rows[..eq.len()].to_vec();
                    return Ok((
                        newton_iter,
                        (eq_lam, src_lam),
                        resi_rela,
                        resi_maxi,
                        residuals,
                        settled,
                    ));
                }
                if settled >= max_iterations {
                    return Err(FemError::NoConvergence {
                        time: t,
                        iterations: settled,
                        resi_rela,
                        resi_maxi,
                        cycling: None,
                    });
                }
            } else {
                if let (Some(_), Some((u0, f0))) = (plastic.as_ref(), base.take()) {
                    // Solve the same linearised problem with the new set:
                    // back to its iterate (and the Gauss-point trial states
                    // and tangents there).
                    u.copy_from_slice(&u0);
                    for sr in srcs.iter_mut().flatten() {
                        sr.tracked = None;
                    }
                    step_forces(model, k, dynamics, plastic, u)?;
                    fint_now = Some(f0);
                    new_outer = false;
                }
                set_changes += 1;
                let state: Vec<Vec<bool>> = srcs.iter().flatten().map(|s| s.state()).collect();
                if history.contains(&state) {
                    return Err(FemError::ActiveSet {
                        time: t,
                        message: format!(
                            "the active set cycles after {set_changes} updates ({} rows active): the conditions are probably redundant or conflicting",
                            state.iter().flatten().filter(|&&a| a).count()
                        ),
                    });
                }
                history.push(state);
                if set_changes > active_set_max_iter {
                    return Err(FemError::ActiveSet {
                        time: t,
                        message: format!(
                            "no stable active set after {} updates",
                            active_set_max_iter
                        ),
                    });
                }
            }
        }
    }
}

/// code_aster's flip rule (`nmctcc` with `mm_cycl_flip` and
/// `mm_cycl_d4`) for a contact loop outside Newton
/// (ALGO_RESO_CONT='POINT_FIXE' of the continuous formulation): from the
/// second loop on (`loop_cont_count` ≥ 2), a loop whose statuses changed
/// is declared converged when some point's pressure is near zero
/// (|λ| ≤ 1e-3 × the shortest edge; an inactive point's is 0: that is the
/// test here) and `resi_pressure` < 1e-4 × `cont_pressure`. code_aster
/// measures `resi_pressure`, each point's change of pressure, against
/// 1e12 × the number of points × the longest edge, so the second test
/// holds whenever some pressure is non-zero (`cont_pressure`, the mean
/// pressure of the points in contact, is then positive). `pressures`: the
/// multipliers of each such source's rows after the solve.
fn flip_ends_contact_loop<'a>(
    contact_loops: usize,
    pressures: impl Iterator<Item = &'a [f64]>,
) -> bool {
    if contact_loops < 2 {
        return false;
    }
    let (mut near_zero, mut some_pressure) = (false, false);
    for lam in pressures {
        near_zero |= lam.contains(&0.0);
        some_pressure |= lam.iter().any(|&l| l != 0.0);
    }
    near_zero && some_pressure
}

/// RECH_LINEAIRE on the correction `delta` from `u` (unchanged on
/// return; the behaviour cells are left at the last ρ tried): f(ρ) =
/// Δ · (f_int(u + ρΔ) − f_ext) on the free DOFs, code_aster's `nmrecz`.
/// The reactions of the dualised conditions drop out: after the
/// prediction their rows hold, A Δ = 0, so Δ · Aᵀλ and Δλ · (A u − d)
/// vanish. Under a time scheme the inertia and damping forces stay those
/// of `u` (code_aster's `cnfext` holds them and is not recomputed by
/// `nmrelp`). f(0) is the residual `b` of the solve.
#[allow(clippy::too_many_arguments)]
fn line_search(
    ls: &crate::line_search::LineSearch,
    model: &Model,
    k: &Csc,
    dynamics: Option<&dyn IncrementTerms>,
    plastic: &mut Option<PlasticCells>,
    map: &[usize],
    fext: &[f64],
    b: &[f64],
    delta: &[f64],
    u: &[f64],
    t: f64,
    trace: bool,
) -> Result<f64, FemError> {
    let free: Vec<usize> = (0..u.len()).filter(|&i| map[i] != usize::MAX).collect();
    let f0: f64 = -free.iter().map(|&i| delta[i] * b[map[i]]).sum::<f64>();
    let dyn0 = dynamics.map(|d| d.force(u));
    let mut trial = u.to_vec();
    let outcome = ls.search(f0, |rho| {
        for &i in &free {
            trial[i] = u[i] + rho * delta[i];
        }
        let mut f = step_forces(model, k, dynamics, plastic, &trial)?;
        if let (Some(d), Some(f0)) = (dynamics, dyn0.as_ref()) {
            for ((f, now), then) in f.iter_mut().zip(d.force(&trial)).zip(f0) {
                *f += then - now;
            }
        }
        Ok::<f64, FemError>(free.iter().map(|&i| delta[i] * (f[i] - fext[i])).sum())
    });
    let outcome = match outcome {
        Ok(o) => o,
        Err(crate::line_search::LineSearchError::Evaluation(e)) => return Err(e),
        Err(crate::line_search::LineSearchError::Ascent { f0 }) => {
            return Err(FemError::Model(format!(
                "RECH_LINEAIRE METHODE='MIXTE' at time {t}: the Newton correction is not a descent direction (f(0) = {f0:.6e} > 0); code_aster then searches along the opposite direction and applies the opposite step, not reproduced"
            )))
        }
    };
    if trace {
        eprintln!("[newton] {}", outcome.trace(f0));
    }
    Ok(outcome.rho)
}

/// The rows to dualise among `rows` (the first `n_eq` are equalities, the
/// others active unilateral rows): rows entirely on eliminated DOFs are
/// dropped (an inconsistent equality is an error), and a DOF imposed twice
/// by equalities is kept once, as code_aster imposes one value per node and
/// component (two different values are an error).
pub(crate) fn kept_rows(
    model: &Model,
    rows: &[(Vec<(usize, f64)>, f64)],
    n_eq: usize,
    map: &[usize],
    u: &[f64],
) -> Result<Vec<usize>, FemError> {
    let mut kept = Vec::with_capacity(rows.len());
    let mut imposed: std::collections::HashMap<usize, f64> = Default::default();
    for (r, (terms, rhs)) in rows.iter().enumerate() {
        if terms.iter().all(|&(i, _)| map[i] == usize::MAX) {
            let v: f64 = terms.iter().map(|&(i, c)| c * u[i]).sum();
            if (v - rhs).abs() > 1e-9 * rhs.abs().max(v.abs()).max(1e-300) && r < n_eq {
                return Err(FemError::Model(format!(
                    "a dualised condition on {} contradicts the value imposed by elimination",
                    terms
                        .iter()
                        .map(|&(i, _)| model.dofs().dof(i).describe(model.mesh()))
                        .collect::<Vec<_>>()
                        .join(", ")
                )));
            }
            continue;
        }
        if let ([(i, c)], true) = (terms.as_slice(), r < n_eq) {
            let value = rhs / c;
            match imposed.get(i) {
                Some(&v) if (v - value).abs() <= 1e-12 * v.abs().max(value.abs()) => continue,
                Some(&v) => {
                    return Err(FemError::Model(format!(
                        "{} is imposed twice with different values ({v} and {value})",
                        model.dofs().dof(*i).describe(model.mesh())
                    )))
                }
                None => {
                    imposed.insert(*i, value);
                }
            }
        }
        kept.push(r);
    }
    Ok(kept)
}

/// The outcome of every source's rows at a converged increment (time
/// `t`, multipliers `lambdas` per source row), handed to the sources.
/// The contact and unilateral forces at a converged state, on the
/// internal-force side: the force sources' (friction, continuous contact)
/// and Σ λ·row of every inequality row (its multiplier, or its penalty
/// force).
fn link_forces(
    u: &[f64],
    source_forces: Option<Vec<f64>>,
    srcs: &[Option<SourceRows>],
    outcomes: &[Vec<RowOutcome>],
) -> Vec<f64> {
    let mut links = source_forces.unwrap_or_else(|| vec![0.0; u.len()]);
    for (sr, outs) in srcs.iter().zip(outcomes) {
        let Some(sr) = sr else { continue };
        for (idx, o) in sr.idx.iter().zip(outs) {
            for &(i, c) in idx {
                links[i] += o.multiplier * c;
            }
        }
    }
    links
}

fn report_outcomes(
    model: &Model,
    sources: &mut [Box<dyn UnilateralSource + '_>],
    srcs: &[Option<SourceRows>],
    u: &[f64],
    t: f64,
    lambdas: &[Vec<f64>],
) -> Result<Vec<Vec<RowOutcome>>, FemError> {
    let _t = crate::newton_timing::phase(crate::newton_timing::Phase::Contact);
    let mut unil = Vec::with_capacity(sources.len());
    for (s, src) in sources.iter_mut().enumerate() {
        let Some(sr) = &srcs[s] else {
            unil.push(Vec::new());
            continue;
        };
        let state = State {
            mesh: model.mesh(),
            dofs: model.dofs(),
            displacement: u,
            time: t,
        };
        let outcomes: Vec<RowOutcome> = sr
            .rows
            .iter()
            .enumerate()
            .map(|(r, row)| {
                let g = match (sr.method, &sr.tracked) {
                    (UnilateralMethod::Penalty { .. }, Some(t)) => t[r],
                    _ => gap(&sr.idx[r], row.rhs, u),
                };
                let multiplier = match sr.method {
                    UnilateralMethod::ActiveSet => {
                        if sr.active[r] {
                            lambdas[s][r]
                        } else {
                            0.0
                        }
                    }
                    UnilateralMethod::Penalty { coef } if row.bilateral => coef * g,
                    UnilateralMethod::Penalty { coef } => coef * g.max(0.0),
                };
                RowOutcome {
                    id: row.id,
                    multiplier,
                    active: sr.active[r],
                    violation: g,
                }
            })
            .collect();
        src.converged(&state, &outcomes)?;
        unil.push(outcomes);
    }
    Ok(unil)
}

fn gap(idx: &[(usize, f64)], rhs: f64, u: &[f64]) -> f64 {
    idx.iter().map(|&(i, c)| c * u[i]).sum::<f64>() - rhs
}

/// Characteristic length for gap tolerances: the mesh size plus |u|.
/// The penetration an inactive row may show and stay inactive: 1e-10 of
/// the largest displacement, with a floor of 1e-15 of the model's size (the
/// round-off of gaps computed from coordinates). Relative to the
/// displacement, not to the size: a 4 m rotor turning under a unit moment
/// (sdnl133d) moves by 1e-9 m, and 1e-10 of its size accepted penetrations
/// of the order of the displacements themselves — the active set then
/// settled on states that depend on the load path. code_aster's
/// `CONTRAINTE` algorithm tests gaps against `r8prem()` (`cfpeti`).
fn gap_tolerance(model: &Model, u: &[f64]) -> f64 {
    (1e-10 * max_abs(u))
        .max(1e-15 * model_size(model))
        .max(1e-300)
}

fn length_scale(model: &Model, u: &[f64]) -> f64 {
    model_size(model).max(max_abs(u)).max(1e-300)
}

/// The largest extent of the mesh's bounding box.
fn model_size(model: &Model) -> f64 {
    let (lo, hi) = aster_mesh::bounding_box(model.mesh().coords.iter().copied());
    (0..3).map(|k| (hi[k] - lo[k]).max(0.)).fold(0.0, f64::max)
}

/// The largest displacement component.
fn max_abs(u: &[f64]) -> f64 {
    u.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// f_int(u): K u, plus the plastic cells' corrections (their trial states
/// and consistent tangents are updated on the way).
/// The internal forces of a step's Newton loop: K u, the plastic cells
/// and the time integrator's force (inertia, damping).
/// Whether the step's imposed values (the eliminated DOFs of
/// `AFFE_CHAR_CINE`) moved any DOF from where the step starts.
pub(crate) fn imposed_moved(u: &[f64], start: &[f64], elim: impl Iterator<Item = usize>) -> bool {
    elim.into_iter().any(|i| u[i] != start[i])
}

/// The iterate with the eliminated DOFs back at the step's start: the
/// state where code_aster's prediction (`nmprta`, and code_aster 17's
/// `NewtonSolver` at iteration 0) takes the residual.
pub(crate) fn before_imposed(
    u: &[f64],
    start: &[f64],
    elim: impl Iterator<Item = usize>,
) -> Vec<f64> {
    let mut u0 = u.to_vec();
    for i in elim {
        u0[i] = start[i];
    }
    u0
}

/// The prediction's lifting of the imposed increment: `fint += K_T Δū`
/// where Δū is the move of the eliminated DOFs (the elastic `k`, plus the
/// behaviours' correction when the consistent tangent is used). The
/// increment is then spread through the body by the tangent solve instead
/// of internal forces being computed on the kinked state where only the
/// eliminated DOFs moved (whose neighbouring cells would yield, or invert
/// under finite strains, in that trial state).
pub(crate) fn add_imposed_lift(
    k: &Csc,
    pc: &PlasticCells,
    consistent: bool,
    u: &[f64],
    start: &[f64],
    elim: impl Iterator<Item = usize>,
    fint: &mut [f64],
) {
    let mut du = vec![0.0; u.len()];
    for i in elim {
        du[i] = u[i] - start[i];
    }
    let mut kdu = k.mul(&du);
    if consistent {
        pc.add_tangent_correction_times(&du, &mut kdu);
    }
    for (f, d) in fint.iter_mut().zip(&kdu) {
        *f += d;
    }
}

pub(crate) fn step_forces(
    model: &Model,
    k: &Csc,
    dynamics: Option<&dyn IncrementTerms>,
    plastic: &mut Option<PlasticCells>,
    u: &[f64],
) -> Result<Vec<f64>, FemError> {
    let _t = crate::newton_timing::phase(crate::newton_timing::Phase::Behaviour);
    let mut fint = internal_forces(model, k, plastic, u)?;
    if let Some(d) = dynamics {
        for (f, x) in fint.iter_mut().zip(d.force(u)) {
            *f += x;
        }
    }
    Ok(fint)
}

pub(crate) fn internal_forces(
    model: &Model,
    k: &Csc,
    plastic: &mut Option<PlasticCells>,
    u: &[f64],
) -> Result<Vec<f64>, FemError> {
    let mut fint = k.mul(u);
    if let Some(pc) = plastic.as_mut() {
        pc.update(model, u, &mut fint)?;
    }
    Ok(fint)
}

/// The matrix of Newton iteration `iter` of a step with plastic cells
/// (`None` in `tangent`: the elastic K_ff): iteration 0 uses the
/// prediction (`PREDICTION`), later ones the consistent tangent of the last
/// update every `REAC_ITER` iterations (0: never), `MATRICE='ELASTIQUE'`
/// the elastic stiffness throughout. A tangent with no plastic correction
/// is the elastic K_ff (kept as `None`, so that its factorisation is
/// reused). Returns whether the matrix was set anew.
#[allow(clippy::too_many_arguments)]
pub(crate) fn choose_tangent(
    tangent: &mut Option<Csc>,
    pc: &mut PlasticCells,
    model: &Model,
    kff: &Csc,
    map: &[usize],
    newton: NewtonOptions,
    iter: usize,
) -> Result<bool, FemError> {
    let _t = crate::newton_timing::phase(crate::newton_timing::Phase::Assembly);
    let consistent = |pc: &mut PlasticCells| {
        if pc.tangent_is_elastic() {
            None
        } else {
            Some(pc.tangent_restricted(kff, map))
        }
    };
    if newton.matrix == MatrixKind::Elastique {
        *tangent = None;
        return Ok(true);
    }
    if iter == 0 {
        *tangent = if newton.prediction == Prediction::Elastique && !pc.has_finite_strains() {
            None
        } else {
            // Finite strains: code_aster's RIGI_MECA_ELAS is the tangent
            // at the converged geometry with the elastic material matrix.
            pc.prediction(model, newton.prediction == Prediction::Elastique)?;
            consistent(pc)
        };
        return Ok(true);
    }
    if newton.reac_iter > 0 && iter.is_multiple_of(newton.reac_iter) {
        *tangent = consistent(pc);
        return Ok(true);
    }
    Ok(false)
}

/// Asks every source that updates its geometry at each iteration for its
/// rows at the current iterate `u` and installs the ones that changed
/// (keeping the previous active set as the start). Returns whether any
/// source's rows were replaced, and whether one of those restarts Newton's
/// count with a new pairing ([`OuterLoops::pairing_restarts`]).
fn refresh_geometry_rows(
    model: &Model,
    sources: &mut [Box<dyn UnilateralSource + '_>],
    srcs: &mut [Option<SourceRows>],
    u: &[f64],
    t: f64,
) -> Result<(bool, bool), FemError> {
    let _t = crate::newton_timing::phase(crate::newton_timing::Phase::Contact);
    let mut changed = false;
    let mut restarts = false;
    for (src, slot) in sources.iter_mut().zip(srcs.iter_mut()) {
        let Some(sr) = slot else { continue };
        if sr.update != GeometryUpdate::EachIteration {
            continue;
        }
        let state = State {
            mesh: model.mesh(),
            dofs: model.dofs(),
            displacement: u,
            time: t,
        };
        let rows = src.rows(&state)?;
        if rows == sr.rows {
            continue;
        }
        let prev = Some(sr.active.clone());
        *slot = Some(make_rows(
            model,
            rows,
            src.augmented_terms(),
            (src.method(), src.geometry_update(), src.outer_loops()),
            prev,
            u,
        )?);
        changed = true;
        restarts |= src.outer_loops().pairing_restarts;
    }
    Ok((changed, restarts))
}

fn make_rows(
    model: &Model,
    rows: Vec<InequalityRow>,
    augmented: Vec<AugmentedTerm>,
    (method, update, outer): (UnilateralMethod, GeometryUpdate, OuterLoops),
    prev_active: Option<Vec<bool>>,
    u: &[f64],
) -> Result<SourceRows, FemError> {
    let indices = |row: &InequalityRow| -> Result<Vec<(usize, f64)>, FemError> {
        let mut r = Vec::with_capacity(row.terms.len());
        for &(dof, c) in &row.terms {
            let i = model.dofs().index(dof).ok_or_else(|| {
                FemError::Model(format!(
                    "unilateral condition on {}, which is not a degree of freedom of the model",
                    dof.describe(model.mesh())
                ))
            })?;
            r.push((i, c));
        }
        Ok(r)
    };
    let mut idx = Vec::with_capacity(rows.len());
    for row in &rows {
        idx.push(indices(row)?);
    }
    let active = match prev_active {
        Some(a) if a.len() == rows.len() => a,
        _ => rows
            .iter()
            .zip(&idx)
            // Touching rows start active (gap ≥ −tol): a body resting on
            // its unilateral supports is then held from the first solve;
            // the multiplier test releases the ones in tension.
            .map(|(row, r)| gap(r, row.rhs, u) >= -1e-10 * length_scale(model, u))
            .collect(),
    };
    // Bilateral rows (GLISSIERE) are always enforced.
    let active: Vec<bool> = active
        .into_iter()
        .zip(&rows)
        .map(|(a, row)| a || row.bilateral)
        .collect();
    // An augmented term starts on when one of the rows it rides on is.
    let mut aug = Vec::with_capacity(augmented.len());
    for a in &augmented {
        aug.push(AugRow {
            idx: indices(&a.row)?,
            rhs: a.row.rhs,
            stiffness: a.coef * a.weight,
            coef: a.coef,
            on: a.support.iter().any(|&(r, _)| active.get(r) == Some(&true)),
            support: a.support.clone(),
        });
    }
    Ok(SourceRows {
        rows,
        idx,
        active,
        method,
        update,
        outer,
        aug,
        tracked: None,
    })
}

/// The fields stored with a step: SIEF_ELGA (the free strain's stress
/// taken off) and, with a plastic behaviour, VARI_ELGA — the same for the
/// initial state and every converged increment.
fn step_fields(
    model: &Model,
    loads: &Loads,
    plastic: Option<&PlasticCells>,
    u: &[f64],
    t: f64,
) -> Result<(Vec<CellValues>, Vec<CellValues>), FemError> {
    let mut stress = post::sief_elga(model, u)?;
    loads.subtract_free_strain(model, t, &mut stress)?;
    let internal_variables = match plastic {
        Some(pc) => pc.fields(&mut stress),
        None => Vec::new(),
    };
    Ok((stress, internal_variables))
}

#[cfg(test)]
mod tests {
    use super::flip_ends_contact_loop;

    #[test]
    fn the_flip_rule_ends_a_contact_loop_from_its_second_pass_only() {
        // A point out of contact (λ = 0) beside one pressed: from the
        // second loop on, a change of statuses ends the loop.
        let zone = [0.0, 3.5, 0.0];
        assert!(!flip_ends_contact_loop(1, [&zone[..]].into_iter()));
        assert!(flip_ends_contact_loop(2, [&zone[..]].into_iter()));
        assert!(flip_ends_contact_loop(7, [&zone[..]].into_iter()));
        // Every point pressed: no point near zero, the loop goes on.
        let pressed = [1.0, 3.5, 2.0];
        assert!(!flip_ends_contact_loop(3, [&pressed[..]].into_iter()));
        // No pressure at all (code_aster's cont_pressure = 0): goes on.
        let open = [0.0, 0.0];
        assert!(!flip_ends_contact_loop(3, [&open[..]].into_iter()));
        // Over the zones: one open, one pressed.
        assert!(flip_ends_contact_loop(
            2,
            [&open[..], &pressed[..]].into_iter()
        ));
        // No source with its contact loop outside Newton.
        assert!(!flip_ends_contact_loop(5, std::iter::empty()));
    }
}
