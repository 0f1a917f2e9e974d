//! The fill of the sparse Cholesky factor of a 3D stiffness matrix under
//! each ordering (issue 19's 3D scale):
//!
//! ```text
//! cargo run --profile ci -p aster-fem --example fill3d -- MESH.mail \
//!     [--graph FILE] [--metis FILE] [--solve] [--skip-amd]
//! cargo run --profile ci -p aster-fem --example fill3d -- --grid N ...
//! ```
//!
//! MESH.mail is a mesh written by `benches/peers/hertz3d.py` (HEXA8 cells,
//! node groups SYMX, SYMY, BOT, TOP). Its stiffness matrix (E = 2e5,
//! ν = 0.3) is assembled with the DOFs of the problem's Dirichlet conditions
//! eliminated (DX on SYMX, DY on SYMY, DZ on BOT and TOP), and for each
//! ordering the factor's exact non-zeros and flops are printed
//! (`ordering::factor_size`): faer's AMD, the project's nested dissection,
//! and METIS's nested dissection when `--metis FILE` gives its node order
//! (one 0-based node index per line, as `benches/peers/metis_order.py`
//! writes it from the node graph that `--graph FILE` writes). `--solve`
//! also factorises and solves as `aster` does (`linalg::solve_with`, with
//! `ASTER_FEM_TIMING=1` for its sub-phases). `--grid N` takes instead the
//! unit cube of N³ HEXA8 clamped at its bottom (`scenes::hexa8_grid`). Each phase prints its wall time
//! and the process CPU it used.

use aster_fem::assembly::{assemble_stiffness_into, restrict_owned, stiffness_pattern};
use aster_fem::dof::Comp;
use aster_fem::linalg::{self, Csc};
use aster_fem::ordering::{factor_size, nested_dissection, FactorSize};
use aster_fem::{Elastic, Element, ElementKind, Hypothesis, Model};
use aster_mesh::{CellId, CellType};
use std::io::Write;
use std::time::Instant;

type Error = Box<dyn std::error::Error>;

/// User + system CPU seconds of this process (Linux /proc; 0 elsewhere).
fn cpu() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.);
    (ticks(11) + ticks(12)) / 100.0
}

/// Runs `f`, printing its wall and CPU time after `what`.
fn timed<T>(what: &str, f: impl FnOnce() -> T) -> T {
    let (w, c) = (Instant::now(), cpu());
    let r = f();
    println!(
        "{what}: {:.3} s wall, {:.2} s cpu",
        w.elapsed().as_secs_f64(),
        cpu() - c
    );
    r
}

fn report(what: &str, n: usize, s: FactorSize) {
    println!(
        "{what:<24} nnz(L) {:>13}  ({:>6.0} per row)  flops {:.3e}",
        s.nnz,
        s.nnz as f64 / n as f64,
        s.flops
    );
}

/// faer's AMD ordering of `a` (what `linalg` uses without coordinates).
fn amd_order(a: &Csc) -> Result<Vec<usize>, Error> {
    use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, SymmetricOrdering};
    let sym =
        faer::sparse::SymbolicSparseColMatRef::new_checked(a.n, a.n, &a.col_ptr, None, &a.row_idx);
    let symbolic = factorize_symbolic_cholesky(
        sym,
        faer::Side::Lower,
        SymmetricOrdering::Amd,
        Default::default(),
    )
    .map_err(|e| format!("AMD: {e:?}"))?;
    let perm = symbolic.perm().ok_or("AMD gave no permutation")?;
    Ok(perm.arrays().0.to_vec())
}

/// The model of a `hertz3d.py` mesh and its free-unknown map.
fn from_mail(mail: &str) -> Result<(Model, Vec<usize>), Error> {
    let mesh = timed("read mesh", || aster_mesh::read_mesh(mail.as_ref()))?;
    let material = Elastic::new(2e5, 0.3)?;
    let elements: Vec<Element> = (0..mesh.cells.len())
        .filter(|&c| mesh.cells[c].ty == CellType::HEXA8)
        .map(|c| Element {
            cell: CellId(c as u32),
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::Solid3D,
                material,
            },
        })
        .collect();
    let nnodes = mesh.coords.len();
    let mut fixed = vec![[false; 3]; nnodes];
    for g in &mesh.groups_no {
        let comps: &[usize] = match g.name.as_str() {
            "SYMX" => &[0],
            "SYMY" => &[1],
            "BOT" | "TOP" => &[2],
            _ => &[],
        };
        for &nd in &g.members {
            for &c in comps {
                fixed[nd.0 as usize][c] = true;
            }
        }
    }
    let model = Model::new(mesh, elements)?;
    let dofs = model.dofs();
    let mut map = vec![usize::MAX; dofs.len()];
    let mut nfree = 0;
    for (k, m) in map.iter_mut().enumerate() {
        let d = dofs.dof(k);
        let c = match d.comp {
            Comp::DX => 0,
            Comp::DY => 1,
            _ => 2,
        };
        if !fixed[d.node.0 as usize][c] {
            *m = nfree;
            nfree += 1;
        }
    }
    Ok((model, map))
}

fn main() -> Result<(), Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (mut mail, mut grid) = (None, None);
    let (mut graph, mut metis, mut solve, mut skip_amd) = (None, None, false, false);
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--graph" => graph = it.next().cloned(),
            "--metis" => metis = it.next().cloned(),
            "--solve" => solve = true,
            "--skip-amd" => skip_amd = true,
            "--grid" => grid = it.next().and_then(|g| g.parse::<usize>().ok()),
            _ => mail = Some(a.clone()),
        }
    }
    let (model, map) = match grid {
        Some(g) => aster_fem::scenes::hexa8_grid(g)?,
        None => {
            let mail = mail.ok_or(
                "usage: fill3d (MESH.mail | --grid N) [--graph FILE] [--metis FILE] [--solve]",
            )?;
            from_mail(&mail)?
        }
    };
    let dofs = model.dofs();
    let nnodes = model.mesh().coords.len();
    let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
    let kff = timed("assembly (pattern, values, elimination)", || {
        let mut k = stiffness_pattern(&model);
        assemble_stiffness_into(&model, &mut k).map(|()| restrict_owned(k, &map, nfree))
    })?;
    println!(
        "{} nodes, {} free unknowns, nnz(K) {} (both triangles)",
        nnodes,
        kff.n,
        kff.row_idx.len()
    );
    let coords: Vec<[f64; 3]> = (0..dofs.len())
        .filter(|&i| map[i] != usize::MAX)
        .map(|i| model.mesh().coord(dofs.dof(i).node))
        .collect();
    // Free unknowns of each node, in free order.
    let mut node_dofs: Vec<Vec<usize>> = vec![Vec::new(); nnodes];
    for (k, &m) in map.iter().enumerate() {
        if m != usize::MAX {
            node_dofs[dofs.dof(k).node.0 as usize].push(m);
        }
    }
    if let Some(path) = &graph {
        // The node graph (nodes with a free unknown, coupled through K),
        // METIS's text format: "n m", then each node's 1-based neighbours.
        let nodes: Vec<usize> = (0..nnodes).filter(|&v| !node_dofs[v].is_empty()).collect();
        let mut id = vec![usize::MAX; nnodes];
        for (k, &v) in nodes.iter().enumerate() {
            id[v] = k;
        }
        let mut dof_node = vec![0usize; kff.n];
        for (v, ds) in node_dofs.iter().enumerate() {
            for &d in ds {
                dof_node[d] = v;
            }
        }
        let mut adj: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
        for (k, &v) in nodes.iter().enumerate() {
            let mut nb: Vec<usize> = node_dofs[v]
                .iter()
                .flat_map(|&d| &kff.row_idx[kff.col_ptr[d]..kff.col_ptr[d + 1]])
                .map(|&r| id[dof_node[r]])
                .filter(|&u| u != k)
                .collect();
            nb.sort_unstable();
            nb.dedup();
            adj[k] = nb;
        }
        let edges: usize = adj.iter().map(Vec::len).sum::<usize>() / 2;
        let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
        writeln!(w, "{} {}", nodes.len(), edges)?;
        for nb in &adj {
            let line: Vec<String> = nb.iter().map(|u| (u + 1).to_string()).collect();
            writeln!(w, "{}", line.join(" "))?;
        }
        // The graph's vertex k is mesh node nodes[k].
        let mut w2 = std::io::BufWriter::new(std::fs::File::create(format!("{path}.nodes"))?);
        for v in &nodes {
            writeln!(w2, "{v}")?;
        }
        println!(
            "node graph: {} vertices, {edges} edges -> {path}",
            nodes.len()
        );
    }
    let n = kff.n;
    if !skip_amd {
        let order = timed("ordering: AMD (faer)", || amd_order(&kff))?;
        let s = factor_size(&kff, &order).ok_or("AMD: not a permutation")?;
        report("AMD (faer)", n, s);
    }
    let order = timed("ordering: nested dissection (aster)", || {
        nested_dissection(&kff, &coords)
    });
    let s = factor_size(&kff, &order).ok_or("ND: not a permutation")?;
    report("nested dissection", n, s);
    if let Some(path) = &metis {
        // Graph vertex order from METIS, mapped to mesh nodes, expanded to
        // each node's free unknowns.
        let nodes: Vec<usize> = std::fs::read_to_string(format!(
            "{}.nodes",
            graph.as_deref().ok_or("--metis needs --graph")?
        ))?
        .lines()
        .map(|l| l.trim().parse::<usize>())
        .collect::<Result<_, _>>()?;
        let vorder: Vec<usize> = std::fs::read_to_string(path)?
            .lines()
            .map(|l| l.trim().parse::<usize>())
            .collect::<Result<_, _>>()?;
        let mut order = Vec::with_capacity(n);
        for v in vorder {
            let node = *nodes.get(v).ok_or("METIS order: vertex out of range")?;
            order.extend(&node_dofs[node]);
        }
        let s = factor_size(&kff, &order).ok_or("METIS: not a permutation")?;
        report("METIS (node graph)", n, s);
    }
    if solve {
        let mut b = vec![0.0; n];
        b[n - 1] = 1.0;
        let r = timed(
            "ordering + factorisation + solve (linalg::solve_with)",
            || linalg::solve_with(&kff, &b, n, true, Some(&coords)),
        )
        .map_err(|f| format!("solve failed: {f:?}"))?;
        println!(
            "{}: backward error {:.2e}",
            if r.cholesky { "Cholesky" } else { "LU" },
            r.backward_error
        );
    }
    Ok(())
}
