//! A force source without unknowns of its own and with a symmetric
//! tangent ([`ForceSource::symmetric_tangent`], the cohesive joints) is
//! solved through the constrained solver of the Newton loop without
//! sources (pinned rows, relations through their Schur complement or the
//! augmented LDLᵀ, a kept symbolic analysis) instead of the bordered LU:
//! both paths must give the same iterates, displacements and multipliers of
//! the relations (LIAISON_DDL) alike.

mod common;

use aster_fem::*;
use aster_mesh::NodeId;
use common::pulled_square as square;

/// A non-linear spring on a node's DX and DY (force k·u + c·u³ on each,
/// coupled by a symmetric term), declaring its tangent symmetric or not.
struct Spring {
    node: NodeId,
    symmetric: bool,
}

impl ForceSource for Spring {
    fn name(&self) -> String {
        "spring".into()
    }
    fn unknowns(&self) -> usize {
        0
    }
    fn symmetric_tangent(&self) -> bool {
        self.symmetric
    }
    fn begin_increment(&mut self, _: &State, _: &mut [f64]) -> Result<(), FemError> {
        Ok(())
    }
    fn evaluate(&mut self, state: &State, _: &[f64]) -> Result<Contribution, FemError> {
        let ix = state.dofs.index(Dof::new(self.node, Comp::DX)).expect("DX");
        let iy = state.dofs.index(Dof::new(self.node, Comp::DY)).expect("DY");
        let (x, y) = (state.displacement[ix], state.displacement[iy]);
        let (k, c, g) = (500.0, 4.0e6, 100.0);
        Ok(Contribution {
            forces: vec![
                (ix, k * x + c * x * x * x + g * y),
                (iy, k * y + c * y * y * y + g * x),
            ],
            own_residual: Vec::new(),
            tangent: vec![
                (Unknown::Dof(ix), Unknown::Dof(ix), k + 3.0 * c * x * x),
                (Unknown::Dof(ix), Unknown::Dof(iy), g),
                (Unknown::Dof(iy), Unknown::Dof(ix), g),
                (Unknown::Dof(iy), Unknown::Dof(iy), k + 3.0 * c * y * y),
            ],
        })
    }
    fn after_iteration(&mut self, _: &State, _: &mut [f64]) -> Result<bool, FemError> {
        Ok(true)
    }
    fn converged(&mut self, _: &State, _: &[f64]) -> Result<(), FemError> {
        Ok(())
    }
}

fn solve(symmetric: bool) -> NonLinearResult {
    let (model, mut loads, corner) = square();
    // The top nodes' DX tied (LIAISON_DDL DX(N2) − DX(N3) = 0): a
    // relation over two free unknowns, kept as a row.
    let top = NodeId(3);
    loads.push(Load::Relation {
        terms: vec![
            (Dof::new(corner, Comp::DX), 1.0),
            (Dof::new(top, Comp::DX), -1.0),
        ],
        rhs: 0.0,
    });
    let mut spring = Spring {
        node: corner,
        symmetric,
    };
    let mut snl = StaticNonLinear {
        instants: vec![0.0, 0.5, 1.0],
        forces: vec![Box::new(&mut spring)],
        subdivision: None,
        ..Default::default()
    };
    snl.solve(&model, &loads).expect("converges")
}

#[test]
fn a_symmetric_source_gives_the_bordered_lu_s_answer() {
    let kkt = solve(true);
    let lu = solve(false);
    assert_eq!(kkt.steps.len(), lu.steps.len());
    for (a, b) in kkt.steps.iter().zip(&lu.steps) {
        assert_eq!(a.newton_iterations, b.newton_iterations, "t = {}", a.time);
        let scale = b.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (x, y) in a.displacement.iter().zip(&b.displacement) {
            assert!((x - y).abs() <= 1e-10 * scale, "t = {}: {x} vs {y}", a.time);
        }
        assert_eq!(a.multipliers.len(), 1);
        let (la, lb) = (a.multipliers[0], b.multipliers[0]);
        assert!(
            (la - lb).abs() <= 1e-8 * lb.abs().max(1e-12),
            "{la} vs {lb}"
        );
    }
    // The tie holds, and the spring pulled the corner: DX ≠ 0.
    let last = kkt.last().unwrap();
    assert!(last.resi_glob_rela <= 1e-6);
    assert!(last.multipliers[0].abs() > 1e-6, "{:?}", last.multipliers);
}
