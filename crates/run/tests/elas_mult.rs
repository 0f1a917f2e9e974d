//! MACRO_ELAS_MULT: the project's scene (comm/elas_mult_strip.comm: a DKT
//! cantilever under load cases named by NOM_CAS, their combination, a
//! `reuse` adding and replacing cases, REAC_NODA, POST_RELEVE_T and
//! CREA_CHAMP by NOM_CAS) against beam theory, and the errors and
//! refusals, located.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &Path, tag: &str) -> aster_run::program::Outcome {
    let out = std::env::temp_dir().join(format!("aster-elas-mult-{tag}-{}", std::process::id()));
    let mesh = root().join("comm").join("edge_strip.mail");
    let case = aster_run::program::prepare(comm, Some(&mesh), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    outcome
}

#[test]
fn load_cases_of_a_dkt_cantilever_against_beam_theory() {
    let outcome = run(&root().join("comm").join("elas_mult_strip.comm"), "scene");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    // 15 values x 2 (NON_REGRESSION, ANALYTIQUE).
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (30, 0));
}

/// The strip, its clamp and two cases; `tail` follows.
fn program(tail: &str) -> String {
    format!(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA="STRIP", PHENOMENE="MECANIQUE", MODELISATION="DKT"))
cara = AFFE_CARA_ELEM(MODELE=model, COQUE=_F(GROUP_MA="STRIP", EPAIS=0.1))
steel = DEFI_MATERIAU(ELAS=_F(E=1.0e7, NU=0.0))
mater = AFFE_MATERIAU(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", MATER=steel))
clamp = AFFE_CHAR_MECA(MODELE=model, DDL_IMPO=_F(GROUP_NO="CLAMP", DX=0.0, DY=0.0, DZ=0.0, DRX=0.0, DRY=0.0, DRZ=0.0))
pres = AFFE_CHAR_MECA(MODELE=model, FORCE_COQUE=_F(TOUT="OUI", PRES=1.0))
axial = AFFE_CHAR_MECA(MODELE=model, FORCE_COQUE=_F(TOUT="OUI", FX=10.0))
{tail}
FIN()
"#
    )
}

const SOLVED: &str = r#"res = MACRO_ELAS_MULT(MODELE=model, CHAM_MATER=mater, CARA_ELEM=cara, CHAR_MECA_GLOBAL=clamp,
    CAS_CHARGE=(_F(NOM_CAS="PRES", CHAR_MECA=pres), _F(NOM_CAS="AXIAL", CHAR_MECA=axial, OPTION="SANS")))"#;

/// Runs a program on the strip and returns its error message.
fn error_of(source: &str, tag: &str) -> String {
    let dir =
        std::env::temp_dir().join(format!("aster-elas-mult-src-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join(format!("{tag}.comm"));
    std::fs::write(&comm, source).unwrap();
    let outcome = run(&comm, tag);
    let _ = std::fs::remove_dir_all(dir);
    outcome.error.expect("an error").message
}

#[test]
fn an_unknown_nom_cas_names_the_cases_there_are() {
    let err = error_of(
        &program(&format!(
            "{SOLVED}\nTEST_RESU(RESU=_F(RESULTAT=res, NOM_CAS=\"PRESS\", NOM_CHAM=\"DEPL\", GROUP_NO=\"TIP\", NOM_CMP=\"DZ\", VALE_CALC=-1.52))"
        )),
        "unknown",
    );
    assert!(
        err.contains("the result has no load case 'PRESS' (its NOM_CAS: 'PRES', 'AXIAL')"),
        "{err}"
    );
    assert!(err.contains("unknown.comm:12:33"), "{err}");
}

#[test]
fn a_mult_elas_has_no_instant_and_an_evol_elas_no_nom_cas() {
    let err = error_of(
        &program(&format!(
            "{SOLVED}\nu = CREA_CHAMP(OPERATION=\"EXTR\", TYPE_CHAM=\"NOEU_DEPL_R\", RESULTAT=res, NOM_CHAM=\"DEPL\", INST=0.0)"
        )),
        "inst",
    );
    assert!(err.contains("CREA_CHAMP/INST: the result is a MACRO_ELAS_MULT's (mult_elas): its steps are named by NOM_CAS or NUME_ORDRE"), "{err}");
    let err = error_of(
        &program(
            "res = MECA_STATIQUE(MODELE=model, CHAM_MATER=mater, CARA_ELEM=cara, EXCIT=(_F(CHARGE=clamp), _F(CHARGE=pres)))\nu = CREA_CHAMP(OPERATION=\"EXTR\", TYPE_CHAM=\"NOEU_DEPL_R\", RESULTAT=res, NOM_CHAM=\"DEPL\", NOM_CAS=\"PRES\")",
        ),
        "evol",
    );
    assert!(
        err.contains(
            "'PRES': the result is not a MACRO_ELAS_MULT's (mult_elas), it has no NOM_CAS"
        ),
        "{err}"
    );
}

#[test]
fn option_sans_stores_no_stresses_until_calc_champ_computes_them() {
    let extract = "s = CREA_CHAMP(OPERATION=\"EXTR\", TYPE_CHAM=\"ELGA_SIEF_R\", RESULTAT=res, NOM_CHAM=\"SIEF_ELGA\", NOM_CAS=\"AXIAL\")";
    let err = error_of(&program(&format!("{SOLVED}\n{extract}")), "sans");
    assert!(err.contains("SIEF_ELGA"), "{err}");
    // The case with the default OPTION='SIEF_ELGA' has them; CALC_CHAMP
    // computes them for the other.
    let ok = format!("{SOLVED}\n{}\nres = CALC_CHAMP(reuse=res, RESULTAT=res, NOM_CAS=\"AXIAL\", CONTRAINTE=\"SIEF_ELGA\")\n{extract}", extract.replace("AXIAL", "PRES"));
    let dir = std::env::temp_dir().join(format!("aster-elas-mult-src-calc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("calc.comm");
    std::fs::write(&comm, program(&ok)).unwrap();
    let outcome = run(&comm, "calc");
    let _ = std::fs::remove_dir_all(dir);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
}

#[test]
fn conditions_in_a_case_and_time_functions_are_refused_at_the_keyword() {
    let err = error_of(
        &program(
            "res = MACRO_ELAS_MULT(MODELE=model, CHAM_MATER=mater, CARA_ELEM=cara, CHAR_MECA_GLOBAL=pres,\n    CAS_CHARGE=_F(NOM_CAS=\"C\", CHAR_MECA=clamp))",
        ),
        "cond",
    );
    assert!(
        err.contains(
            "not supported yet: MACRO_ELAS_MULT/CAS_CHARGE/CHAR_MECA: a load with conditions"
        ),
        "{err}"
    );
    assert!(err.contains("cond.comm:11:"), "{err}");
    let err = error_of(
        &program(
            "ramp = DEFI_FONCTION(NOM_PARA=\"INST\", VALE=(0.0, 0.0, 1.0, 1.0))\nrp = AFFE_CHAR_MECA_F(MODELE=model, FORCE_COQUE=_F(TOUT=\"OUI\", PRES=ramp))\nres = MACRO_ELAS_MULT(MODELE=model, CHAM_MATER=mater, CARA_ELEM=cara, CHAR_MECA_GLOBAL=clamp,\n    CAS_CHARGE=_F(NOM_CAS=\"C\", CHAR_MECA=rp))",
        ),
        "time",
    );
    assert!(err.contains("not supported yet: MACRO_ELAS_MULT/CAS_CHARGE/CHAR_MECA: a load given by functions of INST"), "{err}");
    assert!(err.contains("time.comm:13:32"), "{err}");
}

#[test]
fn fourier_modes_are_refused_before_the_run() {
    let err = error_of(
        &program(
            "res = MACRO_ELAS_MULT(MODELE=model, CHAM_MATER=mater, CARA_ELEM=cara, CHAR_MECA_GLOBAL=clamp,\n    CAS_CHARGE=_F(MODE_FOURIER=0, CHAR_MECA=pres))",
        ),
        "fourier",
    );
    assert!(
        err.contains("MACRO_ELAS_MULT/CAS_CHARGE/MODE_FOURIER"),
        "{err}"
    );
    assert!(
        err.contains("(Fourier modes need the AXIS_FOURIER modelisation"),
        "{err}"
    );
    assert!(!err.contains("(("), "{err}");
    assert!(err.contains("fourier.comm:11:"), "{err}");
}

#[test]
fn a_reuse_on_other_global_loads_is_refused() {
    let err = error_of(
        &program(&format!(
            "{SOLVED}\nres = MACRO_ELAS_MULT(reuse=res, RESULTAT=res, MODELE=model, CHAM_MATER=mater, CARA_ELEM=cara, CHAR_MECA_GLOBAL=(clamp, axial),\n    CAS_CHARGE=_F(NOM_CAS=\"MORE\", CHAR_MECA=pres))"
        )),
        "reuse",
    );
    assert!(err.contains("not supported yet: MACRO_ELAS_MULT with reuse= on another MODELE, CHAM_MATER, CARA_ELEM or CHAR_MECA_GLOBAL"), "{err}");
}
