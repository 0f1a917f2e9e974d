//! MODI_REPERE (code_aster's chrpno): the project's scene
//! comm/modi_repere_square.comm (a square under a uniform tension, its
//! stresses in the cylindrical frame and its displacements in a turned
//! frame, against the closed forms) and the refusals, located.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/modi_repere_square.mail", tag)
}

#[test]
fn stresses_in_the_cylindrical_frame_and_displacements_in_a_turned_one() {
    // 6 values x 2 (NON_REGRESSION, ANALYTIQUE).
    let got = run(&scene::read("modi_repere_square.comm"), "square");
    assert_eq!(got, (12, 0, None));
}

/// The same scene with the angle turned the other way: the values checked
/// against +30 degrees must fail (the rotation is not an identity).
#[test]
fn the_opposite_angle_gives_other_values() {
    let text = scene::read("modi_repere_square.comm").replace("ANGL_NAUT=30.0", "ANGL_NAUT=-30.0");
    let (ok, nook, err) = run(&text, "square-opposite");
    assert!(err.is_none(), "{err:?}");
    assert_eq!((ok, nook), (8, 4));
}

fn refused(from: &str, to: &str, tag: &str) -> String {
    let text = scene::read("modi_repere_square.comm");
    assert!(text.contains(from), "{from}");
    let (_, nook, err) = run(&text.replacen(from, to, 1), tag);
    assert_eq!(nook, 0);
    err.expect("an error")
}

#[test]
fn shell_frames_groups_and_element_fields_are_refused_at_their_keyword() {
    let err = refused(
        r#"REPERE="UTILISATEUR""#,
        r#"REPERE="COQUE_INTR_UTIL""#,
        "coque",
    );
    assert!(
        err.contains("REPERE") && err.contains("case.comm:"),
        "{err}"
    );
    let err = refused(
        r#"AFFE=_F(ANGL_NAUT=30.0, TOUT="OUI")"#,
        r#"AFFE=_F(ANGL_NAUT=30.0, GROUP_NO="N3")"#,
        "group",
    );
    assert!(
        err.contains("GROUP_NO") && err.contains("case.comm:"),
        "{err}"
    );
    let err = refused(
        r#"MODI_CHAM=_F(NOM_CHAM="SIGM_NOEU", TYPE_CHAM="TENS_2D")"#,
        r#"MODI_CHAM=_F(NOM_CHAM="SIGM_ELNO", TYPE_CHAM="TENS_2D")"#,
        "elno",
    );
    assert!(
        err.contains("element field SIGM_ELNO") && err.contains("case.comm:"),
        "{err}"
    );
    let err = refused(
        r#"MODI_CHAM=_F(NOM_CHAM="DEPL", TYPE_CHAM="VECT_2D")"#,
        r#"MODI_CHAM=_F(NOM_CHAM="DEPL", TYPE_CHAM="TENS_2D")"#,
        "tens-of-depl",
    );
    assert!(
        err.contains("TYPE_CHAM") && err.contains("stress or strain"),
        "{err}"
    );
}
