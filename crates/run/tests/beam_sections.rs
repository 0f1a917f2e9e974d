//! MACR_CARA_POUTRE and POST_ELEM/CARA_GEOM on the project's scene
//! `comm/beam_sections.export` (a rectangle and a circular tube against
//! closed forms), and the refusals around them.

mod scene;

use scene::{root, run_case as run, temp};

fn refused(name: &str, edits: &[(&str, &str)]) -> String {
    scene::refused_export(
        "beam_sections.comm",
        &["beam_section_rect.mail", "beam_section_tube.mail"],
        edits,
        &format!("sections-{name}"),
    )
}

#[test]
fn rectangle_and_tube_match_their_closed_forms() {
    let out = temp("sections");
    let (outcome, report) = run(&root().join("comm/beam_sections.export"), &out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    // 17 TEST_TABLE, each against VALE_CALC and the analytic VALE_REFE.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (34, 0), "{report}");
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn the_torsion_constant_of_a_section_with_holes_is_not_read() {
    let error = refused(
        "jx-tube",
        &[("    (\"A\", 6.283181465937491e-03", "    (\"JX\", 1.0e-4")],
    );
    assert!(
        error.contains("no row of `tube` has a value of JX"),
        "{error}"
    );
}

#[test]
fn per_group_torsion_is_refused_before_the_run() {
    let error = refused(
        "group-ma",
        &[(
            "GROUP_MA_BORD=\"BORD\",",
            "GROUP_MA_BORD=\"BORD\", GROUP_MA=\"BORD\",",
        )],
    );
    assert!(
        error.contains("not supported yet: MACR_CARA_POUTRE/GROUP_MA with GROUP_MA_BORD")
            && error.contains("case.comm:18:"),
        "{error}"
    );
}

#[test]
fn shear_functions_need_a_fixed_node() {
    let error = refused(
        "no-group-no",
        &[(
            "GROUP_MA_BORD=\"BORD\", GROUP_NO=\"P1\",",
            "GROUP_MA_BORD=\"BORD\",",
        )],
    );
    assert!(
        error.contains("MACR_CARA_POUTRE/GROUP_MA_BORD without GROUP_NO")
            && error.contains("case.comm:18:"),
        "{error}"
    );
}
