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
        assert_eq!(json["schema_version"], 1);
        assert_eq!(json["kind"], "commands");
        assert_eq!(json["path"], scene);
        insta::assert_snapshot!(name, out);
    }
}

/// `--emit commands --compact --no-defaults`: JSON Lines, one object per
/// file; only the keywords written, each with its line and column.
#[test]
fn emitted_commands_compact_without_defaults() {
    let dir = std::env::temp_dir().join(format!("aster-emit-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let (a, b) = (dir.join("a.comm"), dir.join("b.comm"));
    let _ = std::fs::write(
        &a,
        "DEBUT()\nMAT = DEFI_MATERIAU(\n    ELAS=_F(E=2.0e5, NU=0.3))\nFIN()\n",
    );
    let _ = std::fs::write(&b, "DEBUT()\nFIN()\n");
    let (a, b) = (a.display().to_string(), b.display().to_string());
    let (code, out, err) = aster(&[
        "check",
        "--emit",
        "commands",
        "--compact",
        "--no-defaults",
        &a,
        &b,
    ]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object per line"))
        .collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert_eq!(lines[0]["path"], a.as_str());
    assert_eq!(lines[1]["path"], b.as_str());
    let mat = &lines[0]["commands"][1];
    assert_eq!(mat["command"], "DEFI_MATERIAU");
    assert_eq!((&mat["line"], &mat["column"]), (&2.into(), &7.into()));
    assert_eq!(
        (&mat["end_line"], &mat["end_column"]),
        (&3.into(), &30.into())
    );
    let elas = &mat["keywords"][0];
    assert_eq!(elas["name"], "ELAS");
    assert_eq!(mat["keywords"].as_array().map(Vec::len), Some(1), "{mat}");
    let occ = &elas["value"]["value"][0];
    let names: Vec<&str> = occ
        .as_array()
        .map(|o| o.iter().filter_map(|k| k["name"].as_str()).collect())
        .unwrap_or_default();
    assert_eq!(names, ["E", "NU"], "defaults left out: {occ}");
    assert_eq!(
        (&occ[1]["line"], &occ[1]["column"]),
        (&3.into(), &22.into())
    );
    // With the defaults they are there, flagged and without a position.
    let (_, full, _) = aster(&["check", "--emit", "commands", "--compact", &a]);
    let full: serde_json::Value =
        serde_json::from_str(full.lines().next().unwrap_or("")).expect("JSON");
    let occ = &full["commands"][1]["keywords"][0]["value"]["value"][0];
    let defaulted: Vec<&serde_json::Value> = occ
        .as_array()
        .map(|o| o.iter().filter(|k| k["defaulted"] == true).collect())
        .unwrap_or_default();
    assert!(!defaulted.is_empty(), "{occ}");
    assert!(defaulted.iter().all(|k| k.get("line").is_none()), "{occ}");
    // The shaping options need --emit.
    let (code, _, _) = aster(&["check", "--compact", &a]);
    assert_eq!(code, 2);
    let _ = std::fs::remove_dir_all(&dir);
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

/// The JSON Schema of docs/json.md holds for what `--emit commands` prints:
/// every `required` field of the envelope, of each command, keyword and
/// scalar is there, and scalar tags are the listed ones.
#[test]
fn emitted_commands_follow_the_documented_schema() {
    let Ok(doc) = std::fs::read_to_string(root().join("docs/json.md")) else {
        eprintln!("skipped: docs/json.md not found");
        return;
    };
    let section = doc.split("## `kind: \"commands\"`").nth(1).unwrap_or("");
    let block = section
        .split("```json")
        .nth(1)
        .and_then(|b| b.split("```").next());
    let schema: serde_json::Value = serde_json::from_str(block.unwrap_or(""))
        .expect("the schema block of docs/json.md is JSON");
    let required = |v: &serde_json::Value| -> Vec<String> {
        v["required"]
            .as_array()
            .map(|r| {
                r.iter()
                    .filter_map(|s| s.as_str().map(String::from))
                    .collect()
            })
            .unwrap_or_default()
    };
    let defs = &schema["$defs"];
    let tags: Vec<&str> = defs["scalar"]["properties"]["t"]["enum"]
        .as_array()
        .map(|e| e.iter().filter_map(|s| s.as_str()).collect())
        .unwrap_or_default();
    assert!(tags.contains(&"Real") && !required(&defs["command"]).is_empty());
    fn keywords(
        list: &serde_json::Value,
        kw_req: &[String],
        scalar_req: &[String],
        tags: &[&str],
        seen: &mut usize,
    ) {
        for kw in list.as_array().into_iter().flatten() {
            *seen += 1;
            for r in kw_req {
                assert!(kw.get(r).is_some(), "keyword without `{r}`: {kw}");
            }
            let value = &kw["value"];
            match value["kind"].as_str() {
                Some("Simple") => {
                    for s in value["value"].as_array().into_iter().flatten() {
                        for r in scalar_req {
                            assert!(s.get(r).is_some(), "scalar without `{r}`: {s}");
                        }
                        assert!(tags.contains(&s["t"].as_str().unwrap_or("")), "{s}");
                    }
                }
                Some("Factor") => {
                    for occ in value["value"].as_array().into_iter().flatten() {
                        keywords(occ, kw_req, scalar_req, tags, seen);
                    }
                }
                other => panic!("keyword value kind {other:?}: {kw}"),
            }
        }
    }
    let (code, out, err) = aster(&[
        "check",
        "--emit",
        "commands",
        "--compact",
        "comm/zzzz237a.comm",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("one object");
    for r in required(&schema) {
        assert!(v.get(&r).is_some(), "envelope without `{r}`");
    }
    assert_eq!(
        v["schema_version"],
        schema["properties"]["schema_version"]["const"]
    );
    let (mut seen, kw_req, sc_req) = (0, required(&defs["keyword"]), required(&defs["scalar"]));
    for c in v["commands"].as_array().into_iter().flatten() {
        for r in required(&defs["command"]) {
            assert!(c.get(&r).is_some(), "command without `{r}`: {c}");
        }
        keywords(&c["keywords"], &kw_req, &sc_req, &tags, &mut seen);
    }
    assert!(seen > 100, "{seen} keywords");
}

/// Colour only on a terminal: piped output (as here) has no escape codes;
/// `CLICOLOR_FORCE=1` colours the same text, `NO_COLOR` wins over it.
#[test]
fn diagnostics_are_coloured_only_when_asked_or_on_a_terminal() {
    let file = "crates/eval/tests/errors/unknown_keyword.comm";
    let run = |env: &[(&str, &str)]| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_aster"));
        c.args(["check", file]).current_dir(root());
        c.env_remove("NO_COLOR").env_remove("CLICOLOR_FORCE");
        for (k, v) in env {
            c.env(k, v);
        }
        let out = c.output().expect("run aster");
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let plain = run(&[]);
    assert!(!plain.contains('\u{1b}'), "{plain:?}");
    assert!(plain.contains(":8:33: error: "), "{plain}");
    let forced = run(&[("CLICOLOR_FORCE", "1")]);
    assert!(
        forced.contains("\u{1b}[1m\u{1b}[31merror\u{1b}[0m"),
        "{forced:?}"
    );
    let stripped: String = {
        let mut out = String::new();
        let mut chars = forced.chars();
        while let Some(c) = chars.next() {
            if c == '\u{1b}' {
                for d in chars.by_ref() {
                    if d == 'm' {
                        break;
                    }
                }
            } else {
                out.push(c);
            }
        }
        out
    };
    assert_eq!(stripped, plain);
    let no_color = run(&[("CLICOLOR_FORCE", "1"), ("NO_COLOR", "1")]);
    assert_eq!(no_color, plain);
}
