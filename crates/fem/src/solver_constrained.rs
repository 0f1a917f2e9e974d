//! The constrained linear systems of Newton's iterations, solved through
//! the stiffness alone (a Schur complement on the multipliers):
//!
//! ```text
//! [ K  Aᵀ ] [Δu] = [b]
//! [ A  0  ] [λ ]   [d]
//! ```
//!
//! Why: assembling and LU-factorising the bordered (indefinite) matrix for
//! every Newton iteration and every active-set change dominated the run time
//! of contact cases (ssnv506c: ~450 sparse LU of 11,000 unknowns, two thirds
//! of the CPU). Here
//!
//! - single-DOF equality rows (DDL_IMPO, and LIAISON_DDL rows reduced to one
//!   free DOF) *pin* their DOF: Δuᵢ = dᵣ/cᵣ, the DOF leaves the factorised
//!   matrix and its multiplier is the residual of its equilibrium row;
//! - the remaining matrix K_rr is factorised once per matrix (Cholesky, the
//!   symbolic analysis kept while the pattern is the same; LU when it is not
//!   positive definite) and reused for every active set, step and geometric
//!   pass that keeps the matrix — an elastic model factorises once for the
//!   whole analysis;
//! - the other rows (inequality rows, multi-DOF relations: a few hundred at
//!   most) enter through S = A K_rr⁻¹ Aᵀ, a small dense matrix, with the
//!   columns K_rr⁻¹ aᵣ cached per row for the current factor;
//! - when only the multi-DOF equality rows hold the model (a body hung on
//!   LIAISON_ELEM 3D_POU), they are factorised with K_rr: augmented by
//!   their Lagrangian terms Σ wᵣ aᵣaᵣᵀ (exact: zero where the rows hold)
//!   and factorised as LDLᵀ without pivoting, each multiplier after its
//!   row's anchor (`augmented_ldlt_order`); an unsymmetric matrix takes
//!   the bordered LU of K_rr and those rows.
//!
//! When that structure does not apply (the pinned DOFs do not hold the
//! model, a DOF pinned twice, S singular, a factorisation failure) the
//! caller falls back to the bordered LU ([`crate::linalg::solve_with`]),
//! which also names what is wrong.

use crate::linalg::{Csc, SolveFailure, SolveReport, MAX_BACKWARD_ERROR};
use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, SymbolicCholesky};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Mat, Side};
use nalgebra::DMatrix;
use std::collections::HashMap;
use std::sync::Arc;

/// Which matrix the caller hands over: the constant elastic one, or a
/// tangent identified by the id [`KktSolver::new_tangent`] gave it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MatrixKey {
    Elastic,
    /// A tangent; a non-symmetric one (SIMO_MIEHE) is factorised by LU.
    Tangent {
        id: u64,
        symmetric: bool,
    },
}

impl MatrixKey {
    fn symmetric(self) -> bool {
        match self {
            MatrixKey::Elastic => true,
            MatrixKey::Tangent { symmetric, .. } => symmetric,
        }
    }
}

/// One constraint row over free unknowns: Σ c·Δu = d.
pub(crate) struct Row<'a> {
    pub terms: &'a [(usize, f64)],
    pub d: f64,
    /// An equality (may pin its DOF); inequality rows never do, as their
    /// activity changes.
    pub equality: bool,
}

/// Most passes of iterative refinement per solve.
const REFINEMENT_STEPS: usize = 4;

/// A refinement pass whose correction is at most this relative to the
/// solution (in the displacements or in the multipliers) is the last: it
/// is applied without computing the residual again. Measured on sdnl133d
/// (199 rows, 6 pinned): the first correction is 5e-13 relative, the
/// second 7e-17 — below the rounding of the values it corrects.
const REFINED: f64 = 1e-12;

/// Below this many reduced unknowns the factorisation uses AMD; above it, a
/// geometric nested dissection when coordinates are given.
const ND_THRESHOLD: usize = 20_000;

/// Most entries Σ |aᵣ|² the augmented Lagrangian may add (a row over k
/// unknowns adds a k × k clique; ssnv166b adds 2.0 M): beyond it,
/// rows over tens of thousands of unknowns, the bordered matrix keeps the
/// LU rather than build cliques of that size.
const AUGMENTED_MAX_TERMS: usize = 25_000_000;

enum RFactor {
    Llt {
        symbolic: Arc<SymbolicCholesky<usize>>,
        values: Vec<f64>,
    },
    /// The bordered matrix of the inside rows, augmented (see
    /// [`augmented_ldlt_order`]): LDLᵀ without pivoting, each multiplier
    /// ordered after the unknowns of its row.
    Ldlt {
        symbolic: Arc<SymbolicCholesky<usize>>,
        values: Vec<f64>,
    },
    Lu(Box<faer::sparse::linalg::solvers::Lu<usize, f64>>),
}

/// The factorised reduced matrix and what it was built from.
struct Reduced {
    key: MatrixKey,
    penalty: Vec<(usize, usize, f64)>,
    pinned: Vec<usize>,
    /// K + penalty terms, when there are penalty terms (else the caller's).
    keff: Option<Csc>,
    /// The equality rows factorised with K_rr (free indexing), when the
    /// pinned DOFs alone do not hold the model: the factorised matrix is
    /// then the bordered [K_rr Aᵢᵀ; Aᵢ 0] (LU), its multipliers after the
    /// reduced unknowns. Empty: K_rr alone.
    inside: Vec<Vec<(usize, f64)>>,
    /// Free index → reduced index (usize::MAX when pinned).
    red_of: Vec<usize>,
    /// Reduced index → free index.
    full_of: Vec<usize>,
    /// The augmented Lagrangian weights wᵣ of the inside rows (the
    /// factorised matrix holds K_rr + Σ wᵣ aᵣaᵣᵀ; the right-hand side gets
    /// Σ wᵣ aᵣ dᵣ): empty when K_rr is factorised as it is.
    weights: Vec<f64>,
    /// Symmetric scaling of the factorised matrix: 1/√|Kᵢᵢ| for the reduced
    /// unknowns, then one factor per inside row's multiplier.
    scale: Vec<f64>,
    factor: RFactor,
    /// ‖K_eff‖∞, for backward errors.
    norm_inf: f64,
    /// K_rr⁻¹ aᵣ per reduced row (keyed by its terms).
    columns: HashMap<Vec<(usize, u64)>, Vec<f64>>,
}

/// Equality rows over several free unknowns (terms in free indexing).
pub(crate) type Relations = Vec<Vec<(usize, f64)>>;

/// A symbolic Cholesky with the pattern (column pointers, row indices) it
/// was computed for.
type PatternSymbolic = (Vec<usize>, Vec<usize>, Arc<SymbolicCholesky<usize>>);

/// Factorisations and their by-products kept across Newton iterations,
/// active sets and steps.
#[derive(Default)]
pub(crate) struct KktSolver {
    reduced: Option<Reduced>,
    /// The symbolic Cholesky of the last reduced pattern.
    symbolic: Option<PatternSymbolic>,
    /// Whether the pinned DOFs (with the eliminated ones) hold the model.
    held: Vec<(Vec<usize>, bool)>,
    /// Whether the pinned DOFs and these equality rows hold it.
    held_with_rows: Vec<(Vec<usize>, Relations, bool)>,
    next_id: u64,
    /// Statistics: numeric factorisations and reduced solves done.
    pub factorisations: usize,
    pub solves: usize,
}

impl KktSolver {
    /// A fresh id for a newly assembled tangent.
    pub fn new_tangent(&mut self, symmetric: bool) -> MatrixKey {
        self.next_id += 1;
        MatrixKey::Tangent {
            id: self.next_id,
            symmetric,
        }
    }

    /// Solves the bordered system for `base` (+ `penalty` triplets, free
    /// indices) with `rows`; `b` holds the free right-hand side. Returns
    /// [Δu, λ in row order], or `None` when the structure does not apply
    /// and the caller should use the bordered LU. `held(pinned)` says
    /// whether the pinned free unknowns hold the model (asked once per
    /// pinned set).
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        key: MatrixKey,
        base: &Csc,
        penalty: &[(usize, usize, f64)],
        rows: &[Row],
        b: &[f64],
        coords: Option<&[[f64; 3]]>,
        held: &dyn Fn(&[usize], &Relations) -> bool,
    ) -> Result<Option<SolveReport>, SolveFailure> {
        let _solve = crate::newton_timing::phase(crate::newton_timing::Phase::Solve);
        let n = base.n;
        // Pinned rows: equality rows on one free DOF.
        let mut pin_of_dof: HashMap<usize, usize> = HashMap::new();
        let mut pinned_rows: Vec<(usize, usize, f64)> = Vec::new(); // (row, dof, coef)
        for (r, row) in rows.iter().enumerate() {
            if let (true, [(i, c)]) = (row.equality, row.terms) {
                if *c == 0.0 {
                    return Ok(None);
                }
                if pin_of_dof.insert(*i, r).is_some() {
                    // Two rows on one DOF: a redundant pair the bordered
                    // path reports.
                    return Ok(None);
                }
                pinned_rows.push((r, *i, *c));
            }
        }
        let mut pinned: Vec<usize> = pinned_rows.iter().map(|p| p.1).collect();
        pinned.sort_unstable();
        let mut penalty_sorted = penalty.to_vec();
        penalty_sorted.sort_unstable_by_key(|a| (a.1, a.0));
        // Equality rows over several free unknowns (or one already pinned):
        // factorised with K_rr when the pins alone do not hold the model.
        let mut is_pinned_row = vec![false; rows.len()];
        for p in &pinned_rows {
            is_pinned_row[p.0] = true;
        }
        let general: Vec<usize> = (0..rows.len()).filter(|&r| !is_pinned_row[r]).collect();
        let general_eq: Vec<Vec<(usize, f64)>> = general
            .iter()
            .filter(|&&r| rows[r].equality)
            .map(|&r| rows[r].terms.to_vec())
            .collect();
        let current = self.reduced.as_ref().is_some_and(|r| {
            r.key == key
                && r.pinned == pinned
                && r.penalty == penalty_sorted
                && (r.inside.is_empty() || r.inside == general_eq)
        });
        if !current {
            if std::env::var_os("ASTER_FEM_TRACE").is_some() {
                let why = match self.reduced.as_ref() {
                    None => "first".to_string(),
                    Some(r) => format!(
                        "key {} pinned {} penalty {} inside {}",
                        r.key == key,
                        r.pinned == pinned,
                        r.penalty == penalty_sorted,
                        r.inside.is_empty() || r.inside == general_eq
                    ),
                };
                eprintln!("[kkt] new factorisation ({why})");
            }
            self.reduced = None;
            let is_held = match self.held.iter().find(|(p, _)| *p == pinned) {
                Some(&(_, h)) => h,
                None => {
                    let h = held(&pinned, &Vec::new());
                    self.held.push((pinned.clone(), h));
                    h
                }
            };
            let inside = if is_held {
                Vec::new()
            } else {
                // The model is held through multi-DOF relations (a body
                // hung on LIAISON_ELEM, LIAISON_SOLIDE rows): K_rr is
                // singular, the bordered matrix of those rows is not.
                if general_eq.is_empty() {
                    return Ok(None);
                }
                let known = self
                    .held_with_rows
                    .iter()
                    .find(|(p, e, _)| *p == pinned && *e == general_eq)
                    .map(|h| h.2);
                let h = match known {
                    Some(h) => h,
                    None => {
                        let h = held(&pinned, &general_eq);
                        self.held_with_rows
                            .push((pinned.clone(), general_eq.clone(), h));
                        h
                    }
                };
                if !h {
                    return Ok(None);
                }
                general_eq.clone()
            };
            let Some(red) = self.factorise(key, base, penalty_sorted, pinned, inside, coords)
            else {
                return Ok(None);
            };
            self.factorisations += 1;
            self.reduced = Some(red);
        }
        let Some(red) = self.reduced.as_mut() else {
            return Ok(None);
        };
        let keff = red.keff.as_ref().unwrap_or(base);
        // General rows, reduced: terms on pinned DOFs move to the right.
        let reduced_terms: Vec<Vec<(usize, f64)>> = general
            .iter()
            .map(|&r| {
                rows[r]
                    .terms
                    .iter()
                    .filter(|(i, _)| red.red_of[*i] != usize::MAX)
                    .map(|&(i, c)| (red.red_of[i], c))
                    .collect()
            })
            .collect();
        // Rows whose terms all sit on pinned DOFs must hold as they are;
        // S would be singular with them.
        if reduced_terms.iter().any(|t| t.is_empty()) {
            return Ok(None);
        }
        // Which general rows are factorised (their multiplier is unknown
        // nr + k of the factor) and which go through S.
        let bordered = !red.inside.is_empty();
        let outside: Vec<usize> = (0..general.len())
            .filter(|&k| !(bordered && rows[general[k]].equality))
            .collect();
        let inside_pos: Vec<usize> = (0..general.len())
            .filter(|&k| bordered && rows[general[k]].equality)
            .collect();
        // M⁻¹ [aᵣ; 0] for the rows not seen with this factor.
        let keys: Vec<Vec<(usize, u64)>> = outside
            .iter()
            .map(|&k| {
                reduced_terms[k]
                    .iter()
                    .map(|&(i, c)| (i, c.to_bits()))
                    .collect()
            })
            .collect();
        let missing: Vec<usize> = (0..keys.len())
            .filter(|&q| !red.columns.contains_key(&keys[q]))
            .collect();
        if !missing.is_empty() {
            let _t = crate::newton_timing::phase(crate::newton_timing::Phase::RowColumns);
            let nt = red.scale.len();
            let mut rhs = Mat::<f64>::zeros(nt, missing.len());
            for (col, &q) in missing.iter().enumerate() {
                for &(j, c) in &reduced_terms[outside[q]] {
                    rhs[(j, col)] += c;
                }
            }
            red.solve_many(&mut rhs);
            for (col, &q) in missing.iter().enumerate() {
                let w: Vec<f64> = (0..nt).map(|j| rhs[(j, col)]).collect();
                red.columns.insert(keys[q].clone(), w);
            }
        }
        let m = outside.len();
        let red: &Reduced = red;
        let cols: Vec<&[f64]> = keys.iter().map(|k| red.columns[k].as_slice()).collect();
        let mut s = DMatrix::<f64>::zeros(m, m);
        for (q, &kq) in outside.iter().enumerate() {
            for (r, w) in cols.iter().enumerate() {
                s[(q, r)] = reduced_terms[kq].iter().map(|&(j, c)| c * w[j]).sum();
            }
        }
        // S = A K⁻¹ Aᵀ is symmetric positive definite when the rows are
        // independent; a rank-deficient S (redundant rows) goes to the
        // bordered path.
        let s_factor = if m == 0 {
            None
        } else {
            let chol = if key.symmetric() {
                nalgebra::linalg::Cholesky::new(s.clone())
            } else {
                None
            };
            match chol {
                Some(c) => Some(SFactor::Chol(c)),
                None => {
                    let lu = s.clone().full_piv_lu();
                    let diag_max = (0..m).fold(0.0f64, |a, i| a.max(s[(i, i)].abs()));
                    let u = lu.u();
                    let min_piv = (0..m).fold(f64::INFINITY, |a, i| a.min(u[(i, i)].abs()));
                    if min_piv.is_nan() || min_piv <= 1e-12 * diag_max {
                        return Ok(None);
                    }
                    Some(SFactor::Lu(lu))
                }
            }
        };
        let d: Vec<f64> = rows.iter().map(|r| r.d).collect();
        let norm_aug = {
            let mut row_sums = vec![0.0f64; n];
            let mut cons = 0.0f64;
            for row in rows {
                let mut s = 0.0;
                for &(i, c) in row.terms {
                    row_sums[i] += c.abs();
                    s += c.abs();
                }
                cons = cons.max(s);
            }
            red.norm_inf + row_sums.iter().fold(0.0f64, |a, v| a.max(*v)) + cons
        };
        let ctx = SolveCtx {
            red,
            keff,
            rows,
            pinned_rows: &pinned_rows,
            general: &general,
            reduced_terms: &reduced_terms,
            outside: &outside,
            inside_pos: &inside_pos,
            cols: &cols,
            s_factor: s_factor.as_ref(),
        };
        let mut x = ctx.apply(b, &d);
        let norm_b = b.iter().chain(&d).fold(0.0f64, |a, v| a.max(v.abs()));
        let berr = |x: &[f64]| -> (f64, Vec<f64>, Vec<f64>) {
            let (ru, rd) =
                crate::newton_timing::timed(crate::newton_timing::Phase::Residuals, || {
                    residual(keff, rows, b, &d, x)
                });
            let nr = ru.iter().chain(&rd).fold(0.0f64, |a, v| a.max(v.abs()));
            let nx = x.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let den = norm_aug * nx + norm_b;
            (if den > 0.0 { nr / den } else { 0.0 }, ru, rd)
        };
        // Iterative refinement with accurate residuals: each pass divides
        // the error by about cond(K_rr)·ε, so it converges to the solution
        // of the system as given (soft modes included) even when the
        // normwise backward error is already tiny. Stops when a correction
        // no longer changes the displacements or the multipliers.
        let (mut be, mut ru, mut rd) = berr(&x);
        let block_max = |v: &[f64]| -> (f64, f64) {
            let (a, b) = v.split_at(n);
            let m = |s: &[f64]| s.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            (m(a), m(b))
        };
        let mut last_step = f64::INFINITY;
        for _ in 0..REFINEMENT_STEPS {
            let dx = ctx.apply(&ru, &rd);
            let (du_max, dl_max) = block_max(&dx);
            let (u_max, l_max) = block_max(&x);
            let step = (du_max / u_max.max(1e-300)).max(dl_max / l_max.max(1e-300));
            if std::env::var_os("ASTER_FEM_TRACE").is_some() {
                eprintln!("[kkt] refinement: backward error {be:.3e}, correction {du_max:.3e} (u) {dl_max:.3e} (λ), relative {step:.3e}, {} rows, {} pinned", rows.len(), pinned_rows.len());
            }
            if step.is_nan() || step >= last_step {
                break;
            }
            last_step = step;
            let cand: Vec<f64> = x.iter().zip(&dx).map(|(a, b)| a + b).collect();
            if step <= REFINED {
                // A correction this small leaves an error of about its
                // size times cond·ε: nothing the next pass would change
                // beyond the last bits. Take it and stop (the backward
                // error kept is the previous iterate's, an upper bound).
                x = cand;
                break;
            }
            let (be2, ru2, rd2) = berr(&cand);
            x = cand;
            (be, ru, rd) = (be2, ru2, rd2);
        }
        self.solves += 1;
        if x.iter().any(|v| !v.is_finite()) || be > MAX_BACKWARD_ERROR {
            return Ok(None);
        }
        Ok(Some(SolveReport {
            x,
            backward_error: be,
            cholesky: matches!(
                self.reduced.as_ref().map(|r| &r.factor),
                Some(RFactor::Llt { .. })
            ),
        }))
    }

    /// Builds and factorises the reduced matrix; `None` when neither
    /// Cholesky nor LU succeeds.
    fn factorise(
        &mut self,
        key: MatrixKey,
        base: &Csc,
        penalty: Vec<(usize, usize, f64)>,
        pinned: Vec<usize>,
        inside: Vec<Vec<(usize, f64)>>,
        coords: Option<&[[f64; 3]]>,
    ) -> Option<Reduced> {
        use crate::newton_timing::{phase, Phase};
        let assembling = phase(Phase::Assembly);
        let n = base.n;
        let keff = (!penalty.is_empty()).then(|| base.with_extra(n, penalty.clone()));
        let k = keff.as_ref().unwrap_or(base);
        let mut red_of = vec![0usize; n];
        for &p in &pinned {
            red_of[p] = usize::MAX;
        }
        let mut full_of = Vec::with_capacity(n - pinned.len());
        for (i, r) in red_of.iter_mut().enumerate() {
            if *r != usize::MAX {
                *r = full_of.len();
                full_of.push(i);
            }
        }
        let krr = crate::assembly::restrict(k, &red_of, full_of.len());
        // A model held by its relations and a symmetric matrix: the
        // relations' augmented Lagrangian terms make K_rr definite, so the
        // bordered matrix factorises as LDLᵀ (a Cholesky's fill and work)
        // instead of an LU, whose column ordering and pivoting a row over a
        // whole face (LIAISON_ELEM 3D_POU) ruin: 45 s against ~2 s for the
        // 60,000 unknowns of ssnv166b.
        let augmented_terms: usize = inside.iter().map(|t| t.len() * t.len()).sum();
        let augmented =
            key.symmetric() && !inside.is_empty() && augmented_terms <= AUGMENTED_MAX_TERMS;
        if augmented && std::env::var_os("ASTER_FEM_TIMING").is_some() {
            eprintln!(
                "[fem] augmented Lagrangian of {} relations: {augmented_terms} terms",
                inside.len()
            );
        }
        let (krr, weights) = if augmented {
            augment(&krr, &inside, &red_of)
        } else {
            (krr, Vec::new())
        };
        let mut scale: Vec<f64> = krr
            .diagonal()
            .iter()
            .map(|d| {
                let d = d.abs();
                if d > 0.0 && d.is_finite() {
                    1.0 / d.sqrt()
                } else {
                    1.0
                }
            })
            .collect();
        let nr = krr.n;
        // The bordered matrix of the inside rows, their multipliers scaled
        // by the largest scaled coefficient of their row.
        let m = if inside.is_empty() {
            krr
        } else {
            let mut extra = Vec::new();
            for (q, terms) in inside.iter().enumerate() {
                let mut row_max = 0.0f64;
                for &(i, c) in terms {
                    let j = red_of[i];
                    if j != usize::MAX {
                        extra.push((nr + q, j, c));
                        extra.push((j, nr + q, c));
                        row_max = row_max.max((c * scale[j]).abs());
                    }
                }
                scale.push(if row_max > 0.0 { 1.0 / row_max } else { 1.0 });
            }
            krr.with_extra(nr + inside.len(), extra)
        };
        // On the pattern of the kept symbolic analysis when it fits (a
        // cohesive joint's tangent drops and regains entries from one
        // iteration to the next): the analysis is then reused.
        let m = match self.symbolic.as_ref() {
            Some((cp, ri, _)) => crate::linalg::on_kept_pattern(cp, ri, m),
            None => m,
        };
        let mut values = Vec::with_capacity(m.values.len());
        for j in 0..m.n {
            for p in m.col_ptr[j]..m.col_ptr[j + 1] {
                values.push(m.values[p] * scale[m.row_idx[p]] * scale[j]);
            }
        }
        drop(assembling);
        let _factorising = phase(Phase::Factorisation);
        let nt = m.n;
        let sym = SymbolicSparseColMatRef::new_checked(nt, nt, &m.col_ptr, None, &m.row_idx);
        let mat = SparseColMatRef::new(sym, &values);
        let chol = if key.symmetric() && inside.is_empty() {
            self.cholesky(&m, mat, &full_of, coords)
        } else if augmented {
            self.ldlt(&m, nr, &inside, &red_of, mat)
        } else {
            None
        };
        let factor = match chol {
            Some(f) => f,
            None => RFactor::Lu(Box::new(mat.sp_lu().ok()?)),
        };
        Some(Reduced {
            key,
            penalty,
            pinned,
            inside,
            norm_inf: k.norm_inf(),
            keff,
            red_of,
            full_of,
            weights,
            scale,
            factor,
            columns: HashMap::new(),
        })
    }

    /// Numeric LDLᵀ of the scaled, augmented bordered matrix `m` (its first
    /// `nr` unknowns the reduced ones, then one multiplier per inside row),
    /// in the order of [`augmented_ldlt_order`], reusing the symbolic
    /// analysis when the pattern is unchanged. `None` on a zero pivot
    /// (redundant rows): the caller then takes the LU.
    fn ldlt(
        &mut self,
        m: &Csc,
        nr: usize,
        inside: &[Vec<(usize, f64)>],
        red_of: &[usize],
        mat: SparseColMatRef<'_, usize, f64>,
    ) -> Option<RFactor> {
        use faer::sparse::linalg::cholesky::SymmetricOrdering;
        let same = self
            .symbolic
            .as_ref()
            .is_some_and(|(cp, ri, _)| *cp == m.col_ptr && *ri == m.row_idx);
        if !same {
            let rows: Vec<Vec<usize>> = inside
                .iter()
                .map(|t| {
                    t.iter()
                        .map(|&(i, _)| red_of[i])
                        .filter(|&j| j != usize::MAX)
                        .collect()
                })
                .collect();
            let order = augmented_ldlt_order(m, nr, &rows)?;
            let nt = m.n;
            let mut inv = vec![0usize; nt];
            for (k, &i) in order.iter().enumerate() {
                inv[i] = k;
            }
            let perm = faer::perm::PermRef::new_checked(&order, &inv, nt);
            let symbolic = factorize_symbolic_cholesky(
                mat.symbolic(),
                Side::Lower,
                SymmetricOrdering::Custom(perm),
                symbolic_params(nt),
            )
            .ok()?;
            if std::env::var_os("ASTER_FEM_TIMING").is_some() {
                eprintln!(
                    "[fem] augmented LDLT factor: {} unknowns ({} multipliers), {} non-zeros",
                    nt,
                    nt - nr,
                    symbolic.len_val()
                );
            }
            self.symbolic = Some((m.col_ptr.clone(), m.row_idx.clone(), Arc::new(symbolic)));
        }
        let symbolic = self.symbolic.as_ref()?.2.clone();
        let mut values = vec![0.0; symbolic.len_val()];
        let par = crate::linalg::factor_parallelism(symbolic.len_val());
        let mut mem = faer::dyn_stack::MemBuffer::try_new(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
        )
        .ok()?;
        symbolic
            .factorize_numeric_ldlt(
                &mut values,
                mat,
                Side::Lower,
                Default::default(),
                par,
                faer::dyn_stack::MemStack::new(&mut mem),
                Default::default(),
            )
            .ok()?;
        if values.iter().any(|v| !v.is_finite()) {
            return None;
        }
        Some(RFactor::Ldlt { symbolic, values })
    }

    /// Numeric Cholesky of the scaled reduced matrix, reusing the symbolic
    /// analysis when the pattern is unchanged.
    fn cholesky(
        &mut self,
        krr: &Csc,
        mat: SparseColMatRef<'_, usize, f64>,
        full_of: &[usize],
        coords: Option<&[[f64; 3]]>,
    ) -> Option<RFactor> {
        let same = self
            .symbolic
            .as_ref()
            .is_some_and(|(cp, ri, _)| *cp == krr.col_ptr && *ri == krr.row_idx);
        if !same {
            use faer::sparse::linalg::cholesky::SymmetricOrdering;
            let nr = krr.n;
            let order: Option<Vec<usize>> = coords.filter(|_| nr >= ND_THRESHOLD).map(|c| {
                let rc: Vec<[f64; 3]> = full_of.iter().map(|&i| c[i]).collect();
                crate::ordering::nested_dissection(krr, &rc)
            });
            let symbolic = match &order {
                Some(order) => {
                    let mut inv = vec![0usize; nr];
                    for (k, &i) in order.iter().enumerate() {
                        inv[i] = k;
                    }
                    let perm = faer::perm::PermRef::new_checked(order, &inv, nr);
                    factorize_symbolic_cholesky(
                        mat.symbolic(),
                        Side::Lower,
                        SymmetricOrdering::Custom(perm),
                        symbolic_params(nr),
                    )
                }
                None => factorize_symbolic_cholesky(
                    mat.symbolic(),
                    Side::Lower,
                    SymmetricOrdering::Amd,
                    symbolic_params(nr),
                ),
            }
            .ok()?;
            if std::env::var_os("ASTER_FEM_TIMING").is_some() {
                eprintln!(
                    "[fem] reduced Cholesky factor ({}): {} unknowns, {} non-zeros",
                    if order.is_some() {
                        "nested dissection"
                    } else {
                        "AMD"
                    },
                    nr,
                    symbolic.len_val()
                );
            }
            self.symbolic = Some((krr.col_ptr.clone(), krr.row_idx.clone(), Arc::new(symbolic)));
        }
        let symbolic = self.symbolic.as_ref()?.2.clone();
        let mut values = vec![0.0; symbolic.len_val()];
        crate::linalg::numeric_llt(
            &symbolic,
            mat,
            &mut values,
            crate::linalg::factor_parallelism(symbolic.len_val()),
        )?;
        Some(RFactor::Llt { symbolic, values })
    }
}

/// From this many unknowns the Cholesky and LDLᵀ factors are supernodal
/// whatever faer's flop heuristic says: on a 2D mesh (ssnv110e, 24,915
/// unknowns, ~40 entries per column of L) the heuristic picks the
/// simplicial factorisation, 56 ms per numeric LDLᵀ against 39 ms
/// supernodal (the same symbolic work in both).
const SUPERNODAL_MIN: usize = 10_000;

/// faer's symbolic Cholesky parameters for a matrix of `n` unknowns.
fn symbolic_params(n: usize) -> faer::sparse::linalg::cholesky::CholeskySymbolicParams<'static> {
    use faer::sparse::linalg::SupernodalThreshold;
    faer::sparse::linalg::cholesky::CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: if n >= SUPERNODAL_MIN {
            SupernodalThreshold::FORCE_SUPERNODAL
        } else {
            SupernodalThreshold::AUTO
        },
        ..Default::default()
    }
}

/// K_rr + Σ wᵣ aᵣaᵣᵀ over the inside rows (terms on reduced unknowns),
/// with the weights wᵣ. At the solution every row holds (aᵣ·u = dᵣ), so
/// the bordered system [K_rr + AᵀWA, Aᵀ; A, 0] [u; λ] = [b + AᵀWd; d] has
/// the same solution as [K_rr, Aᵀ; A, 0] [u; λ] = [b; d], exactly; but its
/// leading block is positive definite when the rows hold the model
/// (K_rr alone is singular then). wᵣ = k̄ᵣ/‖aᵣ‖², k̄ᵣ the largest diagonal
/// stiffness on the row's unknowns (else the largest of K_rr): the added
/// terms are of the stiffness's own size.
fn augment(krr: &Csc, inside: &[Vec<(usize, f64)>], red_of: &[usize]) -> (Csc, Vec<f64>) {
    let diag = krr.diagonal();
    let k_max = diag.iter().fold(0.0f64, |a, d| a.max(d.abs()));
    let mut extra = Vec::new();
    let mut weights = Vec::with_capacity(inside.len());
    for terms in inside {
        let t: Vec<(usize, f64)> = terms
            .iter()
            .filter(|(i, _)| red_of[*i] != usize::MAX)
            .map(|&(i, c)| (red_of[i], c))
            .collect();
        let norm2: f64 = t.iter().map(|(_, c)| c * c).sum();
        let k_row = t.iter().fold(0.0f64, |a, &(j, _)| a.max(diag[j].abs()));
        let k_bar = if k_row > 0.0 { k_row } else { k_max };
        let w = if norm2 > 0.0 && k_bar > 0.0 && (k_bar / norm2).is_finite() {
            k_bar / norm2
        } else {
            0.0
        };
        weights.push(w);
        if w == 0.0 {
            continue;
        }
        for &(i, ci) in &t {
            for &(j, cj) in &t {
                extra.push((i, j, w * ci * cj));
            }
        }
    }
    (krr.with_extra(krr.n, extra), weights)
}

/// The elimination order of the augmented bordered matrix `m` (`nr`
/// reduced unknowns, then one multiplier per row of `rows`, given by its
/// reduced unknowns): AMD on the leading block K̃ (the geometric nested
/// dissection, which the rows' couplings cross, gave ssnv166b a factor of
/// 242 M non-zeros against AMD's 123 M), each multiplier placed right after its row's anchor: the
/// first of the row's *private* unknowns (on no other row) when it has
/// one, else the last of its unknowns. Every leading block of the permuted
/// matrix is then [K̃_PP, A_QPᵀ; A_QP, 0] with K̃ positive definite and
/// A_QP of full row rank (a row anchored at a private unknown is the only
/// one with a coefficient in that column; the others are whole, and
/// independent while the rows are), so every pivot is non-zero: LDLᵀ
/// needs no pivoting. The multiplier's column of the factor is about its
/// anchor's: anchoring at the last unknown (often in a top separator)
/// doubled ssnv166b's factor (192 M non-zeros against 98 M for K̃ alone),
/// the slave DOF of a LIAISON_MAIL row is eliminated early. The
/// elimination tree's postorder keeps these positions (a multiplier is an
/// ancestor of every unknown of its row ordered before it). `None` when a
/// row has no reduced unknown (its multiplier would be a zero pivot).
fn augmented_ldlt_order(m: &Csc, nr: usize, rows: &[Vec<usize>]) -> Option<Vec<usize>> {
    use faer::sparse::linalg::cholesky::SymmetricOrdering;
    // The leading block's pattern.
    let mut col_ptr = Vec::with_capacity(nr + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for j in 0..nr {
        for p in m.col_ptr[j]..m.col_ptr[j + 1] {
            if m.row_idx[p] < nr {
                row_idx.push(m.row_idx[p]);
            }
        }
        col_ptr.push(row_idx.len());
    }
    let sym = SymbolicSparseColMatRef::new_checked(nr, nr, &col_ptr, None, &row_idx);
    let symbolic =
        factorize_symbolic_cholesky(sym, Side::Lower, SymmetricOrdering::Amd, Default::default())
            .ok()?;
    let order: Vec<usize> = match symbolic.perm() {
        Some(p) => p.arrays().0.to_vec(),
        None => (0..nr).collect(),
    };
    let mut pos = vec![0usize; nr];
    for (k, &i) in order.iter().enumerate() {
        pos[i] = k;
    }
    // Each multiplier right after its row's anchor: the first of its
    // private unknowns (on no other row: the slave DOF of a LIAISON_MAIL
    // row) when it has one, else the last of its unknowns.
    let mut rows_on = vec![0u32; nr];
    for r in rows {
        for &j in r {
            rows_on[j] = rows_on[j].saturating_add(1);
        }
    }
    let mut after: Vec<Vec<usize>> = vec![Vec::new(); nr];
    for (q, r) in rows.iter().enumerate() {
        let private = r
            .iter()
            .filter(|&&j| rows_on[j] == 1)
            .map(|&j| pos[j])
            .min();
        let anchor = match private {
            Some(p) => p,
            None => r.iter().map(|&j| pos[j]).max()?,
        };
        after[anchor].push(nr + q);
    }
    let mut full = Vec::with_capacity(m.n);
    for (k, &i) in order.iter().enumerate() {
        full.push(i);
        full.extend_from_slice(&after[k]);
    }
    (full.len() == m.n).then_some(full)
}

enum SFactor {
    Chol(nalgebra::linalg::Cholesky<f64, nalgebra::Dyn>),
    Lu(nalgebra::linalg::FullPivLU<f64, nalgebra::Dyn, nalgebra::Dyn>),
}

impl SFactor {
    fn solve(&self, r: &nalgebra::DVector<f64>) -> Option<nalgebra::DVector<f64>> {
        match self {
            SFactor::Chol(c) => Some(c.solve(r)),
            SFactor::Lu(l) => l.solve(r),
        }
    }
}

impl Reduced {
    /// K_rr⁻¹ applied in place to the columns of `rhs` (reduced indexing).
    fn solve_many(&self, rhs: &mut Mat<f64>) {
        let (nr, nc) = (rhs.nrows(), rhs.ncols());
        for j in 0..nc {
            for i in 0..nr {
                rhs[(i, j)] *= self.scale[i];
            }
        }
        match &self.factor {
            RFactor::Llt { symbolic, values } => {
                let par = crate::linalg::factor_parallelism(values.len());
                let mut mem = faer::dyn_stack::MemBuffer::new(
                    symbolic.solve_in_place_scratch::<f64>(nc, par),
                );
                faer::sparse::linalg::cholesky::LltRef::new(symbolic, values)
                    .solve_in_place_with_conj(
                        faer::Conj::No,
                        rhs.as_mut(),
                        par,
                        faer::dyn_stack::MemStack::new(&mut mem),
                    );
            }
            RFactor::Ldlt { symbolic, values } => {
                let par = crate::linalg::factor_parallelism(values.len());
                let mut mem = faer::dyn_stack::MemBuffer::new(
                    symbolic.solve_in_place_scratch::<f64>(nc, par),
                );
                faer::sparse::linalg::cholesky::LdltRef::new(symbolic, values)
                    .solve_in_place_with_conj(
                        faer::Conj::No,
                        rhs.as_mut(),
                        par,
                        faer::dyn_stack::MemStack::new(&mut mem),
                    );
            }
            RFactor::Lu(lu) => {
                use faer::linalg::solvers::Solve;
                lu.solve_in_place(rhs.as_mut());
            }
        }
        for j in 0..nc {
            for i in 0..nr {
                rhs[(i, j)] *= self.scale[i];
            }
        }
    }
}

struct SolveCtx<'a> {
    red: &'a Reduced,
    keff: &'a Csc,
    rows: &'a [Row<'a>],
    pinned_rows: &'a [(usize, usize, f64)],
    general: &'a [usize],
    reduced_terms: &'a [Vec<(usize, f64)>],
    /// Positions in `general` of the rows solved through S, and of the
    /// rows factorised with K_rr (in the factor's order).
    outside: &'a [usize],
    inside_pos: &'a [usize],
    /// M⁻¹ [aᵣ; 0] of the `outside` rows, in their order.
    cols: &'a [&'a [f64]],
    s_factor: Option<&'a SFactor>,
}

impl SolveCtx<'_> {
    /// [Δu, λ] for right-hand sides (b, d), exactly (up to round-off).
    fn apply(&self, b: &[f64], d: &[f64]) -> Vec<f64> {
        let red = self.red;
        let n = b.len();
        let nr = red.full_of.len();
        let nt = red.scale.len();
        let mut du = vec![0.0; n];
        for &(r, i, c) in self.pinned_rows {
            du[i] = d[r] / c;
        }
        // A general row's right-hand side once its pinned terms moved there.
        let rhs_of = |k: usize, du: &[f64]| -> f64 {
            let r = self.general[k];
            let pinned_part: f64 = self.rows[r]
                .terms
                .iter()
                .filter(|(i, _)| red.red_of[*i] == usize::MAX)
                .map(|&(i, c)| c * du[i])
                .sum();
            d[r] - pinned_part
        };
        // Right-hand side of the reduced unknowns: b − K_rp Δu_p; then the
        // factorised rows' own.
        let kp = self.keff.mul(&du);
        let mut y = Mat::<f64>::zeros(nt, 1);
        for (j, &i) in red.full_of.iter().enumerate() {
            y[(j, 0)] = b[i] - kp[i];
        }
        for (q, &k) in self.inside_pos.iter().enumerate() {
            let dr = rhs_of(k, &du);
            y[(nr + q, 0)] = dr;
            // The augmented Lagrangian's Σ wᵣ aᵣ dᵣ.
            if let Some(&w) = red.weights.get(q) {
                for &(j, c) in &self.reduced_terms[k] {
                    y[(j, 0)] += w * c * dr;
                }
            }
        }
        red.solve_many(&mut y);
        let mut lam_general = vec![0.0; self.general.len()];
        if let Some(sf) = self.s_factor {
            let rhs = nalgebra::DVector::from_iterator(
                self.outside.len(),
                self.outside.iter().map(|&k| {
                    let ay: f64 = self.reduced_terms[k]
                        .iter()
                        .map(|&(j, c)| c * y[(j, 0)])
                        .sum();
                    ay - rhs_of(k, &du)
                }),
            );
            if let Some(l) = sf.solve(&rhs) {
                for (&k, &v) in self.outside.iter().zip(l.iter()) {
                    lam_general[k] = v;
                }
            }
        }
        let mut z: Vec<f64> = (0..nt).map(|j| y[(j, 0)]).collect();
        for (w, &k) in self.cols.iter().zip(self.outside) {
            let l = lam_general[k];
            for (v, wj) in z.iter_mut().zip(w.iter()) {
                *v -= wj * l;
            }
        }
        for (q, &k) in self.inside_pos.iter().enumerate() {
            lam_general[k] = z[nr + q];
        }
        for (j, &i) in red.full_of.iter().enumerate() {
            du[i] = z[j];
        }
        // A row on one free unknown holds exactly (a support or a contact
        // row on a rigid master reads 0, not 1e-32): its value is set from
        // the row, which moves it by round-off only.
        for &k in self.outside {
            if let [(j, c)] = self.reduced_terms[k].as_slice() {
                du[red.full_of[*j]] = rhs_of(k, &du) / c;
            }
        }
        let mut x = du;
        let mut lam = vec![0.0; self.rows.len()];
        for (k, &r) in self.general.iter().enumerate() {
            lam[r] = lam_general[k];
        }
        // Pinned rows: λ is what their DOF's equilibrium lacks.
        if !self.pinned_rows.is_empty() {
            let kdu = self.keff.mul(&x);
            let mut others = vec![0.0; n];
            for (k, &r) in self.general.iter().enumerate() {
                for &(i, c) in self.rows[r].terms {
                    others[i] += c * lam_general[k];
                }
            }
            for &(r, i, c) in self.pinned_rows {
                lam[r] = (b[i] - kdu[i] - others[i]) / c;
            }
        }
        x.extend(lam);
        x
    }
}

/// The rounding error of p = a·b (Dekker's product with Veltkamp's split):
/// exact unless a·b over- or underflows. Inline arithmetic: without a
/// hardware FMA in the target, `mul_add` is a library call that cost more
/// than the rest of the residual.
#[inline]
fn product_error(a: f64, b: f64, p: f64) -> f64 {
    const SPLIT: f64 = 134_217_729.0; // 2^27 + 1
    let t = SPLIT * a;
    let ah = t - (t - a);
    let al = a - ah;
    let t = SPLIT * b;
    let bh = t - (t - b);
    let bl = b - bh;
    ((ah * bh - p) + ah * bl + al * bh) + al * bl
}

/// A sum carried with its rounding error (Ogita, Rump & Oishi's Dot2):
/// the result is as accurate as if computed in twice the working precision,
/// then rounded.
#[derive(Clone, Copy, Default)]
struct Compensated {
    sum: f64,
    err: f64,
}

impl Compensated {
    fn new(v: f64) -> Self {
        Compensated { sum: v, err: 0.0 }
    }

    /// Adds a·b.
    #[inline]
    fn add_product(&mut self, a: f64, b: f64) {
        let p = a * b;
        let ep = product_error(a, b, p);
        let s = self.sum + p;
        let bb = s - self.sum;
        let es = (self.sum - (s - bb)) + (p - bb);
        self.sum = s;
        self.err += ep + es;
    }

    fn value(self) -> f64 {
        self.sum + self.err
    }
}

/// Residuals (b − K Δu − Aᵀλ, d − A Δu) of the bordered system at x,
/// with compensated sums: a residual that is a small difference of large
/// terms (a stiff body on a soft support) is then exact enough for the
/// refinement to converge in the soft modes too.
fn residual(k: &Csc, rows: &[Row], b: &[f64], d: &[f64], x: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = k.n;
    let (du, lam) = x.split_at(n);
    let mut ru: Vec<Compensated> = b.iter().map(|&v| Compensated::new(v)).collect();
    for j in 0..n {
        let xj = du[j];
        if xj == 0.0 {
            continue;
        }
        for p in k.col_ptr[j]..k.col_ptr[j + 1] {
            ru[k.row_idx[p]].add_product(-k.values[p], xj);
        }
    }
    let mut rd: Vec<Compensated> = d.iter().map(|&v| Compensated::new(v)).collect();
    for (r, row) in rows.iter().enumerate() {
        for &(i, c) in row.terms {
            ru[i].add_product(-c, lam[r]);
            rd[r].add_product(-c, du[i]);
        }
    }
    (
        ru.into_iter().map(Compensated::value).collect(),
        rd.into_iter().map(Compensated::value).collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::linalg::dense_to_csc;

    /// Rows over `data` (terms, right-hand side), all equalities or all
    /// inequalities.
    fn rows_of(data: &[(Vec<(usize, f64)>, f64)], equality: bool) -> Vec<Row<'_>> {
        data.iter()
            .map(|(t, d)| Row {
                terms: t,
                d: *d,
                equality,
            })
            .collect()
    }

    /// A chain of 4 springs (stiffness 1, 2, 3, 4) between 5 points.
    fn chain() -> Csc {
        let k = [1.0, 2.0, 3.0, 4.0];
        let mut a = vec![vec![0.0; 5]; 5];
        for (e, ke) in k.iter().enumerate() {
            a[e][e] += ke;
            a[e + 1][e + 1] += ke;
            a[e][e + 1] -= ke;
            a[e + 1][e] -= ke;
        }
        dense_to_csc(&a)
    }

    fn bordered(k: &Csc, rows: &[(Vec<(usize, f64)>, f64)], b: &[f64]) -> Vec<f64> {
        let n = k.n;
        let mut extra = Vec::new();
        for (r, (t, _)) in rows.iter().enumerate() {
            for &(i, c) in t {
                extra.push((n + r, i, c));
                extra.push((i, n + r, c));
            }
        }
        let a = k.with_extra(n + rows.len(), extra);
        let mut rhs = b.to_vec();
        rhs.extend(rows.iter().map(|r| r.1));
        crate::linalg::solve(&a, &rhs, n, false)
            .expect("bordered")
            .x
    }

    #[test]
    fn matches_the_bordered_lu_with_pinned_and_general_rows() {
        let k = chain();
        // Point 0 pinned at 0.1, points 2 and 4 tied (u2 − u4 = 0.05), a
        // unilateral-like row on 3 and 4 (u3 + 2 u4 = 0.3).
        let rows_data = vec![
            (vec![(0, 2.0)], 0.2),
            (vec![(2, 1.0), (4, -1.0)], 0.05),
            (vec![(3, 1.0), (4, 2.0)], 0.3),
        ];
        let b = vec![0.0, 1.0, -0.5, 0.25, 2.0];
        let rows: Vec<Row> = rows_data
            .iter()
            .enumerate()
            .map(|(r, (t, d))| Row {
                terms: t,
                d: *d,
                equality: r < 2,
            })
            .collect();
        let mut s = KktSolver::default();
        let x = s
            .solve(MatrixKey::Elastic, &k, &[], &rows, &b, None, &|_, _| true)
            .expect("no failure")
            .expect("applies")
            .x;
        let reference = bordered(&k, &rows_data, &b);
        for (a, r) in x.iter().zip(&reference) {
            assert!(
                (a - r).abs() < 1e-12 * r.abs().max(1.0),
                "{x:?} vs {reference:?}"
            );
        }
        // Same matrix: the factor and the row columns are reused.
        let again = s
            .solve(MatrixKey::Elastic, &k, &[], &rows, &b, None, &|_, _| true)
            .expect("no failure")
            .expect("applies")
            .x;
        assert_eq!(s.factorisations, 1);
        assert_eq!(x, again);
    }

    #[test]
    fn relations_holding_the_model_are_factorised_with_k() {
        // Two chains, points 0–4 and 5–9, nothing pinned: the first held
        // by u0 + u5 = 0.1 and u0 − u5 = 0 (multi-DOF relations, as a body
        // hung on LIAISON_ELEM), the second tied to it by u4 − 2 u9 = 0;
        // an inequality row (solved through S) on points 3 and 7, its
        // active set changing while the factor stays.
        let c = chain();
        let mut a = vec![vec![0.0; 10]; 10];
        for j in 0..5 {
            for p in c.col_ptr[j]..c.col_ptr[j + 1] {
                let i = c.row_idx[p];
                a[i][j] = c.values[p];
                a[i + 5][j + 5] = c.values[p];
            }
        }
        let k = dense_to_csc(&a);
        let equalities = vec![
            (vec![(0, 1.0), (5, 1.0)], 0.1),
            (vec![(0, 1.0), (5, -1.0)], 0.0),
            (vec![(4, 1.0), (9, -2.0)], 0.0),
        ];
        let contact = (vec![(3, 1.0), (7, -1.0)], 0.02);
        let b = vec![0.0, 1.0, -0.5, 0.25, 2.0, 0.5, 0.0, -1.0, 0.0, 0.75];
        let mut s = KktSolver::default();
        let held_calls = std::cell::Cell::new(0);
        // The pins (none) do not hold the model; pins and relations do.
        let held = |_: &[usize], relations: &Relations| {
            held_calls.set(held_calls.get() + 1);
            !relations.is_empty()
        };
        for with_contact in [false, true, false] {
            let mut data = equalities.clone();
            if with_contact {
                data.push(contact.clone());
            }
            let rows: Vec<Row> = data
                .iter()
                .enumerate()
                .map(|(r, (t, d))| Row {
                    terms: t,
                    d: *d,
                    equality: r < 3,
                })
                .collect();
            let x = s
                .solve(MatrixKey::Elastic, &k, &[], &rows, &b, None, &held)
                .expect("no failure")
                .expect("applies")
                .x;
            let reference = bordered(&k, &data, &b);
            for (a, r) in x.iter().zip(&reference) {
                assert!(
                    (a - r).abs() < 1e-12 * r.abs().max(1.0),
                    "{x:?} vs {reference:?}"
                );
            }
        }
        // One factorisation for the three active sets; the hold asked once
        // without and once with the relations.
        assert_eq!(s.factorisations, 1);
        assert_eq!(held_calls.get(), 2);
    }

    #[test]
    fn penalty_terms_enter_the_factorised_matrix() {
        let k = chain();
        let rows_data = [(vec![(0, 1.0)], 0.0)];
        let rows = rows_of(&rows_data, true);
        let b = vec![0.0, 0.0, 0.0, 0.0, 1.0];
        let penalty = vec![(4, 4, 100.0)];
        let mut s = KktSolver::default();
        let x = s
            .solve(
                MatrixKey::Elastic,
                &k,
                &penalty,
                &rows,
                &b,
                None,
                &|_, _| true,
            )
            .expect("no failure")
            .expect("applies")
            .x;
        let kp = k.with_extra(5, penalty.clone());
        let reference = bordered(&kp, &[(vec![(0, 1.0)], 0.0)], &b);
        for (a, r) in x.iter().zip(&reference) {
            assert!(
                (a - r).abs() < 1e-12 * r.abs().max(1.0),
                "{x:?} vs {reference:?}"
            );
        }
    }

    /// A body held only through a dense row (a beam node tied to a whole
    /// face, LIAISON_ELEM 3D_POU) and a second body tied to it node by
    /// node (LIAISON_MAIL rows, each with its own slave DOF), solved by the
    /// augmented LDLᵀ, against a dense LU of the bordered system; over
    /// pseudo-random stiffnesses, weights and loads.
    #[test]
    fn dense_rows_through_the_augmented_ldlt_match_the_direct_solve() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..8 {
            // Unknowns: body A 0..na (a chain), the beam node's two DOFs
            // na (translation) and na + 1 (rotation, no stiffness), body B
            // na + 2 .. na + 2 + nb (a chain).
            let (na, nb) = (24 + 3 * case, 6 + case);
            let n = na + 2 + nb;
            let mut a = vec![vec![0.0; n]; n];
            let spring = |a: &mut Vec<Vec<f64>>, i: usize, j: usize, k: f64| {
                a[i][i] += k;
                a[j][j] += k;
                a[i][j] -= k;
                a[j][i] -= k;
            };
            for e in 0..na - 1 {
                spring(&mut a, e, e + 1, 1e3 * (1.0 + next()));
            }
            for e in 0..nb - 1 {
                spring(&mut a, na + 2 + e, na + 3 + e, 10.0 * (1.0 + next()));
            }
            // The beam node's translation has a (soft) stiffness of its own.
            a[na][na] += 1.0 + next();
            let k = dense_to_csc(&a);
            let mut data: Vec<(Vec<(usize, f64)>, f64)> = Vec::new();
            // The beam node pinned (DDL_IMPO).
            data.push((vec![(na, 1.0)], 0.0));
            // Mean of body A = the beam node; first moment = its rotation.
            let w: Vec<f64> = (0..na).map(|_| 0.5 + next()).collect();
            let total: f64 = w.iter().sum();
            let mut mean: Vec<(usize, f64)> = (0..na).map(|i| (i, -w[i] / total)).collect();
            mean.push((na, 1.0));
            data.push((mean, 0.0));
            let xc: Vec<f64> = (0..na).map(|i| i as f64 - 0.5 * na as f64).collect();
            let mut moment: Vec<(usize, f64)> = (0..na).map(|i| (i, w[i] * xc[i])).collect();
            let inertia: f64 = (0..na).map(|i| w[i] * xc[i] * xc[i]).sum();
            moment.push((na + 1, -inertia));
            data.push((moment, 0.01 * next()));
            // Body B's nodes on body A's "elements" (slave DOF first).
            for j in 0..nb {
                let e = (j * 3 + case) % (na - 1);
                let xi = next();
                data.push((vec![(na + 2 + j, 1.0), (e, -(1.0 - xi)), (e + 1, -xi)], 0.0));
            }
            let b: Vec<f64> = (0..n).map(|_| next() - 0.5).collect();
            let rows = rows_of(&data, true);
            let mut s = KktSolver::default();
            let x = s
                .solve(MatrixKey::Elastic, &k, &[], &rows, &b, None, &|_, r| {
                    !r.is_empty()
                })
                .expect("no failure")
                .expect("applies")
                .x;
            assert!(
                matches!(
                    s.reduced.as_ref().map(|r| &r.factor),
                    Some(RFactor::Ldlt { .. })
                ),
                "case {case}: the augmented LDLᵀ is used"
            );
            // Dense LU of the bordered system.
            let m = data.len();
            let mut full = DMatrix::<f64>::zeros(n + m, n + m);
            for i in 0..n {
                for j in 0..n {
                    full[(i, j)] = a[i][j];
                }
            }
            for (r, (t, _)) in data.iter().enumerate() {
                for &(i, c) in t {
                    full[(n + r, i)] += c;
                    full[(i, n + r)] += c;
                }
            }
            let rhs = nalgebra::DVector::from_iterator(
                n + m,
                b.iter().copied().chain(data.iter().map(|r| r.1)),
            );
            let reference = full.full_piv_lu().solve(&rhs).expect("regular");
            let (u_max, l_max) = (reference.rows(0, n).amax(), reference.rows(n, m).amax());
            for (i, (v, r)) in x.iter().zip(reference.iter()).enumerate() {
                let scale = if i < n { u_max } else { l_max };
                assert!(
                    (v - r).abs() <= 1e-12 * scale,
                    "case {case}, unknown {i}: {v} against {r}"
                );
            }
        }
    }

    #[test]
    fn an_unheld_reduced_matrix_or_redundant_rows_fall_back() {
        let k = chain();
        let b = vec![0.0; 5];
        let free = [(vec![(2usize, 1.0)], 0.0)];
        let rows = rows_of(&free, false);
        let mut s = KktSolver::default();
        // Nothing pinned: the chain floats, the caller's check says so.
        assert!(s
            .solve(MatrixKey::Elastic, &k, &[], &rows, &b, None, &|p, _| !p
                .is_empty())
            .expect("no failure")
            .is_none());
        // Two equality rows on one DOF.
        let twice = [(vec![(0usize, 1.0)], 0.0), (vec![(0usize, 2.0)], 0.0)];
        let rows = rows_of(&twice, true);
        assert!(s
            .solve(MatrixKey::Elastic, &k, &[], &rows, &b, None, &|_, _| true)
            .expect("no failure")
            .is_none());
    }
}

#[cfg(test)]
mod compensated_tests {
    use super::*;

    #[test]
    fn products_and_sums_keep_their_rounding_errors() {
        // 0.1·3 is not 0.3 in binary: the product's error is recovered.
        let (a, b) = (0.1f64, 3.0f64);
        let p = a * b;
        assert_eq!(product_error(a, b, p), a.mul_add(b, -p));
        // 1e16 + 1 − 1e16 cancels in plain arithmetic, not here.
        let mut s = Compensated::new(1e16);
        s.add_product(1.0, 1.0);
        s.add_product(-1e16, 1.0);
        assert_eq!(s.value(), 1.0);
    }
}
