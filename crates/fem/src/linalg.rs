//! Sparse matrices in compressed-column form and the direct solve (faer).
//!
//! The solve equilibrates the system symmetrically before factorising:
//! displacement rows/columns are scaled by 1/√|Kᵢᵢ|, multiplier rows by the
//! inverse of their largest scaled coefficient. This makes stiffness ratios
//! of 1e7 and more (and Lagrange rows of arbitrary units) harmless. Systems
//! without multipliers use a sparse Cholesky factorisation, falling back to
//! LU with partial pivoting; systems with multipliers (symmetric indefinite)
//! use LU. The residual is checked and refined after the solve. An LU
//! answer of a system with multipliers whose residual exceeds the
//! right-hand side (an unsymmetric generalised-Newton friction matrix the
//! symmetric scaling leaves hopelessly conditioned) is replaced by a solve
//! equilibrated by rows, then columns.

use crate::error::FemError;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Col, Side};

/// A square sparse matrix in compressed-column form with sorted rows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Csc {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub values: Vec<f64>,
}

impl Csc {
    /// Builds the pattern from per-column row lists (sorted and deduplicated
    /// here); values start at zero.
    pub fn from_columns(n: usize, mut cols: Vec<Vec<u32>>) -> Csc {
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let total: usize = cols.iter().map(|c| c.len()).sum();
        let mut row_idx = Vec::with_capacity(total);
        for c in cols.iter_mut() {
            c.sort_unstable();
            c.dedup();
            row_idx.extend(c.iter().map(|&r| r as usize));
            col_ptr.push(row_idx.len());
        }
        let values = vec![0.0; row_idx.len()];
        Csc {
            n,
            col_ptr,
            row_idx,
            values,
        }
    }

    /// Position of entry (row, col) in `values`.
    #[inline]
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        let (a, b) = (self.col_ptr[col], self.col_ptr[col + 1]);
        self.row_idx[a..b].binary_search(&row).ok().map(|k| a + k)
    }

    /// Adds `v` at (row, col); the entry must be in the pattern.
    #[inline]
    pub fn add(&mut self, row: usize, col: usize, v: f64) -> bool {
        match self.position(row, col) {
            Some(p) => {
                self.values[p] += v;
                true
            }
            None => false,
        }
    }

    pub fn diagonal(&self) -> Vec<f64> {
        (0..self.n)
            .map(|j| self.position(j, j).map(|p| self.values[p]).unwrap_or(0.0))
            .collect()
    }

    /// y = A x.
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n];
        self.mul_add(1.0, x, &mut y);
        y
    }

    /// y += c·A x.
    pub fn mul_add(&self, c: f64, x: &[f64], y: &mut [f64]) {
        for j in 0..self.n {
            let xj = x[j];
            if xj == 0. {
                continue;
            }
            for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                y[self.row_idx[p]] += c * self.values[p] * xj;
            }
        }
    }

    /// ‖A‖∞ (max row sum).
    pub fn norm_inf(&self) -> f64 {
        let mut s = vec![0.0; self.n];
        for j in 0..self.n {
            for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                s[self.row_idx[p]] += self.values[p].abs();
            }
        }
        s.into_iter().fold(0.0, f64::max)
    }

    /// A bordered matrix: this one (size n) plus extra entries given as
    /// triplets, possibly outside the current pattern and beyond n.
    pub fn with_extra(&self, n_total: usize, mut extra: Vec<(usize, usize, f64)>) -> Csc {
        extra.sort_unstable_by_key(|&(r, c, _)| (c, r));
        let mut col_ptr = Vec::with_capacity(n_total + 1);
        let mut row_idx = Vec::with_capacity(self.row_idx.len() + extra.len());
        let mut values = Vec::with_capacity(self.row_idx.len() + extra.len());
        col_ptr.push(0);
        let mut e = 0;
        for j in 0..n_total {
            let (mut p, pend) = if j < self.n {
                (self.col_ptr[j], self.col_ptr[j + 1])
            } else {
                (0, 0)
            };
            loop {
                let next_k = (p < pend).then(|| self.row_idx[p]);
                let next_e = (e < extra.len() && extra[e].1 == j).then(|| extra[e].0);
                let (row, v) = match (next_k, next_e) {
                    (None, None) => break,
                    (Some(r), None) => {
                        p += 1;
                        (r, self.values[p - 1])
                    }
                    (None, Some(r)) => {
                        e += 1;
                        (r, extra[e - 1].2)
                    }
                    (Some(rk), Some(re)) => {
                        if rk <= re {
                            p += 1;
                            (rk, self.values[p - 1])
                        } else {
                            e += 1;
                            (re, extra[e - 1].2)
                        }
                    }
                };
                if row_idx.len() > col_ptr[j] && row_idx.last() == Some(&row) {
                    if let Some(last) = values.last_mut() {
                        *last += v;
                    }
                } else {
                    row_idx.push(row);
                    values.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        Csc {
            n: n_total,
            col_ptr,
            row_idx,
            values,
        }
    }
}

/// Outcome of a linear solve.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveReport {
    pub x: Vec<f64>,
    /// Backward error ‖b − A x‖∞ / (‖A‖∞ ‖x‖∞ + ‖b‖∞) after refinement.
    pub backward_error: f64,
    /// Whether Cholesky (true) or LU (false) was used.
    pub cholesky: bool,
}

/// Largest backward error accepted after refinement.
pub const MAX_BACKWARD_ERROR: f64 = 1e-9;

/// Why a factorisation or solve failed, before the caller names the DOFs.
#[derive(Clone, Debug, PartialEq)]
pub enum SolveFailure {
    /// Structurally or numerically singular; `index` is a hint of an
    /// unknown involved when known.
    Singular {
        index: Option<usize>,
    },
    Poor {
        backward_error: f64,
    },
    Other(String),
}

enum Factor {
    /// Cholesky with a caller-given (nested dissection) ordering.
    LltOrdered {
        symbolic: Box<faer::sparse::linalg::cholesky::SymbolicCholesky<usize>>,
        values: Vec<f64>,
    },
    Llt(faer::sparse::linalg::solvers::Llt<usize, f64>),
    /// Cholesky split at the top separator, halves on two threads.
    Split(Box<crate::split_llt::SplitLlt>),
    Lu(Box<symbolic_cache::KeptLu>),
}

impl Factor {
    fn solve(&self, b: &[f64]) -> Vec<f64> {
        let mut c = Col::<f64>::from_fn(b.len(), |i| b[i]);
        match self {
            Factor::LltOrdered { symbolic, values } => {
                let par = faer::get_global_parallelism();
                let mut mem =
                    faer::dyn_stack::MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, par));
                faer::sparse::linalg::cholesky::LltRef::new(symbolic, values)
                    .solve_in_place_with_conj(
                        faer::Conj::No,
                        c.as_mat_mut(),
                        par,
                        faer::dyn_stack::MemStack::new(&mut mem),
                    );
            }
            Factor::Llt(f) => f.solve_in_place(c.as_mat_mut()),
            Factor::Split(f) => return f.solve(b),
            Factor::Lu(f) => f.solve_in_place(c.as_mat_mut()),
        }
        (0..b.len()).map(|i| c[i]).collect()
    }
}

/// The symbolic factorisations (fill-reducing ordering, elimination tree,
/// supernodes) of the last sparsity pattern factorised on this thread.
///
/// A Newton loop factorises nearly the same pattern again and again: the
/// tangent of a plastic or large-strain problem changes its values, not its
/// non-zeros, and a contact problem's bordered matrix changes only where
/// the active set or the pairing moves. The symbolic work — COLAMD and the
/// supernodal structure for LU, the ordering and elimination tree for
/// Cholesky — depends on the pattern only, so it is kept:
///
/// - Cholesky reuses it when the pattern is the same (the factor is then
///   the one a fresh analysis gives, to the bit);
/// - LU also when the pattern is contained in the kept one: the matrix is
///   written on the kept pattern, the missing entries as explicit zeros.
///   When it is not contained, the union of both patterns is analysed and
///   kept (unless the union is over 25 % larger than the new pattern: then
///   the new pattern alone), so that after a few iterations every active
///   set a step visits fits. Explicit zeros change no value of the
///   factors; the ordering computed on a larger pattern may differ, which
///   changes the solution by rounding only.
mod symbolic_cache {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
    use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
    use faer::sparse::linalg::LuError;
    use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
    use faer::{MatMut, Side};
    use std::cell::RefCell;
    use std::sync::Arc;

    /// A pattern (column pointers, row indices) and its symbolic factor.
    type Kept<S> = Option<(Vec<usize>, Vec<usize>, S)>;

    thread_local! {
        static LU: RefCell<Kept<Arc<SymbolicLu<usize>>>> = const { RefCell::new(None) };
        static LLT: RefCell<Kept<SymbolicLlt<usize>>> = const { RefCell::new(None) };
        /// The numeric LU factor of the last factorisation, once dropped,
        /// and the factorisation's workspace: the next factorisation
        /// writes into their memory (faer grows them as needed) instead of
        /// allocating — and page-faulting — tens of MB afresh at every
        /// Newton iteration.
        static NUMERIC_LU: RefCell<Option<PooledLu>> = const { RefCell::new(None) };
        static LU_SCRATCH: RefCell<Option<MemBuffer>> = const { RefCell::new(None) };
    }

    /// A numeric factor kept for the next factorisation of the same
    /// analysis (faer sizes some of its arrays by the analysis and never
    /// shrinks them: another analysis starts from a new factor).
    type PooledLu = (Arc<SymbolicLu<usize>>, NumericLu<usize, f64>);

    /// A numeric LU factor and its symbolic analysis; its memory goes back
    /// to this thread's pool when it is dropped.
    pub(crate) struct KeptLu {
        symbolic: Arc<SymbolicLu<usize>>,
        numeric: NumericLu<usize, f64>,
        par: faer::Par,
    }

    impl KeptLu {
        /// Solves A X = B in place (`rhs` holds B, then X).
        pub(crate) fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
            let mut mem = MemBuffer::new(
                self.symbolic
                    .solve_in_place_scratch::<f64>(rhs.ncols(), self.par),
            );
            LuRef::new_unchecked(&self.symbolic, &self.numeric).solve_in_place_with_conj(
                faer::Conj::No,
                rhs,
                self.par,
                MemStack::new(&mut mem),
            );
        }
    }

    impl Drop for KeptLu {
        fn drop(&mut self) {
            let pooled = (self.symbolic.clone(), std::mem::take(&mut self.numeric));
            NUMERIC_LU.with(|k| *k.borrow_mut() = Some(pooled));
        }
    }

    /// The numeric factorisation of `mat` (written on the symbolic
    /// analysis' pattern) into the pooled factor and workspace.
    fn factorize(
        symbolic: Arc<SymbolicLu<usize>>,
        mat: SparseColMatRef<'_, usize, f64>,
    ) -> Result<KeptLu, LuError> {
        let par = super::factor_parallelism(mat.compute_nnz());
        let mut numeric = NUMERIC_LU
            .with(|k| k.borrow_mut().take())
            .filter(|(kept, _)| Arc::ptr_eq(kept, &symbolic))
            .map_or_else(NumericLu::new, |(_, n)| n);
        let req = symbolic.factorize_numeric_lu_scratch::<f64>(par, Default::default());
        let mut scratch = LU_SCRATCH
            .with(|k| k.borrow_mut().take())
            .filter(|b| b.len() >= req.unaligned_bytes_required());
        let buffer = match &mut scratch {
            Some(b) => b,
            None => scratch.insert(
                MemBuffer::try_new(req)
                    .map_err(|_| LuError::Generic(faer::sparse::FaerError::OutOfMemory))?,
            ),
        };
        let done = symbolic
            .factorize_numeric_lu(
                &mut numeric,
                mat,
                par,
                MemStack::new(buffer),
                Default::default(),
            )
            .map(|_| ());
        LU_SCRATCH.with(|k| *k.borrow_mut() = scratch);
        done?;
        Ok(KeptLu {
            symbolic,
            numeric,
            par,
        })
    }

    /// How much larger than the new pattern a kept union may be.
    const UNION_SLACK: f64 = 1.25;

    fn timing(what: &str) {
        if std::env::var_os("ASTER_FEM_TIMING").is_some() {
            eprintln!("[fem] symbolic factorisation {what}");
        }
    }

    /// `mat`'s values written on the pattern (`cp`, `ri`), zeros where
    /// `mat` has no entry; `None` when `mat` has an entry outside it. Rows
    /// are sorted in every column of both.
    fn scatter(
        cp: &[usize],
        ri: &[usize],
        mat: SparseColMatRef<'_, usize, f64>,
    ) -> Option<Vec<f64>> {
        let sym = mat.symbolic();
        let (mcp, mri, mv) = (sym.col_ptr(), sym.row_idx(), mat.val());
        if cp.len() != mcp.len() {
            return None;
        }
        let mut values = vec![0.0; ri.len()];
        for j in 0..cp.len() - 1 {
            let mut p = cp[j];
            for q in mcp[j]..mcp[j + 1] {
                while p < cp[j + 1] && ri[p] < mri[q] {
                    p += 1;
                }
                if p == cp[j + 1] || ri[p] != mri[q] {
                    return None;
                }
                values[p] = mv[q];
                p += 1;
            }
        }
        Some(values)
    }

    /// The union of two patterns of the same size (sorted rows).
    fn union(
        cp: &[usize],
        ri: &[usize],
        sym: SymbolicSparseColMatRef<'_, usize>,
    ) -> (Vec<usize>, Vec<usize>) {
        let (mcp, mri) = (sym.col_ptr(), sym.row_idx());
        let mut ucp = Vec::with_capacity(cp.len());
        let mut uri = Vec::with_capacity(ri.len().max(mri.len()));
        ucp.push(0);
        for j in 0..cp.len() - 1 {
            let (a, b) = (&ri[cp[j]..cp[j + 1]], &mri[mcp[j]..mcp[j + 1]]);
            let (mut x, mut y) = (0, 0);
            while x < a.len() || y < b.len() {
                let r = match (a.get(x), b.get(y)) {
                    (Some(&u), Some(&v)) if u == v => {
                        x += 1;
                        y += 1;
                        u
                    }
                    (Some(&u), Some(&v)) if u < v => {
                        x += 1;
                        u
                    }
                    (Some(_), Some(&v)) | (None, Some(&v)) => {
                        y += 1;
                        v
                    }
                    (Some(&u), None) => {
                        x += 1;
                        u
                    }
                    (None, None) => break,
                };
                uri.push(r);
            }
            ucp.push(uri.len());
        }
        (ucp, uri)
    }

    /// `m` written on a kept pattern (`cp`, `ri`) so that a symbolic
    /// analysis of that pattern serves it: on the kept pattern itself when
    /// it contains `m`'s (the missing entries explicit zeros), else on the
    /// union of both when that is at most [`UNION_SLACK`] times `m`'s
    /// size, else `m` as it is. The policy of [`lu`], for the callers that
    /// keep their own symbolic factorisations (`crate::solver_constrained`).
    pub(crate) fn on_kept_pattern(cp: &[usize], ri: &[usize], m: super::Csc) -> super::Csc {
        if cp.len() != m.n + 1 {
            return m;
        }
        let n = m.n;
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &m.col_ptr, None, &m.row_idx);
        let mat = SparseColMatRef::new(sym, &m.values);
        if let Some(values) = scatter(cp, ri, mat) {
            return super::Csc {
                n,
                col_ptr: cp.to_vec(),
                row_idx: ri.to_vec(),
                values,
            };
        }
        let (ucp, uri) = union(cp, ri, sym);
        if (uri.len() as f64) > UNION_SLACK * m.row_idx.len() as f64 {
            return m;
        }
        match scatter(&ucp, &uri, mat) {
            Some(values) => super::Csc {
                n,
                col_ptr: ucp,
                row_idx: uri,
                values,
            },
            None => m,
        }
    }

    /// Sparse LU with partial pivoting (`SparseColMatRef::sp_lu`), on the
    /// kept pattern when `mat`'s fits in it.
    pub(super) fn lu(mat: SparseColMatRef<'_, usize, f64>) -> Result<KeptLu, LuError> {
        let sym = mat.symbolic();
        let n = sym.ncols();
        let kept = LU.with(|k| k.borrow_mut().take());
        let fitted = kept.and_then(|(cp, ri, s)| {
            if cp.len() != n + 1 {
                return None;
            }
            match scatter(&cp, &ri, mat) {
                Some(v) => Some(Ok((cp, ri, s, v))),
                None => Some(Err((cp, ri))),
            }
        });
        let (cp, ri, symbolic, values) = match fitted {
            Some(Ok(found)) => {
                timing("reused");
                found
            }
            other => {
                let (cp, ri) = match other {
                    Some(Err((cp, ri))) => {
                        let (ucp, uri) = union(&cp, &ri, sym);
                        if (uri.len() as f64) <= UNION_SLACK * sym.row_idx().len() as f64 {
                            timing("new (union with the kept pattern)");
                            (ucp, uri)
                        } else {
                            timing("new");
                            (sym.col_ptr().to_vec(), sym.row_idx().to_vec())
                        }
                    }
                    _ => {
                        timing("new");
                        (sym.col_ptr().to_vec(), sym.row_idx().to_vec())
                    }
                };
                let pattern = SymbolicSparseColMatRef::new_checked(n, n, &cp, None, &ri);
                let symbolic = Arc::new(factorize_symbolic_lu(pattern, Default::default())?);
                let values = match scatter(&cp, &ri, mat) {
                    Some(v) => v,
                    // Unreachable: the pattern contains mat's; factorise
                    // mat alone rather than fail.
                    None => {
                        let own = Arc::new(factorize_symbolic_lu(sym, Default::default())?);
                        return factorize(own, mat);
                    }
                };
                (cp, ri, symbolic, values)
            }
        };
        let pattern = SymbolicSparseColMatRef::new_checked(n, n, &cp, None, &ri);
        let lu = factorize(symbolic.clone(), SparseColMatRef::new(pattern, &values));
        LU.with(|k| *k.borrow_mut() = Some((cp, ri, symbolic)));
        lu
    }

    /// Sparse Cholesky of the lower triangle (`sp_cholesky(Side::Lower)`),
    /// reusing the kept analysis of the same pattern; `None` when the
    /// matrix is not positive definite.
    pub(super) fn llt(mat: SparseColMatRef<'_, usize, f64>) -> Option<Llt<usize, f64>> {
        let sym = mat.symbolic();
        let hit = LLT.with(|k| {
            k.borrow().as_ref().and_then(|(cp, ri, s)| {
                (cp.as_slice() == sym.col_ptr() && ri.as_slice() == sym.row_idx())
                    .then(|| s.clone())
            })
        });
        let symbolic = match hit {
            Some(s) => {
                timing("reused");
                s
            }
            None => {
                timing("new");
                let s = SymbolicLlt::try_new(sym, Side::Lower).ok()?;
                LLT.with(|k| {
                    *k.borrow_mut() =
                        Some((sym.col_ptr().to_vec(), sym.row_idx().to_vec(), s.clone()))
                });
                s
            }
        };
        Llt::try_new_with_symbolic(symbolic, mat, Side::Lower).ok()
    }
}

pub(crate) use symbolic_cache::on_kept_pattern;

/// Solves A x = b. `n_primal` is the number of leading displacement unknowns
/// (the rest are multipliers); `spd_hint` says the matrix should be
/// symmetric positive definite (no multipliers), so Cholesky is tried first.
pub fn solve(
    a: &Csc,
    b: &[f64],
    n_primal: usize,
    spd_hint: bool,
) -> Result<SolveReport, SolveFailure> {
    solve_with(a, b, n_primal, spd_hint, None)
}

/// The numeric Cholesky factor of `mat` into `values` (sized
/// `symbolic.len_val()`), on `symbolic`'s pattern; `None` when `mat` is not
/// positive definite (or the scratch memory cannot be had).
pub(crate) fn numeric_llt<I: faer::Index>(
    symbolic: &faer::sparse::linalg::cholesky::SymbolicCholesky<I>,
    mat: SparseColMatRef<'_, I, f64>,
    values: &mut [f64],
    par: faer::Par,
) -> Option<()> {
    let mut mem = faer::dyn_stack::MemBuffer::try_new(
        symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
    )
    .ok()?;
    symbolic
        .factorize_numeric_llt(
            values,
            mat,
            Side::Lower,
            Default::default(),
            par,
            faer::dyn_stack::MemStack::new(&mut mem),
            Default::default(),
        )
        .ok()?;
    Some(())
}

/// Below this many unknowns the default (AMD) ordering is used even when
/// coordinates are given.
const ND_THRESHOLD: usize = 20_000;

/// Cholesky with a custom fill-reducing ordering (`order[k]` = original
/// index of the k-th pivot).
fn cholesky_ordered(mat: SparseColMatRef<'_, usize, f64>, order: &[usize]) -> Option<Factor> {
    use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, SymmetricOrdering};
    let n = order.len();
    let mut inv = vec![0usize; n];
    for (k, &i) in order.iter().enumerate() {
        inv[i] = k;
    }
    let perm = faer::perm::PermRef::new_checked(order, &inv, n);
    let symbolic = factorize_symbolic_cholesky(
        mat.symbolic(),
        Side::Lower,
        SymmetricOrdering::Custom(perm),
        Default::default(),
    )
    .ok()?;
    let mut values = vec![0.0; symbolic.len_val()];
    if std::env::var_os("ASTER_FEM_TIMING").is_some() {
        eprintln!("[fem] Cholesky factor: {} non-zeros", symbolic.len_val());
    }
    numeric_llt(
        &symbolic,
        mat,
        &mut values,
        factor_parallelism(symbolic.len_val()),
    )?;
    Some(Factor::LltOrdered {
        symbolic: Box::new(symbolic),
        values,
    })
}

/// Sets faer's global parallelism to rayon's thread count, explicitly, so
/// that reading the setting does not start rayon's pool.
///
/// faer's default setting is `Par::rayon(0)`, "as many threads as rayon's
/// global pool has", and every factorisation reads it
/// (`get_global_parallelism`): the first one, however small, started the
/// pool (two threads here, 3 % of a one-element case's CPU). With the count
/// given, rayon's pool starts when work is first handed to it, which small
/// systems never do; the parallelism every solve sees is the same number,
/// so results do not change. The count is rayon's own (`RAYON_NUM_THREADS`
/// when set, else the cores available). To be called once, before any
/// factorisation (`aster` does it first thing).
pub fn defer_thread_pool() {
    let threads = std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|s| s.parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    faer::set_global_parallelism(faer::Par::rayon(threads));
}

/// Below this many non-zeros in the factor a numeric factorisation runs on
/// one thread: the threads' synchronisation costs more than they save.
/// Measured on the 2-core machine (one case at a time, wall / user +
/// system): ssnv110e's 2D factor of 1.25 M non-zeros (24,915 unknowns)
/// 27.7 s / 29.2 s with two threads against 18.1 s / 18.1 s with one;
/// ssnv166b's 3D factor of 123 M non-zeros gains from two (29.5 s wall
/// against 34.8 s). On ssnv506d (9,700 unknowns) too the threads cost more
/// CPU than they saved (the former rule: 20,000 unknowns).
const PARALLEL_MIN_FACTOR_NONZEROS: usize = 5_000_000;

/// The parallelism of a numeric factorisation whose factor has
/// `factor_nonzeros` values (and of the solves with it): faer's global
/// setting for large factors,
/// one thread below [`PARALLEL_MIN_FACTOR_NONZEROS`].
pub(crate) fn factor_parallelism(factor_nonzeros: usize) -> faer::Par {
    if factor_nonzeros < PARALLEL_MIN_FACTOR_NONZEROS {
        faer::Par::Seq
    } else {
        faer::get_global_parallelism()
    }
}

/// Threads available to the factorisation (faer's global setting: rayon's
/// pool unless set otherwise).
fn parallel_threads() -> usize {
    faer::get_global_parallelism().degree()
}

/// The symmetrically scaled matrix (entry (i, j) times s[i]·s[j]) as a faer
/// matrix.
struct Scaled {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
}

impl Scaled {
    fn as_ref(&self) -> SparseColMatRef<'_, usize, f64> {
        let symbolic = SymbolicSparseColMatRef::new_checked(
            self.n,
            self.n,
            &self.col_ptr,
            None,
            &self.row_idx,
        );
        SparseColMatRef::new(symbolic, &self.values)
    }
}

fn scaled_copy(a: &Csc, s: &[f64]) -> Scaled {
    let mut values = Vec::with_capacity(a.values.len());
    for j in 0..a.n {
        for p in a.col_ptr[j]..a.col_ptr[j + 1] {
            values.push(a.values[p] * s[a.row_idx[p]] * s[j]);
        }
    }
    Scaled {
        n: a.n,
        col_ptr: a.col_ptr.clone(),
        row_idx: a.row_idx.clone(),
        values,
    }
}

/// [`solve`] with the coordinates of the unknowns, used for a nested
/// dissection ordering on large positive definite systems.
pub fn solve_with(
    a: &Csc,
    b: &[f64],
    n_primal: usize,
    spd_hint: bool,
    coords: Option<&[[f64; 3]]>,
) -> Result<SolveReport, SolveFailure> {
    let n = a.n;
    let _solve = crate::newton_timing::phase(crate::newton_timing::Phase::Solve);
    let timing = std::env::var_os("ASTER_FEM_TIMING").is_some();
    let clock = std::time::Instant::now();
    let lap = |what: &str| {
        if timing {
            eprintln!(
                "[fem] {what}: {:.3} s{}",
                clock.elapsed().as_secs_f64(),
                crate::diag::process_usage()
            );
        }
    };
    // Equilibration.
    let diag = a.diagonal();
    let mut s = vec![1.0; n];
    for i in 0..n_primal.min(n) {
        let d = diag[i].abs();
        s[i] = if d > 0. && d.is_finite() {
            1. / d.sqrt()
        } else {
            1.0
        };
    }
    if n_primal < n {
        let mut rowmax = vec![0.0f64; n];
        for j in 0..n_primal {
            for p in a.col_ptr[j]..a.col_ptr[j + 1] {
                let r = a.row_idx[p];
                if r >= n_primal {
                    rowmax[r] = rowmax[r].max((a.values[p] * s[j]).abs());
                }
            }
        }
        for i in n_primal..n {
            if rowmax[i] > 0. {
                s[i] = 1. / rowmax[i];
            }
        }
    }
    let factorising = crate::newton_timing::phase(crate::newton_timing::Phase::Factorisation);
    let mut factor = None;
    // Whether a Cholesky factorisation is still worth trying: not after one
    // found the matrix not positive definite.
    let mut try_cholesky = spd_hint;
    // Large positive definite systems with coordinates: nested dissection,
    // split in two halves factorised in parallel when there are two cores.
    if spd_hint {
        if let Some(c) = coords.filter(|c| n >= ND_THRESHOLD && c.len() == n) {
            lap("scaling");
            let dissection = crate::ordering::nested_dissection_split(a, c);
            lap("nested dissection");
            if parallel_threads() >= 2 {
                use crate::split_llt::{SplitFailure, SplitLlt};
                match SplitLlt::factorise(a, &s, &dissection) {
                    Ok(f) => {
                        if timing {
                            eprintln!("[fem] split Cholesky factor: {} non-zeros", f.len_val());
                        }
                        factor = Some(Factor::Split(Box::new(f)));
                    }
                    Err(SplitFailure::NoSplit) => {}
                    Err(SplitFailure::Failed) => try_cholesky = false,
                }
                lap("Cholesky (split)");
            }
            if factor.is_none() && try_cholesky {
                let scaled = scaled_copy(a, &s);
                factor = cholesky_ordered(scaled.as_ref(), &dissection.order);
                try_cholesky = factor.is_some();
                lap("Cholesky (ordered)");
            }
        }
    }
    let factor = match factor {
        Some(f) => f,
        None => {
            let scaled = scaled_copy(a, &s);
            let mat = scaled.as_ref();
            let llt = if try_cholesky {
                symbolic_cache::llt(mat)
            } else {
                None
            };
            match llt {
                Some(f) => Factor::Llt(f),
                None => match symbolic_cache::lu(mat) {
                    Ok(f) => Factor::Lu(Box::new(f)),
                    Err(faer::sparse::linalg::LuError::SymbolicSingular { index }) => {
                        return Err(SolveFailure::Singular { index: Some(index) })
                    }
                    Err(e) => return Err(SolveFailure::Other(format!("{e:?}"))),
                },
            }
        }
    };
    drop(factorising);
    let cholesky = matches!(
        factor,
        Factor::Llt(_) | Factor::LltOrdered { .. } | Factor::Split(_)
    );
    // Solve the scaled system and refine in the original one.
    let solve_orig = |r: &[f64]| -> Vec<f64> {
        let rs: Vec<f64> = r.iter().zip(&s).map(|(v, si)| v * si).collect();
        let y = factor.solve(&rs);
        y.iter().zip(&s).map(|(v, si)| v * si).collect()
    };
    let mut x = solve_orig(b);
    lap("first solve");
    if x.iter().any(|v| !v.is_finite()) {
        return Err(SolveFailure::Singular { index: None });
    }
    let norm_a = a.norm_inf();
    let norm_b = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let berr = |x: &[f64]| -> (f64, Vec<f64>) {
        let ax = a.mul(x);
        let r: Vec<f64> = b.iter().zip(&ax).map(|(bi, ai)| bi - ai).collect();
        let nr = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let nx = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let den = norm_a * nx + norm_b;
        (if den > 0. { nr / den } else { 0. }, r)
    };
    let (mut be, mut r) = berr(&x);
    for _ in 0..3 {
        if be <= 1e-15 {
            break;
        }
        let dx = solve_orig(&r);
        let cand: Vec<f64> = x.iter().zip(&dx).map(|(a, b)| a + b).collect();
        let (be2, r2) = berr(&cand);
        if be2 < be {
            x = cand;
            be = be2;
            r = r2;
        } else {
            break;
        }
    }
    lap("refinement");
    // An unsymmetric system with multipliers (continuous friction in
    // slip) can be so badly scaled by the symmetric equilibration that the
    // LU returns garbage whose backward error still looks small because x
    // itself is huge: a residual above the right-hand side gives it away.
    // Then the system is equilibrated by rows and then by columns and
    // factorised again; the better answer in the original system is kept.
    if !cholesky && n_primal < n {
        let nr = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if nr > norm_b || nr.is_nan() {
            if let Some(y) = solve_two_sided(a, b) {
                let (be2, r2) = berr(&y);
                let nr2 = r2.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                if y.iter().all(|v| v.is_finite()) && nr2 < nr {
                    x = y;
                    be = be2;
                }
            }
        }
    }
    if x.iter().any(|v| !v.is_finite()) {
        return Err(SolveFailure::Singular { index: None });
    }
    if be > MAX_BACKWARD_ERROR {
        return Err(SolveFailure::Poor { backward_error: be });
    }
    Ok(SolveReport {
        x,
        backward_error: be,
        cholesky,
    })
}

/// Solves `a x = b` after a two-sided equilibration: every row scaled by
/// the inverse of its largest coefficient, then every column likewise; LU
/// with partial pivoting, refined in the original system (three passes at
/// most). `None` when the factorisation fails.
fn solve_two_sided(a: &Csc, b: &[f64]) -> Option<Vec<f64>> {
    let n = a.n;
    let mut row = vec![0.0f64; n];
    for j in 0..n {
        for p in a.col_ptr[j]..a.col_ptr[j + 1] {
            let i = a.row_idx[p];
            row[i] = row[i].max(a.values[p].abs());
        }
    }
    let row: Vec<f64> = row
        .iter()
        .map(|&m| if m > 0. && m.is_finite() { 1. / m } else { 1. })
        .collect();
    let mut col = vec![1.0f64; n];
    for (j, c) in col.iter_mut().enumerate() {
        let m = (a.col_ptr[j]..a.col_ptr[j + 1])
            .map(|p| (a.values[p] * row[a.row_idx[p]]).abs())
            .fold(0.0f64, f64::max);
        if m > 0. && m.is_finite() {
            *c = 1. / m;
        }
    }
    let mut values = Vec::with_capacity(a.values.len());
    for j in 0..n {
        for p in a.col_ptr[j]..a.col_ptr[j + 1] {
            values.push(a.values[p] * row[a.row_idx[p]] * col[j]);
        }
    }
    let scaled = Scaled {
        n,
        col_ptr: a.col_ptr.clone(),
        row_idx: a.row_idx.clone(),
        values,
    };
    let factor = Factor::Lu(Box::new(symbolic_cache::lu(scaled.as_ref()).ok()?));
    let solve = |r: &[f64]| -> Vec<f64> {
        let rs: Vec<f64> = r.iter().zip(&row).map(|(v, s)| v * s).collect();
        let y = factor.solve(&rs);
        y.iter().zip(&col).map(|(v, s)| v * s).collect()
    };
    let resid = |x: &[f64]| -> (f64, Vec<f64>) {
        let ax = a.mul(x);
        let r: Vec<f64> = b.iter().zip(&ax).map(|(bi, ai)| bi - ai).collect();
        (r.iter().fold(0.0f64, |m, v| m.max(v.abs())), r)
    };
    let mut x = solve(b);
    let (mut nr, mut r) = resid(&x);
    for _ in 0..3 {
        let dx = solve(&r);
        let cand: Vec<f64> = x.iter().zip(&dx).map(|(u, v)| u + v).collect();
        let (nr2, r2) = resid(&cand);
        if nr2 < nr {
            x = cand;
            nr = nr2;
            r = r2;
        } else {
            break;
        }
    }
    Some(x)
}

/// Convenience: maps a failure to a [`FemError`] given a namer for unknowns.
pub fn failure_to_error(f: SolveFailure, name: impl Fn(usize) -> String) -> FemError {
    match f {
        SolveFailure::Singular { index } => FemError::Singular {
            free_dofs: index.map(|i| vec![name(i)]).unwrap_or_default(),
        },
        SolveFailure::Poor { backward_error } => FemError::PoorSolve {
            relative_residual: backward_error,
        },
        SolveFailure::Other(m) => FemError::Model(format!("sparse factorisation failed: {m}")),
    }
}

/// A dense test matrix as a `Csc` (its nonzero entries only).
#[cfg(test)]
pub(crate) fn dense_to_csc(a: &[Vec<f64>]) -> Csc {
    let n = a.len();
    let cols: Vec<Vec<u32>> = (0..n)
        .map(|j| {
            (0..n)
                .filter(|&i| a[i][j] != 0.)
                .map(|i| i as u32)
                .collect()
        })
        .collect();
    let mut m = Csc::from_columns(n, cols);
    for j in 0..n {
        for i in 0..n {
            if a[i][j] != 0. {
                m.add(i, j, a[i][j]);
            }
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_sided_equilibration_solves_a_wildly_row_scaled_unsymmetric_system() {
        // An unsymmetric saddle-point system (a sliding friction row
        // couples the unknowns one way only) with rows of 1e-12 to 1e14:
        // the answer is x* to the refinement's accuracy.
        let a = vec![
            vec![4e14, -1e14, 3e13, 1e14],
            vec![-2e-3, 5e-3, 0., 0.],
            vec![7e5, 0., 2e6, 1e6],
            vec![1e-12, 0., 0., 0.],
        ];
        let xs = [1.5, -2.0, 0.25, 3.0];
        let b: Vec<f64> = a
            .iter()
            .map(|r| r.iter().zip(&xs).map(|(u, v)| u * v).sum())
            .collect();
        let x = solve_two_sided(&dense_to_csc(&a), &b).expect("factorised");
        for (u, v) in x.iter().zip(&xs) {
            assert!((u - v).abs() <= 1e-10 * v.abs(), "{x:?}");
        }
    }

    #[test]
    fn solves_an_indefinite_kkt_system_with_wild_scales() {
        // Two springs 2e16 and 2e9 in series, end 0 held by a multiplier.
        let (k1, k2) = (2e16, 2e9);
        let a = vec![
            vec![k1, -k1, 0., 1.],
            vec![-k1, k1 + k2, -k2, 0.],
            vec![0., -k2, k2, 0.],
            vec![1., 0., 0., 0.],
        ];
        let m = dense_to_csc(&a);
        let b = vec![0., 0., 1.0, 0.];
        let r = solve(&m, &b, 3, false).expect("solvable");
        assert!(!r.cholesky);
        let u2 = 1. / k1 + 1. / k2;
        assert!((r.x[2] - u2).abs() / u2 < 1e-12, "{:?}", r.x);
        assert!((r.x[3] - 1.).abs() < 1e-9, "multiplier {:?}", r.x[3]);
    }

    /// A bordered (KKT) system of a chain of `n` springs with multiplier
    /// rows holding the given nodes, and its exact solution for a unit
    /// load at the free end.
    fn chain_with_holds(n: usize, holds: &[usize]) -> (Csc, Vec<f64>) {
        let m = n + holds.len();
        let mut a = vec![vec![0.0; m]; m];
        for i in 0..n - 1 {
            let k = 1.0 + i as f64;
            a[i][i] += k;
            a[i + 1][i + 1] += k;
            a[i][i + 1] -= k;
            a[i + 1][i] -= k;
        }
        for (r, &h) in holds.iter().enumerate() {
            a[n + r][h] = 1.0;
            a[h][n + r] = 1.0;
        }
        let mut b = vec![0.0; m];
        b[n - 1] = 1.0;
        (dense_to_csc(&a), b)
    }

    #[test]
    fn lu_keeps_its_symbolic_analysis_across_nearby_patterns() {
        // The same pattern, a pattern inside it (a hold released: its row
        // stays, uncoupled, as a released contact row does), one outside it
        // (another node held): each solve must be what a fresh
        // factorisation gives.
        let n = 6;
        let (a0, b0) = chain_with_holds(n, &[0, 2]);
        let mut released = a0.clone();
        // Release the second hold: its coupling becomes a zero value, then
        // drops out of the pattern, the row keeping a unit diagonal.
        let (r, h) = (n + 1, 2);
        let mut dense = vec![vec![0.0; n + 2]; n + 2];
        for j in 0..n + 2 {
            for p in released.col_ptr[j]..released.col_ptr[j + 1] {
                dense[released.row_idx[p]][j] = released.values[p];
            }
        }
        dense[r][h] = 0.0;
        dense[h][r] = 0.0;
        dense[r][r] = 1.0;
        released = dense_to_csc(&dense);
        let (moved, bm) = chain_with_holds(n, &[0, 4]);
        // The numeric factor's memory is pooled per analysis: the same
        // analysis with other values, then smaller and larger systems,
        // then the first again, must each be solved as afresh.
        let mut stiffer = a0.clone();
        stiffer.values.iter_mut().for_each(|v| *v *= 3.0);
        let (small, bs) = chain_with_holds(3, &[0]);
        let (large, bl) = chain_with_holds(9, &[1, 5]);
        for (a, b, primal) in [
            (&a0, &b0, n),
            (&a0, &b0, n),
            (&stiffer, &b0, n),
            (&released, &b0, n),
            (&moved, &bm, n),
            (&small, &bs, 3),
            (&large, &bl, 9),
            (&a0, &b0, n),
        ] {
            let r = solve(a, b, primal, false).expect("solvable");
            assert!(!r.cholesky);
            let fresh = {
                let s =
                    SymbolicSparseColMatRef::new_checked(a.n, a.n, &a.col_ptr, None, &a.row_idx);
                let lu = SparseColMatRef::new(s, &a.values).sp_lu().expect("regular");
                let mut c = Col::<f64>::from_fn(b.len(), |i| b[i]);
                lu.solve_in_place(c.as_mat_mut());
                c
            };
            for i in 0..a.n {
                assert!(
                    (r.x[i] - fresh[i]).abs() <= 1e-12 * (1.0 + fresh[i].abs()),
                    "{i}: {:?}",
                    r.x
                );
            }
            // Residual of the original system.
            let ax = a.mul(&r.x);
            for i in 0..a.n {
                assert!((ax[i] - b[i]).abs() < 1e-12, "row {i}: {ax:?}");
            }
        }
    }

    #[test]
    fn bordering_merges_and_sums() {
        let m = dense_to_csc(&[vec![2., 1.], vec![1., 2.]]);
        let b = m.with_extra(3, vec![(0, 0, 1.), (2, 1, 5.), (1, 2, 5.)]);
        assert_eq!(b.col_ptr, vec![0, 2, 5, 6]);
        assert_eq!(b.values, vec![3., 1., 1., 2., 5., 5.]);
    }
}
