//! Degrees of freedom and their numbering.

use aster_mesh::{Mesh, NodeId};
use std::fmt;

/// A displacement (or, later, rotation) component, with code_aster's names.
#[allow(clippy::upper_case_acronyms)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Comp {
    DX,
    DY,
    DZ,
    DRX,
    DRY,
    DRZ,
}

impl Comp {
    pub const ALL: [Comp; 6] = [
        Comp::DX,
        Comp::DY,
        Comp::DZ,
        Comp::DRX,
        Comp::DRY,
        Comp::DRZ,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Comp::DX => "DX",
            Comp::DY => "DY",
            Comp::DZ => "DZ",
            Comp::DRX => "DRX",
            Comp::DRY => "DRY",
            Comp::DRZ => "DRZ",
        }
    }

    pub fn from_name(name: &str) -> Option<Comp> {
        Comp::ALL.into_iter().find(|c| c.name() == name)
    }

    /// Translation components of a space of dimension `dim` (2 → DX DY).
    pub fn translations(dim: usize) -> &'static [Comp] {
        match dim {
            1 => &[Comp::DX],
            2 => &[Comp::DX, Comp::DY],
            _ => &[Comp::DX, Comp::DY, Comp::DZ],
        }
    }
}

/// One degree of freedom: a component at a node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Dof {
    pub node: NodeId,
    pub comp: Comp,
}

impl Dof {
    pub fn new(node: NodeId, comp: Comp) -> Dof {
        Dof { node, comp }
    }

    /// `N3 DX` with the mesh's node name.
    pub fn describe(self, mesh: &Mesh) -> String {
        let name = mesh
            .node_names
            .get(self.node.0 as usize)
            .cloned()
            .unwrap_or_else(|| format!("#{}", self.node.0 + 1));
        format!("{name} {}", self.comp.name())
    }
}

impl fmt::Display for Dof {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "node #{} {}", self.node.0 + 1, self.comp.name())
    }
}

/// The numbering of the displacement unknowns: only nodes carried by an
/// element of the model get DOFs, each with the model's components (DX DY in
/// plane problems, DX DY DZ in 3D). Numbering is node-major, so the DOFs of a
/// node are contiguous.
#[derive(Clone, Debug, PartialEq)]
pub struct DofNumbering {
    comps: Vec<Comp>,
    /// First DOF index of each mesh node, `u32::MAX` when the node has none.
    node_first: Vec<u32>,
    dofs: Vec<Dof>,
}

const NONE: u32 = u32::MAX;

impl DofNumbering {
    /// Numbers `comps` on every node with `carried[node] == true`, in node order.
    pub fn new(comps: &[Comp], carried: &[bool]) -> DofNumbering {
        let mut node_first = vec![NONE; carried.len()];
        let mut dofs = Vec::new();
        for (n, &c) in carried.iter().enumerate() {
            if c {
                node_first[n] = dofs.len() as u32;
                for &comp in comps {
                    dofs.push(Dof::new(NodeId(n as u32), comp));
                }
            }
        }
        DofNumbering {
            comps: comps.to_vec(),
            node_first,
            dofs,
        }
    }

    /// Number of displacement DOFs.
    pub fn len(&self) -> usize {
        self.dofs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }

    /// Components carried by every numbered node.
    pub fn comps(&self) -> &[Comp] {
        &self.comps
    }

    /// All DOFs in index order.
    pub fn dofs(&self) -> &[Dof] {
        &self.dofs
    }

    pub fn dof(&self, index: usize) -> Dof {
        self.dofs[index]
    }

    /// Index of a DOF, `None` when the node carries no element or the
    /// component is not part of the model.
    pub fn index(&self, dof: Dof) -> Option<usize> {
        let first = *self.node_first.get(dof.node.0 as usize)?;
        if first == NONE {
            return None;
        }
        let k = self.comps.iter().position(|&c| c == dof.comp)?;
        Some(first as usize + k)
    }

    /// The value of a DOF in a vector indexed by this numbering (DEPL,
    /// FORC_NODA, REAC_NODA…); `None` when the DOF is not numbered.
    pub fn value(&self, field: &[f64], dof: Dof) -> Option<f64> {
        self.index(dof).and_then(|i| field.get(i).copied())
    }

    /// First DOF index of a node (its components follow contiguously).
    pub fn node_first(&self, node: NodeId) -> Option<usize> {
        match self.node_first.get(node.0 as usize) {
            Some(&f) if f != NONE => Some(f as usize),
            _ => None,
        }
    }

    /// Whether the node carries DOFs.
    pub fn has_node(&self, node: NodeId) -> bool {
        self.node_first(node).is_some()
    }

    /// Number of components per node.
    pub fn comps_per_node(&self) -> usize {
        self.comps.len()
    }
}
