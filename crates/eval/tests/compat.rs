//! What code_aster 17 itself accepts must check clean: its compatibility
//! rewrites (`compat_syntax`/`adapt_syntax` of the commands), result types
//! that its macros compute differently from the catalog's `sd_prod`, and
//! values only known when the commands run. One case per kind of former
//! false error, each with the keywords the model layer then sees.

use aster_eval::*;
use aster_syntax::CodeMap;

fn check(src: &str) -> (CheckReport, String) {
    let map = CodeMap::new("c.comm", src);
    let report = check_source(&map, true);
    let text = report.diagnostics.render(&map);
    (report, text)
}

fn clean(src: &str) -> (CheckReport, String) {
    let (report, text) = check(src);
    assert!(report.ok(), "should check clean:\n{text}");
    (report, text)
}

fn call<'a>(report: &'a CheckReport, command: &str) -> &'a CommandCall {
    match report.calls.iter().find(|c| c.command == command) {
        Some(c) => c,
        None => panic!("no {command} call recorded"),
    }
}

const THERMAL_SETUP: &str = r#"
MA = LIRE_MAILLAGE(FORMAT="MED")
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="THERMIQUE", MODELISATION="PLAN"))
MAT = DEFI_MATERIAU(THER=_F(LAMBDA=1.0, RHO_CP=1.0))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
CH = AFFE_CHAR_THER(MODELE=MO, TEMP_IMPO=_F(GROUP_MA="BORD", TEMP=0.0))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=10.0, NOMBRE=5))
"#;

#[test]
fn sech_non_line_takes_theta_from_schema_temps() {
    let src = format!(
        "{THERMAL_SETUP}
R = SECH_NON_LINE(
    MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH),
    SCHEMA_TEMPS=_F(SCHEMA='THETA', THETA=0.6),
    ETAT_INIT=_F(VALE=1.0),
    INCREMENT=_F(LIST_INST=L),
    COMPORTEMENT=_F(RELATION='SECH_GRANGER', TOUT='OUI'),
)
"
    );
    let (report, text) = clean(&src);
    assert!(
        text.contains("warning: `SECH_NON_LINE/SCHEMA_TEMPS=_F(THETA=...)` is compatibility syntax: now PARM_THETA"),
        "{text}"
    );
    let k = &call(&report, "SECH_NON_LINE").keywords;
    assert_eq!(k.f64("PARM_THETA"), Some(0.6));
    assert!(!k.contains("SCHEMA_TEMPS"));
}

#[test]
fn lire_fonction_separ_is_separateur() {
    let (report, text) = clean(
        r#"F = LIRE_FONCTION(UNITE=30, NOM_PARA="FREQ", SEPAR=";")
"#,
    );
    assert!(
        text.contains("`LIRE_FONCTION/SEPAR` is legacy syntax: now SEPARATEUR"),
        "{text}"
    );
    let k = &call(&report, "LIRE_FONCTION").keywords;
    assert_eq!(k.str("SEPARATEUR"), Some(";"));
    assert_eq!(
        report.calls[0].result.as_ref().map(|c| c.typ.as_str()),
        Some("fonction_sdaster")
    );

    // Only the four separators code_aster translates; never both spellings.
    let (report, text) = check(
        r#"F = LIRE_FONCTION(UNITE=30, NOM_PARA="FREQ", SEPAR="|")
"#,
    );
    assert!(!report.ok());
    assert!(text.contains("c.comm:1:46: error: `LIRE_FONCTION/SEPAR` (legacy spelling of SEPARATEUR): value '|' is not allowed"), "{text}");
    let (report, text) = check(
        r#"F = LIRE_FONCTION(UNITE=30, NOM_PARA="FREQ", SEPAR=",", SEPARATEUR=",")
"#,
    );
    assert!(!report.ok());
    assert!(text.contains("give only SEPARATEUR"), "{text}");
}

#[test]
fn removed_keywords_of_detruire_and_fin_are_ignored() {
    let (report, text) = clean(
        r#"L = DEFI_LIST_REEL(VALE=1.0)
DETRUIRE(NOM=L, OBJET=_F(CHAINE="L"))
FIN(FORMAT_HDF="NON")
"#,
    );
    assert!(
        text.contains("`DETRUIRE/OBJET` no longer exists and is ignored"),
        "{text}"
    );
    assert!(
        text.contains("`FIN/FORMAT_HDF` no longer exists and is ignored"),
        "{text}"
    );
    assert!(!call(&report, "DETRUIRE").keywords.contains("OBJET"));
    assert!(!call(&report, "FIN").keywords.contains("FORMAT_HDF"));
}

#[test]
fn a_complex_formula_is_a_formula() {
    // formule_c is a subclass of formule in code_aster's data structures.
    let (report, _) = clean(
        r#"FC = FORMULE(VALE_C="complex(X, 2.0*X)", NOM_PARA="X")
TEST_FONCTION(VALEUR=_F(FONCTION=FC, VALE_PARA=1.0, VALE_CALC_C=1.0 + 2.0j))
"#,
    );
    assert_eq!(
        report.calls[0].result.as_ref().map(|c| c.typ.as_str()),
        Some("formule_c")
    );
}

#[test]
fn extr_table_of_a_number_is_a_number() {
    let (report, _) = clean(
        r#"T = CREA_TABLE(LISTE=(_F(PARA="N", LISTE_I=(1, 2)), _F(PARA="X", LISTE_R=(1.0, 2.0))))
n = EXTR_TABLE(TYPE_RESU="ENTIER", TABLE=T, NOM_PARA="N", FILTRE=_F(NOM_PARA="X", VALE=2.0))
x = EXTR_TABLE(TYPE_RESU="REEL", TABLE=T, NOM_PARA="X", FILTRE=_F(NOM_PARA="N", VALE_I=1))
T2 = CREA_TABLE(LISTE=(_F(PARA="N", LISTE_I=n), _F(PARA="X", LISTE_R=x * 2.0)))
"#,
    );
    // The numbers are known when the commands run: the call keeps them
    // as such, the checker does not invent a value.
    let t2 = &report.calls[3].keywords;
    assert_eq!(t2.factor("LISTE").len(), 2);
}

#[test]
fn calc_ther_mult_gives_a_dictionary_of_results() {
    let src = format!(
        "{THERMAL_SETUP}
RT = CALC_THER_MULT(
    MODELE=MO, CHAM_MATER=CM, CHAR_THER_GLOBAL=CH,
    CAS_CHARGE=(_F(COEF_H=1e-3, DUREE_CHOC=0.1, LIST_INST=L, GROUP_MA='BORD', NOM_CAS='C1'),),
)
R1 = EXTR_CONCEPT(NOM='C1', DICT=RT)
MOM = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))
ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, ALPHA=1e-5))
CMM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))
BLOC = AFFE_CHAR_MECA(MODELE=MOM, DDL_IMPO=_F(GROUP_MA='BORD', DX=0.0, DY=0.0))
RM = CALC_MECA_MULT(MODELE=MOM, CHAM_MATER=CMM, CHAR_MECA_GLOBAL=BLOC,
                    CAS_CHARGE=_F(EVOL_THER=RT, VALE_REF=0.0))
"
    );
    let (report, _) = clean(&src);
    let typ = |cmd: &str| {
        call(&report, cmd)
            .result
            .as_ref()
            .map(|c| c.typ.clone())
            .unwrap_or_default()
    };
    assert_eq!(typ("CALC_THER_MULT"), "evol_ther_dict");
    assert_eq!(typ("EXTR_CONCEPT"), "?");
    assert_eq!(typ("CALC_MECA_MULT"), "evol_noli_dict");
    // A single evol_ther still needs its case name.
    let src = format!(
        "{THERMAL_SETUP}
RT = THER_LINEAIRE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH), INCREMENT=_F(LIST_INST=L))
MOM = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))
ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, ALPHA=1e-5))
CMM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))
BLOC = AFFE_CHAR_MECA(MODELE=MOM, DDL_IMPO=_F(GROUP_MA='BORD', DX=0.0, DY=0.0))
RM = CALC_MECA_MULT(MODELE=MOM, CHAM_MATER=CMM, CHAR_MECA_GLOBAL=BLOC,
                    CAS_CHARGE=_F(EVOL_THER=RT, VALE_REF=0.0))
"
    );
    let (report, text) = check(&src);
    assert!(!report.ok());
    assert!(text.contains("missing mandatory keyword NOM_CAS"), "{text}");
}

const MECHANICAL_RESULT: &str = r#"
MA = LIRE_MAILLAGE(FORMAT="MED")
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=ACIER))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_MA="BORD", DX=0.0, DY=0.0))
R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=BLOC))
"#;

#[test]
fn extr_coupe_gives_a_result_of_the_type_it_cuts() {
    let src = format!(
        "{MECHANICAL_RESULT}
TC = CREA_TABLE(LISTE=_F(PARA='NOM', LISTE_K=('C1',)))
RC = EXTR_COUPE(RESULTAT=R, COUPE=TC, REPERE='GLOBAL', LINEARISATION='NON', REPARTITION='UNIFORME')
D = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=RC, NOM_CHAM='DEPL', NUME_ORDRE=1)
"
    );
    let (report, _) = clean(&src);
    assert_eq!(
        call(&report, "EXTR_COUPE")
            .result
            .as_ref()
            .map(|c| c.typ.as_str()),
        Some("evol_elas")
    );
}

#[test]
fn a_concept_known_only_at_run_time_opens_its_blocks() {
    // `R.copy()` is a concept the checker cannot type: the blocks that
    // depend on its type accept their keywords.
    let src = format!(
        "{MECHANICAL_RESULT}
R0 = R.copy()
CALC_CHAMP(reuse=R0, RESULTAT=R0, CONTRAINTE='SIGM_ELNO')
"
    );
    let (report, _) = clean(&src);
    let k = &call(&report, "CALC_CHAMP").keywords;
    assert_eq!(k.str("CONTRAINTE"), Some("SIGM_ELNO"));
    // With a known type, the block still closes where code_aster closes it.
    let src = format!(
        "{MECHANICAL_RESULT}
L = DEFI_LIST_REEL(VALE=1.0)
CALC_CHAMP(RESULTAT=L, CONTRAINTE='SIGM_ELNO')
"
    );
    let (report, _) = check(&src);
    assert!(!report.ok());
}

#[test]
fn getattr_reads_attributes() {
    let (report, _) = clean(
        r#"T = CREA_TABLE(LISTE=_F(PARA="X", LISTE_R=(1.0, 2.0)))
x = getattr(T.EXTR_TABLE(), "X")[0]
s = getattr("abc", "upper")()
L = DEFI_LIST_REEL(VALE=(x, len(s)))
"#,
    );
    assert_eq!(report.calls.len(), 2);
    let (report, text) = check("x = getattr(1.0, 2)\n");
    assert!(!report.ok());
    assert!(text.contains("attribute name must be a string"), "{text}");
}

#[test]
fn try_except_import_error_runs_the_fallback() {
    let (report, text) = clean(
        r#"try:
    from code_aster.Utilities import sympy
    sympy.__version__
    HAVE_SYMPY = True
except ImportError:
    HAVE_SYMPY = False
if HAVE_SYMPY:
    X = sympy.symbols("X")
    F = FORMULE(VALE=str(X * 2), NOM_PARA="X")
else:
    F = FORMULE(VALE="X*2.0", NOM_PARA="X")
try:
    import math
except (ImportError, ModuleNotFoundError):
    raise
else:
    L = DEFI_LIST_REEL(VALE=math.pi)
finally:
    M = DEFI_LIST_REEL(VALE=1.0)
"#,
    );
    assert!(
        text.contains("c.comm:3:11: warning: `code_aster.Utilities.sympy.__version__` raises ImportError here: checking the `except ImportError` branch"),
        "{text}"
    );
    let names: Vec<_> = report.calls.iter().map(|c| c.command.as_str()).collect();
    assert_eq!(names, ["FORMULE", "DEFI_LIST_REEL", "DEFI_LIST_REEL"]);
    assert_eq!(report.calls[0].keywords.str("VALE"), Some("X*2.0"));
    let (report, _) = clean("try:\n    import numpy as np\nexcept ImportError:\n    np = None\n");
    assert!(report.calls.is_empty());
}

#[test]
fn other_try_statements_stay_outside_the_subset() {
    // A handler for code_aster's errors: the body is checked (its commands
    // raise nothing while checking).
    let (report, text) = check(
        r#"try:
    L = DEFI_LIST_REEL(VALE=1.0)
except CA.AsterError as err:
    ok = err.id_message == "CONTACT_93"
"#,
    );
    assert!(report.ok(), "{text}");
    assert_eq!(report.calls.len(), 1);
    // Checking runs no command: what the handler assigns is known only when
    // the program runs, so an assertion on it is left to the run...
    let (report, text) = check(
        r#"test = CA.TestCase()
is_ok = 0
try:
    L = DEFI_LIST_REEL(VALE=1.0)
except CA.AsterError as err:
    if err.id_message == "CONTACT_93":
        is_ok = 1
test.assertEqual(is_ok, 1)
"#,
    );
    assert!(report.ok(), "{text}");
    // ...and an error in the body may be the one the program expects: not
    // the file's error, a step known only when the commands run.
    let (report, text) = check(
        r#"try:
    L = DEFI_LIST_REEL(VALE=1.0, NO_SUCH=2)
except CA.AsterError as err:
    pass
"#,
    );
    assert!(!report.ok());
    assert!(!text.contains("unknown keyword"), "{text}");
    assert!(text.contains("c.comm:1:1: error: not supported: checking `try: … except CA.AsterError` around a command with an error"), "{text}");
    assert!(
        report
            .diagnostics
            .0
            .iter()
            .all(|d| d.kind == aster_eval::DiagKind::RunTimeValue),
        "{text}"
    );
    // Mixed with another exception: outside the subset.
    let (report, text) = check(
        "try:
    L = DEFI_LIST_REEL(VALE=1.0)
except (CA.AsterError, ValueError):
    pass
except KeyError:
    pass
",
    );
    assert!(!report.ok());
    assert!(text.contains("c.comm:1:1: error: not supported: try/except mixing code_aster's errors with other exceptions"), "{text}");
    let (report, text) = check("try:\n    x = 1 / 0\nexcept ZeroDivisionError:\n    x = 0\n");
    assert!(!report.ok());
    assert!(text.contains("c.comm:1:1: error: not supported: try/except (only `except ImportError` around imports is supported)"), "{text}");
    // An ImportError handler does not swallow other unsupported things.
    let (report, text) = check("try:\n    f = open('x')\nexcept ImportError:\n    f = None\n");
    assert!(!report.ok());
    assert!(text.contains("not supported: the builtin `open`"), "{text}");
}

#[test]
fn testcase_assertions_are_evaluated_when_their_values_are_known() {
    let (report, _) = clean(
        r#"test = CA.TestCase()
n = len([1, 2, 3])
test.assertEqual(n, 3)
test.assertTrue(n > 2)
test.assertFalse(n > 5)
test.assertAlmostEqual(0.1 + 0.2, 0.3)
test.assertAlmostEqual(1.0, 1.05, delta=0.1)
test.assertSequenceEqual([1, 2], (1, 2))
test.assertIn("DX", ("DX", "DY"))
test.assertLessEqual(n, 3)
test.assertIsNone(None)
T = CREA_TABLE(LISTE=_F(PARA="X", LISTE_R=(1.0, 2.0)))
test.assertEqual(T["X", 1], 99.0)
test.printSummary()
"#,
    );
    assert_eq!(report.calls.len(), 1);
    // A failing assertion is what the run would report: an error, and the
    // program goes on.
    let (report, text) = check(
        r#"test = CA.TestCase()
test.assertEqual(2 + 2, 5)
test.assertAlmostEqual(1.0, 1.001, places=4)
L = DEFI_LIST_REEL(VALE=1.0)
"#,
    );
    assert!(!report.ok());
    assert!(
        text.contains("c.comm:2:1: error: TestCase assertion fails: assertEqual(4, 5) is false"),
        "{text}"
    );
    assert!(
        text.contains("assertAlmostEqual(1.0, 1.001) is false"),
        "{text}"
    );
    assert_eq!(report.calls.len(), 1);
    let (report, text) = check("test = CA.TestCase()\ntest.assertRaises(1)\n");
    assert!(!report.ok());
    assert!(
        text.contains("not supported: `TestCase.assertRaises`"),
        "{text}"
    );
}

#[test]
fn defi_cont_is_imported_as_its_catalog_command() {
    // code_aster 17's DEFI_CONT (a Python macro, imported from
    // code_aster.MacroCommands.defi_cont) is checked against its catalog
    // (DEFI_CONT_CATA): MODELE is required, and the result is a char_cont.
    let (report, text) = check(
        "from code_aster.MacroCommands.defi_cont import DEFI_CONT\nC = DEFI_CONT(ZONE=_F(GROUP_MA_ESCL='S', GROUP_MA_MAIT='M'))\n",
    );
    assert!(!report.ok());
    assert!(
        text.contains("c.comm:2:5: error:") && text.contains("MODELE"),
        "{text}"
    );
    let (report, _) = clean(
        "from code_aster.MacroCommands.defi_cont import DEFI_CONT\nM = LIRE_MAILLAGE()\nMO = AFFE_MODELE(MAILLAGE=M, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\nC = DEFI_CONT(MODELE=MO, ZONE=_F(GROUP_MA_ESCL='S', GROUP_MA_MAIT='M', COEF_CONT=10.0))\n",
    );
    assert_eq!(report.calls.len(), 3);
    assert_eq!(report.calls[2].command, "DEFI_CONT");
}

#[test]
fn numpy_is_imported_and_refused_where_used() {
    // SSNP167G imports numpy and never uses it: the file runs.
    let (report, _) = clean("import numpy as NP\nL = DEFI_LIST_REEL(VALE=1.0)\n");
    assert_eq!(report.calls.len(), 1);
    // A use is refused at the attribute, located.
    let (report, text) = check("import numpy as NP\nx = NP.array([1.0])\n");
    assert!(!report.ok());
    assert!(
        text.contains("c.comm:2:8: error: not supported: `numpy.array`"),
        "{text}"
    );
    let (report, text) = check("from numpy import array\n");
    assert!(!report.ok());
    assert!(
        text.contains("not supported: import from module `numpy`"),
        "{text}"
    );
}
