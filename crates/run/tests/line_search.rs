//! `RECH_LINEAIRE` on the project's scene `comm/line_search_bar.comm`: a
//! bar pulled by a force beyond the knee of a traction curve, with and
//! without the line search (CORDE, MIXTE, MECA_NON_LINE's, DYNA_NON_LINE's),
//! against the
//! uniaxial closed form; and what is refused before the run.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &str, name: &str) -> aster_run::program::Outcome {
    run_on(comm, name, "comm/hexs8_beam.mail")
}

fn run_on(comm: &str, name: &str, mesh: &str) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-linesearch-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.comm"));
    std::fs::write(&file, comm).unwrap();
    let mesh = root().join(mesh);
    let case = aster_run::program::prepare(&file, Some(&mesh), &dir).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

fn scene() -> String {
    std::fs::read_to_string(root().join("comm/line_search_bar.comm")).unwrap()
}

/// Five analyses × three instants × (SIXX, DX, V1), each checked against
/// the closed form to 1e-9 (and its own VALE_CALC).
#[test]
fn line_search_bar_matches_the_closed_form() {
    let outcome = run(&scene(), "bar");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (90, 0));
}

fn refused(comm: &str, name: &str, expected: &str) {
    refused_on(comm, name, expected, "comm/hexs8_beam.mail")
}

fn refused_on(comm: &str, name: &str, expected: &str, mesh: &str) {
    let outcome = run_on(comm, name, mesh);
    let err = format!("{:?}", outcome.error.expect("refused"));
    assert!(err.contains(expected), "{err}");
    assert_eq!(outcome.tally.ok, 0, "refused before the run");
}

/// PILOTAGE needs the continuation method.
#[test]
fn pilotage_is_refused() {
    refused(
        &scene().replace(
            r#"METHODE="MIXTE", ITER_LINE_MAXI=5"#,
            r#"METHODE="PILOTAGE""#,
        ),
        "pilotage",
        "RECH_LINEAIRE/METHODE",
    );
}

/// MIXTE with a tangent kept over iterations: code_aster's fields and
/// displacement then belong to different ρ.
#[test]
fn mixte_without_a_tangent_at_every_iteration_is_refused() {
    refused(
        &scene().replace(
            r#"METHODE="MIXTE", ITER_LINE_MAXI=5)"#,
            r#"METHODE="MIXTE"), NEWTON=_F(MATRICE="ELASTIQUE")"#,
        ),
        "mixte",
        "METHODE='MIXTE' with a tangent not reassembled",
    );
}

/// With contact (here a LIAISON_UNIL on the clamped end).
#[test]
fn line_search_with_contact_is_refused() {
    let comm = scene()
        .replace(
            "common = dict(",
            "unil = DEFI_CONTACT(MODELE=model, FORMULATION=\"LIAISON_UNIL\", ZONE=_F(GROUP_NO=\"TIP\", NOM_CMP=\"DY\", COEF_IMPO=1.0, COEF_MULT=-1.0))\n\ncommon = dict(",
        )
        .replace(
            "corde = STAT_NON_LINE(RECH_LINEAIRE=_F(), **common)",
            "corde = STAT_NON_LINE(RECH_LINEAIRE=_F(), CONTACT=unil, **common)",
        );
    refused(&comm, "contact", "RECH_LINEAIRE with CONTACT");
}

/// DYNA_NON_LINE's line search is validated with NEWMARK only.
#[test]
fn line_search_with_hht_is_refused() {
    refused(
        &scene().replace(r#"SCHEMA="NEWMARK""#, r#"SCHEMA="HHT", ALPHA=-0.1"#),
        "hht",
        "SCHEMA='HHT'",
    );
}

/// MECA_NON_LINE with a DEFI_CONT: the line search's trial residuals on
/// the pairing of the iteration's start (frictionless Lagrangian and
/// penalised methods, `tests/lsdefi.rs`); the plastic plate of
/// comm/plastic_plate_defi_cont.comm (2D, VMIS_ISOT_NL) keeps its 30
/// analytic checks with it.
#[test]
fn meca_non_line_line_search_with_defi_cont_matches_the_closed_form() {
    let comm = std::fs::read_to_string(root().join("comm/plastic_plate_defi_cont.comm"))
        .unwrap()
        .replace(
            "resu = MECA_NON_LINE(",
            "resu = MECA_NON_LINE(\n    RECH_LINEAIRE=_F(),",
        );
    let outcome = run_on(&comm, "defi_cont", "comm/plastic_plate.mail");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (30, 0));
}

/// With a DEFI_CONT whose residual on a frozen pairing is not written
/// (friction, VARIANTE='CLASSIQUE', NITSCHE): refused at RECH_LINEAIRE.
#[test]
fn meca_non_line_line_search_with_other_defi_cont_methods_is_refused() {
    let scene = std::fs::read_to_string(root().join("comm/plastic_plate_defi_cont.comm"))
        .unwrap()
        .replace(
            "resu = MECA_NON_LINE(",
            "resu = MECA_NON_LINE(\n    RECH_LINEAIRE=_F(),",
        );
    for (zone, name, expected) in [
        (
            r#"GROUP_MA_MAIT="EF", FROTTEMENT="OUI", TYPE_FROT="COULOMB", COULOMB=0.3"#,
            "friction",
            "RECH_LINEAIRE with a DEFI_CONT with friction",
        ),
        (
            r#"GROUP_MA_MAIT="EF", VARIANTE="CLASSIQUE""#,
            "classique",
            "VARIANTE='CLASSIQUE'",
        ),
        (
            r#"GROUP_MA_MAIT="EF", ALGO_CONT="NITSCHE""#,
            "nitsche",
            "ALGO_CONT='NITSCHE'",
        ),
    ] {
        let comm = scene.replace(r#"GROUP_MA_MAIT="EF""#, zone);
        let outcome = run_on(&comm, name, "comm/plastic_plate.mail");
        let err = format!("{:?}", outcome.error.expect("refused"));
        assert!(err.contains(expected), "{err}");
        assert!(err.contains("MECA_NON_LINE/RECH_LINEAIRE"), "{err}");
        assert_eq!(outcome.tally.ok, 0, "refused before the run");
    }
}
