//! `CALC_CHAMP/GROUP_MA`: element fields on the given cells only, on the
//! project's scene `comm/calc_champ_group.comm` (a bar of two materials in
//! series, the strain of each part in closed form).

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &str, name: &str) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-ccgroup-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.comm"));
    std::fs::write(&file, comm).unwrap();
    let mesh = root().join("comm/hexs8_beam.mail");
    let case = aster_run::program::prepare(&file, Some(&mesh), &dir).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

fn scene() -> String {
    std::fs::read_to_string(root().join("comm/calc_champ_group.comm")).unwrap()
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
