//! Cholesky factorisation split at the top separator of a nested dissection,
//! so that both halves are factorised at the same time on two cores.
//!
//! faer's supernodal factorisation walks the supernodes one after the other
//! and only parallelises inside dense blocks, which are small for most of a
//! 2D mesh: on two cores it ran at ~1.3 cores. Here the permuted matrix is
//!
//! ```text
//!     [ A₁₁   0    A₁ₛ ]
//! K = [  0   A₂₂   A₂ₛ ]      (halves 1, 2 uncoupled; s the separator)
//!     [ Aₛ₁  Aₛ₂   Aₛₛ ]
//! ```
//!
//! and each half is factorised with the separator as its last block:
//! Bᵢ = [Aᵢᵢ Aᵢₛ; Aₛᵢ Aₛₛ] = Fᵢ Fᵢᵀ with Fᵢ = [Lᵢᵢ 0; Lₛᵢ Mᵢ]. Bᵢ is positive
//! definite whenever K is (its Schur complement Aₛₛ − Wᵢ dominates
//! K's Aₛₛ − W₁ − W₂). Then K = L Lᵀ with
//!
//! ```text
//!     [ L₁₁   0    0  ]
//! L = [  0   L₂₂   0  ]      Lₛₛ Lₛₛᵀ = M₁M₁ᵀ + M₂M₂ᵀ − Aₛₛ  (dense)
//!     [ Lₛ₁  Lₛ₂  Lₛₛ ]
//! ```
//!
//! The solve uses each Fᵢ's forward and backward substitutions: forward on
//! [bᵢ; 0] gives [yᵢ; zᵢ] with Lₛᵢ yᵢ = −Mᵢ zᵢ; backward on [yᵢ; Mᵢᵀ xₛ]
//! gives [Lᵢᵢ⁻ᵀ(yᵢ − Lₛᵢᵀ xₛ); xₛ]. The extra work against one factorisation
//! is the separator's dense blocks (factorised in both halves, then the
//! Schur complement): a few percent of the flops on a 2D mesh.

use crate::linalg::Csc;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, Par, Side};

/// One half with the separator as its last block, factorised.
struct Half {
    /// Permuted indices of the half's own unknowns: `first..first + len`.
    first: usize,
    len: usize,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// Mᵢ: the separator block of the factor, dense lower triangular.
    m: Mat<f64>,
}

impl Half {
    fn supernode_count(&self) -> usize {
        self.supernodal()
            .map_or(0, |llt| llt.symbolic().n_supernodes())
    }

    /// Multiply–adds of the factorisation (Σ over columns of the squared
    /// column count), for timing diagnostics.
    fn flops(&self) -> f64 {
        let Some(llt) = self.supernodal() else {
            return 0.0;
        };
        let sn = llt.symbolic();
        (0..sn.n_supernodes())
            .map(|s| {
                let node = llt.supernode(s);
                let (w, m) = (node.val().ncols(), node.val().nrows());
                (0..w).map(|k| ((m - k) as f64).powi(2)).sum::<f64>()
            })
            .sum()
    }

    fn supernodal(&self) -> Option<SupernodalLltRef<'_, usize, f64>> {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => Some(SupernodalLltRef::new(s, &self.values)),
            SymbolicCholeskyRaw::Simplicial(_) => None,
        }
    }
}

/// A Cholesky factor of a symmetric positive definite matrix, in two
/// halves and a dense separator block.
pub(crate) struct SplitLlt {
    /// `order[k]` = original index of the k-th permuted unknown.
    order: Vec<usize>,
    halves: [Half; 2],
    /// Lₛₛ, dense lower triangular.
    lss: Mat<f64>,
}

/// The permuted, scaled matrix restricted to one half and the separator,
/// both triangles, in compressed columns (faer's symbolic analysis reads
/// the upper triangle, its numeric factorisation the lower one).
struct HalfMatrix {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
}

/// Builds Bᵢ: local unknowns `0..len` are permuted `first..first + len`,
/// local `len..len + ns` the separator, permuted `sep_first..`.
fn half_matrix(
    a: &Csc,
    scale: &[f64],
    order: &[usize],
    inverse: &[usize],
    first: usize,
    len: usize,
    sep_first: usize,
) -> HalfMatrix {
    let ns = a.n - sep_first;
    let local = |p: usize| -> Option<usize> {
        if p >= sep_first {
            Some(len + p - sep_first)
        } else if p >= first && p < first + len {
            Some(p - first)
        } else {
            None
        }
    };
    let permuted = |k: usize| {
        if k < len {
            first + k
        } else {
            sep_first + k - len
        }
    };
    let bound: usize = (0..len + ns)
        .map(|k| {
            let j = order[permuted(k)];
            a.col_ptr[j + 1] - a.col_ptr[j]
        })
        .sum();
    let mut col_ptr = Vec::with_capacity(len + ns + 1);
    let mut row_idx = Vec::with_capacity(bound);
    let mut values = Vec::with_capacity(bound);
    col_ptr.push(0);
    let mut column: Vec<(usize, f64)> = Vec::with_capacity(64);
    for k in 0..len + ns {
        let j = order[permuted(k)];
        column.clear();
        for p in a.col_ptr[j]..a.col_ptr[j + 1] {
            let r = a.row_idx[p];
            if let Some(lr) = local(inverse[r]) {
                column.push((lr, a.values[p] * scale[r] * scale[j]));
            }
        }
        column.sort_unstable_by_key(|&(r, _)| r);
        row_idx.extend(column.iter().map(|&(r, _)| r));
        values.extend(column.iter().map(|&(_, v)| v));
        col_ptr.push(row_idx.len());
    }
    HalfMatrix {
        col_ptr,
        row_idx,
        values,
    }
}

/// Factorises one half (sequentially: the two halves run on two threads)
/// and extracts Mᵢ.
fn factorise_half(b: &HalfMatrix, first: usize, len: usize) -> Option<Half> {
    let n = b.col_ptr.len() - 1;
    let pattern = SymbolicSparseColMatRef::new_checked(n, n, &b.col_ptr, None, &b.row_idx);
    // Default supernode relaxation: tighter or looser settings measured no
    // faster on the 1M-DOF grid and only changed the stored zeros.
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    let symbolic =
        factorize_symbolic_cholesky(pattern, Side::Lower, SymmetricOrdering::Identity, params)
            .ok()?;
    let mut values = vec![0.0; symbolic.len_val()];
    let mut mem = MemBuffer::try_new(
        symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
    )
    .ok()?;
    symbolic
        .factorize_numeric_llt(
            &mut values,
            SparseColMatRef::new(pattern, &b.values),
            Side::Lower,
            Default::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .ok()?;
    drop(mem);
    let mut half = Half {
        first,
        len,
        symbolic,
        values,
        m: Mat::zeros(0, 0),
    };
    let ns = n - len;
    let mut m = Mat::<f64>::zeros(ns, ns);
    let llt = half.supernodal()?;
    let sn: &SymbolicSupernodalCholesky<usize> = llt.symbolic();
    for s in 0..sn.n_supernodes() {
        let node = llt.supernode(s);
        let (start, val) = (node.start(), node.val());
        let width = val.ncols();
        if start + width <= len {
            continue;
        }
        for c in start.max(len)..start + width {
            let lc = c - start;
            for r in c..start + width {
                m[(r - len, c - len)] = val[(r - start, lc)];
            }
            for (idx, &r) in node.pattern().iter().enumerate() {
                m[(r - len, c - len)] = val[(width + idx, lc)];
            }
        }
    }
    half.m = m;
    Some(half)
}

/// Mᵢ Mᵢᵀ, lower triangle.
fn gram_lower(m: &Mat<f64>, par: Par) -> Mat<f64> {
    let ns = m.nrows();
    let mut g = Mat::<f64>::zeros(ns, ns);
    triangular::matmul(
        g.as_mut(),
        BlockStructure::TriangularLower,
        Accum::Replace,
        m.as_ref(),
        BlockStructure::TriangularLower,
        m.as_ref().transpose(),
        BlockStructure::TriangularUpper,
        1.0,
        par,
    );
    g
}

/// Whether splitting at a separator of `ns` unknowns (out of `n`) saves
/// time. The separator's dense block is factorised in both halves, then
/// its Gram products and the Schur complement: ≈ ns³ more flops on the
/// critical path, against half of the rest. On 2D meshes the separator is
/// a line, ns² ≈ 2n for a QUAD4 grid (56 GFlop in all against ns³ = 2.8 GFlop
/// at 1M DOFs): a clear gain. On 3D meshes it is a plane (ns² ≈ 3k·n on a
/// k³ hexahedral grid) whose dense factorisation dominates the total, and
/// doing it three times would be slower than one factorisation.
pub(crate) fn split_pays_off(n: usize, ns: usize) -> bool {
    ns > 0 && (ns as f64).powi(2) <= 16.0 * n as f64
}

/// Why [`SplitLlt::factorise`] gave no factor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SplitFailure {
    /// The dissection has no first split (or an empty part): another
    /// Cholesky factorisation may be tried.
    NoSplit,
    /// The matrix is not numerically positive definite (or the factor
    /// could not be allocated): another Cholesky would fail too.
    Failed,
}

impl SplitLlt {
    /// Factorises `a` scaled symmetrically by `scale` (entry (i, j) times
    /// scale[i]·scale[j]) in the order of `dissection`, whose first split
    /// gives the halves.
    pub(crate) fn factorise(
        a: &Csc,
        scale: &[f64],
        dissection: &crate::ordering::Dissection,
    ) -> Result<SplitLlt, SplitFailure> {
        let [n1, n2] = dissection.halves.ok_or(SplitFailure::NoSplit)?;
        let ns = dissection.separator_len();
        if n1 == 0 || n2 == 0 || !split_pays_off(a.n, ns) {
            return Err(SplitFailure::NoSplit);
        }
        Self::factorise_split(a, scale, dissection.order.clone(), n1, n2, ns)
            .ok_or(SplitFailure::Failed)
    }

    fn factorise_split(
        a: &Csc,
        scale: &[f64],
        order: Vec<usize>,
        n1: usize,
        n2: usize,
        ns: usize,
    ) -> Option<SplitLlt> {
        let mut inverse = vec![0usize; order.len()];
        for (k, &i) in order.iter().enumerate() {
            inverse[i] = k;
        }
        let sep_first = n1 + n2;
        let build_and_factorise = |first: usize, len: usize| -> Option<(Half, Mat<f64>)> {
            let b = half_matrix(a, scale, &order, &inverse, first, len, sep_first);
            let half = factorise_half(&b, first, len)?;
            drop(b);
            let g = gram_lower(&half.m, Par::Seq);
            if std::env::var_os("ASTER_FEM_TIMING").is_some() {
                eprintln!(
                    "[fem] half of {len} + {ns} unknowns factorised: {} supernodes, {:.2} GFlop{}",
                    half.supernode_count(),
                    half.flops() * 1e-9,
                    crate::diag::thread_usage()
                );
            }
            Some((half, g))
        };
        let (r1, r2) = crate::parallel::join(
            || build_and_factorise(0, n1),
            || build_and_factorise(n1, n2),
        );
        let ((h1, g1), (h2, g2)) = (r1?, r2?);
        let timing = std::env::var_os("ASTER_FEM_TIMING").is_some();
        let clock = std::time::Instant::now();
        // Lₛₛ Lₛₛᵀ = M₁M₁ᵀ + M₂M₂ᵀ − Aₛₛ (lower triangle).
        let mut s = g1;
        for c in 0..ns {
            for r in c..ns {
                s[(r, c)] += g2[(r, c)];
            }
        }
        drop(g2);
        for c in 0..ns {
            let j = order[sep_first + c];
            for p in a.col_ptr[j]..a.col_ptr[j + 1] {
                let i = a.row_idx[p];
                let r = inverse[i];
                if r >= sep_first + c {
                    s[(r - sep_first, c)] -= a.values[p] * scale[i] * scale[j];
                }
            }
        }
        // One thread: ~1 GFlop for a 1414-unknown separator, and rayon workers
        // stall each other when the machine is shared.
        let par = Par::Seq;
        let mut mem = MemBuffer::try_new(
            faer::linalg::cholesky::llt::factor::cholesky_in_place_scratch::<f64>(
                ns,
                par,
                Default::default(),
            ),
        )
        .ok()?;
        faer::linalg::cholesky::llt::factor::cholesky_in_place(
            s.as_mut(),
            Default::default(),
            par,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .ok()?;
        if timing {
            eprintln!(
                "[fem] separator Schur complement ({ns} unknowns) assembled and factorised in {:.3} s{}",
                clock.elapsed().as_secs_f64(),
                crate::diag::thread_usage()
            );
        }
        Some(SplitLlt {
            order,
            halves: [h1, h2],
            lss: s,
        })
    }

    /// Non-zeros stored in the factor (both halves and Lₛₛ's triangle).
    pub(crate) fn len_val(&self) -> usize {
        let ns = self.lss.nrows();
        self.halves.iter().map(|h| h.values.len()).sum::<usize>() + ns * (ns + 1) / 2
    }

    /// Solves K x = b (K the scaled matrix, b in original numbering).
    pub(crate) fn solve(&self, b: &[f64]) -> Vec<f64> {
        let ns = self.lss.nrows();
        let sep_first = self.order.len() - ns;
        let bp: Vec<f64> = self.order.iter().map(|&i| b[i]).collect();
        // Forward substitution in each half: [bᵢ; 0] → [yᵢ; zᵢ].
        let forward = |h: &Half| -> Mat<f64> {
            let mut y = Mat::<f64>::zeros(h.len + ns, 1);
            for k in 0..h.len {
                y[(k, 0)] = bp[h.first + k];
            }
            if let Some(llt) = h.supernodal() {
                let mut mem =
                    MemBuffer::new(llt.symbolic().solve_in_place_scratch::<f64>(1, Par::Seq));
                llt.l_solve_with_conj(Conj::No, y.as_mut(), Par::Seq, MemStack::new(&mut mem));
            }
            y
        };
        let (y1, y2) =
            crate::parallel::join(|| forward(&self.halves[0]), || forward(&self.halves[1]));
        // tₛ = bₛ − Lₛ₁y₁ − Lₛ₂y₂ = bₛ + M₁z₁ + M₂z₂, then xₛ = Lₛₛ⁻ᵀLₛₛ⁻¹tₛ.
        let mut t = Mat::<f64>::from_fn(ns, 1, |k, _| bp[sep_first + k]);
        for (h, y) in self.halves.iter().zip([&y1, &y2]) {
            let z = y.as_ref().subrows(h.len, ns);
            triangular::matmul(
                t.as_mut(),
                BlockStructure::Rectangular,
                Accum::Add,
                h.m.as_ref(),
                BlockStructure::TriangularLower,
                z,
                BlockStructure::Rectangular,
                1.0,
                Par::Seq,
            );
        }
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            self.lss.as_ref(),
            t.as_mut(),
            Par::Seq,
        );
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(
            self.lss.as_ref().transpose(),
            t.as_mut(),
            Par::Seq,
        );
        let xs = t;
        // Backward substitution: [yᵢ; Mᵢᵀxₛ] → [xᵢ; xₛ].
        let backward = |h: &Half, mut y: Mat<f64>| -> Mat<f64> {
            triangular::matmul(
                y.as_mut().subrows_mut(h.len, ns),
                BlockStructure::Rectangular,
                Accum::Replace,
                h.m.as_ref().transpose(),
                BlockStructure::TriangularUpper,
                xs.as_ref(),
                BlockStructure::Rectangular,
                1.0,
                Par::Seq,
            );
            if let Some(llt) = h.supernodal() {
                let mut mem =
                    MemBuffer::new(llt.symbolic().solve_in_place_scratch::<f64>(1, Par::Seq));
                llt.l_transpose_solve_with_conj(
                    Conj::No,
                    y.as_mut(),
                    Par::Seq,
                    MemStack::new(&mut mem),
                );
            }
            y
        };
        let (x1, x2) = crate::parallel::join(
            || backward(&self.halves[0], y1),
            || backward(&self.halves[1], y2),
        );
        let mut x = vec![0.0; b.len()];
        for (h, xh) in self.halves.iter().zip([&x1, &x2]) {
            for k in 0..h.len {
                x[self.order[h.first + k]] = xh[(k, 0)];
            }
        }
        for k in 0..ns {
            x[self.order[sep_first + k]] = xs[(k, 0)];
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ordering::nested_dissection_split;

    /// A 2D grid Laplacian (9-point, as QUAD4 couplings) plus `shift`·I,
    /// with the nodes' coordinates.
    fn grid(k: usize, shift: f64) -> (Csc, Vec<[f64; 3]>) {
        let id = |i: usize, j: usize| j * k + i;
        let n = k * k;
        let mut cols = vec![Vec::new(); n];
        let mut entries = Vec::new();
        for j in 0..k {
            for i in 0..k {
                for dj in -1i64..=1 {
                    for di in -1i64..=1 {
                        let (ii, jj) = (i as i64 + di, j as i64 + dj);
                        if ii < 0 || jj < 0 || ii >= k as i64 || jj >= k as i64 {
                            continue;
                        }
                        let other = id(ii as usize, jj as usize);
                        let v = if other == id(i, j) { 8.0 + shift } else { -1.0 };
                        cols[id(i, j)].push(other as u32);
                        entries.push((other, id(i, j), v));
                    }
                }
            }
        }
        let mut a = Csc::from_columns(n, cols);
        for (r, c, v) in entries {
            a.add(r, c, v);
        }
        let coords = (0..n)
            .map(|p| [(p % k) as f64, (p / k) as f64 * 1.01, 0.])
            .collect();
        (a, coords)
    }

    #[test]
    fn split_factor_solves_a_grid_problem_to_round_off() {
        let (a, coords) = grid(60, 0.5);
        let dissection = nested_dissection_split(&a, &coords);
        let [n1, n2] = dissection.halves.expect("a 3600-unknown grid splits");
        assert!(n1 > 1000 && n2 > 1000, "balanced halves: {n1} {n2}");
        assert!(dissection.separator_len() >= 60);
        // Scaling by 1/√aᵢᵢ, as the solver does.
        let scale: Vec<f64> = a.diagonal().iter().map(|d| 1. / d.sqrt()).collect();
        let f = SplitLlt::factorise(&a, &scale, &dissection).expect("SPD");
        let b: Vec<f64> = (0..a.n).map(|i| ((i * 37) % 101) as f64 - 50.).collect();
        // f solves the scaled system S A S y = S b; x = S y.
        let sb: Vec<f64> = b.iter().zip(&scale).map(|(v, s)| v * s).collect();
        let y = f.solve(&sb);
        let x: Vec<f64> = y.iter().zip(&scale).map(|(v, s)| v * s).collect();
        let ax = a.mul(&x);
        let err = ax
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        let xmax = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(err <= 1e-12 * (a.norm_inf() * xmax), "residual {err}");
    }

    #[test]
    fn split_only_where_the_separator_is_small() {
        // The 1M-DOF QUAD4 grid: 1,001,112 free unknowns, separator 1,414.
        assert!(split_pays_off(1_001_112, 1_414));
        // A 40³ HEXA8 grid: 3·41³ unknowns, a plane of 3·41² in the middle.
        assert!(!split_pays_off(3 * 41 * 41 * 41, 3 * 41 * 41));
        assert!(!split_pays_off(1000, 0));
    }

    #[test]
    fn indefinite_matrices_are_refused() {
        // Shift −8.5 makes the diagonal negative: not positive definite.
        let (a, coords) = grid(40, -8.5);
        let dissection = nested_dissection_split(&a, &coords);
        assert_eq!(
            SplitLlt::factorise(&a, &vec![1.0; a.n], &dissection).err(),
            Some(SplitFailure::Failed)
        );
    }

    #[test]
    fn an_indefinite_system_hinted_positive_falls_back_to_lu() {
        // 142×142 = 20,164 unknowns (nested dissection range); the shift
        // puts some eigenvalues below zero.
        let (a, coords) = grid(142, -0.3);
        let b: Vec<f64> = (0..a.n).map(|i| ((i * 13) % 7) as f64 - 3.).collect();
        let r = crate::linalg::solve_with(&a, &b, a.n, true, Some(&coords)).expect("solves");
        assert!(!r.cholesky);
        assert!(r.backward_error <= 1e-12, "{}", r.backward_error);
    }

    #[test]
    fn dissection_without_split_is_refused() {
        let (a, coords) = grid(3, 0.5);
        let dissection = nested_dissection_split(&a, &coords);
        assert_eq!(dissection.halves, None);
        assert_eq!(
            SplitLlt::factorise(&a, &vec![1.0; a.n], &dissection).err(),
            Some(SplitFailure::NoSplit)
        );
    }
}
