//! The project's COQUE_3D scene (comm/coque3d_strip.comm on
//! comm/coque3d_strip.mail): a cantilever strip of eight QUAD9 cells of
//! code_aster's `MEC3QU9H` run through the runner — an end moment and an
//! end tension against beam theory (ν = 0: tip deflection and rotation,
//! stretch, mid-span deflection within 1e-9; the bottom and top stresses of
//! POST_CHAMP/EXTR_COQUE averaged by SIGM_NOEU within 1e-7), and a
//! PRES_REP whose clamp reaction equals p·L·b within 1e-9; the efforts
//! EFGE_ELGA, EFGE_ELNO, EFGE_NOEU under the end moment and tension (NXX =
//! N/b, MXX = M/b) and an end shear force (QX = V/b, MXX = −V(L − x)/b)
//! within 1e-9, by STAT_NON_LINE (code_aster's `ef0415`) and by
//! MECA_STATIQUE (`ef0410`, EFGE_ELNO from the reduced points); the same
//! strip of TRIA7 cells (`MEC3TR7H`,
//! comm/coque3d_strip_tria7.comm).

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/coque3d_strip.mail", &format!("coque3d-{tag}"))
}

fn strip() -> String {
    scene::read("coque3d_strip.comm")
}

#[test]
fn coque3d_strip_matches_beam_theory_and_statics() {
    assert_eq!(run(&strip(), "strip"), (62, 0, None));
}

/// The same strip meshed with TRIA7 (comm/coque3d_strip_tria7.comm on
/// comm/coque3d_strip_tria7.mail, code_aster's `MEC3TR7H`): the end
/// moment and tension are in the triangle's space too (tip DZ, DRY, DX,
/// mid-span DZ within 1e-9; measured ≤ 1.5e-10), the layer stresses
/// averaged at the nodes within 1e-7 (measured 1.3e-11), the clamp's
/// reaction to the pressure p·L·b within 1e-9.
#[test]
fn coque3d_tria7_strip_matches_beam_theory_and_statics() {
    let text = scene::read("coque3d_strip_tria7.comm");
    let got = scene::run_on(&text, "comm/coque3d_strip_tria7.mail", "coque3d-tria7");
    assert_eq!(got, (60, 0, None));
}

/// Two layers (COQUE_NCOU=2): the bottom of the second layer is the
/// mid-surface, where only the tension acts (N/(b·h) = 4e7); the
/// displacements are unchanged (Simpson's rule per layer is exact through
/// a flat strip's thickness).
#[test]
fn the_bottom_of_the_second_of_two_layers_is_the_mid_surface() {
    let t = strip()
        .replacen("EPAIS=0.05)", "EPAIS=0.05, COQUE_NCOU=2)", 1)
        .replacen(
            "NUME_COUCHE=1, NIVE_COUCHE=\"INF\"",
            "NUME_COUCHE=2, NIVE_COUCHE=\"INF\"",
            1,
        )
        .replacen(
            "VALE_CALC=3.52e7, VALE_REFE=3.52e7",
            "VALE_CALC=4.0e7, VALE_REFE=4.0e7",
            1,
        );
    // The top of the second layer is the strip's top, as before.
    let t = t.replacen(
        "NUME_COUCHE=1, NIVE_COUCHE=\"SUP\"",
        "NUME_COUCHE=2, NIVE_COUCHE=\"SUP\"",
        1,
    );
    assert!(t.contains("COQUE_NCOU=2") && t.contains("VALE_CALC=4.0e7"));
    // The efforts (EFGE_*) integrate the two layers to the same N and M.
    assert_eq!(run(&t, "layers"), (62, 0, None));
    // A third layer does not exist.
    let t = t.replacen(
        "NUME_COUCHE=2, NIVE_COUCHE=\"INF\"",
        "NUME_COUCHE=3, NIVE_COUCHE=\"INF\"",
        1,
    );
    let (_, _, err) = run(&t, "layer3");
    let err = err.expect("an error");
    assert!(
        err.contains("layer 3") && err.contains("COQUE_NCOU"),
        "{err}"
    );
}

/// Continuous contact on a model with COQUE_3D cells is code_aster's
/// error CONTACT_94 (the centres of QUAD9 shells): an error, not a run.
#[test]
fn continuous_contact_with_coque3d_is_code_asters_error() {
    let t = strip()
        .replacen(
            "LINST = DEFI_LIST_REEL(",
            "MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_MA=(\
             _F(NOM=\"C1\", MAILLE=\"M1\"), _F(NOM=\"C8\", MAILLE=\"M8\")))\n\
             CONT = DEFI_CONTACT(MODELE=MO, FORMULATION=\"CONTINUE\", \
             ZONE=_F(GROUP_MA_MAIT=\"C1\", GROUP_MA_ESCL=\"C8\"))\n\nLINST = DEFI_LIST_REEL(",
            1,
        )
        .replacen(
            "EXCIT=(_F(CHARGE=CLAMP), _F(CHARGE=TIP)),",
            "EXCIT=(_F(CHARGE=CLAMP), _F(CHARGE=TIP)),\n    CONTACT=CONT,",
            1,
        );
    assert!(t.contains("CONTACT=CONT"));
    let (ok, nook, err) = run(&t, "continue");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("an error");
    assert!(err.contains("CONTACT_94"), "{err}");
}

/// A strip of COQUE_3D launched in its first beam mode under DYNA_NON_LINE
/// (comm/coque3d_vibration.comm, code_aster's `te0406` mass): the tip
/// against the Timoshenko-corrected frequency, the energy conserved.
#[test]
fn coque3d_strip_vibrates_at_its_beam_frequency() {
    let text = scene::read("coque3d_vibration.comm");
    assert_eq!(run(&text, "dyna"), (24, 0, None));
}
