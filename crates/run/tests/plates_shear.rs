//! The project's scene of the shear-deformable plates (comm/thick_strips.comm
//! on comm/thick_strips.mail): five thick cantilever strips (L/h = 5) under
//! a tip force against Timoshenko's beam — DSQ exact (deflection with the
//! shear term P·L/(κGA), rotation, QX, MXX, GAX, SIXX and the parabolic
//! SIXZ of POST_CHAMP/EXTR_COQUE, 1e-9), DST triangles, Q4G quadrangles
//! and triangles within 0.5 %, and a DKT strip at Kirchhoff's P·L³/(3EI)
//! exactly (no shear deflection); then what is refused with these plates.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/thick_strips.mail",
        &format!("plates-shear-{tag}"),
    )
}

fn strips() -> String {
    scene::read("thick_strips.comm")
}

#[test]
fn thick_strips_match_timoshenko_and_dkt_matches_kirchhoff() {
    assert_eq!(run(&strips(), "strips"), (30, 0, None));
}

/// The DKT plates have no transverse shear stresses here: with the DKT on
/// S1, the TEST_RESU on its SIXZ is refused, naming the component (the
/// deflection the DKT misses is measured in aster-fem's tests/plates_shear.rs).
#[test]
fn dkt_in_place_of_dst_has_no_sixz() {
    let t = strips().replacen(
        "_F(GROUP_MA=(\"S1\", \"S2\"), PHENOMENE=\"MECANIQUE\", MODELISATION=\"DST\")",
        "_F(GROUP_MA=\"S2\", PHENOMENE=\"MECANIQUE\", MODELISATION=\"DST\"),\n        _F(GROUP_MA=\"S1\", PHENOMENE=\"MECANIQUE\", MODELISATION=\"DKT\")",
        1,
    );
    assert!(t.contains("MODELISATION=\"DKT\")"), "the edit applies");
    let (_, _, err) = run(&t, "dkt-s1");
    let err = err.expect("refused");
    assert!(err.contains("no component SIXZ"), "{err}");
}

/// code_aster's DST and Q4G elements have no RAPH_MECA/FULL_MECA: a
/// STAT_NON_LINE on them is refused, located.
#[test]
fn stat_non_line_on_dst_is_refused() {
    let t = strips().replacen(
        "RESU = MECA_STATIQUE(\n    MODELE=MO,",
        "LINST = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))\n\nRESU = STAT_NON_LINE(\n    INCREMENT=_F(LIST_INST=LINST),\n    MODELE=MO,",
        1,
    );
    assert!(t.contains("STAT_NON_LINE("), "the edit applies");
    let (_, _, err) = run(&t, "snl");
    let err = err.expect("refused");
    assert!(
        err.contains("STAT_NON_LINE") && err.contains("'DST'") && err.contains("RAPH_MECA"),
        "{err}"
    );
}

/// An offset (EXCENTREMENT) is refused at its keyword, as for the DKT.
#[test]
fn an_offset_is_refused() {
    let t = strips().replacen("EPAIS=0.2)", "EPAIS=0.2, EXCENTREMENT=0.01)", 1);
    assert!(t.contains("EXCENTREMENT"), "the edit applies");
    let (_, _, err) = run(&t, "excentrement");
    let err = err.expect("refused");
    assert!(err.contains("EXCENTREMENT"), "{err}");
}

/// MACRO_ELAS_MULT is linear like MECA_STATIQUE: the strips computed as
/// one load case of a mult_elas give the same 30 checks.
#[test]
fn macro_elas_mult_runs_the_shear_plates_as_meca_statique() {
    let t = strips().replacen(
        "RESU = MECA_STATIQUE(\n    MODELE=MO,\n    CHAM_MATER=MAT,\n    CARA_ELEM=CARA,\n    EXCIT=(_F(CHARGE=CLAMP), _F(CHARGE=TIP)),\n)",
        "RESU = MACRO_ELAS_MULT(\n    MODELE=MO,\n    CHAM_MATER=MAT,\n    CARA_ELEM=CARA,\n    CHAR_MECA_GLOBAL=CLAMP,\n    CAS_CHARGE=_F(NOM_CAS=\"TIP\", CHAR_MECA=TIP),\n)",
        1,
    );
    assert!(t.contains("MACRO_ELAS_MULT("), "the edit applies");
    assert_eq!(run(&t, "mult"), (30, 0, None));
}
