//! `RELATION='VMIS_ISOT_NL'` with `DEFI_MATERIAU/ECRO_NL` on the project's
//! scene `comm/ecro_nl_bar.comm`: a bar pulled into the plastic range
//! against the uniaxial closed form (a scalar equation solved by bisection
//! in the command file), and the law's kinematics refused as code_aster
//! refuses them.

mod scene;

/// (TEST_RESU OK, NOOK, the error that stopped the run) on the bar mesh.
fn run(comm: &str, name: &str) -> (usize, usize, Option<String>) {
    scene::run_on(comm, "comm/hexs8_beam.mail", name)
}

fn scene() -> String {
    scene::read("ecro_nl_bar.comm")
}

/// σ, p, the plasticity indicator and the plastic strains (V3 = p,
/// V4 = −p/2) against the closed form to 1e-8.
#[test]
fn vmis_isot_nl_bar_matches_the_uniaxial_closed_form() {
    let outcome = run(&scene(), "bar");
    assert!(outcome.2.is_none(), "{:?}", outcome.2);
    assert_eq!((outcome.0, outcome.1), (10, 0));
}

/// code_aster's VMIS_ISOT_NL takes PETIT and GDEF_LOG only.
#[test]
fn vmis_isot_nl_refuses_other_kinematics() {
    let comm = scene().replace(
        "RELATION=\"VMIS_ISOT_NL\", TOUT=\"OUI\"",
        "RELATION=\"VMIS_ISOT_NL\", DEFORMATION=\"PETIT_REAC\", TOUT=\"OUI\"",
    );
    let outcome = run(&comm, "reac");
    let err = format!("{:?}", outcome.2.expect("PETIT_REAC refused"));
    assert!(
        err.contains("DEFORMATION='PETIT_REAC' with RELATION='VMIS_ISOT_NL'"),
        "{err}"
    );
}
