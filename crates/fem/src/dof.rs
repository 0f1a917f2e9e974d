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
    /// The pressure unknown of code_aster's mixed incompressible elements
    /// (`*_INCO_UPG`, [`crate::mixed_upg`]): the mean stress, at vertices.
    PRES,
    /// The swelling (volume change) unknown of the same elements.
    GONF,
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
            Comp::PRES => "PRES",
            Comp::GONF => "GONF",
        }
    }

    pub fn from_name(name: &str) -> Option<Comp> {
        match name {
            "PRES" => Some(Comp::PRES),
            "GONF" => Some(Comp::GONF),
            _ => Comp::ALL.into_iter().find(|c| c.name() == name),
        }
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
/// element of the model get DOFs. Each numbered node has its own component
/// set, which begins with the model's translations (DX DY in plane
/// problems, DX DY DZ in 3D): the nodes of continuum elements have only
/// those, the nodes of shell elements the rotations DRX DRY DRZ after them.
/// The one exception is the centre node of a COQUE_3D cell, which carries
/// DRX DRY DRZ alone (code_aster's `MEC3QU9H`): code that reads a node's
/// translations by position checks [`DofNumbering::node_comps`].
/// Numbering is node-major, so the DOFs of a node are contiguous and an
/// element that uses the first `k` components of its nodes finds them at
/// `node_first(n)..node_first(n) + k`.
#[derive(Clone, Debug, PartialEq)]
pub struct DofNumbering {
    /// The translations every numbered node carries first.
    comps: Vec<Comp>,
    /// The component sets of the nodes (`sets[0]` is `comps`).
    sets: Vec<Vec<Comp>>,
    /// First DOF index of each mesh node, `u32::MAX` when the node has none.
    node_first: Vec<u32>,
    /// Index in `sets` of each numbered node's components.
    node_set: Vec<u8>,
    dofs: Vec<Dof>,
}

const NONE: u32 = u32::MAX;

impl DofNumbering {
    /// Numbers `comps` on every node with `carried[node] == true`, in node order.
    pub fn new(comps: &[Comp], carried: &[bool]) -> DofNumbering {
        let sets: Vec<Option<u8>> = carried.iter().map(|&c| c.then_some(0)).collect();
        DofNumbering::per_node(vec![comps.to_vec()], &sets)
    }

    /// Numbers, on each node with `set[node] = Some(s)`, the components
    /// `sets[s]`, in node order. Every set begins with `sets[0]` (the
    /// translations), so that an element using only those finds them first
    /// — except a set of rotations alone (COQUE_3D centres), which only
    /// the element owning the node uses.
    pub fn per_node(sets: Vec<Vec<Comp>>, set: &[Option<u8>]) -> DofNumbering {
        let mut node_first = vec![NONE; set.len()];
        let mut node_set = vec![0u8; set.len()];
        let mut dofs = Vec::new();
        for (n, s) in set.iter().enumerate() {
            if let Some(s) = *s {
                node_first[n] = dofs.len() as u32;
                node_set[n] = s;
                for &comp in &sets[s as usize] {
                    dofs.push(Dof::new(NodeId(n as u32), comp));
                }
            }
        }
        DofNumbering {
            comps: sets.first().cloned().unwrap_or_default(),
            sets,
            node_first,
            node_set,
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

    /// The translations, which every numbered node carries first.
    pub fn comps(&self) -> &[Comp] {
        &self.comps
    }

    /// The components of a node, in their numbering order (empty when the
    /// node carries no element).
    pub fn node_comps(&self, node: NodeId) -> &[Comp] {
        match self.node_first.get(node.0 as usize) {
            Some(&f) if f != NONE => &self.sets[self.node_set[node.0 as usize] as usize],
            _ => &[],
        }
    }

    /// All DOFs in index order.
    pub fn dofs(&self) -> &[Dof] {
        &self.dofs
    }

    pub fn dof(&self, index: usize) -> Dof {
        self.dofs[index]
    }

    /// Index of a DOF, `None` when the node carries no element or the
    /// component is not one of the node's.
    pub fn index(&self, dof: Dof) -> Option<usize> {
        let first = *self.node_first.get(dof.node.0 as usize)?;
        if first == NONE {
            return None;
        }
        let k = self
            .node_comps(dof.node)
            .iter()
            .position(|&c| c == dof.comp)?;
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

    /// Whether some node carries rotations.
    pub fn has_rotations(&self) -> bool {
        self.sets.iter().any(|s| s.contains(&Comp::DRX))
    }

    /// Whether some node carries the pressure and swelling unknowns of
    /// the mixed elements ([`crate::mixed_upg`]).
    pub fn has_mixed(&self) -> bool {
        self.sets.iter().any(|s| s.contains(&Comp::PRES))
    }

    /// The same numbering with `extra` appended to the components of the
    /// nodes `extended` marks (which carry the translations alone).
    pub fn extended(&self, extended: &[bool], extra: &[Comp]) -> DofNumbering {
        let mut sets = self.sets.clone();
        let mut with = self.comps.clone();
        with.extend_from_slice(extra);
        let added = sets.len() as u8;
        sets.push(with);
        let set: Vec<Option<u8>> = (0..self.node_first.len())
            .map(|n| {
                if self.node_first[n] == NONE {
                    None
                } else if extended.get(n).copied().unwrap_or(false) {
                    Some(added)
                } else {
                    Some(self.node_set[n])
                }
            })
            .collect();
        DofNumbering::per_node(sets, &set)
    }
}
