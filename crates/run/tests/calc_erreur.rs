//! CALC_ERREUR on the project's scene `comm/calc_erreur_patch.comm` (a
//! plane-strain square in uniform tension, the exact solution in the
//! finite-element space): the residual estimator vanishes and SIGCAL,
//! TAILLE take their closed forms.

mod scene;

fn run(comm: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(comm, "comm/calc_erreur_patch.mail", tag)
}

fn scene() -> String {
    scene::read("calc_erreur_patch.comm")
}

/// Every check of the scene passes: ERREST, NUEST, TERMNO, TERMSA zero to
/// 1e-9, SIGCAL = ½ S √(1 + ν²) and TAILLE = √2/2 to round-off.
#[test]
fn the_patch_has_no_error() {
    let outcome = run(&scene(), "patch");
    assert!(outcome.2.is_none(), "{:?}", outcome.2);
    assert_eq!((outcome.0, outcome.1), (12, 0));
}

/// Without the traction on x = 1 the bar is unloaded (σ = 0 everywhere
/// while the skin cells carry no load): the same SIGCAL checks fail, so
/// the scene's checks can fail.
#[test]
fn a_wrong_reference_is_a_nook() {
    let comm = scene().replace(
        "VALE_REFE=0.5 * S * (1.0 + NU * NU) ** 0.5",
        "VALE_REFE=0.5 * S * (1.0 + NU * NU) ** 0.5 * 1.01",
    );
    let outcome = run(&comm, "wrong");
    assert!(outcome.2.is_none(), "{:?}", outcome.2);
    assert_eq!((outcome.0, outcome.1), (11, 1));
}

/// A traction that is not σ·n on the loaded edge (the load doubled after
/// the solve is not possible; a pressure added on the same edge is): the
/// boundary term of the cells along x = 1 is then positive — the zero
/// checks of TERMNO and ERREST of M2 fail.
#[test]
fn an_unbalanced_traction_is_a_boundary_residual() {
    let comm = scene().replace(
        "FORCE_CONTOUR=_F(GROUP_MA=\"RIGHT\", FX=S),",
        "FORCE_CONTOUR=_F(GROUP_MA=\"RIGHT\", FX=S),\n)\nextra = AFFE_CHAR_MECA(\n    MODELE=model,\n    FORCE_INTERNE=_F(GROUP_MA=\"SURF\", FY=-1.0),",
    )
    .replace(
        "EXCIT=_F(CHARGE=loads)",
        "EXCIT=(_F(CHARGE=loads), _F(CHARGE=extra))",
    );
    let outcome = run(&comm, "weight");
    assert!(outcome.2.is_none(), "{:?}", outcome.2);
    // SIGCAL changes too (σyy no longer 0), TAILLE does not.
    assert!(outcome.1 >= 3, "{outcome:?}");
}

/// The thermal estimator is refused at its value, before anything runs.
#[test]
fn the_thermal_estimator_is_refused() {
    let comm = scene().replace(
        "OPTION=(\"ERME_ELEM\", \"ERME_ELNO\")",
        "OPTION=(\"ERME_ELEM\", \"ERTH_ELEM\")",
    );
    let outcome = run(&comm, "erth");
    let err = outcome.2.expect("refused");
    assert!(err.contains("CALC_ERREUR/OPTION='ERTH_ELEM'"), "{err}");
    assert_eq!(outcome.0 + outcome.1, 0);
}
