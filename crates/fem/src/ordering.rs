//! Geometric nested dissection: a fill-reducing ordering for the sparse
//! Cholesky factorisation of large meshes. Unknowns are split recursively
//! at the coordinate median of the longest extent; unknowns of one half
//! coupled to the other form the separator, numbered last. On 2D meshes
//! this gives O(n log n) fill against the approximate minimum degree's
//! larger fronts.

use crate::linalg::Csc;

/// Leaves below this size are kept in their original (node-major) order.
/// Measured on the 1M-DOF QUAD4 grid: 128 → 144.5M factor non-zeros,
/// 32 → 129.6M, 16 → 127.8M, 8 → 125.8M, the dissection itself costing
/// 0.27 s CPU at 128, 0.34 s at 16 and 0.39 s at 8.
const LEAF: usize = 16;

/// Returns `order` with `order[k]` = original index of the k-th unknown.
/// `coords[i]` is the position of unknown i (its node's coordinates).
pub fn nested_dissection(a: &Csc, coords: &[[f64; 3]]) -> Vec<usize> {
    nested_dissection_split(a, coords).order
}

/// A nested dissection ordering with the sizes of its first split.
#[derive(Clone, Debug, PartialEq)]
pub struct Dissection {
    /// `order[k]` = original index of the k-th unknown.
    pub order: Vec<usize>,
    /// The first split, when there is one: `order` is the first half's
    /// `halves[0]` unknowns, then the second half's `halves[1]`, then the
    /// separator's (the rest). The two halves are not coupled to each
    /// other, so they can be factorised independently.
    pub halves: Option<[usize; 2]>,
}

impl Dissection {
    /// Number of separator unknowns of the first split (0 without one).
    pub fn separator_len(&self) -> usize {
        self.halves.map_or(0, |[a, b]| self.order.len() - a - b)
    }
}

/// Above this many unknowns the two halves of the first split are ordered
/// on two threads.
const PARALLEL_MIN: usize = 50_000;

/// [`nested_dissection`], also telling where the first split lies.
pub fn nested_dissection_split(a: &Csc, coords: &[[f64; 3]]) -> Dissection {
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    dissect(a, coords, threads >= 2 && a.n >= PARALLEL_MIN)
}

fn dissect(a: &Csc, coords: &[[f64; 3]], parallel: bool) -> Dissection {
    let n = a.n;
    let mut ids = SetIds {
        set_id: vec![0u32; n],
        next_id: 1,
    };
    let all: Vec<usize> = (0..n).collect();
    let Some(Split { left, rest, sep }) = split(a, coords, &all, &mut ids) else {
        let mut order = all;
        order.sort_unstable();
        return Dissection {
            order,
            halves: None,
        };
    };
    let halves = Some([left.len(), rest.len()]);
    let (mut order, second) = if parallel {
        // Each thread marks sets in its own copy: a set id is only ever
        // compared with ids created after it, on the same thread.
        let mut ids2 = SetIds {
            set_id: ids.set_id.clone(),
            next_id: ids.next_id,
        };
        crate::parallel::join(
            || order_subtree(a, coords, left, &mut ids),
            || order_subtree(a, coords, rest, &mut ids2),
        )
    } else {
        let first = order_subtree(a, coords, left, &mut ids);
        let second = order_subtree(a, coords, rest, &mut ids);
        (first, second)
    };
    order.extend(second);
    order.extend(sep);
    Dissection { order, halves }
}

/// Set labels used to find separators.
struct SetIds {
    /// The latest set each unknown was put in.
    set_id: Vec<u32>,
    next_id: u32,
}

/// One bisection: `left` and `rest` are not coupled; `sep` holds the
/// unknowns of the right side coupled to the left.
struct Split {
    left: Vec<usize>,
    rest: Vec<usize>,
    sep: Vec<usize>,
}

/// Bisects `v` at the median coordinate of one axis, or None when it is a
/// leaf or cannot be split (all on one coordinate). Each axis along which
/// the set has an extent is tried, and the split with the smallest
/// separator kept (ties: the longer extent, tried first). On graded 3D
/// meshes the longest extent is often not the thinnest cut: the
/// refinement towards a contact makes the median plane of one axis cross
/// many more nodes than another's.
fn split(a: &Csc, coords: &[[f64; 3]], v: &[usize], ids: &mut SetIds) -> Option<Split> {
    if v.len() <= LEAF {
        return None;
    }
    let (lo, hi) = aster_mesh::bounding_box(v.iter().map(|&i| coords[i]));
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&x, &y| (hi[y] - lo[y]).total_cmp(&(hi[x] - lo[x])));
    let mut work = v.to_vec();
    let mut best: Option<Split> = None;
    for axis in axes {
        if hi[axis].partial_cmp(&lo[axis]) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        if let Some(s) = split_on(a, coords, &mut work, axis, ids) {
            if best.as_ref().is_none_or(|b| s.sep.len() < b.sep.len()) {
                best = Some(s);
            }
        }
    }
    let best = best?;
    // The kept split's sets are marked last (a later trial may have
    // relabelled its unknowns): its separator gets the newest id.
    let sid = ids.next_id;
    ids.next_id += 1;
    for &i in &best.sep {
        ids.set_id[i] = sid;
    }
    Some(best)
}

/// The split of `v` at the median coordinate along `axis`: left strictly
/// below the median (so that a node's components stay together), the
/// separator the right side's unknowns coupled to the left.
fn split_on(
    a: &Csc,
    coords: &[[f64; 3]],
    v: &mut [usize],
    axis: usize,
    ids: &mut SetIds,
) -> Option<Split> {
    let mid = v.len() / 2;
    v.select_nth_unstable_by(mid, |&x, &y| coords[x][axis].total_cmp(&coords[y][axis]));
    let pivot = coords[v[mid]][axis];
    let (left, right): (Vec<usize>, Vec<usize>) = v.iter().partition(|&&i| coords[i][axis] < pivot);
    if left.is_empty() || right.is_empty() {
        return None;
    }
    let lid = ids.next_id;
    ids.next_id += 1;
    for &i in &left {
        ids.set_id[i] = lid;
    }
    let mut sep = Vec::new();
    let mut rest = Vec::with_capacity(right.len());
    for &j in &right {
        let touches = a.row_idx[a.col_ptr[j]..a.col_ptr[j + 1]]
            .iter()
            .any(|&r| ids.set_id[r] == lid);
        if touches {
            sep.push(j);
        } else {
            rest.push(j);
        }
    }
    Some(Split { left, rest, sep })
}

/// Orders `root` recursively: left half, right half, then separator.
fn order_subtree(a: &Csc, coords: &[[f64; 3]], root: Vec<usize>, ids: &mut SetIds) -> Vec<usize> {
    let mut order = Vec::with_capacity(root.len());
    // Explicit stack of tasks: Split(set) or Emit(set).
    enum Task {
        Split(Vec<usize>),
        Emit(Vec<usize>),
    }
    let mut stack = vec![Task::Split(root)];
    while let Some(task) = stack.pop() {
        match task {
            Task::Emit(v) => order.extend(v),
            Task::Split(mut v) => match split(a, coords, &v, ids) {
                None => {
                    v.sort_unstable();
                    order.extend(v);
                }
                Some(Split { left, rest, sep }) => {
                    // Processed in stack order: left, right, then separator.
                    stack.push(Task::Emit(sep));
                    stack.push(Task::Split(rest));
                    stack.push(Task::Split(left));
                }
            },
        }
    }
    order
}

/// Size of the sparse Cholesky factor L of a symmetric pattern under an
/// ordering, without computing it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FactorSize {
    /// Non-zeros of L, its diagonal included (no supernodal padding).
    pub nnz: usize,
    /// Floating-point operations of the factorisation, Σ_j c_j² with c_j
    /// the non-zeros of column j of L (the usual count, as CHOLMOD's and
    /// METIS's `fl` up to lower-order terms).
    pub flops: f64,
}

/// The exact [`FactorSize`] of `a` (a symmetric pattern, both triangles
/// stored) ordered by `order` (`order[k]` = original index of the k-th
/// pivot). The elimination tree by Liu's algorithm with path compression,
/// then each row's subtree walked once: O(nnz(L)) time, O(n) memory.
/// Returns `None` when `order` is not a permutation of `0..a.n`.
pub fn factor_size(a: &Csc, order: &[usize]) -> Option<FactorSize> {
    const NONE: usize = usize::MAX;
    let n = a.n;
    if order.len() != n {
        return None;
    }
    let mut inv = vec![NONE; n];
    for (k, &i) in order.iter().enumerate() {
        if i >= n || inv[i] != NONE {
            return None;
        }
        inv[i] = k;
    }
    // Elimination tree of the permuted matrix.
    let mut parent = vec![NONE; n];
    let mut ancestor = vec![NONE; n];
    for k in 0..n {
        let j = order[k];
        for &i in &a.row_idx[a.col_ptr[j]..a.col_ptr[j + 1]] {
            let mut r = inv[i];
            if r >= k {
                continue;
            }
            while ancestor[r] != NONE && ancestor[r] != k {
                let next = ancestor[r];
                ancestor[r] = k;
                r = next;
            }
            if ancestor[r] == NONE {
                ancestor[r] = k;
                parent[r] = k;
            }
        }
    }
    // Row k of L is the union of the tree paths from its entries to k.
    let mut count = vec![1usize; n];
    let mut mark = vec![NONE; n];
    for k in 0..n {
        mark[k] = k;
        let j = order[k];
        for &i in &a.row_idx[a.col_ptr[j]..a.col_ptr[j + 1]] {
            let mut r = inv[i];
            while r < k && mark[r] != k {
                count[r] += 1;
                mark[r] = k;
                r = parent[r];
            }
        }
    }
    Some(FactorSize {
        nnz: count.iter().sum(),
        flops: count.iter().map(|&c| (c as f64) * (c as f64)).sum(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordering_is_a_permutation() {
        // A path graph of 1000 unknowns on a line.
        let n = 1000;
        let cols: Vec<Vec<u32>> = (0..n)
            .map(|j| {
                let mut c = vec![j as u32];
                if j > 0 {
                    c.push(j as u32 - 1);
                }
                if j + 1 < n {
                    c.push(j as u32 + 1);
                }
                c
            })
            .collect();
        let a = Csc::from_columns(n, cols);
        let coords: Vec<[f64; 3]> = (0..n).map(|i| [((i * 7919) % n) as f64, 0., 0.]).collect();
        let mut o = nested_dissection(&a, &coords);
        assert_eq!(o.len(), n);
        o.sort_unstable();
        assert!(o.iter().enumerate().all(|(k, &v)| k == v));
    }

    #[test]
    fn two_threads_give_the_sequential_order() {
        let (model, map) = crate::scenes::quad4_grid(40).expect("grid");
        let k = crate::assembly::assemble_stiffness(&model).expect("assembles");
        let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
        let kff = crate::assembly::restrict(&k, &map, nfree);
        let coords = crate::scenes::free_coords(&model, &map);
        let sequential = dissect(&kff, &coords, false);
        let parallel = dissect(&kff, &coords, true);
        assert_eq!(sequential, parallel);
        // The first split (along x, the longer extent once the bottom row
        // is clamped): two halves and one column of 40 free nodes.
        let [n1, n2] = sequential.halves.expect("splits");
        assert_eq!(sequential.separator_len(), 2 * 40);
        assert_eq!(n1 + n2 + 2 * 40, nfree);
        let mut sorted = sequential.order;
        sorted.sort_unstable();
        assert!(sorted.iter().enumerate().all(|(k, &v)| k == v));
    }

    /// Brute-force symbolic elimination: the non-zeros of L column by
    /// column (a dense boolean pattern, for small matrices).
    fn dense_fill(a: &Csc, order: &[usize]) -> (usize, f64) {
        let n = a.n;
        let mut inv = vec![0; n];
        for (k, &i) in order.iter().enumerate() {
            inv[i] = k;
        }
        let mut p = vec![vec![false; n]; n];
        for j in 0..n {
            for &i in &a.row_idx[a.col_ptr[j]..a.col_ptr[j + 1]] {
                p[inv[i]][inv[j]] = true;
            }
        }
        let (mut nnz, mut flops) = (0, 0.0);
        for k in 0..n {
            let below: Vec<usize> = (k + 1..n).filter(|&i| p[i][k]).collect();
            for &i in &below {
                for &j in &below {
                    p[i][j] = true;
                }
            }
            let c = below.len() + 1;
            nnz += c;
            flops += (c * c) as f64;
        }
        (nnz, flops)
    }

    fn grid_kff(n: usize) -> (Csc, Vec<[f64; 3]>) {
        let (model, map) = crate::scenes::hexa8_grid(n).expect("grid");
        let k = crate::assembly::assemble_stiffness(&model).expect("assembles");
        let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
        (
            crate::assembly::restrict(&k, &map, nfree),
            crate::scenes::free_coords(&model, &map),
        )
    }

    #[test]
    fn factor_size_counts_the_fill_exactly() {
        // A path in its natural order: no fill; the star with its centre
        // first: a full factor; centre last: none.
        let path = |n: usize| {
            Csc::from_columns(
                n,
                (0..n)
                    .map(|j| {
                        let mut c = vec![j as u32];
                        if j > 0 {
                            c.push(j as u32 - 1);
                        }
                        if j + 1 < n {
                            c.push(j as u32 + 1);
                        }
                        c
                    })
                    .collect(),
            )
        };
        let id: Vec<usize> = (0..10).collect();
        let s = factor_size(&path(10), &id).expect("permutation");
        assert_eq!(s.nnz, 19);
        assert_eq!(s.flops, 9.0 * 4.0 + 1.0);
        let star = Csc::from_columns(
            8,
            (0..8u32)
                .map(|j| if j == 0 { (0..8).collect() } else { vec![0, j] })
                .collect(),
        );
        assert_eq!(factor_size(&star, &id[..8]).map(|s| s.nnz), Some(36));
        let last: Vec<usize> = (1..8).chain([0]).collect();
        assert_eq!(factor_size(&star, &last).map(|s| s.nnz), Some(15));
        assert_eq!(factor_size(&star, &[0, 1, 2]), None);
        assert_eq!(factor_size(&star, &[0, 1, 2, 3, 4, 5, 6, 6]), None);
        // A 3D elastic grid under three orderings, against brute force.
        let (a, coords) = grid_kff(3);
        let nd = nested_dissection(&a, &coords);
        let reversed: Vec<usize> = (0..a.n).rev().collect();
        let natural: Vec<usize> = (0..a.n).collect();
        for order in [nd, reversed, natural] {
            let s = factor_size(&a, &order).expect("permutation");
            assert_eq!((s.nnz, s.flops), dense_fill(&a, &order));
        }
    }

    #[test]
    fn nested_dissection_of_a_3d_grid_keeps_the_fill_low() {
        // 16³ HEXA8 (13,872 unknowns): METIS_NodeND (pymetis 2025.2.2) on
        // the node graph, expanded to the nodes' unknowns, gives 5,443,125
        // non-zeros, faer's AMD 8,103,606, this dissection 5,166,399
        // (benches/peers/fill3d.sh, `--grid 16`). Bound: METIS's count.
        let (a, coords) = grid_kff(16);
        assert_eq!(a.n, 3 * 16 * 17 * 17);
        let order = nested_dissection(&a, &coords);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert!(sorted.iter().enumerate().all(|(k, &v)| k == v));
        let s = factor_size(&a, &order).expect("permutation");
        assert!(s.nnz <= 5_443_125, "nnz(L) = {}", s.nnz);
    }
}
