//! Runs a contact method on a linear elastic model with the contact crate's
//! multiplier-space driver, timing the linear solver apart from the rest.
//!
//! It is `aster_contact::run_linear` unrolled so that each phase's CPU time
//! can be measured: assembly, factorisation, every solve with the factor
//! (through a timing wrapper around [`StiffnessSolve`]), pairing, and the
//! rest of the contact algorithm.

use crate::clock::{cpu_now, cpu_since};
use crate::method::{Method, MethodFamily};
use crate::outcome::{Failure, FailureKind, Phases};
use aster_contact::dual::{
    solve_dual_cached, ColumnCache, DualAlgorithm, IndexedRow, StiffnessSolve,
};
use aster_contact::{
    index_row, positions, solve_step_cached, ContactDefinition, ContactError, ContinueAlgo,
    ContinueLaw, DiscreteAlgo, FactorizedStiffness, Frottement, Zone, ZoneContact, ZoneGeometry,
};
use aster_fem::assembly::assemble_stiffness;
use aster_fem::{InequalityRow, Loads, Model};
use aster_mesh::NodeId;
use std::cell::Cell;

/// A solved contact problem and what it cost.
pub struct Solved {
    /// Normal force on each slave node carrying one (contact pairs' forces
    /// spread on their slave nodes; LIAISON_UNIL reactions).
    pub forces: Vec<(NodeId, f64)>,
    /// Largest interpenetration at convergence (≥ 0): along each pair's
    /// normal for contact, the largest row violation for LIAISON_UNIL.
    pub penetration: f64,
    pub contact_iterations: usize,
    pub geom_iterations: usize,
    /// CPU time of the phases from the contact zones to the converged
    /// contact solution (`mesh` and `post` are left to the scene).
    pub phases: Phases,
}

/// The `DEFI_CONTACT` a method stands for, on one zone; `fixed_normal` is
/// `VECT_MAIT='FIXE', MAIT_FIXE=…`.
pub fn definition(
    method: &Method,
    master: &str,
    slave: &str,
    fixed_normal: Option<[f64; 3]>,
) -> Result<ContactDefinition, Failure> {
    let mut geometry = ZoneGeometry::new(master, slave);
    if let Some(v) = fixed_normal {
        geometry = geometry
            .with_fixed_master_normal(v)
            .map_err(contact_failure)?;
    }
    let coef = method.coefficient().unwrap_or(100.0);
    let discrete = |law| {
        ContactDefinition::discrete(
            vec![Zone {
                geometry: geometry.clone(),
                law,
            }],
            Frottement::Sans,
        )
    };
    let continuous = |algo| {
        ContactDefinition::continuous(
            vec![Zone {
                geometry: geometry.clone(),
                law: ContinueLaw {
                    algo,
                    ..ContinueLaw::default()
                },
            }],
            Frottement::Sans,
        )
    };
    let def = match method.family() {
        MethodFamily::DiscreteContrainte => discrete(DiscreteAlgo::Contrainte),
        MethodFamily::DiscretePenalisation => discrete(DiscreteAlgo::Penalisation { e_n: coef }),
        MethodFamily::DiscreteGcp => discrete(DiscreteAlgo::Gcp {
            resi_abso: None,
            iter_maxi: 0,
        }),
        MethodFamily::ContinuousStandard => continuous(ContinueAlgo::Standard { coef_cont: coef }),
        MethodFamily::ContinuousPenalisation => continuous(ContinueAlgo::Penalisation {
            coef_pena_cont: coef,
        }),
        MethodFamily::LiaisonUnil | MethodFamily::LiaisonUnilPenalisation => {
            return Err(Failure::new(
                FailureKind::Unsupported,
                "LIAISON_UNIL is not DEFI_CONTACT contact: give its rows with `unilateral`",
            ))
        }
        MethodFamily::DiscreteFrictionPenalisation
        | MethodFamily::ContinuousFrictionStandard
        | MethodFamily::ContinuousFrictionPenalisation => {
            return Err(Failure::new(
                FailureKind::Unsupported,
                "a frictional method runs on a frictional scene (`friction`), not on a frictionless linear one",
            ))
        }
    };
    def.map_err(contact_failure)
}

/// What enforces non-penetration in a run.
pub enum Conditions {
    /// `DEFI_CONTACT` DISCRETE or CONTINUE: pairing and rows at every
    /// geometric iteration.
    Contact(ContactDefinition),
    /// `DEFI_CONTACT FORMULATION='LIAISON_UNIL'`: fixed rows
    /// Σ COEF_MULT·u ≤ COEF_IMPO on the total displacement, exact
    /// (CONTRAINTE, `penalty = None`) or penalised (λ = COEF_PENA × violation).
    Unilateral {
        rows: Vec<InequalityRow>,
        penalty: Option<f64>,
    },
}

/// The conditions a method stands for: contact on the zone (master,
/// slave, fixed normal), or, for LIAISON_UNIL, the scene's `unilateral`
/// rows (built only then).
pub fn conditions(
    method: &Method,
    master: &str,
    slave: &str,
    fixed_normal: Option<[f64; 3]>,
    unilateral: impl FnOnce() -> Result<Vec<InequalityRow>, Failure>,
) -> Result<Conditions, Failure> {
    match method.family() {
        MethodFamily::LiaisonUnil => Ok(Conditions::Unilateral {
            rows: unilateral()?,
            penalty: None,
        }),
        MethodFamily::LiaisonUnilPenalisation => Ok(Conditions::Unilateral {
            rows: unilateral()?,
            penalty: method.coefficient(),
        }),
        _ => definition(method, master, slave, fixed_normal).map(Conditions::Contact),
    }
}

/// Classifies a contact error into the study's failure kinds.
pub fn contact_failure(e: ContactError) -> Failure {
    let kind = match &e {
        ContactError::Cycling { .. } => FailureKind::Cycling,
        ContactError::NotConverged { .. } => FailureKind::NoConvergence,
        ContactError::SingularContact { .. } => FailureKind::SingularMatrix,
        ContactError::Solver(m) if m.contains("singular") || m.contains("non-finite") => {
            FailureKind::SingularMatrix
        }
        ContactError::Solver(_) => FailureKind::PoorSolve,
        ContactError::Unsupported { .. } => FailureKind::Unsupported,
        _ => FailureKind::Other,
    };
    Failure::new(kind, e.to_string())
}

struct Timed<'a> {
    k: &'a FactorizedStiffness,
    seconds: Cell<f64>,
}

impl StiffnessSolve for Timed<'_> {
    fn len(&self) -> usize {
        self.k.len()
    }
    fn reads(&self, i: usize) -> bool {
        self.k.reads(i)
    }
    fn solve(&self, rhs: &[f64]) -> Result<Vec<f64>, String> {
        let start = cpu_now();
        let out = self.k.solve(rhs);
        self.seconds.set(self.seconds.get() + cpu_since(start));
        out
    }
    fn solve_many(&self, rhs: &[Vec<f64>]) -> Result<Vec<Vec<f64>>, String> {
        let start = cpu_now();
        let out = self.k.solve_many(rhs);
        self.seconds.set(self.seconds.get() + cpu_since(start));
        out
    }
}

/// Solves the contact problem at `instants` (the first one is the initial,
/// unloaded state). Each instant pairs on the previous converged geometry.
/// The phases from `model` to `contact` are filled in CPU seconds; the
/// scene adds `mesh`, the model's construction and `post`.
pub fn solve(
    conditions: &Conditions,
    model: &Model,
    loads: &Loads,
    instants: &[f64],
) -> Result<Solved, Failure> {
    let mut phases = Phases::default();
    let start = cpu_now();
    let mut enforced = match conditions {
        Conditions::Contact(def) => Enforced::Zones(
            def,
            ZoneContact::build_all(def, model.mesh()).map_err(contact_failure)?,
        ),
        Conditions::Unilateral { rows, penalty } => {
            let indexed = rows
                .iter()
                .map(|r| index_row(r, model.dofs(), model.mesh()))
                .collect::<Result<Vec<_>, _>>()
                .map_err(contact_failure)?;
            let eps = vec![penalty.map_or(0.0, |c| 1.0 / c); rows.len()];
            Enforced::Rows {
                rows,
                indexed,
                eps,
                lambda: vec![0.0; rows.len()],
                active: None,
            }
        }
    };
    phases.model = cpu_since(start);
    let start = cpu_now();
    let assembled =
        assemble_stiffness(model).map_err(|e| Failure::new(FailureKind::Other, e.to_string()))?;
    phases.assembly = cpu_since(start);
    let start = cpu_now();
    let k =
        FactorizedStiffness::from_assembled(model, loads, assembled).map_err(contact_failure)?;
    phases.factorisation = cpu_since(start);
    let timed = Timed {
        k: &k,
        seconds: Cell::new(0.0),
    };
    // One K for the whole run: its columns K⁻¹aⱼ serve every geometric
    // iteration and instant whose rows are unchanged on the free DOFs.
    let mut cache = ColumnCache::new();
    let mut u = vec![0.0; model.dofs().len()];
    let (mut contact_iterations, mut geom_iterations) = (0, 0);
    for &t in instants.iter().skip(1) {
        let start = cpu_now();
        let u_free = k.free_solution(model, loads, t).map_err(contact_failure)?;
        phases.solves += cpu_since(start);
        let start = cpu_now();
        let solves_before = timed.seconds.get();
        let (next, pairing_seconds) = match &mut enforced {
            Enforced::Zones(def, zones) => {
                let report = solve_step_cached(
                    def,
                    zones,
                    model.mesh(),
                    model.dofs(),
                    &timed,
                    &u_free,
                    &u,
                    &mut cache,
                )
                .map_err(contact_failure)?;
                contact_iterations += report.contact_iterations;
                geom_iterations += report.geom_iterations;
                (report.u, report.pairing_seconds)
            }
            Enforced::Rows {
                indexed,
                eps,
                lambda,
                active,
                ..
            } => {
                let m = indexed.len();
                let algo = DualAlgorithm::ActiveSet {
                    max_iter: 4 * m.max(1),
                    stop_singulier: true,
                };
                let sol = solve_dual_cached(
                    &timed,
                    &u_free,
                    indexed,
                    eps,
                    algo,
                    active.as_deref(),
                    &mut cache,
                )
                .map_err(contact_failure)?;
                contact_iterations += sol.iterations;
                // Fixed rows: one "geometric" pass per instant.
                geom_iterations += 1;
                *lambda = sol.lambda;
                *active = Some(sol.active);
                (sol.u, 0.0)
            }
        };
        let step = cpu_since(start);
        let solves = timed.seconds.get() - solves_before;
        // The step's pairing is timed on the wall clock by the contact
        // crate: on one busy thread the two agree.
        let pairing = pairing_seconds.min(step - solves).max(0.0);
        phases.solves += solves;
        phases.pairing += pairing;
        phases.contact += (step - solves - pairing).max(0.0);
        u = next;
    }
    if u.iter().any(|x| !x.is_finite()) {
        return Err(Failure::new(
            FailureKind::SingularMatrix,
            "non-finite displacement",
        ));
    }
    let (forces, penetration) = match &enforced {
        Enforced::Zones(_, zones) => (
            zones.iter().flat_map(|z| z.nodal_forces()).collect(),
            contact_penetration(zones, model, &u),
        ),
        Enforced::Rows {
            rows,
            indexed,
            lambda,
            ..
        } => (
            unilateral_forces(rows, lambda),
            indexed
                .iter()
                .map(|r| r.terms.iter().map(|&(i, c)| c * u[i]).sum::<f64>() - r.rhs)
                .fold(0.0f64, f64::max),
        ),
    };
    Ok(Solved {
        forces,
        penetration,
        contact_iterations,
        geom_iterations,
        phases,
    })
}

/// The conditions at work during a solve.
enum Enforced<'a> {
    Zones(&'a ContactDefinition, Vec<ZoneContact>),
    Rows {
        rows: &'a [InequalityRow],
        indexed: Vec<IndexedRow>,
        eps: Vec<f64>,
        /// Multipliers of the last instant.
        lambda: Vec<f64>,
        /// Active set of the last instant (warm start of the next).
        active: Option<Vec<bool>>,
    },
}

/// The reaction of each LIAISON_UNIL row, as a normal force on the nodes
/// of its terms: λ spread over the row's nodes in proportion to their
/// coefficients (one node per row for node-wise rows).
fn unilateral_forces(rows: &[InequalityRow], lambda: &[f64]) -> Vec<(NodeId, f64)> {
    let mut out: Vec<(NodeId, f64)> = Vec::new();
    for (row, &l) in rows.iter().zip(lambda) {
        let total: f64 = row.terms.iter().map(|t| t.1.abs()).sum();
        if total == 0.0 {
            continue;
        }
        for &(dof, c) in &row.terms {
            let f = l.max(0.0) * c.abs() / total;
            match out.iter_mut().find(|(n, _)| *n == dof.node) {
                Some(e) => e.1 += f,
                None => out.push((dof.node, f)),
            }
        }
    }
    out
}

/// Largest interpenetration (≥ 0) of the paired slave points on the final
/// geometry, measured along each pair's normal.
fn contact_penetration(zones: &[ZoneContact], model: &Model, u: &[f64]) -> f64 {
    let x = positions(model.mesh(), model.dofs(), u);
    let at = |nodes: &[(aster_mesh::NodeId, f64)]| {
        let mut p = [0.0; 3];
        for &(n, w) in nodes {
            for c in 0..3 {
                p[c] += w * x[n.0 as usize][c];
            }
        }
        p
    };
    let mut worst = 0.0f64;
    for zone in zones {
        for pair in zone.pairs() {
            let Some(p) = pair.pairing() else { continue };
            let s = at(&pair.point.nodes);
            let m = at(&p.master);
            let gap: f64 = (0..3).map(|c| (s[c] - m[c]) * p.normal[c]).sum();
            worst = worst.max(-gap);
        }
    }
    worst
}
