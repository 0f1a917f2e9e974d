//! SSNP121 B and C (code_aster's two plates in contact, slave EF on master
//! AB, DDL_IMPO on CD and GH) on the real mesh (../shared, skipped when
//! absent), through fem's STAT_NON_LINE: the DEPL values of the TEST_RESU.

use std::path::Path;

use aster_contact::*;
use aster_fem::{
    Comp, Dof, Elastic, Element, ElementKind, Hypothesis, Load, Loads, Model, Multiplier,
    StaticNonLinear, UnilateralSource,
};
use aster_mesh::CellType;

fn problem() -> Option<(Model, Loads)> {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/cases/ssnp121b/ssnp121a.mmed");
    if !path.exists() {
        eprintln!("skipped: {} not found", path.display());
        return None;
    }
    let mut mesh = aster_mesh::read_med(&path).unwrap();
    for g in ["AB", "CD", "EF", "FG", "GH", "HE"] {
        let cells = mesh.group_ma(g).unwrap().members.clone();
        let nodes = mesh.nodes_of_cells(&cells);
        mesh.set_group_no(g, nodes);
    }
    let material = Elastic::new(2e6, 0.0).unwrap();
    let elements = (0..mesh.cells.len())
        .map(|i| {
            let cell = aster_mesh::CellId(i as u32);
            let kind = match mesh.cells[i].ty {
                CellType::SEG2 | CellType::SEG3 | CellType::POI1 => ElementKind::Boundary,
                _ => ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material,
                },
            };
            Element { cell, kind }
        })
        .collect();
    let mut loads = Loads::new();
    let ramp = || Multiplier::from_fn(Ok);
    for (g, dy) in [("CD", -0.1), ("GH", 0.0)] {
        for &n in &mesh.group_no(g).unwrap().members {
            loads.add(
                Load::Imposed {
                    dof: Dof::new(n, Comp::DX),
                    value: 0.0,
                },
                ramp(),
            );
            loads.add(
                Load::Imposed {
                    dof: Dof::new(n, Comp::DY),
                    value: dy,
                },
                ramp(),
            );
        }
    }
    Some((Model::new(mesh, elements).unwrap(), loads))
}

fn dy(model: &Model, u: &[f64], group: &str) -> f64 {
    let n = model.mesh().group_no(group).unwrap().members[0];
    u[model.dofs().index(Dof::new(n, Comp::DY)).unwrap()]
}

#[test]
fn ssnp121_b_and_c_displacements() {
    let Some((model, loads)) = problem() else {
        return;
    };
    // With code_aster's geometric loop (REAC_GEOM='AUTOMATIQUE': stop when
    // the displacement changes by less than RESI_GEOM = 1 % between two
    // pairings, here after the second one) the non-regression values are
    // reproduced at TEST_RESU's 1e-6. B: CONTRAINTE, C: PENALISATION E_N = 1e7.
    for (algo, expected) in [
        (
            DiscreteAlgo::Contrainte,
            [-0.050173429, -0.049166893, -0.049166893],
        ),
        (
            DiscreteAlgo::Penalisation { e_n: 1e7 },
            [-0.051060634, -0.049650696, -0.049650696],
        ),
    ] {
        let def = ContactDefinition::discrete(
            vec![Zone {
                geometry: ZoneGeometry::new("AB", "EF"),
                law: algo,
            }],
            Frottement::Sans,
        )
        .unwrap();
        let mut zones = ZoneContact::build_all(&def, model.mesh()).unwrap();
        let mut snl = StaticNonLinear {
            instants: vec![0.0, 1.0],
            sources: zones
                .iter_mut()
                .map(|z| Box::new(z) as Box<dyn UnilateralSource>)
                .collect(),
            ..Default::default()
        };
        let res = snl.solve(&model, &loads).unwrap();
        let u = &res.last().unwrap().displacement;
        for (g, calc) in ["N14", "A", "B"].into_iter().zip(expected) {
            let got = dy(&model, u, g);
            eprintln!("{algo:?}: DY({g}) = {got:.9} (code_aster {calc})");
            assert!((got - calc).abs() < 1e-6 * calc.abs(), "DY({g}) = {got}");
        }
        drop(snl);
        assert_eq!(zones[0].geom_pairings(), 2);
    }
}
