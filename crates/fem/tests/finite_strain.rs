//! Finite strains in STAT_NON_LINE: Newton's quadratic convergence with the
//! consistent tangents of GREEN_LAGRANGE, GDEF_LOG and SIMO_MIEHE (the last
//! one non-symmetric, factorised by LU), on a block sheared and pressed by
//! forces into large strains and plasticity, in D_PLAN, AXIS and 3D.

// Grid loops index rows and columns as the formulas do.
#![allow(clippy::needless_range_loop)]

mod common;

use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;
use std::sync::Arc;

const E: f64 = 1000.0;
const NU: f64 = 0.3;

fn material() -> Elastic {
    Elastic::new(E, NU).unwrap()
}

/// A block of nx × ny (× nz in 3D) cells, [1, 3] × [0, 1] (× [0, 1]),
/// clamped at y = 0, its top loaded by a total force (2 force, −force)
/// growing with t, spread over its nodes.
fn sheared_block(hyp: Hypothesis, force: f64) -> (Model, Loads, Vec<NodeId>) {
    let dim = hyp.dim();
    let (nx, ny, nz) = if dim == 2 { (6, 4, 0) } else { (3, 2, 2) };
    let mut mb = MeshBuilder::new(dim as u8);
    let id = |i: usize, j: usize, k: usize, mb: &mut MeshBuilder| {
        mb.node(
            &format!("N{i}_{j}_{k}"),
            [
                1.0 + 2.0 * i as f64 / nx as f64,
                j as f64 / ny as f64,
                if nz > 0 { k as f64 / nz as f64 } else { 0.0 },
            ],
        )
    };
    let mut grid = vec![vec![vec![NodeId(0); nz + 1]; ny + 1]; nx + 1];
    for i in 0..=nx {
        for j in 0..=ny {
            for k in 0..=nz {
                grid[i][j][k] = id(i, j, k, &mut mb);
            }
        }
    }
    let mut elements = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            let cell = if dim == 2 {
                mb.cell(
                    &format!("M{i}_{j}"),
                    CellType::QUAD4,
                    &[
                        grid[i][j][0],
                        grid[i + 1][j][0],
                        grid[i + 1][j + 1][0],
                        grid[i][j + 1][0],
                    ],
                )
            } else {
                let mut cells = Vec::new();
                for k in 0..nz {
                    cells.push(mb.cell(
                        &format!("M{i}_{j}_{k}"),
                        CellType::HEXA8,
                        &[
                            grid[i][j][k],
                            grid[i + 1][j][k],
                            grid[i + 1][j + 1][k],
                            grid[i][j + 1][k],
                            grid[i][j][k + 1],
                            grid[i + 1][j][k + 1],
                            grid[i + 1][j + 1][k + 1],
                            grid[i][j + 1][k + 1],
                        ],
                    ));
                }
                for c in &cells[..cells.len() - 1] {
                    elements.push(Element {
                        cell: *c,
                        kind: ElementKind::Continuum {
                            hypothesis: hyp,
                            material: material(),
                        },
                    });
                }
                cells[cells.len() - 1]
            };
            elements.push(Element {
                cell,
                kind: ElementKind::Continuum {
                    hypothesis: hyp,
                    material: material(),
                },
            });
        }
    }
    let model = Model::new(mb.mesh, elements).unwrap();
    let mut loads = Loads::new();
    let comps: &[Comp] = if dim == 2 {
        &[Comp::DX, Comp::DY]
    } else {
        &[Comp::DX, Comp::DY, Comp::DZ]
    };
    let mut top = Vec::new();
    for i in 0..=nx {
        for k in 0..=nz {
            for &comp in comps {
                loads.push(Load::Eliminated {
                    dof: Dof::new(grid[i][0][k], comp),
                    value: 0.,
                });
            }
            top.push(grid[i][ny][k]);
        }
    }
    let per_node = 1.0 / top.len() as f64;
    for &n in &top {
        for (comp, f) in [(Comp::DX, 2.0 * force), (Comp::DY, -force)] {
            loads.add(
                Load::NodalForce {
                    dof: Dof::new(n, comp),
                    value: f * per_node,
                },
                Multiplier::from_fn(Ok),
            );
        }
    }
    (model, loads, top)
}

fn solve(
    hyp: Hypothesis,
    law: Option<Arc<VonMises>>,
    kinematics: Kinematics,
    newton: NewtonOptions,
) -> (Model, NonLinearResult, Vec<NodeId>) {
    // Elastic blocks need a larger load for large strains.
    let force = if law.is_some() { 12.0 } else { 40.0 };
    let (model, loads, top) = sheared_block(hyp, force);
    let mut behaviours = Behaviours::elastic();
    for el in model.elements() {
        behaviours.assign_with(el.cell, law.clone(), kinematics);
    }
    let mut snl = StaticNonLinear {
        instants: vec![0.0, 0.25, 0.5, 0.75, 1.0],
        newton,
        convergence: Convergence {
            resi_glob_rela: Some(1e-12),
            resi_glob_maxi: None,
            iter_glob_maxi: 25,
            at_least_one: false,
        },
        behaviours,
        ..StaticNonLinear::default()
    };
    let result = snl
        .solve(&model, &loads)
        .unwrap_or_else(|e| panic!("{kinematics:?} {hyp:?}: {e}"));
    (model, result, top)
}

/// Once the residual is small it is about squared at each iteration:
/// log r_{k+1} / log r_k ≥ 1.7 (until round-off). Returns how many such
/// pairs were seen.
fn assert_quadratic(result: &NonLinearResult, what: &str) -> usize {
    let mut observed = 0;
    for step in &result.steps[1..] {
        let r = &step.residual_history;
        assert!(r.len() <= 10, "{what}: {r:?}");
        for w in r.windows(2) {
            if w[0] < 1e-2 && w[1] > 1e-11 {
                let rate = w[1].ln() / w[0].ln();
                assert!(rate > 1.7, "{what}: convergence rate {rate} in {r:?}");
                observed += 1;
            }
        }
    }
    observed
}

/// The largest displacement of the loaded face over the block's height.
fn largest_top_displacement(model: &Model, result: &NonLinearResult, top: &[NodeId]) -> f64 {
    let u = &result.last().unwrap().displacement;
    let mut m = 0.0f64;
    for &n in top {
        for c in [Comp::DX, Comp::DY] {
            if let Some(i) = model.dofs().index(Dof::new(n, c)) {
                m = m.max(u[i].abs());
            }
        }
    }
    m
}

#[test]
fn consistent_tangents_converge_quadratically_in_large_strains() {
    let vmis = Arc::new(VonMises::linear(E, 5.0, 100.0).unwrap());
    let cases: Vec<(Hypothesis, Option<Arc<VonMises>>, Kinematics)> = vec![
        (Hypothesis::PlaneStrain, None, Kinematics::GreenLagrange),
        (
            Hypothesis::PlaneStrain,
            Some(vmis.clone()),
            Kinematics::Logarithmic,
        ),
        (
            Hypothesis::PlaneStress,
            Some(vmis.clone()),
            Kinematics::Logarithmic,
        ),
        (
            Hypothesis::Axisymmetric,
            Some(vmis.clone()),
            Kinematics::Logarithmic,
        ),
        (
            Hypothesis::PlaneStrain,
            Some(vmis.clone()),
            Kinematics::SimoMiehe,
        ),
        (
            Hypothesis::Axisymmetric,
            Some(vmis.clone()),
            Kinematics::SimoMiehe,
        ),
        (
            Hypothesis::Solid3D,
            Some(vmis.clone()),
            Kinematics::Logarithmic,
        ),
        (
            Hypothesis::Solid3D,
            Some(vmis.clone()),
            Kinematics::SimoMiehe,
        ),
        (Hypothesis::Solid3D, None, Kinematics::GreenLagrange),
    ];
    for (hyp, law, kinematics) in cases {
        let what = format!("{kinematics:?} {hyp:?}");
        let (model, result, top) = solve(hyp, law.clone(), kinematics, NewtonOptions::default());
        let observed = assert_quadratic(&result, &what);
        assert!(observed >= 2, "{what}: no iteration in the quadratic range");
        // Large strains: the top moves by a good fraction of the height,
        // and the plastic laws yield.
        let d = largest_top_displacement(&model, &result, &top);
        assert!(d > 0.15, "{what}: the top moved by {d} only");
        if law.is_some() {
            let plastic = result
                .last()
                .unwrap()
                .internal_variables
                .iter()
                .flat_map(|cv| cv.points.iter())
                .filter(|p| p[0] > 1e-3)
                .count();
            assert!(plastic > 4, "{what}: {plastic} plastic points");
        }
    }
}

/// MATR_RIGI_SYME='OUI' replaces SIMO_MIEHE's non-symmetric tangent by its
/// symmetric part: Newton still converges (linearly) to the same answer.
#[test]
fn a_symmetrised_simo_miehe_tangent_converges_to_the_same_answer() {
    let vmis = Arc::new(VonMises::linear(E, 5.0, 100.0).unwrap());
    let (_, exact, _) = solve(
        Hypothesis::PlaneStrain,
        Some(vmis.clone()),
        Kinematics::SimoMiehe,
        NewtonOptions::default(),
    );
    let (_, sym, _) = solve(
        Hypothesis::PlaneStrain,
        Some(vmis),
        Kinematics::SimoMiehe,
        NewtonOptions {
            symmetrize: true,
            ..NewtonOptions::default()
        },
    );
    let (a, b) = (
        &exact.last().unwrap().displacement,
        &sym.last().unwrap().displacement,
    );
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() < 1e-8 * scale, "{x} vs {y}");
    }
    let iterations =
        |r: &NonLinearResult| -> usize { r.steps.iter().map(|s| s.newton_iterations).sum() };
    assert!(iterations(&sym) > iterations(&exact));
}
