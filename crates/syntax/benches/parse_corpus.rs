//! Parsing throughput on the real v17 corpus (skipped when `../shared` is
//! absent) and on the project's own inputs. Run with
//! `cargo bench -p aster-syntax --bench parse_corpus`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::path::Path;

fn load(dir: &Path) -> Vec<String> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map(|rd| rd.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    files.retain(|p: &std::path::PathBuf| p.extension().is_some_and(|x| x == "comm"));
    files.sort();
    files
        .iter()
        .filter_map(|p| aster_syntax::read_source(p).ok())
        .collect()
}

fn bench(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let own = load(&root.join("tests/inputs"));
    let own_bytes: usize = own.iter().map(String::len).sum();
    let mut g = c.benchmark_group("parse");
    g.throughput(Throughput::Bytes(own_bytes as u64));
    g.bench_function("own_inputs", |b| {
        b.iter(|| {
            own.iter()
                .filter(|s| aster_syntax::parse_module(s).is_ok())
                .count()
        })
    });
    let corpus_dir = root.join("../../../shared/corpus/v17");
    if corpus_dir.exists() {
        let corpus = load(&corpus_dir);
        let bytes: usize = corpus.iter().map(String::len).sum();
        g.throughput(Throughput::Bytes(bytes as u64));
        g.sample_size(10);
        g.bench_function("corpus_v17", |b| {
            b.iter(|| {
                corpus
                    .iter()
                    .filter(|s| aster_syntax::parse_module(s).is_ok())
                    .count()
            })
        });
    } else {
        eprintln!("corpus_v17 skipped: {} not found", corpus_dir.display());
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
