//! Non-linear and time-dependent heat conduction (comm/heat_nonlinear.comm):
//! THER_NON_LINE with λ(T) against the Kirchhoff transform's exact profile
//! and its fluxes (CALC_CHAMP/THERMIQUE), a flux ramped in time through a
//! slab by THER_NON_LINE and THER_LINEAIRE against the exact solution
//! (linear in time, so the θ-weighted loads are tested tightly); then what
//! is refused and the errors a user meets.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/heat_strip.mail", &format!("heatnl-{tag}"))
}

fn text() -> String {
    scene::read("heat_nonlinear.comm")
}

#[test]
fn kirchhoff_profile_and_ramped_flux_match_their_closed_forms() {
    assert_eq!(run(&text(), "scene"), (22, 0, None));
}

#[test]
fn the_line_search_of_the_legacy_newton_keyword_is_refused_at_it() {
    let t = text().replace(
        "NEWTON=_F(REAC_ITER=1),",
        "NEWTON=_F(REAC_ITER=1, ITER_LINE_MAXI=2),",
    );
    assert!(t.contains("ITER_LINE_MAXI=2"));
    let (ok, nook, err) = run(&t, "line");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("a refusal");
    assert!(
        err.contains("not supported yet: THER_NON_LINE/RECH_LINEAIRE"),
        "{err}"
    );
}

#[test]
fn a_linear_material_in_ther_non_line_is_an_error_naming_the_cell() {
    let t = text().replace(
        "CHAM_MATER=mat_nl, EXCIT=_F(CHARGE=ramp),\n    ETAT_INIT=_F(CHAM_NO=t0), INCREMENT=_F(LIST_INST=times),\n)\nramp_lin",
        "CHAM_MATER=mat_lin, EXCIT=_F(CHARGE=ramp),\n    ETAT_INIT=_F(CHAM_NO=t0), INCREMENT=_F(LIST_INST=times),\n)\nramp_lin",
    );
    assert!(t.contains("CHAM_MATER=mat_lin, EXCIT=_F(CHARGE=ramp),\n    ETAT_INIT"));
    let (_, nook, err) = run(&t, "linmat");
    assert_eq!(nook, 0);
    let err = err.expect("an error");
    assert!(
        err.contains("has no THER_NL (LAMBDA, BETA or RHO_CP)"),
        "{err}"
    );
}

#[test]
fn a_temperature_outside_an_excluded_conductivity_is_an_error_not_a_number() {
    // λ(T) tabulated on [0, 50] only (PROL EXCLU): the steady profile
    // reaches 100.
    let t = text().replace(
        "NOM_PARA=\"TEMP\", VALE=(0.0, L0, 100.0, L0 * (1.0 + B * 100.0)),\n    PROL_GAUCHE=\"LINEAIRE\", PROL_DROITE=\"LINEAIRE\",",
        "NOM_PARA=\"TEMP\", VALE=(0.0, L0, 50.0, L0 * (1.0 + B * 50.0)),",
    );
    assert!(t.contains("VALE=(0.0, L0, 50.0"));
    let (ok, nook, err) = run(&t, "exclu");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("an error");
    assert!(
        err.contains("beyond the last abscissa 50 of a material function prolonged EXCLU"),
        "{err}"
    );
}

#[test]
fn too_few_newton_iterations_is_a_located_failure() {
    // λ(T) strongly non-linear and one iteration allowed.
    let t = text().replace(
        "NEWTON=_F(REAC_ITER=1),",
        "NEWTON=_F(REAC_ITER=1), CONVERGENCE=_F(ITER_GLOB_MAXI=1, RESI_GLOB_RELA=1e-12),",
    );
    let (ok, nook, err) = run(&t, "iter");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("an error");
    assert!(err.contains("Newton did not converge"), "{err}");
}
