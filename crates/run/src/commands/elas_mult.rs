//! `MACRO_ELAS_MULT`: several linear elastic load cases solved with one
//! factorisation into one `mult_elas` result, each case named by its
//! `NOM_CAS` (code_aster's `macro_elas_mult_ops.py`).
//!
//! code_aster assembles the stiffness with the conditions of
//! `CHAR_MECA_GLOBAL` only, factorises it once, and solves each
//! `CAS_CHARGE` for the right-hand side of its `CHAR_MECA` plus
//! `CHAR_MECA_GLOBAL` (imposed values included), then stores `DEPL` under
//! `NOM_CAS` at NUME_ORDRE 1, 2, … and computes `SIEF_ELGA` unless
//! `OPTION='SANS'`. Here the cases go through MECA_STATIQUE's path
//! ([`crate::fembridge::solve`]): case k is the solve's k-th instant, its
//! loads multiplied by 1 at that instant and 0 at the others, the global
//! ones by 1 everywhere, so the one factorisation of the solve serves every
//! case. Refused before solving, located: load functions of `INST` and
//! temperatures varying in time (code_aster evaluates them at instants of
//! its own, which a case's instant here is not), conditions in a case's
//! `CHAR_MECA` (they are not in code_aster's matrix), `MODE_FOURIER`
//! (`AXIS_FOURIER` is not a modelisation aster has), `VECT_ASSE` and
//! `LIAISON_DISCRET`.

use crate::concept::*;
use crate::executor::{store_result, Executor};
use crate::function::Function;
use crate::solve::{Excitation, LoadRef};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use std::rc::Rc;

/// What MACRO_ELAS_MULT reads (`crate::support`).
pub(crate) const MACRO_ELAS_MULT: Support = Support {
    keywords: &[
        "RESULTAT",
        "MODELE",
        "CHAM_MATER",
        "CARA_ELEM",
        "NUME_DDL",
        "CHAR_MECA_GLOBAL",
        "CAS_CHARGE",
        "CAS_CHARGE/NOM_CAS",
        "CAS_CHARGE/CHAR_MECA",
        "CAS_CHARGE/OPTION",
        "CAS_CHARGE/SOUS_TITRE",
        // A direct solve whatever the method: the same answer.
        "SOLVEUR",
        "SOLVEUR/*",
        "INFO",
        "TITRE",
    ],
    values: &[Values::new("CAS_CHARGE/OPTION", &["SIEF_ELGA", "SANS"])],
    hints: &[
        (
            "CAS_CHARGE/MODE_FOURIER",
            "Fourier modes need the AXIS_FOURIER modelisation, which aster does not have",
        ),
        (
            "CAS_CHARGE/VECT_ASSE",
            "an assembled right-hand side as a load case: give the loads as CHAR_MECA",
        ),
        (
            "LIAISON_DISCRET",
            "discrete-contact conditions as load cases: give CHAR_MECA_GLOBAL",
        ),
    ],
    reuse: true,
    rules: None,
};

/// The load cases of a `mult_elas`, with what they were solved on (a
/// `reuse` adds cases solved on the same).
#[derive(Debug)]
pub struct LoadCases {
    pub model: Rc<ModelDef>,
    pub materials: Rc<MaterialField>,
    pub cara: Option<Rc<CaraElem>>,
    /// `CHAR_MECA_GLOBAL`: in every case, its conditions in the matrix.
    pub global: Vec<Rc<MechanicalLoad>>,
    /// In NUME_ORDRE order (the i-th at NUME_ORDRE i + 1).
    pub cases: Vec<LoadCase>,
}

/// One `CAS_CHARGE` occurrence.
#[derive(Clone, Debug)]
pub struct LoadCase {
    /// `NOM_CAS`.
    pub name: String,
    /// `CHAR_MECA`.
    pub loads: Vec<Rc<MechanicalLoad>>,
    /// `OPTION='SIEF_ELGA'` (the default): the stresses are stored.
    pub stresses: bool,
}

impl LoadCases {
    /// The NUME_ORDRE of case `name`.
    pub fn order_of(&self, name: &str) -> Option<u32> {
        self.cases
            .iter()
            .position(|c| c.name == name)
            .map(|i| i as u32 + 1)
    }

    /// The NOM_CAS stored at a NUME_ORDRE.
    pub fn name_of(&self, nume_ordre: u32) -> Option<&str> {
        let i = (nume_ordre as usize).checked_sub(1)?;
        self.cases.get(i).map(|c| c.name.as_str())
    }
}

const CMD: &str = "MACRO_ELAS_MULT";

/// The mechanical loads a keyword names (`CHAR_MECA_GLOBAL`,
/// `CAS_CHARGE/CHAR_MECA`).
fn loads_of(
    ex: &Executor,
    kw: &Keywords,
    name: &str,
) -> Result<Vec<Rc<MechanicalLoad>>, ExecError> {
    let mut out = Vec::new();
    for s in kw.simple(name) {
        let Some(c) = s.as_concept() else { continue };
        match ex.concept(c)? {
            Concept::MechanicalLoad(l) => out.push(l.clone()),
            other => {
                return Err(ex.kw_error(
                    CMD,
                    kw,
                    name,
                    format!("`{}` is {}, expected AFFE_CHAR_MECA", c.name, other.kind()),
                ))
            }
        }
    }
    Ok(out)
}

/// Whether a load holds conditions (dualised in code_aster: terms of the
/// matrix).
fn has_conditions(l: &MechanicalLoad) -> bool {
    !l.imposed.is_empty()
        || !l.relations.is_empty()
        || !l.imposed_fn.is_empty()
        || !l.relations_fn.is_empty()
}

/// Whether a load holds a function of `INST`.
fn depends_on_time(l: &MechanicalLoad) -> bool {
    let of_time = |f: &LoadFunction| f.0.parameters().contains(&"INST");
    l.imposed_fn
        .iter()
        .chain(&l.nodal_forces_fn)
        .any(|i| of_time(&i.function))
        || l.relations_fn.iter().any(|r| of_time(&r.function))
        || l.boundary_fn.iter().any(|b| match b {
            BoundaryFn::Force { force, .. } => force.iter().flatten().any(of_time),
            BoundaryFn::Pressure { pressure, .. } => of_time(pressure),
        })
        || l.volume
            .iter()
            .any(|v| v.functions.iter().flatten().any(of_time))
        || l.edges
            .iter()
            .any(|e| e.functions.iter().flatten().any(of_time))
        || l.shells
            .iter()
            .any(|s| s.functions.iter().flatten().any(of_time))
}

/// The multiplier that selects case `k` (the solve's instant `k`): 1 there,
/// 0 at the other cases' instants.
fn case_selector(k: usize) -> Rc<Function> {
    let at = k as f64;
    Rc::new(Function::Formula {
        parameters: vec!["INST".into()],
        eval: Rc::new(move |args: &[(String, f64)]| {
            let t = args.first().map_or(f64::NAN, |a| a.1);
            Ok(if (t - at).abs() < 0.5 { 1.0 } else { 0.0 })
        }),
    })
}

pub fn macro_elas_mult(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    // MECA_STATIQUE's set-up of the model, materials and elements (their
    // checks included); the loads and instants are the cases'.
    let mut setup = crate::solve::parse_setup(ex, call, true)?;
    let global = loads_of(ex, kw, "CHAR_MECA_GLOBAL")?;
    let time_refusal = |occ: &Keywords, key: &str, what: &str| {
        ex.unsupported(
            &format!("{CMD}/{what}: a load given by functions of INST (code_aster evaluates them at an instant of its own, not reproduced)"),
            occ.keyword(key).map_or(call.span, |k| k.span),
        )
    };
    if global.iter().any(|l| depends_on_time(l)) {
        return Err(time_refusal(kw, "CHAR_MECA_GLOBAL", "CHAR_MECA_GLOBAL"));
    }
    let mut new_cases: Vec<LoadCase> = Vec::new();
    for occ in kw.factor("CAS_CHARGE") {
        let Some(name) = occ.str("NOM_CAS") else {
            return Err(ex.unsupported(
                &format!("{CMD}/CAS_CHARGE without NOM_CAS (Fourier modes)"),
                occ.entries.first().map_or(call.span, |k| k.span),
            ));
        };
        let loads = loads_of(ex, occ, "CHAR_MECA")?;
        if loads.iter().any(|l| depends_on_time(l)) {
            return Err(time_refusal(occ, "CHAR_MECA", "CAS_CHARGE/CHAR_MECA"));
        }
        for l in &loads {
            let why = if has_conditions(l) {
                "a load with conditions (DDL_IMPO, LIAISON_*) as a case's CHAR_MECA: code_aster's matrix holds the conditions of CHAR_MECA_GLOBAL only"
            } else if global.iter().any(|g| Rc::ptr_eq(g, l)) {
                "a load both in CHAR_MECA_GLOBAL and in a case's CHAR_MECA (code_aster would add it twice)"
            } else {
                continue;
            };
            return Err(ex.unsupported(
                &format!("{CMD}/CAS_CHARGE/CHAR_MECA: {why}"),
                occ.keyword("CHAR_MECA").map_or(call.span, |k| k.span),
            ));
        }
        let case = LoadCase {
            name: name.to_string(),
            loads,
            stresses: occ.str("OPTION").unwrap_or("SIEF_ELGA") == "SIEF_ELGA",
        };
        // A NOM_CAS given twice: the later replaces the earlier (CREA_RESU's
        // AFFE finds the case by its name).
        match new_cases.iter_mut().find(|c| c.name == case.name) {
            Some(c) => *c = case,
            None => new_cases.push(case),
        }
    }
    if let Some(t) = setup
        .materials
        .temperature
        .as_ref()
        .filter(|t| t.fields.len() > 1)
    {
        return Err(ex.unsupported(
            &format!("{CMD} with a temperature varying in time (AFFE_VARC/EVOL at {}): code_aster takes it at an instant of its own, not reproduced", t.at),
            kw.keyword("CHAM_MATER").map_or(call.span, |k| k.span),
        ));
    }
    if let Some(t) = setup
        .materials
        .temperature
        .as_ref()
        .filter(|t| t.shell.is_some())
    {
        return Err(ex.unsupported(
            &format!("{CMD} with a temperature through the thickness of shells (CREA_RESU/PREP_VARC, AFFE_VARC at {}): not done", t.at),
            kw.keyword("CHAM_MATER").map_or(call.span, |k| k.span),
        ));
    }
    // reuse=: the cases of the result first (a NOM_CAS again replaces its
    // case), solved again with the new ones on the same model, materials,
    // elements and global loads.
    let previous = match &call.reuse {
        Some(r) => Some(ex.result(r)?),
        None => None,
    };
    let mut cases: Vec<LoadCase> = Vec::new();
    if let Some(prev) = &previous {
        let Some(pc) = prev.cases.as_ref() else {
            return Err(ex.kw_error(
                CMD,
                kw,
                "RESULTAT",
                "reuse= of a result that is not a MACRO_ELAS_MULT's (mult_elas)",
            ));
        };
        let same = Rc::ptr_eq(&pc.model, &setup.model)
            && Rc::ptr_eq(&pc.materials, &setup.materials)
            && match (&pc.cara, &setup.cara) {
                (None, None) => true,
                (Some(a), Some(b)) => Rc::ptr_eq(a, b),
                _ => false,
            }
            && pc.global.len() == global.len()
            && pc.global.iter().zip(&global).all(|(a, b)| Rc::ptr_eq(a, b));
        if !same {
            return Err(ex.unsupported(
                &format!("{CMD} with reuse= on another MODELE, CHAM_MATER, CARA_ELEM or CHAR_MECA_GLOBAL than the reused result's (one factorisation serves the cases of a result here)"),
                call.span,
            ));
        }
        cases.clone_from(&pc.cases);
    }
    let first_new = cases.len();
    let mut replaced: Vec<usize> = Vec::new();
    for case in new_cases {
        match cases.iter().position(|c| c.name == case.name) {
            Some(i) => {
                replaced.push(i);
                cases[i] = case;
            }
            None => cases.push(case),
        }
    }
    if let Some(n) = kw.concept("NUME_DDL") {
        let model_id = ex.required(CMD, kw, "MODELE")?.id;
        match ex.concept(n) {
            Ok(Concept::Numbering(id)) if *id != model_id => {
                return Err(ex.kw_error(
                    CMD,
                    kw,
                    "NUME_DDL",
                    format!("`{}` numbers another model's DOFs", n.name),
                ))
            }
            Ok(Concept::Numbering(_)) => {}
            _ => {
                let n = n.clone();
                ex.insert(&n, Concept::Numbering(model_id));
            }
        }
    }
    // Case k (1-based) is the solve's instant k.
    setup.excitations = global
        .iter()
        .map(|l| Excitation {
            load: LoadRef::Mechanical(l.clone()),
            multiplier: None,
            kind: Default::default(),
        })
        .collect();
    for (i, case) in cases.iter().enumerate() {
        for l in &case.loads {
            setup.excitations.push(Excitation {
                load: LoadRef::Mechanical(l.clone()),
                multiplier: Some(case_selector(i + 1)),
                kind: Default::default(),
            });
        }
    }
    setup.instants = (1..=cases.len()).map(|k| k as f64).collect();
    let (solved, fem) = crate::fembridge::solve(ex, &setup, true)?;
    let mut steps = Vec::with_capacity(cases.len());
    for (mut step, case) in solved.into_iter().zip(&cases) {
        let i = step.nume_ordre as usize - 1;
        // A case of the reused result keeps its stored fields (those
        // CALC_CHAMP added): the same solve gives the same state.
        if let Some(prev) = previous
            .as_ref()
            .filter(|_| i < first_new && !replaced.contains(&i))
        {
            if let Some(s) = prev.step_numbered(step.nume_ordre) {
                steps.push(s.clone());
                continue;
            }
        }
        // A mult_elas has no instant.
        step.inst = 0.0;
        if !case.stresses {
            step.fields.remove("SIEF_ELGA");
        }
        steps.push(step);
    }
    let mesh = setup.model.mesh;
    let result = EvolResult {
        prep_varc: false,
        typ: "mult_elas".into(),
        mesh,
        steps,
        fem: Some(fem),
        tables: Vec::new(),
        modal: None,
        thermal: None,
        cases: Some(Rc::new(LoadCases {
            model: setup.model.clone(),
            materials: setup.materials.clone(),
            cara: setup.cara.clone(),
            global,
            cases,
        })),
    };
    store_result(ex, call, Concept::Result(Rc::new(result)))
}
