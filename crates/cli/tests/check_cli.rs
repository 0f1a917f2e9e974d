//! `aster check` and `aster explain` from the command line.

mod cli;

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn aster(args: &[&str]) -> (i32, String, String) {
    cli::aster_in(&root(), args)
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

/// `explain` for learners: what `aster run` does with the keyword, paths
/// copied from diagnostics, legacy names with their replacement.
#[test]
fn explain_says_what_run_supports_and_reads_legacy_names() {
    let (code, out, _) = aster(&["explain", "AFFE_MODELE/AFFE[1]/MODELISATION"]);
    assert_eq!(code, 0);
    let run = out.lines().last().unwrap_or("");
    assert!(
        run.starts_with(
            "aster run: AFFE_MODELE/AFFE/MODELISATION is supported with the values 'D_PLAN'"
        ),
        "{out}"
    );
    let (_, out, _) = aster(&["explain", "MACR_ADAP_MAIL"]);
    assert!(out.contains("aster run: MACR_ADAP_MAIL is refused before the run (mesh adaptation runs the external HOMARD tool"), "{out}");
    let (code, out, _) = aster(&["explain", "DEFI_CONTACT/ZONE/TOLE_APPA"]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with(
            "TOLE_APPA is the code_aster 11–15 name of DIST_APPA: `aster migrate` rewrites it\n"
        ),
        "{out}"
    );
    assert!(out.contains("DEFI_CONTACT/ZONE/DIST_APPA\n"), "{out}");
    let (code, out, _) = aster(&["explain", "STAT_NON_LINE/SOLVEUR/SYME"]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with("SYME is gone from code_aster 17 (the solver detects symmetry itself)"),
        "{out}"
    );
    let (code, _, err) = aster(&["explain", "STAT_NON_LINE/RESI_GLOB_RELA"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("exists as `STAT_NON_LINE/CONVERGENCE/RESI_GLOB_RELA`"),
        "{err}"
    );
}

/// `--format json`: one JSON object per file (JSON Lines), stable codes,
/// levels and positions.
#[test]
fn json_format_gives_codes_levels_and_positions() {
    let files = [
        "crates/eval/tests/errors/unknown_keyword.comm",
        "crates/eval/tests/errors/not_supported.comm",
        "comm/zzzz237b.comm",
    ];
    let mut args = vec!["check", "--format", "json"];
    args.extend(files);
    let (code, out, err) = aster(&args);
    assert_eq!(code, 1, "an error in one file: exit 1\n{err}");
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object per line"))
        .collect();
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[0]["schema_version"], 1);
    assert_eq!(lines[0]["path"], files[0]);
    assert_eq!(lines[0]["status"], "error");
    let d = &lines[0]["diagnostics"][0];
    assert_eq!(d["code"], "E-unknown-keyword");
    assert_eq!(d["level"], "error");
    assert_eq!(
        (d["line"].as_u64(), d["column"].as_u64()),
        (Some(8), Some(33))
    );
    assert!(
        d["suggestion"]
            .as_str()
            .is_some_and(|s| s.contains("GROUP_MA_ESCL")),
        "{d}"
    );
    assert_eq!(lines[1]["status"], "unsupported");
    assert_eq!(lines[1]["diagnostics"][0]["code"], "U-unsupported");
    assert_eq!(lines[1]["diagnostics"][0]["level"], "unsupported");
    assert_eq!(lines[2]["status"], "clean");
    insta::assert_snapshot!("json_format", out);
    assert!(
        err.contains("check: 1 clean, 1 with errors, 1 not supported"),
        "{err}"
    );
}

/// "Not supported" is not an error in the file: its own exit code.
#[test]
fn unsupported_only_exits_3() {
    let (code, _, err) = aster(&["check", "crates/eval/tests/errors/not_supported.comm"]);
    assert_eq!(code, 3, "{err}");
    assert!(err.contains("not supported by aster"), "{err}");
    let (code, _, _) = aster(&[
        "check",
        "crates/eval/tests/errors/not_supported.comm",
        "comm/zzzz237a.comm",
    ]);
    assert_eq!(code, 3);
    let (code, _, _) = aster(&[
        "check",
        "crates/eval/tests/errors/not_supported.comm",
        "crates/eval/tests/errors/rule_violated.comm",
    ]);
    assert_eq!(code, 1, "an error wins over unsupported");
}

#[test]
fn github_format_annotations() {
    let (code, out, _) = aster(&[
        "check",
        "--format",
        "github",
        "crates/eval/tests/errors/unknown_keyword.comm",
        "crates/eval/tests/errors/not_supported.comm",
        "crates/eval/tests/errors/legacy_v11.comm",
    ]);
    assert_eq!(code, 1);
    assert!(out.lines().all(|l| l.starts_with("::")), "{out}");
    assert!(
        out.contains("::error file=crates/eval/tests/errors/unknown_keyword.comm,line=8,col=33,"),
        "{out}"
    );
    assert!(
        out.contains("::notice file=crates/eval/tests/errors/not_supported.comm,"),
        "{out}"
    );
    insta::assert_snapshot!("github_format", out);
}

/// The SARIF log holds what the SARIF 2.1.0 schema requires of the parts
/// it uses (sarif-schema-2.1.0.json: `version` "2.1.0", `runs`, each run's
/// `tool.driver.name`, each result's `message.text`, a `level` among
/// none/note/warning/error, regions with 1-based lines and columns, a
/// `ruleIndex` pointing at the rule of the `ruleId`, unique rule ids).
#[test]
fn sarif_format_follows_the_2_1_0_schema() {
    let (code, out, _) = aster(&[
        "check",
        "--format",
        "sarif",
        "crates/eval/tests/errors/unknown_keyword.comm",
        "crates/eval/tests/errors/not_supported.comm",
        "crates/eval/tests/errors/legacy_v11.comm",
        "crates/eval/tests/errors/rule_violated.comm",
    ]);
    assert_eq!(code, 1);
    let log: serde_json::Value = serde_json::from_str(&out).expect("one JSON document");
    assert_eq!(log["version"], "2.1.0");
    let obj_keys = |v: &serde_json::Value| -> Vec<String> {
        v.as_object().expect("an object").keys().cloned().collect()
    };
    // sarifLog: additionalProperties false.
    for k in obj_keys(&log) {
        assert!(
            [
                "$schema",
                "version",
                "runs",
                "inlineExternalProperties",
                "properties"
            ]
            .contains(&k.as_str()),
            "{k}"
        );
    }
    let runs = log["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 1);
    let driver = &runs[0]["tool"]["driver"];
    assert_eq!(driver["name"], "aster");
    let rules = driver["rules"].as_array().expect("rules");
    let mut ids: Vec<&str> = rules
        .iter()
        .map(|r| r["id"].as_str().expect("id"))
        .collect();
    let n = ids.len();
    ids.sort();
    ids.dedup();
    assert_eq!(ids.len(), n, "rule ids are unique");
    let levels = ["none", "note", "warning", "error"];
    for r in rules {
        assert!(r["shortDescription"]["text"].is_string());
        assert!(levels.contains(&r["defaultConfiguration"]["level"].as_str().unwrap()));
    }
    let results = runs[0]["results"].as_array().expect("results");
    assert!(results.len() >= 4, "{out}");
    for r in results {
        assert!(r["message"]["text"].as_str().is_some_and(|t| !t.is_empty()));
        assert!(levels.contains(&r["level"].as_str().unwrap()));
        let i = r["ruleIndex"].as_u64().expect("ruleIndex") as usize;
        assert_eq!(rules[i]["id"], r["ruleId"]);
        let loc = &r["locations"][0]["physicalLocation"];
        assert!(loc["artifactLocation"]["uri"]
            .as_str()
            .is_some_and(|u| !u.contains(' ')));
        let region = &loc["region"];
        for k in ["startLine", "startColumn", "endLine", "endColumn"] {
            assert!(region[k].as_u64().is_some_and(|v| v >= 1), "{k}: {region}");
        }
        assert!(
            (region["endLine"].as_u64(), region["endColumn"].as_u64())
                > (region["startLine"].as_u64(), region["startColumn"].as_u64())
        );
    }
    let codes: Vec<&str> = results
        .iter()
        .map(|r| r["ruleId"].as_str().unwrap())
        .collect();
    assert!(codes.contains(&"E-unknown-keyword"), "{codes:?}");
    assert!(codes.contains(&"U-unsupported"), "{codes:?}");
    assert!(codes.contains(&"E-rule"), "{codes:?}");
    insta::assert_snapshot!("sarif_format", out);
}
