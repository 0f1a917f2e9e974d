//! Global assembly of the stiffness matrix over the model's DOFs.

use crate::element::{
    continuum_stiffness_fast, element_dofs_into, element_stiffness, hooke_array, RefData,
    MAX_EL_DOFS,
};
use crate::error::FemError;
use crate::linalg::Csc;
use crate::material::{Elastic, Hypothesis};
use crate::model::{ElementKind, Model};
use aster_mesh::NodeId;

/// The sparsity pattern of the model's stiffness: DOFs of nodes sharing an
/// element are coupled. Built from node adjacency (node-major numbering, so
/// every component of a node shares its column structure).
pub fn stiffness_pattern(model: &Model) -> Csc {
    let mesh = model.mesh();
    let dofs = model.dofs();
    let nd = dofs.len();
    let ncomp = dofs.comps_per_node();
    let nnodes = mesh.node_count();
    // Node → cells incidence (CSR), then each node's sorted neighbours.
    let mut count = vec![0usize; nnodes + 1];
    let stiff = |el: &crate::model::Element| !matches!(el.kind, ElementKind::Boundary);
    for el in model.elements().iter().filter(|e| stiff(e)) {
        for n in &mesh.cell(el.cell).nodes {
            count[n.0 as usize + 1] += 1;
        }
    }
    for i in 0..nnodes {
        count[i + 1] += count[i];
    }
    let mut fill = count.clone();
    let mut inc = vec![0u32; count[nnodes]];
    for (e, el) in model.elements().iter().enumerate() {
        if !stiff(el) {
            continue;
        }
        for n in &mesh.cell(el.cell).nodes {
            inc[fill[n.0 as usize]] = e as u32;
            fill[n.0 as usize] += 1;
        }
    }
    let mut col_ptr = Vec::with_capacity(nd + 1);
    col_ptr.push(0usize);
    let mut row_idx: Vec<usize> = Vec::with_capacity(nd * 9 * ncomp);
    let mut neigh: Vec<u32> = Vec::with_capacity(64);
    for node in 0..nnodes {
        let Some(first) = dofs.node_first(NodeId(node as u32)) else {
            continue;
        };
        debug_assert_eq!(first, col_ptr.len() - 1);
        neigh.clear();
        for &e in &inc[count[node]..count[node + 1]] {
            let el = &model.elements()[e as usize];
            neigh.extend(mesh.cell(el.cell).nodes.iter().map(|n| n.0));
        }
        if neigh.is_empty() {
            // Nodes of boundary-only cells keep a diagonal entry.
            neigh.push(node as u32);
        }
        neigh.sort_unstable();
        neigh.dedup();
        let start = row_idx.len();
        for &m in &neigh {
            if let Some(f) = dofs.node_first(NodeId(m)) {
                row_idx.extend(f..f + ncomp);
            }
        }
        let end = row_idx.len();
        col_ptr.push(end);
        for _ in 1..ncomp {
            row_idx.extend_from_within(start..end);
            col_ptr.push(row_idx.len());
        }
    }
    let values = vec![0.0; row_idx.len()];
    Csc {
        n: nd,
        col_ptr,
        row_idx,
        values,
    }
}

/// Assembles the stiffness of all elements over all displacement DOFs.
pub fn assemble_stiffness(model: &Model) -> Result<Csc, FemError> {
    let mut k = stiffness_pattern(model);
    let mesh = model.mesh();
    let mut refs: Vec<RefData> = Vec::new();
    let mut hooke: Option<(Elastic, Hypothesis, [[f64; 6]; 6])> = None;
    let mut buf = vec![0.0; MAX_EL_DOFS * MAX_EL_DOFS];
    let mut dofs = Vec::with_capacity(MAX_EL_DOFS);
    for (idx, el) in model.elements().iter().enumerate() {
        let ndof = match &el.kind {
            ElementKind::Continuum {
                hypothesis,
                material,
            } => {
                let cell = mesh.cell(el.cell);
                let rd = match refs.iter().position(|r| r.ty == cell.ty) {
                    Some(p) => &refs[p],
                    None => {
                        refs.push(RefData::new(cell.ty));
                        &refs[refs.len() - 1]
                    }
                };
                let d = match &hooke {
                    Some((m, h, d)) if m == material && h == hypothesis => d,
                    _ => {
                        let d = hooke_array(material, *hypothesis);
                        &hooke.insert((*material, *hypothesis, d)).2
                    }
                };
                continuum_stiffness_fast(mesh, &cell.nodes, rd, *hypothesis, d, &mut buf).map_err(
                    |m| FemError::Model(format!("cell {} is {m}", model.cell_name(el.cell))),
                )?
            }
            ElementKind::Spring { .. } => {
                let Some(ke) = element_stiffness(model, idx)? else {
                    continue;
                };
                let n = ke.nrows();
                for a in 0..n {
                    for b in 0..n {
                        buf[a * n + b] = ke[(a, b)];
                    }
                }
                n
            }
            ElementKind::Boundary => continue,
        };
        dofs.clear();
        element_dofs_into(model, el.cell, &mut dofs);
        for (b, &j) in dofs.iter().enumerate() {
            let (start, end) = (k.col_ptr[j], k.col_ptr[j + 1]);
            let rows = &k.row_idx[start..end];
            for (a, &i) in dofs.iter().enumerate() {
                // Symmetric element matrices: (a, b) = (b, a).
                let v = buf[a * ndof + b];
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
