//! The project's CALC_PRESSION scene (comm/pressure.comm on
//! comm/strip.mail): the normal stress on both vertical edges of a strip in
//! uniform tension, and no shear.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn pressure_on_the_edges_of_a_strip_in_tension() {
    let out = std::env::temp_dir().join(format!("aster-pressure-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/pressure.comm"),
        Some(&root().join("comm/strip.mail")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (6, 0));
    let _ = std::fs::remove_dir_all(out);
}
