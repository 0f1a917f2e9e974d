//! POST_ELEM/TRAV_EXT, ENER_TOTALE and MINMAX (comm/post_elem_trav_ext.comm
//! on comm/post_elem_bar.mail, written for the project): the work of a
//! ramped end pressure on a bar against ½ F u and the trapezoidal rule, its
//! elastic energy, and the extrema of nodal and Gauss-point fields with
//! their nodes and cells, against the closed forms; and the errors around
//! them.

mod scene;

fn scene_text() -> String {
    scene::read("post_elem_trav_ext.comm")
}

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/post_elem_bar.mail", &format!("trav-ext-{tag}"))
}

#[test]
fn work_and_extrema_match_the_bar() {
    assert_eq!(run(&scene_text(), "scene"), (58, 0, None));
}

/// TRAV_EXT needs FORC_NODA at every step (code_aster stops there too).
#[test]
fn work_without_nodal_forces_names_the_field() {
    let t = scene_text().replacen(
        "RESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, FORCE=\"FORC_NODA\")\n",
        "",
        1,
    );
    let (_, nook, err) = run(&t, "noforc");
    let err = err.expect("an error");
    assert_eq!(nook, 0);
    assert!(err.contains("FORC_NODA"), "{err}");
}

/// A component the field lacks is an error at NOM_CMP.
#[test]
fn a_missing_component_is_located() {
    let t = scene_text().replacen("NOM_CMP=(\"DZ\", \"DX\")", "NOM_CMP=(\"DZ\", \"TEMP\")", 1);
    let (_, nook, err) = run(&t, "cmp");
    let err = err.expect("an error");
    assert_eq!(nook, 0);
    assert!(
        err.contains("NOM_CMP") && err.contains("no component TEMP"),
        "{err}"
    );
}
