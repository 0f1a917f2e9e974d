//! SSNP121 D–K (code_aster's two blocks of PENTA15 pressed together, 3D):
//! continuous contact between TRIA6 faces on the real mesh (../shared,
//! skipped when absent), through fem's STAT_NON_LINE. The blocks are
//! pressed by DZ = −0.1 (E = 2e6, ν = 0): the interface moves by −0.05 and
//! the contact pressure is uniform, LAGS_C = −1e5 on every slave node —
//! corners (which carry the pressure of TRIA6 faces) and mid-side nodes.

use std::path::Path;

use aster_contact::*;
use aster_fem::{
    Comp, Dof, Elastic, Element, ElementKind, Hypothesis, Load, Loads, Model, Multiplier,
    StaticNonLinear, UnilateralSource,
};

fn problem() -> Option<(Model, Loads)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes/ssnp121e.mmed");
    if !path.exists() {
        eprintln!("skipped: {} not found", path.display());
        return None;
    }
    let mut mesh = aster_mesh::read_med(&path).unwrap();
    for g in ["SURESC", "SURMAI", "SURCHA", "ENCAST"] {
        let cells = mesh.group_ma(g).unwrap().members.clone();
        let nodes = mesh.nodes_of_cells(&cells);
        mesh.set_group_no(g, nodes);
    }
    let material = Elastic::new(2e6, 0.0).unwrap();
    let mut elements = Vec::new();
    for g in ["V1", "V2"] {
        for &cell in &mesh.group_ma(g).unwrap().members {
            elements.push(Element {
                cell,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::Solid3D,
                    material,
                },
            });
        }
    }
    let mut loads = Loads::new();
    for (g, dz) in [("SURCHA", -0.1), ("ENCAST", 0.0)] {
        for &n in &mesh.group_no(g).unwrap().members {
            for (comp, v) in [(Comp::DX, 0.0), (Comp::DY, 0.0), (Comp::DZ, dz)] {
                loads.add(
                    Load::Imposed {
                        dof: Dof::new(n, comp),
                        value: v,
                    },
                    Multiplier::from_fn(Ok),
                );
            }
        }
    }
    Some((Model::new(mesh, elements).unwrap(), loads))
}

#[test]
fn ssnp121_3d_uniform_pressure_on_tria6_faces() {
    let Some((model, loads)) = problem() else {
        return;
    };
    // E (Gauss ORDRE_INT=4), D (SIMPSON), J (NCOTES), I (SIMPSON 4).
    for integration in [
        Integration::Gauss(4),
        Integration::Simpson(1),
        Integration::NCotes(3),
        Integration::Simpson(4),
    ] {
        let mut def = ContactDefinition::continuous(
            vec![Zone {
                geometry: ZoneGeometry::new("SURMAI", "SURESC"),
                law: ContinueLaw {
                    algo: ContinueAlgo::Standard { coef_cont: 1000.0 },
                    integration,
                },
            }],
            Frottement::Sans,
        )
        .unwrap();
        if let ContactDefinition::Continue(c) = &mut def {
            c.algo_reso_cont = Resolution::PointFixe;
            c.algo_reso_geom = Resolution::PointFixe;
        }
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
        let u = res.last().unwrap().displacement.clone();
        drop(snl);
        let lags = zones[0].lags_c().unwrap();
        assert_eq!(lags.len(), 81, "{integration:?}: slave nodes");
        for (n, l) in &lags {
            assert!(
                (l + 1e5).abs() < 1e-6 * 1e5,
                "{integration:?}: LAGS_C({n:?}) = {l}"
            );
        }
        for g in ["A21", "A22", "A23", "A24"] {
            let n = model.mesh().group_no(g).unwrap().members[0];
            let dz = u[model.dofs().index(Dof::new(n, Comp::DZ)).unwrap()];
            assert!(
                (dz + 0.05).abs() < 1e-6 * 0.05,
                "{integration:?}: DZ({g}) = {dz}"
            );
        }
    }
}
