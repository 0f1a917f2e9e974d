//! code_aster's Newton prediction with imposed displacements (`nmprta`):
//! an increment imposed by elimination (AFFE_CHAR_CINE) is spread through
//! the body by the prediction's tangent solve, exactly as a dualised one
//! (DDL_IMPO) is — both give the same iterates, the same iteration counts
//! and the same converged states. Before, the eliminated DOFs alone were
//! moved and the internal forces were computed on that kinked state: the
//! cells next to the punch yielded in the trial state and Newton needed
//! many more iterations (or step cuts).

mod common;

use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;
use std::sync::Arc;

const E: f64 = 200e3;
const NU: f64 = 0.3;
const SY: f64 = 200.;
const ET: f64 = 2000.;

/// A plane-strain block 4 × 2 (16 × 8 QUAD4) clamped at its base; the
/// middle quarter of its top is pushed down by 0.004·t (a rigid punch,
/// DX held): a local plastic zone grows under the punch.
fn punched_block(eliminated: bool, instants: &[f64]) -> (Model, NonLinearResult) {
    punched_block_by(eliminated, instants, -0.004)
}

fn punched_block_by(eliminated: bool, instants: &[f64], dy: f64) -> (Model, NonLinearResult) {
    let (nx, ny) = (16, 8);
    let mut mb = MeshBuilder::new(2);
    let mut grid = vec![vec![NodeId(0); nx + 1]; ny + 1];
    for (j, row) in grid.iter_mut().enumerate() {
        for (i, n) in row.iter_mut().enumerate() {
            *n = mb.node(
                &format!("N{i}_{j}"),
                [4.0 * i as f64 / nx as f64, 2.0 * j as f64 / ny as f64, 0.],
            );
        }
    }
    let mut elements = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let c = mb.cell(
                &format!("M{i}_{j}"),
                CellType::QUAD4,
                &[
                    grid[j][i],
                    grid[j][i + 1],
                    grid[j + 1][i + 1],
                    grid[j + 1][i],
                ],
            );
            elements.push(Element {
                cell: c,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material: Elastic::new(E, NU).unwrap(),
                },
            });
        }
    }
    let model = Model::new(mb.mesh, elements).unwrap();
    let mut loads = Loads::new();
    for &n in &grid[0] {
        for comp in [Comp::DX, Comp::DY] {
            loads.push(Load::Eliminated {
                dof: Dof::new(n, comp),
                value: 0.,
            });
        }
    }
    for &n in &grid[ny][3 * nx / 8..=5 * nx / 8] {
        for (comp, value) in [(Comp::DX, 0.0), (Comp::DY, dy)] {
            let dof = Dof::new(n, comp);
            let load = if eliminated {
                Load::Eliminated { dof, value }
            } else {
                Load::Imposed { dof, value }
            };
            loads.add(load, Multiplier::from_fn(Ok));
        }
    }
    let law = Arc::new(VonMises::linear(E, SY, ET).unwrap());
    let mut behaviours = Behaviours::elastic();
    for el in model.elements() {
        behaviours.assign(el.cell, law.clone());
    }
    let mut snl = StaticNonLinear {
        instants: instants.to_vec(),
        convergence: Convergence {
            resi_glob_rela: Some(1e-8),
            ..Default::default()
        },
        behaviours,
        subdivision: Some(Subdivision::default()),
        ..Default::default()
    };
    let res = snl.solve(&model, &loads).unwrap();
    (model, res)
}

const INSTANTS: [f64; 6] = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];

#[test]
fn eliminated_and_dualised_punches_give_the_same_newton_and_answer() {
    let (m, cine) = punched_block(true, &INSTANTS);
    let (_, dual) = punched_block(false, &INSTANTS);

    // The punch goes plastic: the last step has yielded Gauss points.
    let last = cine.steps.last().unwrap();
    let plastic = last
        .internal_variables
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|p| p[0] > 0.0)
        .count();
    assert!(plastic > 20, "{plastic} plastic points");
    let scale = last.displacement.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for (a, b) in cine.steps.iter().zip(&dual.steps) {
        assert_eq!(
            a.newton_iterations, b.newton_iterations,
            "Newton iterations at t = {}",
            a.time
        );
        for i in 0..m.dofs().len() {
            let (x, y) = (a.displacement[i], b.displacement[i]);
            assert!(
                (x - y).abs() <= 1e-9 * scale,
                "t = {} dof {i}: {x} vs {y}",
                a.time
            );
        }
    }
    // Neither needed a step cut, and each step took a few iterations
    // (quadratic Newton from the tangent prediction).
    for res in [&cine, &dual] {
        assert!(res.attempts.iter().all(|a| a.failure.is_none()));
        assert_eq!(res.attempts.len(), INSTANTS.len() - 1);
        assert!(
            res.steps.iter().all(|s| s.newton_iterations <= 6),
            "{:?}",
            res.steps
                .iter()
                .map(|s| s.newton_iterations)
                .collect::<Vec<_>>()
        );
    }
}

#[test]
fn failed_attempts_and_cuts_are_recorded() {
    // A punch of 0.01 in one increment: Newton stalls (ITER_GLOB_MAXI = 10)
    // and the increment is cut in four; the failed attempt, with its
    // residuals, and the pieces are all in `attempts` — the same for both
    // ways of imposing the punch.
    let (_, cine) = punched_block_by(true, &[0.0, 1.0], -0.01);
    let (_, dual) = punched_block_by(false, &[0.0, 1.0], -0.01);
    for res in [&cine, &dual] {
        let first = &res.attempts[0];
        assert_eq!((first.from, first.to, first.level), (0.0, 1.0, 0));
        assert!(first.failure.is_some() && first.cut, "{first:?}");
        assert_eq!(first.residuals.len(), 10, "iterations 0 to 9 were tried");
        let pieces: Vec<(f64, f64, usize)> = res.attempts[1..]
            .iter()
            .map(|a| (a.from, a.to, a.level))
            .collect();
        assert_eq!(
            pieces,
            [
                (0.0, 0.25, 1),
                (0.25, 0.5, 1),
                (0.5, 0.75, 1),
                (0.75, 1.0, 1)
            ]
        );
        assert!(res.attempts[1..].iter().all(|a| a.failure.is_none()));
    }
    let it = |r: &NonLinearResult| r.attempts.iter().map(|a| a.iterations).collect::<Vec<_>>();
    assert_eq!(it(&cine), it(&dual));
}
