//! Global assembly of the stiffness matrix over the model's DOFs.

use crate::element::{element_dofs, element_stiffness};
use crate::error::FemError;
use crate::linalg::Csc;
use crate::model::{ElementKind, Model};

/// The sparsity pattern of the model's stiffness: DOFs of nodes sharing an
/// element are coupled. Built from node adjacency (node-major numbering, so
/// every component of a node shares its column structure).
pub fn stiffness_pattern(model: &Model) -> Csc {
    let mesh = model.mesh();
    let nd = model.dofs().len();
    let ncomp = model.dofs().comps_per_node();
    let nnodes = mesh.node_count();
    // Node adjacency lists.
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); nnodes];
    for el in model.elements() {
        if matches!(el.kind, ElementKind::Boundary) {
            continue;
        }
        let nodes = &mesh.cell(el.cell).nodes;
        for &a in nodes {
            let list = &mut adj[a.0 as usize];
            for &b in nodes {
                list.push(b.0);
            }
        }
    }
    let mut cols: Vec<Vec<u32>> = vec![Vec::new(); nd];
    for (node, list) in adj.iter_mut().enumerate() {
        list.sort_unstable();
        list.dedup();
        let Some(first) = model.dofs().node_first(aster_mesh::NodeId(node as u32)) else {
            continue;
        };
        let mut rows = Vec::with_capacity(list.len() * ncomp);
        for &m in list.iter() {
            if let Some(f) = model.dofs().node_first(aster_mesh::NodeId(m)) {
                rows.extend((f..f + ncomp).map(|r| r as u32));
            }
        }
        for k in 0..ncomp {
            cols[first + k] = rows.clone();
        }
    }
    for (j, c) in cols.iter_mut().enumerate() {
        // Keep a diagonal entry for every DOF (nodes of boundary-only cells).
        if c.is_empty() {
            c.push(j as u32);
        }
    }
    Csc::from_columns(nd, cols)
}

/// Assembles the stiffness of all elements over all displacement DOFs.
pub fn assemble_stiffness(model: &Model) -> Result<Csc, FemError> {
    let mut k = stiffness_pattern(model);
    for (idx, el) in model.elements().iter().enumerate() {
        let Some(ke) = element_stiffness(model, idx)? else {
            continue;
        };
        let dofs = element_dofs(model, el.cell);
        for (b, &j) in dofs.iter().enumerate() {
            let (start, end) = (k.col_ptr[j], k.col_ptr[j + 1]);
            let rows = &k.row_idx[start..end];
            for (a, &i) in dofs.iter().enumerate() {
                let v = ke[(a, b)];
                if v != 0. {
                    if let Ok(p) = rows.binary_search(&i) {
                        k.values[start + p] += v;
                    }
                }
            }
        }
    }
    Ok(k)
}

/// The sub-matrix on the free DOFs: `map[i]` is the free index of DOF i or
/// `usize::MAX` for an eliminated one.
pub fn restrict(k: &Csc, map: &[usize], nfree: usize) -> Csc {
    let mut col_ptr = Vec::with_capacity(nfree + 1);
    let mut row_idx = Vec::with_capacity(k.row_idx.len());
    let mut values = Vec::with_capacity(k.row_idx.len());
    col_ptr.push(0);
    for j in 0..k.n {
        if map[j] == usize::MAX {
            continue;
        }
        for p in k.col_ptr[j]..k.col_ptr[j + 1] {
            let r = map[k.row_idx[p]];
            if r != usize::MAX {
                row_idx.push(r);
                values.push(k.values[p]);
            }
        }
        col_ptr.push(row_idx.len());
    }
    // Row order is preserved because `map` is increasing on free DOFs.
    Csc {
        n: nfree,
        col_ptr,
        row_idx,
        values,
    }
}
