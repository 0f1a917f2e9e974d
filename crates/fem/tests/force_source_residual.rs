//! The convergence test of a force source that asks for it
//! ([`ForceSource::residual_before_update`]) is made with the statuses and
//! pairing its last solve was built on, as code_aster's continuous contact
//! (`nmfcor` → `nmconv` test the forces, then `cfmmcv` → `mmbclc` pairs
//! again): a slave point sitting on a master node, whose pairing flips
//! between the two cells at every update, no longer stalls Newton at the
//! force jump between them (ssnp152f at t = 0.5).

mod common;

use aster_fem::*;
use aster_mesh::NodeId;
use common::pulled_square as square;

/// A spring on a node's DX anchored at ±`offset`, the sign flipping at
/// every update (a point paired alternately with the two cells around a
/// master node, each giving a slightly different force); its statuses
/// never change, so it always reports itself settled.
struct FlippingSpring {
    node: NodeId,
    stiffness: f64,
    offset: f64,
    side: f64,
    test_before_update: bool,
}

impl ForceSource for FlippingSpring {
    fn name(&self) -> String {
        "flipping spring".into()
    }
    fn unknowns(&self) -> usize {
        0
    }
    fn begin_increment(&mut self, _: &State, _: &mut [f64]) -> Result<(), FemError> {
        Ok(())
    }
    fn evaluate(&mut self, state: &State, _: &[f64]) -> Result<Contribution, FemError> {
        let dof = Dof::new(self.node, Comp::DX);
        let i = state.dofs.index(dof).expect("DX of the node");
        let u = state.displacement[i];
        Ok(Contribution {
            forces: vec![(i, self.stiffness * (u - self.side * self.offset))],
            own_residual: Vec::new(),
            tangent: vec![(Unknown::Dof(i), Unknown::Dof(i), self.stiffness)],
        })
    }
    fn after_iteration(&mut self, _: &State, _: &mut [f64]) -> Result<bool, FemError> {
        self.side = -self.side;
        Ok(true)
    }
    fn converged(&mut self, _: &State, _: &[f64]) -> Result<(), FemError> {
        Ok(())
    }
    fn residual_before_update(&self) -> bool {
        self.test_before_update
    }
}

fn solve(test_before_update: bool) -> Result<NonLinearResult, FemError> {
    let (model, loads, corner) = square();
    let mut spring = FlippingSpring {
        node: corner,
        stiffness: 1000.0,
        offset: 1e-3,
        side: 1.0,
        test_before_update,
    };
    let mut snl = StaticNonLinear {
        instants: vec![0.0, 1.0],
        forces: vec![Box::new(&mut spring)],
        subdivision: None,
        ..Default::default()
    };
    snl.solve(&model, &loads)
}

#[test]
fn a_pairing_that_flips_at_every_update_stalls_a_test_made_after_it() {
    // Tested with the new pairing, the residual is the jump between the two
    // anchors (2 k offset against reactions of ~10): never below 1e-6.
    let err = solve(false).map(|_| ()).unwrap_err();
    let FemError::NoConvergence { resi_rela, .. } = err else {
        panic!("{err}")
    };
    assert!(resi_rela > 1e-2, "{resi_rela}");
}

#[test]
fn the_test_made_on_the_solve_s_pairing_converges() {
    // Tested with the pairing the solve was built on (code_aster's order):
    // the spring is linear, so the first correction is exact.
    let r = solve(true).expect("converges");
    let last = r.last().unwrap();
    assert!(last.resi_glob_rela <= 1e-6, "{}", last.resi_glob_rela);
}
