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
use aster_contact::dual::StiffnessSolve;
use aster_contact::{
    positions, solve_step, ContactDefinition, ContactError, ContinueAlgo, ContinueLaw,
    DiscreteAlgo, FactorizedStiffness, Frottement, Zone, ZoneContact, ZoneGeometry,
};
use aster_fem::assembly::assemble_stiffness;
use aster_fem::{Loads, Model};
use std::cell::Cell;

/// A solved contact problem and what it cost.
pub struct Solved {
    pub zones: Vec<ZoneContact>,
    /// Final total displacement (model numbering).
    pub u: Vec<f64>,
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
        MethodFamily::LiaisonUnil => {
            return Err(Failure::new(
                FailureKind::Unsupported,
                "LIAISON_UNIL needs node-to-node rows on matching meshes; not wired in this scene",
            ))
        }
    };
    def.map_err(contact_failure)
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
    fn solve(&self, rhs: &[f64]) -> Result<Vec<f64>, String> {
        let start = cpu_now();
        let out = self.k.solve(rhs);
        self.seconds.set(self.seconds.get() + cpu_since(start));
        out
    }
}

/// Solves the contact problem at `instants` (the first one is the initial,
/// unloaded state). Each instant pairs on the previous converged geometry.
/// The phases from `model` to `contact` are filled in CPU seconds; the
/// scene adds `mesh`, the model's construction and `post`.
pub fn solve(
    def: &ContactDefinition,
    model: &Model,
    loads: &Loads,
    instants: &[f64],
) -> Result<Solved, Failure> {
    let mut phases = Phases::default();
    let start = cpu_now();
    let mut zones = ZoneContact::build_all(def, model.mesh()).map_err(contact_failure)?;
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
    let mut u = vec![0.0; model.dofs().len()];
    let (mut contact_iterations, mut geom_iterations) = (0, 0);
    for &t in instants.iter().skip(1) {
        let start = cpu_now();
        let u_free = k.free_solution(model, loads, t).map_err(contact_failure)?;
        phases.solves += cpu_since(start);
        let start = cpu_now();
        let solves_before = timed.seconds.get();
        let report = solve_step(
            def,
            &mut zones,
            model.mesh(),
            model.dofs(),
            &timed,
            &u_free,
            &u,
        )
        .map_err(contact_failure)?;
        let step = cpu_since(start);
        let solves = timed.seconds.get() - solves_before;
        // The step's pairing is timed on the wall clock by the contact
        // crate: on one busy thread the two agree.
        let pairing = report.pairing_seconds.min(step - solves).max(0.0);
        phases.solves += solves;
        phases.pairing += pairing;
        phases.contact += (step - solves - pairing).max(0.0);
        contact_iterations += report.contact_iterations;
        geom_iterations += report.geom_iterations;
        u = report.u;
    }
    if u.iter().any(|x| !x.is_finite()) {
        return Err(Failure::new(
            FailureKind::SingularMatrix,
            "non-finite displacement",
        ));
    }
    Ok(Solved {
        zones,
        u,
        contact_iterations,
        geom_iterations,
        phases,
    })
}

/// Largest interpenetration (≥ 0) of the paired slave points on the final
/// geometry, measured along each pair's normal.
pub fn penetration(solved: &Solved, model: &Model) -> f64 {
    let x = positions(model.mesh(), model.dofs(), &solved.u);
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
    for zone in &solved.zones {
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
