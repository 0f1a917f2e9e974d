//! The hot paths the Hertz study shows: stiffness assembly, the sparse
//! factorisation alone, pairing with its contact rows, and one whole
//! contact run per method family. Throughputs (DOFs per second) are
//! reported by criterion. faer runs sequentially, as in the study, and the
//! time criterion sees is the thread's CPU time (`iter_custom`), like the
//! study's: wall time on the shared build machine varied by 3×.

use aster_contact::{positions, FactorizedStiffness, ZoneContact};
use aster_fem::assembly::assemble_stiffness;
use aster_study::clock::{cpu_now, cpu_since};
use aster_study::scenes::driver;
use aster_study::scenes::hertz::Hertz;
use aster_study::{Method, MethodFamily, Point, Scene};
use criterion::{criterion_group, criterion_main, Bencher, Criterion, Throughput};
use std::collections::BTreeMap;
use std::time::Duration;

/// Runs `f` `iters` times and reports the CPU time it took.
fn cpu_iter<T>(b: &mut Bencher, mut f: impl FnMut() -> T) {
    b.iter_custom(|iters| {
        let start = cpu_now();
        for _ in 0..iters {
            std::hint::black_box(f());
        }
        Duration::from_secs_f64(cpu_since(start))
    })
}

fn hertz() -> Hertz {
    aster_study::clock::run_sequentially();
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
        let Ok(k) = assemble_stiffness(&model) else {
            panic!("assembly n = {n}");
        };
        let mut g = c.benchmark_group(format!("hertz n={n} ({} dofs)", model.dofs().len()));
        g.sample_size(10);
        g.throughput(Throughput::Elements(model.dofs().len() as u64));
        g.bench_function("assembly", |b| {
            cpu_iter(b, || assemble_stiffness(&model).map(|k| k.n))
        });
        g.bench_function("factorisation", |b| {
            cpu_iter(b, || {
                FactorizedStiffness::from_assembled(&model, &loads, k.clone()).is_ok()
            })
        });
        g.finish();
    }
}

fn pairing(c: &mut Criterion) {
    let scene = hertz();
    let mut g = c.benchmark_group("hertz pairing + rows");
    g.sample_size(20);
    for n in [16usize, 64] {
        let Ok((model, _)) = scene.problem(n) else {
            panic!("Hertz problem n = {n}");
        };
        let Ok(method) = Method::new(MethodFamily::DiscreteContrainte, None) else {
            panic!("method");
        };
        let Ok(def) = driver::definition(&method, "MAIT", "ESCL", None) else {
            panic!("definition");
        };
        let Ok(mut zones) = ZoneContact::build_all(&def, model.mesh()) else {
            panic!("zones");
        };
        let x = positions(model.mesh(), model.dofs(), &vec![0.0; model.dofs().len()]);
        g.throughput(Throughput::Elements(zones[0].zone.slave_nodes.len() as u64));
        g.bench_function(format!("n={n}"), |b| {
            cpu_iter(b, || zones[0].pair(model.mesh(), &x).map(|r| r.len()))
        });
    }
    g.finish();
}

fn contact_runs(c: &mut Criterion) {
    let scene = hertz();
    for refine in [16, 32] {
        let mut g = c.benchmark_group(format!("hertz n={refine} run"));
        g.sample_size(10);
        for (family, coef) in [
            (MethodFamily::DiscreteContrainte, None),
            (MethodFamily::DiscretePenalisation, Some(1e9)),
            (MethodFamily::DiscreteGcp, None),
            (MethodFamily::ContinuousStandard, None),
            (MethodFamily::ContinuousPenalisation, Some(1e8)),
            (MethodFamily::LiaisonUnil, None),
        ] {
            let Ok(method) = Method::new(family, coef) else {
                panic!("method {family}");
            };
            let point = Point {
                index: 0,
                method,
                refine,
                stiffness_ratio: 1.0,
                steps: 1,
                coulomb: 0.0,
            };
            g.bench_function(method.label(), |b| {
                cpu_iter(b, || scene.run(&point).is_ok())
            });
        }
        g.finish();
    }
}

criterion_group!(benches, linear_algebra, pairing, contact_runs);
criterion_main!(benches);
