//! Checking the whole v17 corpus (bar: under 5 s on one core), and the
//! part this crate owns alone: evaluation + validation of modules parsed
//! beforehand (bar: under 3 s). Skips when ../shared is absent.
//!
//! ```text
//! cargo bench -p aster-eval --bench check_corpus
//! ```

use aster_eval::{check_module, check_source};
use aster_syntax::CodeMap;
use criterion::{criterion_group, criterion_main, Criterion};
use std::path::PathBuf;

fn corpus() -> Vec<CodeMap> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/v17");
    let Ok(rd) = std::fs::read_dir(&dir) else {
        return Vec::new();
    };
    let mut files: Vec<_> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    files.sort();
    files
        .into_iter()
        .filter(|p| p.extension().is_some_and(|x| x == "comm"))
        .filter_map(|p| {
            let bytes = std::fs::read(&p).ok()?;
            let s = match String::from_utf8(bytes) {
                Ok(s) => s,
                Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
            };
            Some(CodeMap::new(p.display().to_string(), s))
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let files = corpus();
    if files.is_empty() {
        eprintln!("skipped: ../shared/corpus/v17 not found");
        return;
    }
    // Load the catalog outside the measurement (it is loaded once per process).
    let _ = aster_catalog::catalog();
    let modules: Vec<_> = files
        .iter()
        .filter_map(|m| Some((m, aster_syntax::parse_module(m.source()).ok()?)))
        .collect();
    let mut g = c.benchmark_group("check");
    g.sample_size(10);
    g.bench_function(
        format!(
            "v17 corpus, evaluate+validate only ({} parsed files)",
            modules.len()
        ),
        |b| {
            b.iter(|| {
                let mut errors = 0usize;
                for (m, module) in &modules {
                    errors += usize::from(!check_module(m, module, false).ok());
                }
                errors
            })
        },
    );
    g.bench_function(format!("v17 corpus ({} files)", files.len()), |b| {
        b.iter(|| {
            let mut errors = 0usize;
            for m in &files {
                errors += usize::from(!check_source(m, false).ok());
            }
            errors
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
