//! The Hertz cylinder-on-plane scene (plane strain): the right half of a
//! cylinder pressed by its hub onto a rigid plane, on the contact crate's
//! mesh generator (refined near the contact). `refine` is the number of
//! cells across the refined contact sector.
//!
//! Compared quantity: the peak pressure p₀, from the contact force of the
//! node on the symmetry line over its tributary length h/2. Reference: the
//! analytic p₀ = 2P/(πa), a = √(4PR/(πE*)), with P the load per unit length
//! the run actually transmitted (twice the half model's contact force), so
//! the error measures the contact pressure, not the load.

use super::driver;
use crate::clock::{cpu_now, cpu_since};
use crate::error::StudyError;
use crate::outcome::{Failure, FailureKind, Measures, Phases};
use crate::scene::{Params, Scene};
use crate::spec::Point;
use aster_contact::hertz::{hertz_mesh, plane_strain_modulus, HertzMesh, HertzSolution};
use aster_contact::scenes::hertz_problem;
use aster_fem::{Comp, Dof, Elastic, InequalityRow, Loads, Model};
use aster_mesh::Mesh;
use std::collections::BTreeMap;

pub struct Hertz {
    radius: f64,
    young: f64,
    poisson: f64,
    /// Imposed downward displacement of the hub at the last instant.
    depth: f64,
    /// Angle of the refined sector (rad); must hold the contact.
    contact_angle: f64,
    /// Penetration beyond which a converged run is a wrong answer.
    max_penetration: f64,
}

const KNOWN: &[&str] = &[
    "radius",
    "young",
    "poisson",
    "depth",
    "contact_angle",
    "max_penetration",
];

impl Hertz {
    pub fn from_params(table: &BTreeMap<String, f64>) -> Result<Hertz, StudyError> {
        let p = Params::new("hertz", table, KNOWN)?;
        Ok(Hertz {
            radius: p.positive("radius", 50.0)?,
            young: p.positive("young", 2e5)?,
            poisson: p.within("poisson", 0.3, 0.0, 0.5)?,
            depth: p.positive("depth", 0.25)?,
            contact_angle: p.within("contact_angle", 0.15, 1e-3, 1.5)?,
            max_penetration: p.positive("max_penetration", 1e-3)?,
        })
    }

    /// The model and loads with `n` cells across the refined sector.
    pub fn problem(&self, n: usize) -> Result<(Model, Loads), Failure> {
        self.model(self.mesh(n)?)
    }

    /// The mesh with `n` cells across the refined sector.
    pub fn mesh(&self, n: usize) -> Result<Mesh, Failure> {
        hertz_mesh(&HertzMesh::new(self.radius, self.contact_angle, n))
            .map_err(|e| Failure::new(FailureKind::Other, e.to_string()))
    }

    /// The model and loads on a mesh from [`Hertz::mesh`]: the contact
    /// crate's Hertz problem ([`hertz_problem`]), so the study solves the
    /// scene the contact tests check against the analytic solution.
    pub fn model(&self, mesh: Mesh) -> Result<(Model, Loads), Failure> {
        let other = |m: String| Failure::new(FailureKind::Other, m);
        let material = Elastic::new(self.young, self.poisson).map_err(|e| other(e.to_string()))?;
        hertz_problem(mesh, material, self.depth).map_err(|e| other(e.to_string()))
    }
}

impl Hertz {
    /// The rigid plane as LIAISON_UNIL on the cylinder's contact-side nodes
    /// (`ESCL`): DY ≥ −gap, i.e. the row −DY ≤ gap with COEF_IMPO the
    /// node's initial height above the plane y = 0.
    fn unilateral_rows(&self, model: &Model) -> Result<Vec<InequalityRow>, Failure> {
        let mesh = model.mesh();
        let nodes = mesh.group_no("ESCL").ok_or_else(|| {
            Failure::new(FailureKind::Other, "generated mesh lacks node group ESCL")
        })?;
        Ok(nodes
            .members
            .iter()
            .enumerate()
            .map(|(i, &n)| {
                InequalityRow::new(vec![(Dof::new(n, Comp::DY), -1.0)], mesh.coord(n)[1], i)
            })
            .collect())
    }
}

impl Scene for Hertz {
    fn quantity(&self) -> String {
        "peak pressure p0 (MPa)".into()
    }

    fn describe(&self) -> String {
        format!(
            "Hertz half cylinder R = {} mm on a rigid plane, plane strain, E = {}, ν = {}, hub pushed {} mm",
            self.radius, self.young, self.poisson, self.depth
        )
    }

    fn run(&self, p: &Point) -> Result<Measures, Failure> {
        let n = p.refine as usize;
        let start = cpu_now();
        let mesh = self.mesh(n)?;
        let mesh_seconds = cpu_since(start);
        let start = cpu_now();
        let (model, loads) = self.model(mesh)?;
        let conditions = driver::conditions(&p.method, "MAIT", "ESCL", None, || {
            self.unilateral_rows(&model)
        })?;
        let model_seconds = cpu_since(start);
        let instants: Vec<f64> = (0..=p.steps).map(|i| i as f64 / p.steps as f64).collect();
        let solved = driver::solve(&conditions, &model, &loads, &instants)?;
        let post_start = cpu_now();
        let mesh = model.mesh();
        let mut forces: Vec<(f64, f64)> = solved
            .forces
            .iter()
            .map(|&(node, f)| (mesh.coord(node)[0], f))
            .collect();
        forces.sort_by(|a, b| a.0.total_cmp(&b.0));
        let h = self.radius * self.contact_angle / n as f64;
        let load = 2.0 * forces.iter().map(|f| f.1).sum::<f64>();
        let penetration = solved.penetration;
        let e_star = plane_strain_modulus(self.young, self.poisson, f64::INFINITY, 0.0);
        let exact = HertzSolution::new(load.max(f64::MIN_POSITIVE), self.radius, e_star);
        let p0 = forces
            .first()
            .filter(|f| f.0.abs() < 1e-9 * self.radius)
            .map_or(0.0, |f| f.1)
            / (h / 2.0);
        let last = forces.iter().rposition(|f| f.1 > 0.0);
        let measured_a = last.map_or(0.0, |i| forces[i].0);
        let phases = Phases {
            mesh: mesh_seconds,
            model: model_seconds + solved.phases.model,
            post: cpu_since(post_start),
            ..solved.phases
        };
        let m = Measures {
            value: p0,
            reference: Some(exact.peak_pressure),
            own_reference: None,
            h,
            dofs: model.dofs().len(),
            newton_iterations: solved.geom_iterations,
            contact_iterations: solved.contact_iterations,
            solver_seconds: Some(phases.solver()),
            phases: Some(phases),
            penetration: Some(penetration),
            extras: vec![
                ("load_P".into(), load),
                ("a_analytic".into(), exact.half_width),
                ("a_last_loaded_node".into(), measured_a),
            ],
        };
        // `load > 0` is false for NaN too: a NaN load is no contact.
        if load.is_nan() || load <= 0.0 || p0 <= 0.0 {
            return Err(Failure::wrong(
                FailureKind::LostContact,
                format!("no contact force at the symmetry node (load P = {load:.3e})"),
                m,
            ));
        }
        if exact.half_width > 0.5 * self.radius * self.contact_angle {
            return Err(Failure::new(
                FailureKind::Other,
                format!(
                    "contact half-width {:.3} exceeds half the refined sector: raise contact_angle",
                    exact.half_width
                ),
            ));
        }
        if penetration > self.max_penetration {
            return Err(Failure::wrong(
                FailureKind::Penetration,
                format!(
                    "penetration {penetration:.3e} mm > {:.1e} mm",
                    self.max_penetration
                ),
                m,
            ));
        }
        Ok(m)
    }
}
