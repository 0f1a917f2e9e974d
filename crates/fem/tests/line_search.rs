//! `RECH_LINEAIRE` in the static Newton loop: a unit cube under a uniaxial
//! force beyond the knee of a traction curve. The converged state is the
//! closed form (σxx = F, εxx on the curve) with and without the line
//! search; the search changes the Newton path (iteration counts, the
//! residuals of the first correction).

mod common;

use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;
use std::sync::Arc;

const E: f64 = 200e3;
const NU: f64 = 0.3;
/// A sharp knee: slope E up to 200, then 30 000 up to 230, then 1 458.
const CURVE_EPS: [f64; 3] = [1e-3, 2e-3, 5e-2];
const CURVE_SIG: [f64; 3] = [200., 230., 300.];

/// εxx on the curve at σ (beyond yield).
fn curve_eps(sig: f64) -> f64 {
    let k = CURVE_SIG.windows(2).position(|w| sig <= w[1]).unwrap();
    CURVE_EPS[k]
        + (CURVE_EPS[k + 1] - CURVE_EPS[k]) * (sig - CURVE_SIG[k])
            / (CURVE_SIG[k + 1] - CURVE_SIG[k])
}

/// The unit cube (one HEXA8), symmetry planes x = 0, y = 0, z = 0, the
/// force `forces[t]` spread on the four nodes of x = 1.
fn cube(
    forces: &[f64],
    newton: NewtonOptions,
) -> Result<(Model, NonLinearResult, Vec<NodeId>), FemError> {
    let mut mb = MeshBuilder::new(3);
    let mut nodes = Vec::new();
    for (x, y, z) in [
        (0., 0., 0.),
        (1., 0., 0.),
        (1., 1., 0.),
        (0., 1., 0.),
        (0., 0., 1.),
        (1., 0., 1.),
        (1., 1., 1.),
        (0., 1., 1.),
    ] {
        nodes.push(mb.node(&format!("N{}", nodes.len() + 1), [x, y, z]));
    }
    let cell = mb.cell("M1", CellType::HEXA8, &nodes);
    let model = Model::new(
        mb.mesh,
        vec![Element {
            cell,
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::Solid3D,
                material: Elastic::new(E, NU).unwrap(),
            },
        }],
    )
    .unwrap();
    let mut loads = Loads::new();
    for &n in &nodes {
        let x = model.mesh().coord(n);
        for (c, comp) in [Comp::DX, Comp::DY, Comp::DZ].into_iter().enumerate() {
            if x[c] == 0. {
                loads.push(Load::Eliminated {
                    dof: Dof::new(n, comp),
                    value: 0.,
                });
            }
        }
        if x[0] == 1. {
            let table = forces.to_vec();
            loads.add(
                Load::NodalForce {
                    dof: Dof::new(n, Comp::DX),
                    value: 0.25,
                },
                Multiplier::from_fn(move |t| Ok(table[t.round() as usize])),
            );
        }
    }
    let law = Arc::new(VonMises::traction(E, &CURVE_EPS, &CURVE_SIG, CurveEnd::Linear).unwrap());
    let mut behaviours = Behaviours::elastic();
    behaviours.assign(cell, law);
    let mut snl = StaticNonLinear {
        instants: (0..forces.len()).map(|i| i as f64).collect(),
        newton,
        convergence: Convergence {
            resi_glob_rela: Some(1e-11),
            resi_glob_maxi: None,
            iter_glob_maxi: 30,
            at_least_one: false,
        },
        behaviours,
        subdivision: None,
        ..Default::default()
    };
    let res = snl.solve(&model, &loads)?;
    Ok((model, res, nodes))
}

const FORCES: [f64; 4] = [0., 150., 260., 290.];

fn searched(method: LineSearchMethod) -> NewtonOptions {
    NewtonOptions {
        line_search: Some(LineSearch {
            method,
            ..LineSearch::default()
        }),
        ..NewtonOptions::default()
    }
}

/// εxx of every step at the node (1, 1, 1), against the curve.
fn check_closed_form(model: &Model, res: &NonLinearResult, nodes: &[NodeId]) {
    let dx = model.dofs().index(Dof::new(nodes[6], Comp::DX)).unwrap();
    for (step, &f) in res.steps.iter().zip(&FORCES).skip(1) {
        let eps = if f <= CURVE_SIG[0] {
            f / E
        } else {
            curve_eps(f)
        };
        let got = step.displacement[dx];
        assert!(
            (got - eps).abs() <= 1e-9 * eps,
            "F = {f}: εxx {got:.12e}, closed form {eps:.12e}"
        );
    }
}

#[test]
fn the_line_search_keeps_the_converged_state_and_changes_the_path() {
    let (model, plain, nodes) = cube(&FORCES, NewtonOptions::default()).unwrap();
    check_closed_form(&model, &plain, &nodes);
    let counts = |r: &NonLinearResult| r.attempts.iter().map(|a| a.iterations).collect::<Vec<_>>();
    for method in [LineSearchMethod::Corde, LineSearchMethod::Mixte] {
        let (_, with, _) = cube(&FORCES, searched(method)).unwrap();
        check_closed_form(&model, &with, &nodes);
        for (a, b) in plain.steps.iter().zip(&with.steps) {
            for (x, y) in a.displacement.iter().zip(&b.displacement) {
                assert!((x - y).abs() <= 1e-9 * 0.02, "{x} vs {y}");
            }
        }
        eprintln!(
            "{method:?}: iterations {:?} (plain {:?}), residuals {:?} (plain {:?})",
            counts(&with),
            counts(&plain),
            with.attempts
                .iter()
                .map(|a| &a.residuals)
                .collect::<Vec<_>>(),
            plain
                .attempts
                .iter()
                .map(|a| &a.residuals)
                .collect::<Vec<_>>()
        );
        // The elastic step has nothing to search (one correction at most,
        // f(1) ≈ 0): the same residuals.
        assert_eq!(
            with.attempts[0].residuals.len(),
            plain.attempts[0].residuals.len()
        );
        // The knee is crossed on the way to F = 260: f(1) is about half
        // f(0), the first correction is scaled (the secant, bounded by
        // RHO_MAX) and the residual after it is smaller (0.016 against
        // 0.073 without the search).
        let (w, p) = (
            with.attempts[1].residuals[1],
            plain.attempts[1].residuals[1],
        );
        assert!(w < 0.5 * p, "{method:?}: {w} against {p}");
    }
}
