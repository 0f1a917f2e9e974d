//! Legacy syntax (code_aster 11–15) mapped to its code_aster 17 form, with a
//! warning that names the new spelling. The table is documented in
//! docs/legacy.md. A mapping applies only where the old keyword is unknown
//! to the v17 catalog at that place, so current files are never touched.

use crate::command::Scalar;
use crate::diag::{DiagKind, Diagnostic};
use crate::validate::Given;
use crate::value::Value;
use aster_catalog::{find_in, Entry, Lit};

/// Plain keyword renames: (command or `*`, old name, new name, note).
/// `*` applies at any level of any command.
pub const RENAMES: &[(&str, &str, &str, &str)] = &[
    ("*", "COMP_INCR", "COMPORTEMENT", ""),
    ("*", "COMP_ELAS", "COMPORTEMENT", ""),
    ("DEFI_CONTACT", "TOLE_APPA", "DIST_APPA", ""),
    (
        "*",
        "NOEUD",
        "GROUP_NO",
        "node names are no longer accepted; the name is looked up as a node group, then as a node",
    ),
    (
        "*",
        "MAILLE",
        "GROUP_MA",
        "cell names are no longer accepted; the name is looked up as a cell group, then as a cell",
    ),
    ("*", "NOEUD_ORIG", "GROUP_NO_ORIG", ""),
    ("*", "RESI_INTE_MAXI", "RESI_INTE", ""),
    ("*", "RESI_INTE_RELA", "RESI_INTE", ""),
    ("THER_NON_LINE", "STATIONNAIRE", "STAT", ""),
    ("*", "NOEUD_EXTR", "GROUP_NO_EXTR", ""),
];

/// Renames applied only in code_aster 11 files (see
/// `aster_syntax::dialect::generation`): (command or `*`, old, new).
pub const LEGACY_RENAMES: &[(&str, &str, &str)] = &[
    ("AFFE_MATERIAU", "CHAMP_GD", "CHAM_GD"),
    ("THER_LINEAIRE", "STATIONNAIRE", "STAT"),
    ("DEFI_CONTACT", "MAILLE_MAIT", "GROUP_MA_MAIT"),
    ("DEFI_CONTACT", "MAILLE_ESCL", "GROUP_MA_ESCL"),
    ("DEFI_CONTACT", "NOEUD_ESCL", "GROUP_NO_ESCL"),
    ("THER_NON_LINE", "COMP_THER_NL", "COMPORTEMENT"),
    ("SECH_NON_LINE", "COMP_THER_NL", "COMPORTEMENT"),
    ("DEFI_CABLE_BP", "NOEUD_ANCRAGE", "GROUP_NO_ANCRAGE"),
];

/// Keywords dropped only in code_aster 11 files, with why: (command or `*`,
/// factor keyword or `*`, name, why).
pub const LEGACY_DROPPED: &[(&str, &str, &str, &str)] = &[
    (
        "AFFE_CARA_ELEM",
        "POUTRE",
        "PREC_AIRE",
        "the check of a multifibre section's area against the beam's is gone",
    ),
    (
        "AFFE_CARA_ELEM",
        "POUTRE",
        "PREC_INERTIE",
        "the check of a multifibre section's inertia against the beam's is gone",
    ),
    (
        "CREA_MAILLAGE",
        "*",
        "PREF_NOEUD",
        "the new nodes are named by code_aster",
    ),
];

/// Keywords that no longer exist and had no effect on the result: dropped
/// with a warning. (command or `*`, factor keyword or `*`, name, why)
pub const DROPPED: &[(&str, &str, &str, &str)] = &[
    ("*", "SOLVEUR", "SYME", "the solver detects symmetry itself"),
    ("DEBUT", "CODE", "NOM", "the test name is no longer given"),
    (
        "DEBUT",
        "CODE",
        "NIV_PUB_WEB",
        "publication level no longer exists",
    ),
    ("DEBUT", "*", "PAR_LOT", "commands always run one by one"),
    (
        "POURSUITE",
        "*",
        "PAR_LOT",
        "commands always run one by one",
    ),
    ("*", "*", "TITRE", "titles are no longer stored"),
    (
        "*",
        "COMPORTEMENT",
        "ITER_INTE_PAS",
        "not used by code_aster 17",
    ),
    ("DEBUT", "DEBUG", "HIST_ETAPE", "no longer exists"),
    (
        "DETRUIRE",
        "*",
        "OBJET",
        "only whole concepts are destroyed: DETRUIRE(NOM=...)",
    ),
    (
        "FIN",
        "*",
        "FORMAT_HDF",
        "the database is always saved in the same format",
    ),
    ("FIN", "*", "PROC0", "no longer exists"),
    ("AFFE_MODELE", "*", "VERIF", "the model is always verified"),
    (
        "NUME_DDL",
        "*",
        "METHODE",
        "the numbering method is chosen by the solver",
    ),
    (
        "NUME_DDL",
        "*",
        "RENUM",
        "the renumbering is chosen by the solver",
    ),
];

/// Renamed values: (keyword, old value, new value).
pub const VALUES: &[(&str, &str, &str)] = &[
    ("NOM_CHAM", "VALE_CONT", "CONT_NOEU"),
    ("NOM_CHAM", "SIEF_ELNO_ELGA", "SIEF_ELNO"),
    ("NOM_CHAM", "SIGM_ELNO_DEPL", "SIGM_ELNO"),
    ("NOM_CHAM", "EPSI_ELNO_DEPL", "EPSI_ELNO"),
    ("NOM_CHAM", "EQUI_ELNO_SIGM", "SIEQ_ELNO"),
    ("OPTION", "SIEF_ELNO_ELGA", "SIEF_ELNO"),
    ("OPTION", "SIGM_ELNO_DEPL", "SIGM_ELNO"),
    ("OPTION", "EPSI_ELNO_DEPL", "EPSI_ELNO"),
    ("OPTION", "EQUI_ELNO_SIGM", "SIEQ_ELNO"),
];

/// Commands removed since code_aster 11, with what replaced them.
pub fn removed_command(name: &str) -> Option<String> {
    let new = match name {
        "CALC_ELEM" | "CALC_NO" => "CALC_CHAMP",
        "DEFI_SQUELETTE" => "CREA_MAILLAGE",
        "IMPR_OAR" => "no replacement",
        "CALC_G_THETA_T" | "CALC_THETA" => "CALC_G",
        "POST_K1_K2_K3" => "POST_K1_K2_K3 (still exists) or CALC_G",
        "DETRUIRE_CONCEPT" => "DETRUIRE",
        _ => return None,
    };
    Some(format!("note: {name} was replaced by {new}"))
}

fn last_segment(path: &str) -> &str {
    let seg = path.rsplit('/').next().unwrap_or(path);
    seg.split('[').next().unwrap_or(seg)
}

fn applies(rule_cmd: &str, cmd: &str) -> bool {
    rule_cmd == "*" || rule_cmd == cmd
}

fn warn(diags: &mut Vec<Diagnostic>, g: &Given, msg: String) {
    diags.push(Diagnostic::warning(DiagKind::Legacy, g.span, msg));
}

/// Rewrites the keywords given at one level (`path` is `CMD` or
/// `CMD/FACTOR[i]`) into their current form.
pub(crate) fn transform_level(
    cmd: &str,
    path: &str,
    entries: &[Entry],
    given: &mut Vec<Given>,
    diags: &mut Vec<Diagnostic>,
    legacy: bool,
) {
    let factor = if path.contains('/') {
        last_segment(path)
    } else {
        ""
    };
    let known = |n: &str| find_in(entries, n).is_some();
    // Almost every level of a current file writes only known keywords: the
    // rewrites keyed on an unknown one are then skipped at once.
    let all_known = given.iter().all(|g| known(&g.name));

    if legacy && !all_known {
        merge_comp_elas(path, given, diags);
    }
    if legacy && cmd == "CREA_RESU" && factor.is_empty() {
        crea_resu_nom_cham(path, given, diags);
    }
    if legacy && cmd == "CREA_CHAMP" && factor.is_empty() {
        crea_champ_prol_zero(path, given, diags);
    }
    if legacy {
        legacy_levels(cmd, path, factor, given, diags);
    }
    if legacy && cmd == "DEFI_LIST_INST" && factor.is_empty() {
        defi_list_methode(path, given, diags);
    }
    // Structural rewrites first.
    let names: Vec<String> = if all_known {
        Vec::new()
    } else {
        given.iter().map(|g| g.name.clone()).collect()
    };
    for name in names {
        if known(&name) {
            continue;
        }
        let Some(i) = given.iter().position(|g| g.name == name) else {
            continue;
        };
        match (cmd, factor, name.as_str()) {
            // DETRUIRE(CONCEPT=_F(NOM=X)) → DETRUIRE(NOM=X)
            ("DETRUIRE", "", "CONCEPT") => {
                let g = &mut given[i];
                warn(
                    diags,
                    g,
                    format!("`{path}/CONCEPT=_F(NOM=...)` is code_aster 11 syntax: now NOM=..."),
                );
                let mut names = Vec::new();
                for occ in crate::validate::flatten(&g.value) {
                    if let Value::Dict(d) = occ {
                        if let Some(v) = d.borrow().get(&Value::str("NOM")) {
                            names.extend(crate::validate::flatten(v));
                        }
                    }
                }
                g.name = "NOM".into();
                g.value = Value::tuple(names);
            }
            ("MODI_MAILLAGE", "", "ORIE_PEAU_2D" | "ORIE_PEAU_3D") => {
                let g = &mut given[i];
                warn(diags, g, format!("`{path}/{name}` is code_aster 11 syntax: now ORIE_PEAU=_F(GROUP_MA_PEAU=...)"));
                g.name = "ORIE_PEAU".into();
                rename_inside(&g.value, "GROUP_MA", "GROUP_MA_PEAU");
            }
            _ => {}
        }
    }
    // DEBUT/POURSUITE CODE=_F(...) → CODE='OUI'
    if matches!(cmd, "DEBUT" | "POURSUITE") && factor.is_empty() {
        if let Some(g) = given.iter_mut().find(|g| {
            g.name == "CODE" && matches!(g.value, Value::Dict(_) | Value::Tuple(_) | Value::List(_))
        }) {
            warn(
                diags,
                g,
                format!("`{path}/CODE=_F(NOM=...)` is code_aster 11 syntax: now CODE='OUI'"),
            );
            g.value = Value::str("OUI");
        }
    }
    // Thermal commands (code_aster's own compatibility rules):
    // PARM_THETA=x → SCHEMA_TEMPS=_F(SCHEMA='THETA', THETA=x); a linear
    // computation without initial state is stationary.
    if matches!(cmd, "THER_LINEAIRE" | "THER_NON_LINE") && factor.is_empty() {
        if let Some(g) = given.iter_mut().find(|g| g.name == "PARM_THETA") {
            warn(diags, g, format!("`{path}/PARM_THETA` is legacy syntax: now SCHEMA_TEMPS=_F(SCHEMA='THETA', THETA=...)"));
            let mut d = crate::value::Dict::default();
            d.insert(Value::str("SCHEMA"), Value::str("THETA"), g.span);
            d.insert(Value::str("THETA"), g.value.clone(), g.span);
            g.name = "SCHEMA_TEMPS".into();
            g.value = Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(d)));
        }
        // NEWTON=_F(ITER_LINE_MAXI, RESI_LINE_RELA) → RECH_LINEAIRE=_F(…)
        // (THER_NON_LINE's compat_syntax: the line search keeps working).
        if cmd == "THER_NON_LINE" && !given.iter().any(|g| g.name == "RECH_LINEAIRE") {
            let mut moved = crate::value::Dict::default();
            let mut span = None;
            if let Some(g) = given.iter().find(|g| g.name == "NEWTON") {
                if let Value::Dict(d) = &g.value {
                    let mut d = d.borrow_mut();
                    for key in ["ITER_LINE_MAXI", "RESI_LINE_RELA"] {
                        if let Some(v) = d.remove(&Value::str(key)) {
                            moved.insert(Value::str(key), v, g.span);
                            span = Some(g.span);
                        }
                    }
                }
            }
            if let Some(span) = span {
                if let Some(g) = given.iter().find(|g| g.name == "NEWTON") {
                    warn(diags, g, format!("`{path}/NEWTON/ITER_LINE_MAXI` is legacy syntax: now RECH_LINEAIRE=_F(ITER_LINE_MAXI=...)"));
                }
                given.push(Given {
                    name: "RECH_LINEAIRE".into(),
                    span,
                    value: Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(moved))),
                });
            }
        }
        let stat = given
            .iter()
            .any(|g| g.name == "TYPE_CALCUL" && g.value.to_string() == "STAT");
        if cmd == "THER_LINEAIRE" && !stat && !given.iter().any(|g| g.name == "ETAT_INIT") {
            // No initial state: the transient starts from the stationary
            // solution (code_aster's compatibility rule).
            let span = given.first().map(|g| g.span).unwrap_or_default();
            let mut d = crate::value::Dict::default();
            d.insert(Value::str("STAT"), Value::str("OUI"), span);
            given.push(Given {
                name: "ETAT_INIT".into(),
                span,
                value: Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(d))),
            });
        }
    }
    if cmd == "SECH_NON_LINE" && factor.is_empty() {
        sech_non_line(path, given, diags);
    }
    if cmd == "PROJ_CHAMP" && factor.is_empty() {
        proj_champ_prol_zero(path, given, diags);
    }
    if cmd == "LIRE_FONCTION" && factor.is_empty() && !known("SEPAR") {
        lire_fonction_separ(path, given, diags);
    }
    if all_known {
        return;
    }
    // DDL_IMPO/LIAISON='ENCASTRE' → BLOCAGE=('DEPLACEMENT', 'ROTATION')
    if !known("LIAISON") && known("BLOCAGE") {
        if let Some(g) = given.iter_mut().find(|g| g.name == "LIAISON") {
            if g.value.to_string() == "ENCASTRE" {
                warn(diags, g, format!("`{path}/LIAISON='ENCASTRE'` is legacy syntax: now BLOCAGE=('DEPLACEMENT', 'ROTATION')"));
                g.name = "BLOCAGE".into();
                g.value = Value::tuple(vec![Value::str("DEPLACEMENT"), Value::str("ROTATION")]);
            }
        }
    }
    // TEST_RESU-like occurrences: VALE= → VALE_CALC / VALE_REFE.
    if !known("VALE") && known("VALE_CALC") {
        test_resu_vale(path, given, diags);
    }

    let mut i = 0;
    while i < given.len() {
        let name = given[i].name.clone();
        if known(&name) {
            i += 1;
            continue;
        }
        let legacy_rename = LEGACY_RENAMES
            .iter()
            .filter(|_| legacy)
            .find(|(c, old, _)| applies(c, cmd) && *old == name)
            .map(|(c, o, n)| (*c, *o, *n, ""));
        if let Some((_, _, new, note)) = RENAMES
            .iter()
            .copied()
            .chain(legacy_rename)
            .find(|(c, old, _, _)| applies(c, cmd) && *old == name)
        {
            if known(new) && !given.iter().any(|g| g.name == *new) {
                warn(
                    diags,
                    &given[i],
                    format!("`{path}/{name}` is legacy syntax: now {new}"),
                );
                if !note.is_empty() {
                    if let Some(d) = diags.last_mut() {
                        d.notes.push(format!("note: {note}"));
                    }
                }
                given[i].name = new.to_string();
                i += 1;
                continue;
            }
        }
        let legacy_dropped = LEGACY_DROPPED.iter().filter(|_| legacy);
        if let Some((_, _, _, why)) = DROPPED
            .iter()
            .chain(legacy_dropped)
            .find(|(c, f, n, _)| applies(c, cmd) && (*f == "*" || *f == factor) && *n == name)
        {
            warn(
                diags,
                &given[i],
                format!("`{path}/{name}` no longer exists and is ignored: {why}"),
            );
            given.remove(i);
            continue;
        }
        i += 1;
    }
}

/// The entry `key` of a `_F(...)` value (the first occurrence of a list).
fn factor_entry(v: &Value, key: &str) -> Option<Value> {
    let occ = match v {
        Value::Dict(_) => v.clone(),
        other => crate::validate::flatten(other).into_iter().next()?,
    };
    let Value::Dict(d) = occ else {
        return None;
    };
    let found = d.borrow().get(&Value::str(key)).cloned();
    found
}

/// code_aster 17's own compatibility rules of SECH_NON_LINE (its
/// `compat_syntax`): a transient computation takes its theta from
/// `SCHEMA_TEMPS=_F(THETA=x)` as `PARM_THETA=x`, and `ETAT_INIT` says
/// `STAT='OUI'` where it said `STATIONNAIRE='OUI'`.
fn sech_non_line(path: &str, given: &mut [Given], diags: &mut Vec<Diagnostic>) {
    let transient = given
        .iter()
        .find(|g| g.name == "TYPE_CALCUL")
        .is_none_or(|g| g.value.to_string() == "TRAN");
    if transient && !given.iter().any(|g| g.name == "PARM_THETA") {
        if let Some(i) = given.iter().position(|g| g.name == "SCHEMA_TEMPS") {
            if let Some(theta) = factor_entry(&given[i].value, "THETA") {
                let g = &mut given[i];
                warn(
                    diags,
                    g,
                    format!("`{path}/SCHEMA_TEMPS=_F(THETA=...)` is compatibility syntax: now PARM_THETA=..."),
                );
                g.name = "PARM_THETA".into();
                g.value = theta;
            }
        }
    }
    if let Some(g) = given.iter().find(|g| g.name == "ETAT_INIT") {
        if factor_entry(&g.value, "STATIONNAIRE").is_some() {
            warn(
                diags,
                g,
                format!("`{path}/ETAT_INIT/STATIONNAIRE` is legacy syntax: now STAT='OUI'"),
            );
            rename_inside(&g.value, "STATIONNAIRE", "STAT");
        }
    }
}

/// `PROJ_CHAMP(PROL_ZERO=...)`, translated by code_aster 17's
/// `compat_syntax`: 'OUI' becomes `PROL_VALE=0.0` (every node of the target
/// mesh without a projected value gets 0), 'NON' (the default) is dropped.
fn proj_champ_prol_zero(path: &str, given: &mut Vec<Given>, diags: &mut Vec<Diagnostic>) {
    let Some(i) = given.iter().position(|g| g.name == "PROL_ZERO") else {
        return;
    };
    let g = given.remove(i);
    if g.value.to_string() == "OUI" && !given.iter().any(|g| g.name == "PROL_VALE") {
        warn(
            diags,
            &g,
            format!("`{path}/PROL_ZERO='OUI'` is compatibility syntax: now PROL_VALE=0.0"),
        );
        given.push(Given {
            name: "PROL_VALE".into(),
            span: g.span,
            value: Value::Float(0.0),
        });
    } else {
        warn(
            diags,
            &g,
            format!("`{path}/PROL_ZERO` is compatibility syntax: 'NON' is the default"),
        );
    }
}

/// `LIRE_FONCTION(SEPAR=...)`, still translated by code_aster 17 into
/// `SEPARATEUR` for the four separators it knew; anything else, or both
/// keywords at once, is an error there too.
fn lire_fonction_separ(path: &str, given: &mut Vec<Given>, diags: &mut Vec<Diagnostic>) {
    const ACCEPTED: [&str; 4] = ["None", ",", ";", "/"];
    let Some(i) = given.iter().position(|g| g.name == "SEPAR") else {
        return;
    };
    let g = &given[i];
    if given.iter().any(|o| o.name == "SEPARATEUR") {
        diags.push(Diagnostic::error(
            DiagKind::Rule,
            g.span,
            format!("`{path}`: SEPAR is the old spelling of SEPARATEUR: give only SEPARATEUR"),
        ));
        given.remove(i);
        return;
    }
    let sep = match &g.value {
        Value::Str(s) => Some(s.to_string()),
        _ => None,
    };
    match sep {
        Some(s) if ACCEPTED.contains(&s.as_str()) => {
            warn(
                diags,
                g,
                format!("`{path}/SEPAR` is legacy syntax: now SEPARATEUR"),
            );
            given[i].name = "SEPARATEUR".into();
        }
        _ => {
            diags.push(
                Diagnostic::error(
                    DiagKind::NotInto,
                    g.span,
                    format!(
                        "`{path}/SEPAR` (legacy spelling of SEPARATEUR): value {} is not allowed",
                        g.value.repr()
                    ),
                )
                .note("note: allowed values: 'None', ',', ';', '/'".to_string()),
            );
            given.remove(i);
        }
    }
}

/// code_aster 11 wrote `COMP_INCR` and `COMP_ELAS` side by side (parts of
/// the model in each): both become one `COMPORTEMENT` with the occurrences
/// of both (then renamed with the other legacy keywords).
fn merge_comp_elas(path: &str, given: &mut Vec<Given>, diags: &mut Vec<Diagnostic>) {
    let (Some(_), Some(e)) = (
        given.iter().position(|g| g.name == "COMP_INCR"),
        given.iter().position(|g| g.name == "COMP_ELAS"),
    ) else {
        return;
    };
    let elas = given.remove(e);
    warn(
        diags,
        &elas,
        format!("`{path}/COMP_ELAS` is legacy syntax: now COMPORTEMENT, together with the occurrences of COMP_INCR"),
    );
    if let Some(incr) = given.iter_mut().find(|g| g.name == "COMP_INCR") {
        let mut occ = crate::validate::flatten(&incr.value);
        occ.extend(crate::validate::flatten(&elas.value));
        incr.value = Value::tuple(occ);
    }
}

/// code_aster 11: `CREA_RESU(OPERATION='AFFE', NOM_CHAM='TEMP', AFFE=_F(...))`
/// named the field once for every occurrence; code_aster 17 names it in
/// each `AFFE` occurrence.
fn crea_resu_nom_cham(path: &str, given: &mut Vec<Given>, diags: &mut Vec<Diagnostic>) {
    let affe_op = given
        .iter()
        .any(|g| g.name == "OPERATION" && g.value.to_string() == "AFFE");
    let (Some(n), Some(a)) = (
        given.iter().position(|g| g.name == "NOM_CHAM"),
        given.iter().position(|g| g.name == "AFFE"),
    ) else {
        return;
    };
    if !affe_op {
        return;
    }
    let nom = given[n].clone();
    warn(
        diags,
        &nom,
        format!("`{path}/NOM_CHAM` is code_aster 11 syntax: now AFFE=_F(NOM_CHAM=...) in each occurrence"),
    );
    given[a].value = with_entry_in_each(&given[a].value, "NOM_CHAM", &nom.value, nom.span);
    given.remove(n);
}

/// A code_aster 11 construct refused with one message, the keywords that
/// belong to it removed (they would only repeat it).
struct Refused {
    command: &'static str,
    factor: &'static str,
    /// The keyword and value that mark the construct.
    keyword: &'static str,
    value: &'static str,
    companions: &'static [&'static str],
    why: &'static str,
}

const REFUSED: &[Refused] = &[
    Refused {
        command: "DYNA_NON_LINE",
        factor: "SCHEMA_TEMPS",
        keyword: "SCHEMA",
        value: "THETA_METHODE",
        companions: &["THETA"],
        why: "the theta-method time scheme of DYNA_NON_LINE was removed",
    },
    Refused {
        command: "DEFI_LIST_INST",
        factor: "ECHEC",
        keyword: "EVENEMENT",
        value: "COLLISION",
        companions: &["SUBD_INST", "SUBD_DUREE"],
        why: "the collision event and its subdivision of the time step were removed",
    },
];

/// Smaller code_aster 11 rewrites, one level at a time.
fn legacy_levels(
    cmd: &str,
    path: &str,
    factor: &str,
    given: &mut Vec<Given>,
    diags: &mut Vec<Diagnostic>,
) {
    let has = |given: &[Given], n: &str| given.iter().any(|g| g.name == n);
    // AFFE_MODELE/MODI_MODELE(PARTITION=_F(PARALLELISME=...)) →
    // DISTRIBUTION=_F(METHODE=...): how elements are spread over processes.
    if matches!(cmd, "AFFE_MODELE" | "MODI_MODELE")
        && factor.is_empty()
        && !has(given, "DISTRIBUTION")
    {
        if let Some(g) = given.iter_mut().find(|g| g.name == "PARTITION") {
            warn(
                diags,
                g,
                format!("`{path}/PARTITION=_F(PARALLELISME=...)` is code_aster 11 syntax: now DISTRIBUTION=_F(METHODE=...)"),
            );
            g.name = "DISTRIBUTION".into();
            if let Some(Value::Dict(d)) = crate::validate::flatten(&g.value).into_iter().next() {
                let mut d = d.borrow().clone();
                // The FETI sub-domains (DEFI_PART_FETI) are gone with FETI.
                d.remove(&Value::str("PARTITION"));
                for e in d.entries.iter_mut() {
                    if matches!(&e.key, Value::Str(k) if &**k == "PARALLELISME") {
                        e.key = Value::str("METHODE");
                    }
                }
                g.value = Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(d)));
            }
        }
    }
    // AFFE_MODELE/AFFE/MODELISATION=('D_PLAN', 'D_PLAN_SI'): code_aster 11
    // applied each modelisation in turn, a later one taking the cells it
    // has elements for. code_aster 17 takes one per occurrence: one
    // occurrence per modelisation, in the same order, does the same.
    if cmd == "AFFE_MODELE" && factor.is_empty() {
        if let Some(g) = given.iter_mut().find(|g| g.name == "AFFE") {
            split_modelisations(path, g, diags);
        }
    }
    if cmd == "DEFI_CONTACT" && factor == "ZONE" {
        contact_zone(path, given, diags);
    }
    // Titles given as several strings (code_aster 11 printed one per
    // line): one text now.
    for g in given.iter_mut() {
        if !matches!(g.name.as_str(), "TITRE" | "SOUS_TITRE") {
            continue;
        }
        let parts = crate::validate::flatten(&g.value);
        if parts.len() > 1 && parts.iter().all(|p| matches!(p, Value::Str(_))) {
            let joined: Vec<String> = parts.iter().map(|p| p.to_string()).collect();
            warn(
                diags,
                g,
                format!("`{path}/{}` with several strings is code_aster 11 syntax: now one text (joined by spaces)", g.name),
            );
            g.value = Value::str(&joined.join(" "));
        }
    }
    for r in REFUSED {
        if r.command != cmd || r.factor != factor {
            continue;
        }
        let Some(i) = given
            .iter()
            .position(|g| g.name == r.keyword && g.value.to_string() == r.value)
        else {
            continue;
        };
        let g = given.remove(i);
        given.retain(|o| !r.companions.contains(&o.name.as_str()));
        diags.push(Diagnostic::error(
            DiagKind::NotSupported,
            g.span,
            format!(
                "not supported: `{path}/{}='{}'` (code_aster 11): {}",
                r.keyword, r.value, r.why
            ),
        ));
    }
    // Drying computed by THER_NON_LINE (code_aster 11): now SECH_NON_LINE,
    // on a model of its own — not a rename of the command.
    if cmd == "THER_NON_LINE" && factor.is_empty() {
        let drying_law = given
            .iter()
            .filter(|g| matches!(g.name.as_str(), "COMP_THER_NL" | "COMPORTEMENT"))
            .filter_map(|g| factor_entry(&g.value, "RELATION"))
            .any(|r| r.to_string().starts_with("SECH_"));
        if drying_law || has(given, "EVOL_THER_SECH") {
            let at = given
                .iter()
                .find(|g| matches!(g.name.as_str(), "COMP_THER_NL" | "EVOL_THER_SECH"))
                .map(|g| g.span)
                .unwrap_or_default();
            given.retain(|g| !matches!(g.name.as_str(), "COMP_THER_NL" | "EVOL_THER_SECH"));
            diags.push(Diagnostic::error(
                DiagKind::NotSupported,
                at,
                format!("not supported: drying computed by `{path}` (code_aster 11, COMP_THER_NL=_F(RELATION='SECH_...'), EVOL_THER_SECH): now SECH_NON_LINE on a drying model"),
            ));
        }
    }
    // DEFI_MATERIAU(ELAS_FO=_F(..., FONC_DESORP=F)) (code_aster 11): the
    // desorption function has its own factor keyword now,
    // BETON_DESORP=_F(FONC_DESORP=F).
    if cmd == "DEFI_MATERIAU" && factor.is_empty() && !has(given, "BETON_DESORP") {
        if let Some(i) = given.iter().position(|g| g.name == "ELAS_FO") {
            if let Some(f) = factor_entry(&given[i].value, "FONC_DESORP") {
                if let Some(Value::Dict(d)) =
                    crate::validate::flatten(&given[i].value).into_iter().next()
                {
                    let mut elas = d.borrow().clone();
                    elas.remove(&Value::str("FONC_DESORP"));
                    let span = given[i].span;
                    given[i].value = Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(elas)));
                    let mut desorp = crate::value::Dict::default();
                    desorp.insert(Value::str("FONC_DESORP"), f, span);
                    let g = Given {
                        name: "BETON_DESORP".into(),
                        span,
                        value: Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(desorp))),
                    };
                    warn(
                        diags,
                        &g,
                        format!("`{path}/ELAS_FO/FONC_DESORP` is code_aster 11 syntax: now BETON_DESORP=_F(FONC_DESORP=...)"),
                    );
                    given.push(g);
                }
            }
        }
    }
    // The kind of vector projected on a modal basis: code_aster 11's
    // default was a force, code_aster 17 wants it said.
    let projects_vector = (cmd == "PROJ_VECT_BASE" && factor.is_empty())
        || (cmd == "PROJ_BASE" && factor == "VECT_ASSE_GENE");
    if projects_vector && !has(given, "TYPE_VECT") {
        let span = given.first().map(|g| g.span).unwrap_or_default();
        let g = Given {
            name: "TYPE_VECT".into(),
            span,
            value: Value::str("FORC"),
        };
        warn(
            diags,
            &g,
            format!("`{path}` without TYPE_VECT: code_aster 11's default TYPE_VECT='FORC' is now written"),
        );
        given.push(g);
    }
    if cmd == "MODI_MAILLAGE" && factor.is_empty() {
        if let Some(i) = given.iter().position(|g| g.name == "ORIE_SHB") {
            let g = given.remove(i);
            diags.push(Diagnostic::error(
                DiagKind::NotSupported,
                g.span,
                format!("not supported: `{path}/ORIE_SHB` (code_aster 11): the solid-shell elements are now MODELISATION='COQUE_SOLIDE', on a mesh prepared by CREA_MAILLAGE(COQUE_SOLIDE=...)"),
            ));
        }
    }
    // Elements on nodes: code_aster 11 let AFFE_MODELE and the discrete
    // characteristics name nodes; code_aster 17 puts discrete elements on
    // POI1 cells, which the mesh must have (CREA_MAILLAGE(CREA_POI1=...)).
    let on_nodes = matches!(
        (cmd, factor),
        ("AFFE_MODELE", "AFFE") | ("AFFE_CARA_ELEM", "DISCRET" | "DISCRET_2D")
    );
    if on_nodes {
        if let Some(i) = given
            .iter()
            .position(|g| matches!(g.name.as_str(), "GROUP_NO" | "NOEUD"))
        {
            let g = given.remove(i);
            given.retain(|o| !matches!(o.name.as_str(), "GROUP_NO" | "NOEUD"));
            diags.push(Diagnostic::error(
                DiagKind::NotSupported,
                g.span,
                format!("not supported: `{path}/{}` (code_aster 11): elements on nodes; code_aster 17 puts them on POI1 cells (make them with CREA_MAILLAGE(CREA_POI1=...), then name their GROUP_MA)", g.name),
            ));
        }
    }
    // IMPR_RESU printed in its own text format by default in code_aster 11
    // (MED in code_aster 17). The format is written only where the call
    // asks for the text format (a keyword MED refuses): elsewhere both
    // formats print the same results, and MED is what the runner writes.
    if cmd == "IMPR_RESU" && factor.is_empty() && !has(given, "FORMAT") {
        const TEXT_ONLY: [&str; 8] = [
            "BORNE_INF",
            "BORNE_SUP",
            "FORMAT_R",
            "FORM_TABL",
            "IMPR_COOR",
            "TOUT_PARA",
            "VALE_MAX",
            "VALE_MIN",
        ];
        let text_resu = given.iter().filter(|g| g.name == "RESU").any(|g| {
            TEXT_ONLY
                .iter()
                .any(|k| factor_entry(&g.value, k).is_some())
        });
        let asks_text = given.iter().find(|g| g.name == "MODELE").or(if text_resu {
            given.iter().find(|g| g.name == "RESU")
        } else {
            None
        });
        if let Some(m) = asks_text {
            let g = Given {
                name: "FORMAT".into(),
                span: m.span,
                value: Value::str("RESULTAT"),
            };
            warn(
                diags,
                &g,
                format!("`{path}` without FORMAT printed text in code_aster 11 (MED in code_aster 17): FORMAT='RESULTAT' written, as {} asks for it", m.name),
            );
            given.push(g);
        }
    }
    // INCREMENT/PRECISION served to find INST_INIT/INST_FIN in the list;
    // without them code_aster 17 has no place for it, nor any use.
    if factor == "INCREMENT"
        && !has(given, "INST_INIT")
        && !has(given, "INST_FIN")
        && !has(given, "CRITERE")
    {
        if let Some(i) = given.iter().position(|g| g.name == "PRECISION") {
            let g = given.remove(i);
            warn(
                diags,
                &g,
                format!("`{path}/PRECISION` without INST_INIT or INST_FIN has no use: ignored (code_aster 11 accepted it)"),
            );
        }
    }
}

/// code_aster 11's `DEFI_CONTACT/ZONE`: the pairing direction
/// `TYPE_APPA='PROCHE'|'FIXE'` (with `DIRE_APPA`) is now
/// `TYPE_PROJECTION='ORTHOGONALE'|'FIXE'` (`TYPE_APPA` now names LAC's
/// pairing algorithm); `EXCLUSION_PIV_NUL` (drop slave nodes with a zero
/// pivot) is gone: `'NON'` is what code_aster 17 does, `'OUI'` is refused.
fn contact_zone(path: &str, given: &mut Vec<Given>, diags: &mut Vec<Diagnostic>) {
    if !given.iter().any(|g| g.name == "TYPE_PROJECTION") {
        if let Some(g) = given.iter_mut().find(|g| g.name == "TYPE_APPA") {
            let new = match g.value.to_string().as_str() {
                "FIXE" => Some("FIXE"),
                "PROCHE" => Some("ORTHOGONALE"),
                _ => None,
            };
            if let Some(new) = new {
                warn(
                    diags,
                    g,
                    format!("`{path}/TYPE_APPA={}` is code_aster 11 syntax: now TYPE_PROJECTION='{new}'", g.value.repr()),
                );
                g.name = "TYPE_PROJECTION".into();
                g.value = Value::str(new);
            }
        }
    }
    if let Some(i) = given.iter().position(|g| g.name == "USURE") {
        let g = given.remove(i);
        given.retain(|o| !matches!(o.name.as_str(), "K" | "H"));
        diags.push(Diagnostic::error(
            DiagKind::NotSupported,
            g.span,
            format!("not supported: `{path}/USURE` (code_aster 11): the wear computation of the contact (with K, H) was removed"),
        ));
    }
    if let Some(i) = given.iter().position(|g| g.name == "EXCLUSION_PIV_NUL") {
        let g = given.remove(i);
        if g.value.to_string() == "OUI" {
            diags.push(Diagnostic::error(
                DiagKind::NotSupported,
                g.span,
                format!("not supported: `{path}/EXCLUSION_PIV_NUL='OUI'` (code_aster 11): excluding the slave nodes with a zero pivot has no code_aster 17 form"),
            ));
        } else {
            warn(
                diags,
                &g,
                format!("`{path}/EXCLUSION_PIV_NUL` no longer exists and is ignored: 'NON' is what code_aster 17 does"),
            );
        }
    }
}

/// See `legacy_levels`: `AFFE=_F(MODELISATION=(a, b))` → `AFFE=(_F(MODELISATION=a),
/// _F(MODELISATION=b))`, the other keywords copied.
fn split_modelisations(path: &str, g: &mut Given, diags: &mut Vec<Diagnostic>) {
    let occs = crate::validate::flatten(&g.value);
    let several = |o: &Value| match o {
        Value::Dict(d) => d
            .borrow()
            .get(&Value::str("MODELISATION"))
            .map(|m| crate::validate::flatten(m).len() > 1)
            .unwrap_or(false),
        _ => false,
    };
    if !occs.iter().any(several) {
        return;
    }
    warn(
        diags,
        g,
        format!("`{path}/AFFE/MODELISATION` with several values is code_aster 11 syntax: now one AFFE occurrence per modelisation, in the same order (a later one takes the cells it has elements for)"),
    );
    let mut out = Vec::new();
    for o in occs {
        let Value::Dict(d) = &o else {
            out.push(o);
            continue;
        };
        let d = d.borrow();
        let models = d
            .get(&Value::str("MODELISATION"))
            .map(crate::validate::flatten)
            .unwrap_or_default();
        if models.len() <= 1 {
            out.push(o.clone());
            continue;
        }
        for m in models {
            let mut copy = d.clone();
            copy.insert(Value::str("MODELISATION"), m, g.span);
            out.push(Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(copy))));
        }
    }
    g.value = Value::tuple(out);
}

/// code_aster 11 accepted `CREA_CHAMP(PROL_ZERO='OUI')` for any field;
/// code_aster 17 only where a numbering or a model field is given (nodal
/// fields from `NUME_DDL`/`CHAM_NO`, element fields); elsewhere it has no
/// such choice, so the keyword is dropped with a warning.
fn crea_champ_prol_zero(path: &str, given: &mut Vec<Given>, diags: &mut Vec<Diagnostic>) {
    let applies = given.iter().any(|g| {
        matches!(g.name.as_str(), "NUME_DDL" | "CHAM_NO")
            || (g.name == "TYPE_CHAM" && g.value.to_string().starts_with("EL"))
    });
    if applies {
        return;
    }
    if let Some(i) = given.iter().position(|g| g.name == "PROL_ZERO") {
        let g = given.remove(i);
        warn(
            diags,
            &g,
            format!("`{path}/PROL_ZERO` applies only to fields with a numbering (NUME_DDL, CHAM_NO) or element fields in code_aster 17: ignored (code_aster 17 offers no such choice for this field)"),
        );
    }
}

/// code_aster 11: `DEFI_LIST_INST(DEFI_LIST=_F(METHODE='AUTO', ...))`; the
/// method now sits at the top level (it opens the blocks of `DEFI_LIST`).
fn defi_list_methode(path: &str, given: &mut Vec<Given>, diags: &mut Vec<Diagnostic>) {
    if given.iter().any(|g| g.name == "METHODE") {
        return;
    }
    let Some(i) = given.iter().position(|g| g.name == "DEFI_LIST") else {
        return;
    };
    let Some(methode) = factor_entry(&given[i].value, "METHODE") else {
        return;
    };
    let Some(Value::Dict(d)) = crate::validate::flatten(&given[i].value).into_iter().next() else {
        return;
    };
    // A copy without METHODE: the `_F(...)` may be shared.
    let mut inner = d.borrow().clone();
    let span = inner
        .entries
        .iter()
        .find(|e| matches!(&e.key, Value::Str(k) if &**k == "METHODE"))
        .map(|e| e.span)
        .unwrap_or(given[i].span);
    inner.remove(&Value::str("METHODE"));
    let g = Given {
        name: "METHODE".into(),
        span,
        value: methode,
    };
    given[i].value = Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(inner)));
    // 'MANUEL' is the default at the top: left to it, as a current file
    // that wants the given instants writes nothing.
    if g.value.to_string() == "MANUEL" {
        warn(
            diags,
            &g,
            format!("`{path}/DEFI_LIST/METHODE` is code_aster 11 syntax: now {path}/METHODE, whose default is 'MANUEL'"),
        );
        return;
    }
    warn(
        diags,
        &g,
        format!("`{path}/DEFI_LIST/METHODE` is code_aster 11 syntax: now {path}/METHODE"),
    );
    given.push(g);
}

/// A copy of a factor keyword value (`_F(...)` or several) with `key=value`
/// added to each occurrence that lacks it. A copy, not an edit: the
/// `_F(...)` may be a variable that other calls use too.
fn with_entry_in_each(v: &Value, key: &str, value: &Value, span: aster_syntax::Span) -> Value {
    let copy = |occ: &Value| match occ {
        Value::Dict(d) => {
            let mut d = d.borrow().clone();
            if d.get(&Value::str(key)).is_none() {
                d.insert(Value::str(key), value.clone(), span);
            }
            Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(d)))
        }
        other => other.clone(),
    };
    match v {
        Value::Dict(_) => copy(v),
        other => Value::tuple(crate::validate::flatten(other).iter().map(copy).collect()),
    }
}

fn rename_inside(v: &Value, old: &str, new: &str) {
    let dicts: Vec<Value> = match v {
        Value::Dict(_) => vec![v.clone()],
        other => crate::validate::flatten(other),
    };
    for d in dicts {
        if let Value::Dict(d) = d {
            for e in d.borrow_mut().entries.iter_mut() {
                if matches!(&e.key, Value::Str(k) if &**k == old) {
                    e.key = Value::str(new);
                }
            }
        }
    }
}

/// `VALE=x` of code_aster 11 test keywords: with `REFERENCE='NON_REGRESSION'`
/// (or no reference) it is the value computed by code_aster → `VALE_CALC`,
/// checked with the old `PRECISION` (default 1e-3) as `TOLE_MACHINE`; with
/// another reference it is the reference value → `VALE_REFE` (checked with
/// `PRECISION`) and also `VALE_CALC` with the same tolerance.
fn test_resu_vale(path: &str, given: &mut Vec<Given>, diags: &mut Vec<Diagnostic>) {
    let Some(i) = given.iter().position(|g| g.name == "VALE") else {
        return;
    };
    let reference = given
        .iter()
        .find(|g| g.name == "REFERENCE")
        .map(|g| g.value.to_string());
    let precision = given
        .iter()
        .find(|g| g.name == "PRECISION")
        .map(|g| g.value.clone())
        .unwrap_or(Value::Float(1e-3));
    let g = given[i].clone();
    let has_tole = given.iter().any(|g| g.name == "TOLE_MACHINE");
    match reference.as_deref() {
        None | Some("NON_REGRESSION") => {
            warn(diags, &g, format!("`{path}/VALE` is code_aster 11 syntax: now VALE_CALC (checked with TOLE_MACHINE = the old PRECISION)"));
            given[i].name = "VALE_CALC".into();
            given.retain(|x| x.name != "REFERENCE" && x.name != "PRECISION");
            if !has_tole {
                given.push(Given {
                    name: "TOLE_MACHINE".into(),
                    span: g.span,
                    value: precision,
                });
            }
        }
        Some(r) => {
            warn(diags, &g, format!("`{path}/VALE` with REFERENCE='{r}' is code_aster 11 syntax: now VALE_REFE (and VALE_CALC with TOLE_MACHINE = PRECISION)"));
            given[i].name = "VALE_REFE".into();
            given.push(Given {
                name: "VALE_CALC".into(),
                span: g.span,
                value: g.value.clone(),
            });
            if !has_tole {
                given.push(Given {
                    name: "TOLE_MACHINE".into(),
                    span: g.span,
                    value: precision,
                });
            }
        }
    }
}

/// Values of code_aster 11 that code_aster 17 no longer allows, translated
/// only in a code_aster 11 file (a current file writing them is wrong):
/// (keyword, old value, new value, why).
pub const LEGACY_VALUES: &[(&str, &str, &str, &str)] = &[
    ("MODELISATION", "3D_INCO", "3D_INCO_UPG", INCO),
    ("MODELISATION", "D_PLAN_INCO", "D_PLAN_INCO_UPG", INCO),
    ("MODELISATION", "AXIS_INCO", "AXIS_INCO_UPG", INCO),
    ("MODELISATION", "3D_INCO_OSGS", "3D_INCO_UPO", OSGS),
    ("MODELISATION", "D_PLAN_INCO_OSGS", "D_PLAN_INCO_UPO", OSGS),
    ("MODELISATION", "AXIS_INCO_OSGS", "AXIS_INCO_UPO", OSGS),
    (
        "INFO_DBG",
        "FACTORISATION",
        "FACTOR",
        "debugging output of the factorisation",
    ),
    (
        "ALGO_CONT",
        "LAGRANGIEN",
        "CONTRAINTE",
        "code_aster 11's discrete Lagrangian contact: for frictionless contact it is code_aster 17's active-set method",
    ),
];

const INCO: &str = "the displacement-pressure-swelling formulation (as the code_aster 17 versions of the same test files write it)";
const OSGS: &str = "the OSGS-stabilised displacement-pressure formulation (as the code_aster 17 versions of the same test files write it)";

/// code_aster 11 modelisations that later versions removed (the test files
/// that used them were rewritten with other elements): no code_aster 17
/// form. The large-strain incompressible ones (`*_INCO_GD`, `*_INCO_LOG`)
/// became a `COMPORTEMENT/DEFORMATION` of `*_INCO_UPG`: not a rename of
/// the modelisation alone.
pub const REMOVED_MODELISATIONS: &[&str] = &[
    "SHB",
    "POU_C_T",
    "COQUE_C_PLAN",
    "COQUE_D_PLAN",
    "3D_GRAD_EPSI",
    "D_PLAN_GRAD_EPSI",
    "C_PLAN_GRAD_EPSI",
    "3D_INCO_GD",
    "D_PLAN_INCO_GD",
    "AXIS_INCO_GD",
    "3D_INCO_LOG",
    "D_PLAN_INCO_LOG",
    "AXIS_INCO_LOG",
    "3D_XFEM_CONT",
    "C_PLAN_XFEM_CONT",
    "D_PLAN_XFEM_CONT",
    "PLAN_ELDI",
    "AXIS_ELDI",
];

/// What becomes of a value that is not allowed.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum ValueFix {
    /// The value under its current spelling, and why.
    Renamed(Scalar, Option<&'static str>),
    /// A code_aster 11 value with no code_aster 17 equivalent.
    Unsupported(String),
}

/// A renamed value of a keyword with allowed values. `legacy`: the file was
/// written for code_aster 11 (see `aster_syntax::dialect::generation`), so
/// its values that code_aster 17 dropped are translated too; `default` is
/// the keyword's default at that place.
pub(crate) fn value(
    path: &str,
    s: &Scalar,
    into: &[Lit],
    default: Option<&[Lit]>,
    legacy: bool,
) -> Option<ValueFix> {
    let Scalar::Str(v) = s else {
        return None;
    };
    let kw = last_segment(path);
    let allowed = |new: &str| into.iter().any(|l| matches!(l, Lit::Str(x) if *x == new));
    if let Some((_, _, new)) = VALUES.iter().find(|(k, old, _)| *k == kw && old == v) {
        return allowed(new).then(|| ValueFix::Renamed(Scalar::Str(new.to_string()), None));
    }
    if !legacy {
        return None;
    }
    if let Some((_, _, new, why)) = LEGACY_VALUES
        .iter()
        .find(|(k, old, _, _)| *k == kw && old == v)
    {
        return allowed(new).then(|| ValueFix::Renamed(Scalar::Str(new.to_string()), Some(why)));
    }
    match (kw, v.as_str()) {
        // The renumbering of the unknowns changes the cost of a direct
        // solve, never its solution: code_aster 11's choices that the
        // method no longer offers become its current default.
        ("RENUM", _) => match default {
            Some([Lit::Str(d)]) => Some(ValueFix::Renamed(
                Scalar::Str(d.to_string()),
                Some("the renumbering changes the cost of the solve, not its solution"),
            )),
            _ => None,
        },
        ("MODELISATION", "SHB") => Some(ValueFix::Unsupported(format!(
            "not supported: `{path}='SHB'` (code_aster 11): the solid-shell elements are now MODELISATION='COQUE_SOLIDE', on a mesh prepared by CREA_MAILLAGE(COQUE_SOLIDE=...)"
        ))),
        ("MODELISATION", m) if REMOVED_MODELISATIONS.contains(&m) => Some(ValueFix::Unsupported(format!(
            "not supported: `{path}='{m}'` (code_aster 11): this modelisation was removed after code_aster 11"
        ))),
        ("FORMAT", "CASTEM") => Some(ValueFix::Unsupported(format!(
            "not supported: `{path}='CASTEM'` (code_aster 11): the CASTEM output format was removed after code_aster 11 (formats now: RESULTAT, IDEAS, ASTER, MED, GMSH)"
        ))),
        ("ALGO_FROT", "LAGRANGIEN") => Some(ValueFix::Unsupported(format!(
            "not supported: `{path}='LAGRANGIEN'` (code_aster 11): discrete Lagrangian friction has no code_aster 17 form (its discrete friction is penalised only: ALGO_FROT='PENALISATION')"
        ))),
        _ => None,
    }
}

/// Commands whose legacy form no longer exists in the v17 catalog but whose
/// meaning is still clear: validated against a small legacy definition.
/// `CALC_VECT_ELEM(OPTION='FORC_NODA', SIEF_ELGA=...)` (code_aster ≤ 14)
/// became `CALCUL(OPTION='FORC_NODA_ELEM')` + `EXTR_TABLE`; the call keeps
/// its old form and means "the nodal forces of the stress field SIEF_ELGA".
pub(crate) fn legacy_command(
    name: &str,
    given: &[Given],
) -> Option<(&'static aster_catalog::Command, String)> {
    use aster_catalog::{
        Cache, Command, CommandKind, Entry, Max, Node, Produces, Reentrant, SimpleKw, Status,
        ValueType,
    };
    const fn kw(
        name: &'static str,
        status: Status,
        types: &'static [ValueType],
        into: Option<&'static [Lit]>,
        default: Option<&'static [Lit]>,
    ) -> Entry {
        Entry {
            name,
            node: Node::Simple(SimpleKw {
                status,
                types,
                into,
                default,
                min: 1,
                max: Max::Count(1),
                val_min: None,
                val_max: None,
                default_cond: Cache::new(),
            }),
        }
    }
    static KEYWORDS: [Entry; 6] = [
        kw(
            "OPTION",
            Status::Mandatory,
            &[ValueType::Text],
            Some(&[Lit::Str("FORC_NODA")]),
            None,
        ),
        kw(
            "MODELE",
            Status::Mandatory,
            &[ValueType::Concept("modele_sdaster")],
            None,
            None,
        ),
        kw(
            "SIEF_ELGA",
            Status::Mandatory,
            &[ValueType::Concept("cham_elem")],
            None,
            None,
        ),
        kw(
            "CARA_ELEM",
            Status::Optional,
            &[ValueType::Concept("cara_elem")],
            None,
            None,
        ),
        kw(
            "CHAM_MATER",
            Status::Optional,
            &[ValueType::Concept("cham_mater")],
            None,
            None,
        ),
        kw(
            "INST",
            Status::Optional,
            &[ValueType::Real],
            None,
            Some(&[Lit::Real(0.0)]),
        ),
    ];
    static FORC_NODA: Command = Command {
        name: "CALC_VECT_ELEM",
        kind: CommandKind::Operator,
        produces: Produces::Type("vect_elem_depl_r"),
        reentrant: Reentrant::No,
        rules: &[],
        keywords: &KEYWORDS,
    };
    let option = given
        .iter()
        .find(|g| g.name == "OPTION")
        .map(|g| g.value.to_string());
    if name != "CALC_VECT_ELEM" || option.as_deref() != Some("FORC_NODA") {
        return None;
    }
    let cmd = &FORC_NODA;
    Some((
        cmd,
        "CALC_VECT_ELEM(OPTION='FORC_NODA') was removed in code_aster 15 (now CALCUL(OPTION='FORC_NODA_ELEM') then EXTR_TABLE); checked against its code_aster 11 definition".to_string(),
    ))
}
