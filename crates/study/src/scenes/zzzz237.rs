//! The ZZZZ237 two-block scene: a soft square (E = 2e9) pushed 20 m down
//! onto a block `stiffness_ratio` times stiffer, with `refine × refine`
//! cells per block, on the contact crate's generator (built through
//! aster-mesh's `Mesh`).
//!
//! Compared quantity: the total contact force at the last instant.
//! Reference: the finest run of the study's first method (there is no
//! closed form for a deformable base); the rigid-base value
//! 100·E/(1−ν²)·0.2 is recorded as the `rigid_limit` extra.

use super::driver;
use crate::clock::{cpu_now, cpu_since};
use crate::error::StudyError;
use crate::outcome::{Failure, FailureKind, Measures, Phases};
use crate::scene::{Params, Scene};
use crate::spec::Point;
use aster_contact::scenes::{two_blocks_mesh, two_blocks_problem};
use aster_fem::{Comp, Dof, InequalityRow, Model};
use std::collections::BTreeMap;

pub struct TwoBlocks {
    /// Imposed downward displacement of CD at the last instant (m).
    push: f64,
    /// Penetration beyond which a converged run is a wrong answer (m).
    max_penetration: f64,
}

impl TwoBlocks {
    pub fn from_params(table: &BTreeMap<String, f64>) -> Result<TwoBlocks, StudyError> {
        let p = Params::new("zzzz237", table, &["push", "max_penetration"])?;
        Ok(TwoBlocks {
            push: p.positive("push", 20.0)?,
            max_penetration: p.positive("max_penetration", 1e-3)?,
        })
    }
}

/// As ZZZZ237 B: the base AB of the soft square may not go below y = 0,
/// −DY ≤ 0 on every node of AB (COEF_MULT −1, COEF_IMPO 0).
fn base_rows(model: &Model) -> Result<Vec<InequalityRow>, Failure> {
    let nodes = model
        .mesh()
        .group_no("AB")
        .ok_or_else(|| Failure::new(FailureKind::Other, "generated mesh lacks node group AB"))?;
    Ok(nodes
        .members
        .iter()
        .enumerate()
        .map(|(i, &n)| InequalityRow::new(vec![(Dof::new(n, Comp::DY), -1.0)], 0.0, i))
        .collect())
}

impl Scene for TwoBlocks {
    fn quantity(&self) -> String {
        "total contact force (N/m)".into()
    }

    fn describe(&self) -> String {
        format!(
            "ZZZZ237 two blocks, plane strain: soft square pushed {} m onto a stiffer block",
            self.push
        )
    }

    fn run(&self, p: &Point) -> Result<Measures, Failure> {
        let n = p.refine as usize;
        let other = |m: String| Failure::new(FailureKind::Other, m);
        let start = cpu_now();
        let mesh = two_blocks_mesh(n).map_err(|e| other(e.to_string()))?;
        let mesh_seconds = cpu_since(start);
        let start = cpu_now();
        let (model, loads) =
            two_blocks_problem(mesh, p.stiffness_ratio).map_err(|e| other(e.to_string()))?;
        // As the code_aster case: VECT_MAIT='FIXE', MAIT_FIXE=(0, 1, 0).
        let conditions = driver::conditions(&p.method, "HE", "AB", Some([0.0, 1.0, 0.0]), || {
            base_rows(&model)
        })?;
        let model_seconds = cpu_since(start);
        let instants: Vec<f64> = (0..=p.steps)
            .map(|i| self.push * i as f64 / p.steps as f64)
            .collect();
        let solved = driver::solve(&conditions, &model, &loads, &instants)?;
        let post_start = cpu_now();
        let force: f64 = solved.forces.iter().map(|f| f.1).sum();
        let penetration = solved.penetration;
        let rigid = 100.0 * 2e9 / (1.0 - 0.09) * (self.push / 100.0);
        // LIAISON_UNIL holds the square on a rigid base: its reference is
        // the rigid-base force (exact on any mesh: the state is uniform),
        // not the deformable base of the contact runs.
        let unilateral = p.method.family().is_unilateral();
        let phases = Phases {
            mesh: mesh_seconds,
            model: model_seconds + solved.phases.model,
            post: cpu_since(post_start),
            ..solved.phases
        };
        let m = Measures {
            value: force,
            reference: None,
            own_reference: unilateral.then_some(rigid),
            h: 100.0 / n as f64,
            dofs: model.dofs().len(),
            newton_iterations: solved.geom_iterations,
            contact_iterations: solved.contact_iterations,
            solver_seconds: Some(phases.solver()),
            phases: Some(phases),
            penetration: Some(penetration),
            extras: vec![("rigid_limit".into(), rigid)],
        };
        if force.is_nan() || force <= 0.0 {
            return Err(Failure::wrong(
                FailureKind::LostContact,
                format!("no contact force (total {force:.3e}) while the square is pushed"),
                m,
            ));
        }
        if penetration > self.max_penetration {
            return Err(Failure::wrong(
                FailureKind::Penetration,
                format!(
                    "penetration {penetration:.3e} m > {:.1e} m",
                    self.max_penetration
                ),
                m,
            ));
        }
        Ok(m)
    }
}
