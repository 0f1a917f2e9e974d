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
