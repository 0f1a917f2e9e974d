//! Reading a 1-million-node MED mesh (written by our own writer): the bar is < 1 s.

use aster_mesh::{read_med, write_med};
use criterion::{criterion_group, criterion_main, Criterion};
use std::time::Duration;

mod grid;
use grid::grid;

fn bench(c: &mut Criterion) {
    let mesh = grid(1000);
    let path = std::env::temp_dir().join(format!("aster-bench-1M-{}.med", std::process::id()));
    if let Err(e) = write_med(&path, &mesh, "GRID", &[]) {
        eprintln!("cannot write the benchmark mesh: {e}");
        return;
    }
    let mut g = c.benchmark_group("med");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    // Dropping the mesh (3 million allocations) is not reading it: outputs
    // are dropped outside the timed region.
    g.bench_function("read_1M_nodes", |b| {
        b.iter_with_large_drop(|| {
            let m = read_med(&path).expect("benchmark mesh reads");
            assert_eq!(m.node_count(), 1_000_000);
            m
        })
    });
    g.bench_function("write_1M_nodes", |b| {
        b.iter(|| aster_mesh::med_bytes(&mesh, "GRID", &[]).expect("writes"))
    });
    g.finish();
    let _ = std::fs::remove_file(&path);
}

criterion_group!(benches, bench);
criterion_main!(benches);
