//! The project's cohesive-joint scene (comm/cohesive_joint.comm on
//! comm/cohesive_joint.mail): one PLAN_JOINT QUAD4 under an elastic block,
//! opened in mode I with CZM_LIN_REG and sheared in mode II with CZM_TURON.
//! Every TEST_RESU passes against the closed-form equilibrium of the block
//! and the law (1e-6), the reactions on the joint's held face (its nodal
//! forces) included.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/cohesive_joint.mail",
        &format!("cohesive-joint-{tag}"),
    )
}

#[test]
fn the_joint_follows_its_laws_closed_forms_in_both_modes() {
    assert_eq!(
        run(&scene::read("cohesive_joint.comm"), "all"),
        (24, 0, None)
    );
}

#[test]
fn without_orie_fissure_the_clockwise_joint_opens_the_other_way() {
    // The mesh numbers the joint clockwise: its 1-2 face normal then points
    // into it and an opening is read as a closing (penalised contact), as
    // code_aster's nmfisa would read it. ORIE_FISSURE is what makes the
    // scene right.
    let text = scene::read("cohesive_joint.comm").replace(
        "mesh = MODI_MAILLAGE(reuse=mesh, MAILLAGE=mesh, ORIE_FISSURE=_F(GROUP_MA=\"COLLE\"))",
        "",
    );
    let (ok, nook, err) = run(&text, "no-orie");
    assert_eq!(err, None);
    assert!(nook >= 6, "{ok} OK, {nook} NOOK");
}

#[test]
fn a_joint_with_an_elastic_relation_is_refused() {
    let text = scene::read("cohesive_joint.comm").replace(
        "_F(GROUP_MA=\"COLLE\", RELATION=\"CZM_LIN_REG\")",
        "_F(GROUP_MA=\"COLLE\", RELATION=\"ELAS\")",
    );
    let (ok, nook, err) = run(&text, "elas");
    let err = err.expect("a refusal");
    assert_eq!((ok, nook), (0, 0));
    assert!(err.contains("CZM_LIN_REG or CZM_TURON"), "{err}");
}
