//! One joint cell (`PLAN_JOINT` on QUAD4, [`aster_fem::joint`]) opened in
//! mode I and sheared in mode II by imposed displacements of its upper
//! face, its lower face held, through the non-linear solver: at every
//! converged step the traction at both Gauss points follows the closed
//! form of the cohesive law (CZM_LIN_REG: r(κ0)·δ, then σc (1 − δ/δc), then
//! 0; CZM_TURON: K δ, then σc (δf − δ)/(δf − δ0), then 0), and the free
//! component of the upper face stays in equilibrium at zero jump.

mod common;

use aster_fem::cohesive::{CohesiveLaw, LinReg, Turon, TuronCriterion};
use aster_fem::joint::{JointCell, JointCells};
use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;

/// Returns every converged step's (imposed jump, traction along the mode
/// at both Gauss points, other traction component).
fn run(law: CohesiveLaw, mode: usize, jump_max: f64, steps: usize) -> Vec<(f64, [f64; 2], f64)> {
    let mut mb = MeshBuilder::new(2);
    let p = [[0.0, 0.0], [0.5, 0.0], [0.5, 0.01], [0.0, 0.01]];
    let n: Vec<NodeId> = p
        .iter()
        .enumerate()
        .map(|(i, x)| mb.node(&format!("N{}", i + 1), [x[0], x[1], 0.0]))
        .collect();
    let joint = mb.cell("J", CellType::QUAD4, &n);
    let low = mb.cell("LOW", CellType::SEG2, &[n[0], n[1]]);
    let up = mb.cell("UP", CellType::SEG2, &[n[2], n[3]]);
    let model = Model::new(
        mb.mesh,
        [low, up]
            .iter()
            .map(|&cell| Element {
                cell,
                kind: ElementKind::Boundary,
            })
            .collect(),
    )
    .unwrap();
    let mut loads = Loads::new();
    for &b in &n[..2] {
        for comp in [Comp::DX, Comp::DY] {
            loads.push(Load::Eliminated {
                dof: Dof::new(b, comp),
                value: 0.,
            });
        }
    }
    let comp = if mode == 0 { Comp::DY } else { Comp::DX };
    for &t in &n[2..] {
        loads.add(
            Load::Eliminated {
                dof: Dof::new(t, comp),
                value: jump_max,
            },
            Multiplier::from_fn(Ok),
        );
    }
    let mut cells = JointCells::new(vec![JointCell {
        cell: joint,
        nodes: [n[0], n[1], n[2], n[3]],
        geom: p,
        law,
    }]);
    {
        let mut snl = StaticNonLinear {
            instants: (0..=steps).map(|k| k as f64 / steps as f64).collect(),
            forces: vec![Box::new(&mut cells)],
            subdivision: None,
            ..Default::default()
        };
        let result = snl.solve(&model, &loads).expect("the joint converges");
        assert_eq!(result.last().unwrap().time, 1.0);
    }
    cells
        .history()
        .iter()
        .filter(|(t, _)| *t > 0.0)
        .map(|(t, pts)| {
            let s = &pts[0].traction;
            (
                t * jump_max,
                [s[0][mode].abs(), s[1][mode].abs()],
                s[0][1 - mode].abs().max(s[1][1 - mode].abs()),
            )
        })
        .collect()
}

fn check(law: CohesiveLaw, mode: usize, closed: impl Fn(f64) -> f64, jump_max: f64, scale: f64) {
    let out = run(law, mode, jump_max, 30);
    assert_eq!(out.len(), 30);
    for (delta, s, other) in out {
        let expected = closed(delta);
        for v in s {
            assert!(
                (v - expected).abs() <= 1e-6 * scale,
                "mode {mode}, δ = {delta}: traction {v}, closed form {expected}"
            );
        }
        assert!(
            other <= 1e-6 * scale,
            "mode {mode}: the other traction {other}"
        );
    }
}

#[test]
fn czm_lin_reg_follows_its_linear_softening_in_both_modes() {
    let m = LinReg {
        gc: 1000.0,
        sigma_c: 30e6,
        pena_adherence: 0.077,
        pena_contact: 1.0,
    };
    let lc = 2.0 * m.gc / m.sigma_c;
    let k0 = lc * m.pena_adherence;
    let closed = |d: f64| {
        if d <= k0 {
            m.sigma_c * (1.0 - k0 / lc) / k0 * d
        } else if d < lc {
            m.sigma_c * (1.0 - d / lc)
        } else {
            0.0
        }
    };
    for mode in [0, 1] {
        check(CohesiveLaw::LinReg(m), mode, closed, 1.2 * lc, m.sigma_c);
    }
}

#[test]
fn czm_turon_is_bilinear_in_both_pure_modes() {
    let m = Turon {
        k: 1e13,
        sigma_c_n: 10e6,
        sigma_c_t: 27.69e6,
        gc_n: 200.0,
        gc_t: 923.0,
        c_rupt: 0.001,
        eta_bk: 2.3,
        criterion: TuronCriterion::Turon,
    };
    for (mode, sc, gc) in [(0, m.sigma_c_n, m.gc_n), (1, m.sigma_c_t, m.gc_t)] {
        let d0 = sc / m.k;
        let df = 2.0 * gc / sc;
        let closed = |d: f64| {
            if d <= d0 {
                m.k * d
            } else if d < df {
                sc * (df - d) / (df - d0)
            } else {
                0.0
            }
        };
        check(CohesiveLaw::Turon(m), mode, closed, 1.1 * df, sc);
    }
}
