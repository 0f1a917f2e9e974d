//! Static substructuring (comm/substructure.comm): a macro element
//! (MACR_ELEM_STAT) assembled as a super cell onto its own mesh, solved by
//! STAT_NON_LINE with its load cases (SOUS_STRUC). The scene's checks are
//! analytic (uniaxial stress in a column of two cubes); the variants below
//! check the interior conditions held without a load case and the
//! refusals.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/substructure.mail",
        &format!("substructure-{tag}"),
    )
}

fn text() -> String {
    scene::read("substructure.comm")
}

#[test]
fn both_load_cases_give_the_uniaxial_answers() {
    assert_eq!(run(&text(), "scene"), (10, 0, None));
}

#[test]
fn without_a_load_case_the_macro_element_keeps_its_interior_conditions_at_zero() {
    // NU = 0 (no lateral strain, so each cube's state is uniform), no
    // SOUS_STRUC: the macro element's top stays at DZ = 0 (CHAR_MACR_ELEM
    // held with a zero value) while a force -1 on each of the four MID
    // nodes is shared by the two cubes, stiffness E·A/L = 1000 each:
    // DZ(MID) = -4 / 2000 = -0.002.
    let t = text();
    let cut = t.find("MOPRES = AFFE_MODELE(").expect("the scene changed");
    let first = t[..cut].to_string();
    let start = first.find("TEST_RESU(").expect("the scene changed");
    let mut variant = first[..start]
        .replace("NU=0.3", "NU=0.0")
        .replace(
            "    SOUS_STRUC=_F(CAS_CHARGE=\"PUSH\", SUPER_MAILLE=\"S1\", FONC_MULT=ramp),\n",
            "",
        )
        .replace(
            "        _F(GROUP_NO=\"YAXIS\", DX=0.0),\n    ),\n)",
            "        _F(GROUP_NO=\"YAXIS\", DX=0.0),\n    ),\n    FORCE_NODALE=_F(GROUP_NO=\"MID\", FZ=-1.0),\n)",
        );
    assert!(variant.contains("FZ=-1.0") && !variant.contains("CAS_CHARGE=\"PUSH\", SUPER"));
    variant.push_str(
        "TEST_RESU(RESU=_F(RESULTAT=RPUSH, INST=1.0, NOM_CHAM=\"DEPL\", GROUP_NO=\"C6\", \
         NOM_CMP=\"DZ\", REFERENCE=\"ANALYTIQUE\", VALE_REFE=-0.002, VALE_CALC=-0.002, \
         PRECISION=1.0e-9))\nFIN()\n",
    );
    assert_eq!(run(&variant, "held"), (2, 0, None));
}

#[test]
fn a_non_linear_behaviour_on_the_macro_element_is_refused() {
    let t = text().replace(
        "STEEL = DEFI_MATERIAU(ELAS=_F(E=1000.0, NU=0.3))",
        "STEEL = DEFI_MATERIAU(ELAS=_F(E=1000.0, NU=0.3), ECRO_LINE=_F(D_SIGM_EPSI=10.0, SY=1.0))",
    );
    let t = t.replacen(
        "COMPORTEMENT=_F(RELATION=\"ELAS\", TOUT=\"OUI\")",
        "COMPORTEMENT=_F(RELATION=\"VMIS_ISOT_LINE\", TOUT=\"OUI\")",
        1,
    );
    let (ok, nook, error) = run(&t, "plastic");
    let e = error.expect("refused");
    assert!(e.contains("a macro element is linear elastic"), "{e}");
    assert_eq!((ok, nook), (0, 0));
}

#[test]
fn renamed_exterior_nodes_are_refused() {
    // INDEX=(1, 2, 1, 8): the nodes become S1N5…, which MAILLAGE_1 does
    // not have; aster solves a macro element only on its own nodes.
    let t = text().replacen("INDEX=(1, 0, 1, 8)", "INDEX=(1, 2, 1, 8)", 1);
    let (ok, nook, error) = run(&t, "renamed");
    let e = error.expect("refused");
    assert!(e.contains("exterior node S1N5"), "{e}");
    assert_eq!((ok, nook), (0, 0));
}

#[test]
fn a_heated_macro_element_is_refused() {
    // code_aster condenses the thermal strains of AFFE_VARC into the load
    // cases (zzzz104a); aster's load cases hold their CHARGE only.
    let t = text().replacen(
        "MAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=STEEL))",
        "HOT = CREA_CHAMP(OPERATION=\"AFFE\", TYPE_CHAM=\"NOEU_TEMP_R\", MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", NOM_CMP=\"TEMP\", VALE=50.0))
MAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=STEEL), AFFE_VARC=_F(TOUT=\"OUI\", NOM_VARC=\"TEMP\", CHAM_GD=HOT, VALE_REF=0.0))",
        1,
    );
    let (ok, nook, error) = run(&t, "heated");
    let e = error.expect("refused");
    assert!(
        e.contains("a macro element whose CHAM_MATER gives its cells a temperature"),
        "{e}"
    );
    assert_eq!((ok, nook), (0, 0));
}
