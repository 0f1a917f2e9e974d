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

/// Runs a prepared case (a `.comm` or `.export`) with its output in `out`;
/// returns the outcome and the report text.
pub fn run_case(
    case: &std::path::Path,
    out: &std::path::Path,
) -> (aster_run::program::Outcome, String) {
    let prepared = aster_run::program::prepare(case, None, out).unwrap();
    std::fs::create_dir_all(out).unwrap();
    let report = out.join("report.txt");
    let file = std::fs::File::create(&report).unwrap();
    let outcome = aster_run::program::run(&prepared, Box::new(file));
    let text = std::fs::read_to_string(&report).unwrap_or_default();
    (outcome, text)
}

/// A fresh temporary folder for a test, named by `tag` and the process id.
pub fn temp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-scene-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `comm/<comm>` edited (`from` → `to`, each present, first occurrence),
/// run through an `.export` naming the meshes `comm/<mesh>` on units 20,
/// 21…: the message of the error it must stop on.
pub fn refused_export(comm: &str, meshes: &[&str], edits: &[(&str, &str)], tag: &str) -> String {
    let dir = temp(tag);
    let mut text = read(comm);
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    std::fs::write(dir.join("case.comm"), text).unwrap();
    let mut export = String::from("F comm case.comm D 1\n");
    for (i, mesh) in meshes.iter().enumerate() {
        std::fs::copy(root().join("comm").join(mesh), dir.join(mesh)).unwrap();
        export.push_str(&format!("F mail {mesh} D {}\n", 20 + i));
    }
    std::fs::write(dir.join("case.export"), export).unwrap();
    let (outcome, report) = run_case(&dir.join("case.export"), &dir.join("out"));
    let _ = std::fs::remove_dir_all(&dir);
    outcome
        .error
        .unwrap_or_else(|| panic!("{tag}: not refused\n{report}"))
        .message
}
