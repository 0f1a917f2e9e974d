//! The whole `aster` process, as an editor integration or a pre-commit hook
//! sees it (issue 19, "instant start"): the process floor (`--version`),
//! `aster check` of one command file, and `aster run` of the seed scenes
//! (the project's ZZZZ237 A and B: two and one elements), each a fresh
//! process; with `../shared` beside the repository, also the real
//! `zzzz237a.v17.export` and `zzzz237b.v17.export` (21 and 20 TEST_RESU,
//! the bar of issue 19), skipped when it is absent.
//!
//! ```text
//! cargo bench -p aster-cli --bench start
//! ```

use criterion::{criterion_group, criterion_main, Criterion};
use std::path::PathBuf;
use std::process::{Command, Stdio};

fn aster(args: &[&str]) {
    let status = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .expect("aster starts");
    assert!(status.success(), "aster {args:?}: {status}");
}

fn start(c: &mut Criterion) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let comm = root.join("comm/zzzz237b.comm").display().to_string();
    let mesh = root.join("comm/zzzz237.mail").display().to_string();
    let out = std::env::temp_dir().join("aster-bench-start");
    let out = out.display().to_string();
    let mut g = c.benchmark_group("process");
    g.bench_function("aster --version", |b| b.iter(|| aster(&["--version"])));
    g.bench_function("aster check zzzz237b.comm", |b| {
        b.iter(|| aster(&["check", &comm]))
    });
    g.bench_function("aster run zzzz237b.comm", |b| {
        b.iter(|| aster(&["run", &comm, "--mesh", &mesh, "--out", &out, "-q"]))
    });
    let comm_a = root.join("comm/zzzz237a.comm").display().to_string();
    g.bench_function("aster run zzzz237a.comm", |b| {
        b.iter(|| aster(&["run", &comm_a, "--mesh", &mesh, "--out", &out, "-q"]))
    });
    let shared = root.join("../shared/cases/zzzz237");
    for case in ["zzzz237a", "zzzz237b"] {
        let export = shared.join(format!("{case}.v17.export"));
        if !export.exists() {
            eprintln!("skipped: {} not found", export.display());
            continue;
        }
        let export = export.display().to_string();
        g.bench_function(format!("aster run {case}.v17.export (shared)"), |b| {
            b.iter(|| aster(&["run", &export, "--out", &out, "-q"]))
        });
    }
    g.finish();
}

criterion_group!(benches, start);
criterion_main!(benches);
