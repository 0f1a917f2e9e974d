//! `CALC_CHAMP/GROUP_MA`: element fields on the given cells only, on the
//! project's scene `comm/calc_champ_group.comm` (a bar of two materials in
//! series, the strain of each part in closed form).

mod scene;

/// (TEST_RESU OK, NOOK, the error that stopped the run) on the bar mesh.
fn run(comm: &str, name: &str) -> (usize, usize, Option<String>) {
    scene::run_on(comm, "comm/hexs8_beam.mail", name)
}

fn scene() -> String {
    scene::read("calc_champ_group.comm")
}

/// EPSI_ELGA on the stiff half only: its largest and smallest EPXX are
/// both F/E1 (to 1e-10).
#[test]
fn element_fields_are_computed_on_the_group_only() {
    let outcome = run(&scene(), "group");
    assert!(outcome.2.is_none(), "{:?}", outcome.2);
    assert_eq!((outcome.0, outcome.1), (6, 0));
}

/// Over the whole bar the largest strain is the soft half's, F/E2: the
/// same checks then fail, so the group is what makes them pass.
#[test]
fn without_the_group_the_soft_half_counts() {
    let comm = scene().replace("    GROUP_MA=\"LEFT\",\n", "");
    let outcome = run(&comm, "whole");
    assert!(outcome.2.is_none(), "{:?}", outcome.2);
    assert_eq!((outcome.0, outcome.1), (4, 2));
}

/// The nodal forces of some cells only are not computed: refused at
/// GROUP_MA, before any value is printed.
#[test]
fn nodal_forces_on_a_group_are_refused() {
    let comm = scene().replace("DEFORMATION=\"EPSI_ELGA\",", "FORCE=\"REAC_NODA\",");
    let outcome = run(&comm, "reac");
    let err = format!("{:?}", outcome.2.expect("refused"));
    assert!(
        err.contains("CALC_CHAMP/GROUP_MA with FORCE='REAC_NODA'"),
        "{err}"
    );
    assert_eq!(outcome.0 + outcome.1, 0);
    // Located in the command file the run read (`scene::run_on` writes
    // it as case.comm).
    assert!(err.contains("case.comm"), "{err}");
}
