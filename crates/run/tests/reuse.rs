//! STAT_NON_LINE `reuse=R` with `ETAT_INIT/EVOL_NOLI=R`: the computation
//! continues the result (zzzz231b's use). The project's seed scene
//! (comm/zzzz237b.comm, elastic, analytic answers) is solved to t = 8, then
//! continued to t = 20: every check passes as in one go.

mod scene;

/// Runs a command file's text on the seed mesh: (OK, NOOK, error).
fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/zzzz237.mail", &format!("reuse-{tag}"))
}

const FIRST: &str = "    INCREMENT=_F(LIST_INST=times),\n)\n";

const FORCES: &str = "FORCE=(\"FORC_NODA\", \"REAC_NODA\"))";

/// The seed scene solved to t = 8, then continued by `second`; its nodal
/// forces computed at t = 20 only.
fn continued(second: &str) -> String {
    all_steps(second).replace(FORCES, "FORCE=(\"FORC_NODA\", \"REAC_NODA\"), INST=20.0)")
}

/// The same with the nodal forces computed at every step.
fn all_steps(second: &str) -> String {
    let text = scene::read("zzzz237b.comm");
    assert!(
        text.contains(FIRST) && text.contains(FORCES),
        "the scene changed"
    );
    text.replacen(
        FIRST,
        &format!("    INCREMENT=_F(LIST_INST=times, INST_FIN=8.0),\n)\n\n{second}"),
        1,
    )
}

const CONTINUATION: &str = "resu = STAT_NON_LINE(
    reuse=resu,
    ETAT_INIT=_F(EVOL_NOLI=resu),
    MODELE=model,
    CHAM_MATER=materials,
    CARA_ELEM=springs,
    EXCIT=(_F(CHARGE=push, FONC_MULT=ramp), _F(CHARGE=anchors)),
    CONTACT=base,
    COMPORTEMENT=_F(RELATION=\"ELAS\"),
    INCREMENT=_F(LIST_INST=times),
)
";

#[test]
fn a_continued_result_passes_every_check_at_its_last_step() {
    let (ok, nook, error) = run(&continued(CONTINUATION), "seed");
    assert_eq!(error, None);
    assert_eq!(
        (ok, nook),
        (14, 0),
        "the seed scene's 7 checks, VALE_CALC and VALE_REFE"
    );
    // And the continued result holds every instant, numbered on: its
    // NUME_ORDRE 20 is t = 20.
    let text = continued(CONTINUATION).replace("INST=20.0,\n                NOM_CHAM=\"DEPL\",\n                GROUP_NO=node,\n                NOM_CMP=\"DY\"", "NUME_ORDRE=20,\n                NOM_CHAM=\"DEPL\",\n                GROUP_NO=node,\n                NOM_CMP=\"DY\"");
    assert!(text.contains("NUME_ORDRE=20"));
    assert_eq!(run(&text, "order"), (14, 0, None));
}

#[test]
fn a_reuse_without_its_own_initial_state_is_refused() {
    let other = CONTINUATION.replace("    ETAT_INIT=_F(EVOL_NOLI=resu),\n", "");
    let (ok, nook, error) = run(&continued(&other), "noinit");
    let e = error.expect("refused");
    assert!(
        e.contains("STAT_NON_LINE with reuse= whose ETAT_INIT/EVOL_NOLI is not the reused result"),
        "{e}"
    );
    assert_eq!((ok, nook), (0, 0));
}

#[test]
fn fields_of_the_steps_before_the_continuation_come_from_the_first_run() {
    // The same problem continued: CALC_CHAMP on every step of the
    // continued result computes the first run's steps from its states, and
    // every check passes as in one go.
    assert_eq!(run(&all_steps(CONTINUATION), "before"), (14, 0, None));
}

#[test]
fn fields_of_the_steps_before_a_different_continuation_are_not_recomputed() {
    // The continuation lists its loads in another order: not the same
    // problem as far as the stored states go, so CALC_CHAMP at a step of
    // the first run is an error, never values computed with the other
    // run's loads.
    let other = CONTINUATION.replace(
        "EXCIT=(_F(CHARGE=push, FONC_MULT=ramp), _F(CHARGE=anchors)),",
        "EXCIT=(_F(CHARGE=anchors), _F(CHARGE=push, FONC_MULT=ramp)),",
    );
    assert_ne!(other, CONTINUATION);
    let (ok, nook, error) = run(&all_steps(&other), "different");
    let e = error.expect("an error");
    assert!(
        e.contains("CALC_CHAMP: no computed state at NUME_ORDRE 0"),
        "{e}"
    );
    assert_eq!((ok, nook), (0, 0));
}
