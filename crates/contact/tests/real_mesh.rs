//! ZZZZ237 A on code_aster's own mesh (../shared, skipped when absent):
//! the three analyses of zzzz237a.v17.comm through the contact API and
//! fem's STAT_NON_LINE, checked against the file's TEST_RESU values.

use std::path::Path;

use aster_contact::scenes::two_blocks_problem;
use aster_contact::*;
use aster_fem::{post, Comp, Dof, Model, NonLinearResult, StaticNonLinear, UnilateralSource};

fn mesh() -> Option<aster_mesh::Mesh> {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/cases/zzzz237/zzzz237a.mmed");
    if !path.exists() {
        eprintln!("skipped: {} not found", path.display());
        return None;
    }
    let mut mesh = aster_mesh::read_med(&path).unwrap();
    mesh.crea_group_no_tout_group_ma();
    Some(mesh)
}

fn run(model: &Model, loads: &aster_fem::Loads, def: &ContactDefinition) -> NonLinearResult {
    let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
    let mut snl = StaticNonLinear {
        instants: (0..=20).map(|i| i as f64).collect(),
        sources: zones
            .iter_mut()
            .map(|z| Box::new(z) as Box<dyn UnilateralSource>)
            .collect(),
        ..Default::default()
    };
    snl.solve(model, loads).unwrap()
}

fn value(model: &Model, res: &NonLinearResult, group: &str, comp: Comp) -> f64 {
    let n = model.mesh().group_no(group).unwrap().members[0];
    res.last().unwrap().displacement[model.dofs().index(Dof::new(n, comp)).unwrap()]
}

#[test]
fn zzzz237a_on_the_real_mesh() {
    let Some(mesh) = mesh() else { return };
    let (model, loads) = two_blocks_problem(mesh, 1e7).unwrap();
    let zone = |d: Option<f64>, fixed: bool| {
        let mut g = ZoneGeometry::new("HE", "AB");
        if fixed {
            g.vect_mait = NormalSource::Fixed([0.0, 1.0, 0.0]);
        }
        if let Some(d) = d {
            g = g.with_dist_appa(d);
        }
        g
    };
    let cont = ContactDefinition::discrete(
        vec![Zone {
            geometry: zone(None, true),
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap();
    let res = run(&model, &loads, &cont);
    // TEST_RESU (CRITERE='ABSOLU', TOLE_MACHINE 1e-6).
    for (g, calc) in [("A", -9.14285676e-07), ("B", -9.14285664e-07)] {
        let dy = value(&model, &res, g, Comp::DY);
        eprintln!("DY({g}) = {dy:.9e} (code_aster {calc:e})");
        assert!((dy - calc).abs() < 1e-6, "DY({g}) = {dy}");
    }
    for (g, refe) in [("A", -4.28571), ("B", 4.28571)] {
        let dx = value(&model, &res, g, Comp::DX);
        eprintln!("DX({g}) = {dx:.9}");
        assert!((dx - refe).abs() < 1e-3 * 4.28571, "DX({g}) = {dx}");
    }
    let f = post::forc_noda(&model, &res.last().unwrap().displacement).unwrap();
    for g in ["A", "B"] {
        let n = model.mesh().group_no(g).unwrap().members[0];
        let fy = f[model.dofs().index(Dof::new(n, Comp::DY)).unwrap()];
        eprintln!("FORC_NODA DY({g}) = {fy:.6e}");
        assert!((fy - 2.1978e10).abs() < 1e-3 * 2.1978e10);
    }
    let ta = ContactDefinition::discrete(
        vec![Zone {
            geometry: zone(Some(1.0), false),
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap();
    let tc = ContactDefinition::continuous(
        vec![Zone {
            geometry: zone(Some(1.0), false),
            law: ContinueLaw::default(),
        }],
        Frottement::Sans,
    )
    .unwrap();
    for def in [ta, tc] {
        let res = run(&model, &loads, &def);
        for g in ["A", "B"] {
            assert!((value(&model, &res, g, Comp::DY) - -20.0).abs() < 1e-6);
        }
    }
}
