//! The hot paths the Hertz study shows: stiffness assembly, the sparse
//! factorisation, and one whole contact run per method family.
//! Throughputs (DOFs per second) are reported by criterion.

use aster_contact::FactorizedStiffness;
use aster_fem::assembly::assemble_stiffness;
use aster_study::scenes::hertz::Hertz;
use aster_study::{Method, MethodFamily, Point, Scene};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::collections::BTreeMap;

fn hertz() -> Hertz {
    match Hertz::from_params(&BTreeMap::new()) {
        Ok(h) => h,
        Err(e) => panic!("default Hertz scene: {e}"),
    }
}

fn linear_algebra(c: &mut Criterion) {
    let scene = hertz();
    for n in [16usize, 64] {
        let Ok((model, loads)) = scene.problem(n) else {
            panic!("Hertz problem n = {n}");
        };
        let mut g = c.benchmark_group(format!("hertz n={n} ({} dofs)", model.dofs().len()));
        g.sample_size(10);
        g.throughput(Throughput::Elements(model.dofs().len() as u64));
        g.bench_function("assembly", |b| {
            b.iter(|| assemble_stiffness(&model).map(|k| k.n))
        });
        g.bench_function("assembly + factorisation", |b| {
            b.iter(|| FactorizedStiffness::new(&model, &loads).is_ok())
        });
        g.finish();
    }
}

fn contact_runs(c: &mut Criterion) {
    let scene = hertz();
    let mut g = c.benchmark_group("hertz n=32 run");
    g.sample_size(10);
    for (family, coef) in [
        (MethodFamily::DiscreteContrainte, None),
        (MethodFamily::DiscretePenalisation, Some(1e9)),
        (MethodFamily::DiscreteGcp, None),
        (MethodFamily::ContinuousStandard, None),
    ] {
        let Ok(method) = Method::new(family, coef) else {
            panic!("method {family}");
        };
        let point = Point {
            index: 0,
            method,
            refine: 32,
            stiffness_ratio: 1.0,
            steps: 1,
        };
        g.bench_function(method.label(), |b| b.iter(|| scene.run(&point).is_ok()));
    }
    g.finish();
}

criterion_group!(benches, linear_algebra, contact_runs);
criterion_main!(benches);
