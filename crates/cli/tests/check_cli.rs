//! `aster check` and `aster explain` from the command line.

use std::path::PathBuf;
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn aster(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("run aster");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn scenes_check_clean() {
    for scene in ["comm/zzzz237a.comm", "comm/zzzz237b.comm"] {
        if !root().join(scene).exists() {
            eprintln!("skipped: {scene} not found");
            continue;
        }
        let (code, _, err) = aster(&["check", scene]);
        assert_eq!(code, 0, "{scene}:\n{err}");
        assert!(err.contains("ok (0 warning(s))"), "{err}");
    }
}

#[test]
fn emitted_commands_of_the_scenes() {
    for (scene, name) in [
        ("comm/zzzz237a.comm", "emit_zzzz237a"),
        ("comm/zzzz237b.comm", "emit_zzzz237b"),
    ] {
        if !root().join(scene).exists() {
            eprintln!("skipped: {scene} not found");
            continue;
        }
        let (code, out, err) = aster(&["check", "--emit", "commands", scene]);
        assert_eq!(code, 0, "{err}");
        let json: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
        assert!(json["commands"].as_array().is_some_and(|c| c.len() > 10));
        insta::assert_snapshot!(name, out);
    }
}

#[test]
fn errors_exit_1_with_positions() {
    let (code, _, err) = aster(&["check", "crates/eval/tests/errors/unknown_keyword.comm"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("crates/eval/tests/errors/unknown_keyword.comm:8:33: error:"),
        "{err}"
    );
    assert!(err.contains("`GROUP_MA_ESCL`"), "{err}");
    let (code, _, _) = aster(&["check", "no/such/file.comm"]);
    assert_eq!(code, 1);
}

#[test]
fn explain_prints_trees_and_suggests() {
    let (code, out, _) = aster(&["explain", "DEFI_CONTACT/ZONE/GROUP_MA_ESCL"]);
    assert_eq!(code, 0);
    assert!(out.contains("type: a cell group name (grma)"), "{out}");
    let (code, _, err) = aster(&["explain", "DEFI_CONTAKT"]);
    assert_eq!(code, 1);
    assert!(err.contains("`DEFI_CONTACT`"), "{err}");
}
