//! `aster run` end to end: the project's own scenes, `.export` handling,
//! exit codes, and (when ../shared is present) the real ZZZZ237 files.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/run_data")
        .join(name)
}

fn out_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-run-cli-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

struct Run {
    code: i32,
    stdout: String,
    stderr: String,
}

fn aster_run(args: &[&Path], mesh: Option<&Path>, tag: &str) -> Run {
    let out = out_dir(tag);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_aster"));
    cmd.arg("run");
    for a in args {
        cmd.arg(a);
    }
    if let Some(m) = mesh {
        cmd.arg("--mesh").arg(m);
    }
    cmd.arg("--out").arg(&out);
    let o = cmd.output().expect("aster runs");
    Run {
        code: o.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
    }
}

fn last_line(s: &str) -> &str {
    s.lines().last().unwrap_or("")
}

#[test]
fn project_scene_b_passes_every_check() {
    let r = aster_run(
        &[&root().join("comm/zzzz237b.comm")],
        Some(&root().join("comm/zzzz237.mail")),
        "b",
    );
    assert_eq!(r.code, 0, "{}\n{}", r.stdout, r.stderr);
    assert_eq!(
        last_line(&r.stdout),
        "TEST_RESU: 14 OK, 0 NOOK",
        "{}",
        r.stdout
    );
    assert!(
        r.stdout.contains("#ASTER"),
        "the table is printed:\n{}",
        r.stdout
    );
}

#[test]
fn project_scene_a_contact_passes_every_check() {
    let r = aster_run(
        &[&root().join("comm/zzzz237a.comm")],
        Some(&root().join("comm/zzzz237.mail")),
        "a",
    );
    assert_eq!(r.code, 0, "{}\n{}", r.stdout, r.stderr);
    assert_eq!(
        last_line(&r.stdout),
        "TEST_RESU: 28 OK, 0 NOOK",
        "{}",
        r.stdout
    );
}

#[test]
fn export_file_gives_the_command_file_and_the_mesh() {
    let dir = out_dir("export");
    let export = dir.join("case.export");
    std::fs::write(
        &export,
        format!(
            "P testlist verification\nF comm {} D 1\nF mail {} D 20\n",
            data("nook.comm").display(),
            data("nook.mail").display()
        ),
    )
    .unwrap();
    let r = aster_run(&[&export], None, "export");
    // One right check, one wrong: exit 1.
    assert_eq!(r.code, 1, "{}\n{}", r.stdout, r.stderr);
    assert_eq!(last_line(&r.stdout), "TEST_RESU: 1 OK, 1 NOOK");
    assert!(r.stdout.contains("NOOK  NON_REGRESSION"), "{}", r.stdout);
}

#[test]
fn mesh_beside_the_command_file_is_found() {
    // nook.mail sits beside nook.comm.
    let r = aster_run(&[&data("nook.comm")], None, "beside");
    assert_eq!(r.code, 1, "{}\n{}", r.stdout, r.stderr);
}

#[test]
fn unsupported_input_is_refused_before_anything_runs() {
    let r = aster_run(&[&data("unsupported.comm")], None, "unsupported");
    assert_eq!(r.code, 2, "{}\n{}", r.stdout, r.stderr);
    // Nothing ran: no check was printed, though TEST_RESU comes before the
    // last refused keyword.
    assert_eq!(r.stdout, "TEST_RESU: 0 OK, 0 NOOK\n");
    // Every reason at once, each at its keyword, in source order: an
    // unsupported material, a large-strain measure, a group that no mesh
    // has, and a MED output option after the solve.
    let dir = data("").display().to_string();
    insta::assert_snapshot!(r.stderr.replace(&dir, "<data>/"));
}

#[test]
fn missing_case_is_an_error() {
    let r = aster_run(&[Path::new("/nonexistent/case.comm")], None, "missing");
    assert_eq!(r.code, 2);
    assert!(r.stderr.contains("no such file"), "{}", r.stderr);
}

/// The real code_aster files, when ../shared is there.
fn shared_case(name: &str) -> Option<PathBuf> {
    let p = root().join("../shared/cases/zzzz237").join(name);
    if p.exists() {
        Some(p)
    } else {
        eprintln!("skipped: {} is absent", p.display());
        None
    }
}

#[test]
fn real_zzzz237a_all_versions() {
    // v15 adds the CALCUL → EXTR_TABLE → NUME_DDL → ASSE_VECTEUR chain,
    // v11 its CALC_VECT_ELEM ancestor and VALE_CONT.
    for (v, checks) in [("v11", 19), ("v15", 25), ("v17", 21)] {
        let (Some(comm), Some(mesh)) = (
            shared_case(&format!("zzzz237a.{v}.comm")),
            shared_case("zzzz237a.mmed"),
        ) else {
            return;
        };
        let r = aster_run(&[&comm], Some(&mesh), &format!("real-a-{v}"));
        assert_eq!(r.code, 0, "{v}:\n{}\n{}", r.stdout, r.stderr);
        assert_eq!(
            last_line(&r.stdout),
            format!("TEST_RESU: {checks} OK, 0 NOOK"),
            "{v}"
        );
    }
}

#[test]
fn real_zzzz237b_all_versions() {
    // v11 has four VALE_CALC-only checks where v15/v17 also give VALE_REFE.
    for (v, checks) in [("v11", 16), ("v15", 20), ("v17", 20)] {
        let (Some(comm), Some(mesh)) = (
            shared_case(&format!("zzzz237b.{v}.comm")),
            shared_case("zzzz237a.mmed"),
        ) else {
            return;
        };
        let r = aster_run(&[&comm], Some(&mesh), &format!("real-b-{v}"));
        assert_eq!(r.code, 0, "{v}:\n{}\n{}", r.stdout, r.stderr);
        assert_eq!(
            last_line(&r.stdout),
            format!("TEST_RESU: {checks} OK, 0 NOOK"),
            "{v}"
        );
    }
}

/// Issue 15's reproducers and the inputs the fuzzers found
/// (crates/eval/tests/crashes): `aster run` ends each with its result or
/// exit code 2 and a located message (`file:line:col`), quickly — never a
/// crash (101), an abort or a hang. Deep nesting is built here (the files
/// would be large).
#[test]
fn crash_corpus_runs_end_in_a_result_or_a_located_error() {
    let dir = root().join("crates/eval/tests/crashes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "comm"))
        .collect();
    let gen = out_dir("crash-gen");
    for (name, text) in [
        ("not.comm", format!("x = {}1\n", "not ".repeat(30_000))),
        ("attr.comm", format!("x = a{}\n", ".b".repeat(150_000))),
        (
            "elif.comm",
            format!("if 1:\n    pass\n{}", "elif 1:\n    pass\n".repeat(87_000)),
        ),
    ] {
        let p = gen.join(name);
        std::fs::write(&p, text).unwrap();
        files.push(p);
    }
    files.sort();
    assert!(files.len() > 10);
    for f in &files {
        let t = std::time::Instant::now();
        let r = aster_run(&[f.as_path()], None, "crash");
        assert!(
            t.elapsed().as_secs_f64() < 10.0,
            "{}: {:?}",
            f.display(),
            t.elapsed()
        );
        match r.code {
            0 => {}
            2 => {
                let name = f.file_name().unwrap().to_string_lossy().to_string();
                let all = format!("{}{}", r.stdout, r.stderr);
                assert!(
                    all.contains(&format!("{name}:")),
                    "{name}: no location in\n{all}"
                );
            }
            c => panic!("{}: exit {c}\n{}{}", f.display(), r.stdout, r.stderr),
        }
    }
}

/// Replaces every `"seconds": <number>` and `time="<number>"` by a fixed
/// text: run times differ from run to run.
fn without_times(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let mut l = line.to_string();
        for key in ["\"seconds\": ", "time=\""] {
            if let Some(i) = l.find(key) {
                let start = i + key.len();
                let end = l[start..]
                    .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
                    .map_or(l.len(), |e| start + e);
                l.replace_range(start..end, "T");
            }
        }
        out.push_str(&l);
        out.push('\n');
    }
    out
}

#[test]
fn json_report_has_every_check_and_command() {
    let out = out_dir("report-json");
    let report = out.join("report.json");
    let o = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(root().join("comm/zzzz237b.comm"))
        .arg("--mesh")
        .arg(root().join("comm/zzzz237.mail"))
        .arg("--out")
        .arg(&out)
        .args(["-q", "--report", "json"])
        .arg(&report)
        .output()
        .expect("aster runs");
    assert_eq!(o.status.code(), Some(0));
    assert!(o.stderr.is_empty(), "-q: no progress");
    let text = std::fs::read_to_string(&report).expect("the report is written");
    let v: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    assert_eq!(v["summary"]["ok"], 14);
    assert_eq!(v["summary"]["nook"], 0);
    let checks = v["checks"].as_array().unwrap();
    assert_eq!(checks.len(), 14);
    for c in checks {
        assert_eq!(c["verdict"], "OK");
        assert!(c["file"].as_str().unwrap().ends_with("comm/zzzz237b.comm"));
        assert!(c["line"].as_u64().unwrap() > 1);
        let err = c["error"].as_f64().unwrap();
        assert!(err <= c["tolerance"].as_f64().unwrap(), "{c}");
    }
    let commands = v["commands"].as_array().unwrap();
    assert!(commands
        .iter()
        .any(|c| c["command"] == "STAT_NON_LINE" && c["result"] == "resu"));
    let dir = root().join("comm").canonicalize().unwrap();
    let shown = without_times(&text)
        .replace(&root().join("comm").display().to_string(), "<comm>")
        .replace(&dir.display().to_string(), "<comm>");
    insta::assert_snapshot!(shown);
}

#[test]
fn junit_report_marks_nook_as_failures() {
    let out = out_dir("report-junit");
    let report = out.join("report.xml");
    let o = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(data("nook.comm"))
        .arg("--out")
        .arg(&out)
        .args(["-q", "--report", "junit"])
        .arg(&report)
        .output()
        .expect("aster runs");
    assert_eq!(o.status.code(), Some(1));
    let text = std::fs::read_to_string(&report).expect("the report is written");
    assert!(text.contains("<failure type=\"NOOK\""), "{text}");
    assert!(text.contains("tests=\"2\" failures=\"1\""), "{text}");
    let shown = without_times(&text).replace(&data("").display().to_string(), "<data>/");
    insta::assert_snapshot!(shown);
}

#[test]
fn default_out_is_a_fresh_case_folder_and_progress_is_live() {
    let cwd = out_dir("default-out");
    let o = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(root().join("comm/zzzz237a.comm"))
        .arg("--mesh")
        .arg(root().join("comm/zzzz237.mail"))
        .current_dir(&cwd)
        .output()
        .expect("aster runs");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{stderr}");
    assert!(cwd.join("zzzz237a-out").is_dir());
    let stray: Vec<_> = std::fs::read_dir(&cwd)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("fort."))
        .collect();
    assert!(stray.is_empty(), "{stray:?}");
    // One line per command with its time, a table per increment.
    assert!(stderr.contains("= STAT_NON_LINE"), "{stderr}");
    assert!(stderr.contains("| RESI_GLOB_RELA |"), "{stderr}");
    assert!(stderr.contains("converged in"), "{stderr}");
    let commands = stderr.lines().filter(|l| l.contains(" s  ")).count();
    assert!(commands > 10, "{stderr}");
}

#[test]
fn mess_file_of_the_export_gets_the_progress() {
    let dir = out_dir("mess");
    let export = dir.join("case.export");
    std::fs::write(
        &export,
        format!(
            "P testlist verification\nF comm {} D 1\nF mail {} D 20\nF mess {} R 6\n",
            root().join("comm/zzzz237b.comm").display(),
            root().join("comm/zzzz237.mail").display(),
            dir.join("case.mess").display(),
        ),
    )
    .unwrap();
    let out = dir.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(&export)
        .arg("--out")
        .arg(&out)
        .arg("-q")
        .output()
        .expect("aster runs");
    assert_eq!(o.status.code(), Some(0));
    let mess = std::fs::read_to_string(out.join("case.mess")).expect("the .mess is written");
    assert!(mess.contains("= STAT_NON_LINE"), "{mess}");
    assert!(mess.contains("| RESI_GLOB_RELA |"), "{mess}");
    assert!(mess.contains("TEST_RESU: 14 OK, 0 NOOK"), "{mess}");
}

/// The live progress as a snapshot: a line per command, a code_aster-style
/// table per increment. Times are masked, and so are the residuals of rows
/// at round-off (relative residual below 1e-6: they depend on the order of
/// floating-point sums, which the SIMD path of the CPU decides).
#[test]
fn progress_table_snapshot() {
    let cwd = out_dir("progress-snapshot");
    let o = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg("comm/zzzz237a.comm")
        .arg("--mesh")
        .arg("comm/zzzz237.mail")
        .arg("--out")
        .arg(&cwd)
        .current_dir(root())
        .env_remove("CLICOLOR_FORCE")
        .output()
        .expect("aster runs");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{stderr}");
    let mask = |line: &str| -> String {
        let mut words: Vec<String> = Vec::new();
        let cells: Vec<&str> = line.split('|').collect();
        if cells.len() == 8 && cells[1].trim().parse::<u32>().is_ok() {
            // | iter | RESI_RELA | RESI_MAXI | contact | pairings | time |
            // A row at round-off (relative residual below 1e-6): both
            // residuals masked.
            let converged = cells[2].trim().parse::<f64>().is_ok_and(|v| v.abs() < 1e-6);
            for (i, c) in cells.iter().enumerate() {
                let masked = match i {
                    2 | 3 if converged => format!("{:>w$}", "round-off ", w = c.len()),
                    6 => format!("{:>w$}", "T ", w = c.len()),
                    _ => c.to_string(),
                };
                words.push(masked);
            }
            return words.join("|");
        }
        // `name = COMMAND   0.003 s  file:line:col`
        match line.find(" s  ") {
            Some(p) => {
                let start = line[..p].rfind(' ').map_or(0, |s| s + 1);
                format!("{}T{}", &line[..start], &line[p..])
            }
            None => line.to_string(),
        }
    };
    let shown: Vec<String> = stderr.lines().map(mask).collect();
    insta::assert_snapshot!(shown.join("\n"));
}
