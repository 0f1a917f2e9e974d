//! The energy balance of a dynamic analysis (`DYNA_NON_LINE/ENERGIE`):
//! code_aster's `nmener`/`enerca` bookkeeping, one row per converged
//! increment.
//!
//! Between two converged states (u₀, v₀) and (u₁, v₁), with Δu = u₁ − u₀,
//! v̄ = ½(v₀ + v₁), Δv = v₁ − v₀ and each force f of a kind averaged over
//! the increment, f̄ = ½(f₀ + f₁) (the trapezoidal rule):
//!
//! - `TRAV_EXT` += Δu · f̄_ext, the external forces being the loads and the
//!   reactions of the conditions (code_aster's −CNDIRI);
//! - `ENER_CIN` += v̄ · M Δv (= the change of ½ vᵀMv, M symmetric);
//! - `ENER_TOT` += Δu · f̄_int (the internal forces B^Tσ);
//! - `TRAV_AMOR` += Δu · C v̄ (Rayleigh damping);
//! - `TRAV_LIAI` += Δu · f̄_liai (the contact and unilateral forces, on the
//!   internal-force side of the equilibrium: f_int + M a + C v + f_liai =
//!   f_ext);
//! - `DISS_SCH` += TRAV_EXT − ENER_CIN − ENER_TOT − TRAV_AMOR − TRAV_LIAI
//!   of the increment: what the time scheme dissipates (zero for the
//!   trapezoidal Newmark rule on a linear elastic body).
//!
//! The first increment's "previous" external force is code_aster's
//! (`nmfini`): M a₀ + C v₀ + f_int(u₀), the equilibrium of the initial
//! state, and its previous link force is zero. Every column is the sum
//! from the initial state; the initial state's row is all zeros.

use crate::linalg::Csc;

/// One row of code_aster's `PARA_CALC` table (cumulated values).
#[derive(Clone, Debug, PartialEq)]
pub struct EnergyRow {
    pub time: f64,
    pub trav_ext: f64,
    pub ener_cin: f64,
    pub ener_tot: f64,
    pub trav_amor: f64,
    pub trav_liai: f64,
    pub diss_sch: f64,
}

impl EnergyRow {
    fn zero(time: f64) -> Self {
        EnergyRow {
            time,
            trav_ext: 0.0,
            ener_cin: 0.0,
            ener_tot: 0.0,
            trav_amor: 0.0,
            trav_liai: 0.0,
            diss_sch: 0.0,
        }
    }
}

/// The forces of a converged state, per DOF index.
pub struct StateForces<'a> {
    /// External forces: loads and the reactions of the conditions.
    pub external: &'a [f64],
    /// Internal forces (B^Tσ, springs).
    pub internal: &'a [f64],
    /// Contact and unilateral link forces (internal-force side).
    pub links: &'a [f64],
}

#[derive(Clone, Debug)]
struct Previous {
    u: Vec<f64>,
    v: Vec<f64>,
    external: Vec<f64>,
    internal: Vec<f64>,
    links: Vec<f64>,
}

/// The running balance: the last converged state and the rows so far.
#[derive(Clone, Debug)]
pub struct EnergyBalance {
    previous: Previous,
    total: EnergyRow,
    pub rows: Vec<EnergyRow>,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn mean_dot(du: &[f64], f0: &[f64], f1: &[f64]) -> f64 {
    du.iter()
        .zip(f0.iter().zip(f1))
        .map(|(d, (a, b))| d * 0.5 * (a + b))
        .sum()
}

impl EnergyBalance {
    /// Starts from the initial state (time t₀, u₀, v₀) with code_aster's
    /// initial external force (M a₀ + C v₀ + f_int(u₀), `nmfini`) and its
    /// internal forces; the row of t₀ is all zeros.
    pub fn new(t0: f64, u0: &[f64], v0: &[f64], external0: Vec<f64>, internal0: Vec<f64>) -> Self {
        let n = u0.len();
        EnergyBalance {
            previous: Previous {
                u: u0.to_vec(),
                v: v0.to_vec(),
                external: external0,
                internal: internal0,
                links: vec![0.0; n],
            },
            total: EnergyRow::zero(t0),
            rows: vec![EnergyRow::zero(t0)],
        }
    }

    /// Adds the increment to the converged state (time `t`, `u`, `v`) and
    /// its row.
    pub fn record(
        &mut self,
        t: f64,
        u: &[f64],
        v: &[f64],
        forces: &StateForces,
        mass: &Csc,
        damping: Option<&Csc>,
    ) {
        let p = &self.previous;
        let du: Vec<f64> = u.iter().zip(&p.u).map(|(a, b)| a - b).collect();
        let vbar: Vec<f64> = v.iter().zip(&p.v).map(|(a, b)| 0.5 * (a + b)).collect();
        let dv: Vec<f64> = v.iter().zip(&p.v).map(|(a, b)| a - b).collect();
        let wext = mean_dot(&du, &p.external, forces.external);
        let wint = mean_dot(&du, &p.internal, forces.internal);
        let liai = mean_dot(&du, &p.links, forces.links);
        let ecin = dot(&vbar, &mass.mul(&dv));
        let amor = damping.map_or(0.0, |c| dot(&du, &c.mul(&vbar)));
        let wsch = wext - ecin - wint - amor - liai;
        let tot = &mut self.total;
        tot.time = t;
        tot.trav_ext += wext;
        tot.ener_cin += ecin;
        tot.ener_tot += wint;
        tot.trav_amor += amor;
        tot.trav_liai += liai;
        tot.diss_sch += wsch;
        self.rows.push(tot.clone());
        self.previous = Previous {
            u: u.to_vec(),
            v: v.to_vec(),
            external: forces.external.to_vec(),
            internal: forces.internal.to_vec(),
            links: forces.links.to_vec(),
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit mass on a unit spring, trapezoidal Newmark by hand: the
    /// balance of one increment.
    #[test]
    fn one_increment_by_hand() {
        let mut m = Csc::from_columns(1, vec![vec![0]]);
        m.add(0, 0, 2.0);
        let mut b = EnergyBalance::new(0.0, &[0.0], &[1.0], vec![0.0], vec![0.0]);
        // u₁ = 0.1, v₁ = 0.8, f_int = 3 u, an external force 0.5 at t₁.
        let f = StateForces {
            external: &[0.5],
            internal: &[0.3],
            links: &[0.0],
        };
        b.record(0.1, &[0.1], &[0.8], &f, &m, None);
        let r = &b.rows[1];
        assert!((r.trav_ext - 0.1 * 0.25).abs() < 1e-15);
        assert!((r.ener_tot - 0.1 * 0.15).abs() < 1e-15);
        // v̄ M Δv = 0.9 · 2 · (−0.2) = ½·2·(0.64 − 1).
        assert!((r.ener_cin - (0.64 - 1.0)).abs() < 1e-15);
        assert!((r.diss_sch - (r.trav_ext - r.ener_cin - r.ener_tot)).abs() < 1e-15);
        assert_eq!(b.rows[0], EnergyRow::zero(0.0));
    }
}
