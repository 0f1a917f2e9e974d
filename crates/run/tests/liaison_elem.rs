//! LIAISON_ELEM(OPTION='3D_POU') on the project's scene
//! (comm/solid_to_beam.comm on comm/solid_to_beam.mail): a HEXA8 bar whose
//! end face is tied to a DIS_TR node, pulled through that node — uniform
//! tension against F·L/(E·A) within 1e-9, no rotation of the node — and
//! the errors of a misused coupling.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/solid_to_beam.mail",
        &format!("liaison-elem-{tag}"),
    )
}

fn bar() -> String {
    scene::read("solid_to_beam.comm")
}

#[test]
fn a_force_on_the_node_stretches_the_tied_bar_uniformly() {
    assert_eq!(run(&bar(), "pull"), (10, 0, None));
}

/// Without the coupling the node's rotations and translations are held by
/// nothing (its DIS_TR has zero stiffness): the system is singular.
#[test]
fn without_the_coupling_the_node_is_free() {
    let text = bar().replace(
        "    LIAISON_ELEM=_F(OPTION=\"3D_POU\", GROUP_MA_1=\"FACE\", GROUP_NO_2=\"P\"),\n",
        "",
    );
    assert!(!text.contains("GROUP_MA_1=\"FACE\""));
    let (ok, nook, err) = run(&text, "free");
    assert_eq!((ok, nook), (0, 0));
    assert!(err.is_some());
}

/// A torque on the node through AFFE_CHAR_MECA_F (MX a function of time)
/// twists the bar as the same constant torque does (DRX 0.12 for both).
#[test]
fn a_torque_given_by_a_function_acts_like_the_constant_one() {
    let check = "TEST_RESU(RESU=_F(NUME_ORDRE=1, RESULTAT=RESU, NOM_CHAM=\"DEPL\", \
                 GROUP_NO=\"P\", NOM_CMP=\"DRX\", VALE_CALC=0.12000000000001197))\nFIN()\n";
    let base = bar();
    let head = &base[..base.find("TEST_RESU(").unwrap()];
    let constant = head.replace(
        "FORCE_NODALE=_F(GROUP_NO=\"P\", FX=100.0)",
        "FORCE_NODALE=_F(GROUP_NO=\"P\", MX=100.0)",
    ) + check;
    assert_eq!(run(&constant, "torque"), (1, 0, None));
    let function = head.replace(
        "PULL = AFFE_CHAR_MECA(MODELE=MO, FORCE_NODALE=_F(GROUP_NO=\"P\", FX=100.0))",
        "T = DEFI_FONCTION(NOM_PARA=\"INST\", VALE=(0.0, 0.0, 1.0, 100.0))\n\
         PULL = AFFE_CHAR_MECA_F(MODELE=MO, FORCE_NODALE=_F(GROUP_NO=\"P\", MX=T))",
    ) + check;
    assert!(function.contains("MX=T"));
    assert_eq!(run(&function, "torque-f"), (1, 0, None));
}

#[test]
fn the_beam_side_is_one_node() {
    let text = bar().replace("GROUP_NO_2=\"P\"", "GROUP_NO_2=\"CLAMP\"");
    let (_, _, err) = run(&text, "two");
    let err = err.expect("an error");
    assert!(
        err.contains("GROUP_NO_2") && err.contains("4 nodes"),
        "{err}"
    );
}

#[test]
fn other_options_are_refused_at_the_keyword() {
    let text = bar().replace("OPTION=\"3D_POU\"", "OPTION=\"2D_POU\"");
    let (_, _, err) = run(&text, "option");
    let err = err.expect("refused");
    assert!(
        err.contains("not supported yet") && err.contains("LIAISON_ELEM/OPTION"),
        "{err}"
    );
}
