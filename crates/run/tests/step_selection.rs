//! The step selection every post-processing command shares
//! (`TOUT_ORDRE`, `NUME_ORDRE`, `LIST_ORDRE`, `INST`, `LIST_INST`): the
//! seed scene (comm/zzzz237b.comm, elastic, analytic answers, 20 steps,
//! checks at t = 20) with its nodal forces computed at the steps a
//! DEFI_LIST_ENTI designates.

mod scene;

const FORCES: &str = "FORCE=(\"FORC_NODA\", \"REAC_NODA\"))";

/// The seed scene with CALC_CHAMP's steps given by `LIST_ORDRE=orders`,
/// `orders` the integers of `vale`.
fn with_orders(vale: &str) -> String {
    let text = scene::read("zzzz237b.comm");
    assert!(text.contains(FORCES), "the scene changed");
    text.replace(
        "resu = CALC_CHAMP(",
        &format!("orders = DEFI_LIST_ENTI(VALE=({vale}))\n\nresu = CALC_CHAMP("),
    )
    .replace(
        FORCES,
        "FORCE=(\"FORC_NODA\", \"REAC_NODA\"), LIST_ORDRE=orders)",
    )
}

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/zzzz237.mail", &format!("steps-{tag}"))
}

#[test]
fn calc_champ_computes_the_steps_list_ordre_designates() {
    // Steps 19 and 20: the checks at t = 20 find their nodal forces.
    assert_eq!(run(&with_orders("19, 20"), "last"), (14, 0, None));
}

#[test]
fn a_step_left_out_by_list_ordre_has_no_nodal_forces() {
    // Steps 1 and 2 only: the FORC_NODA check at t = 20 finds no field —
    // an error, never a value.
    let (ok, nook, error) = run(&with_orders("1, 2"), "first");
    let e = error.expect("an error");
    assert!(e.contains("FORC_NODA"), "{e}");
    assert_eq!(nook, 0);
    assert!(ok < 14);
}
