//! code_aster's geometric loop of discrete contact (`cfcgeo`) and DOFs
//! imposed twice.

mod common;

use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;

/// Two QUAD4 cells [0, 2]×[0, 1]; returns the model and all its nodes.
fn strip() -> (Model, Vec<NodeId>) {
    let mut mb = MeshBuilder::new(2);
    let bottom: Vec<NodeId> = (0..3)
        .map(|i| mb.node(&format!("B{i}"), [i as f64, 0., 0.]))
        .collect();
    let top: Vec<NodeId> = (0..3)
        .map(|i| mb.node(&format!("T{i}"), [i as f64, 1., 0.]))
        .collect();
    let material = Elastic::new(1000., 0.25).unwrap();
    let elements = (0..2)
        .map(|i| Element {
            cell: mb.cell(
                &format!("M{i}"),
                CellType::QUAD4,
                &[bottom[i], bottom[i + 1], top[i + 1], top[i]],
            ),
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::PlaneStrain,
                material,
            },
        })
        .collect();
    let nodes = bottom.into_iter().chain(top).collect();
    (Model::new(mb.mesh, elements).unwrap(), nodes)
}

/// code_aster's geometric test (as contact's `GeomLoopState` runs it for
/// `REAC_GEOM='AUTOMATIQUE'`): pair again while
/// |uₖ − uₖ₋₁| / |uₖ₋₁ − u₀| ≥ `resi_geom`, at most `iter_maxi` pairings.
#[derive(Clone, Copy)]
struct ResiGeom {
    resi_geom: f64,
    iter_maxi: usize,
}

/// An obstacle under every node whose height depends on where the nodes
/// were when it was paired: u_y ≥ 0.1 − β·u_y(pairing). Each pairing is
/// then solved exactly by a rigid translation u_k = 0.1 − β·u_{k−1}, so the
/// sequence of pairings is known in closed form; its fixed point is
/// 0.1 / (1 + β). With a [`ResiGeom`] the source runs the test itself and
/// ends fem's geometric loop by returning its last rows again.
struct MovingObstacle {
    nodes: Vec<NodeId>,
    beta: f64,
    criterion: Option<ResiGeom>,
    /// u_y at each pairing (u₀ is the first).
    pairings: Vec<f64>,
    last_rows: Vec<InequalityRow>,
}

impl UnilateralSource for MovingObstacle {
    fn geometry_update(&self) -> GeometryUpdate {
        GeometryUpdate::EachIteration
    }
    fn rows(&mut self, state: &State) -> Result<Vec<InequalityRow>, FemError> {
        let uy = state
            .value(Dof::new(self.nodes[0], Comp::DY))
            .unwrap_or(0.0);
        if let (Some(c), [u0, .., prev]) = (self.criterion, self.pairings.as_slice()) {
            if self.pairings.len() >= 2 {
                let r = (uy - prev).abs() / (prev - u0).abs();
                if r < c.resi_geom {
                    return Ok(self.last_rows.clone());
                }
            }
            if self.pairings.len() >= c.iter_maxi {
                return Err(FemError::Source(format!(
                    "the geometric loop does not converge after {} pairings (ITER_GEOM_MAXI)",
                    self.pairings.len()
                )));
            }
        }
        self.pairings.push(uy);
        let rhs = -(0.1 - self.beta * uy);
        self.last_rows = self
            .nodes
            .iter()
            .enumerate()
            .map(|(k, &n)| InequalityRow::new(vec![(Dof::new(n, Comp::DY), -1.)], rhs, k))
            .collect();
        Ok(self.last_rows.clone())
    }
}

fn lift(criterion: Option<ResiGeom>) -> (Result<NonLinearResult, FemError>, Vec<f64>) {
    let (m, nodes) = strip();
    let mut loads = Loads::new();
    loads.push(Load::Eliminated {
        dof: Dof::new(nodes[0], Comp::DX),
        value: 0.,
    });
    // Each node pressed on the obstacle by its own unit force: the rows
    // carry λ = 1 each and the body lifts rigidly.
    for &n in &nodes {
        loads.push(Load::NodalForce {
            dof: Dof::new(n, Comp::DY),
            value: -1.,
        });
    }
    let mut src = MovingObstacle {
        nodes: nodes.clone(),
        beta: 0.1,
        criterion,
        pairings: Vec::new(),
        last_rows: Vec::new(),
    };
    let res = {
        let mut snl = StaticNonLinear {
            instants: vec![0., 1.],
            // Each node's load is balanced by its own row, so the relative
            // residual has no reference: test the absolute one.
            convergence: Convergence {
                resi_glob_rela: None,
                resi_glob_maxi: Some(1e-9),
                iter_glob_maxi: 10,
                at_least_one: false,
            },
            sources: vec![Box::new(&mut src)],
            ..Default::default()
        };
        snl.solve(&m, &loads)
    };
    // A rigid lift: every node moves as the first one.
    if let Ok(r) = &res {
        let d = &r.last().unwrap().displacement;
        for &n in &nodes {
            let i = m.dofs().index(Dof::new(n, Comp::DY)).unwrap();
            assert!((d[i] - d[1]).abs() < 1e-12, "{d:?}");
        }
    }
    (res, src.pairings)
}

#[test]
fn a_source_repeating_its_rows_ends_the_geometric_loop() {
    let (res, pairings) = lift(Some(ResiGeom {
        resi_geom: 0.01,
        iter_maxi: 10,
    }));
    let r = res.unwrap();
    // u₁ = 0.1 (paired at 0), u₂ = 0.09, u₃ = 0.091, u₄ = 0.0909. Tests:
    // after the first pairing there is nothing to compare with;
    // |u₂−u₁|/|u₁| = 0.1, |u₃−u₂|/|u₂| = 0.0111 fail; |u₄−u₃|/|u₃| = 0.0011
    // < 0.01 passes: the source repeats its rows and fem stops at u₄,
    // paired at u₃, 1e-4 away from the fixed point 0.1/1.1.
    let u = r.last().unwrap().displacement[1];
    assert!((u - 0.0909).abs() < 1e-12, "{u}");
    assert_eq!(pairings.len(), 4, "{pairings:?}");
    for (p, want) in pairings.iter().zip([0.0, 0.1, 0.09, 0.091]) {
        assert!((p - want).abs() < 1e-12, "{pairings:?}");
    }
}

#[test]
fn without_criterion_the_geometric_loop_reaches_the_fixed_point() {
    let (res, pairings) = lift(None);
    let u = res.unwrap().last().unwrap().displacement[1];
    assert!((u - 0.1 / 1.1).abs() < 1e-9, "{u}");
    assert!(pairings.len() > 4);
}

#[test]
fn a_source_error_in_the_geometric_loop_fails_the_step_with_its_message() {
    let (res, pairings) = lift(Some(ResiGeom {
        resi_geom: 0.01,
        iter_maxi: 3,
    }));
    let e = res.unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, FemError::Source(_)), "{msg}");
    assert!(msg.contains("after 3 pairings"), "{msg}");
    assert_eq!(pairings.len(), 3, "{pairings:?}");
}

/// A column under its own weight-like top load, the bottom held by
/// DDL_IMPO given once or twice.
fn column(imposed_twice: Option<f64>) -> Result<NonLinearResult, FemError> {
    let (m, nodes) = strip();
    let mut loads = Loads::new();
    for &n in &nodes[..3] {
        loads.push(Load::Imposed {
            dof: Dof::new(n, Comp::DY),
            value: 0.,
        });
    }
    loads.push(Load::Imposed {
        dof: Dof::new(nodes[0], Comp::DX),
        value: 0.,
    });
    if let Some(v) = imposed_twice {
        loads.push(Load::Imposed {
            dof: Dof::new(nodes[1], Comp::DY),
            value: v,
        });
    }
    for &n in &nodes[3..] {
        loads.push(Load::NodalForce {
            dof: Dof::new(n, Comp::DY),
            value: -10.,
        });
    }
    let mut snl = StaticNonLinear {
        instants: vec![0., 1.],
        ..Default::default()
    };
    snl.solve(&m, &loads)
}

#[test]
fn a_dof_imposed_twice_with_one_value_is_one_condition() {
    let once = column(None).unwrap();
    let twice = column(Some(0.)).unwrap();
    let (a, b) = (once.last().unwrap(), twice.last().unwrap());
    for (x, y) in a.displacement.iter().zip(&b.displacement) {
        assert!((x - y).abs() <= 1e-12 * x.abs().max(1e-9), "{x} {y}");
    }
    // The reaction is carried once: total vertical reaction = 30 either way.
    let sum = |s: &Step| {
        s.multipliers.iter().take(3).sum::<f64>() + s.multipliers.iter().skip(4).sum::<f64>()
    };
    // (multipliers are reaction magnitudes along the rows: −30 for +DY rows)
    assert!((sum(a).abs() - 30.).abs() < 1e-9, "{}", sum(a));
    assert!((sum(b).abs() - 30.).abs() < 1e-9, "{}", sum(b));
}

#[test]
fn a_dof_imposed_twice_with_two_values_is_an_error() {
    let e = column(Some(0.5)).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("imposed twice"), "{msg}");
    assert!(msg.contains("0.5"), "{msg}");
}

/// A penalised source whose second pairing brings back, on new rows, an
/// active set seen during the first pairing: that is no cycle (SSNV104H's
/// step 2 stopped so — "the active set cycles" — and was cut, moving its
/// results by 0.3 %). One node on a ground spring (k = 1) pushed down by
/// 1 onto two obstacles; pairing 1: obstacles at −0.5 and −0.9, the
/// second released after one pass (active sets {0, 1} then {0}); pairing 2
/// raises the second to −0.45: {0, 1} again, then {1}.
struct RaisedObstacle {
    node: NodeId,
    calls: usize,
}

impl UnilateralSource for RaisedObstacle {
    fn method(&self) -> UnilateralMethod {
        UnilateralMethod::Penalty { coef: 1e3 }
    }
    fn geometry_update(&self) -> GeometryUpdate {
        GeometryUpdate::EachIteration
    }
    fn rows(&mut self, _state: &State) -> Result<Vec<InequalityRow>, FemError> {
        self.calls += 1;
        let second = if self.calls == 1 { 0.9 } else { 0.45 };
        let dy = Dof::new(self.node, Comp::DY);
        Ok(vec![
            InequalityRow::new(vec![(dy, -1.)], 0.5, 0),
            InequalityRow::new(vec![(dy, -1.)], second, 1),
        ])
    }
}

#[test]
fn an_active_set_seen_with_the_previous_pairing_is_no_cycle() {
    let mut mb = MeshBuilder::new(2);
    let p = mb.node("P", [0., 0., 0.]);
    let cell = mb.cell("PT", CellType::POI1, &[p]);
    let m = Model::new(
        mb.mesh,
        vec![Element {
            cell,
            kind: ElementKind::Spring {
                stiffness: vec![1., 1.],
                frame: Frame::Global,
            },
        }],
    )
    .unwrap();
    let mut loads = Loads::new();
    loads.push(Load::NodalForce {
        dof: Dof::new(p, Comp::DY),
        value: -1.,
    });
    let mut src = RaisedObstacle { node: p, calls: 0 };
    let res = {
        let mut snl = StaticNonLinear {
            instants: vec![0., 1.],
            sources: vec![Box::new(&mut src)],
            // No step cutting: the step must pass as it is.
            subdivision: None,
            ..Default::default()
        };
        snl.solve(&m, &loads)
    };
    let res = res.expect("no cycle across pairings");
    let d = &res.last().unwrap().displacement;
    let i = m.dofs().index(Dof::new(p, Comp::DY)).unwrap();
    // Only the raised obstacle presses: (1 + κ) u = −1 − 0.45 κ.
    assert!((d[i] - (-1. - 450.) / 1001.).abs() < 1e-12, "{}", d[i]);
}
