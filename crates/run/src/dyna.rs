//! DYNA_NON_LINE: the keywords of STAT_NON_LINE (read by
//! [`crate::solve::parse_setup`]) plus the time scheme (`SCHEMA_TEMPS`),
//! the mass (`ELAS/RHO`, discrete masses, `MASS_DIAG`), Rayleigh damping
//! (`AMOR_ALPHA`, `AMOR_BETA`) and the initial velocity and acceleration
//! (`ETAT_INIT`), turned into aster-fem's [`DynamicNonLinear`]. The Newton
//! loop, conditions, contact and behaviours are STAT_NON_LINE's.

use crate::concept::ContactDef;
use crate::executor::Executor;
use crate::field::Field;
use crate::solve::{parse_setup, snl_rules, store_solution, SolveSetup, SNL_KEYWORDS, SNL_VALUES};
use crate::support::{joined, Refusal, Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_fem::{
    DiscreteMass, DynamicNonLinear, Frame, Lumping, MassData, Model, NonLinearResult, Rayleigh,
    Scheme, StaticNonLinear,
};
use aster_mesh::Mesh;
use std::collections::HashMap;
use std::rc::Rc;

/// DYNA_NON_LINE's settings beyond STAT_NON_LINE's.
#[derive(Clone, Debug)]
pub struct DynamicSetup {
    pub scheme: Scheme,
    pub lumping: Lumping,
    /// `ENERGIE`: code_aster's energy balance, the result's `PARA_CALC`
    /// table.
    pub energy: bool,
}

/// The keywords DYNA_NON_LINE executes besides STAT_NON_LINE's.
const DYNA_KEYWORDS: &[&str] = &[
    "SCHEMA_TEMPS",
    "SCHEMA_TEMPS/SCHEMA",
    "SCHEMA_TEMPS/FORMULATION",
    "SCHEMA_TEMPS/BETA",
    "SCHEMA_TEMPS/GAMMA",
    "SCHEMA_TEMPS/ALPHA",
    "SCHEMA_TEMPS/MODI_EQUI",
    "MASS_DIAG",
    "AMOR_RAYL_RIGI",
    "ETAT_INIT/VITE",
    "ETAT_INIT/ACCE",
    "ENERGIE",
    "ENERGIE/CALCUL",
];

/// The values DYNA_NON_LINE handles besides STAT_NON_LINE's.
const DYNA_VALUES: &[Values] = &[
    Values::new("SCHEMA_TEMPS/SCHEMA", &["NEWMARK", "HHT"])
        .why("(the explicit schemes and NOHHT are not implemented: no contact case uses them)"),
    Values::new("SCHEMA_TEMPS/FORMULATION", &["DEPLACEMENT"])
        .why("(only the displacement formulation of the implicit schemes)"),
    Values::new("AMOR_RAYL_RIGI", &["ELASTIQUE"])
        .why("(Rayleigh damping on the tangent stiffness)"),
];

const DYNA_ALL_KEYWORDS: [&str; SNL_KEYWORDS.len() + DYNA_KEYWORDS.len()] =
    joined(SNL_KEYWORDS, DYNA_KEYWORDS);
const DYNA_ALL_VALUES: [Values; SNL_VALUES.len() + DYNA_VALUES.len()] =
    joined(SNL_VALUES, DYNA_VALUES);

/// What DYNA_NON_LINE reads (`crate::support`): STAT_NON_LINE's keywords
/// and values, the time scheme, the mass options and the initial velocity
/// and acceleration.
pub(crate) const DYNA_NON_LINE: Support = Support {
    keywords: &DYNA_ALL_KEYWORDS,
    values: &DYNA_ALL_VALUES,
    hints: &[],
    reuse: true,
    rules: Some(dyna_rules),
};

/// STAT_NON_LINE's rules, the finite-strain kinematics not validated in
/// dynamics and a mass shift (`COEF_MASS_SHIFT`) refused.
fn dyna_rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    snl_rules(call, out);
    // PETIT_REAC (SDNL111D) and SIMO_MIEHE (SDNV103E/K) are validated in
    // dynamics, every TEST_RESU OK; the total-Lagrangian kinematics are
    // not: with GDEF_LOG lifted, ssnp165b/d (continuous Coulomb contact
    // under large sliding, HHT) end 16/24 and 6/10 NOOK, 1e-3 to 2.5e-2
    // off, and ssnp165a stops in the geometric loop at t = 0.75 as the
    // static ssnp165e does at 0.758 (the contact, not the inertia,
    // differs). SIMO_MIEHE needed the inertia
    // force on the increment (`IncrementTerms::force`) and ΔF from the
    // increment (`nmgpfi`): a symmetry velocity tested at 1e-8 absolute
    // was round-off amplified by γ/(βΔt) = 3.7e7 (6.7e-8; now 2.7e-10,
    // code_aster 2.1e-9).
    for occ in call.keywords.factor("COMPORTEMENT") {
        if let Some(d @ ("GREEN_LAGRANGE" | "GROT_GDEP" | "GDEF_LOG")) = occ.str("DEFORMATION") {
            out.push(Refusal::at(
                format!(
                    "DYNA_NON_LINE/COMPORTEMENT/DEFORMATION='{d}' (total-Lagrangian finite strains in dynamics are not validated against code_aster: PETIT, PETIT_REAC and SIMO_MIEHE only; the real GDEF_LOG cases, with a continuous contact under large sliding, end 1e-3 to 2.5e-2 off or stop in its geometric loop as their static twin does; SDNV103G (HEXA20 3D_SI, discrete penalised Coulomb contact, HHT) with it lifted ends 2 OK / 1 NOOK, its slave node B1 off the wall by 3.6e-2 at t = 2.5e-7 where code_aster's JEU is 0 — the same with PETIT_REAC or VMIS_ISOT_LINE, cause not found; docs/fem.md)"
                ),
                occ,
                "DEFORMATION",
                call.span,
            ));
        }
    }
    for st in call.keywords.factor("SCHEMA_TEMPS") {
        if st.f64("COEF_MASS_SHIFT").is_some_and(|c| c != 0.0) {
            out.push(Refusal::at(
                "DYNA_NON_LINE/SCHEMA_TEMPS/COEF_MASS_SHIFT (mass shift)".into(),
                st,
                "COEF_MASS_SHIFT",
                call.span,
            ));
        }
    }
}

pub fn dyna_non_line(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let mut setup = parse_setup(ex, call, false)?;
    let dynamics = parse_dynamics(ex, call)?;
    // The weighted equilibrium also weights the continuous contact forces
    // of the previous step (code_aster's CNELTC): not done here; nor
    // validated for the discrete friction forces (no real case).
    if let (Scheme::Hht { modified: true, .. }, Some(c)) = (dynamics.scheme, &setup.contact) {
        if let ContactDef::Zones { keywords, .. } = &**c {
            let continuous = keywords.str("FORMULATION") == Some("CONTINUE");
            let friction = keywords.str("FROTTEMENT") == Some("COULOMB");
            if continuous || friction {
                let span = call
                    .keywords
                    .factor("SCHEMA_TEMPS")
                    .first()
                    .and_then(|st| st.keyword("MODI_EQUI").or(st.keyword("SCHEMA")))
                    .map(|k| k.span)
                    .unwrap_or(call.span);
                return Err(ex.unsupported(
                    if continuous {
                        "DYNA_NON_LINE/SCHEMA_TEMPS HHT with MODI_EQUI='OUI' and a continuous contact (FORMULATION='CONTINUE': its forces of the previous step are weighted)"
                    } else {
                        "DYNA_NON_LINE/SCHEMA_TEMPS HHT with MODI_EQUI='OUI' and discrete friction (FROTTEMENT='COULOMB': how code_aster weights the friction forces of the previous step is not validated; MODI_EQUI='NON' is)"
                    },
                    span,
                ));
            }
        }
    }
    // Discrete penalised friction with a plastic behaviour in dynamics:
    // code_aster's answer is where its Newton stops on the friction's
    // linear convergence, carried forward by the plastic strains and the
    // inertia. Its iterates are reproduced (the prediction, the matrix of
    // each iterate, the geometric loop nested in Newton, at most
    // ITER_GLOB_MAXI residual checks per increment as `nmconv` counts
    // them), and the increments code_aster cuts are cut: SDNV103J (one
    // pairing per increment, NB_ITER_GEOM=1, its cuts forced by
    // ITER_GLOB_MAXI=5) ends within 2e-11 of code_aster. With a geometric
    // loop of two or more pairings per increment and a cut, SDNV103B stays
    // 0.1-7.6 % off code_aster, cause not found: a failed increment is not
    // cut there, the analysis stops, refused (docs/friction.md).
    if let Some(c) = &setup.contact {
        if let ContactDef::Zones { keywords, .. } = &**c {
            let reac_geom = keywords.str("REAC_GEOM").unwrap_or("AUTOMATIQUE");
            let nb_iter_geom = keywords.f64("NB_ITER_GEOM").unwrap_or(2.0);
            let several_pairings = match reac_geom {
                "SANS" => false,
                "CONTROLE" => nb_iter_geom >= 2.0,
                _ => true,
            };
            if keywords.str("FROTTEMENT") == Some("COULOMB")
                && keywords.str("FORMULATION").unwrap_or("DISCRETE") == "DISCRETE"
                && several_pairings
            {
                let plastic = call
                    .keywords
                    .factor("COMPORTEMENT")
                    .iter()
                    .find(|occ| occ.str("RELATION").is_some_and(|r| r != "ELAS"));
                if let Some(occ) = plastic {
                    let span = occ.keyword("RELATION").map(|k| k.span).unwrap_or(call.span);
                    let geom = if reac_geom == "CONTROLE" {
                        format!("REAC_GEOM='CONTROLE', NB_ITER_GEOM={nb_iter_geom}")
                    } else {
                        format!("REAC_GEOM='{reac_geom}'")
                    };
                    setup.cut_refused = Some(format!(
                        "DYNA_NON_LINE/COMPORTEMENT/RELATION='{}'{} with discrete friction (FORMULATION='DISCRETE', FROTTEMENT='COULOMB') and a geometric loop of several pairings per increment (DEFI_CONTACT/{geom}): after a cut the answer is 0.1-7.6 % off code_aster's on SDNV103B, cause not found (cuts are reproduced with one pairing per increment, NB_ITER_GEOM=1)",
                        occ.str("RELATION").unwrap_or(""),
                        ex.location(span).map(|l| format!(" ({l})")).unwrap_or_default()
                    ));
                }
            }
        }
    }
    if dynamics.energy {
        if let Some(c) = &setup.contact {
            let continuous = match &**c {
                ContactDef::Zones { keywords, .. } => {
                    keywords.str("FORMULATION") == Some("CONTINUE")
                }
                _ => false,
            };
            if continuous {
                let span = call
                    .keywords
                    .keyword("ENERGIE")
                    .map_or(call.span, |k| k.span);
                return Err(ex.unsupported(
                    "DYNA_NON_LINE/ENERGIE with a continuous contact (FORMULATION='CONTINUE': code_aster moves the contact elements' forces CNELTC/CNELTF from the internal forces to the links' work; not reproduced)",
                    span,
                ));
            }
        }
    }
    setup.dynamics = Some(dynamics);
    store_solution(ex, call, &setup, false)
}

fn parse_dynamics(ex: &Executor, call: &CommandCall) -> Result<DynamicSetup, ExecError> {
    let cmd = call.command.as_str();
    let kw = &call.keywords;
    let Some(st) = kw.factor("SCHEMA_TEMPS").first() else {
        return Err(ExecError::new(format!("{cmd}: SCHEMA_TEMPS is required")));
    };
    let real = |name: &str, default: f64| st.f64(name).unwrap_or(default);
    let scheme = match st.str("SCHEMA") {
        Some("HHT") => Scheme::Hht {
            alpha: real("ALPHA", -0.1),
            modified: st.str("MODI_EQUI").unwrap_or("OUI") == "OUI",
        },
        _ => Scheme::Newmark {
            beta: real("BETA", 0.25),
            gamma: real("GAMMA", 0.5),
        },
    };
    // code_aster (MECANONLINE5_13): a diagonal mass is for explicit schemes.
    if kw.str("MASS_DIAG") == Some("OUI") {
        return Err(ex.kw_error(
            cmd,
            kw,
            "MASS_DIAG",
            "a diagonal (lumped) mass is only for the explicit schemes (DIFF_CENT, TCHAMWA); the implicit NEWMARK and HHT use the consistent mass",
        ));
    }
    let energy = kw.keyword("ENERGIE").is_some_and(|k| !k.defaulted);
    if energy {
        // The balance of aster-fem's `energy_balance` is code_aster's
        // `nmener`/`enerca` for the forces reproduced here: the weighted
        // equilibrium (its reactions) and the continuous contact elements
        // (code_aster moves their forces from the internal forces to the
        // links, CNELTC/CNELTF) are not validated.
        let span = kw.keyword("ENERGIE").map_or(call.span, |k| k.span);
        if let Scheme::Hht { modified: true, .. } = scheme {
            return Err(ex.unsupported(
                "DYNA_NON_LINE/ENERGIE with HHT MODI_EQUI='OUI' (the energy balance of the weighted equilibrium is not validated; MODI_EQUI='NON' and NEWMARK are)",
                span,
            ));
        }
    }
    Ok(DynamicSetup {
        scheme,
        lumping: Lumping::Consistent,
        energy,
    })
}

/// The densities (ELAS/RHO) of the model's cells, the discrete masses and
/// the Rayleigh coefficients.
pub(crate) fn mass_data(
    mesh: &Mesh,
    model: &crate::concept::ModelDef,
    materials: &crate::concept::MaterialField,
    cara: Option<&crate::concept::CaraElem>,
) -> Result<(MassData, HashMap<aster_mesh::CellId, Rayleigh>), ExecError> {
    let mut data = MassData::default();
    let mut rayleigh = HashMap::new();
    for (&cell, _) in model.cells.iter() {
        let Some(mat) = materials.cells.get(&cell) else {
            continue;
        };
        if let Some(rho) = mat.resolved_density().map_err(ExecError::new)? {
            data.density.insert(cell, rho);
        }
        let r = Rayleigh {
            alpha: mat.amor_alpha.unwrap_or(0.0),
            beta: mat.amor_beta.unwrap_or(0.0),
        };
        if r.alpha != 0.0 || r.beta != 0.0 {
            rayleigh.insert(cell, r);
        }
    }
    if let Some(cara) = cara {
        data.discrete = discrete_masses(mesh, model, cara)?;
    }
    Ok((data, rayleigh))
}

/// The discrete masses of `AFFE_CARA_ELEM` (`M_T_D_N`, `M_TR_D_N`,
/// `M_TR_D_L`, the matrices `M_T_N`…) on the cells of a model.
pub(crate) fn discrete_masses(
    mesh: &Mesh,
    model: &crate::concept::ModelDef,
    cara: &crate::concept::CaraElem,
) -> Result<Vec<DiscreteMass>, ExecError> {
    let mut out = Vec::new();
    for m in &cara.masses {
        for &cell in &m.cells {
            if !model.cells.contains_key(&cell) {
                return Err(ExecError::new(format!(
                    "AFFE_CARA_ELEM: a mass ({}) on cell {}, which is not in the model",
                    m.cara,
                    crate::select::cell_name(mesh, cell)
                )));
            }
            let frame = if m.local { Frame::Local } else { Frame::Global };
            out.push(match (m.cara.as_str(), m.values.len()) {
                ("M_TR_D_N", 10) => {
                    let mut v = [0.0; 10];
                    v.copy_from_slice(&m.values);
                    DiscreteMass::node_with_inertia(cell, &v)
                }
                ("M_TR_D_L", 4) => {
                    let mut v = [0.0; 4];
                    v.copy_from_slice(&m.values);
                    DiscreteMass::segment_with_inertia(cell, &v, frame)
                }
                ("M_T_D_N", 1) => DiscreteMass::Node {
                    cell,
                    mass: m.values[0],
                },
                _ => DiscreteMass::Matrix {
                    cell,
                    upper: m.values.clone(),
                    frame,
                },
            });
        }
    }
    Ok(out)
}

/// A vector per DOF index of `model` from a nodal field (components the
/// field lacks are zero).
fn dof_vector(model: &Model, field: &Field) -> Option<Vec<f64>> {
    let Field::Nodal(f) = field else {
        return None;
    };
    Some(
        model
            .dofs()
            .dofs()
            .iter()
            .map(|d| f.get(d.node, d.comp.name()).unwrap_or(0.0))
            .collect(),
    )
}

/// Runs the dynamic analysis of a set-up with the static solver `solver`
/// (instants, Newton, conditions, contact, behaviours, initial
/// displacement) and the initial velocity and acceleration: those of
/// `ETAT_INIT`, else of its `EVOL_NOLI` step, else zero and the
/// equilibrium's.
pub(crate) fn solve(
    ex: &mut Executor,
    dynamics: &DynamicSetup,
    setup: &SolveSetup,
    mesh: &Mesh,
    model: &Model,
    loads: &aster_fem::Loads,
    solver: StaticNonLinear<'_>,
) -> Result<Result<NonLinearResult, aster_fem::FemError>, ExecError> {
    let cmd = "DYNA_NON_LINE";
    let (data, rayleigh) = mass_data(mesh, &setup.model, &setup.materials, setup.cara.as_deref())?;
    let mut dyna = DynamicNonLinear::new(solver, dynamics.scheme, data);
    dyna.lumping = dynamics.lumping;
    dyna.rayleigh = rayleigh;
    dyna.energy = dynamics.energy;
    let vector = |f: &(Rc<Field>, aster_syntax::Span), what: &str| {
        dof_vector(model, &f.0).ok_or_else(|| {
            ExecError::new(format!(
                "{cmd}/ETAT_INIT/{what}: expected a nodal field (CREA_CHAMP NOEU_DEPL_R)"
            ))
        })
    };
    if let Some(v) = &setup.initial_fields.vite {
        dyna.velocity = Some(vector(v, "VITE")?);
    }
    if let Some(a) = &setup.initial_fields.acce {
        dyna.acceleration = Some(vector(a, "ACCE")?);
    }
    if let Some((prev, t0)) = &setup.initial {
        if let Some(step) = prev.step_at(*t0, 1e-6, false) {
            if let Some(v) = step.fields.get("VITE") {
                dyna.velocity = dof_vector(model, v);
            }
            if let Some(a) = step.fields.get("ACCE") {
                dyna.acceleration = dof_vector(model, a);
            }
        }
    }
    let out = dyna.solve(model, loads);
    if dyna.acceleration_singular {
        ex.write_report(
            "<A> DYNA_NON_LINE: the initial acceleration could not be computed (the mass matrix is singular): it is taken as zero, as code_aster does (MECANONLINE_69)\n",
        )?;
    }
    Ok(out)
}

/// The initial displacement of `ETAT_INIT/DEPL` given without stresses.
/// code_aster starts such a state stress-free: σ₀ = 0 (no `SIGM`) and its
/// elastic law is incremental (`nmelas`: σ = σ₀ + D·Δε), so the strains
/// count from u₀. The solver here computes elastic stresses from the total
/// displacement, which is the same only when u₀ strains nothing: a rigid
/// motion of each body, K·u₀ = 0 to rounding (‖K·u₀‖∞ ≤ 1e-10 · max Kᵢᵢ ·
/// ‖u₀‖∞). Such a u₀ is the initial state (stored at the first instant, the
/// geometry of contact pairing moved by it); any other is refused at the
/// keyword.
pub(crate) fn initial_displacement(
    ex: &Executor,
    setup: &SolveSetup,
    model: &Model,
) -> Result<Option<Vec<f64>>, ExecError> {
    let Some((f, span)) = &setup.initial_fields.depl else {
        return Ok(None);
    };
    let Some(u0) = dof_vector(model, f) else {
        return Err(ex.unsupported(
            "ETAT_INIT/DEPL other than a nodal field (CREA_CHAMP NOEU_DEPL_R)",
            *span,
        ));
    };
    let umax = u0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if umax == 0.0 {
        return Ok(None);
    }
    let k = aster_fem::assembly::assemble_stiffness(model)
        .map_err(|e| ExecError::new(format!("ETAT_INIT/DEPL: {e}")))?;
    let kmax = k.diagonal().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let ku = k.mul(&u0);
    let kumax = ku.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if kumax > 1e-10 * kmax * umax {
        return Err(ex.unsupported(
            &format!(
                "ETAT_INIT/DEPL with a displacement that strains the structure (|K·u0| = {kumax:.3e}, not zero: code_aster starts it stress-free, its strains counted from u0, and aster's elastic stresses are those of the total displacement) and no SIGM"
            ),
            *span,
        ));
    }
    Ok(Some(u0))
}
