//! Helpers to build small meshes in tests.
#![allow(dead_code)]

use aster_mesh::{Cell, CellId, CellType, Group, Mesh, NodeId};

pub struct MeshBuilder {
    pub mesh: Mesh,
}

impl MeshBuilder {
    pub fn new(dim: u8) -> MeshBuilder {
        MeshBuilder {
            mesh: Mesh {
                dim,
                ..Mesh::default()
            },
        }
    }

    pub fn node(&mut self, name: &str, x: [f64; 3]) -> NodeId {
        self.mesh.coords.push(x);
        self.mesh.node_names.push(name.to_string());
        NodeId(self.mesh.coords.len() as u32 - 1)
    }

    pub fn cell(&mut self, name: &str, ty: CellType, nodes: &[NodeId]) -> CellId {
        self.mesh.cells.push(Cell {
            ty,
            nodes: nodes.to_vec(),
        });
        self.mesh.cell_names.push(name.to_string());
        CellId(self.mesh.cells.len() as u32 - 1)
    }

    pub fn group_no(&mut self, name: &str, nodes: &[NodeId]) {
        self.mesh.groups_no.push(Group {
            name: name.to_string(),
            members: nodes.to_vec(),
        });
    }
}

/// One QUAD4 [0, 1]², bottom held, the top pulled up by DY = 0.01 t (its
/// last node returned).
pub fn pulled_square() -> (aster_fem::Model, aster_fem::Loads, NodeId) {
    use aster_fem::*;
    let mut mb = MeshBuilder::new(2);
    let n: Vec<NodeId> = [[0., 0.], [1., 0.], [1., 1.], [0., 1.]]
        .iter()
        .enumerate()
        .map(|(i, p)| mb.node(&format!("N{i}"), [p[0], p[1], 0.]))
        .collect();
    let c = mb.cell("M1", CellType::QUAD4, &n);
    let model = Model::new(
        mb.mesh,
        vec![Element {
            cell: c,
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::PlaneStrain,
                material: Elastic::new(1000., 0.25).unwrap(),
            },
        }],
    )
    .unwrap();
    let mut loads = Loads::new();
    for &b in &n[..2] {
        for comp in [Comp::DX, Comp::DY] {
            loads.push(Load::Eliminated {
                dof: Dof::new(b, comp),
                value: 0.,
            });
        }
    }
    for &t in &n[2..] {
        loads.add(
            Load::Eliminated {
                dof: Dof::new(t, Comp::DY),
                value: 0.01,
            },
            Multiplier::from_fn(Ok),
        );
    }
    (model, loads, n[2])
}

/// The dense solution of K·u = f with the DOFs `fixed` held at zero (their
/// rows and columns removed; zero in the result).
pub fn solve_held(
    k: &nalgebra::DMatrix<f64>,
    f: &nalgebra::DVector<f64>,
    fixed: &[usize],
) -> nalgebra::DVector<f64> {
    let n = k.nrows();
    let free: Vec<usize> = (0..n).filter(|i| !fixed.contains(i)).collect();
    let kr = nalgebra::DMatrix::from_fn(free.len(), free.len(), |a, b| k[(free[a], free[b])]);
    let fr = nalgebra::DVector::from_fn(free.len(), |a, _| f[free[a]]);
    let ur = kr.lu().solve(&fr).expect("non-singular");
    let mut u = nalgebra::DVector::zeros(n);
    for (a, &i) in free.iter().enumerate() {
        u[i] = ur[a];
    }
    u
}
