//! Detection of rigid-body modes that nothing holds, so that a singular
//! model is reported with the DOFs that are free instead of NaN results.
//!
//! The model is split into parts connected by elements (springs between two
//! nodes and multi-node relations count as connections). For each part, its
//! rigid-body modes (translations and rotations; only the axial translation
//! in AXIS) are tested against every condition that ties it to the ground:
//! eliminated DOFs, dualised rows, inequality rows and node-to-ground
//! springs. A combination of modes that no condition sees is a mechanism;
//! its DOFs are reported.

use crate::dof::Comp;
use crate::material::Hypothesis;
use crate::model::{ElementKind, Model};
use aster_mesh::CellType;
use nalgebra::DMatrix;

fn find(p: &mut [usize], mut i: usize) -> usize {
    while p[i] != i {
        p[i] = p[p[i]];
        i = p[i];
    }
    i
}

/// Returns the names of free DOFs (empty when every part is held).
/// `rows` are all grounding rows over DOF indices (eliminated DOFs as unit
/// rows, dualised and inequality rows); multi-node rows also connect parts.
pub fn free_dofs(model: &Model, rows: &[Vec<(usize, f64)>]) -> Vec<String> {
    let mesh = model.mesh();
    let dofs = model.dofs();
    let ncomp = dofs.comps().len();
    let nn = mesh.node_count();
    let mut parent: Vec<usize> = (0..nn).collect();
    let union = |p: &mut Vec<usize>, a: usize, b: usize| {
        let (ra, rb) = (find(p, a), find(p, b));
        if ra != rb {
            p[ra] = rb;
        }
    };
    let mut ground_rows: Vec<Vec<(usize, f64)>> = Vec::new();
    for el in model.elements() {
        let c = mesh.cell(el.cell);
        match &el.kind {
            ElementKind::Continuum { .. }
            | ElementKind::Shell { .. }
            | ElementKind::Beam { .. }
            | ElementKind::Bar { .. }
            | ElementKind::Grid { .. }
            | ElementKind::Coque3d { .. } => {
                for w in c.nodes.windows(2) {
                    union(&mut parent, w[0].0 as usize, w[1].0 as usize);
                }
            }
            ElementKind::Spring { stiffness, .. } => {
                if c.ty == CellType::POI1 {
                    if let Some(first) = dofs.node_first(c.nodes[0]) {
                        // Global stiffness rows of the spring hold the node.
                        let (k, _) = crate::element::spring_stiffness(
                            mesh,
                            el.cell,
                            stiffness,
                            crate::model::Frame::Global,
                        );
                        for a in 0..ncomp.min(k.nrows()) {
                            let row: Vec<(usize, f64)> = (0..ncomp.min(k.ncols()))
                                .filter(|&b| k[(a, b)] != 0.)
                                .map(|b| (first + b, k[(a, b)]))
                                .collect();
                            if !row.is_empty() {
                                ground_rows.push(row);
                            }
                        }
                    }
                } else if stiffness.iter().any(|&k| k != 0.) {
                    union(&mut parent, c.nodes[0].0 as usize, c.nodes[1].0 as usize);
                }
            }
            ElementKind::Boundary => {}
        }
    }
    for r in rows {
        let nodes: Vec<usize> = r
            .iter()
            .map(|&(i, _)| dofs.dof(i).node.0 as usize)
            .collect();
        for w in nodes.windows(2) {
            union(&mut parent, w[0], w[1]);
        }
        ground_rows.push(r.clone());
    }
    // Parts: root → nodes.
    let mut parts: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for n in 0..nn {
        if dofs.has_node(aster_mesh::NodeId(n as u32)) {
            parts.entry(find(&mut parent, n)).or_default().push(n);
        }
    }
    let mut part_of = vec![usize::MAX; nn];
    for (k, (_, nodes)) in parts.iter().enumerate() {
        for &n in nodes {
            part_of[n] = k;
        }
    }
    let hyp = model.hypothesis();
    let dim = model.dim();
    let mut out = Vec::new();
    let parts: Vec<Vec<usize>> = parts.into_values().collect();
    // Rows per part.
    let mut part_rows: Vec<Vec<&Vec<(usize, f64)>>> = vec![Vec::new(); parts.len()];
    for r in &ground_rows {
        if let Some(&(i, _)) = r.first() {
            let n = dofs.dof(i).node.0 as usize;
            part_rows[part_of[n]].push(r);
        }
    }
    for (k, nodes) in parts.iter().enumerate() {
        // Centroid and size for well-scaled rotation modes.
        let mut ctr = [0.0; 3];
        for &n in nodes {
            let p = mesh.coords[n];
            for a in 0..3 {
                ctr[a] += p[a] / nodes.len() as f64;
            }
        }
        let mut size = 0.0f64;
        for &n in nodes {
            let p = mesh.coords[n];
            for a in 0..3 {
                size = size.max((p[a] - ctr[a]).abs());
            }
        }
        let size = if size > 0. { size } else { 1. };
        // Mode value at (node, comp) for mode m.
        let modes: Vec<&str> = match (hyp, dim) {
            (Some(Hypothesis::Axisymmetric), _) => vec!["TY"],
            (_, 2) => {
                if nodes.len() > 1 {
                    vec!["TX", "TY", "RZ"]
                } else {
                    vec!["TX", "TY"]
                }
            }
            _ => {
                if nodes.len() > 1 {
                    vec!["TX", "TY", "TZ", "RX", "RY", "RZ"]
                } else {
                    vec!["TX", "TY", "TZ"]
                }
            }
        };
        // Rotation components (shell nodes): the mode's rotation, 1/size
        // about its axis as the translations above are scaled.
        let value = |m: &str, n: usize, c: Comp| -> f64 {
            let p = mesh.coords[n];
            let (x, y, z) = (
                (p[0] - ctr[0]) / size,
                (p[1] - ctr[1]) / size,
                (p[2] - ctr[2]) / size,
            );
            match (m, c) {
                ("TX", Comp::DX) | ("TY", Comp::DY) | ("TZ", Comp::DZ) => 1.,
                ("RZ", Comp::DX) => -y,
                ("RZ", Comp::DY) => x,
                ("RX", Comp::DY) => -z,
                ("RX", Comp::DZ) => y,
                ("RY", Comp::DX) => z,
                ("RY", Comp::DZ) => -x,
                ("RX", Comp::DRX) | ("RY", Comp::DRY) | ("RZ", Comp::DRZ) => 1. / size,
                _ => 0.,
            }
        };
        let rows = &part_rows[k];
        let nm = modes.len();
        let mut g: DMatrix<f64> = DMatrix::zeros(rows.len().max(1), nm);
        for (r, row) in rows.iter().enumerate() {
            let scale = row.iter().fold(0.0f64, |m, &(_, c)| m.max(c.abs()));
            for &(i, c) in row.iter() {
                let d = dofs.dof(i);
                for (mi, m) in modes.iter().enumerate() {
                    g[(r, mi)] += c / scale * value(m, d.node.0 as usize, d.comp);
                }
            }
        }
        // Null space of G via the eigen-decomposition of GᵀG.
        let gtg = g.transpose() * &g;
        let eig = gtg.symmetric_eigen();
        let maxev = eig
            .eigenvalues
            .iter()
            .fold(0.0f64, |m: f64, v: &f64| m.max(v.abs()));
        let tol = 1e-10 * maxev.max(1.0);
        // The part's DOFs, node-major (each node with its own components).
        let part_dofs: Vec<usize> = nodes
            .iter()
            .flat_map(|&n| {
                let node = aster_mesh::NodeId(n as u32);
                let first = dofs.node_first(node).unwrap_or(0);
                first..first + dofs.node_comps(node).len()
            })
            .collect();
        let mut free = vec![false; part_dofs.len()];
        let mut any = false;
        for (e, &ev) in eig.eigenvalues.iter().enumerate() {
            if ev.abs() > tol {
                continue;
            }
            any = true;
            let v = eig.eigenvectors.column(e);
            let field: Vec<f64> = part_dofs
                .iter()
                .map(|&i| {
                    let d = dofs.dof(i);
                    modes
                        .iter()
                        .enumerate()
                        .map(|(mi, m)| v[mi] * value(m, d.node.0 as usize, d.comp))
                        .sum::<f64>()
                })
                .collect();
            let fmax = field.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (i, f) in field.iter().enumerate() {
                if f.abs() > 1e-6 * fmax {
                    free[i] = true;
                }
            }
        }
        if any {
            for (k, &i) in part_dofs.iter().enumerate() {
                if free[k] {
                    out.push(dofs.dof(i).describe(mesh));
                }
            }
        }
    }
    out
}
