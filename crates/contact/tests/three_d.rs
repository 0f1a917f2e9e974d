//! 3D contact end to end: two HEXA8 blocks stacked, the upper one pushed
//! down onto the lower one (QUAD4 faces), through the linear driver and
//! through fem's STAT_NON_LINE. With matching 2×2 grids, ν = 0 and equal
//! stiffness, the interface moves by exactly half the imposed displacement
//! and the contact force equals E × strain × area. With non-matching grids
//! (node-to-face does not pass the patch test) no slave node penetrates and
//! equilibrium holds.

use aster_contact::*;
use aster_fem::{
    Comp, Dof, Elastic, Element, ElementKind, Hypothesis, Load, Loads, Model, Multiplier,
    StaticNonLinear, UnilateralSource,
};
use aster_mesh::{Cell, CellId, CellType, Group, Mesh, NodeId};

/// Cells (volumes, bottom faces, top faces) and nodes (bottom, top) of a block.
type Block = (
    Vec<CellId>,
    Vec<CellId>,
    Vec<CellId>,
    Vec<NodeId>,
    Vec<NodeId>,
);

/// A block [0,1]² × [z0, z0+1] with n×n×1 HEXA8.
fn block(m: &mut Mesh, n: usize, z0: f64) -> Block {
    let base = m.coords.len();
    let id = |i: usize, j: usize, k: usize| {
        NodeId((base + k * (n + 1) * (n + 1) + j * (n + 1) + i) as u32)
    };
    for k in 0..2 {
        for j in 0..=n {
            for i in 0..=n {
                m.coords
                    .push([i as f64 / n as f64, j as f64 / n as f64, z0 + k as f64]);
            }
        }
    }
    let push = |m: &mut Mesh, ty, nodes: Vec<NodeId>| {
        m.cells.push(Cell { ty, nodes });
        CellId(m.cells.len() as u32 - 1)
    };
    let (mut vol, mut bot, mut top) = (vec![], vec![], vec![]);
    for j in 0..n {
        for i in 0..n {
            let q = |k| {
                [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                ]
            };
            let (b, t) = (q(0), q(1));
            vol.push(push(m, CellType::HEXA8, [b, t].concat()));
            bot.push(push(m, CellType::QUAD4, vec![b[0], b[3], b[2], b[1]]));
            top.push(push(m, CellType::QUAD4, t.to_vec()));
        }
    }
    let layer = |k| {
        (0..=n)
            .flat_map(|j| (0..=n).map(move |i| id(i, j, k)))
            .collect::<Vec<_>>()
    };
    (vol, bot, top, layer(0), layer(1))
}

fn problem(n_upper: usize) -> (Model, Loads) {
    let mut m = Mesh {
        dim: 3,
        ..Mesh::default()
    };
    let (low, _, low_top, low_bottom_nodes, _) = block(&mut m, 2, -1.0);
    let (up, up_bottom, _, _, up_top_nodes) = block(&mut m, n_upper, 0.0);
    m.node_names = (1..=m.coords.len()).map(|i| format!("N{i}")).collect();
    m.cell_names = (1..=m.cells.len()).map(|i| format!("M{i}")).collect();
    m.groups_ma.push(Group {
        name: "MAIT".into(),
        members: low_top,
    });
    m.groups_ma.push(Group {
        name: "ESCL".into(),
        members: up_bottom,
    });
    let material = Elastic::new(1.0, 0.0).unwrap();
    let elements = low
        .iter()
        .chain(&up)
        .map(|&cell| Element {
            cell,
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::Solid3D,
                material,
            },
        })
        .collect();
    let mut loads = Loads::new();
    for n in low_bottom_nodes {
        for c in [Comp::DX, Comp::DY, Comp::DZ] {
            loads.push(Load::Eliminated {
                dof: Dof::new(n, c),
                value: 0.0,
            });
        }
    }
    for n in up_top_nodes {
        loads.push(Load::Eliminated {
            dof: Dof::new(n, Comp::DX),
            value: 0.0,
        });
        loads.push(Load::Eliminated {
            dof: Dof::new(n, Comp::DY),
            value: 0.0,
        });
        loads.add(
            Load::Eliminated {
                dof: Dof::new(n, Comp::DZ),
                value: -0.01,
            },
            Multiplier::from_fn(Ok),
        );
    }
    (Model::new(m, elements).unwrap(), loads)
}

fn definition() -> ContactDefinition {
    ContactDefinition::discrete(
        vec![Zone {
            geometry: ZoneGeometry::new("MAIT", "ESCL"),
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap()
}

fn check(model: &Model, u: &[f64], zones: &[ZoneContact]) {
    let mesh = model.mesh();
    for &n in &mesh
        .group_ma("ESCL")
        .map(|g| mesh.nodes_of_cells(&g.members))
        .unwrap()
    {
        let dz = u[model.dofs().index(Dof::new(n, Comp::DZ)).unwrap()];
        assert!((dz - -0.005).abs() < 1e-9, "DZ = {dz}");
    }
    let total: f64 = zones[0].forces().iter().sum();
    assert!((total - 0.005).abs() < 1e-9, "contact force {total}");
}

#[test]
fn stacked_blocks_linear_driver() {
    let (model, loads) = problem(2);
    let def = definition();
    let mut zones = ZoneContact::build_all(&def, model.mesh()).unwrap();
    let r = run_linear(&def, &mut zones, &model, &loads, &[0.0, 1.0]).unwrap();
    check(&model, &r[0].report.u, &zones);
}

#[test]
fn stacked_blocks_fem_newton() {
    let (model, loads) = problem(2);
    let mut zones = ZoneContact::build_all(&definition(), model.mesh()).unwrap();
    let u = {
        let mut snl = StaticNonLinear {
            instants: vec![0.0, 1.0],
            sources: zones
                .iter_mut()
                .map(|z| Box::new(z) as Box<dyn UnilateralSource>)
                .collect(),
            ..Default::default()
        };
        snl.solve(&model, &loads)
            .unwrap()
            .last()
            .unwrap()
            .displacement
            .clone()
    };
    check(&model, &u, &zones);
}

#[test]
fn non_matching_faces_hold_without_penetration() {
    let (model, loads) = problem(3);
    let def = definition();
    let mut zones = ZoneContact::build_all(&def, model.mesh()).unwrap();
    let r = run_linear(&def, &mut zones, &model, &loads, &[0.0, 1.0]).unwrap();
    let u = &r[0].report.u;
    let x = positions(model.mesh(), model.dofs(), u);
    let cn = ContNoeu::from_zones(&zones, &x, model.mesh()).unwrap();
    for (n, v) in cn.nodes.iter().zip(&cn.values) {
        // Up to the geometric loop tolerance (RESI_GEOM) on 0.005 displacements.
        assert!(v[1] > -1e-8, "node {n:?} penetrates: JEU = {}", v[1]);
        assert_eq!(v[0], 1.0, "every slave node is in contact");
    }
    // The total force is what the upper block carries: between the two
    // stiffness bounds of a uniform 0.005 strain, ±10 %.
    let total: f64 = zones[0].forces().iter().sum();
    assert!((total - 0.005).abs() < 0.1 * 0.005, "contact force {total}");
}
