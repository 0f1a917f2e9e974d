//! A quasi-static contact driver for linear elastic models: the stiffness
//! is assembled and factorised once (fem's assembly, faer's sparse
//! Cholesky, symmetric diagonal equilibration so that stiffness ratios of
//! 1e7 are harmless), then each instant solves the contact problem in the
//! multiplier space with the algorithm `DEFI_CONTACT` asks for — including
//! GCP and the continuous augmented-Lagrangian loops, which fem's Newton
//! solver does not host.
//!
//! Only eliminated kinematic conditions (`AFFE_CHAR_CINE`) are supported
//! here; dualised ones (`DDL_IMPO`, `LIAISON_DDL`) go through fem's
//! `StaticNonLinear` with [`crate::ZoneContact`] as a source.

use std::collections::HashMap;

use aster_fem::assembly::{assemble_stiffness, restrict};
use aster_fem::linalg::Csc;
use aster_fem::{Load, Loads, Model};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Col, Mat, Side};

use crate::dual::{ColumnCache, StiffnessSolve};
use crate::error::ContactError;
use crate::source::ZoneContact;
use crate::step::{solve_step_cached, StepReport};
use crate::zone::ContactDefinition;

enum Factor {
    Llt(faer::sparse::linalg::solvers::Llt<usize, f64>),
    Lu(Box<faer::sparse::linalg::solvers::Lu<usize, f64>>),
}

/// The factorised stiffness on the free DOFs of a model.
pub struct FactorizedStiffness {
    k: Csc,
    /// Free index of each DOF, `usize::MAX` when eliminated.
    map: Vec<usize>,
    free: Vec<usize>,
    scale: Vec<f64>,
    factor: Factor,
}

impl FactorizedStiffness {
    /// Assembles and factorises K on the DOFs not eliminated by `loads`.
    pub fn new(model: &Model, loads: &Loads) -> Result<Self, ContactError> {
        let k = assemble_stiffness(model)
            .map_err(|e: aster_fem::FemError| ContactError::Solver(e.to_string()))?;
        Self::from_assembled(model, loads, k)
    }

    /// Factorises an already assembled stiffness `k` of `model` (from
    /// [`assemble_stiffness`]) on the DOFs not eliminated by `loads`: lets
    /// a caller time or reuse the assembly apart from the factorisation.
    pub fn from_assembled(model: &Model, loads: &Loads, k: Csc) -> Result<Self, ContactError> {
        if k.n != model.dofs().len() {
            return Err(ContactError::Solver(format!(
                "assembled stiffness of {} unknowns for a model of {}",
                k.n,
                model.dofs().len()
            )));
        }
        if loads
            .items
            .iter()
            .any(|i| matches!(i.load, Load::Imposed { .. } | Load::Relation { .. }))
        {
            return Err(ContactError::Unsupported {
                feature: "dualised conditions (DDL_IMPO, LIAISON_DDL) in the linear contact driver".into(),
                hint: "impose them by elimination (AFFE_CHAR_CINE) or run fem's StaticNonLinear with ZoneContact sources".into(),
            });
        }
        let fem = |e: aster_fem::FemError| ContactError::Solver(e.to_string());
        let elim = loads.eliminated(model, 0.0).map_err(fem)?;
        let n = model.dofs().len();
        let mut map = vec![usize::MAX; n];
        let mut free = Vec::new();
        for (i, m) in map.iter_mut().enumerate() {
            if !elim.contains_key(&i) {
                *m = free.len();
                free.push(i);
            }
        }
        let mut kff = restrict(&k, &map, free.len());
        let scale: Vec<f64> = kff
            .diagonal()
            .iter()
            .map(|d| {
                if *d > 0.0 && d.is_finite() {
                    1.0 / d.sqrt()
                } else {
                    1.0
                }
            })
            .collect();
        for j in 0..kff.n {
            for p in kff.col_ptr[j]..kff.col_ptr[j + 1] {
                kff.values[p] *= scale[kff.row_idx[p]] * scale[j];
            }
        }
        let symbolic =
            SymbolicSparseColMatRef::new_checked(kff.n, kff.n, &kff.col_ptr, None, &kff.row_idx);
        let mat = SparseColMatRef::new(symbolic, &kff.values);
        let factor = match mat.sp_cholesky(Side::Lower) {
            Ok(f) => Factor::Llt(f),
            Err(_) => Factor::Lu(Box::new(mat.sp_lu().map_err(|e| {
                ContactError::Solver(format!(
                    "the stiffness is singular ({e:?}): some degrees of freedom are not held"
                ))
            })?)),
        };
        Ok(FactorizedStiffness {
            k,
            map,
            free,
            scale,
            factor,
        })
    }

    fn solve_once(&self, b: &[f64]) -> Vec<f64> {
        let mut c = Col::<f64>::from_fn(b.len(), |i| b[i] * self.scale[i]);
        match &self.factor {
            Factor::Llt(f) => f.solve_in_place(c.as_mat_mut()),
            Factor::Lu(f) => f.solve_in_place(c.as_mat_mut()),
        }
        (0..b.len()).map(|i| c[i] * self.scale[i]).collect()
    }

    /// [`Self::solve_once`] for several right-hand sides in one block
    /// solve: the factor is traversed once for all of them.
    fn solve_once_many(&self, bs: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let n = self.free.len();
        let mut m = Mat::<f64>::from_fn(n, bs.len(), |i, j| bs[j][i] * self.scale[i]);
        match &self.factor {
            Factor::Llt(f) => f.solve_in_place(m.as_mut()),
            Factor::Lu(f) => f.solve_in_place(m.as_mut()),
        }
        (0..bs.len())
            .map(|j| (0..n).map(|i| m[(i, j)] * self.scale[i]).collect())
            .collect()
    }

    /// [`Self::solve_free`] for several right-hand sides: block solves,
    /// then the refinement of the columns whose residual is too large, in
    /// one block too.
    fn solve_free_many(&self, bs: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let mut xs = self.solve_once_many(bs);
        for _ in 0..2 {
            let mut need = Vec::new();
            let mut residuals = Vec::new();
            for (j, (b, x)) in bs.iter().zip(&xs).enumerate() {
                let bmax = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let kx = self.mul_free(x);
                let r: Vec<f64> = b.iter().zip(&kx).map(|(bi, ki)| bi - ki).collect();
                if r.iter().fold(0.0f64, |m, v| m.max(v.abs())) > 1e-12 * bmax {
                    need.push(j);
                    residuals.push(r);
                }
            }
            if need.is_empty() {
                break;
            }
            for (j, dx) in need.into_iter().zip(self.solve_once_many(&residuals)) {
                for (xi, di) in xs[j].iter_mut().zip(&dx) {
                    *xi += di;
                }
            }
        }
        xs
    }

    /// K_ff x for a free-DOF vector.
    fn mul_free(&self, x: &[f64]) -> Vec<f64> {
        let mut full = vec![0.0; self.map.len()];
        for (k, &i) in self.free.iter().enumerate() {
            full[i] = x[k];
        }
        let y = self.k.mul(&full);
        self.free.iter().map(|&i| y[i]).collect()
    }

    /// Solve, refined (at most twice) while the residual exceeds 1e-12 of
    /// the right-hand side: soft modes (a body held by springs 1e8 times
    /// softer than its elements) are otherwise determined only to round-off.
    fn solve_free(&self, b: &[f64]) -> Vec<f64> {
        let mut x = self.solve_once(b);
        let bmax = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for _ in 0..2 {
            let kx = self.mul_free(&x);
            let r: Vec<f64> = b.iter().zip(&kx).map(|(bi, ki)| bi - ki).collect();
            if r.iter().fold(0.0f64, |m, v| m.max(v.abs())) <= 1e-12 * bmax {
                break;
            }
            let dx = self.solve_once(&r);
            for (xi, di) in x.iter_mut().zip(&dx) {
                *xi += di;
            }
        }
        x
    }

    /// The displacement without contact at time `t`: eliminated values
    /// imposed, K_ff u_f = f_f − K_fe u_e.
    pub fn free_solution(
        &self,
        model: &Model,
        loads: &Loads,
        t: f64,
    ) -> Result<Vec<f64>, ContactError> {
        let fem = |e: aster_fem::FemError| ContactError::Solver(e.to_string());
        let elim: HashMap<usize, f64> = loads.eliminated(model, t).map_err(fem)?;
        let mut u = vec![0.0; self.map.len()];
        for (&i, &v) in &elim {
            if self.map.get(i) != Some(&usize::MAX) {
                return Err(ContactError::Solver(format!(
                    "the set of eliminated degrees of freedom changed at time {t}"
                )));
            }
            u[i] = v;
        }
        let f = loads.external_forces(model, t).map_err(fem)?;
        let ku = self.k.mul(&u);
        let rhs: Vec<f64> = self.free.iter().map(|&i| f[i] - ku[i]).collect();
        let uf = self.solve_free(&rhs);
        for (k, &i) in self.free.iter().enumerate() {
            u[i] = uf[k];
        }
        Ok(u)
    }
}

impl StiffnessSolve for FactorizedStiffness {
    fn len(&self) -> usize {
        self.map.len()
    }

    fn reads(&self, i: usize) -> bool {
        self.map.get(i).is_some_and(|&m| m != usize::MAX)
    }

    fn solve(&self, rhs: &[f64]) -> Result<Vec<f64>, String> {
        if rhs.len() != self.map.len() {
            return Err(format!(
                "right-hand side of {} values for {} unknowns",
                rhs.len(),
                self.map.len()
            ));
        }
        let b: Vec<f64> = self.free.iter().map(|&i| rhs[i]).collect();
        let x = self.solve_free(&b);
        if x.iter().any(|v| !v.is_finite()) {
            return Err(
                "the factorised stiffness gave a non-finite solution (singular system)".into(),
            );
        }
        let mut out = vec![0.0; self.map.len()];
        for (k, &i) in self.free.iter().enumerate() {
            out[i] = x[k];
        }
        Ok(out)
    }

    fn solve_many(&self, rhs: &[Vec<f64>]) -> Result<Vec<Vec<f64>>, String> {
        if let Some(bad) = rhs.iter().find(|r| r.len() != self.map.len()) {
            return Err(format!(
                "right-hand side of {} values for {} unknowns",
                bad.len(),
                self.map.len()
            ));
        }
        let bs: Vec<Vec<f64>> = rhs
            .iter()
            .map(|r| self.free.iter().map(|&i| r[i]).collect())
            .collect();
        self.solve_free_many(&bs)
            .into_iter()
            .map(|x| {
                if x.iter().any(|v| !v.is_finite()) {
                    return Err(
                        "the factorised stiffness gave a non-finite solution (singular system)"
                            .to_string(),
                    );
                }
                let mut out = vec![0.0; self.map.len()];
                for (k, &i) in self.free.iter().enumerate() {
                    out[i] = x[k];
                }
                Ok(out)
            })
            .collect()
    }
}

/// One computed instant.
#[derive(Clone, Debug, PartialEq)]
pub struct Instant {
    pub time: f64,
    pub report: StepReport,
    /// Normal force of every pair of every zone at this instant.
    pub forces: Vec<Vec<f64>>,
}

/// Runs a quasi-static contact analysis of a linear elastic model over
/// `instants` (the first is the initial state, zero displacement, not
/// computed). The zones keep the state of the last instant.
pub fn run_linear(
    def: &ContactDefinition,
    zones: &mut [ZoneContact],
    model: &Model,
    loads: &Loads,
    instants: &[f64],
) -> Result<Vec<Instant>, ContactError> {
    let k = FactorizedStiffness::new(model, loads)?;
    // One K for the whole analysis: its columns K⁻¹aⱼ serve every step.
    let mut cache = ColumnCache::new();
    let mut u = vec![0.0; model.dofs().len()];
    let mut out = Vec::with_capacity(instants.len());
    for &t in instants.iter().skip(1) {
        let u_free = k.free_solution(model, loads, t)?;
        let report = solve_step_cached(
            def,
            zones,
            model.mesh(),
            model.dofs(),
            &k,
            &u_free,
            &u,
            &mut cache,
        )?;
        u = report.u.clone();
        out.push(Instant {
            time: t,
            report,
            forces: zones.iter().map(|z| z.forces().to_vec()).collect(),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::{two_blocks_mesh, two_blocks_problem};

    #[test]
    fn block_solves_match_single_solves() {
        let mesh = two_blocks_mesh(3).unwrap();
        let (model, loads) = two_blocks_problem(mesh, 1e3).unwrap();
        let k = FactorizedStiffness::new(&model, &loads).unwrap();
        let n = k.len();
        let rhs: Vec<Vec<f64>> = (0..5)
            .map(|j| {
                (0..n)
                    .map(|i| ((i * 7 + j * 3) % 11) as f64 - 5.0)
                    .collect()
            })
            .collect();
        let block = k.solve_many(&rhs).unwrap();
        assert_eq!(block.len(), rhs.len());
        for (b, x) in rhs.iter().zip(&block) {
            let single = k.solve(b).unwrap();
            let scale = single.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(scale > 0.0);
            for (a, c) in x.iter().zip(&single) {
                assert!((a - c).abs() <= 1e-10 * scale, "{a} vs {c}");
            }
        }
        assert!(k.solve_many(&[vec![1.0; n + 1]]).is_err());
    }
}
