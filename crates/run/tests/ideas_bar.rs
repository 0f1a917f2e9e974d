//! An I-DEAS universal file run as code_aster reads it (comm/ideas_bar.comm
//! on comm/ideas_bar.unv): two HEXA20 in series, a QUAD8 end face and a
//! SEG3 edge listed in I-DEAS node order, so the permutations of code_aster's
//! PRE_IDEAS decide every checked value; `TYPE_MAILLE` filters and a
//! `CREA_MAILLE` copy carry the load. Read once by `LIRE_MAILLAGE(FORMAT=
//! 'IDEAS')`, once by `PRE_IDEAS` then `LIRE_MAILLAGE(FORMAT='ASTER')`.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &Path, tag: &str) -> (usize, usize) {
    let out = std::env::temp_dir().join(format!("aster-ideas-{tag}-{}", std::process::id()));
    let case =
        aster_run::program::prepare(comm, Some(&root().join("comm/ideas_bar.unv")), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    (outcome.tally.ok, outcome.tally.nook)
}

#[test]
fn ideas_bar_runs_to_its_analytic_values() {
    assert_eq!(run(&root().join("comm/ideas_bar.comm"), "lire"), (12, 0));
}

#[test]
fn pre_ideas_writes_the_same_mesh() {
    let text = std::fs::read_to_string(root().join("comm/ideas_bar.comm")).unwrap();
    let via_pre = text.replace(
        r#"mesh0 = LIRE_MAILLAGE(FORMAT="IDEAS", UNITE=20)"#,
        "PRE_IDEAS(UNITE_IDEAS=20, UNITE_MAILLAGE=21)\nmesh0 = LIRE_MAILLAGE(FORMAT=\"ASTER\", UNITE=21)",
    );
    assert_ne!(via_pre, text);
    let dir = std::env::temp_dir().join(format!("aster-pre-ideas-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("pre_ideas.comm");
    std::fs::write(&comm, via_pre).unwrap();
    let tally = run(&comm, "pre");
    let _ = std::fs::remove_dir_all(dir);
    assert_eq!(tally, (12, 0));
}
