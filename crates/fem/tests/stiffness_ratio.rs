//! Robustness at a stiffness ratio of 1e7: a stack of a very stiff block
//! (E = 2e16) on a soft one (E = 2e9), as in the contact scene, with a
//! dualised imposed displacement and a unilateral support.

mod common;

use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;

#[test]
fn stiff_on_soft_blocks_solve_accurately() {
    // Columns of nodes x = 0..=4, rows y = 0 (base), 1 (interface), 2 (top).
    let mut mb = MeshBuilder::new(2);
    let mut ids = vec![vec![NodeId(0); 5]; 3];
    for (j, row) in ids.iter_mut().enumerate() {
        for (i, id) in row.iter_mut().enumerate() {
            *id = mb.node(&format!("N{i}_{j}"), [i as f64, j as f64, 0.]);
        }
    }
    let soft = Elastic::new(2e9, 0.).unwrap();
    let stiff = Elastic::new(2e16, 0.).unwrap();
    let mut elements = Vec::new();
    for j in 0..2 {
        for i in 0..4 {
            let c = mb.cell(
                &format!("M{i}_{j}"),
                CellType::QUAD4,
                &[ids[j][i], ids[j][i + 1], ids[j + 1][i + 1], ids[j + 1][i]],
            );
            elements.push(Element {
                cell: c,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material: if j == 0 { soft } else { stiff },
                },
            });
        }
    }
    let model = Model::new(mb.mesh, elements).unwrap();
    let mut loads = Loads::new();
    // Top pushed down by 1e-3 (dualised), base on unilateral supports,
    // one node held in x.
    for &n in &ids[2] {
        loads.push(Load::Imposed {
            dof: Dof::new(n, Comp::DY),
            value: -1e-3,
        });
    }
    loads.push(Load::Eliminated {
        dof: Dof::new(ids[0][0], Comp::DX),
        value: 0.,
    });
    let rows = ids[0]
        .iter()
        .enumerate()
        .map(|(k, &n)| InequalityRow::new(vec![(Dof::new(n, Comp::DY), -1.)], 0., k))
        .collect();
    let mut snl = StaticNonLinear {
        instants: vec![0., 1.],
        sources: vec![Box::new(FixedRows {
            name: "base".into(),
            rows,
            method: UnilateralMethod::ActiveSet,
        })],
        ..Default::default()
    };
    let res = snl.solve(&model, &loads).unwrap();
    let s = res.last().unwrap();
    // The stiff block barely deforms (1e-10 of the shortening): the soft
    // one takes the whole 1e-3; with ν = 0 the stress is uniform,
    // σyy = E·εyy, over the width 4.
    let u = |n: NodeId, c| model.dofs().value(&s.displacement, Dof::new(n, c)).unwrap();
    for (&base, &interface) in ids[0].iter().zip(&ids[1]) {
        assert!(u(base, Comp::DY).abs() < 1e-15);
        let dy = u(interface, Comp::DY);
        assert!((dy + 1e-3).abs() < 1e-9, "interface DY {dy}");
    }
    let sigma = 2e9 * (-1e-3);
    let total: f64 = s.unilateral[0].iter().map(|o| o.multiplier).sum();
    assert!(
        (total + sigma * 4.).abs() < 1e-6 * (sigma * 4.).abs(),
        "{total}"
    );
    for cv in s.stress.iter().take(4) {
        for p in &cv.points {
            assert!((p[1] - sigma).abs() < 1e-6 * sigma.abs(), "{p:?}");
        }
    }
    assert!(s.resi_glob_rela < 1e-6);
}
