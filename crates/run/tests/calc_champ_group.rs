//! `CALC_CHAMP/GROUP_MA`: element fields on the given cells only, on the
//! project's scene `comm/calc_champ_group.comm` (a bar of two materials in
//! series, the strain of each part in closed form).

mod common;

fn run(comm: &str, name: &str) -> aster_run::program::Outcome {
    common::run_text(comm, name, "hexs8_beam.mail")
}

fn scene() -> String {
    common::scene("calc_champ_group.comm")
}

/// EPSI_ELGA on the stiff half only: its largest and smallest EPXX are
/// both F/E1 (to 1e-10).
#[test]
fn element_fields_are_computed_on_the_group_only() {
    let outcome = run(&scene(), "group");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (6, 0));
}

/// Over the whole bar the largest strain is the soft half's, F/E2: the
/// same checks then fail, so the group is what makes them pass.
#[test]
fn without_the_group_the_soft_half_counts() {
    let comm = scene().replace("    GROUP_MA=\"LEFT\",\n", "");
    let outcome = run(&comm, "whole");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (4, 2));
}

/// The nodal forces of some cells only are not computed: refused at
/// GROUP_MA, before any value is printed.
#[test]
fn nodal_forces_on_a_group_are_refused() {
    let comm = scene().replace("DEFORMATION=\"EPSI_ELGA\",", "FORCE=\"REAC_NODA\",");
    let outcome = run(&comm, "reac");
    let err = format!("{:?}", outcome.error.expect("refused"));
    assert!(
        err.contains("CALC_CHAMP/GROUP_MA with FORCE='REAC_NODA'"),
        "{err}"
    );
    assert_eq!(outcome.tally.ok + outcome.tally.nook, 0);
    assert!(
        err.contains("calc_champ_group.comm") || err.contains("reac.comm"),
        "{err}"
    );
}
