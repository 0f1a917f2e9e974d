//! POST_RELEVE_T in the local frame of a path of nodes (comm/releve_local.comm
//! on comm/bent_path.mail): the components of a constant vector along and
//! across a bent path, against the frame code_aster's `rvrlln` builds
//! (derived by hand in the command file), the path walked both ways and
//! read from a node group made from cells listed backwards; and
//! a resultant in that frame refused, located.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &Path, tag: &str) -> aster_run::program::Outcome {
    let out = std::env::temp_dir().join(format!("aster-releve-{tag}-{}", std::process::id()));
    let case =
        aster_run::program::prepare(comm, Some(&root().join("comm/bent_path.mail")), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    outcome
}

#[test]
fn components_in_the_local_frame_of_a_bent_path() {
    let outcome = run(&root().join("comm/releve_local.comm"), "ok");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (20, 0));
}

#[test]
fn a_resultant_in_the_local_frame_is_refused_at_repere() {
    let text = std::fs::read_to_string(root().join("comm/releve_local.comm")).unwrap();
    let changed = text.replacen(
        "NOM_CMP=(\"DX\", \"DY\"), REPERE",
        "RESULTANTE=\"DX\", REPERE",
        1,
    );
    assert_ne!(text, changed);
    let dir = std::env::temp_dir().join(format!("aster-releve-resultant-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("resultant.comm");
    std::fs::write(&comm, changed).unwrap();
    let outcome = run(&comm, "resultant");
    let _ = std::fs::remove_dir_all(&dir);
    let err = outcome.error.expect("refused").to_string();
    assert!(
        err.contains("POST_RELEVE_T/ACTION/REPERE='LOCAL' with RESULTANTE")
            && err.contains("resultant.comm:28:26)"),
        "{err}"
    );
}
