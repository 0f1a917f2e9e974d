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
    assert_eq!(run(&text(), "scene"), (42, 0, None));
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
    assert_eq!(run(&t, "generale"), (42, 0, None));
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
    let t = text()
        .replace(
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
