//! ZZZZ237 A end to end through the APIs: the analyses of the test file
//! (contact with VECT_MAIT='FIXE', the same restarted from it, DIST_APPA in
//! DISCRETE and in CONTINUE), 20 steps each — through fem's STAT_NON_LINE
//! with ZoneContact sources (the runner's path), and through the linear
//! contact driver. The Hertz scene (n = 30) through the linear driver.

use aster_contact::hertz::{hertz_mesh, HertzMesh};
use aster_contact::scenes::{two_blocks_mesh, two_blocks_problem};
use aster_contact::*;
use aster_fem::{
    Comp, Dof, Elastic, InitialState, Loads, Model, StaticNonLinear, UnilateralSource,
};
use criterion::{criterion_group, criterion_main, Criterion};

fn zone(dist_appa: Option<f64>, fixed: bool) -> ZoneGeometry {
    let mut g = ZoneGeometry::new("HE", "AB");
    if fixed {
        g.vect_mait = NormalSource::Fixed([0.0, 1.0, 0.0]);
    }
    if let Some(d) = dist_appa {
        g = g.with_dist_appa(d);
    }
    g
}

fn definitions() -> [ContactDefinition; 3] {
    let d = |g| {
        ContactDefinition::discrete(
            vec![Zone {
                geometry: g,
                law: DiscreteAlgo::Contrainte,
            }],
            Frottement::Sans,
        )
        .unwrap()
    };
    let c = ContactDefinition::continuous(
        vec![Zone {
            geometry: zone(Some(1.0), false),
            law: ContinueLaw::default(),
        }],
        Frottement::Sans,
    )
    .unwrap();
    [d(zone(None, true)), d(zone(Some(1.0), false)), c]
}

fn fem_path(model: &Model, loads: &Loads, defs: &[ContactDefinition; 3]) -> f64 {
    let times: Vec<f64> = (0..=20).map(|i| i as f64).collect();
    let solve = |def: &ContactDefinition, initial: Option<InitialState>| {
        let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
        let mut snl = StaticNonLinear {
            instants: times.clone(),
            initial,
            sources: zones
                .iter_mut()
                .map(|z| Box::new(z) as Box<dyn UnilateralSource>)
                .collect(),
            ..Default::default()
        };
        snl.solve(model, loads).unwrap()
    };
    let resu0 = solve(&defs[0], None);
    let init = InitialState {
        time: Some(0.0),
        displacement: resu0.steps[0].displacement.clone(),
        ..Default::default()
    };
    let resu = solve(&defs[0], Some(init));
    let ta = solve(&defs[1], None);
    let tc = solve(&defs[2], None);
    let a = model
        .dofs()
        .index(Dof::new(
            model.mesh().group_no("A").unwrap().members[0],
            Comp::DY,
        ))
        .unwrap();
    resu.steps.last().unwrap().displacement[a]
        + ta.steps.last().unwrap().displacement[a]
        + tc.steps.last().unwrap().displacement[a]
}

fn linear_path(model: &Model, loads: &Loads, defs: &[ContactDefinition; 3]) -> f64 {
    let times: Vec<f64> = (0..=20).map(|i| i as f64).collect();
    let mut s = 0.0;
    for (k, def) in [&defs[0], &defs[0], &defs[1], &defs[2]]
        .into_iter()
        .enumerate()
    {
        let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
        let r = run_linear(def, &mut zones, model, loads, &times).unwrap();
        s += k as f64 * r.last().unwrap().report.u[0];
    }
    s
}

fn hertz_problem(n: usize) -> (Model, Loads) {
    let mesh = hertz_mesh(&HertzMesh::new(50.0, 0.15, n)).unwrap();
    scenes::hertz_problem(mesh, Elastic::new(2e5, 0.3).unwrap(), 0.25).unwrap()
}

fn bench(c: &mut Criterion) {
    let (model, loads) = two_blocks_problem(two_blocks_mesh(1).unwrap(), 1e7).unwrap();
    let defs = definitions();
    c.bench_function("zzzz237a_fem_stat_non_line_4x20_steps", |b| {
        b.iter(|| fem_path(&model, &loads, &defs))
    });
    c.bench_function("zzzz237a_linear_driver_4x20_steps", |b| {
        b.iter(|| linear_path(&model, &loads, &defs))
    });
    let (hm, hl) = hertz_problem(30);
    let def = ContactDefinition::discrete(
        vec![Zone {
            geometry: ZoneGeometry::new("MAIT", "ESCL"),
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap();
    let mut group = c.benchmark_group("hertz_n30");
    group.sample_size(10);
    group.bench_function("contrainte_1_step", |b| {
        b.iter(|| {
            let mut zones = ZoneContact::build_all(&def, hm.mesh()).unwrap();
            run_linear(&def, &mut zones, &hm, &hl, &[0.0, 1.0])
                .unwrap()
                .len()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
