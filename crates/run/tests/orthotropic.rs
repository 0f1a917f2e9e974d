//! The project's orthotropic scenes: `comm/ortho_cube.comm` (3D, on
//! `comm/ortho_cube.mail`) and `comm/ortho_square.comm` (D_PLAN and
//! C_PLAN, on `comm/ortho_square.mail`): a block under a uniform uniaxial
//! stress off the material axes (ELAS_ORTH turned by AFFE_CARA_ELEM/MASSIF,
//! ANGL_REP and ANGL_EULER), displacements and stresses against the turned
//! compliance to 1e-10; and what is refused with an orthotropic material.

mod scene;

fn cube(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/ortho_cube.mail", &format!("ortho-cube-{tag}"))
}

fn square(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/ortho_square.mail",
        &format!("ortho-square-{tag}"),
    )
}

#[test]
fn the_3d_block_follows_the_turned_compliance() {
    assert_eq!(cube(&scene::read("ortho_cube.comm"), "all"), (100, 0, None));
}

#[test]
fn the_plane_blocks_follow_the_turned_compliance() {
    assert_eq!(
        square(&scene::read("ortho_square.comm"), "all"),
        (50, 0, None)
    );
}

#[test]
fn another_frame_moves_the_displacements() {
    // γ of the opposite sign in the code only: the reference keeps +10°.
    let text = scene::read("ortho_cube.comm").replace(
        "ANGL_REP=(30.0, 20.0, 10.0)))",
        "ANGL_REP=(30.0, 20.0, -10.0)))",
    );
    let (ok, nook, err) = cube(&text, "gamma");
    assert_eq!(err, None);
    assert!(nook >= 10, "{ok} OK, {nook} NOOK");
    // In 2D only the first angle counts (code_aster's rcangm): β and γ
    // given to the D_PLAN frame change nothing.
    let text = scene::read("ortho_square.comm")
        .replace("ANGL_REP=30.0))", "ANGL_REP=(30.0, 50.0, 20.0)))");
    assert_eq!(square(&text, "beta"), (50, 0, None));
}

#[test]
fn large_strains_on_an_orthotropic_material_are_refused() {
    let text = scene::read("ortho_cube.comm").replace(
        "COMPORTEMENT=_F(RELATION=\"ELAS\", TOUT=\"OUI\")",
        "COMPORTEMENT=_F(RELATION=\"ELAS\", DEFORMATION=\"GDEF_LOG\", TOUT=\"OUI\")",
    );
    let (ok, nook, err) = cube(&text, "gdef");
    let err = err.expect("a refusal");
    assert_eq!(nook, 0, "{ok} OK");
    assert!(
        err.contains("not supported yet")
            && err.contains("DEFORMATION='GDEF_LOG'")
            && err.contains("orthotropic (ELAS_ORTH)"),
        "{err}"
    );
}

#[test]
fn a_plastic_law_beside_elas_orth_is_refused() {
    let text = scene::read("ortho_cube.comm").replace(
        "NU_TN=NUTN\n    )\n)",
        "NU_TN=NUTN\n    ),\n    ECRO_LINE=_F(SY=1.0e8, D_SIGM_EPSI=1.0e9),\n)",
    );
    let (_, _, err) = cube(&text, "ecro");
    let err = err.expect("a refusal");
    assert!(
        err.contains("not supported yet: DEFI_MATERIAU/ECRO_LINE with ELAS_ORTH"),
        "{err}"
    );
}

#[test]
fn euler_angles_are_three() {
    let text = scene::read("ortho_cube.comm")
        .replace("ANGL_EULER=(40.0, 25.0, -15.0)", "ANGL_EULER=(40.0, 25.0)");
    let (_, _, err) = cube(&text, "euler2");
    let err = err.expect("an error");
    assert!(err.contains("ANGL_EULER needs the three angles"), "{err}");
}

#[test]
fn a_missing_modulus_is_named() {
    let text = scene::read("ortho_cube.comm").replace("E_N=EN, ", "");
    let (_, _, err) = cube(&text, "en");
    let err = err.expect("an error");
    assert!(err.contains("E_N must be positive and finite"), "{err}");
}
