//! Assembling and factorising a 2D plane-strain QUAD4 problem (issue 5's
//! speed bar: 1 million DOFs under 5 s on 2 cores, under 4 GB).
//!
//! `cargo bench -p aster-fem --bench assembly` runs 100k DOFs;
//! `ASTER_BENCH_1M=1 cargo bench -p aster-fem --bench assembly` adds the
//! 1M-DOF case (n = 707). Each iteration builds the pattern, assembles,
//! eliminates the clamped edge, factorises and solves once.

use aster_fem::assembly::{assemble_stiffness_into, restrict_owned, stiffness_pattern};
use aster_fem::linalg;
use aster_fem::scenes::{free_coords, quad4_grid};
use aster_fem::Model;
use criterion::{criterion_group, criterion_main, Criterion};
use std::time::Duration;

fn assemble_and_factorise(model: &Model, map: &[usize], coords: &[[f64; 3]]) -> f64 {
    let mut k = stiffness_pattern(model);
    if let Err(e) = assemble_stiffness_into(model, &mut k) {
        panic!("the benchmark grid assembles: {e}");
    }
    let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
    let kff = restrict_owned(k, map, nfree);
    let mut b = vec![0.0; nfree];
    b[nfree - 1] = 1e6;
    match linalg::solve_with(&kff, &b, nfree, true, Some(coords)) {
        Ok(r) => r.x[nfree - 1],
        Err(f) => panic!("the benchmark grid solves: {f:?}"),
    }
}

fn bench(c: &mut Criterion) {
    let sizes: &[usize] = if std::env::var_os("ASTER_BENCH_1M").is_some() {
        &[224, 707]
    } else {
        &[224]
    };
    let mut g = c.benchmark_group("plane_strain_quad4");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(20));
    for &n in sizes {
        let (model, map) = match quad4_grid(n) {
            Ok(m) => m,
            Err(e) => panic!("the benchmark grid is valid: {e}"),
        };
        let dofs = model.dofs().len();
        let coords = free_coords(&model, &map);
        g.bench_function(format!("assemble+factorise {dofs} dofs"), |bch| {
            bch.iter(|| assemble_and_factorise(&model, &map, &coords))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
