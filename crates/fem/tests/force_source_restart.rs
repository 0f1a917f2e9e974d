//! A fixed-point loop of a force source that asks for another pass
//! ([`LoopVerdict::Again`]) restarts the step from its start, as
//! code_aster's continuous contact loops do (`nmnewt` → `nmible`, `nmnble`
//! → `nonlinInitDisp`: DEPPLU = DEPMOI, DEPDEL = 0, then a new
//! prediction); a loop that continues Newton
//! ([`ForceSource::again_continues_newton`], the discrete geometric loop)
//! goes on from the current iterate.

mod common;

use aster_fem::*;
use aster_mesh::NodeId;
use common::pulled_square as square;

/// A spring on a node's DX with one own unknown (its equation: own = 1),
/// asking for `passes` passes per step and recording, at the first
/// evaluation of each pass after the first, the node's DX and its unknown.
struct Passes {
    node: NodeId,
    passes: usize,
    done: usize,
    continues: bool,
    pending: bool,
    seen: Vec<(f64, f64)>,
}

impl ForceSource for Passes {
    fn name(&self) -> String {
        "passes".into()
    }
    fn unknowns(&self) -> usize {
        1
    }
    fn begin_increment(&mut self, _: &State, own: &mut [f64]) -> Result<(), FemError> {
        own[0] = 0.0;
        self.done = 0;
        Ok(())
    }
    fn evaluate(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError> {
        let i = state
            .dofs
            .index(Dof::new(self.node, Comp::DX))
            .expect("DX of the node");
        let u = state.displacement[i];
        if self.pending {
            self.seen.push((u, own[0]));
            self.pending = false;
        }
        Ok(Contribution {
            forces: vec![(i, 100.0 * u)],
            own_residual: vec![own[0] - 1.0],
            tangent: vec![
                (Unknown::Dof(i), Unknown::Dof(i), 100.0),
                (Unknown::Own(0), Unknown::Own(0), 1.0),
            ],
        })
    }
    fn after_iteration(&mut self, _: &State, _: &mut [f64]) -> Result<bool, FemError> {
        Ok(true)
    }
    fn after_convergence(&mut self, _: &State, _: &[f64]) -> Result<LoopVerdict, FemError> {
        self.done += 1;
        if self.done < self.passes {
            self.pending = true;
            Ok(LoopVerdict::Again)
        } else {
            Ok(LoopVerdict::Done)
        }
    }
    fn converged(&mut self, _: &State, _: &[f64]) -> Result<(), FemError> {
        Ok(())
    }
    fn again_continues_newton(&self) -> bool {
        self.continues
    }
}

/// Two steps of the pulled square with three passes each: (the state each
/// restarted pass starts from, the corner's DX after each step).
fn solve(continues: bool) -> (Vec<(f64, f64)>, Vec<f64>) {
    let (model, loads, corner) = square();
    let mut source = Passes {
        node: corner,
        passes: 3,
        done: 0,
        continues,
        pending: false,
        seen: Vec::new(),
    };
    let steps = {
        let mut snl = StaticNonLinear {
            instants: vec![0.0, 0.5, 1.0],
            forces: vec![Box::new(&mut source)],
            subdivision: None,
            ..Default::default()
        };
        snl.solve(&model, &loads).expect("converges").steps
    };
    let i = model.dofs().index(Dof::new(corner, Comp::DX)).expect("DX");
    let dx = steps.iter().map(|s| s.displacement[i]).collect();
    (source.seen, dx)
}

#[test]
fn a_restarting_pass_starts_again_from_the_start_of_the_step() {
    let (seen, dx) = solve(false);
    // Steps at 0 (initial state), 0.5 and 1; the corner moves.
    assert_eq!(dx.len(), 3);
    assert!(dx[1].abs() > 1e-6 && (dx[2] - dx[1]).abs() > 1e-6, "{dx:?}");
    // Two restarted passes per step, each from the step's start: the
    // corner where the previous step left it, the unknown as
    // `begin_increment` set it.
    assert_eq!(seen.len(), 4);
    for (k, &(u, own)) in seen.iter().enumerate() {
        let start = dx[k / 2];
        assert!(
            (u - start).abs() <= 1e-14 * (1.0 + start.abs()),
            "{k}: {u} vs {start}"
        );
        assert_eq!(own, 0.0, "{k}");
    }
}

#[test]
fn a_pass_that_continues_newton_goes_on_from_the_current_iterate() {
    let (seen, dx) = solve(true);
    assert_eq!(seen.len(), 4);
    for (k, &(u, own)) in seen.iter().enumerate() {
        // The converged state of the previous pass: the step's end.
        let end = dx[k / 2 + 1];
        assert!(
            (u - end).abs() <= 1e-9 * (1.0 + end.abs()),
            "{k}: {u} vs {end}"
        );
        assert!((own - 1.0).abs() <= 1e-12, "{k}: {own}");
    }
    // Both give the same (linear) answer.
    let (_, restarted) = solve(false);
    for (a, b) in dx.iter().zip(&restarted) {
        assert!((a - b).abs() <= 1e-12 * (1.0 + a.abs()), "{a} vs {b}");
    }
}
