//! The project's body-force scene (comm/volume.comm on comm/strip.mail):
//! FORCE_INTERNE (constant and a function of INST), FACE_IMPO and
//! LIAISON_UNIF / LIAISON_GROUP on a bar whose nodal solution is exact.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn body_force_bar_matches_the_exact_nodal_values() {
    let out = std::env::temp_dir().join(format!("aster-volume-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/volume.comm"),
        Some(&root().join("comm/strip.mail")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (10, 0));
    let _ = std::fs::remove_dir_all(out);
}
