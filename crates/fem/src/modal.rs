//! The real symmetric generalised eigenproblem of modal analysis
//! (`CALC_MODES` on `MATR_RIGI` K and `MATR_MASS` M): K x = λ M x under
//! homogeneous linear constraints C x = 0 (code_aster dualises `DDL_IMPO`
//! and `LIAISON_*` with Lagrange multipliers; the eigenvalues of the
//! bordered pencil are those of K and M restricted to the null space of C).
//!
//! Solved exactly, not iterated: the constraints are eliminated
//! (x = T z, T a basis of ker C built by Gauss–Jordan elimination of the
//! relation rows, imposed DOFs dropped), the reduced pencil is made dense
//! and shifted, A = Tᵀ(K + s M)T = L Lᵀ (Cholesky: positive definite for
//! s > 0 whenever K is positive semi-definite — free structures included —
//! and no direction is without both stiffness and mass), and the standard
//! symmetric problem L⁻¹ (TᵀMT) L⁻ᵀ y = μ y gives every eigenpair at once:
//! λ = 1/μ − s, x = L⁻ᵀ y (μ ≤ 0: a massless direction, an infinite
//! eigenvalue, left out). The shift s is chosen twice: first the ratio of
//! the traces (a rough scale of the spectrum), then √(λ_lo λ_hi) over the
//! selected modes, which bounds the relative error of the eigenvalues by
//! ε·max(λ_hi/s, s/λ_lo). Each selected eigenvalue is finally the Rayleigh
//! quotient xᵀKx / xᵀMx of its vector on the full matrices.
//!
//! Dense by design (the modal studies of code_aster's test base have a few
//! hundred to a few thousand unknowns): memory 8·n² bytes per matrix, a few
//! matrices; larger reduced problems are refused with their size
//! ([`MAX_DENSE`]).

use crate::error::FemError;
use crate::linalg::Csc;
use faer::{Mat, Side};

/// The largest reduced problem solved (unknowns after the constraints are
/// eliminated): 5 dense matrices of this size are about 640 MB.
pub const MAX_DENSE: usize = 4000;

/// Which eigenpairs (`CALC_MODES/OPTION`), on λ = ω².
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Selection {
    /// `PLUS_PETITE`: the `count` smallest.
    Lowest(usize),
    /// `CENTRE`: the `count` closest to λ = `centre`.
    Centre { centre: f64, count: usize },
    /// `BANDE`: every λ in [lo, hi].
    Band { lo: f64, hi: f64 },
    /// `TOUT`: all of them.
    All,
}

/// One eigenpair: λ and its vector over the full DOFs (M-normalised:
/// xᵀMx = 1), the constrained DOFs at zero (or as the relations give them).
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    pub lambda: f64,
    pub vector: Vec<f64>,
}

/// The basis T of the constraints' null space: each full DOF as a
/// combination of reduced unknowns.
struct Reduction {
    /// Per full DOF, its terms (reduced index, coefficient).
    rows: Vec<Vec<(usize, f64)>>,
    nr: usize,
}

/// Gauss–Jordan elimination of the constraint rows: a row with one term
/// fixes its DOF; the others are reduced (full pivoting on the largest
/// coefficient of each row), each pivot DOF then a combination of the
/// DOFs that remain free. Redundant rows are dropped.
fn reduction(n: usize, constraints: &[Vec<(usize, f64)>]) -> Result<Reduction, FemError> {
    let mut fixed = vec![false; n];
    for row in constraints {
        let terms: Vec<&(usize, f64)> = row.iter().filter(|(_, c)| *c != 0.0).collect();
        if terms.len() == 1 {
            let i = terms[0].0;
            if i >= n {
                return Err(FemError::Model(format!("constraint on DOF #{i} of {n}")));
            }
            fixed[i] = true;
        }
    }
    // Relations with at least two terms, fixed DOFs removed.
    let mut rels: Vec<Vec<(usize, f64)>> = Vec::new();
    for row in constraints {
        let mut r: Vec<(usize, f64)> = Vec::new();
        for &(i, c) in row {
            if i >= n {
                return Err(FemError::Model(format!("constraint on DOF #{i} of {n}")));
            }
            if c == 0.0 || fixed[i] {
                continue;
            }
            match r.iter_mut().find(|(j, _)| *j == i) {
                Some(t) => t.1 += c,
                None => r.push((i, c)),
            }
        }
        if r.iter().filter(|(_, c)| *c != 0.0).count() >= 2 && row.len() >= 2 {
            rels.push(r);
        } else if r.len() == 1 && row.len() >= 2 {
            // A relation that, with the fixed DOFs, fixes one more.
            fixed[r[0].0] = true;
        }
    }
    // Dense elimination over the DOFs the relations involve.
    let mut cols: Vec<usize> = rels.iter().flatten().map(|(i, _)| *i).collect();
    cols.sort_unstable();
    cols.dedup();
    let pos = |i: usize| cols.binary_search(&i).ok();
    let nc = cols.len();
    let mut a: Vec<Vec<f64>> = rels
        .iter()
        .map(|r| {
            let mut v = vec![0.0; nc];
            for &(i, c) in r {
                if let Some(p) = pos(i) {
                    v[p] += c;
                }
            }
            v
        })
        .collect();
    let mut pivots: Vec<(usize, usize)> = Vec::new(); // (row, column)
    let mut is_pivot = vec![false; nc];
    for r in 0..a.len() {
        let scale = a[r].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let (mut best, mut bv) = (usize::MAX, 0.0);
        for (j, v) in a[r].iter().enumerate() {
            if !is_pivot[j] && v.abs() > bv {
                bv = v.abs();
                best = j;
            }
        }
        if best == usize::MAX || bv <= 1e-12 * scale.max(f64::MIN_POSITIVE) {
            continue; // redundant
        }
        let p = a[r][best];
        for v in a[r].iter_mut() {
            *v /= p;
        }
        let pivot_row = a[r].clone();
        for (k, row) in a.iter_mut().enumerate() {
            if k == r {
                continue;
            }
            let f = row[best];
            if f != 0.0 {
                for (x, y) in row.iter_mut().zip(&pivot_row) {
                    *x -= f * y;
                }
                row[best] = 0.0;
            }
        }
        is_pivot[best] = true;
        pivots.push((r, best));
    }
    let mut dependent = vec![false; n];
    for &(_, c) in &pivots {
        dependent[cols[c]] = true;
    }
    let mut index = vec![usize::MAX; n];
    let mut nr = 0;
    for i in 0..n {
        if !fixed[i] && !dependent[i] {
            index[i] = nr;
            nr += 1;
        }
    }
    let mut rows: Vec<Vec<(usize, f64)>> = (0..n)
        .map(|i| {
            if index[i] != usize::MAX {
                vec![(index[i], 1.0)]
            } else {
                Vec::new()
            }
        })
        .collect();
    for &(r, c) in &pivots {
        let mut terms = Vec::new();
        for (j, &v) in a[r].iter().enumerate() {
            if j != c && v != 0.0 && !is_pivot[j] && index[cols[j]] != usize::MAX {
                terms.push((index[cols[j]], -v));
            }
        }
        rows[cols[c]] = terms;
    }
    Ok(Reduction { rows, nr })
}

/// Calls `f(row, column, value)` for every term of TᵀAT (repeated
/// positions are to be summed).
fn for_each_reduced(a: &Csc, t: &Reduction, mut f: impl FnMut(usize, usize, f64)) {
    for j in 0..a.n {
        let tj = &t.rows[j];
        if tj.is_empty() {
            continue;
        }
        for p in a.col_ptr[j]..a.col_ptr[j + 1] {
            let v = a.values[p];
            if v == 0.0 {
                continue;
            }
            for &(ri, ci) in &t.rows[a.row_idx[p]] {
                for &(rj, cj) in tj {
                    f(ri, rj, ci * v * cj);
                }
            }
        }
    }
}

/// TᵀAT, dense.
fn reduce(a: &Csc, t: &Reduction) -> Mat<f64> {
    let mut out = Mat::<f64>::zeros(t.nr, t.nr);
    for_each_reduced(a, t, |r, c, v| out[(r, c)] += v);
    out
}

fn expand(t: &Reduction, z: impl Fn(usize) -> f64) -> Vec<f64> {
    t.rows
        .iter()
        .map(|terms| terms.iter().map(|&(r, c)| c * z(r)).sum())
        .collect()
}

/// A mode from a vector of the full space: scaled to uᵀMu = 1, its
/// eigenvalue the Rayleigh quotient uᵀKu; `None` when uᵀMu ≤ 0.
fn mass_normalised(k: &Csc, m: &Csc, mut u: Vec<f64>) -> Option<Mode> {
    let mass = dot(&u, &m.mul(&u));
    if mass <= 0.0 {
        return None;
    }
    let f = 1.0 / mass.sqrt();
    u.iter_mut().for_each(|x| *x *= f);
    Some(Mode {
        lambda: dot(&u, &k.mul(&u)),
        vector: u,
    })
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The eigenvalues λ (ascending, finite ones only) and the solver of the
/// shifted problem at shift `s`.
struct Shifted {
    lambdas: Vec<f64>,
    /// Eigenvectors y of L⁻¹ M L⁻ᵀ, column k for `lambdas[k]`.
    y: Mat<f64>,
    /// The column of `y` of each λ.
    column: Vec<usize>,
    l: Mat<f64>,
}

fn shifted(k: &Mat<f64>, m: &Mat<f64>, s: f64) -> Result<Shifted, FemError> {
    let n = k.nrows();
    let mut a = k.clone();
    for j in 0..n {
        for i in 0..n {
            a[(i, j)] += s * m[(i, j)];
        }
    }
    let llt = a.llt(Side::Lower).map_err(|_| {
        FemError::Model(
            "the shifted stiffness K + s·M is not positive definite: the stiffness has negative directions (a buckling or unstable structure), or a direction has neither stiffness nor mass".into(),
        )
    })?;
    let l = llt.L().to_owned();
    let mut x = m.clone();
    l.as_ref().solve_lower_triangular_in_place(x.as_mut());
    let mut c = x.transpose().to_owned();
    l.as_ref().solve_lower_triangular_in_place(c.as_mut());
    // Symmetrised and scaled by s (its eigenvalues s·μ in (0, 1]): the
    // eigensolver's tolerances are absolute, and μ ≤ 1/s may be 1e-14.
    for j in 0..n {
        c[(j, j)] *= s;
        for i in 0..j {
            let v = 0.5 * s * (c[(i, j)] + c[(j, i)]);
            c[(i, j)] = v;
            c[(j, i)] = v;
        }
    }
    let eig = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| FemError::Model(format!("symmetric eigensolver: {e:?}")))?;
    let mu: Vec<f64> = (0..n).map(|i| eig.S()[i] / s).collect();
    let mumax = mu.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let mut pairs: Vec<(f64, usize)> = mu
        .iter()
        .enumerate()
        .filter(|(_, &m)| m > 1e-13 * mumax)
        .map(|(i, &m)| (1.0 / m - s, i))
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(Shifted {
        lambdas: pairs.iter().map(|p| p.0).collect(),
        column: pairs.iter().map(|p| p.1).collect(),
        y: eig.U().to_owned(),
        l,
    })
}

/// Indices (into the ascending λ) that a selection keeps, ascending.
fn select(lambdas: &[f64], sel: Selection) -> Vec<usize> {
    let n = lambdas.len();
    match sel {
        Selection::Lowest(c) => (0..c.min(n)).collect(),
        Selection::All => (0..n).collect(),
        Selection::Band { lo, hi } => (0..n)
            .filter(|&i| lambdas[i] >= lo && lambdas[i] <= hi)
            .collect(),
        Selection::Centre { centre, count } => {
            let mut idx: Vec<usize> = (0..n).collect();
            idx.sort_by(|&a, &b| {
                (lambdas[a] - centre)
                    .abs()
                    .total_cmp(&(lambdas[b] - centre).abs())
            });
            idx.truncate(count);
            idx.sort_unstable();
            idx
        }
    }
}

/// The selected eigenpairs of K x = λ M x under C x = 0 (each constraint a
/// row of (DOF, coefficient) terms), ascending in λ, each vector
/// M-normalised, λ its Rayleigh quotient.
pub fn modes(
    k: &Csc,
    m: &Csc,
    constraints: &[Vec<(usize, f64)>],
    selection: Selection,
) -> Result<Vec<Mode>, FemError> {
    if k.n != m.n {
        return Err(FemError::Model(format!(
            "the stiffness has {} DOFs and the mass {}",
            k.n, m.n
        )));
    }
    let t = reduction(k.n, constraints)?;
    if t.nr == 0 {
        return Ok(Vec::new());
    }
    if t.nr > MAX_DENSE {
        return Err(FemError::Model(format!(
            "{} unknowns after the boundary conditions: the dense modal solver takes at most {MAX_DENSE}",
            t.nr
        )));
    }
    let kr = reduce(k, &t);
    let mr = reduce(m, &t);
    let (mut trk, mut trm) = (0.0, 0.0);
    for i in 0..t.nr {
        trk += kr[(i, i)].abs();
        trm += mr[(i, i)].abs();
    }
    if trm == 0.0 {
        return Err(FemError::Model("the mass matrix is zero".into()));
    }
    let s0 = (trk / trm).max(f64::MIN_POSITIVE);
    let mut sh = shifted(&kr, &mr, s0)?;
    let mut chosen = select(&sh.lambdas, selection);
    // The shift that bounds the relative error of the selected eigenvalues
    // best; a rigid mode (|λ| ≤ 1e-10·s0) only needs s > 0.
    let positive: Vec<f64> = chosen
        .iter()
        .map(|&i| sh.lambdas[i])
        .filter(|&l| l > 1e-10 * s0)
        .collect();
    let s1 = match (positive.first(), positive.last()) {
        (Some(lo), Some(hi)) => (lo * hi).sqrt(),
        _ => s0 * 1e-6,
    };
    if !(1e-2..=1e2).contains(&(s1 / s0)) {
        sh = shifted(&kr, &mr, s1)?;
        chosen = select(&sh.lambdas, selection);
    }
    let n = t.nr;
    let mut out = Vec::with_capacity(chosen.len());
    let lt = sh.l.transpose().to_owned();
    for &i in &chosen {
        let col = sh.column[i];
        let mut y = Mat::<f64>::zeros(n, 1);
        for r in 0..n {
            y[(r, 0)] = sh.y[(r, col)];
        }
        lt.as_ref().solve_upper_triangular_in_place(y.as_mut());
        out.extend(mass_normalised(k, m, expand(&t, |r| y[(r, 0)])));
    }
    out.sort_by(|a, b| a.lambda.total_cmp(&b.lambda));
    Ok(out)
}

/// The number of unknowns once the constraints are eliminated.
pub fn unknowns(n: usize, constraints: &[Vec<(usize, f64)>]) -> Result<usize, FemError> {
    Ok(reduction(n, constraints)?.nr)
}

/// TᵀAT + s·TᵀBT, sparse, the lower triangle (for the Cholesky) and the
/// full TᵀBT (the M-products of the Lanczos vectors).
fn reduce_sparse(a: &Csc, t: &Reduction) -> Csc {
    let mut trip: Vec<(usize, usize, f64)> = Vec::new();
    for_each_reduced(a, t, |ri, rj, v| trip.push((rj, ri, v)));
    trip.sort_unstable_by_key(|&(c, r, _)| (c, r));
    let mut col_ptr = vec![0usize; t.nr + 1];
    let mut row_idx = Vec::with_capacity(trip.len());
    let mut values: Vec<f64> = Vec::with_capacity(trip.len());
    let mut last = (usize::MAX, usize::MAX);
    for (c, r, v) in trip {
        if (c, r) == last {
            *values.last_mut().expect("an entry") += v;
        } else {
            row_idx.push(r);
            values.push(v);
            col_ptr[c + 1] += 1;
            last = (c, r);
        }
    }
    for c in 0..t.nr {
        col_ptr[c + 1] += col_ptr[c];
    }
    Csc {
        n: t.nr,
        col_ptr,
        row_idx,
        values,
    }
}

/// The `count` smallest eigenpairs of a problem too large for the dense
/// solver: shift-invert Lanczos with full M-reorthogonalisation on the
/// sparse Cholesky factorisation of Tᵀ(K + s M)T (faer), s a small
/// positive shift (free structures), the Krylov space grown until the
/// wanted Ritz pairs have converged (residual ≤ 1e-12 relative).
pub fn lowest_modes(
    k: &Csc,
    m: &Csc,
    constraints: &[Vec<(usize, f64)>],
    count: usize,
) -> Result<Vec<Mode>, FemError> {
    use faer::linalg::solvers::Solve;
    use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
    use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
    let t = reduction(k.n, constraints)?;
    let n = t.nr;
    if n == 0 || count == 0 {
        return Ok(Vec::new());
    }
    let kr = reduce_sparse(k, &t);
    let mr = reduce_sparse(m, &t);
    let (trk, trm) = (
        kr.diagonal().iter().map(|v| v.abs()).sum::<f64>(),
        mr.diagonal().iter().map(|v| v.abs()).sum::<f64>(),
    );
    if trm == 0.0 {
        return Err(FemError::Model("the mass matrix is zero".into()));
    }
    // A shift well below the mean eigenvalue: rigid modes need s > 0, and
    // s small keeps the low spectrum apart under the inversion.
    let s = 1e-6 * trk / trm;
    // A = Kr + s Mr, lower triangle.
    let mut lower = Csc {
        n,
        col_ptr: vec![0; n + 1],
        row_idx: Vec::new(),
        values: Vec::new(),
    };
    {
        let mut kv: std::collections::BTreeMap<(usize, usize), f64> = Default::default();
        for (a, f) in [(&kr, 1.0), (&mr, s)] {
            for j in 0..n {
                for p in a.col_ptr[j]..a.col_ptr[j + 1] {
                    let i = a.row_idx[p];
                    if i >= j {
                        *kv.entry((j, i)).or_insert(0.0) += f * a.values[p];
                    }
                }
            }
        }
        for ((j, i), v) in kv {
            lower.row_idx.push(i);
            lower.values.push(v);
            lower.col_ptr[j + 1] += 1;
        }
        for j in 0..n {
            lower.col_ptr[j + 1] += lower.col_ptr[j];
        }
    }
    let sym = SymbolicSparseColMatRef::new_checked(n, n, &lower.col_ptr, None, &lower.row_idx);
    let mat = SparseColMatRef::new(sym, &lower.values);
    let symbolic = SymbolicLlt::try_new(sym, Side::Lower)
        .map_err(|e| FemError::Model(format!("sparse Cholesky analysis: {e:?}")))?;
    let llt = Llt::try_new_with_symbolic(symbolic, mat, Side::Lower).map_err(|_| {
        FemError::Model(
            "the shifted stiffness K + s·M is not positive definite: the stiffness has negative directions (a buckling or unstable structure), or a direction has neither stiffness nor mass".into(),
        )
    })?;
    // A⁻¹ (M x) from M x: the Krylov loop has M vⱼ already (profiled on
    // sdll18a: the products by M were a quarter of the time).
    let solve_m = |mx: &[f64]| -> Vec<f64> {
        let mut c = faer::Col::<f64>::from_fn(n, |i| mx[i]);
        llt.solve_in_place(c.as_mat_mut());
        (0..n).map(|i| c[i]).collect()
    };
    let op = |x: &[f64]| -> Vec<f64> { solve_m(&mr.mul(x)) };
    // Lanczos in the M-inner product on Op = A⁻¹ M (self-adjoint in it),
    // the Krylov vectors kept M-orthogonal to `locked` (M-normalised
    // reduced vectors already found, with their M-products).
    let mdot = |a: &[f64], b: &[f64]| -> f64 { dot(a, &mr.mul(b)) };
    type Locked = Vec<(Vec<f64>, Vec<f64>)>;
    let run = |count: usize,
               locked: &Locked,
               salt: u64|
     -> Result<Vec<(f64, Vec<f64>)>, FemError> {
        let free = n.saturating_sub(locked.len());
        let mut steps = (2 * count + 20).min(free);
        let mut seed = 0x9E37_79B9_7F4A_7C15u64 ^ salt;
        let r0: Vec<f64> = (0..n)
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect();
        let orth = |z: &mut Vec<f64>, v: &[Vec<f64>], mv: &[Vec<f64>]| {
            for _ in 0..2 {
                for (vi, mvi) in locked.iter().map(|(a, b)| (a, b)).chain(v.iter().zip(mv)) {
                    let c = dot(z, mvi);
                    z.iter_mut().zip(vi).for_each(|(x, y)| *x -= c * y);
                }
            }
        };
        let mut w = op(&r0);
        orth(&mut w, &[], &[]);
        let nrm = mdot(&w, &w).max(0.0).sqrt();
        if nrm == 0.0 {
            return Ok(Vec::new());
        }
        w.iter_mut().for_each(|x| *x /= nrm);
        // The Krylov space is extended, not rebuilt, when it must grow:
        // its first vectors are the same (sdll18a, sdll153a spent their
        // time rebuilding them).
        let mut v: Vec<Vec<f64>> = Vec::with_capacity(steps);
        let mut mv: Vec<Vec<f64>> = Vec::with_capacity(steps);
        let mut alpha: Vec<f64> = Vec::with_capacity(steps);
        let mut beta: Vec<f64> = Vec::with_capacity(steps);
        let mut breakdown = false;
        loop {
            while v.len() < steps && !breakdown {
                let j = v.len();
                let mw = mr.mul(&w);
                v.push(std::mem::take(&mut w));
                mv.push(mw);
                let mut z = solve_m(&mv[j]);
                let a = dot(&z, &mv[j]);
                alpha.push(a);
                orth(&mut z, &v, &mv);
                let b = mdot(&z, &z).max(0.0).sqrt();
                if j + 1 < steps && b <= 1e-14 * a.abs().max(f64::MIN_POSITIVE) {
                    beta.push(0.0);
                    breakdown = true;
                    break;
                }
                beta.push(b);
                if b > 0.0 {
                    z.iter_mut().for_each(|x| *x /= b);
                }
                w = z;
            }
            let mdim = alpha.len();
            let scale = alpha
                .iter()
                .fold(0.0f64, |a, b| a.max(b.abs()))
                .max(f64::MIN_POSITIVE);
            let mut tri = Mat::<f64>::zeros(mdim, mdim);
            for i in 0..mdim {
                tri[(i, i)] = alpha[i] / scale;
                if i + 1 < mdim {
                    tri[(i, i + 1)] = beta[i] / scale;
                    tri[(i + 1, i)] = beta[i] / scale;
                }
            }
            let eig = tri
                .self_adjoint_eigen(Side::Lower)
                .map_err(|e| FemError::Model(format!("symmetric eigensolver: {e:?}")))?;
            let want = count.min(mdim);
            let last_beta = beta.last().copied().unwrap_or(0.0);
            let mut converged = true;
            let mut out = Vec::with_capacity(want);
            for q in 0..want {
                let col = mdim - 1 - q;
                let theta = eig.S()[col] * scale;
                let resid = (last_beta * eig.U()[(mdim - 1, col)]).abs();
                if theta <= 0.0 || resid > 1e-12 * theta.abs() {
                    converged = false;
                }
                let mut z = vec![0.0; n];
                for (i, vi) in v.iter().enumerate() {
                    let c = eig.U()[(i, col)];
                    z.iter_mut().zip(vi).for_each(|(x, y)| *x += c * y);
                }
                out.push((1.0 / theta - s, z));
            }
            if converged || breakdown || steps >= free {
                return Ok(out);
            }
            if steps >= 2000 {
                return Err(FemError::Model(format!(
                    "the Lanczos iterations did not converge for the {count} lowest modes in {steps} steps"
                )));
            }
            steps = (steps * 2).min(free);
        }
    };
    // The lowest `count`, then Lanczos again M-orthogonal to them until no
    // mode below the highest found is left: a single-vector Krylov space
    // holds one vector of a repeated eigenvalue, the others are found by
    // these deflated runs.
    let mut found = run(count, &Vec::new(), 0)?;
    for round in 1..=8u64 {
        let Some(top) = found.iter().map(|f| f.0).reduce(f64::max) else {
            break;
        };
        let locked: Locked = found.iter().map(|(_, z)| (z.clone(), mr.mul(z))).collect();
        if locked.len() >= n {
            break;
        }
        let more = run(count.min(8), &locked, round)?;
        let below: Vec<(f64, Vec<f64>)> = more
            .into_iter()
            .filter(|(l, _)| *l < top + 1e-9 * top.abs())
            .collect();
        if below.is_empty() {
            break;
        }
        found.extend(below);
        found.sort_by(|a, b| a.0.total_cmp(&b.0));
        found.truncate(count);
    }
    let mut modes = Vec::with_capacity(found.len());
    for (_, z) in found {
        modes.extend(mass_normalised(k, m, expand(&t, |r| z[r])));
    }
    modes.sort_by(|a, b| a.lambda.total_cmp(&b.lambda));
    Ok(modes)
}

/// code_aster's default normalisation of modes (`vpnorx`, `SANS_CMP:
/// LAGR`): the vector divided by its component of largest absolute value
/// (the first such in DOF order), which becomes +1. Returns the divisor.
pub fn normalise_max_component(u: &mut [f64]) -> f64 {
    let mut best = 0.0f64;
    for &v in u.iter() {
        if best.abs() < v.abs() {
            best = v;
        }
    }
    if best != 0.0 {
        u.iter_mut().for_each(|v| *v /= best);
    }
    best
}

/// Whether the largest component of `u` is shared (to `rel`) by another
/// component of the opposite sign: the sign code_aster's `vpnorx` gives
/// the mode then depends on which comes first in its own DOF order and on
/// rounding, so aster cannot reproduce it.
pub fn sign_ambiguous(u: &[f64], rel: f64) -> bool {
    let max = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if max == 0.0 {
        return false;
    }
    let pos = u.iter().any(|&v| v > 0.0 && (max - v) <= rel * max);
    let neg = u.iter().any(|&v| v < 0.0 && (max + v) <= rel * max);
    pos && neg
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of n unit masses and unit springs, fixed at one end
    /// (constraint on DOF 0 of n+1): λ_k = 4 sin²((2k−1)π / (2(2n+1))).
    fn chain(n: usize) -> (Csc, Csc) {
        let nd = n + 1;
        let cols: Vec<Vec<u32>> = (0..nd)
            .map(|j| {
                let mut c = vec![j as u32];
                if j > 0 {
                    c.push(j as u32 - 1);
                }
                if j + 1 < nd {
                    c.push(j as u32 + 1);
                }
                c
            })
            .collect();
        let mut k = Csc::from_columns(nd, cols.clone());
        let mut m = Csc::from_columns(nd, cols);
        for e in 0..n {
            k.add(e, e, 1.0);
            k.add(e + 1, e + 1, 1.0);
            k.add(e, e + 1, -1.0);
            k.add(e + 1, e, -1.0);
        }
        for i in 1..nd {
            m.add(i, i, 1.0);
        }
        m.add(0, 0, 1.0);
        (k, m)
    }

    #[test]
    fn fixed_free_chain_matches_its_closed_form() {
        let n = 20;
        let (k, m) = chain(n);
        let modes = modes(&k, &m, &[vec![(0, 1.0)]], Selection::Lowest(5)).unwrap();
        assert_eq!(modes.len(), 5);
        for (i, md) in modes.iter().enumerate() {
            let kk = (i + 1) as f64;
            let exact = 4.0
                * ((2.0 * kk - 1.0) * std::f64::consts::PI / (2.0 * (2.0 * n as f64 + 1.0)))
                    .sin()
                    .powi(2);
            assert!(
                (md.lambda - exact).abs() < 1e-12 * exact,
                "{} {}",
                md.lambda,
                exact
            );
            assert_eq!(md.vector[0], 0.0);
        }
    }

    #[test]
    fn a_free_chain_has_a_rigid_mode_and_a_relation_acts_as_a_support() {
        let (k, m) = chain(6);
        let free = modes(&k, &m, &[], Selection::Lowest(2)).unwrap();
        assert!(free[0].lambda.abs() < 1e-10, "{}", free[0].lambda);
        assert!(free[1].lambda > 1e-3);
        // u0 − u1 = 0 and u0 = 0: the same as fixing the first two DOFs.
        let rel = modes(
            &k,
            &m,
            &[vec![(0, 1.0), (1, -1.0)], vec![(0, 1.0)]],
            Selection::All,
        )
        .unwrap();
        let fix = modes(&k, &m, &[vec![(0, 1.0)], vec![(1, 1.0)]], Selection::All).unwrap();
        assert_eq!(rel.len(), fix.len());
        for (a, b) in rel.iter().zip(&fix) {
            assert!((a.lambda - b.lambda).abs() < 1e-12 * b.lambda.abs().max(1.0));
        }
    }

    /// Two identical chains side by side: every eigenvalue twice.
    fn two_chains(n: usize) -> (Csc, Csc, Vec<Vec<(usize, f64)>>) {
        let (k1, m1) = chain(n);
        let nd = k1.n;
        let mut cols: Vec<Vec<u32>> = Vec::new();
        for off in [0, nd] {
            for j in 0..nd {
                let (a, b) = (k1.col_ptr[j], k1.col_ptr[j + 1]);
                cols.push(k1.row_idx[a..b].iter().map(|&r| (r + off) as u32).collect());
            }
        }
        let mut k = Csc::from_columns(2 * nd, cols.clone());
        let mut m = Csc::from_columns(2 * nd, cols);
        for off in [0, nd] {
            for j in 0..nd {
                for p in k1.col_ptr[j]..k1.col_ptr[j + 1] {
                    k.add(k1.row_idx[p] + off, j + off, k1.values[p]);
                    m.add(k1.row_idx[p] + off, j + off, m1.values[p]);
                }
            }
        }
        (k, m, vec![vec![(0, 1.0)], vec![(nd, 1.0)]])
    }

    fn m_orthonormal(m: &Csc, modes: &[Mode]) {
        for (i, a) in modes.iter().enumerate() {
            let ma = m.mul(&a.vector);
            for (j, b) in modes.iter().enumerate() {
                let g = dot(&b.vector, &ma);
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((g - want).abs() < 1e-9, "({i}, {j}): {g}");
            }
        }
    }

    #[test]
    fn repeated_eigenvalues_are_found_twice_by_both_solvers_and_m_orthonormal() {
        let (k, m, c) = two_chains(30);
        let dense = modes(&k, &m, &c, Selection::Lowest(6)).unwrap();
        let sparse = lowest_modes(&k, &m, &c, 6).unwrap();
        assert_eq!(dense.len(), 6);
        assert_eq!(sparse.len(), 6);
        for pair in dense.chunks(2) {
            assert!((pair[0].lambda - pair[1].lambda).abs() < 1e-12 * pair[0].lambda);
        }
        for (a, b) in dense.iter().zip(&sparse) {
            assert!(
                (a.lambda - b.lambda).abs() < 1e-10 * a.lambda,
                "{} {}",
                a.lambda,
                b.lambda
            );
        }
        m_orthonormal(&m, &dense);
        m_orthonormal(&m, &sparse);
    }

    #[test]
    fn vpnorx_divides_by_the_first_largest_component() {
        let mut u = vec![0.5, -2.0, 1.0];
        assert_eq!(normalise_max_component(&mut u), -2.0);
        assert_eq!(u, vec![-0.25, 1.0, -0.5]);
        assert!(sign_ambiguous(&[1.0, -1.0, 0.2], 1e-8));
        assert!(!sign_ambiguous(&[1.0, 1.0, 0.2], 1e-8));
    }
}
