//! code_aster 11 commands that code_aster 17 replaced by another one with a
//! faithful keyword mapping (done by code_aster itself in versions 12–13,
//! when the old commands became macros over the new one, then were
//! removed). Applied only to code_aster 11 files (see
//! `aster_syntax::dialect::generation`); the call handed to the sink is the
//! new command, so the runner never sees the old name.
//!
//! | old | new |
//! | --- | --- |
//! | `MODE_ITER_SIMULT` | `CALC_MODES` (`CALC_FREQ/OPTION` → `OPTION`, method keywords → `SOLVEUR_MODAL`) |
//! | `MODE_ITER_INV` | `CALC_MODES` (same, `CALC_MODE` → `SOLVEUR_MODAL/OPTION_INV...`, `OPTION` defaults to `'AJUSTE'`) |
//! | `MACRO_MATR_ASSE` | `ASSEMBLAGE` (same keywords; `SOLVEUR` dropped: the numbering is the solver's) |
//! | `CREA_MAILLAGE(MAILLAGE=M, COPIE=_F())` | `COPIER(CONCEPT=M)` |

use crate::diag::{DiagKind, Diagnostic};
use crate::validate::Given;
use crate::value::{Dict, Value};
use aster_syntax::Span;
use std::cell::RefCell;
use std::rc::Rc;

/// (old command, new command).
pub const REPLACED: &[(&str, &str)] = &[
    ("MODE_ITER_SIMULT", "CALC_MODES"),
    ("MODE_ITER_INV", "CALC_MODES"),
    ("MACRO_MATR_ASSE", "ASSEMBLAGE"),
];

/// The command that replaced `old`, if its keywords map faithfully.
pub fn replacement(old: &str) -> Option<&'static str> {
    REPLACED.iter().find(|(o, _)| *o == old).map(|(_, n)| *n)
}

/// code_aster 11 commands removed later whose keywords do not map onto a
/// current command: in a code_aster 11 file they are "not supported" (with
/// what replaced them), not unknown names.
pub const REMOVED_AFTER_V11: &[(&str, &str)] = &[
    ("CALC_THETA", "removed after code_aster 11; the theta field is now given to CALC_G (THETA=_F(...))"),
    ("INTE_MAIL_2D", "removed after code_aster 11; results along a path are now extracted with MACR_LIGN_COUPE"),
    ("INTE_MAIL_3D", "removed after code_aster 11; results along a path are now extracted with MACR_LIGN_COUPE"),
    ("DEFI_PART_FETI", "removed with the FETI solver; the distribution of the elements is AFFE_MODELE/DISTRIBUTION"),
    ("DEFI_PART_OPS", "removed with the FETI solver; the distribution of the elements is AFFE_MODELE/DISTRIBUTION"),
    ("CALC_MODAL", "removed; modes are computed with CALC_MODES"),
    ("MACRO_MODE_MECA", "removed after code_aster 11; modes in a frequency band are computed with CALC_MODES(OPTION='BANDE')"),
    ("DYNA_TRAN_MODAL", "removed after code_aster 11; now DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE')"),
    ("MACR_ECLA_PG", "removed; now CREA_MAILLAGE(ECLA_PG=...) then PROJ_CHAMP(METHODE='ECLA_PG')"),
    ("POST_GP", "removed after code_aster 11"),
    ("GENE_MATR_ALEA", "removed after code_aster 11"),
];

/// Why a code_aster 11 command is gone, if it is one of [`REMOVED_AFTER_V11`].
pub fn removed_after_v11(name: &str) -> Option<&'static str> {
    REMOVED_AFTER_V11
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, why)| *why)
}

/// A command that code_aster 17 still has, called with a keyword that made
/// it another command's job: `CREA_MAILLAGE(COPIE=_F())` copied a mesh,
/// now `COPIER`.
pub(crate) fn replacement_by_keywords(name: &str, given: &[Given]) -> Option<&'static str> {
    (name == "CREA_MAILLAGE" && given.iter().any(|g| g.name == "COPIE")).then_some("COPIER")
}

/// Keywords of the modal solver that code_aster 11 wrote at the top level
/// of `MODE_ITER_SIMULT` (or in `CALC_FREQ`) and code_aster 17 groups under
/// `SOLVEUR_MODAL`.
pub(crate) const SOLVEUR_MODAL_KEYS: &[&str] = &[
    "METHODE",
    "PREC_SOREN",
    "NMAX_ITER_SOREN",
    "PARA_ORTHO_SOREN",
    "PREC_LANCZOS",
    "NMAX_ITER_QR",
    "PREC_ORTHO",
    "NMAX_ITER_ORTHO",
    "MODE_RIGIDE",
    "PREC_BATHE",
    "NMAX_ITER_BATHE",
    "PREC_JACOBI",
    "NMAX_ITER_JACOBI",
    "TYPE_QZ",
    "DIM_SOUS_ESPACE",
    "COEF_DIM_ESPACE",
    "APPROCHE",
    "NMAX_ITER_SEPARE",
    "PREC_SEPARE",
    "NMAX_ITER_AJUSTE",
    "PREC_AJUSTE",
];

/// `MODE_ITER_INV/CALC_MODE` keywords and their `SOLVEUR_MODAL` names.
const CALC_MODE_KEYS: &[(&str, &str)] = &[
    ("OPTION", "OPTION_INV"),
    ("PREC", "PREC_INV"),
    ("NMAX_ITER", "NMAX_ITER_INV"),
];

fn new_dict() -> Rc<RefCell<Dict>> {
    Rc::new(RefCell::new(Dict::default()))
}

fn key(k: &str) -> Value {
    Value::str(k)
}

/// The first `_F(...)` of a factor keyword value.
fn first_occurrence(v: &Value) -> Option<Rc<RefCell<Dict>>> {
    match v {
        Value::Dict(d) => Some(d.clone()),
        other => match crate::validate::flatten(other).into_iter().next()? {
            Value::Dict(d) => Some(d),
            _ => None,
        },
    }
}

/// Rewrites the keywords of a call to `old` into those of its replacement
/// (see the module table), with one warning naming the new command.
/// Returns the new command's name.
pub(crate) fn translate(
    old: &str,
    span: Span,
    given: &mut Vec<Given>,
    diags: &mut Vec<Diagnostic>,
) -> Option<&'static str> {
    let new = replacement(old).or_else(|| replacement_by_keywords(old, given))?;
    let at = diags.len();
    diags.push(Diagnostic::warning(
        DiagKind::Legacy,
        span,
        match old {
            "CREA_MAILLAGE" => {
                format!("`{old}(COPIE=_F())` is code_aster 11 syntax: now {new}(CONCEPT=...)")
            }
            _ => format!("`{old}` is code_aster 11 syntax: now {new}"),
        },
    ));
    match old {
        "MODE_ITER_SIMULT" | "MODE_ITER_INV" => {
            let moved = modal(old, span, given, diags);
            if let (false, Some(d)) = (moved.is_empty(), diags.get_mut(at)) {
                d.notes.push(format!("note: {}", moved.join(", ")));
            }
        }
        "MACRO_MATR_ASSE" => {
            // The numbering of the unknowns is the solver's business.
            if let Some(i) = given.iter().position(|g| g.name == "SOLVEUR") {
                let g = given.remove(i);
                diags.push(Diagnostic::warning(
                    DiagKind::Legacy,
                    g.span,
                    format!("`{old}/SOLVEUR` no longer exists and is ignored: ASSEMBLAGE leaves the numbering to the solver"),
                ));
            }
        }
        "CREA_MAILLAGE" => {
            given.retain(|g| g.name != "COPIE");
            if let Some(g) = given.iter_mut().find(|g| g.name == "MAILLAGE") {
                g.name = "CONCEPT".into();
            }
        }
        _ => {}
    }
    Some(new)
}

/// code_aster 11 named the matrices A, B (C) whatever the problem;
/// CALC_MODES keeps those names only for the general problem: (old, new)
/// for the `TYPE_RESU` given.
pub(crate) fn modal_matrix_names(
    type_resu: Option<&str>,
) -> &'static [(&'static str, &'static str)] {
    match type_resu {
        Some("GENERAL") => &[],
        Some("MODE_FLAMB") => &[("MATR_A", "MATR_RIGI"), ("MATR_B", "MATR_RIGI_GEOM")],
        _ => &[
            ("MATR_A", "MATR_RIGI"),
            ("MATR_B", "MATR_MASS"),
            ("MATR_C", "MATR_AMOR"),
        ],
    }
}

/// `MODE_ITER_SIMULT` / `MODE_ITER_INV` → `CALC_MODES`.
/// Returns what moved (`METHODE → SOLVEUR_MODAL/METHODE`...), for the note.
fn modal(
    old: &str,
    span: Span,
    given: &mut Vec<Given>,
    diags: &mut Vec<Diagnostic>,
) -> Vec<String> {
    let mut moved = Vec::new();
    let type_resu = given
        .iter()
        .find(|g| g.name == "TYPE_RESU")
        .map(|g| g.value.to_string());
    let names = modal_matrix_names(type_resu.as_deref());
    for (from, to) in names {
        if let Some(g) = given.iter_mut().find(|g| g.name == *from) {
            g.name = to.to_string();
            moved.push(format!("{from} → {to}"));
        }
    }
    let solveur = new_dict();
    // The top-level OPTION of code_aster 11's MODE_ITER_SIMULT asked for the
    // rigid-body modes (TRI_DIAG): now SOLVEUR_MODAL/MODE_RIGIDE.
    if let Some(i) = given.iter().position(|g| g.name == "OPTION") {
        let g = given.remove(i);
        if g.value.to_string() == "MODE_RIGIDE" {
            moved.push("OPTION='MODE_RIGIDE' → SOLVEUR_MODAL/MODE_RIGIDE='OUI'".into());
            solveur
                .borrow_mut()
                .insert(key("MODE_RIGIDE"), Value::str("OUI"), g.span);
        }
    }
    // Whether an empty frequency band stops the computation is no longer
    // a choice.
    if let Some(i) = given.iter().position(|g| g.name == "STOP_FREQ_VIDE") {
        let g = given.remove(i);
        diags.push(Diagnostic::warning(
            DiagKind::Legacy,
            g.span,
            format!("`{old}/STOP_FREQ_VIDE` no longer exists and is ignored: CALC_MODES has no such choice"),
        ));
    }
    // Top-level method keywords → SOLVEUR_MODAL.
    given.retain(|g| {
        if SOLVEUR_MODAL_KEYS.contains(&g.name.as_str()) {
            moved.push(format!("{} → SOLVEUR_MODAL/{}", g.name, g.name));
            solveur
                .borrow_mut()
                .insert(key(&g.name), g.value.clone(), g.span);
            false
        } else {
            true
        }
    });
    // CALC_FREQ (or CALC_CHAR_CRIT for buckling): OPTION goes up, method
    // keywords go to SOLVEUR_MODAL, the rest stays.
    let mut option: Option<(Value, Span)> = None;
    for g in given.iter_mut() {
        if !matches!(g.name.as_str(), "CALC_FREQ" | "CALC_CHAR_CRIT") {
            continue;
        }
        let Some(d) = first_occurrence(&g.value) else {
            continue;
        };
        // A copy: the `_F(...)` may be a variable other calls use too.
        let kept = new_dict();
        for e in d.borrow().entries.iter() {
            let name = match &e.key {
                Value::Str(s) => s.to_string(),
                _ => String::new(),
            };
            if name == "OPTION" {
                moved.push(format!("{}/OPTION → OPTION", g.name));
                option = Some((e.value.clone(), e.span));
            } else if SOLVEUR_MODAL_KEYS.contains(&name.as_str()) {
                moved.push(format!("{}/{name} → SOLVEUR_MODAL/{name}", g.name));
                solveur
                    .borrow_mut()
                    .insert(e.key.clone(), e.value.clone(), e.span);
            } else {
                kept.borrow_mut()
                    .insert(e.key.clone(), e.value.clone(), e.span);
            }
        }
        g.value = Value::Dict(kept);
    }
    // MODE_ITER_INV/CALC_MODE → SOLVEUR_MODAL/OPTION_INV, PREC_INV, NMAX_ITER_INV.
    if let Some(i) = given.iter().position(|g| g.name == "CALC_MODE") {
        let g = given.remove(i);
        if let Some(d) = first_occurrence(&g.value) {
            for e in d.borrow().entries.iter() {
                let Value::Str(k) = &e.key else { continue };
                if let Some((_, to)) = CALC_MODE_KEYS.iter().find(|(f, _)| **f == **k) {
                    moved.push(format!("CALC_MODE/{k} → SOLVEUR_MODAL/{to}"));
                    solveur
                        .borrow_mut()
                        .insert(key(to), e.value.clone(), e.span);
                }
            }
        }
    }
    // code_aster 11's MODE_ITER_INV adjusted the given frequencies by
    // default; CALC_MODES' default is the lowest ones.
    if option.is_none() && old == "MODE_ITER_INV" {
        moved.push("OPTION='AJUSTE' (code_aster 11's default)".into());
        option = Some((Value::str("AJUSTE"), span));
    }
    if let Some((value, vspan)) = option {
        given.push(Given {
            name: "OPTION".into(),
            span: vspan,
            value,
        });
    }
    if !solveur.borrow().entries.is_empty() && !given.iter().any(|g| g.name == "SOLVEUR_MODAL") {
        given.push(Given {
            name: "SOLVEUR_MODAL".into(),
            span,
            value: Value::Dict(solveur),
        });
    }
    moved
}
