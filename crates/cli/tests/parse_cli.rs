//! `aster parse` and `aster fmt` as a user runs them.

use std::path::{Path, PathBuf};
use std::process::Command;

fn aster() -> Command {
    Command::new(env!("CARGO_BIN_EXE_aster"))
}

fn syntax_tests() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../syntax/tests")
}

#[test]
fn parse_reports_each_failure_and_a_summary() {
    let good = syntax_tests().join("inputs/commands.comm");
    let bad = syntax_tests().join("errors/error_missing_comma.comm");
    let out = match aster().arg("parse").arg(&good).arg(&bad).output() {
        Ok(o) => o,
        Err(e) => panic!("cannot run aster: {e}"),
    };
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(
            "error_missing_comma.comm:1:29: expected `,` or a closing bracket, found `NU`"
        ),
        "{stderr}"
    );
    assert!(
        stderr.contains("  |                             ^"),
        "{stderr}"
    );
    assert!(
        stderr.trim_end().ends_with("parse: 1 ok, 1 failed"),
        "{stderr}"
    );
}

#[test]
fn parse_json_is_the_ast() {
    let good = syntax_tests().join("inputs/commands.comm");
    let out = match aster().args(["parse", "--json"]).arg(&good).output() {
        Ok(o) => o,
        Err(e) => panic!("cannot run aster: {e}"),
    };
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = match serde_json::from_slice(&out.stdout) {
        Ok(v) => v,
        Err(e) => panic!("not JSON: {e}"),
    };
    assert_eq!(v["body"][0]["stmt"], "Expr");
    assert_eq!(v["body"][0]["value"]["func"]["id"], "DEBUT");
    assert_eq!(v["body"][1]["stmt"], "Assign");
    assert_eq!(v["body"][1]["value"]["args"][0]["name"]["name"], "FORMAT");
    assert_eq!(v["schema_version"], 1);
    assert_eq!(v["kind"], "ast");
    assert_eq!(v["path"], good.display().to_string());
}

/// `--json --compact`: JSON Lines, one AST per file in the order given,
/// every node located by line and column beside its byte span.
#[test]
fn parse_json_compact_is_one_line_per_file_with_positions() {
    let dir = std::env::temp_dir().join(format!("aster-parse-json-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let (a, b) = (dir.join("a.comm"), dir.join("b.comm"));
    let _ = std::fs::write(&a, "DEBUT()\nMA = LIRE_MAILLAGE(\n    FORMAT='MED')\n");
    let _ = std::fs::write(&b, "FIN()\n");
    let out = match aster()
        .args(["parse", "--json", "--compact"])
        .arg(&a)
        .arg(&b)
        .output()
    {
        Ok(o) => o,
        Err(e) => panic!("cannot run aster: {e}"),
    };
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object per line"))
        .collect();
    assert_eq!(lines.len(), 2, "{text}");
    assert_eq!(lines[0]["path"], a.display().to_string());
    assert_eq!(lines[1]["path"], b.display().to_string());
    let call = &lines[0]["body"][1]["value"];
    assert_eq!((&call["line"], &call["column"]), (&2.into(), &6.into()));
    let kw = &call["args"][0];
    assert_eq!(kw["name"]["name"], "FORMAT");
    assert_eq!((&kw["line"], &kw["column"]), (&3.into(), &5.into()));
    assert_eq!(kw["span"][0], 32);
    // --compact alone is a usage error.
    let out = match aster().args(["parse", "--compact"]).arg(&a).output() {
        Ok(o) => o,
        Err(e) => panic!("cannot run aster: {e}"),
    };
    assert_eq!(out.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fmt_prints_the_canonical_form() {
    let dir = std::env::temp_dir().join(format!("aster-fmt-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let file = dir.join("t.comm");
    let _ = std::fs::write(
        &file,
        "MA=LIRE_MAILLAGE( UNITE = 20 ,FORMAT='MED')  # mesh\n",
    );
    let out = match aster().arg("fmt").arg(&file).output() {
        Ok(o) => o,
        Err(e) => panic!("cannot run aster: {e}"),
    };
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "MA = LIRE_MAILLAGE(UNITE=20, FORMAT=\"MED\")  # mesh\n"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
