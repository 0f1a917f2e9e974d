//! `DEFI_MATERIAU/ELAS_FO` (comm/elas_fo_bar.comm): a bar with E(T) and
//! α(T) under a uniform temperature, free and clamped, in MECA_STATIQUE and
//! STAT_NON_LINE, and heated in time through an EVOL_THER, against the
//! closed forms with code_aster's conversion of α to the reference
//! temperature (alfint); then what is refused, located at the keyword.

mod scene;

const MESH: &str = "comm/dyna_bar.mail";

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, MESH, &format!("elasfo-{tag}"))
}

fn text() -> String {
    scene::read("elas_fo_bar.comm")
}

/// `text()` with `from` replaced by `to` (which must be there).
fn edited(from: &str, to: &str) -> String {
    let t = text();
    assert!(t.contains(from), "the scene changed: {from}");
    t.replacen(from, to, 1)
}

#[test]
fn bar_with_temperature_dependent_constants_matches_the_closed_forms() {
    assert_eq!(run(&text(), "scene"), (16, 0, None));
}

/// Without the computed instants as knots of the thermal strain, the
/// strain at t = 0.5 would be the mean of those at 0 and 1 (α' is not
/// constant): a wrong stress, which the scene's check would catch. Here
/// the same check with the mean as reference must fail (NOOK).
#[test]
fn the_strain_between_two_thermal_fields_is_that_of_the_interpolated_temperature() {
    let t = edited(
        "VALE_CALC=-150.0 * eps_th(110.0), VALE_REFE=-150.0 * eps_th(110.0)",
        "VALE_CALC=-150.0 * 0.5 * eps_th(200.0), VALE_REFE=-150.0 * 0.5 * eps_th(200.0)",
    );
    let (ok, nook, err) = run(&t, "mean");
    assert_eq!(err, None);
    assert_eq!((ok, nook), (14, 2));
}

#[test]
fn a_young_modulus_varying_over_a_cell_is_refused_at_the_keyword() {
    // E a function of X: it varies within each cell, where code_aster
    // evaluates it at each Gauss point.
    let t = edited(
        "E_T = DEFI_FONCTION(NOM_PARA=\"TEMP\"",
        "E_T = DEFI_FONCTION(NOM_PARA=\"X\"",
    );
    let (ok, nook, err) = run(&t, "x");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("DEFI_MATERIAU/ELAS_FO/E"), "{err}");
    assert!(err.contains("takes values from"), "{err}");
    assert!(err.contains("case.comm:64:34"), "{err}");
}

/// E(T) with the temperature of the EVOL_THER: E changes between the
/// instants; STAT_NON_LINE evaluates it at each Gauss point and instant
/// (code_aster's nmelas: the stress rescaled by E⁺/E⁻, the same as E⁺ times
/// the elastic strain), so the clamped bar's stress is −E(T) ε_th(T).
#[test]
fn a_young_modulus_varying_in_time_follows_the_temperature() {
    let mut t = edited(
        "    AFFE=_F(GROUP_MA=\"BAR\", MATER=steel_c),\n    AFFE_VARC=_F(NOM_VARC=\"TEMP\", TOUT=\"OUI\", EVOL=history",
        "    AFFE=_F(GROUP_MA=\"BAR\", MATER=steel),\n    AFFE_VARC=_F(NOM_VARC=\"TEMP\", TOUT=\"OUI\", EVOL=history",
    );
    // With the constant E's references the two ramp checks fail…
    let (ok, nook, err) = run(&t, "time-wrong");
    assert_eq!((ok, nook, err), (12, 4, None));
    // …and hold with E(T).
    for temp in ["110.0", "200.0"] {
        let from = format!("-150.0 * eps_th({temp})");
        assert!(t.contains(&from));
        t = t.replace(&from, &format!("-young({temp}) * eps_th({temp})"));
    }
    assert_eq!(run(&t, "time"), (16, 0, None));
}

#[test]
fn a_function_of_the_temperature_without_a_temperature_is_an_error() {
    let t = edited(
        "    AFFE_VARC=_F(NOM_VARC=\"TEMP\", TOUT=\"OUI\", CHAM_GD=hot, VALE_REF=TREF),\n",
        "",
    );
    let (ok, nook, err) = run(&t, "notemp");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("an error");
    assert!(err.contains("is a function of TEMP and cell"), "{err}");
    assert!(err.contains("has no temperature"), "{err}");
}

#[test]
fn a_function_of_a_variable_aster_does_not_supply_is_refused() {
    let t = edited(
        "NU_C = DEFI_CONSTANTE(VALE=0.3)",
        "NU_C = DEFI_FONCTION(NOM_PARA=\"NEUT1\", VALE=(0.0, 0.3, 1.0, 0.3))",
    );
    let (_, nook, err) = run(&t, "neut1");
    assert_eq!(nook, 0);
    let err = err.expect("refused");
    assert!(err.contains("DEFI_MATERIAU/ELAS_FO/NU"), "{err}");
    assert!(err.contains("a function of NEUT1"), "{err}");
}

#[test]
fn alpha_as_a_formula_with_temp_def_alpha_is_an_error_as_in_code_aster() {
    let t = edited(
        "steel = DEFI_MATERIAU(ELAS_FO=_F(E=E_T, NU=NU_C, ALPHA=ALPHA_T,",
        "ALPHA_F = FORMULE(NOM_PARA=\"TEMP\", VALE=\"1.0e-5 + 1.0e-8 * TEMP\")\n\
         steel = DEFI_MATERIAU(ELAS_FO=_F(E=E_T, NU=NU_C, ALPHA=ALPHA_F,",
    );
    let (_, nook, err) = run(&t, "formula");
    assert_eq!(nook, 0);
    let err = err.expect("an error");
    assert!(err.contains("MATERIAL1_1"), "{err}");
}

/// Constant functions (DEFI_CONSTANTE) are ELAS: the same clamped stress
/// with E = 150 given either way.
#[test]
fn constant_functions_are_the_elastic_constants() {
    let t = edited(
        "steel = DEFI_MATERIAU(ELAS_FO=_F(E=E_T,",
        "steel = DEFI_MATERIAU(ELAS_FO=_F(E=E_C,",
    )
    .replace("young(120.0) * eps_th", "150.0 * eps_th");
    assert_eq!(run(&t, "const"), (16, 0, None));
}

/// α(T) on a cell whose temperature varies over it: code_aster takes
/// α(T)(T − T_ref) at the Gauss points, aster's thermal strain is nodal;
/// refused at ALPHA before the solve.
#[test]
fn alpha_of_a_temperature_not_uniform_over_a_cell_is_refused() {
    let t = edited(
        "AFFE=_F(TOUT=\"OUI\", NOM_CMP=\"TEMP\", VALE=120.0)\n)",
        "AFFE=(_F(TOUT=\"OUI\", NOM_CMP=\"TEMP\", VALE=120.0), _F(GROUP_NO=\"TIP\", NOM_CMP=\"TEMP\", VALE=130.0))\n)",
    )
    .replace(
        "steel = DEFI_MATERIAU(ELAS_FO=_F(E=E_T,",
        "steel = DEFI_MATERIAU(ELAS_FO=_F(E=E_C,",
    );
    let (ok, nook, err) = run(&t, "gradient");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("DEFI_MATERIAU/ELAS_FO/ALPHA"), "{err}");
    assert!(err.contains("not uniform"), "{err}");
}

/// POST_ELEM's energies of a result with a thermal strain are refused at
/// the command (code_aster's are those of ε − εth, not ½uᵀKu).
#[test]
fn post_elem_energy_of_a_thermal_result_is_refused() {
    let t = edited(
        "free = MECA_STATIQUE(MODELE=model, CHAM_MATER=mater, EXCIT=_F(CHARGE=free_bc))",
        "free = MECA_STATIQUE(MODELE=model, CHAM_MATER=mater, EXCIT=_F(CHARGE=free_bc))\n\
         epot = POST_ELEM(ENER_POT=_F(TOUT=\"OUI\"), RESULTAT=free)",
    );
    let (_, nook, err) = run(&t, "epot");
    assert_eq!(nook, 0);
    let err = err.expect("a refusal");
    assert!(
        err.contains("not supported yet: POST_ELEM energies of a result with a thermal strain"),
        "{err}"
    );
}
