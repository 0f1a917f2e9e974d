//! A GIBI mesh run as code_aster reads it (comm/gibi_plate.comm on
//! comm/square3.mgib): the node and cell names code_aster's PRE_GIBI gives
//! (nodes by coordinate index through pile 32, cells by their number across
//! the file's meshes) carry two materials in series and the conditions of
//! an exact tension test, so a name given to another node or cell changes
//! the checked values; the strain energy of the mesh is read in the POST_ELEM table
//! by its `LIEU`, `mesh.getName()`.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn gibi_names_carry_the_series_tension_test() {
    let out = std::env::temp_dir().join(format!("aster-gibi-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/gibi_plate.comm"),
        Some(&root().join("comm/square3.mgib")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (12, 0));
}
