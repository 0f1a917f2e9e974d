//! The stick/slip scene: an elastic block pressed on a rigid plane, then
//! dragged sideways (the contact crate's `two_plates_shear_problem` with a
//! rigid base), under Coulomb friction.
//!
//! The block (2 × 1, plane strain, E = 2e6, ν = 0, `refine × refine`
//! cells) is pressed by 0.1 (σ_n = E·0.1 = 2e5 on the rigid base) up to
//! t = 1, then its top is moved sideways by `shear` over `steps` equal
//! steps up to t = 2. The lower plate, clamped, is the rigid plane; its
//! mesh (`refine + 1` cells, stretched to [−1.5 − shear, 1.5 + shear] so
//! that the block never overhangs it) does not match the block's.
//!
//! Compared quantity: Σ FX / Σ FY on the top edge at t = 2, the ratio of
//! the tangential to the normal force the interface carries. Once the top
//! moved past the slip threshold (the uniform shear G·shear above μ σ_n,
//! i.e. `shear` > μ σ_n / G = 0.2 μ), the whole interface slides and
//! Coulomb's law makes the ratio **exactly μ** whatever the mesh: that is
//! the analytic reference, given when `shear` is at least three times that
//! threshold (at 1.7 times, μ = 0.6, the corners of the block still stick:
//! the ratio is 2.6 % below μ). Nearer the threshold, or below it (the
//! block sticks, slipping near its free edges), the ratio has no closed
//! form: the scene gives no analytic reference (use `reference =
//! "finest"`).
//!
//! What the map shows: a penalised tangential law (`E_T`,
//! `COEF_PENA_FROT`) lets the interface deform elastically before it
//! slips, so a small coefficient leaves the block stuck below μ (a
//! converged, wrong answer); a large one stiffens Newton (failures), and
//! big steps make it worse.

use crate::error::StudyError;
use crate::method::MethodFamily;
use crate::outcome::{Failure, FailureKind, Measures};
use crate::scene::{Params, Scene};
use crate::spec::Point;
use aster_contact::friction::{
    ContinueFriction, ContinueZoneFriction, ContinuousFriction, DiscreteFriction,
    DiscreteFrictionDef, DiscreteZoneFriction, FrictionAlgo,
};
use aster_contact::scenes::{two_plates_mesh, two_plates_shear_problem};
use aster_contact::{
    ContactDefinition, ContinueAlgo, ContinueLaw, DiscreteAlgo, Measure, Zone, ZoneGeometry,
};
use aster_fem::{Comp, Convergence, Dof, FemError, ForceSource, Model, StaticNonLinear};
use std::collections::BTreeMap;

/// Young's modulus of both plates (`two_plates_shear_problem`).
const YOUNG: f64 = 2e6;
/// Downward displacement of the block's top at t = 1.
const PRESS: f64 = 0.1;
/// Height of the block.
const HEIGHT: f64 = 1.0;

pub struct Friction {
    /// Sideways displacement of the top from t = 1 to t = 2.
    shear: f64,
    /// `E_N` of the discrete formulation (its contact is penalised too).
    e_n: f64,
    /// `COEF_CONT` of the continuous augmented friction (`ALGO_CONT=
    /// 'STANDARD'` beside `ALGO_FROT='STANDARD'`).
    coef_cont: f64,
    /// `COEF_PENA_CONT` of the continuous penalised friction (`ALGO_CONT=
    /// 'PENALISATION'` beside `ALGO_FROT='PENALISATION'`, as ssnv505m:
    /// beside augmented contact code_aster's `mm_cycl_algo` resets
    /// `COEF_PENA_FROT` on sliding points to 10·a_max/a_min/GLIS_MAXI).
    coef_pena_cont: f64,
    /// `COEF_MATR_FROT` of the discrete formulation (code_aster's default
    /// 0: the sliding part of the tangent left out while RESI_GLOB_RELA ≥
    /// 1e-3).
    coef_matr_frot: f64,
    /// `ITER_GLOB_MAXI` (code_aster's default 10).
    iter_glob_maxi: usize,
    /// Penetration beyond which a converged run is a wrong answer.
    max_penetration: f64,
}

impl Friction {
    pub fn from_params(table: &BTreeMap<String, f64>) -> Result<Friction, StudyError> {
        let p = Params::new(
            "friction",
            table,
            &[
                "shear",
                "e_n",
                "coef_cont",
                "coef_pena_cont",
                "coef_matr_frot",
                "iter_glob_maxi",
                "max_penetration",
            ],
        )?;
        let iter = p.within("iter_glob_maxi", 10.0, 1.0, 1000.0)?;
        if iter.fract() != 0.0 {
            return Err(StudyError::SceneParam(format!(
                "scene `friction`: `iter_glob_maxi` = {iter} must be a whole number"
            )));
        }
        Ok(Friction {
            shear: p.positive("shear", 0.4)?,
            e_n: p.positive("e_n", 1e9)?,
            coef_cont: p.positive("coef_cont", 100.0)?,
            coef_pena_cont: p.positive("coef_pena_cont", 1e10)?,
            coef_matr_frot: p.within("coef_matr_frot", 0.0, 0.0, 1.0 + f64::EPSILON)?,
            iter_glob_maxi: iter as usize,
            max_penetration: p.positive("max_penetration", 1e-3)?,
        })
    }

    /// The slip threshold of the top's sideways motion: the uniform shear
    /// G·s/H reaches μ σ_n at s = μ σ_n H / G (G = E/2 with ν = 0).
    fn threshold(&self, mu: f64) -> f64 {
        let sigma_n = YOUNG * PRESS / HEIGHT;
        mu * sigma_n * HEIGHT / (YOUNG / 2.0)
    }

    /// The contact definition of the point's method.
    fn definition(&self, p: &Point) -> Result<ContactDefinition, Failure> {
        let unsupported = |m: String| Failure::new(FailureKind::Unsupported, m);
        let coef = p.method.coefficient().unwrap_or(100.0);
        let geometry = ZoneGeometry::new("EF", "AB");
        let invalid =
            |e: aster_contact::ContactError| Failure::new(FailureKind::Other, e.to_string());
        match p.method.family() {
            MethodFamily::DiscreteFrictionPenalisation => {
                ContactDefinition::discrete_with_friction(
                    vec![Zone {
                        geometry,
                        law: DiscreteAlgo::Penalisation { e_n: self.e_n },
                    }],
                    DiscreteFrictionDef {
                        zones: vec![DiscreteZoneFriction {
                            coulomb: p.coulomb,
                            e_t: coef,
                            coef_matr_frot: self.coef_matr_frot,
                        }],
                    },
                )
                .map_err(invalid)
            }
            family @ (MethodFamily::ContinuousFrictionStandard
            | MethodFamily::ContinuousFrictionPenalisation) => {
                let mut zone = ContinueZoneFriction::new(p.coulomb);
                let contact = if family == MethodFamily::ContinuousFrictionStandard {
                    zone.algo = FrictionAlgo::Standard { coef_frot: coef };
                    ContinueAlgo::Standard {
                        coef_cont: self.coef_cont,
                    }
                } else {
                    zone.algo = FrictionAlgo::Penalisation {
                        coef_pena_frot: coef,
                    };
                    ContinueAlgo::Penalisation {
                        coef_pena_cont: self.coef_pena_cont,
                    }
                };
                ContactDefinition::continuous_with_friction(
                    vec![Zone {
                        geometry,
                        law: ContinueLaw {
                            algo: contact,
                            ..ContinueLaw::default()
                        },
                    }],
                    ContinueFriction::new(vec![zone]),
                )
                .map_err(invalid)
            }
            other => Err(unsupported(format!(
                "{} is frictionless: the friction scene runs the frictional methods \
                 (discrete-friction-penalisation, continuous-friction-standard, \
                 continuous-friction-penalisation)",
                other.spec_name()
            ))),
        }
    }
}

/// The rigid plane stretched to [−w, w], w = 1.5 + `shear` (x × w on the
/// lower plate's nodes), so that the dragged block never overhangs it: a
/// slave node past the master's end (beyond code_aster's projection
/// tolerance, half a master cell) loses its contact, and the block tips.
fn widened(mut mesh: aster_mesh::Mesh, shear: f64) -> Result<aster_mesh::Mesh, Failure> {
    let low = mesh
        .group_no("LOW")
        .map(|g| g.members.clone())
        .ok_or_else(|| Failure::new(FailureKind::Other, "generated mesh lacks node group LOW"))?;
    for n in low {
        mesh.coords[n.0 as usize][0] *= 1.5 + shear;
    }
    Ok(mesh)
}

/// The force source of a definition, discrete or continuous.
fn source(def: &ContactDefinition, model: &Model) -> Result<Box<dyn ForceSource>, Failure> {
    let other = |e: aster_contact::ContactError| Failure::new(FailureKind::Other, e.to_string());
    Ok(match def {
        ContactDefinition::Discrete(_) => {
            Box::new(DiscreteFriction::new(def, model.mesh()).map_err(other)?)
        }
        ContactDefinition::Continue(c) => {
            Box::new(ContinuousFriction::new(c, model.mesh(), Measure::Plane).map_err(other)?)
        }
    })
}

/// The kind of a fem failure; a step cut until it gives up is the kind of
/// its last piece's failure.
fn failure_kind(e: &FemError) -> FailureKind {
    match e {
        FemError::NoConvergence {
            cycling: Some(_), ..
        } => FailureKind::Cycling,
        FemError::NoConvergence { .. } | FemError::SourceLoop(_) => FailureKind::NoConvergence,
        FemError::ActiveSet { .. } => FailureKind::Cycling,
        FemError::Singular { .. } => FailureKind::SingularMatrix,
        FemError::PoorSolve { .. } => FailureKind::PoorSolve,
        FemError::StepCutting { cause, .. } | FemError::CutNotReproduced { cause, .. } => {
            failure_kind(cause)
        }
        _ => FailureKind::Other,
    }
}

/// A fem failure in the study's terms.
fn fem_failure(e: FemError) -> Failure {
    Failure::new(failure_kind(&e), e.to_string())
}

/// Σ of the internal forces K·u over a node group, per component.
fn group_force(model: &Model, internal: &[f64], group: &str, comp: Comp) -> Result<f64, Failure> {
    let nodes = model.mesh().group_no(group).ok_or_else(|| {
        Failure::new(
            FailureKind::Other,
            format!("generated mesh lacks node group {group}"),
        )
    })?;
    Ok(nodes
        .members
        .iter()
        .filter_map(|&n| model.dofs().index(Dof::new(n, comp)))
        .map(|i| internal[i])
        .sum())
}

impl Scene for Friction {
    fn quantity(&self) -> String {
        "tangential over normal force ΣFX/ΣFY (μ once sliding)".into()
    }

    fn describe(&self) -> String {
        format!(
            "stick/slip: elastic block (plane strain) pressed by {PRESS} on a rigid plane, \
             then dragged {} sideways (slides past 0.2 μ; μ analytic below shear/0.6)",
            self.shear
        )
    }

    fn run(&self, p: &Point) -> Result<Measures, Failure> {
        let other = |m: String| Failure::new(FailureKind::Other, m);
        // First, before anything is built: a frictionless method is
        // refused there, with the families the scene runs.
        let def = self.definition(p)?;
        if p.coulomb <= 0.0 {
            return Err(Failure::new(
                FailureKind::Unsupported,
                "the friction scene needs μ > 0 (sweep.coulomb)",
            ));
        }
        if p.stiffness_ratio != 1.0 {
            return Err(Failure::new(
                FailureKind::Unsupported,
                "the friction scene has a rigid plane: sweep.stiffness_ratio must be [1]",
            ));
        }
        let n = p.refine as usize;
        let mesh = two_plates_mesh(n, n + 1).map_err(|e| other(e.to_string()))?;
        let (model, loads) = two_plates_shear_problem(widened(mesh, self.shear)?, self.shear, true)
            .map_err(|e| other(e.to_string()))?;
        let mut friction = source(&def, &model)?;
        let mut instants = vec![0.0, 1.0];
        instants.extend((1..=p.steps).map(|i| 1.0 + i as f64 / p.steps as f64));
        let result = {
            let mut snl = StaticNonLinear {
                init_time: instants.first().copied(),
                final_time: instants.last().copied(),
                instants,
                convergence: Convergence {
                    iter_glob_maxi: self.iter_glob_maxi,
                    ..Convergence::default()
                },
                forces: vec![Box::new(&mut *friction) as Box<dyn ForceSource>],
                ..Default::default()
            };
            snl.solve(&model, &loads).map_err(fem_failure)?
        };
        let last = result
            .last()
            .ok_or_else(|| other("the solve stored no step".into()))?;
        let k =
            aster_fem::assembly::assemble_stiffness(&model).map_err(|e| other(e.to_string()))?;
        let internal = k.mul(&last.displacement);
        let fx = group_force(&model, &internal, "CD", Comp::DX)?;
        let fy = group_force(&model, &internal, "CD", Comp::DY)?;
        if fy.abs() <= 1e-9 * YOUNG {
            return Err(Failure::new(
                FailureKind::LostContact,
                format!("no normal force at t = 2 (ΣFY = {fy:e})"),
            ));
        }
        // Penetration into the rigid plane y = 0: −DY of the block's base.
        let base = model
            .mesh()
            .group_no("AB")
            .ok_or_else(|| other("generated mesh lacks node group AB".into()))?;
        let displacement = |node, comp| {
            model
                .dofs()
                .index(Dof::new(node, comp))
                .map(|i| last.displacement[i])
                .unwrap_or(0.0)
        };
        let penetration = base
            .members
            .iter()
            .map(|&nd| (-displacement(nd, Comp::DY)).max(0.0))
            .fold(0.0, f64::max);
        if penetration > self.max_penetration {
            return Err(Failure::new(
                FailureKind::Penetration,
                format!(
                    "the block sinks {penetration:.3e} into the plane (limit {:.1e})",
                    self.max_penetration
                ),
            ));
        }
        let slip = base
            .members
            .iter()
            .map(|&nd| displacement(nd, Comp::DX))
            .sum::<f64>()
            / base.members.len() as f64;
        let ratio = (fx / fy).abs();
        // Past three times the uniform-shear threshold the whole interface
        // slides (measured: at 1.7 times, μ = 0.6, the corners still stick
        // and ΣFX/ΣFY is 2.6 % below μ).
        let sliding = self.shear >= 3.0 * self.threshold(p.coulomb);
        let newton_iterations = result.attempts.iter().map(|a| a.iterations).sum();
        Ok(Measures {
            value: ratio,
            reference: sliding.then_some(p.coulomb),
            own_reference: None,
            h: 2.0 / n as f64,
            dofs: model.dofs().len(),
            newton_iterations,
            contact_iterations: 0,
            solver_seconds: None,
            phases: None,
            penetration: Some(penetration),
            extras: vec![
                ("normal_force".into(), fy.abs()),
                ("tangential_force".into(), fx.abs()),
                ("mean_base_slip".into(), slip),
                ("slip_threshold".into(), self.threshold(p.coulomb)),
            ],
        })
    }
}
