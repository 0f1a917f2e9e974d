//! Temperature-dependent plasticity (comm/thermoplast_bar.comm): a bar
//! clamped at both ends heated through its yield point with E, ALPHA, SY and
//! D_SIGM_EPSI functions of the temperature (ELAS_FO, ECRO_LINE_FO), whose
//! stress follows the yield curve at the current temperature, and a pulled
//! bar with E(T) and α(T) converted from TEMP_DEF_ALPHA; then what is
//! refused, located.

mod scene;

const MESH: &str = "comm/thermoplast_bar.mail";

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, MESH, &format!("thermoplast-{tag}"))
}

fn edited(from: &str, to: &str) -> String {
    let t = scene::read("thermoplast_bar.comm");
    assert!(t.contains(from), "the scene changed: {from}");
    t.replacen(from, to, 1)
}

#[test]
fn heated_bars_follow_the_temperature_dependent_closed_forms() {
    let t = scene::read("thermoplast_bar.comm");
    assert_eq!(run(&t, "scene"), (34, 0, None));
}

/// The yield stress at T⁻ instead of T⁺ (the previous step's) would put
/// the plastic stress elsewhere: the reference built that way must fail.
#[test]
fn the_yield_stress_is_that_of_the_current_temperature() {
    let t = edited(
        "    p = max(0.0, (e * eth - sy(T)) / (e + h))",
        "    p = max(0.0, (e * eth - sy(T - 50.0)) / (e + h))",
    );
    let (ok, nook, err) = run(&t, "previous");
    assert_eq!(err, None);
    assert!(nook >= 6, "{ok} OK, {nook} NOOK");
}

#[test]
fn a_hardening_function_of_another_variable_is_refused_at_the_keyword() {
    let t = edited(
        "SY_T = DEFI_FONCTION(NOM_PARA=\"TEMP\"",
        "SY_T = DEFI_FONCTION(NOM_PARA=\"X\"",
    );
    let (ok, nook, err) = run(&t, "x");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("DEFI_MATERIAU/ECRO_LINE_FO/SY"), "{err}");
    assert!(err.contains("a function of X"), "{err}");
    assert!(err.contains("case.comm:"), "{err}");
}

#[test]
fn a_heated_law_without_temperature_dependence_here_is_refused() {
    let t = edited(
        "COMPORTEMENT=_F(RELATION=\"VMIS_ISOT_LINE\")",
        "COMPORTEMENT=_F(RELATION=\"VMIS_ISOT_LINE\", DEFORMATION=\"PETIT_REAC\")",
    );
    let (_, _, err) = run(&t, "reac");
    let err = err.expect("refused");
    assert!(err.contains("DEFORMATION='PETIT_REAC'"), "{err}");
    assert!(err.contains("AFFE_VARC"), "{err}");
}
