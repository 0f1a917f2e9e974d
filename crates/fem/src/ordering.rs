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

/// Bisects `v` at the median coordinate of its longest extent, or None
/// when it is a leaf or cannot be split (all on one coordinate).
fn split(a: &Csc, coords: &[[f64; 3]], v: &[usize], ids: &mut SetIds) -> Option<Split> {
    if v.len() <= LEAF {
        return None;
    }
    let (lo, hi) = aster_mesh::bounding_box(v.iter().map(|&i| coords[i]));
    let axis = (0..3)
        .max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y])))
        .unwrap_or(0);
    let mut v = v.to_vec();
    let mid = v.len() / 2;
    v.select_nth_unstable_by(mid, |&x, &y| coords[x][axis].total_cmp(&coords[y][axis]));
    let pivot = coords[v[mid]][axis];
    // Left: strictly below the median coordinate, so a node's components
    // stay together.
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
    let sid = ids.next_id;
    ids.next_id += 1;
    for &i in &sep {
        ids.set_id[i] = sid;
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
}
