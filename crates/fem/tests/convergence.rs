//! Convergence of the quadratic QUAD8 element on Lamé's thick cylinder
//! under internal pressure (AXIS, plane strain along the axis), with the
//! pressure applied on SEG3 edges.

mod common;

use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;

const A: f64 = 1.0;
const B: f64 = 2.0;
const P: f64 = 100.0;
const E: f64 = 2e5;
const NU: f64 = 0.3;

fn exact_ur(r: f64) -> f64 {
    (1. + NU) * P * A * A / (E * (B * B - A * A)) * ((1. - 2. * NU) * r + B * B / r)
}

/// Max relative error of u_r over the nodes for `nr` QUAD8 cells radially.
fn error(nr: usize) -> f64 {
    let mut mb = MeshBuilder::new(2);
    let h = (B - A) / nr as f64;
    // Node rows z = 0, h/2, h; radial positions every h/2.
    let nx = 2 * nr + 1;
    let mut ids = vec![vec![None::<NodeId>; nx]; 3];
    for (j, row) in ids.iter_mut().enumerate() {
        for (i, slot) in row.iter_mut().enumerate() {
            // No node at mid-height mid-radius positions (QUAD8 centres).
            if j == 1 && i % 2 == 1 {
                continue;
            }
            let r = A + i as f64 * h / 2.;
            *slot = Some(mb.node(&format!("N{i}_{j}"), [r, j as f64 * h / 2., 0.]));
        }
    }
    let n = |i: usize, j: usize| ids[j][i].unwrap();
    let mat = Elastic::new(E, NU).unwrap();
    let mut elements = Vec::new();
    for e in 0..nr {
        let i = 2 * e;
        let c = mb.cell(
            &format!("M{e}"),
            CellType::QUAD8,
            &[
                n(i, 0),
                n(i + 2, 0),
                n(i + 2, 2),
                n(i, 2),
                n(i + 1, 0),
                n(i + 2, 1),
                n(i + 1, 2),
                n(i, 1),
            ],
        );
        elements.push(Element {
            cell: c,
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::Axisymmetric,
                material: mat,
            },
        });
    }
    // Inner edge r = a, SEG3 (ends, then middle).
    let edge = mb.cell("INNER", CellType::SEG3, &[n(0, 2), n(0, 0), n(0, 1)]);
    elements.push(Element {
        cell: edge,
        kind: ElementKind::Boundary,
    });
    let model = Model::new(mb.mesh, elements).unwrap();
    let mut loads = Loads::new();
    loads.push(Load::Pressure {
        cell: edge,
        pressure: P,
    });
    for node in 0..model.mesh().node_count() {
        loads.push(Load::Eliminated {
            dof: Dof::new(NodeId(node as u32), Comp::DY),
            value: 0.,
        });
    }
    let step = &meca_statique(&model, &loads, &[]).unwrap().steps[0];
    let mut err = 0.0f64;
    for node in 0..model.mesh().node_count() {
        let id = NodeId(node as u32);
        let r = model.mesh().coord(id)[0];
        let u = step.displacement[model.dofs().index(Dof::new(id, Comp::DX)).unwrap()];
        err = err.max((u - exact_ur(r)).abs() / exact_ur(A));
    }
    err
}

#[test]
fn quad8_converges_on_the_thick_cylinder() {
    let errs: Vec<f64> = [1, 2, 4, 8].iter().map(|&n| error(n)).collect();
    eprintln!(
        "QUAD8 thick cylinder, max relative u_r error for 1, 2, 4, 8 cells: {:?}",
        errs.iter().map(|e| format!("{e:.3e}")).collect::<Vec<_>>()
    );
    // The pressure pushes outward: right sign and magnitude already on one cell.
    assert!(errs[0] < 2e-2, "{errs:?}");
    assert!(errs[3] < 1e-5, "{errs:?}");
    for w in errs.windows(2) {
        // At least third order in h for nodal displacements.
        assert!(w[0] / w[1] > 7., "{errs:?}");
    }
}
