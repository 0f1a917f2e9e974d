//! The project's step-cutting scene (comm/plastic3d_cutting.comm on
//! comm/plastic3d_cutting.mail): a 3D VMIS_ISOT_LINE block pushed at one
//! corner in one increment that Newton cannot do within ITER_GLOB_MAXI;
//! DEFI_LIST_INST/ECHEC cuts it. The cut run must equal the run with the
//! pieces listed; ARRET must stop with Newton's error; cutting too shallow
//! must stop with an error naming the increment, the limit and where the
//! cutting was set.

mod scene;

/// Runs the scene's text (possibly edited): (OK, NOOK, error).
fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/plastic3d_cutting.mail",
        &format!("cutting-{tag}"),
    )
}

fn scene() -> String {
    scene::read("plastic3d_cutting.comm")
}

fn edited(pairs: &[(&str, &str)]) -> String {
    let mut text = scene();
    for (from, to) in pairs {
        assert!(text.contains(from), "the scene no longer has `{from}`");
        text = text.replace(from, to);
    }
    text
}

const ONE_INCREMENT: &str = "times = DEFI_LIST_REEL(VALE=(0.0, 1.0))";
const ECHEC: &str = "ECHEC=_F(EVENEMENT=\"ERREUR\", ACTION=\"DECOUPE\", SUBD_METHODE=\"MANUEL\", SUBD_PAS=4, SUBD_NIVEAU=3),";

#[test]
fn the_cut_increment_passes_the_checks_of_the_listed_pieces() {
    assert_eq!(run(&scene(), "cut"), (3, 0, None));
    // The same values with the four pieces listed (nothing to cut).
    let listed = edited(&[(
        ONE_INCREMENT,
        "times = DEFI_LIST_REEL(VALE=(0.0, 0.25, 0.5, 0.75, 1.0))",
    )]);
    assert_eq!(run(&listed, "listed"), (3, 0, None));
    // Every piece of the cut increment is archived, as code_aster does
    // (`dinuar`): t = 1 is the fourth step after the initial state in both.
    for (text, tag) in [(scene(), "cut-nume"), (listed, "listed-nume")] {
        let by_number = text.replace("INST=1.0, RESULTAT=resu", "NUME_ORDRE=4, RESULTAT=resu");
        assert_ne!(by_number, text);
        assert_eq!(run(&by_number, tag), (3, 0, None));
        let past_the_end = text.replace("INST=1.0, RESULTAT=resu", "NUME_ORDRE=5, RESULTAT=resu");
        assert!(run(&past_the_end, &format!("{tag}-5")).2.is_some());
    }
}

#[test]
fn arret_stops_with_newtons_error() {
    let text = edited(&[(ECHEC, "ECHEC=_F(EVENEMENT=\"ERREUR\", ACTION=\"ARRET\"),")]);
    let (_, _, err) = run(&text, "arret");
    let err = err.expect("an error");
    assert!(
        err.contains("Newton did not converge at time 1") && err.contains("ITER_GLOB_MAXI"),
        "{err}"
    );
}

#[test]
fn cutting_too_shallow_is_a_located_error() {
    // Two iterations only: the pieces fail too, one level is not enough.
    let text = edited(&[
        (
            ECHEC,
            "ECHEC=_F(ACTION=\"DECOUPE\", SUBD_PAS=4, SUBD_NIVEAU=1),",
        ),
        ("ITER_GLOB_MAXI=5", "ITER_GLOB_MAXI=3"),
    ]);
    let (_, _, err) = run(&text, "shallow");
    let err = err.expect("an error");
    assert!(
        err.contains("the increment from t = 0 to t = 0.25 fails even cut 1 time(s) in 4 pieces")
            && err.contains("SUBD_NIVEAU = 1 reached")
            && err.contains("last failure: Newton did not converge")
            && err.contains("cutting set by DEFI_LIST_INST/ECHEC at")
            && err.contains("case.comm:"),
        "{err}"
    );
}

#[test]
fn subd_pas_below_two_is_refused() {
    let text = edited(&[(ECHEC, "ECHEC=_F(ACTION=\"DECOUPE\", SUBD_PAS=1),")]);
    let (_, _, err) = run(&text, "pas1");
    let err = err.expect("an error");
    assert!(err.contains("SUBD_PAS"), "{err}");
}
