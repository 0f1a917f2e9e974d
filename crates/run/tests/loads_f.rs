//! AFFE_CHAR_MECA_F / AFFE_CHAR_CINE_F: the project's scene
//! (comm/loads_f.comm on comm/strip.mail) against its analytic values, and
//! the refusal of what is not done (a dead pressure of the current
//! coordinates XF, YF, ZF).

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &Path, tag: &str) -> aster_run::program::Outcome {
    let out = std::env::temp_dir().join(format!("aster-loads-f-{tag}-{}", std::process::id()));
    let case =
        aster_run::program::prepare(comm, Some(&root().join("comm/strip.mail")), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    outcome
}

#[test]
fn function_loads_pass_the_analytic_checks() {
    let outcome = run(&root().join("comm/loads_f.comm"), "scene");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (20, 0));
}

#[test]
fn a_dead_pressure_of_the_current_coordinates_is_refused_with_its_location() {
    let dir = std::env::temp_dir().join(format!("aster-loads-f-src-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("pres_x.comm");
    std::fs::write(
        &comm,
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA=("PLATE", "RIGHT"), PHENOMENE="MECANIQUE", MODELISATION="C_PLAN"))
p = FORMULE(NOM_PARA=("XF", "INST"), VALE="10.0 * XF * INST")
load = AFFE_CHAR_MECA_F(MODELE=model, PRES_REP=_F(GROUP_MA="RIGHT", PRES=p))
mat = DEFI_MATERIAU(ELAS=_F(E=1.0, NU=0.3))
chmat = AFFE_MATERIAU(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", MATER=mat))
times = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))
resu = STAT_NON_LINE(MODELE=model, CHAM_MATER=chmat, EXCIT=_F(CHARGE=load), COMPORTEMENT=_F(RELATION="ELAS"), INCREMENT=_F(LIST_INST=times))
FIN()
"#,
    )
    .unwrap();
    // Defined, it may serve a follower load (TYPE_CHARGE='SUIV' evaluates
    // it at each point and time); a dead load refuses it where it is used.
    let outcome = run(&comm, "pres");
    let err = outcome.error.expect("refused").message;
    assert!(
        err.contains(
            "not supported yet: STAT_NON_LINE/EXCIT/CHARGE: a PRES_REP function of the current coordinates XF, YF, ZF"
        ),
        "{err}"
    );
    assert!(err.contains("pres_x.comm:9:"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_liaison_group_of_the_coordinates_is_refused_with_its_location() {
    let dir = std::env::temp_dir().join(format!("aster-loads-f-lg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("lg_x.comm");
    std::fs::write(
        &comm,
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA=("PLATE", "RIGHT", "LEFT"), PHENOMENE="MECANIQUE", MODELISATION="C_PLAN"))
g = FORMULE(NOM_PARA=("X",), VALE="1.0e-3 * X")
load = AFFE_CHAR_MECA_F(MODELE=model, LIAISON_GROUP=_F(GROUP_MA_1="RIGHT", GROUP_MA_2="LEFT", DDL_1="DX", COEF_MULT_1=1.0, DDL_2="DX", COEF_MULT_2=-1.0, COEF_IMPO=g))
FIN()
"#,
    )
    .unwrap();
    let outcome = run(&comm, "lg");
    let err = outcome.error.expect("refused").message;
    assert!(
        err.contains(
            "not supported yet: AFFE_CHAR_MECA_F/LIAISON_GROUP/COEF_IMPO as a function of X (only functions of INST)"
        ),
        "{err}"
    );
    assert!(err.contains("lg_x.comm:5:"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}
