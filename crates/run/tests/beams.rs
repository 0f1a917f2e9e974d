//! The project's beam and rotational-discrete scene
//! (comm/beams_discrete.comm on comm/beams_discrete.mail): POU_D_E
//! cantilevers along X and along Z (the default local frame) under tip
//! forces and a torque, against the closed-form Euler–Bernoulli deflections
//! and rotations and the statics of EFGE_ELNO; DIS_TR points (K_TR_D_N) and
//! segments (K_TR_D_L) under forces and moments against F/k — all within
//! 1e-9. What they cannot run is refused at its keyword.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/beams_discrete.mail", &format!("beams-{tag}"))
}

fn text() -> String {
    scene::read("beams_discrete.comm")
}

#[test]
fn cantilevers_and_discrete_rotations_match_closed_forms() {
    assert_eq!(run(&text(), "scene"), (62, 0, None));
}

/// A circle of the same bending stiffness about y as the rectangle about y
/// is not needed: SECTION='GENERALE' with the rectangle's own A, IY, IZ, JX
/// gives the same answers.
#[test]
fn generale_section_with_the_same_characteristics_is_the_same_beam() {
    let t = text().replace(
        "SECTION=\"RECTANGLE\", CARA=(\"HY\", \"HZ\"), VALE=(0.1, 0.05)",
        "SECTION=\"GENERALE\", CARA=(\"A\", \"IY\", \"IZ\", \"JX\"), \
         VALE=(5.0e-3, 1.0416666666666667e-06, 4.166666666666667e-06, 2.8610026041666676e-06)",
    );
    assert!(t.contains("GENERALE"));
    assert_eq!(run(&t, "generale"), (62, 0, None));
}

fn refused(text: &str, tag: &str, what: &[&str]) {
    let (ok, nook, err) = run(text, tag);
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("not supported yet"), "{err}");
    for w in what {
        assert!(err.contains(w), "{w} in {err}");
    }
}

#[test]
fn plasticity_on_beams_is_refused_at_the_relation() {
    let t = text().replace(
        "COMPORTEMENT=_F(RELATION=\"ELAS\", TOUT=\"OUI\")",
        "COMPORTEMENT=_F(RELATION=\"VMIS_ISOT_LINE\", TOUT=\"OUI\")",
    );
    refused(&t, "plastic", &["RELATION", "POU_D_E"]);
}

#[test]
fn a_varying_section_is_refused_at_vari_sect() {
    let t = text().replace(
        "SECTION=\"RECTANGLE\", CARA=(\"HY\", \"HZ\"), VALE=(0.1, 0.05)",
        "SECTION=\"CERCLE\", VARI_SECT=\"HOMOTHETIQUE\", CARA=(\"R_DEBUT\", \"R_FIN\"), \
         VALE=(0.05, 0.04)",
    );
    refused(&t, "homothetic", &["VARI_SECT", "R_DEBUT"]);
}

/// A constant homothetic circle is a constant circle: the horizontal beam's
/// axial stiffness then follows A = πR².
#[test]
fn an_equal_ended_homothetic_circle_is_a_circle() {
    let r: f64 = (5.0e-3 / std::f64::consts::PI).sqrt();
    let t = text().replace(
        "SECTION=\"RECTANGLE\", CARA=(\"HY\", \"HZ\"), VALE=(0.1, 0.05)",
        &format!(
            "SECTION=\"CERCLE\", VARI_SECT=\"HOMOTHETIQUE\", CARA=(\"R_DEBUT\", \"R_FIN\"), \
                 VALE=({r:e}, {r:e})"
        ),
    );
    // Keep only the axial check (A = 5e-3 as the rectangle's).
    let start = t.find("TEST_RESU(").unwrap();
    let mut t = t[..start].to_string();
    t.push_str(
        "TEST_RESU(RESU=_F(NUME_ORDRE=1, RESULTAT=RESU, NOM_CHAM=\"DEPL\", GROUP_NO=\"H4\", \
         NOM_CMP=\"DX\", VALE_CALC=2.0e-5, VALE_REFE=2.0e-5, REFERENCE=\"ANALYTIQUE\", \
         PRECISION=1.0e-9))\n\nFIN()\n",
    );
    assert_eq!(run(&t, "circle"), (2, 0, None));
}

/// Discrete contact with nodal pairing between point cells (POI1), as
/// code_aster's APPARIEMENT='NODAL' with a fixed slave normal: the tip of
/// the horizontal cantilever, pushed down by P = 1000 (free deflection
/// P·L³/(3·E·IY) = 1.28e-2), meets a fixed point 0.01 below it: the tip
/// stops at DZ = −0.01, the support carries P − 3·E·IY·0.01/L³ =
/// 1000·(1 − 0.01/0.0128) = 218.75 and the clamp the rest, 781.25
/// (REAC_NODA: the contact force is not a reaction of the point).
#[test]
fn a_beam_tip_on_a_point_support_by_nodal_pairing() {
    let t = text();
    let head = &t[..t.find("LINST = ").unwrap()];
    let head = head
        .replace(
            "_F(GROUP_MA=(\"P\", \"K\"), PHENOMENE",
            "_F(GROUP_MA=(\"P\", \"K\", \"G\", \"TIP\"), PHENOMENE",
        )
        .replace(
            "_F(GROUP_MA=\"P\", CARA=\"M_TR_D_N\"",
            "_F(GROUP_MA=(\"G\", \"TIP\"), CARA=\"K_TR_D_N\", VALE=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)),\n        \
             _F(GROUP_MA=\"P\", CARA=\"M_TR_D_N\"",
        )
        .replace("GROUP_NO=\"CLAMP\"", "GROUP_NO=(\"CLAMP\", \"G0\")")
        .replace(
            "FX=1.0e4, FY=500.0, FZ=1000.0, MX=100.0",
            "FZ=-1000.0",
        );
    let text = format!(
        "{head}CONT = DEFI_CONTACT(MODELE=MO, FORMULATION=\"DISCRETE\", ZONE=_F(\
         APPARIEMENT=\"NODAL\", GROUP_MA_MAIT=\"G\", GROUP_MA_ESCL=\"TIP\", NORMALE=\"ESCL\", \
         VECT_ESCL=\"FIXE\", ESCL_FIXE=(0.0, 0.0, -1.0)))\n\n\
         LINST = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))\n\n\
         RESU = STAT_NON_LINE(MODELE=MO, CHAM_MATER=MAT, CARA_ELEM=CARA, \
         EXCIT=(_F(CHARGE=CLAMP), _F(CHARGE=TIP)), CONTACT=CONT, \
         COMPORTEMENT=_F(RELATION=\"ELAS\", TOUT=\"OUI\"), INCREMENT=_F(LIST_INST=LINST))\n\n\
         RESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, FORCE=\"REAC_NODA\")\n\n\
         TEST_RESU(RESU=(\
         _F(NUME_ORDRE=1, RESULTAT=RESU, NOM_CHAM=\"DEPL\", GROUP_NO=\"H4\", NOM_CMP=\"DZ\", \
         VALE_CALC=-0.01, VALE_REFE=-0.01, REFERENCE=\"ANALYTIQUE\", PRECISION=1.0e-9),\
         _F(NUME_ORDRE=1, RESULTAT=RESU, NOM_CHAM=\"REAC_NODA\", GROUP_NO=\"H0\", NOM_CMP=\"DZ\", \
         VALE_CALC=781.25, VALE_REFE=781.25, REFERENCE=\"ANALYTIQUE\", PRECISION=1.0e-9),\
         ))\n\nFIN()\n"
    );
    assert_eq!(run(&text, "nodal-contact"), (4, 0, None));
}

/// `DIST_POUTRE='OUI'`: the radius of the slave beams' circular section is
/// part of the gap (code_aster's `cfdist`/`cfdism`). The horizontal
/// cantilever, now a solid circle R = 0.05 (EI = E·π·R⁴/4), its last cell
/// the slave side of a nodal zone against a point 0.051 below the axis of
/// its tip: the surface of the beam is 0.001 above it, so the tip stops at
/// DZ = −0.001 and the clamp carries 3·EI·0.001/L³ = 368.155… (the support
/// the rest of P).
#[test]
fn dist_poutre_puts_the_beam_surface_on_the_support() {
    let t = text();
    let head = &t[..t.find("LINST = ").unwrap()];
    let head = head
        .replace(
            "_F(GROUP_MA=(\"P\", \"K\"), PHENOMENE",
            "_F(GROUP_MA=(\"P\", \"K\", \"G1\"), PHENOMENE",
        )
        .replace(
            "POUTRE=_F(GROUP_MA=(\"H\", \"V\"), SECTION=\"RECTANGLE\"",
            "POUTRE=(_F(GROUP_MA=\"H\", SECTION=\"CERCLE\", CARA=\"R\", VALE=0.05), \
             _F(GROUP_MA=\"V\", SECTION=\"RECTANGLE\"",
        )
        .replace("VALE=(0.1, 0.05)),", "VALE=(0.1, 0.05))),")
        .replace(
            "_F(GROUP_MA=\"P\", CARA=\"M_TR_D_N\"",
            "_F(GROUP_MA=\"G1\", CARA=\"K_TR_D_N\", VALE=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)),\n        \
             _F(GROUP_MA=\"P\", CARA=\"M_TR_D_N\"",
        )
        .replace("GROUP_NO=\"CLAMP\"", "GROUP_NO=(\"CLAMP\", \"G1\")")
        .replace("FX=1.0e4, FY=500.0, FZ=1000.0, MX=100.0", "FZ=-1000.0");
    let text = format!(
        "{head}CONT = DEFI_CONTACT(MODELE=MO, FORMULATION=\"DISCRETE\", ZONE=_F(\
         APPARIEMENT=\"NODAL\", GROUP_MA_MAIT=\"G1\", GROUP_MA_ESCL=\"MH4\", NORMALE=\"ESCL\", \
         VECT_ESCL=\"FIXE\", ESCL_FIXE=(0.0, 0.0, -1.0), DIST_POUTRE=\"OUI\", CARA_ELEM=CARA))\n\n\
         LINST = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))\n\n\
         RESU = STAT_NON_LINE(MODELE=MO, CHAM_MATER=MAT, CARA_ELEM=CARA, \
         EXCIT=(_F(CHARGE=CLAMP), _F(CHARGE=TIP)), CONTACT=CONT, \
         COMPORTEMENT=_F(RELATION=\"ELAS\", TOUT=\"OUI\"), INCREMENT=_F(LIST_INST=LINST))\n\n\
         RESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, FORCE=\"REAC_NODA\")\n\n\
         TEST_RESU(RESU=(\
         _F(NUME_ORDRE=1, RESULTAT=RESU, NOM_CHAM=\"DEPL\", GROUP_NO=\"H4\", NOM_CMP=\"DZ\", \
         VALE_CALC=-0.001, VALE_REFE=-0.001, REFERENCE=\"ANALYTIQUE\", PRECISION=1.0e-9),\
         _F(NUME_ORDRE=1, RESULTAT=RESU, NOM_CHAM=\"REAC_NODA\", GROUP_NO=\"H0\", NOM_CMP=\"DZ\", \
         VALE_CALC=368.15538909255395, VALE_REFE=368.15538909255395, REFERENCE=\"ANALYTIQUE\", \
         PRECISION=1.0e-9),\
         ))\n\nFIN()\n"
    );
    assert_eq!(run(&text, "dist-poutre"), (4, 0, None));
}
