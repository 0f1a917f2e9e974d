//! The project's creep scene (comm/creep_block.comm on
//! comm/plastic_block.mail): a LEMAITRE (Norton) block relaxing under a
//! held elastic punch through discrete contact. Every TEST_RESU passes:
//! code_aster's θ = 0.5 integration is the trapezoidal rule of the
//! relaxation equation (VALE_CALC to 1e-6), within 2e-3 of the closed-form
//! exponential. LEMAITRE outside small strains is refused before solving.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/plastic_block.mail",
        &format!("creep-block-{tag}"),
    )
}

fn scene() -> String {
    scene::read("creep_block.comm")
}

#[test]
fn a_norton_block_relaxes_as_the_trapezoidal_rule_says() {
    assert_eq!(run(&scene(), "theta05"), (12, 0, None));
}

#[test]
fn the_implicit_scheme_is_not_the_trapezoidal_rule() {
    // θ = 1 (backward Euler) relaxes by (1 + R DT)⁻¹ per step: the
    // VALE_CALC of the trapezoidal rule no longer hold, the analytic
    // references (2e-3) do not either at R DT ≈ 0.1.
    let text = scene().replace("PARM_THETA=0.5", "PARM_THETA=1.0");
    let (ok, nook, err) = run(&text, "theta1");
    assert_eq!(err, None);
    assert!(nook >= 4, "{ok} OK, {nook} NOOK");
}

#[test]
fn lemaitre_outside_small_strains_is_refused_with_its_location() {
    let text = scene().replace(
        "_F(RELATION=\"LEMAITRE\", PARM_THETA=0.5, GROUP_MA=\"BLOC\")",
        "_F(RELATION=\"LEMAITRE\", PARM_THETA=0.5, DEFORMATION=\"GDEF_LOG\", GROUP_MA=\"BLOC\")",
    );
    let (ok, nook, err) = run(&text, "gdef");
    let err = err.expect("a refusal");
    assert_eq!((ok, nook), (0, 0));
    assert!(
        err.contains("DEFORMATION='GDEF_LOG' with RELATION='LEMAITRE'"),
        "{err}"
    );
}
