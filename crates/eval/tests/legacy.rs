//! code_aster 11 files: each legacy construct is translated to its
//! code_aster 17 form (a warning names it) and the calls handed on carry the
//! current names only; a construct with no current form is "not supported";
//! a code_aster 17 file writing the same spellings is still reported.

use aster_eval::*;
use aster_syntax::CodeMap;
use std::path::Path;

fn check(name: &str) -> (CheckReport, String) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/legacy")
        .join(name);
    let source =
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let map = CodeMap::new(format!("tests/legacy/{name}"), source);
    let report = check_source(&map, true);
    let text = report.diagnostics.render(&map);
    (report, text)
}

fn calls<'a>(report: &'a CheckReport, command: &str) -> Vec<&'a CommandCall> {
    report
        .calls
        .iter()
        .filter(|c| c.command == command)
        .collect()
}

fn result_name(c: &CommandCall) -> &str {
    c.result.as_ref().map(|r| r.name.as_str()).unwrap_or("")
}

fn str_of<'a>(k: &'a Keywords, name: &str) -> Option<&'a str> {
    k.str(name)
}

#[test]
fn v11_file_checks_clean_with_each_construct_translated() {
    let (report, text) = check("v11_translated.comm");
    assert!(report.ok(), "must check clean:\n{text}");
    assert!(
        report
            .diagnostics
            .0
            .iter()
            .all(|d| d.kind == DiagKind::Legacy),
        "{text}"
    );
    insta::assert_snapshot!("v11_translated", text);

    // No legacy command reaches the sink.
    for old in ["MODE_ITER_SIMULT", "MODE_ITER_INV", "MACRO_MATR_ASSE"] {
        assert!(calls(&report, old).is_empty(), "{old} handed on");
    }

    // Several modelisations in one AFFE → one occurrence each, in order;
    // PARTITION → DISTRIBUTION.
    let mo = &calls(&report, "AFFE_MODELE")[0].keywords;
    let models: Vec<_> = mo
        .factor("AFFE")
        .iter()
        .map(|o| str_of(o, "MODELISATION").unwrap_or(""))
        .collect();
    assert_eq!(models, ["D_PLAN", "D_PLAN_SI"]);
    assert_eq!(
        str_of(&mo.factor("DISTRIBUTION")[0], "METHODE"),
        Some("CENTRALISE")
    );
    // `xrange` ran the loop; IMPR_RESU keeps code_aster 17's default
    // format unless MODELE= asks for code_aster 11's text one.
    let prints = calls(&report, "IMPR_RESU");
    assert_eq!(prints.len(), 3);
    assert_eq!(str_of(&prints[0].keywords, "FORMAT"), Some("MED"));
    assert_eq!(str_of(&prints[2].keywords, "FORMAT"), Some("RESULTAT"));

    // Discrete Lagrangian contact → CONTRAINTE.
    let cont = calls(&report, "DEFI_CONTACT");
    let zone = &cont[0].keywords.factor("ZONE")[0];
    assert_eq!(str_of(zone, "ALGO_CONT"), Some("CONTRAINTE"));

    // COMP_INCR + COMP_ELAS → one COMPORTEMENT with both occurrences.
    let snl = &calls(&report, "STAT_NON_LINE")[0].keywords;
    let comp: Vec<_> = snl
        .factor("COMPORTEMENT")
        .iter()
        .map(|o| str_of(o, "RELATION").unwrap_or(""))
        .collect();
    assert_eq!(comp, ["VMIS_ISOT_LINE", "ELAS"]);
    // RENUM='SANS' (no longer offered by LDLT) → LDLT's default.
    assert_eq!(str_of(&snl.factor("SOLVEUR")[0], "RENUM"), Some("RCMK"));

    // DEFI_LIST/METHODE → METHODE.
    let li = &calls(&report, "DEFI_LIST_INST")[0].keywords;
    assert_eq!(str_of(li, "METHODE"), Some("MANUEL"));
    // ... as the default: a runner that knows only the default method
    // sees what a current file gives it.
    assert!(li.keyword("METHODE").is_some_and(|k| k.defaulted));
    assert!(!li.factor("DEFI_LIST")[0].contains("METHODE"));

    // MACRO_MATR_ASSE → ASSEMBLAGE, SOLVEUR dropped.
    let asse = calls(&report, "ASSEMBLAGE");
    assert_eq!(asse.len(), 1);
    assert!(!asse[0].keywords.contains("SOLVEUR"));
    assert_eq!(asse[0].keywords.factor("MATR_ASSE").len(), 2);

    // MODE_ITER_SIMULT → CALC_MODES: OPTION up, METHODE into SOLVEUR_MODAL,
    // MATR_A/MATR_B renamed for the dynamic problem.
    let modes = calls(&report, "CALC_MODES");
    assert_eq!(
        modes.len(),
        3,
        "{:?}",
        modes.iter().map(|c| result_name(c)).collect::<Vec<_>>()
    );
    let m = &modes[0].keywords;
    assert_eq!(str_of(m, "OPTION"), Some("BANDE"));
    assert_eq!(
        m.concept("MATR_RIGI").map(|c| c.name.as_str()),
        Some("RIGI")
    );
    assert_eq!(
        m.concept("MATR_MASS").map(|c| c.name.as_str()),
        Some("MASS")
    );
    assert_eq!(
        str_of(&m.factor("SOLVEUR_MODAL")[0], "METHODE"),
        Some("SORENSEN")
    );
    let freqs: Vec<f64> = m.factor("CALC_FREQ")[0]
        .simple("FREQ")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    assert_eq!(freqs, [5.0, 100.0]);
    // The shared `BANDE = _F(...)` was not emptied by the first call.
    assert_eq!(str_of(&modes[1].keywords, "OPTION"), Some("BANDE"));
    // MODE_ITER_INV: OPTION defaults to code_aster 11's 'AJUSTE'; CALC_MODE
    // → SOLVEUR_MODAL/OPTION_INV.
    let inv = &modes[2].keywords;
    assert_eq!(str_of(inv, "OPTION"), Some("AJUSTE"));
    assert_eq!(
        str_of(&inv.factor("SOLVEUR_MODAL")[0], "OPTION_INV"),
        Some("RAYLEIGH")
    );

    // THER_LINEAIRE without INCREMENT: stationary, with a time list made
    // before it.
    let ther = &calls(&report, "THER_LINEAIRE")[0].keywords;
    assert_eq!(str_of(ther, "TYPE_CALCUL"), Some("STAT"));
    assert_eq!(str_of(ther, "TITRE"), Some("STATIONARY CASE"));
    let list = ther.factor("INCREMENT")[0].concept("LIST_INST").cloned();
    let made = report
        .calls
        .iter()
        .find(|c| c.command == "DEFI_LIST_REEL" && c.result.as_ref() == list.as_ref());
    let made = made.map(|c| c.keywords.simple("VALE").to_vec());
    assert_eq!(made, Some(vec![Scalar::Real(0.0)]));

    // CREA_RESU: NOM_CHAM in each AFFE occurrence.
    let crea = &calls(&report, "CREA_RESU")[0].keywords;
    let noms: Vec<_> = crea
        .factor("AFFE")
        .iter()
        .map(|o| str_of(o, "NOM_CHAM"))
        .collect();
    assert_eq!(noms, [Some("TEMP"), Some("TEMP")]);

    // ELAS_FO/RHO=7800.0 (a function since code_aster 12) → a
    // DEFI_CONSTANTE defined just before.
    let acier = report
        .calls
        .iter()
        .position(|c| result_name(c) == "ACIER")
        .unwrap_or(0);
    let rho = report.calls[acier].keywords.factor("ELAS_FO")[0]
        .concept("RHO")
        .cloned();
    assert_eq!(
        rho.as_ref().map(|c| c.typ.as_str()),
        Some("fonction_sdaster")
    );
    let before = &report.calls[acier - 1];
    assert_eq!(before.command, "DEFI_CONSTANTE");
    assert_eq!(before.result, rho);
    assert_eq!(before.keywords.f64("VALE"), Some(7800.0));
    // ELAS_FO/FONC_DESORP → BETON_DESORP=_F(FONC_DESORP=...).
    let acier = &report.calls[acier].keywords;
    assert!(!acier.factor("ELAS_FO")[0].contains("FONC_DESORP"));
    assert_eq!(
        acier.factor("BETON_DESORP")[0]
            .concept("FONC_DESORP")
            .map(|c| c.name.as_str()),
        Some("NUF")
    );

    // CREA_MAILLAGE(COPIE=_F()) → COPIER(CONCEPT=MA).
    let copie = calls(&report, "COPIER");
    assert_eq!(
        copie[0]
            .keywords
            .concept("CONCEPT")
            .map(|c| c.name.as_str()),
        Some("MA")
    );
}

#[test]
fn v11_constructs_without_a_current_form_are_not_supported() {
    let (report, text) = check("v11_refused.comm");
    assert!(!report.ok(), "{text}");
    let errors: Vec<_> = report
        .diagnostics
        .0
        .iter()
        .filter(|d| d.is_error())
        .collect();
    // One refusal each, no "missing E_T" or "missing GROUP_MA" that the
    // refused construct made moot.
    assert_eq!(errors.len(), 4, "{text}");
    for e in &errors {
        assert_eq!(e.kind, DiagKind::NotSupported, "{text}");
        assert!(e.message.contains("(code_aster 11)"), "{text}");
    }
    insta::assert_snapshot!("v11_refused", text);
}

#[test]
fn v17_file_with_the_same_spellings_is_still_reported() {
    let (report, text) = check("v17_not_loosened.comm");
    let kinds: Vec<DiagKind> = report
        .diagnostics
        .0
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.kind)
        .collect();
    assert_eq!(
        kinds,
        [
            DiagKind::NotInto,
            DiagKind::UnknownKeyword,
            DiagKind::UnknownKeyword,
            DiagKind::Rule,
            DiagKind::UnknownCommand
        ],
        "{text}"
    );
    assert!(report
        .diagnostics
        .0
        .iter()
        .all(|d| d.kind != DiagKind::Legacy));
    insta::assert_snapshot!("v17_not_loosened", text);
}
