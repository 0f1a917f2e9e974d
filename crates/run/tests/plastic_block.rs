//! The project's plastic-block scene (comm/plastic_block.comm on
//! comm/plastic_block.mail): a VMIS_ISOT_LINE block pressed by an elastic
//! punch through discrete contact; every TEST_RESU (stresses, VARI_ELGA,
//! VARI_NOEU, SIEF_NOEU, DEPL, REAC_NODA against the analytic uniaxial
//! solution) must pass — also with the same hardening given as a traction
//! curve (VMIS_ISOT_TRAC). Unsupported behaviours fail with clear messages.

mod scene;

use scene::root;
use std::path::Path;

/// Runs the scene's text (possibly edited) and returns (OK, NOOK, error).
fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/plastic_block.mail",
        &format!("plastic-block-{tag}"),
    )
}

fn scene() -> String {
    scene::read("plastic_block.comm")
}

fn edited(from: &str, to: &str) -> String {
    let text = scene();
    assert!(text.contains(from), "the scene no longer has `{from}`");
    text.replace(from, to)
}

#[test]
fn plastic_block_under_a_punch_passes_every_check() {
    let path = root().join("comm/plastic_block.comm");
    assert!(Path::new(&path).exists());
    assert_eq!(run(&scene(), "line"), (24, 0, None));
}

#[test]
fn the_same_hardening_as_a_traction_curve_gives_the_same_answers() {
    // σ(ε) through the elastic limit (SY/E, SY) with slope ET after it,
    // prolonged linearly: VMIS_ISOT_TRAC then equals VMIS_ISOT_LINE.
    let text = edited(
        "block_mat = DEFI_MATERIAU(ELAS=_F(E=E, NU=NU), ECRO_LINE=_F(D_SIGM_EPSI=ET, SY=SY))",
        "curve = DEFI_FONCTION(NOM_PARA=\"EPSI\", PROL_DROITE=\"LINEAIRE\",\n    \
         VALE=(SY / E, SY, 0.05, SY + ET * (0.05 - SY / E)))\n\
         block_mat = DEFI_MATERIAU(ELAS=_F(E=E, NU=NU), TRACTION=_F(SIGM=curve))",
    )
    .replace("RELATION=\"VMIS_ISOT_LINE\"", "RELATION=\"VMIS_ISOT_TRAC\"");
    assert_eq!(run(&text, "trac"), (24, 0, None));
}

#[test]
fn a_plastic_relation_without_its_material_data_is_a_clear_error() {
    let text = edited(
        "block_mat = DEFI_MATERIAU(ELAS=_F(E=E, NU=NU), ECRO_LINE=_F(D_SIGM_EPSI=ET, SY=SY))",
        "block_mat = DEFI_MATERIAU(ELAS=_F(E=E, NU=NU))",
    );
    let (_, _, err) = run(&text, "noecro");
    let err = err.expect("an error");
    assert!(
        err.contains("RELATION='VMIS_ISOT_LINE'") && err.contains("needs ECRO_LINE"),
        "{err}"
    );
}

#[test]
fn kinematics_a_relation_cannot_take_are_refused_with_the_reason() {
    let text = edited(
        "_F(RELATION=\"ELAS\", GROUP_MA=\"PUNCH\")",
        "_F(RELATION=\"ELAS\", DEFORMATION=\"SIMO_MIEHE\", GROUP_MA=\"PUNCH\")",
    );
    let (_, _, err) = run(&text, "simo");
    let err = err.expect("an error");
    assert!(
        err.contains("DEFORMATION='SIMO_MIEHE' with RELATION='ELAS'"),
        "{err}"
    );
    let text = edited(
        "_F(RELATION=\"VMIS_ISOT_LINE\", GROUP_MA=\"BLOC\")",
        "_F(RELATION=\"VMIS_ISOT_LINE\", DEFORMATION=\"GROT_GDEP\", GROUP_MA=\"BLOC\")",
    );
    let (_, _, err) = run(&text, "grot");
    let err = err.expect("an error");
    assert!(
        err.contains("DEFORMATION='GROT_GDEP' with RELATION='VMIS_ISOT_LINE'"),
        "{err}"
    );
}

#[test]
fn an_unknown_relation_lists_the_supported_ones() {
    let text = edited("RELATION=\"VMIS_ISOT_LINE\"", "RELATION=\"VMIS_ECMI_LINE\"");
    let (_, _, err) = run(&text, "cine");
    let err = err.expect("an error");
    assert!(
        err.contains("RELATION='VMIS_ECMI_LINE'")
            && err.contains("ELAS, VMIS_ISOT_LINE, VMIS_ISOT_TRAC"),
        "{err}"
    );
}
