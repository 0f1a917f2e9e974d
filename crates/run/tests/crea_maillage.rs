//! The project's CREA_MAILLAGE scene (comm/crea_maillage.comm on
//! comm/strip.mail): RESTREINT, LINE_QUAD, MODI_MAILLE QUAD_TRIA3,
//! QUAD_LINE and CREA_POI1 meshes each carry a tension test whose exact
//! solution every element type reproduces.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn every_derived_mesh_passes_the_tension_checks() {
    let out = std::env::temp_dir().join(format!("aster-crea-maillage-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/crea_maillage.comm"),
        Some(&root().join("comm/strip.mail")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (12, 0));
    let _ = std::fs::remove_dir_all(out);
}
