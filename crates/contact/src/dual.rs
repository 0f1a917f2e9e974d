//! Contact resolution in the space of the multipliers.
//!
//! For one linearised problem `K u = f` under rows `A u ≤ b`, the
//! displacement is `u = u_free − K⁻¹ Aᵀ λ` (`u_free = K⁻¹ f`), and the
//! multipliers solve the linear complementarity problem
//!
//! ```text
//! λ ≥ 0,   s = q + (S + E) λ ≥ 0,   λᵀ s = 0,
//! S = A K⁻¹ Aᵀ (contact compliance),  q = b − A u_free,  E = diag(εᵢ)
//! ```
//!
//! with εᵢ = 0 for exact rows and εᵢ = 1/(penalty) for penalised rows
//! (then λᵢ = (Aᵢu − bᵢ)/εᵢ: the penalty law). Only solves with K are needed,
//! so any factorisation can be plugged in through [`StiffnessSolve`]. This is
//! how code_aster's discrete algorithms work (Schur complement on the
//! contact set); the algorithms:
//!
//! - [`DualAlgorithm::ActiveSet`] (CONTRAINTE, and PENALISATION with ε > 0):
//!   exact finite algorithm; the columns K⁻¹aⱼ are computed only for rows
//!   that become active.
//! - [`DualAlgorithm::Gcp`] (GCP): MPRGP, Dostál's modified proportioning
//!   with reduced gradient projections — a projected conjugate gradient with
//!   proven convergence, matrix-free (one K solve per iteration).
//! - [`DualAlgorithm::AugmentedLagrangian`] (continuous STANDARD with
//!   POINT_FIXE): multiplier updates λ ← max(0, λ + c (Au − b)), each inner
//!   problem solved exactly.
//! - [`DualAlgorithm::SemiSmoothNewton`] (continuous with NEWTON): the
//!   generalised Newton method on λ = max(0, λ − c s), i.e. the primal–dual
//!   active set strategy.

use std::collections::HashMap;
use std::rc::Rc;

use nalgebra::{DMatrix, DVector};

use crate::error::ContactError;

/// Solves with the (factorised) tangent stiffness.
pub trait StiffnessSolve {
    /// Number of unknowns.
    fn len(&self) -> usize;
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// `K⁻¹ rhs` with every kinematic condition homogeneous (imposed
    /// displacements at zero).
    fn solve(&self, rhs: &[f64]) -> Result<Vec<f64>, String>;
    /// Whether `solve` reads `rhs[i]` (false for an eliminated DOF, whose
    /// value is imposed): rows differing only there share their column
    /// K⁻¹a in a [`ColumnCache`].
    fn reads(&self, _i: usize) -> bool {
        true
    }
    /// `K⁻¹ rhsⱼ` for several right-hand sides; a factorisation overrides
    /// it with a block solve (one traversal of the factor for all).
    fn solve_many(&self, rhs: &[Vec<f64>]) -> Result<Vec<Vec<f64>>, String> {
        rhs.iter().map(|r| self.solve(r)).collect()
    }
}

/// Columns K⁻¹aⱼ kept across dual solves with the same factorised K (the
/// geometric iterations of a step, the steps of a linear analysis): a row
/// whose coefficients on the DOFs K reads are bitwise unchanged reuses its
/// column instead of a new solve. Valid for one K only: make a new cache
/// when K changes.
#[derive(Debug, Default)]
pub struct ColumnCache {
    columns: HashMap<Vec<(usize, u64)>, Rc<Vec<f64>>>,
    /// Columns taken from the cache instead of solved.
    pub hits: usize,
}

impl ColumnCache {
    pub fn new() -> ColumnCache {
        ColumnCache::default()
    }

    /// Number of columns held.
    pub fn len(&self) -> usize {
        self.columns.len()
    }

    pub fn is_empty(&self) -> bool {
        self.columns.is_empty()
    }

    fn key(k: &dyn StiffnessSolve, row: &IndexedRow) -> Vec<(usize, u64)> {
        let mut key: Vec<(usize, u64)> = row
            .terms
            .iter()
            .filter(|&&(i, c)| c != 0.0 && k.reads(i))
            .map(|&(i, c)| (i, c.to_bits()))
            .collect();
        key.sort_unstable();
        key
    }
}

/// A row `Σ coef·u[index] ≤ rhs` in solver numbering.
#[derive(Clone, Debug, PartialEq)]
pub struct IndexedRow {
    pub terms: Vec<(usize, f64)>,
    pub rhs: f64,
}

impl IndexedRow {
    fn dot(&self, u: &[f64]) -> f64 {
        self.terms.iter().map(|&(i, c)| c * u[i]).sum()
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DualAlgorithm {
    /// Exact active set; `max_iter` bounds the changes of the set
    /// (ITER_CONT_MULT × number of rows); `stop_singulier` = false drops a
    /// redundant row instead of failing.
    ActiveSet {
        max_iter: usize,
        stop_singulier: bool,
    },
    /// Projected conjugate gradient (MPRGP); `tol` on the projected gradient
    /// (an interpenetration), `None` = 1e-10 × max |q|.
    Gcp { tol: Option<f64>, max_iter: usize },
    /// Augmented Lagrangian fixed point (`coef` = c relative to each row's
    /// compliance: cᵢ = coef / Sᵢᵢ); stops when the multipliers change by
    /// less than `resi` relatively.
    AugmentedLagrangian {
        coef: f64,
        max_iter: usize,
        resi: f64,
    },
    /// Semi-smooth Newton / primal–dual active set (cᵢ = coef / Sᵢᵢ).
    SemiSmoothNewton { coef: f64, max_iter: usize },
}

/// The outcome of a dual solve.
#[derive(Clone, Debug, PartialEq)]
pub struct DualSolution {
    pub lambda: Vec<f64>,
    pub u: Vec<f64>,
    pub active: Vec<bool>,
    /// Iterations of the algorithm (active-set changes, CG steps, or
    /// multiplier updates).
    pub iterations: usize,
    /// Number of solves with K.
    pub solves: usize,
}

/// Solves the contact LCP. `eps` holds εᵢ ≥ 0 per row; `warm` is an optional
/// initial active set (the previous step's).
pub fn solve_dual(
    k: &dyn StiffnessSolve,
    u_free: &[f64],
    rows: &[IndexedRow],
    eps: &[f64],
    algo: DualAlgorithm,
    warm: Option<&[bool]>,
) -> Result<DualSolution, ContactError> {
    solve_dual_cached(k, u_free, rows, eps, algo, warm, &mut ColumnCache::new())
}

/// [`solve_dual`] reusing (and filling) `cache`'s columns K⁻¹aⱼ; `cache`
/// must have been filled with the same K.
pub fn solve_dual_cached(
    k: &dyn StiffnessSolve,
    u_free: &[f64],
    rows: &[IndexedRow],
    eps: &[f64],
    algo: DualAlgorithm,
    warm: Option<&[bool]>,
    cache: &mut ColumnCache,
) -> Result<DualSolution, ContactError> {
    if u_free.len() != k.len() || eps.len() != rows.len() {
        return Err(ContactError::Solver(format!(
            "inconsistent sizes: {} unknowns, free solution of {}, {} rows, {} penalties",
            k.len(),
            u_free.len(),
            rows.len(),
            eps.len()
        )));
    }
    let mut ctx = Context::new(k, u_free, rows, eps, cache);
    let m = rows.len();
    if m == 0 {
        return ctx.finish(vec![], 0);
    }
    let (lambda, iterations) = match algo {
        DualAlgorithm::ActiveSet {
            max_iter,
            stop_singulier,
        } => {
            let init: Vec<bool> = match warm {
                Some(w) if w.len() == m => w.to_vec(),
                _ => ctx.q.iter().map(|&q| q < 0.0).collect(),
            };
            let shift = vec![0.0; m];
            ctx.active_set(init, &shift, &vec![0.0; m], max_iter, stop_singulier)?
        }
        DualAlgorithm::Gcp { tol, max_iter } => ctx.mprgp(tol, max_iter)?,
        DualAlgorithm::AugmentedLagrangian {
            coef,
            max_iter,
            resi,
        } => ctx.augmented_lagrangian(coef, max_iter, resi, warm)?,
        DualAlgorithm::SemiSmoothNewton { coef, max_iter } => ctx.pdas(coef, max_iter, warm)?,
    };
    ctx.finish(lambda, iterations)
}

fn dotv(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Size of the projected gradient (free part φ and chopped part β): how far
/// the multipliers are from the complementarity conditions.
fn projected_gradient_norm(phi: &[f64], beta: &[f64]) -> f64 {
    phi.iter().chain(beta).fold(0.0f64, |a, v| a.max(v.abs()))
}

/// The active sets an active-set loop has tried: meeting one again is
/// cycling, reported with the iteration and the number of rows.
#[derive(Default)]
struct SeenSets(Vec<Vec<bool>>);

impl SeenSets {
    fn visit(&mut self, active: &[bool], iterations: usize) -> Result<(), ContactError> {
        if self.0.iter().any(|s| s == active) {
            return Err(ContactError::Cycling {
                iterations,
                points: active.len(),
            });
        }
        self.0.push(active.to_vec());
        Ok(())
    }

    fn clear(&mut self) {
        self.0.clear();
    }
}

struct Context<'a> {
    k: &'a dyn StiffnessSolve,
    u_free: &'a [f64],
    rows: &'a [IndexedRow],
    eps: &'a [f64],
    q: Vec<f64>,
    /// K⁻¹ aⱼ, computed on demand (or taken from the cache).
    columns: Vec<Option<Rc<Vec<f64>>>>,
    cache: &'a mut ColumnCache,
    solves: usize,
    tol_s: f64,
}

impl<'a> Context<'a> {
    fn new(
        k: &'a dyn StiffnessSolve,
        u_free: &'a [f64],
        rows: &'a [IndexedRow],
        eps: &'a [f64],
        cache: &'a mut ColumnCache,
    ) -> Self {
        let q: Vec<f64> = rows.iter().map(|r| r.rhs - r.dot(u_free)).collect();
        let scale = q
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        Context {
            k,
            u_free,
            rows,
            eps,
            q,
            columns: vec![None; rows.len()],
            cache,
            solves: 0,
            tol_s: 1e-10 * scale,
        }
    }

    fn apply_transpose(&self, lambda: &[f64]) -> Vec<f64> {
        let mut v = vec![0.0; self.k.len()];
        for (r, &l) in self.rows.iter().zip(lambda) {
            if l != 0.0 {
                for &(i, c) in &r.terms {
                    v[i] += c * l;
                }
            }
        }
        v
    }

    fn column(&mut self, j: usize) -> Result<&[f64], ContactError> {
        if self.columns[j].is_none() {
            let key = ColumnCache::key(self.k, &self.rows[j]);
            let z = match self.cache.columns.get(&key) {
                Some(z) => {
                    self.cache.hits += 1;
                    Rc::clone(z)
                }
                None => {
                    let mut a = vec![0.0; self.k.len()];
                    for &(i, c) in &self.rows[j].terms {
                        a[i] += c;
                    }
                    let z = Rc::new(self.k.solve(&a).map_err(ContactError::Solver)?);
                    self.solves += 1;
                    self.cache.columns.insert(key, Rc::clone(&z));
                    z
                }
            };
            self.columns[j] = Some(z);
        }
        Ok(self.columns[j].as_deref().map_or(&[], |v| v.as_slice()))
    }

    /// Computes the missing columns K⁻¹aⱼ of `js` in one block solve (the
    /// rows entering the active set together), after the cache.
    fn prefetch(&mut self, js: &[usize]) -> Result<(), ContactError> {
        let mut missing: Vec<usize> = Vec::new();
        let mut keys: Vec<Vec<(usize, u64)>> = Vec::new();
        let mut duplicates: Vec<(usize, usize)> = Vec::new();
        for &j in js {
            if self.columns[j].is_some() {
                continue;
            }
            let key = ColumnCache::key(self.k, &self.rows[j]);
            if let Some(z) = self.cache.columns.get(&key) {
                self.cache.hits += 1;
                self.columns[j] = Some(Rc::clone(z));
            } else if let Some(p) = keys.iter().position(|k| *k == key) {
                duplicates.push((j, p));
            } else {
                missing.push(j);
                keys.push(key);
            }
        }
        if missing.is_empty() {
            return Ok(());
        }
        let rhs: Vec<Vec<f64>> = missing
            .iter()
            .map(|&j| {
                let mut a = vec![0.0; self.k.len()];
                for &(i, c) in &self.rows[j].terms {
                    a[i] += c;
                }
                a
            })
            .collect();
        let zs = self.k.solve_many(&rhs).map_err(ContactError::Solver)?;
        self.solves += missing.len();
        for ((&j, key), z) in missing.iter().zip(keys).zip(zs) {
            let z = Rc::new(z);
            self.cache.columns.insert(key, Rc::clone(&z));
            self.columns[j] = Some(z);
        }
        for (j, p) in duplicates {
            self.cache.hits += 1;
            self.columns[j] = self.columns[missing[p]].clone();
        }
        Ok(())
    }

    /// S_ij + ε_i δ_ij.
    fn entry(&mut self, i: usize, j: usize) -> Result<f64, ContactError> {
        let rows = self.rows;
        let z = self.column(j)?;
        let v = rows[i].dot(z);
        Ok(if i == j { v + self.eps[i] } else { v })
    }

    /// u(λ) using the cached columns (λ nonzero only on computed columns).
    fn displacement(&mut self, lambda: &[f64]) -> Result<Vec<f64>, ContactError> {
        let mut u = self.u_free.to_vec();
        for j in 0..lambda.len() {
            if lambda[j] != 0.0 {
                let l = lambda[j];
                let z = self.column(j)?;
                for (ui, zi) in u.iter_mut().zip(z) {
                    *ui -= l * zi;
                }
            }
        }
        Ok(u)
    }

    /// s = b − A u + ε λ.
    fn slack(&mut self, lambda: &[f64]) -> Result<Vec<f64>, ContactError> {
        let u = self.displacement(lambda)?;
        Ok(self
            .rows
            .iter()
            .zip(lambda)
            .zip(self.eps)
            .map(|((r, &l), &e)| r.rhs - r.dot(&u) + e * l)
            .collect())
    }

    /// Solves (S+E+diag(extra))_AA λ_A = −(q + shift)_A.
    fn solve_on(
        &mut self,
        set: &[usize],
        shift: &[f64],
        extra: &[f64],
    ) -> Result<Result<Vec<f64>, usize>, ContactError> {
        self.prefetch(set)?;
        let n = set.len();
        let mut mat = DMatrix::zeros(n, n);
        for (a, &i) in set.iter().enumerate() {
            for (b, &j) in set.iter().enumerate() {
                mat[(a, b)] = self.entry(i, j)? + if i == j { extra[i] } else { 0.0 };
            }
        }
        let rhs = DVector::from_iterator(n, set.iter().map(|&i| -(self.q[i] + shift[i])));
        let diag_max = (0..n).map(|a| mat[(a, a)].abs()).fold(0.0f64, f64::max);
        if let Some(ch) = mat.clone().cholesky() {
            // Cholesky succeeds on nearly singular matrices too: check pivots.
            let l = ch.l();
            if let Some(bad) = (0..n).find(|&a| l[(a, a)] * l[(a, a)] <= 1e-12 * diag_max) {
                return Ok(Err(set[bad]));
            }
            return Ok(Ok(ch.solve(&rhs).iter().copied().collect()));
        }
        // Not positive definite: redundant rows. Find the first dependent one.
        for a in 1..=n {
            let sub = mat.view((0, 0), (a, a)).clone_owned();
            let ok = sub.cholesky().is_some_and(|c| {
                let l = c.l();
                (0..a).all(|k| l[(k, k)] * l[(k, k)] > 1e-12 * diag_max)
            });
            if !ok {
                return Ok(Err(set[a - 1]));
            }
        }
        Ok(Err(set[n - 1]))
    }

    /// The multipliers of all rows with exactly the rows of `set` active:
    /// [`Context::solve_on`] scattered into a vector of every row (0 off the
    /// set); `Err(row)` names a redundant row.
    fn multipliers_on(
        &mut self,
        set: &[usize],
        shift: &[f64],
        extra: &[f64],
    ) -> Result<Result<Vec<f64>, usize>, ContactError> {
        Ok(self.solve_on(set, shift, extra)?.map(|on_set| {
            let mut lambda = vec![0.0; self.rows.len()];
            for (&i, l) in set.iter().zip(on_set) {
                lambda[i] = l;
            }
            lambda
        }))
    }

    /// Active set with "add all violated, drop the most negative" moves.
    /// `shift` and `extra` modify q and the diagonal (augmented Lagrangian).
    fn active_set(
        &mut self,
        mut active: Vec<bool>,
        shift: &[f64],
        extra: &[f64],
        max_iter: usize,
        stop_singulier: bool,
    ) -> Result<(Vec<f64>, usize), ContactError> {
        let m = self.rows.len();
        let mut seen = SeenSets::default();
        let mut dropped = vec![false; m];
        let max_iter = max_iter.max(2 * m + 2);
        for it in 0..max_iter {
            seen.visit(&active, it)?;
            let set: Vec<usize> = (0..m).filter(|&i| active[i] && !dropped[i]).collect();
            let mut lambda = match self.multipliers_on(&set, shift, extra)? {
                Ok(l) => l,
                Err(bad) => {
                    if stop_singulier {
                        return Err(ContactError::SingularContact { point: bad });
                    }
                    dropped[bad] = true;
                    active[bad] = false;
                    seen.clear();
                    continue;
                }
            };
            let lmax = lambda.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if let Some((i, _)) = set
                .iter()
                .map(|&i| (i, lambda[i]))
                .filter(|&(_, l)| l < -1e-12 * lmax)
                .min_by(|a, b| a.1.total_cmp(&b.1))
            {
                active[i] = false;
                continue;
            }
            for l in lambda.iter_mut() {
                *l = l.max(0.0);
            }
            let s = self.slack(&lambda)?;
            let mut changed = false;
            for i in 0..m {
                let si = s[i] + shift[i] + extra[i] * lambda[i];
                if !active[i] && !dropped[i] && si < -self.tol_s {
                    active[i] = true;
                    changed = true;
                }
            }
            if !changed {
                return Ok((lambda, it + 1));
            }
        }
        Err(ContactError::NotConverged {
            what: "contact active set",
            iterations: max_iter,
            residual: f64::NAN,
        })
    }

    /// (S + E) p, matrix-free: one K solve.
    fn apply(&mut self, p: &[f64]) -> Result<Vec<f64>, ContactError> {
        let v = self.apply_transpose(p);
        let z = self.k.solve(&v).map_err(ContactError::Solver)?;
        self.solves += 1;
        Ok(self
            .rows
            .iter()
            .zip(p)
            .zip(self.eps)
            .map(|((r, &pi), &e)| r.dot(&z) + e * pi)
            .collect())
    }

    /// Exact minimisation of ½λᵀMλ + qᵀλ from gradient `g` along `d`
    /// (M = S + E): (M d, dᵀM d, step α = gᵀd / dᵀM d), M d costing one K
    /// solve. Both moves of MPRGP (conjugate gradient and proportioning)
    /// take their step so.
    fn line_step(&mut self, d: &[f64], g: &[f64]) -> Result<(Vec<f64>, f64, f64), ContactError> {
        let md = self.apply(d)?;
        let dmd = dotv(d, &md);
        if dmd.is_nan() || dmd <= 0.0 {
            return Err(ContactError::Solver(
                "the contact compliance matrix is not positive definite".into(),
            ));
        }
        let alpha = dotv(g, d) / dmd;
        Ok((md, dmd, alpha))
    }

    /// MPRGP for min ½λᵀMλ + qᵀλ, λ ≥ 0 (gradient g = Mλ + q = s).
    fn mprgp(
        &mut self,
        tol: Option<f64>,
        max_iter: usize,
    ) -> Result<(Vec<f64>, usize), ContactError> {
        let m = self.rows.len();
        let tol = tol.filter(|t| *t > 0.0).unwrap_or(self.tol_s);
        let max_iter = if max_iter == 0 {
            (10 * m).max(100)
        } else {
            max_iter
        };
        // ‖M‖ by a few power iterations, for the expansion step length.
        let mut v: Vec<f64> = vec![1.0 / (m as f64).sqrt(); m];
        let mut norm_m = 0.0;
        for _ in 0..8 {
            let w = self.apply(&v)?;
            let n = w.iter().map(|x| x * x).sum::<f64>().sqrt();
            if n == 0.0 {
                break;
            }
            norm_m = n;
            v = w.iter().map(|x| x / n).collect();
        }
        if norm_m.is_nan() || norm_m <= 0.0 {
            return Err(ContactError::Solver(
                "the contact compliance matrix is zero".into(),
            ));
        }
        let alpha_bar = 1.0 / (1.1 * norm_m);
        let gamma = 1.0;
        let mut x = vec![0.0; m];
        let mut g = self.q.clone();
        let free = |x: &[f64], g: &[f64]| -> Vec<f64> {
            x.iter()
                .zip(g)
                .map(|(&xi, &gi)| if xi > 0.0 { gi } else { 0.0 })
                .collect()
        };
        let chopped = |x: &[f64], g: &[f64]| -> Vec<f64> {
            x.iter()
                .zip(g)
                .map(|(&xi, &gi)| if xi > 0.0 { 0.0 } else { gi.min(0.0) })
                .collect()
        };
        let mut p = free(&x, &g);
        for it in 0..max_iter {
            let phi = free(&x, &g);
            let beta = chopped(&x, &g);
            if projected_gradient_norm(&phi, &beta) <= tol {
                return Ok((x, it));
            }
            // Reduced free gradient φ̃ (largest feasible step α̅ along φ).
            let phi_t: Vec<f64> = x
                .iter()
                .zip(&phi)
                .map(|(&xi, &fi)| {
                    if fi > 0.0 {
                        (xi / alpha_bar).min(fi)
                    } else {
                        fi
                    }
                })
                .collect();
            if dotv(&beta, &beta) <= gamma * gamma * dotv(&phi_t, &phi) {
                if dotv(&p, &p) == 0.0 {
                    p = phi.clone();
                }
                let (ap, pap, a_cg) = self.line_step(&p, &g)?;
                let a_f = x
                    .iter()
                    .zip(&p)
                    .filter(|(_, &pi)| pi > 0.0)
                    .map(|(&xi, &pi)| xi / pi)
                    .fold(f64::INFINITY, f64::min);
                if a_cg <= a_f {
                    for i in 0..m {
                        x[i] -= a_cg * p[i];
                        g[i] -= a_cg * ap[i];
                    }
                    let phi = free(&x, &g);
                    let b = dotv(&phi, &ap) / pap;
                    for i in 0..m {
                        p[i] = phi[i] - b * p[i];
                    }
                } else {
                    // Expansion: feasible half step, then a projected gradient step.
                    for i in 0..m {
                        x[i] = (x[i] - a_f * p[i]).max(0.0);
                        g[i] -= a_f * ap[i];
                    }
                    let phi = free(&x, &g);
                    for i in 0..m {
                        x[i] = (x[i] - alpha_bar * phi[i]).max(0.0);
                    }
                    g = self.apply(&x)?;
                    for i in 0..m {
                        g[i] += self.q[i];
                    }
                    p = free(&x, &g);
                }
            } else {
                // Proportioning: leave the face along the chopped gradient.
                let (ad, _, a_cg) = self.line_step(&beta, &g)?;
                for i in 0..m {
                    x[i] = (x[i] - a_cg * beta[i]).max(0.0);
                    g[i] -= a_cg * ad[i];
                }
                p = free(&x, &g);
            }
        }
        let residual = projected_gradient_norm(&free(&x, &g), &chopped(&x, &g));
        Err(ContactError::NotConverged {
            what: "GCP (projected conjugate gradient) contact loop",
            iterations: max_iter,
            residual,
        })
    }

    fn relative_coefs(&mut self, coef: f64) -> Result<Vec<f64>, ContactError> {
        let all: Vec<usize> = (0..self.rows.len()).collect();
        self.prefetch(&all)?;
        (0..self.rows.len())
            .map(|i| {
                let d = self.entry(i, i)?;
                Ok(if d > 0.0 { coef / d } else { coef })
            })
            .collect()
    }

    fn augmented_lagrangian(
        &mut self,
        coef: f64,
        max_iter: usize,
        resi: f64,
        warm: Option<&[bool]>,
    ) -> Result<(Vec<f64>, usize), ContactError> {
        let m = self.rows.len();
        let c = self.relative_coefs(coef)?;
        let extra: Vec<f64> = c.iter().map(|ci| 1.0 / ci).collect();
        let mut lambda = vec![0.0; m];
        let mut active: Vec<bool> = match warm {
            Some(w) if w.len() == m => w.to_vec(),
            _ => self.q.iter().map(|&q| q < 0.0).collect(),
        };
        let mut last_change = f64::INFINITY;
        for it in 0..max_iter.max(1) {
            // Inner problem: LCP(M + C⁻¹, q − C⁻¹ λ_k).
            let shift: Vec<f64> = lambda.iter().zip(&extra).map(|(l, e)| -l * e).collect();
            let (mu, _) = self.active_set(active.clone(), &shift, &extra, 4 * m + 4, true)?;
            let change = mu
                .iter()
                .zip(&lambda)
                .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
            let size = mu.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            active = mu.iter().map(|&l| l > 0.0).collect();
            lambda = mu;
            last_change = if size > 0.0 { change / size } else { 0.0 };
            if last_change <= resi {
                return Ok((lambda, it + 1));
            }
        }
        Err(ContactError::NotConverged {
            what: "augmented Lagrangian contact loop (ALGO_RESO_CONT='POINT_FIXE')",
            iterations: max_iter,
            residual: last_change,
        })
    }

    fn pdas(
        &mut self,
        coef: f64,
        max_iter: usize,
        warm: Option<&[bool]>,
    ) -> Result<(Vec<f64>, usize), ContactError> {
        let m = self.rows.len();
        let c = self.relative_coefs(coef)?;
        let mut active: Vec<bool> = match warm {
            Some(w) if w.len() == m => w.to_vec(),
            _ => self.q.iter().map(|&q| q < 0.0).collect(),
        };
        let mut seen = SeenSets::default();
        let zero = vec![0.0; m];
        for it in 0..max_iter.max(2 * m + 2) {
            seen.visit(&active, it)?;
            let set: Vec<usize> = (0..m).filter(|&i| active[i]).collect();
            let mut lambda = self
                .multipliers_on(&set, &zero, &zero)?
                .map_err(|bad| ContactError::SingularContact { point: bad })?;
            let s = self.slack(&lambda)?;
            let next: Vec<bool> = (0..m)
                .map(|i| lambda[i] - c[i] * s[i] > c[i] * self.tol_s)
                .collect();
            if next == active {
                for l in lambda.iter_mut() {
                    *l = l.max(0.0);
                }
                return Ok((lambda, it + 1));
            }
            active = next;
        }
        Err(ContactError::NotConverged {
            what: "semi-smooth Newton contact loop (ALGO_RESO_CONT='NEWTON')",
            iterations: max_iter,
            residual: f64::NAN,
        })
    }

    fn finish(mut self, lambda: Vec<f64>, iterations: usize) -> Result<DualSolution, ContactError> {
        // One more solve for u when columns were not all cached (GCP).
        let need_solve = lambda
            .iter()
            .enumerate()
            .any(|(j, &l)| l != 0.0 && self.columns[j].is_none());
        let u = if need_solve {
            let v = self.apply_transpose(&lambda);
            let z = self.k.solve(&v).map_err(ContactError::Solver)?;
            self.solves += 1;
            self.u_free.iter().zip(z).map(|(a, b)| a - b).collect()
        } else {
            self.displacement(&lambda)?
        };
        let active = lambda.iter().map(|&l| l > 0.0).collect();
        Ok(DualSolution {
            lambda,
            u,
            active,
            iterations,
            solves: self.solves,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dense SPD stiffness: a chain of springs with a ground spring per node.
    struct Dense(DMatrix<f64>);

    impl StiffnessSolve for Dense {
        fn len(&self) -> usize {
            self.0.nrows()
        }
        fn solve(&self, rhs: &[f64]) -> Result<Vec<f64>, String> {
            let lu = self.0.clone().lu();
            lu.solve(&DVector::from_column_slice(rhs))
                .map(|v| v.iter().copied().collect())
                .ok_or_else(|| "singular".to_string())
        }
    }

    fn chain(n: usize) -> Dense {
        let mut k = DMatrix::zeros(n, n);
        for i in 0..n {
            k[(i, i)] += 1.0 + 0.1 * i as f64;
            if i + 1 < n {
                k[(i, i)] += 10.0;
                k[(i + 1, i + 1)] += 10.0;
                k[(i, i + 1)] -= 10.0;
                k[(i + 1, i)] -= 10.0;
            }
        }
        Dense(k)
    }

    /// Obstacles u_i ≥ -gap_i on every node (-u_i ≤ gap_i), pushed down by
    /// a free solution going below them.
    fn problem(n: usize) -> (Dense, Vec<f64>, Vec<IndexedRow>) {
        let k = chain(n);
        let f: Vec<f64> = (0..n).map(|i| -3.0 - (i as f64 * 0.7).sin()).collect();
        let u_free = k.solve(&f).unwrap();
        let rows = (0..n)
            .map(|i| IndexedRow {
                terms: vec![(i, -1.0)],
                rhs: if i % 3 == 1 {
                    5.0
                } else {
                    0.05 + 0.02 * (i as f64 * 1.3).cos()
                },
            })
            .collect();
        (k, u_free, rows)
    }

    fn check_kkt(
        k: &Dense,
        u_free: &[f64],
        rows: &[IndexedRow],
        eps: &[f64],
        s: &DualSolution,
        tol: f64,
    ) {
        // u = u_free − K⁻¹Aᵀλ.
        let mut at = vec![0.0; k.len()];
        for (r, l) in rows.iter().zip(&s.lambda) {
            for &(i, c) in &r.terms {
                at[i] += c * l;
            }
        }
        let z = k.solve(&at).unwrap();
        for i in 0..k.len() {
            assert!((s.u[i] - (u_free[i] - z[i])).abs() < tol);
        }
        for ((r, &l), &e) in rows.iter().zip(&s.lambda).zip(eps) {
            let slack = r.rhs - r.dot(&s.u) + e * l;
            assert!(l >= 0.0);
            assert!(slack >= -tol, "slack {slack}");
            assert!((l * slack).abs() < tol, "complementarity {l} × {slack}");
        }
    }

    #[test]
    fn all_exact_algorithms_agree_and_satisfy_kkt() {
        let (k, u_free, rows) = problem(12);
        let eps = vec![0.0; rows.len()];
        let exact = solve_dual(
            &k,
            &u_free,
            &rows,
            &eps,
            DualAlgorithm::ActiveSet {
                max_iter: 48,
                stop_singulier: true,
            },
            None,
        )
        .unwrap();
        check_kkt(&k, &u_free, &rows, &eps, &exact, 1e-9);
        assert!(
            exact.active.iter().any(|a| *a) && exact.active.iter().any(|a| !*a),
            "{:?}",
            exact.active
        );
        for algo in [
            DualAlgorithm::Gcp {
                tol: Some(1e-12),
                max_iter: 0,
            },
            DualAlgorithm::AugmentedLagrangian {
                coef: 100.0,
                max_iter: 30,
                resi: 1e-12,
            },
            DualAlgorithm::SemiSmoothNewton {
                coef: 1.0,
                max_iter: 50,
            },
        ] {
            let s = solve_dual(&k, &u_free, &rows, &eps, algo, None).unwrap();
            check_kkt(&k, &u_free, &rows, &eps, &s, 1e-8);
            for (a, b) in s.lambda.iter().zip(&exact.lambda) {
                assert!(
                    (a - b).abs() < 1e-7 * (1.0 + b.abs()),
                    "{algo:?}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn penalty_obeys_its_law_and_tends_to_exact() {
        let (k, u_free, rows) = problem(8);
        let exact = solve_dual(
            &k,
            &u_free,
            &rows,
            &[0.0; 8],
            DualAlgorithm::ActiveSet {
                max_iter: 32,
                stop_singulier: true,
            },
            None,
        )
        .unwrap();
        let mut last_err = f64::INFINITY;
        for e_n in [1e2, 1e4, 1e6] {
            let eps = vec![1.0 / e_n; 8];
            let s = solve_dual(
                &k,
                &u_free,
                &rows,
                &eps,
                DualAlgorithm::ActiveSet {
                    max_iter: 32,
                    stop_singulier: true,
                },
                None,
            )
            .unwrap();
            for (r, &l) in rows.iter().zip(&s.lambda) {
                let pen = (r.dot(&s.u) - r.rhs).max(0.0);
                assert!(
                    (l - e_n * pen).abs() < 1e-8 * (1.0 + l),
                    "λ = E_N × penetration"
                );
            }
            let err = s
                .lambda
                .iter()
                .zip(&exact.lambda)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(err < last_err, "penalty error must fall with E_N");
            last_err = err;
        }
        assert!(last_err < 1e-3);
    }

    #[test]
    fn redundant_rows_are_reported_or_dropped() {
        let (k, u_free, mut rows) = problem(4);
        rows.push(rows[0].clone());
        let eps = vec![0.0; rows.len()];
        let err = solve_dual(
            &k,
            &u_free,
            &rows,
            &eps,
            DualAlgorithm::ActiveSet {
                max_iter: 20,
                stop_singulier: true,
            },
            None,
        )
        .unwrap_err();
        assert!(matches!(err, ContactError::SingularContact { .. }), "{err}");
        let s = solve_dual(
            &k,
            &u_free,
            &rows,
            &eps,
            DualAlgorithm::ActiveSet {
                max_iter: 20,
                stop_singulier: false,
            },
            None,
        )
        .unwrap();
        check_kkt(&k, &u_free, &rows, &eps, &s, 1e-9);
    }

    #[test]
    fn cached_columns_are_reused_and_give_the_same_answer() {
        let (k, u_free, rows) = problem(10);
        let eps = vec![0.0; rows.len()];
        let algo = DualAlgorithm::ActiveSet {
            max_iter: 40,
            stop_singulier: true,
        };
        let plain = solve_dual(&k, &u_free, &rows, &eps, algo, None).unwrap();
        let mut cache = ColumnCache::new();
        let first = solve_dual_cached(&k, &u_free, &rows, &eps, algo, None, &mut cache).unwrap();
        assert_eq!(first, plain);
        assert!(first.solves > 0 && cache.len() == first.solves);
        // A second pass with the same rows (a geometric iteration that
        // found the same pairing) solves nothing.
        let again = solve_dual_cached(&k, &u_free, &rows, &eps, algo, None, &mut cache).unwrap();
        assert_eq!((again.lambda, again.u), (plain.lambda, plain.u));
        assert_eq!(again.solves, 0);
        assert_eq!(cache.hits, first.solves);
    }

    /// K with DOF 0 eliminated: `solve` ignores rhs[0].
    struct Eliminated0(Dense);

    impl StiffnessSolve for Eliminated0 {
        fn len(&self) -> usize {
            self.0.len()
        }
        fn reads(&self, i: usize) -> bool {
            i != 0
        }
        fn solve(&self, rhs: &[f64]) -> Result<Vec<f64>, String> {
            let mut b = rhs.to_vec();
            b[0] = 0.0;
            self.0.solve(&b)
        }
    }

    #[test]
    fn rows_differing_on_unread_dofs_share_their_column() {
        let (k, u_free, mut rows) = problem(6);
        // No row on the eliminated DOF itself (its column would be zero).
        rows.remove(0);
        let k = Eliminated0(k);
        let eps = vec![0.0; rows.len()];
        let algo = DualAlgorithm::ActiveSet {
            max_iter: 40,
            stop_singulier: true,
        };
        let mut cache = ColumnCache::new();
        let first = solve_dual_cached(&k, &u_free, &rows, &eps, algo, None, &mut cache).unwrap();
        // The same rows plus a term on the eliminated DOF 0 (a master node
        // held fixed whose weight changed with the projection).
        let moved: Vec<IndexedRow> = rows
            .iter()
            .map(|r| {
                let mut r = r.clone();
                r.terms.insert(0, (0, 0.37));
                r
            })
            .collect();
        let cached = solve_dual_cached(&k, &u_free, &moved, &eps, algo, None, &mut cache).unwrap();
        let fresh = solve_dual(&k, &u_free, &moved, &eps, algo, None).unwrap();
        assert_eq!(cached.solves, 0);
        assert!(first.solves > 0 && cache.hits == first.solves);
        assert_eq!((cached.lambda, cached.u), (fresh.lambda, fresh.u));
    }

    #[test]
    fn no_rows_gives_the_free_solution() {
        let (k, u_free, _) = problem(3);
        let s = solve_dual(
            &k,
            &u_free,
            &[],
            &[],
            DualAlgorithm::Gcp {
                tol: None,
                max_iter: 0,
            },
            None,
        )
        .unwrap();
        assert_eq!(s.u, u_free);
        assert_eq!(s.solves, 0);
    }
}
