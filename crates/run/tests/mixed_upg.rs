//! The project's scene of the mixed incompressible elements
//! (comm/incompressible_cylinder.comm on comm/incompressible_cylinder.mail):
//! a thick cylinder with ν = 0.4999 under internal pressure in
//! AXIS_INCO_UPG, STAT_NON_LINE and MECA_STATIQUE against Lamé's solution
//! (u_r at three radii, the mean stress PRES, 1e-6); then what is refused
//! on these elements, located.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/incompressible_cylinder.mail",
        &format!("mixed-upg-{tag}"),
    )
}

fn cylinder() -> String {
    scene::read("incompressible_cylinder.comm")
}

#[test]
fn thick_cylinder_matches_lame() {
    assert_eq!(run(&cylinder(), "cylinder"), (16, 0, None));
}

/// code_aster's FORC_NODA of these elements (te0591) has pressure and
/// swelling rows: not reproduced, refused rather than computed as a
/// displacement element's.
#[test]
fn forc_noda_is_refused() {
    let t = cylinder().replacen(
        "LIN = MECA_STATIQUE(",
        "SNL = CALC_CHAMP(reuse=SNL, RESULTAT=SNL, FORCE=\"FORC_NODA\")\n\nLIN = MECA_STATIQUE(",
        1,
    );
    assert!(t.contains("FORC_NODA"), "the edit applies");
    let (_, _, err) = run(&t, "forc-noda");
    let err = err.expect("refused");
    assert!(
        err.contains("FORC_NODA") && err.contains("_INCO_UPG"),
        "{err}"
    );
}

/// Large strains on the mixed elements (nifilg, nifism) are refused.
#[test]
fn large_strains_are_refused() {
    let t = cylinder().replacen(
        "COMPORTEMENT=_F(RELATION=\"ELAS\")",
        "COMPORTEMENT=_F(RELATION=\"ELAS\", DEFORMATION=\"GDEF_LOG\")",
        1,
    );
    assert!(t.contains("GDEF_LOG"), "the edit applies");
    let (_, _, err) = run(&t, "gdef-log");
    let err = err.expect("refused");
    assert!(err.contains("_INCO_UPG"), "{err}");
}
