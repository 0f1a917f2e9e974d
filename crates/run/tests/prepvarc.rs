//! Plates heated through their thickness (comm/prepvarc_plates.comm):
//! `CREA_RESU(OPERATION='PREP_VARC')` and the DKT, DST plates it heats —
//! a free plate curving with κ = α ΔT/h without stress, a clamped one
//! carrying M = E α ΔT h²/(12(1−ν)), a restrained one N = E α ΔT h/(1−ν),
//! and STAT_NON_LINE following the temperature in time; then references
//! that must fail and what is refused, located.

mod scene;

const MESH: &str = "comm/prepvarc_plates.mail";

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, MESH, &format!("prepvarc-{tag}"))
}

fn edited(from: &str, to: &str) -> String {
    let t = scene::read("prepvarc_plates.comm");
    assert!(t.contains(from), "the scene changed: {from}");
    t.replacen(from, to, 1)
}

#[test]
fn heated_plates_meet_the_closed_forms() {
    let t = scene::read("prepvarc_plates.comm");
    assert_eq!(run(&t, "scene"), (64, 0, None));
}

/// The curvature of a free plate is α ΔT/h: a reference with the
/// gradient over the half thickness (2 α ΔT/h) must fail.
#[test]
fn a_wrong_curvature_is_not_ok() {
    let t = edited(
        "VALE_CALC=-0.1, VALE_REFE=-0.1, REFERENCE=\"ANALYTIQUE\", PRECISION=1.0e-9),\n        _F(RESULTAT=RESU, NUME_ORDRE=1, NOM_CHAM=\"DEPL\", GROUP_NO=\"A20\"",
        "VALE_CALC=-0.2, VALE_REFE=-0.2, REFERENCE=\"ANALYTIQUE\", PRECISION=1.0e-9),\n        _F(RESULTAT=RESU, NUME_ORDRE=1, NOM_CHAM=\"DEPL\", GROUP_NO=\"A20\"",
    );
    let (ok, nook, err) = run(&t, "curvature");
    assert_eq!(err, None);
    assert_eq!((ok, nook), (62, 2));
}

/// The clamped plate's stress at its faces keeps the thermal part off:
/// the mechanical stress alone (E/(1−ν²)·z·κ = 0 here) must fail.
#[test]
fn the_face_stress_has_its_thermal_part_removed() {
    let t = edited(
        "NOM_CMP=\"SIXX\", VALE_CALC=1.4285714285714285e8, VALE_REFE=1.4285714285714285e8,",
        "NOM_CMP=\"SIXX\", VALE_CALC=0.0, VALE_REFE=0.0, ORDRE_GRANDEUR=1.0,",
    );
    let (_, nook, err) = run(&t, "face");
    assert_eq!(err, None);
    assert_eq!(nook, 2);
}

#[test]
fn a_plate_given_a_plain_temperature_is_refused_at_affe_varc() {
    // A plate given the nodal TEMP of the EVOL itself, not through PREP_VARC.
    let t = edited(
        "AFFE_VARC=_F(TOUT=\"OUI\", NOM_VARC=\"TEMP\", EVOL=TEMPER, VALE_REF=20.0)",
        "AFFE_VARC=_F(TOUT=\"OUI\", NOM_VARC=\"TEMP\", EVOL=EVOLT, VALE_REF=20.0)",
    )
    .replacen(
        "TEMPER = CREA_RESU(",
        "TPLAIN = CREA_CHAMP(OPERATION=\"AFFE\", TYPE_CHAM=\"NOEU_TEMP_R\", MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", NOM_CMP=\"TEMP\", VALE=50.0))\nEVOLT = CREA_RESU(OPERATION=\"AFFE\", TYPE_RESU=\"EVOL_THER\", AFFE=_F(NOM_CHAM=\"TEMP\", CHAM_GD=TPLAIN, INST=0.0))\nTEMPER = CREA_RESU(",
        1,
    );
    let (ok, nook, err) = run(&t, "plain");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("PREP_VARC"), "{err}");
    assert!(err.contains("AFFE_VARC"), "{err}");
    assert!(err.contains("case.comm:"), "{err}");
}

#[test]
fn functions_of_the_temperature_on_heated_plates_are_refused_at_elas_fo() {
    let t = edited(
        "ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, ALPHA=1.0e-5))",
        "EFT = DEFI_FONCTION(NOM_PARA=\"TEMP\", VALE=(0.0, 2.0e11, 200.0, 1.8e11))\nACIER = DEFI_MATERIAU(ELAS_FO=_F(E=EFT, NU=DEFI_CONSTANTE(VALE=0.3), ALPHA=DEFI_CONSTANTE(VALE=1.0e-5), TEMP_DEF_ALPHA=20.0))",
    );
    let (ok, nook, err) = run(&t, "elasfo");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("ELAS_FO/E"), "{err}");
    assert!(err.contains("sub-point"), "{err}");
}

#[test]
fn prep_varc_needs_temp_mil_at_the_shell_nodes() {
    let t = edited(
        "_F(GROUP_MA=\"PC\", NOM_CMP=\"TEMP_MIL\", VALE=120.0)",
        "_F(GROUP_MA=\"PC\", NOM_CMP=\"TEMP_SUP\", VALE=120.0)",
    );
    let (_, _, err) = run(&t, "mil");
    let err = err.expect("an error");
    assert!(err.contains("TEMP_MIL"), "{err}");
    assert!(err.contains("ELEMENTS_53"), "{err}");
}
