//! Ready-made models for benchmarks, examples and tests.

use crate::{Elastic, Element, ElementKind, FemError, Hypothesis, Model};
use aster_mesh::{Cell, CellId, CellType, Mesh, NodeId};

/// An n×n grid of plane-strain QUAD4 on the unit square (steel, E = 2e11,
/// ν = 0.3), with `map[i]` = the free index of DOF i, or `usize::MAX` for
/// the DOFs of the bottom edge (clamped, eliminated). n = 707 gives
/// 1,002,528 DOFs (999,698 free): the issue 5 speed bar.
pub fn quad4_grid(n: usize) -> Result<(Model, Vec<usize>), FemError> {
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
    let material = Elastic::new(2e11, 0.3)?;
    let elements = (0..mesh.cells.len())
        .map(|c| Element {
            cell: CellId(c as u32),
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::PlaneStrain,
                material,
            },
        })
        .collect();
    let model = Model::new(mesh, elements)?;
    let mut map = vec![0; model.dofs().len()];
    let mut nfree = 0;
    for (k, m) in map.iter_mut().enumerate() {
        if model.dofs().dof(k).node.0 as usize <= n {
            *m = usize::MAX;
        } else {
            *m = nfree;
            nfree += 1;
        }
    }
    Ok((model, map))
}

/// An n×n×n grid of HEXA8 on the unit cube (steel, E = 2e11, ν = 0.3),
/// with `map[i]` = the free index of DOF i, or `usize::MAX` for the DOFs of
/// the bottom face z = 0 (clamped, eliminated): 3 n (n + 1)² free unknowns.
pub fn hexa8_grid(n: usize) -> Result<(Model, Vec<usize>), FemError> {
    let mut mesh = Mesh {
        dim: 3,
        ..Mesh::default()
    };
    let m = n + 1;
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                let c = |t: usize| t as f64 / n as f64;
                mesh.coords.push([c(i), c(j), c(k)]);
                mesh.node_names
                    .push(format!("N{}", (k * m + j) * m + i + 1));
            }
        }
    }
    let id = |i: usize, j: usize, k: usize| NodeId(((k * m + j) * m + i) as u32);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let mut nodes = Vec::with_capacity(8);
                for kk in [k, k + 1] {
                    nodes.extend([
                        id(i, j, kk),
                        id(i + 1, j, kk),
                        id(i + 1, j + 1, kk),
                        id(i, j + 1, kk),
                    ]);
                }
                mesh.cells.push(Cell {
                    ty: CellType::HEXA8,
                    nodes,
                });
                mesh.cell_names.push(format!("M{}", mesh.cells.len()));
            }
        }
    }
    let material = Elastic::new(2e11, 0.3)?;
    let elements = (0..mesh.cells.len())
        .map(|c| Element {
            cell: CellId(c as u32),
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::Solid3D,
                material,
            },
        })
        .collect();
    let model = Model::new(mesh, elements)?;
    let mut map = vec![0; model.dofs().len()];
    let mut nfree = 0;
    for (d, slot) in map.iter_mut().enumerate() {
        if (model.dofs().dof(d).node.0 as usize) < m * m {
            *slot = usize::MAX;
        } else {
            *slot = nfree;
            nfree += 1;
        }
    }
    Ok((model, map))
}

/// Coordinates of the free unknowns (their nodes'), in free order: what
/// the solver takes for its nested dissection ordering.
pub fn free_coords(model: &Model, map: &[usize]) -> Vec<[f64; 3]> {
    (0..model.dofs().len())
        .filter(|&i| map[i] != usize::MAX)
        .map(|i| model.mesh().coord(model.dofs().dof(i).node))
        .collect()
}
