//! Times the phases of assembling and solving a plane-strain QUAD4 grid:
//! `cargo run --release -p aster-fem --example phases -- 707`.

use aster_fem::assembly::{assemble_stiffness, restrict};
use aster_fem::linalg;
use aster_fem::*;
use aster_mesh::{Cell, CellId, CellType, Mesh, NodeId};
use std::time::Instant;

fn problem(n: usize) -> (Model, Vec<usize>) {
    let mut mesh = Mesh {
        dim: 2,
        ..Mesh::default()
    };
    for j in 0..=n {
        for i in 0..=n {
            mesh.coords
                .push([i as f64 / n as f64, j as f64 / n as f64, 0.]);
            mesh.node_names.push(format!("N{}", j * (n + 1) + i + 1));
        }
    }
    let id = |i: usize, j: usize| NodeId((j * (n + 1) + i) as u32);
    for j in 0..n {
        for i in 0..n {
            mesh.cells.push(Cell {
                ty: CellType::QUAD4,
                nodes: vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
            });
            mesh.cell_names.push(format!("M{}", j * n + i + 1));
        }
    }
    let material = Elastic::new(2e11, 0.3).unwrap();
    let elements = (0..mesh.cells.len())
        .map(|c| Element {
            cell: CellId(c as u32),
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::PlaneStrain,
                material,
            },
        })
        .collect();
    let model = Model::new(mesh, elements).unwrap();
    let mut map = vec![0; model.dofs().len()];
    let mut nfree = 0;
    for (k, m) in map.iter_mut().enumerate() {
        let dof = model.dofs().dof(k);
        if dof.node.0 as usize <= n {
            *m = usize::MAX; // bottom row clamped (eliminated)
        } else {
            *m = nfree;
            nfree += 1;
        }
    }
    (model, map)
}

/// User + system CPU seconds of this process (Linux /proc; 0 elsewhere):
/// on a shared machine wall times mostly measure the others' load.
fn cpu() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the command name (which is in parentheses).
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.);
    // utime and stime are fields 14 and 15 of the stat line (11, 12 here).
    (ticks(11) + ticks(12)) / 100.0
}

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(224);
    let t = Instant::now();
    let (model, map) = problem(n);
    println!(
        "model: {} dofs in {:.3} s",
        model.dofs().len(),
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let p = aster_fem::assembly::stiffness_pattern(&model);
    println!(
        "pattern: {} non-zeros in {:.3} s",
        p.values.len(),
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let k = assemble_stiffness(&model).unwrap();
    println!(
        "assembly: {} non-zeros in {:.3} s",
        k.values.len(),
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
    let kff = restrict(&k, &map, nfree);
    println!(
        "restrict: {:.3} s (cpu {:.2} s)",
        t.elapsed().as_secs_f64(),
        cpu()
    );
    let mut b = vec![0.0; nfree];
    b[nfree - 1] = 1e6;
    let t = Instant::now();
    let coords: Vec<[f64; 3]> = (0..model.dofs().len())
        .filter(|&i| map[i] != usize::MAX)
        .map(|i| model.mesh().coord(model.dofs().dof(i).node))
        .collect();
    let r = linalg::solve_with(&kff, &b, nfree, true, Some(&coords)).unwrap();
    println!(
        "factorise+solve ({}): {:.3} s, backward error {:.2e}",
        if r.cholesky { "Cholesky" } else { "LU" },
        t.elapsed().as_secs_f64(),
        r.backward_error
    );
    println!("cpu total {:.2} s", cpu());
}

#[allow(dead_code)]
fn faer_phases(kff: &aster_fem::linalg::Csc) {
    use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
    use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
    let n = kff.n;
    let sym = SymbolicSparseColMatRef::new_checked(n, n, &kff.col_ptr, None, &kff.row_idx);
    let t = Instant::now();
    let s = SymbolicLlt::try_new(sym, faer::Side::Lower).unwrap();
    println!("  symbolic: {:.3} s", t.elapsed().as_secs_f64());
    let t = Instant::now();
    let _f =
        Llt::try_new_with_symbolic(s, SparseColMatRef::new(sym, &kff.values), faer::Side::Lower)
            .unwrap();
    println!("  numeric: {:.3} s", t.elapsed().as_secs_f64());
}
