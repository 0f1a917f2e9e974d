//! Force sources: nonlinear contributions to the equilibrium with their own
//! unknowns (contact elements with friction and their multipliers), solved
//! by a generalised Newton method on the whole system.
//!
//! A [`ForceSource`] adds, at the current state, forces to the internal
//! force side of the equilibrium (`f_int + f_src = f_ext`), equations of its
//! own unknowns (e.g. the contact pressure and friction multipliers of the
//! slave nodes), and the derivatives of both with respect to the
//! displacements and its unknowns. The tangent need not be symmetric
//! (friction), so the system is factorised by sparse LU.
//!
//! Per Newton iteration:
//!
//! ```text
//! [ K_ff + ∂f_src/∂u   ∂f_src/∂y   Aᵀ ] [Δu]   [ f_ext − f_int − f_src ]
//! [ ∂g/∂u              ∂g/∂y       0  ] [Δy] = [ −g                    ]
//! [ A                  0           0  ] [λ ]   [ d − A u               ]
//! ```
//!
//! where `y` are the sources' unknowns and `g` their equations. After each
//! solve a source updates its statuses ([`ForceSource::after_iteration`]:
//! contact statuses, pairing on the new geometry); the step has converged
//! when the residual criteria hold and every source reports its statuses
//! settled. A source may then ask for another Newton solve
//! ([`ForceSource::after_convergence`]: code_aster's fixed-point loops on
//! the contact statuses, the friction threshold or the geometry).
//!
//! With `NewtonOptions::line_search` (MECA_NON_LINE's `RECH_LINEAIRE`),
//! each correction after the prediction is scaled by the ρ of
//! [`crate::line_search`] on the projected residual of the whole system,
//! the sources evaluated on the pairing of the iteration's start
//! ([`ForceSource::evaluate_on_pairing`]), as code_aster 17's
//! `SecantLineSearch`.

use crate::behaviour::PlasticCells;
use crate::error::FemError;
use crate::linalg::{self, Csc, SolveFailure};
use crate::loads::EqualityRow;
use crate::model::Model;
use crate::nonlinear::{choose_tangent, kept_rows, step_forces, IncrementTerms, NewtonOptions};
use crate::solver_constrained::{self, KktSolver};
use crate::unilateral::State;

/// An unknown of the system a source contributes to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unknown {
    /// A displacement DOF (index of the model's numbering).
    Dof(usize),
    /// One of the source's own unknowns.
    Own(usize),
}

/// What a source contributes at a state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Contribution {
    /// Forces on the internal-force side, per DOF index (summed when a DOF
    /// appears several times).
    pub forces: Vec<(usize, f64)>,
    /// Residual of each own unknown's equation (length [`ForceSource::unknowns`]).
    pub own_residual: Vec<f64>,
    /// Derivatives (row, column, value) of the forces (rows `Dof`) and of
    /// the own equations (rows `Own`); summed when repeated.
    pub tangent: Vec<(Unknown, Unknown, f64)>,
}

/// What a source decides once Newton has converged.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LoopVerdict {
    /// The state is accepted.
    Done,
    /// Solve again (a fixed-point loop of the source has not converged):
    /// from the start of the step, the Newton iteration count starting
    /// again, or, for a source whose loop
    /// [continues Newton](ForceSource::again_continues_newton), from the
    /// current state.
    Again,
}

/// `DEFI_LIST_INST/ECHEC=_F(EVENEMENT='INTERPENETRATION',
/// ACTION='ADAPT_COEF_PENA')`: after an increment converges, a penalised
/// contact that interpenetrates by more than `pene_maxi` doubles its
/// normal penalty (at most `coef_maxi`) and the increment is redone from
/// the last converged state (code_aster's `nmevin`, `nmadcp`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PenaltyAdaptation {
    /// `PENE_MAXI`: the largest penetration accepted.
    pub pene_maxi: f64,
    /// `COEF_MAXI`: the largest penalty.
    pub coef_maxi: f64,
}

/// What a penalised source does with a converged increment under
/// [`PenaltyAdaptation`].
#[derive(Clone, Debug, PartialEq)]
pub enum PenaltyVerdict {
    /// No penetration beyond `pene_maxi` (or no penalty to adapt).
    Accepted,
    /// The penalties were doubled: redo the increment.
    Raised {
        /// The largest penetration found.
        penetration: f64,
    },
    /// A penalty would exceed `coef_maxi`: it is set to `coef_maxi` and the
    /// action has failed (code_aster stops the analysis).
    Capped {
        /// The largest penetration found.
        penetration: f64,
    },
}

/// A producer of forces with its own unknowns (see the module docs).
pub trait ForceSource {
    /// Short name used in messages.
    fn name(&self) -> String;

    /// Number of own unknowns (constant over the analysis).
    fn unknowns(&self) -> usize;

    /// Whether the tangent [`Contribution::tangent`] is symmetric (a
    /// cohesive joint's Bᵀ D B with a symmetric D; not friction). A step
    /// whose sources have no unknowns of their own and symmetric tangents
    /// is solved as the Newton loop without sources solves it (pinned
    /// rows, Schur complement, sparse Cholesky on a kept symbolic
    /// analysis) instead of the bordered LU. Default: not symmetric.
    fn symmetric_tangent(&self) -> bool {
        false
    }

    /// Start of an increment from the last converged state `state` (at
    /// the new time, before its imposed values are applied). The source may
    /// set its unknowns' starting values.
    fn begin_increment(&mut self, state: &State, own: &mut [f64]) -> Result<(), FemError>;

    /// Forces, own equations and tangent at the current iterate.
    fn evaluate(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError>;

    /// Forces and own equations at `state` on the pairing of `pairing`
    /// (the iterate at the start of the Newton iteration): a trial of
    /// MECA_NON_LINE's line search (`RECH_LINEAIRE`), which code_aster 17
    /// evaluates without pairing again (`SecantLineSearch.compute_f` →
    /// `getResidual`, the contact elements reading the pairing
    /// coordinates). Only the forces and `own_residual` are used. The
    /// default refuses: the source has no such evaluation.
    fn evaluate_on_pairing(
        &mut self,
        _pairing: &State,
        _state: &State,
        _own: &[f64],
    ) -> Result<Contribution, FemError> {
        Err(FemError::Model(format!(
            "RECH_LINEAIRE with {}: its residual on the pairing of the iteration's start is not written",
            self.name()
        )))
    }

    /// After a Newton solve: update the statuses and the geometry the next
    /// evaluation uses; `true` when they did not change and the source's
    /// own criteria hold (the iterate may be accepted). The source may
    /// bring its unknowns back into their admissible set (e.g. friction
    /// directions onto the unit ball): this changes the path, not the
    /// solution.
    fn after_iteration(&mut self, state: &State, own: &mut [f64]) -> Result<bool, FemError>;

    /// Newton converged on the current statuses: accept, or ask for another
    /// solve (fixed-point loops).
    fn after_convergence(&mut self, _state: &State, _own: &[f64]) -> Result<LoopVerdict, FemError> {
        Ok(LoopVerdict::Done)
    }

    /// The increment is accepted (called once per converged increment).
    fn converged(&mut self, state: &State, own: &[f64]) -> Result<(), FemError>;

    /// A name for own unknown `k` in messages (e.g. `LAGS_C of node N3`).
    fn unknown_name(&self, k: usize, _mesh: &aster_mesh::Mesh) -> String {
        format!("unknown #{}", k + 1)
    }

    /// Whether the residual that decides convergence after a solve is
    /// evaluated with the statuses and pairing that solve was built on,
    /// i.e. before [`ForceSource::after_iteration`] updates them, as
    /// code_aster's continuous contact does (`nmfcor` computes the contact
    /// forces of the convergence test, `nmconv` → `nmresi` tests them, and
    /// only then `cfmmcv` → `mmbclc` pairs again and updates the statuses;
    /// `nmfcon` recomputes the forces for the next solve). The default
    /// evaluates after the update.
    fn residual_before_update(&self) -> bool {
        false
    }

    /// Whether the source's own equations are rows of the residual that
    /// decides convergence, as in code_aster 17's `MECA_NON_LINE`
    /// (`NewtonSolver.solve_iteration` → `ConvergenceManager.evalNormResidual`:
    /// RESI_GLOB_MAXI is the largest entry of the whole residual vector,
    /// the `LAGS_C` rows of the contact included, and the reference of
    /// RESI_GLOB_RELA (`getRelativeScaling`) counts them too). Such a
    /// source's [`ForceSource::after_iteration`] usually returns `true`:
    /// a change of status does not by itself prevent convergence there.
    /// The default leaves the own equations to the source's own test.
    fn own_rows_in_residual(&self) -> bool {
        false
    }

    /// Whether this source's [`LoopVerdict::Again`] continues Newton's
    /// iteration (the next solve uses the matrix of the current iterate,
    /// as code_aster's discrete geometric loop `cfconv` → `cfcgeo` inside
    /// `nmnewt`) instead of restarting the step from its start with a
    /// prediction (the default: the fixed-point loops of the continuous
    /// contact, which code_aster restarts from DEPPLU = DEPMOI).
    fn again_continues_newton(&self) -> bool {
        false
    }

    /// A converged increment under [`PenaltyAdaptation`]: a penalised
    /// source whose penetration exceeds `pene_maxi` doubles its penalty.
    /// The default (no penalty) accepts.
    fn adapt_penalty(
        &mut self,
        _state: &State,
        _adaptation: PenaltyAdaptation,
    ) -> Result<PenaltyVerdict, FemError> {
        Ok(PenaltyVerdict::Accepted)
    }

    /// RESI_GLOB_RELA of the iterate just evaluated (called once per
    /// Newton iteration, after the convergence test). code_aster's
    /// discrete friction weights its tangent by it (`cffpm2`).
    fn observe_residual(&mut self, _resi_glob_rela: f64) {}
}

/// A borrowed source, so that the caller keeps it (and what it recorded)
/// after the solve.
impl<T: ForceSource + ?Sized> ForceSource for &mut T {
    fn name(&self) -> String {
        (**self).name()
    }
    fn unknowns(&self) -> usize {
        (**self).unknowns()
    }
    fn symmetric_tangent(&self) -> bool {
        (**self).symmetric_tangent()
    }
    fn begin_increment(&mut self, state: &State, own: &mut [f64]) -> Result<(), FemError> {
        (**self).begin_increment(state, own)
    }
    fn evaluate(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError> {
        (**self).evaluate(state, own)
    }
    fn evaluate_on_pairing(
        &mut self,
        pairing: &State,
        state: &State,
        own: &[f64],
    ) -> Result<Contribution, FemError> {
        (**self).evaluate_on_pairing(pairing, state, own)
    }
    fn after_iteration(&mut self, state: &State, own: &mut [f64]) -> Result<bool, FemError> {
        (**self).after_iteration(state, own)
    }
    fn after_convergence(&mut self, state: &State, own: &[f64]) -> Result<LoopVerdict, FemError> {
        (**self).after_convergence(state, own)
    }
    fn converged(&mut self, state: &State, own: &[f64]) -> Result<(), FemError> {
        (**self).converged(state, own)
    }
    fn unknown_name(&self, k: usize, mesh: &aster_mesh::Mesh) -> String {
        (**self).unknown_name(k, mesh)
    }
    fn residual_before_update(&self) -> bool {
        (**self).residual_before_update()
    }
    fn own_rows_in_residual(&self) -> bool {
        (**self).own_rows_in_residual()
    }
    fn again_continues_newton(&self) -> bool {
        (**self).again_continues_newton()
    }
    fn adapt_penalty(
        &mut self,
        state: &State,
        adaptation: PenaltyAdaptation,
    ) -> Result<PenaltyVerdict, FemError> {
        (**self).adapt_penalty(state, adaptation)
    }
    fn observe_residual(&mut self, resi_glob_rela: f64) {
        (**self).observe_residual(resi_glob_rela)
    }
}

/// What one step's generalised Newton needs from the solver.
pub(crate) struct ForceStep<'a> {
    pub model: &'a Model,
    pub k: &'a Csc,
    pub kff: &'a Csc,
    pub map: &'a [usize],
    pub nfree: usize,
    pub kdiag_max: f64,
    pub newton: NewtonOptions,
    pub resi_glob_rela: Option<f64>,
    pub resi_glob_maxi: Option<f64>,
    pub iter_glob_maxi: usize,
    /// Bound on the restarts asked by the sources' fixed-point loops.
    pub loops_max: usize,
    /// A time integrator's terms (DYNA_NON_LINE): their matrix is already
    /// in `kff`, their constant force in the external forces; their force
    /// of the iterate is added to the internal forces, as in the Newton
    /// loop without force sources. A weighted equilibrium (HHT with
    /// `MODI_EQUI='OUI'`) weights the internal forces of the previous step,
    /// not the sources' forces (code_aster weights its continuous contact
    /// forces too: aster-run refuses that combination).
    pub dynamics: Option<&'a dyn IncrementTerms>,
    /// Coordinates of the free unknowns (the fill-reducing ordering).
    pub coords: &'a [[f64; 3]],
    /// The DOF index of each free unknown.
    pub free_dof: &'a [usize],
    /// The time integrator's mass holds the model.
    pub mass_holds: bool,
}

/// The outcome of a converged step: (solves, equality multipliers,
/// RESI_GLOB_RELA, RESI_GLOB_MAXI, RESI_GLOB_RELA per iteration, Newton
/// iterations, the sources' forces per DOF index at the converged state).
pub(crate) type ForceOutcome = (usize, Vec<f64>, f64, f64, Vec<f64>, usize, Vec<f64>);

fn state<'a>(model: &'a Model, u: &'a [f64], t: f64) -> State<'a> {
    State {
        mesh: model.mesh(),
        dofs: model.dofs(),
        displacement: u,
        time: t,
    }
}

/// One step of the generalised Newton method with force sources.
#[allow(clippy::too_many_arguments)]
pub(crate) fn newton_step(
    ctx: &ForceStep,
    fext: &[f64],
    eq: &[EqualityRow],
    sources: &mut [Box<dyn ForceSource + '_>],
    own: &mut [Vec<f64>],
    u: &mut [f64],
    start: &[f64],
    elim: &std::collections::HashMap<usize, f64>,
    t: f64,
    plastic: &mut Option<PlasticCells>,
    kkt: &mut KktSolver,
) -> Result<ForceOutcome, FemError> {
    let ForceStep {
        model,
        k,
        kff,
        map,
        nfree,
        kdiag_max,
        newton,
        dynamics,
        coords,
        free_dof,
        mass_holds,
        ..
    } = *ctx;
    let nd = u.len();
    let offsets: Vec<usize> = own
        .iter()
        .scan(0usize, |acc, o| {
            let start = *acc;
            *acc += o.len();
            Some(start)
        })
        .collect();
    let nown: usize = own.iter().map(|o| o.len()).sum();
    let trace = std::env::var_os("ASTER_FEM_TRACE").is_some();
    let mut residuals = Vec::new();
    let mut solves = 0usize;
    let mut newton_iterations = 0usize;
    let mut loops = 0usize;
    // Newton iterations of the current solve (restarted by a source's
    // loop that restarts Newton).
    let mut iteration = 0usize;
    // The iteration that chooses the matrix: restarted with `iteration`,
    // except by the loops that continue Newton (discrete geometry): the
    // next solve then uses the tangent of the current iterate, not the
    // prediction's.
    let mut matrix_iteration = 0usize;
    // At most ITER_GLOB_MAXI residual checks, the prediction's included
    // (code_aster's `nmconv`: the step fails at iterat + 1 ≥ ITER_GLOB_MAXI,
    // iterat = 0 the prediction; `crate::nonlinear`).
    let max_iterations = ctx.iter_glob_maxi.max(1);
    // The state the step starts from (the converged displacement with the
    // imposed values of this step, the sources' unknowns as
    // `begin_increment` left them): a restarting loop starts again from it.
    let u_start = u.to_vec();
    let own_start = own.to_vec();
    let mut tangent: Option<Csc> = None;
    // The equality multipliers of the last iterate (line search).
    let mut prev_lam: Option<Vec<f64>> = None;
    let mut evaluated: Option<(Vec<f64>, Vec<crate::force_source::Contribution>)> = None;
    loop {
        // The prediction (iteration 0 of a step, or of a restart from
        // the step's start): the internal forces are those of the state
        // before the imposed increment, which enters as −K_T Δū
        // (`crate::nonlinear::add_imposed_lift`), as in code_aster 17's
        // `NewtonSolver` (the residual at the step's start, the Dirichlet
        // increment through the Jacobian) and STAT_NON_LINE's `nmprta`.
        // The sources are evaluated at the iterate as before.
        let predict = plastic.is_some()
            && evaluated.is_none()
            && iteration == 0
            && crate::nonlinear::imposed_moved(u, start, elim.keys().copied());
        // Internal forces and the sources' contributions at the iterate.
        let (mut fint, contributions) = match evaluated.take() {
            Some(e) => e,
            None if predict => {
                let u0 = crate::nonlinear::before_imposed(u, start, elim.keys().copied());
                let fint = step_forces(model, k, dynamics, plastic, &u0)?;
                (fint, evaluate_sources(model, sources, own, u, t)?)
            }
            None => evaluate_all(model, k, dynamics, plastic, sources, own, u, t)?,
        };
        if let Some(pc) = plastic.as_mut() {
            choose_tangent(&mut tangent, pc, model, kff, map, newton, matrix_iteration)?;
            if predict {
                crate::nonlinear::add_imposed_lift(
                    k,
                    pc,
                    tangent.is_some(),
                    u,
                    start,
                    elim.keys().copied(),
                    &mut fint,
                );
            }
        }
        let matrix = tangent.as_ref().unwrap_or(kff);
        let rows: Vec<(Vec<(usize, f64)>, f64)> =
            eq.iter().map(|r| (r.terms.clone(), r.rhs)).collect();
        let kept = kept_rows(model, &rows, eq.len(), map, u)?;
        let nk = kept.len();
        let n = nfree + nown + nk;
        let mut b = vec![0.0; n];
        let mut src_force = vec![0.0; nd];
        for c in &contributions {
            for &(i, f) in &c.forces {
                src_force[i] += f;
            }
        }
        for i in 0..nd {
            if map[i] != usize::MAX {
                b[map[i]] = fext[i] - fint[i] - src_force[i];
            }
        }

        let mut extra: Vec<(usize, usize, f64)> = Vec::new();
        for (s, c) in contributions.iter().enumerate() {
            for (k, r) in c.own_residual.iter().enumerate() {
                b[nfree + offsets[s] + k] = -r;
            }
            let index = |x: Unknown| -> Option<usize> {
                match x {
                    Unknown::Dof(i) => (map[i] != usize::MAX).then(|| map[i]),
                    Unknown::Own(k) => Some(nfree + offsets[s] + k),
                }
            };
            for &(r, col, v) in &c.tangent {
                let Some(ri) = index(r) else { continue };
                match col {
                    Unknown::Dof(j) if map[j] == usize::MAX => {
                        // An eliminated DOF is at its value: nothing to solve.
                        continue;
                    }
                    _ => {}
                }
                if let Some(ci) = index(col) {
                    extra.push((ri, ci, v));
                }
            }
        }
        for (kk, &r) in kept.iter().enumerate() {
            let row = &eq[r];
            let au: f64 = row.terms.iter().map(|&(i, c)| c * u[i]).sum();
            b[nfree + nown + kk] = row.rhs - au;
        }
        let free_rows: Vec<Vec<(usize, f64)>> = kept
            .iter()
            .map(|&r| {
                eq[r]
                    .terms
                    .iter()
                    .filter(|(i, _)| map[*i] != usize::MAX)
                    .map(|&(i, c)| (map[i], c))
                    .collect()
            })
            .collect();
        // Sources without unknowns of their own and with symmetric
        // tangents (cohesive joints) on a symmetric matrix: the solve of
        // the Newton loop without sources (pinned rows out, the relations
        // through their Schur complement, Cholesky on a kept symbolic
        // analysis with a nested dissection), not the bordered LU.
        let symmetric = nown == 0
            && sources.iter().all(|s| s.symmetric_tangent())
            && plastic.as_ref().is_none_or(|pc| pc.symmetric_tangent());
        let reduced = if symmetric {
            let keff = crate::newton_timing::timed(crate::newton_timing::Phase::Assembly, || {
                matrix.with_extra(nfree, extra.clone())
            });
            let key = kkt.new_tangent(true);
            let krows: Vec<solver_constrained::Row> = free_rows
                .iter()
                .enumerate()
                .map(|(kk, terms)| solver_constrained::Row {
                    terms,
                    d: b[nfree + kk],
                    equality: true,
                })
                .collect();
            let held_by = |pinned: &[usize], relations: &solver_constrained::Relations| {
                mass_holds
                    || crate::nonlinear::held_by_rows(model, elim, free_dof, pinned, relations)
            };
            kkt.solve(key, &keff, &[], &krows, &b[..nfree], Some(coords), &held_by)
                .ok()
                .flatten()
        } else {
            None
        };
        let name = |i: usize| -> String {
            if i < nfree {
                let dof = map.iter().position(|&m| m == i).unwrap_or(0);
                model.dofs().dof(dof).describe(model.mesh())
            } else if i < nfree + nown {
                let s = offsets.iter().rposition(|&o| o <= i - nfree).unwrap_or(0);
                format!(
                    "{} ({})",
                    sources[s].unknown_name(i - nfree - offsets[s], model.mesh()),
                    sources[s].name()
                )
            } else {
                format!("Lagrange multiplier #{}", i - nfree - nown + 1)
            }
        };
        let sol = match reduced {
            Some(sol) => sol,
            None => {
                let mut extra = extra;
                for (kk, terms) in free_rows.iter().enumerate() {
                    for &(i, c) in terms {
                        extra.push((nfree + nown + kk, i, c));
                        extra.push((i, nfree + nown + kk, c));
                    }
                }
                let a = crate::newton_timing::timed(crate::newton_timing::Phase::Assembly, || {
                    matrix.with_extra(n, extra)
                });
                linalg::solve_with(&a, &b, nfree, false, None).map_err(|f| match f {
                    SolveFailure::Singular { index } => FemError::Singular {
                        free_dofs: index.map(|i| vec![name(i)]).unwrap_or_default(),
                    },
                    other => linalg::failure_to_error(other, name),
                })?
            }
        };
        if trace {
            let (imax, vmax) = sol
                .x
                .iter()
                .enumerate()
                .fold((0, 0.0f64), |(i0, v0), (i, v)| {
                    if v.abs() > v0 {
                        (i, v.abs())
                    } else {
                        (i0, v0)
                    }
                });
            eprintln!(
                "[newton/sources] largest correction {vmax:.3e} on {}",
                name(imax)
            );
        }
        // RECH_LINEAIRE after a correction (not after the prediction:
        // code_aster 17's `isPrediction`, iteration 0), the trial
        // residuals on the pairing of the iteration's start.
        let rho = match newton.line_search {
            Some(ls) if iteration > 0 => {
                if dynamics.is_some() {
                    return Err(FemError::Model(
                        "RECH_LINEAIRE with force sources under a time scheme is not supported"
                            .into(),
                    ));
                }
                let trial = Trial {
                    model,
                    k,
                    map,
                    nfree,
                    offsets: &offsets,
                    fext,
                    x: &sol.x,
                    b: &b,
                    t,
                };
                line_search(&ls, &trial, sources, own, u, plastic, trace)?
            }
            _ => 1.0,
        };
        solves += 1;
        iteration += 1;
        matrix_iteration += 1;
        newton_iterations += 1;
        crate::newton_timing::count_iteration();
        for i in 0..nd {
            if map[i] != usize::MAX {
                u[i] += rho * sol.x[map[i]];
            }
        }
        for (s, o) in own.iter_mut().enumerate() {
            for (k, v) in o.iter_mut().enumerate() {
                *v += rho * sol.x[nfree + offsets[s] + k];
            }
        }
        // The equality multipliers: code_aster's are unknowns of the
        // increment, moved by ρ times their correction.
        let mut lam = vec![0.0; eq.len()];
        for (kk, &r) in kept.iter().enumerate() {
            let full = sol.x[nfree + nown + kk];
            lam[r] = match prev_lam.as_ref() {
                Some(p) if rho != 1.0 => p[r] + rho * (full - p[r]),
                _ => full,
            };
        }
        prev_lam = Some(lam.clone());
        // The forces of the convergence test of the sources that test
        // before updating their statuses (code_aster's continuous contact).
        let mut before: Vec<Option<Contribution>> = Vec::with_capacity(sources.len());
        for (s, src) in sources.iter_mut().enumerate() {
            before.push(if src.residual_before_update() {
                Some(src.evaluate(&state(model, u, t), &own[s])?)
            } else {
                None
            });
        }
        // Statuses and geometry at the new iterate.
        let mut settled = true;
        let mut unsettled = Vec::new();
        for (s, src) in sources.iter_mut().enumerate() {
            let ok = crate::newton_timing::timed(crate::newton_timing::Phase::Contact, || {
                src.after_iteration(&state(model, u, t), &mut own[s])
            })?;
            if !ok {
                unsettled.push(src.name());
            }
            settled &= ok;
        }
        // Residual at the new iterate (with the new statuses, or with the
        // solve's for the sources that test before updating).
        let (fint, contributions) = evaluate_all(model, k, dynamics, plastic, sources, own, u, t)?;
        let mut src_force = vec![0.0; nd];
        for (c, b) in contributions.iter().zip(&before) {
            for &(i, f) in &b.as_ref().unwrap_or(c).forces {
                src_force[i] += f;
            }
        }
        let mut reac = vec![0.0; nd];
        for (r, row) in eq.iter().enumerate() {
            for &(i, c) in &row.terms {
                reac[i] -= c * lam[r];
            }
        }
        let mut resi_maxi = 0.0f64;
        let mut reference = 0.0f64;
        // Dynamics: the reference counts the inertia and damping forces
        // with the external ones, as the loop without force sources.
        let dyn_u = dynamics.map(|d| d.force(u));
        let dyn_at = |i: usize| dyn_u.as_ref().map_or(0.0, |f| f[i]);
        for i in 0..nd {
            if map[i] == usize::MAX {
                reference = reference.max((fint[i] - dyn_at(i)).abs());
            } else {
                let r = fext[i] - fint[i] + reac[i] - src_force[i];
                if trace && r.abs() > resi_maxi {
                    eprintln!(
                        "[newton/sources] max residual {r:.3e} at {} (fint {:.3e}, sources {:.3e}, reactions {:.3e})",
                        model.dofs().dof(i).describe(model.mesh()),
                        fint[i],
                        src_force[i],
                        reac[i]
                    );
                }
                resi_maxi = resi_maxi.max(r.abs());
                reference = reference.max((fext[i] - dyn_at(i) + reac[i] - src_force[i]).abs());
            }
        }
        // The own rows of the sources whose equations are residual rows
        // (code_aster 17's LAGS_C rows): in RESI_GLOB_MAXI and, as
        // |f_cont| of those rows, in the reference.
        for ((src, c), b) in sources.iter().zip(&contributions).zip(&before) {
            if src.own_rows_in_residual() {
                for r in &b.as_ref().unwrap_or(c).own_residual {
                    resi_maxi = resi_maxi.max(r.abs());
                    reference = reference.max(r.abs());
                }
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
        let converged_resi = if reference > 0. {
            ctx.resi_glob_rela.is_none_or(|tol| resi_rela <= tol)
                && ctx.resi_glob_maxi.is_none_or(|tol| resi_maxi <= tol)
        } else {
            let umax = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            resi_maxi <= 1e-6 * kdiag_max * umax || resi_maxi == 0.
        };
        residuals.push(resi_rela);
        for src in sources.iter_mut() {
            src.observe_residual(resi_rela);
        }
        if trace {
            eprintln!(
                "[newton/sources] t={t} iteration {iteration} resi_rela {resi_rela:.3e} resi_maxi {resi_maxi:.3e} statuses {}",
                if settled { "settled" } else { "changed" }
            );
        }
        evaluated = Some((fint, contributions));
        if converged_resi && settled {
            let mut again = false;
            let mut restarts = false;
            for (s, src) in sources.iter_mut().enumerate() {
                let verdict =
                    crate::newton_timing::timed(crate::newton_timing::Phase::Contact, || {
                        src.after_convergence(&state(model, u, t), &own[s])
                    })?;
                if verdict == LoopVerdict::Again {
                    again = true;
                    restarts |= !src.again_continues_newton();
                }
            }
            if !again {
                return Ok((
                    solves,
                    lam,
                    resi_rela,
                    resi_maxi,
                    residuals,
                    newton_iterations,
                    src_force,
                ));
            }
            loops += 1;
            if loops > ctx.loops_max {
                return Err(FemError::Source(format!(
                    "the fixed-point loops of {} did not settle after {} Newton solves at time {t}",
                    sources
                        .iter()
                        .map(|s| s.name())
                        .collect::<Vec<_>>()
                        .join(", "),
                    ctx.loops_max
                )));
            }
            // A new Newton solve from the start of the step, or, for a
            // loop nested in Newton (the discrete geometric loop), the next
            // iteration: counted on, with the matrix of the current iterate
            // (as the loop without force sources). code_aster's continuous
            // loops (`nmnewt`: `goto 100` → `nmible`, `nmnble` →
            // `nonlinInitDisp`: DEPPLU = DEPMOI, DEPDEL = 0, then `nmpred`)
            // restart the whole step with the statuses and pairing of the
            // pass; under a linear behaviour that changes nothing but
            // round-off, under finite strains or plasticity it changes the
            // Newton path and so the iterate accepted at RESI_GLOB_RELA.
            if restarts {
                iteration = 0;
                matrix_iteration = 0;
                u.copy_from_slice(&u_start);
                for (o, o0) in own.iter_mut().zip(&own_start) {
                    o.copy_from_slice(o0);
                }
            }
            evaluated = None;
            continue;
        }
        if iteration >= max_iterations {
            return Err(FemError::NoConvergence {
                time: t,
                iterations: iteration,
                resi_rela,
                resi_maxi,
                cycling: (!settled).then(|| unsettled.join(", ")),
            });
        }
    }
}

/// What a line-search trial needs from the Newton iteration: the solve's
/// solution `x` and right-hand side `b` (−R at the iterate) in the
/// system's numbering (free DOFs, then the sources' unknowns at
/// `offsets`).
struct Trial<'a> {
    model: &'a Model,
    k: &'a Csc,
    map: &'a [usize],
    nfree: usize,
    offsets: &'a [usize],
    fext: &'a [f64],
    x: &'a [f64],
    b: &'a [f64],
    t: f64,
}

/// RECH_LINEAIRE with force sources (MECA_NON_LINE with a DEFI_CONT,
/// code_aster 17's `SecantLineSearch`): ρ of the ONE search
/// ([`crate::line_search`]) on
///
/// ```text
/// f(ρ) = Δu · (f_int + f_src − f_ext)(u + ρΔu, y + ρΔy) + Δy · g(u + ρΔu, y + ρΔy)
/// ```
///
/// (`compute_f`: −R·Δ over the whole increment, the sources' unknowns —
/// `LAGS_C` — and their equations included), each source evaluated on the
/// pairing of `u` ([`ForceSource::evaluate_on_pairing`]: code_aster pairs
/// once per iteration, before the search). The equality rows drop out
/// (after the prediction A Δu = 0). f(0) = −Δ·b. `u`, `own` are unchanged
/// on return; the behaviour cells are left at the last ρ tried (the
/// iterate's internal forces are computed again after the step).
fn line_search(
    ls: &crate::line_search::LineSearch,
    tr: &Trial,
    sources: &mut [Box<dyn ForceSource + '_>],
    own: &[Vec<f64>],
    u: &[f64],
    plastic: &mut Option<PlasticCells>,
    trace: bool,
) -> Result<f64, FemError> {
    let nd = u.len();
    let free: Vec<usize> = (0..nd).filter(|&i| tr.map[i] != usize::MAX).collect();
    let nown: usize = own.iter().map(|o| o.len()).sum();
    let own_rows = tr.nfree..tr.nfree + nown;
    let f0: f64 = -free
        .iter()
        .map(|&i| tr.x[tr.map[i]] * tr.b[tr.map[i]])
        .sum::<f64>()
        - own_rows.clone().map(|r| tr.x[r] * tr.b[r]).sum::<f64>();
    let mut trial_u = u.to_vec();
    let mut trial_own = own.to_vec();
    let outcome = ls.search(f0, |rho| {
        for &i in &free {
            trial_u[i] = u[i] + rho * tr.x[tr.map[i]];
        }
        for (s, o) in trial_own.iter_mut().enumerate() {
            for (k, v) in o.iter_mut().enumerate() {
                *v = own[s][k] + rho * tr.x[tr.nfree + tr.offsets[s] + k];
            }
        }
        let fint = step_forces(tr.model, tr.k, None, plastic, &trial_u)?;
        let mut src = vec![0.0; nd];
        let mut f = 0.0;
        for (s, source) in sources.iter_mut().enumerate() {
            let c = crate::newton_timing::timed(crate::newton_timing::Phase::Contact, || {
                source.evaluate_on_pairing(
                    &state(tr.model, u, tr.t),
                    &state(tr.model, &trial_u, tr.t),
                    &trial_own[s],
                )
            })?;
            for &(i, v) in &c.forces {
                src[i] += v;
            }
            for (k, r) in c.own_residual.iter().enumerate() {
                f += tr.x[tr.nfree + tr.offsets[s] + k] * r;
            }
        }
        f += free
            .iter()
            .map(|&i| tr.x[tr.map[i]] * (fint[i] + src[i] - tr.fext[i]))
            .sum::<f64>();
        Ok::<f64, FemError>(f)
    });
    let outcome = match outcome {
        Ok(o) => o,
        Err(crate::line_search::LineSearchError::Evaluation(e)) => return Err(e),
        Err(crate::line_search::LineSearchError::Ascent { f0 }) => {
            return Err(FemError::Model(format!(
                "RECH_LINEAIRE METHODE='MIXTE' at time {}: the Newton correction is not a descent direction (f(0) = {f0:.6e} > 0); code_aster then searches along the opposite direction and applies the opposite step, not reproduced",
                tr.t
            )))
        }
    };
    if trace {
        eprintln!("[newton/sources] {}", outcome.trace(f0));
    }
    Ok(outcome.rho)
}

/// Internal forces (with the time integrator's) and every source's
/// contribution at `u`.
#[allow(clippy::too_many_arguments)]
fn evaluate_all(
    model: &Model,
    k: &Csc,
    dynamics: Option<&dyn IncrementTerms>,
    plastic: &mut Option<PlasticCells>,
    sources: &mut [Box<dyn ForceSource + '_>],
    own: &[Vec<f64>],
    u: &[f64],
    t: f64,
) -> Result<(Vec<f64>, Vec<Contribution>), FemError> {
    let fint = step_forces(model, k, dynamics, plastic, u)?;
    Ok((fint, evaluate_sources(model, sources, own, u, t)?))
}

/// The sources' contributions at the iterate `u`.
fn evaluate_sources(
    model: &Model,
    sources: &mut [Box<dyn ForceSource + '_>],
    own: &[Vec<f64>],
    u: &[f64],
    t: f64,
) -> Result<Vec<Contribution>, FemError> {
    let _t = crate::newton_timing::phase(crate::newton_timing::Phase::Contact);
    let mut out = Vec::with_capacity(sources.len());
    for (s, src) in sources.iter_mut().enumerate() {
        let c = src.evaluate(&state(model, u, t), &own[s])?;
        if c.own_residual.len() != own[s].len() {
            return Err(FemError::Model(format!(
                "{} returned {} equations for {} unknowns",
                src.name(),
                c.own_residual.len(),
                own[s].len()
            )));
        }
        out.push(c);
    }
    Ok(out)
}
