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
