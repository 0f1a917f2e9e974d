//! Running one of the project's `comm/` scenes (possibly edited) from a
//! test: shared by the scene tests so that each does not carry its own copy.
#![allow(dead_code)]

use std::path::PathBuf;

/// The repository root (where `comm/` is).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The text of `comm/<name>`.
pub fn read(name: &str) -> String {
    std::fs::read_to_string(root().join("comm").join(name)).unwrap()
}

/// Runs a command-file text on a mesh (a path from the repository root) in
/// a fresh temporary folder named by `tag` and the process id, and returns
/// (TEST_RESU OK, NOOK, the error that stopped the run).
pub fn run_on(text: &str, mesh: &str, tag: &str) -> (usize, usize, Option<String>) {
    let out = std::env::temp_dir().join(format!("aster-scene-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let comm = out.join("case.comm");
    std::fs::write(&comm, text).unwrap();
    let case = aster_run::program::prepare(&comm, Some(&root().join(mesh)), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(&out);
    (
        outcome.tally.ok,
        outcome.tally.nook,
        outcome.error.map(|e| format!("{e:?}")),
    )
}
