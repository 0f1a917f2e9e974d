//! POST_ELEM/INTEGRALE (comm/post_elem_integrale.comm on
//! comm/elga_block.mail, written for the project): a Gauss-point field and
//! a nodal field integrated over the whole model, groups, their union and
//! a face, and the nodal field given as a field (CHAM_GD), against the
//! closed forms of an imposed linear displacement; and the located errors
//! and refusals around it.

mod scene;

fn scene_text() -> String {
    scene::read("post_elem_integrale.comm")
}

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/elga_block.mail", &format!("integrale-{tag}"))
}

#[test]
fn integrals_and_means_match_the_imposed_field() {
    assert_eq!(run(&scene_text(), "scene"), (28, 0, None));
}

/// A component the field does not have is code_aster's UTILITAI7_12, named
/// at NOM_CMP; NOM_VARI is refused at its keyword.
#[test]
fn a_missing_component_and_nom_vari_are_located() {
    let t = scene_text().replacen(
        "NOM_CMP=\"DZ\", TYPE_MAILLE=\"2D\"",
        "NOM_CMP=\"TEMP\", TYPE_MAILLE=\"2D\"",
        1,
    );
    let (_, nook, err) = run(&t, "cmp");
    let err = err.expect("an error");
    assert_eq!(nook, 0);
    assert!(
        err.contains("NOM_CMP") && err.contains("no component TEMP"),
        "{err}"
    );
    // NOM_VARI (internal variables by name) is not read: refused.
    let t = scene_text().replacen("NOM_CMP=(\"SIZZ\", \"SIXX\")", "NOM_VARI=\"EPSEQ\"", 1);
    assert!(t.contains("NOM_VARI"));
    let (_, _, err) = run(&t, "vari");
    let err = err.expect("a refusal");
    assert!(
        err.contains("not supported yet") && err.contains("NOM_VARI"),
        "{err}"
    );
}
