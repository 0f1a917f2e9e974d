//! Implicit time integration (`DYNA_NON_LINE`, `SCHEMA_TEMPS`), as
//! code_aster's displacement formulation (`ndnpas`, `ndpred`, `ndmapp`,
//! `accel0`, `nmrede`):
//!
//! - Newmark: a(u) = (u − uₙ − Δt vₙ)/(βΔt²) − (1/(2β) − 1) aₙ,
//!   v(u) = vₙ + Δt((1 − γ) aₙ + γ a(u)). Each increment starts from
//!   u = uₙ (code_aster's predictor: the velocity and acceleration that
//!   follow from Δu = 0) and solves, with the Newton loop of
//!   STAT_NON_LINE (through [`IncrementTerms`]),
//!   M a(u) + C v(u) + f_int(u) + Aᵀλ = f_ext(tₙ₊₁):
//!   the matrix gains M/(βΔt²) + γC/(βΔt).
//! - HHT (`ALPHA` = α ≤ 0): β = (1 − α)²/4, γ = ½ − α. With
//!   `MODI_EQUI='NON'` that is all (Newmark with numerical damping); with
//!   `'OUI'` the equilibrium is also weighted,
//!   M a + C v + (1 + α) f_int(uₙ₊₁) − α f_int(uₙ) = (1 + α) f_ext(tₙ₊₁) − α f_ext(tₙ),
//!   solved divided by 1 + α as code_aster does (the reactions of
//!   conditions and discrete contact are not weighted).
//! - The initial acceleration, unless given (`ETAT_INIT/ACCE`), solves
//!   M a₀ = f_ext(t₀) − f_int(u₀) with the dualised conditions (rows
//!   B a₀ = d(t₀) − B u₀, eliminated DOFs a₀ = 0), without damping or
//!   contact; a singular mass gives a₀ = 0 (code_aster's MECANONLINE_69).
//! - The residual's reference (`RESI_GLOB_RELA`) counts the inertia and
//!   damping forces with the external forces and the inertia force
//!   M v/(βΔt).

use crate::assembly::{assemble_stiffness, restrict};
use crate::energy_balance::{EnergyBalance, EnergyRow, StateForces};
use crate::error::FemError;
use crate::linalg::{self, Csc};
use crate::loads::Loads;
use crate::mass::{assemble_mass, assemble_rayleigh, Lumping, MassData, Rayleigh};
use crate::model::Model;
use crate::nonlinear::{ConvergedForces, IncrementTerms, Motion, NonLinearResult, StaticNonLinear};
use aster_mesh::CellId;
use std::collections::HashMap;

/// `SCHEMA_TEMPS`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scheme {
    /// `NEWMARK` (`BETA`, `GAMMA`; code_aster's defaults 0.25 and 0.5, the
    /// average acceleration).
    Newmark { beta: f64, gamma: f64 },
    /// `HHT` (`ALPHA`, default −0.1; `modified`: `MODI_EQUI='OUI'`).
    Hht { alpha: f64, modified: bool },
}

impl Scheme {
    /// Newmark's β and γ.
    pub fn beta_gamma(self) -> (f64, f64) {
        match self {
            Scheme::Newmark { beta, gamma } => (beta, gamma),
            Scheme::Hht { alpha, .. } => ((1. - alpha) * (1. - alpha) / 4., 0.5 - alpha),
        }
    }

    /// α of a weighted (multi-step) equilibrium.
    fn weighted_alpha(self) -> Option<f64> {
        match self {
            Scheme::Hht {
                alpha,
                modified: true,
            } => Some(alpha),
            _ => None,
        }
    }

    fn validate(self) -> Result<(), FemError> {
        let (beta, _) = self.beta_gamma();
        if beta.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(FemError::Model(format!(
                "the Newmark coefficient BETA must be positive (it is {beta}): BETA = 0 is an explicit scheme"
            )));
        }
        if self.weighted_alpha() == Some(-1.0) {
            return Err(FemError::Model(
                "HHT with MODI_EQUI='OUI' needs ALPHA different from -1".into(),
            ));
        }
        Ok(())
    }
}

/// `DYNA_NON_LINE`: the static solver's settings (instants, Newton,
/// conditions, contact, behaviours, cutting, initial displacement) with a
/// time scheme, the mass and damping data and the initial velocity and
/// acceleration.
pub struct DynamicNonLinear<'s> {
    pub solver: StaticNonLinear<'s>,
    pub scheme: Scheme,
    pub mass: MassData,
    /// `MASS_DIAG`.
    pub lumping: Lumping,
    /// Rayleigh coefficients per cell (`AMOR_ALPHA`, `AMOR_BETA`).
    pub rayleigh: HashMap<CellId, Rayleigh>,
    /// `ETAT_INIT/VITE` per DOF index (default zero).
    pub velocity: Option<Vec<f64>>,
    /// `ETAT_INIT/ACCE` per DOF index (default: from the equilibrium at t₀).
    pub acceleration: Option<Vec<f64>>,
    /// Set by [`solve`](Self::solve): the initial acceleration could not be
    /// computed (singular mass) and was taken as zero.
    pub acceleration_singular: bool,
    /// `ENERGIE`: keep code_aster's energy balance
    /// ([`crate::energy_balance`]) in [`NonLinearResult::energy`].
    pub energy: bool,
}

impl<'s> DynamicNonLinear<'s> {
    pub fn new(solver: StaticNonLinear<'s>, scheme: Scheme, mass: MassData) -> Self {
        DynamicNonLinear {
            solver,
            scheme,
            mass,
            lumping: Lumping::Consistent,
            rayleigh: HashMap::new(),
            velocity: None,
            acceleration: None,
            acceleration_singular: false,
            energy: false,
        }
    }

    /// Runs the analysis; every stored step has its `motion`.
    pub fn solve(&mut self, model: &Model, loads: &Loads) -> Result<NonLinearResult, FemError> {
        self.scheme.validate()?;
        loads.validate(model)?;
        let nd = model.dofs().len();
        let m = assemble_mass(model, &self.mass, self.lumping)?;
        let c = assemble_rayleigh(model, &self.mass, &self.rayleigh)?;
        let (t0, _) = self.solver.schedule()?;
        let u0 = match &self.solver.initial {
            Some(i) => i.displacement.clone(),
            None => vec![0.0; nd],
        };
        for (what, v) in [
            ("velocity", &self.velocity),
            ("acceleration", &self.acceleration),
        ] {
            if let Some(v) = v {
                if v.len() != nd {
                    return Err(FemError::Model(format!(
                        "initial {what} has {} values, the model has {nd} degrees of freedom",
                        v.len()
                    )));
                }
            }
        }
        let k = assemble_stiffness(model)?;
        let fint0 = self.initial_internal_forces(model, &k, &u0)?;
        let fext0 = loads.external_forces(model, t0)?;
        let v0 = self.velocity.clone().unwrap_or_else(|| vec![0.0; nd]);
        let a0 = match &self.acceleration {
            Some(a) => a.clone(),
            None => match initial_acceleration(model, loads, t0, &u0, &m, &fext0, &fint0)? {
                Some(a) => a,
                None => {
                    self.acceleration_singular = true;
                    vec![0.0; nd]
                }
            },
        };
        let mass_holds = mass_holds(model, loads, t0, &m)?;
        // code_aster's first "previous" external force (`nmfini`): the
        // initial state's M a₀ + C v₀ + f_int(u₀).
        let balance = self.energy.then(|| {
            let mut ext0 = m.mul(&a0);
            if let Some(c) = &c {
                for (e, x) in ext0.iter_mut().zip(c.mul(&v0)) {
                    *e += x;
                }
            }
            for (e, x) in ext0.iter_mut().zip(&fint0) {
                *e += x;
            }
            EnergyBalance::new(t0, &u0, &v0, ext0, fint0.clone())
        });
        let mut integrator = Newmark::new(self.scheme, m, c, u0, v0, a0, fext0, fint0, mass_holds);
        integrator.balance = balance;
        self.solver.dynamics = Some(Box::new(integrator));
        let out = self.solver.solve(model, loads);
        let energy = self
            .solver
            .dynamics
            .as_ref()
            .map(|d| d.energy_rows())
            .unwrap_or_default();
        self.solver.dynamics = None;
        out.map(|mut r| {
            r.energy = energy;
            r
        })
    }
}

impl DynamicNonLinear<'_> {
    /// f_int(u₀): K u₀, corrected by the behaviour cells of the initial
    /// state when it carries them (a plastic state continued from an
    /// earlier solve: its stresses are not K u₀, and an initial
    /// acceleration from K u₀ would set an equilibrium state moving).
    fn initial_internal_forces(
        &self,
        model: &Model,
        k: &Csc,
        u0: &[f64],
    ) -> Result<Vec<f64>, FemError> {
        let state = self
            .solver
            .initial
            .as_ref()
            .and_then(|i| i.behaviour.as_ref());
        let Some(state) = state else {
            return Ok(k.mul(u0));
        };
        let mut plastic = crate::behaviour::PlasticCells::new(
            model,
            &self.solver.behaviours,
            self.solver.newton.symmetrize,
        )?;
        if let Some(pc) = plastic.as_mut() {
            pc.restore(state)?;
        }
        crate::nonlinear::internal_forces(model, k, &mut plastic, u0)
    }
}

/// Whether every DOF that no condition pins (eliminated, or a dualised
/// condition on it alone) has a mass: then K + M/(βΔt²) is definite
/// whatever holds the body.
fn mass_holds(model: &Model, loads: &Loads, t0: f64, m: &Csc) -> Result<bool, FemError> {
    let nd = model.dofs().len();
    let mut pinned = vec![false; nd];
    for i in loads.eliminated(model, t0)?.keys() {
        pinned[*i] = true;
    }
    for r in loads.equality_rows(model, t0)? {
        if let [(i, c)] = r.terms.as_slice() {
            if *c != 0.0 {
                pinned[*i] = true;
            }
        }
    }
    let d = m.diagonal();
    Ok((0..nd).all(|i| pinned[i] || d[i] > 0.0))
}

/// code_aster's `accel0`: M a₀ = f_ext(t₀) − f_int(u₀) on the free DOFs,
/// the dualised rows B a₀ = d(t₀) − B u₀, eliminated DOFs a₀ = 0. `None`
/// when the system is singular.
fn initial_acceleration(
    model: &Model,
    loads: &Loads,
    t0: f64,
    u0: &[f64],
    m: &Csc,
    fext0: &[f64],
    fint0: &[f64],
) -> Result<Option<Vec<f64>>, FemError> {
    let nd = model.dofs().len();
    let elim = loads.eliminated(model, t0)?;
    let mut map = vec![usize::MAX; nd];
    let mut nfree = 0;
    for (i, slot) in map.iter_mut().enumerate() {
        if !elim.contains_key(&i) {
            *slot = nfree;
            nfree += 1;
        }
    }
    // A DOF imposed twice is one condition (as in the Newton loop).
    let mut rows: Vec<(Vec<(usize, f64)>, f64)> = Vec::new();
    let mut single: HashMap<usize, ()> = HashMap::new();
    for r in loads.equality_rows(model, t0)? {
        let terms: Vec<(usize, f64)> = r
            .terms
            .iter()
            .filter(|(i, _)| map[*i] != usize::MAX)
            .map(|&(i, c)| (map[i], c))
            .collect();
        if terms.is_empty() {
            continue;
        }
        if let [(i, _)] = terms.as_slice() {
            if single.insert(*i, ()).is_some() {
                continue;
            }
        }
        let bu: f64 = r.terms.iter().map(|&(i, c)| c * u0[i]).sum();
        rows.push((terms, r.rhs - bu));
    }
    let mff = restrict(m, &map, nfree);
    let nk = rows.len();
    let mut extra = Vec::new();
    for (k, (terms, _)) in rows.iter().enumerate() {
        for &(i, c) in terms {
            extra.push((nfree + k, i, c));
            extra.push((i, nfree + k, c));
        }
    }
    let a = mff.with_extra(nfree + nk, extra);
    let mut b = vec![0.0; nfree + nk];
    for i in 0..nd {
        if map[i] != usize::MAX {
            b[map[i]] = fext0[i] - fint0[i];
        }
    }
    for (k, (_, d)) in rows.iter().enumerate() {
        b[nfree + k] = *d;
    }
    match linalg::solve_with(&a, &b, nfree, nk == 0, None) {
        Ok(sol) => {
            let mut acc = vec![0.0; nd];
            for i in 0..nd {
                if map[i] != usize::MAX {
                    acc[i] = sol.x[map[i]];
                }
            }
            Ok(Some(acc))
        }
        Err(_) => Ok(None),
    }
}

/// The Newmark family's [`IncrementTerms`].
struct Newmark {
    beta: f64,
    gamma: f64,
    /// (coeequ, coeext = coeint) of a weighted equilibrium: (1/(1+α), −α/(1+α)).
    weights: (f64, f64),
    mass: Csc,
    damping: Option<Csc>,
    /// The last converged state.
    u: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    fext: Vec<f64>,
    fint: Vec<f64>,
    /// The increment's step, matrix, offset and predicted v, a at u = uₙ.
    dt: f64,
    matrix: Csc,
    offset: Vec<f64>,
    v_pred: Vec<f64>,
    a_pred: Vec<f64>,
    mass_holds: bool,
    /// `ENERGIE`'s balance.
    balance: Option<EnergyBalance>,
}

impl Newmark {
    #[allow(clippy::too_many_arguments)]
    fn new(
        scheme: Scheme,
        mass: Csc,
        damping: Option<Csc>,
        u: Vec<f64>,
        v: Vec<f64>,
        a: Vec<f64>,
        fext: Vec<f64>,
        fint: Vec<f64>,
        mass_holds: bool,
    ) -> Newmark {
        let (beta, gamma) = scheme.beta_gamma();
        let weights = match scheme.weighted_alpha() {
            Some(alpha) => (1. / (1. + alpha), -alpha / (1. + alpha)),
            None => (1.0, 0.0),
        };
        let n = u.len();
        let matrix = mass.clone();
        Newmark {
            beta,
            gamma,
            weights,
            mass,
            damping,
            u,
            v,
            a,
            fext,
            fint,
            dt: f64::NAN,
            matrix,
            offset: vec![0.0; n],
            v_pred: vec![0.0; n],
            a_pred: vec![0.0; n],
            mass_holds,
            balance: None,
        }
    }

    fn coefficients(&self) -> (f64, f64) {
        let (b, g, dt) = (self.beta, self.gamma, self.dt);
        (1. / (b * dt * dt), g / (b * dt))
    }

    /// v(u), a(u) of the current increment.
    fn kinematics_at(&self, u: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (cm, cc) = self.coefficients();
        let v = (0..u.len())
            .map(|i| self.v_pred[i] + cc * (u[i] - self.u[i]))
            .collect();
        let a = (0..u.len())
            .map(|i| self.a_pred[i] + cm * (u[i] - self.u[i]))
            .collect();
        (v, a)
    }
}

impl IncrementTerms for Newmark {
    fn begin(&mut self, from: f64, to: f64, _u: &[f64]) -> Result<bool, FemError> {
        let dt = to - from;
        if dt.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(FemError::Model(format!(
                "time step from {from} to {to}: the instants must increase"
            )));
        }
        // NaN in the previous step counts as a change.
        let diff = (dt - self.dt).abs();
        let changed = diff.is_nan() || diff > 1e-12 * dt;
        self.dt = dt;
        let (b, g) = (self.beta, self.gamma);
        let n = self.u.len();
        // code_aster's predictors (ndnpas, DEPLACEMENT): v, a at Δu = 0.
        for i in 0..n {
            self.v_pred[i] = (b - g) / b * self.v[i] + (2. * b - g) * dt / (2. * b) * self.a[i];
            self.a_pred[i] = -self.v[i] / (b * dt) + (2. * b - 1.) / (2. * b) * self.a[i];
        }
        let (cm, cc) = self.coefficients();
        let (equ, ext) = self.weights;
        if changed {
            let mut mat = self.mass.clone();
            for v in mat.values.iter_mut() {
                *v *= equ * cm;
            }
            if let Some(c) = &self.damping {
                for (v, d) in mat.values.iter_mut().zip(&c.values) {
                    *v += equ * cc * d;
                }
            }
            self.matrix = mat;
        }
        // M a(u) + C v(u) = (cm M + cc C)(u − uₙ) + M a_pred + C v_pred.
        let mut off = self.mass.mul(&self.a_pred);
        if let Some(c) = &self.damping {
            for (o, x) in off.iter_mut().zip(c.mul(&self.v_pred)) {
                *o += x;
            }
        }
        for i in 0..n {
            self.offset[i] = -equ * off[i] + ext * (self.fext[i] - self.fint[i]);
        }
        Ok(changed)
    }

    fn matrix(&self) -> &Csc {
        &self.matrix
    }

    fn offset(&self) -> &[f64] {
        &self.offset
    }

    fn force(&self, u: &[f64]) -> Vec<f64> {
        let du: Vec<f64> = u.iter().zip(&self.u).map(|(a, b)| a - b).collect();
        self.matrix.mul(&du)
    }

    fn reference(&self, u: &[f64]) -> f64 {
        let (v, _) = self.kinematics_at(u);
        let coiner = 1. / (self.beta * self.dt);
        self.mass
            .mul(&v)
            .iter()
            .fold(0.0f64, |m, x| m.max((coiner * x).abs()))
    }

    fn needs_internal_forces(&self) -> bool {
        self.weights.1 != 0.0
    }

    fn converged(&mut self, _to: f64, u: &[f64], fext: &[f64], fint: Option<&[f64]>) {
        let (v, a) = self.kinematics_at(u);
        self.v = v;
        self.a = a;
        self.u = u.to_vec();
        self.fext = fext.to_vec();
        if let Some(f) = fint {
            self.fint = f.to_vec();
        }
    }

    fn motion(&self) -> Motion {
        Motion {
            velocity: self.v.clone(),
            acceleration: self.a.clone(),
        }
    }

    fn mass_holds(&self) -> bool {
        self.mass_holds
    }

    fn wants_balance(&self) -> bool {
        self.balance.is_some()
    }

    /// code_aster's external forces are the loads and the reactions of the
    /// conditions (−CNDIRI): on the dualised rows −Σ λ·row, on an
    /// eliminated DOF what the equilibrium leaves there,
    /// f_int + M a + C v + f_liai.
    fn balance(&mut self, to: f64, forces: &ConvergedForces) {
        let Some(b) = self.balance.as_mut() else {
            return;
        };
        let mut external: Vec<f64> = forces
            .loads
            .iter()
            .zip(forces.reactions)
            .map(|(l, r)| l + r)
            .collect();
        if !forces.eliminated.is_empty() {
            let ma = self.mass.mul(&self.a);
            let cv = self.damping.as_ref().map(|c| c.mul(&self.v));
            for &i in forces.eliminated {
                external[i] = forces.internal[i]
                    + ma[i]
                    + cv.as_ref().map_or(0.0, |c| c[i])
                    + forces.links[i];
            }
        }
        b.record(
            to,
            &self.u,
            &self.v,
            &StateForces {
                external: &external,
                internal: forces.internal,
                links: forces.links,
            },
            &self.mass,
            self.damping.as_ref(),
        );
    }

    fn energy_rows(&self) -> Vec<EnergyRow> {
        self.balance
            .as_ref()
            .map(|b| b.rows.clone())
            .unwrap_or_default()
    }
}
