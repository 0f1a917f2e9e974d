//! Shared plumbing of the `CREA_MAILLAGE` operations: replacing cells by
//! other cells (groups follow), adding nodes and cells with fresh names,
//! and dropping nodes no cell uses any more.

use crate::{Cell, CellId, Mesh, NodeId};
use std::collections::HashSet;

/// Names for new nodes or cells: `<prefix><number>` where the number is the
/// entity's (1-based) position, as code_aster 17 names entities it creates;
/// a name already taken gets `_<k>` appended.
pub(crate) struct Namer {
    taken: HashSet<String>,
    prefix: &'static str,
}

impl Namer {
    pub(crate) fn new(existing: &[String], prefix: &'static str) -> Namer {
        Namer {
            taken: existing.iter().cloned().collect(),
            prefix,
        }
    }

    pub(crate) fn name(&mut self, position: usize) -> String {
        let base = format!("{}{}", self.prefix, position + 1);
        let mut name = base.clone();
        let mut k = 1;
        while self.taken.contains(&name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        self.taken.insert(name.clone());
        name
    }
}

impl Mesh {
    /// Adds a node and returns its id.
    pub(crate) fn push_node(&mut self, namer: &mut Namer, xyz: [f64; 3]) -> NodeId {
        let id = NodeId(self.coords.len() as u32);
        let name = namer.name(self.coords.len());
        self.coords.push(xyz);
        self.node_names.push(name);
        id
    }

    /// Replaces every cell by the cells `rewrite` returns for it (the cell
    /// itself, a changed copy, or several pieces). New pieces keep the old
    /// name when there is one piece, else get fresh names; every cell group
    /// holding the old cell holds its pieces, in order.
    pub(crate) fn rewrite_cells(&mut self, mut rewrite: impl FnMut(CellId, &Cell) -> Vec<Cell>) {
        let old_cells = std::mem::take(&mut self.cells);
        let old_names = std::mem::take(&mut self.cell_names);
        let mut namer = Namer::new(&old_names, "M");
        let mut pieces_of: Vec<Vec<CellId>> = Vec::with_capacity(old_cells.len());
        let mut pending: Vec<(usize, Vec<Cell>)> = Vec::new();
        for (i, cell) in old_cells.iter().enumerate() {
            pending.push((i, rewrite(CellId(i as u32), cell)));
        }
        for (i, pieces) in pending {
            let single = pieces.len() == 1;
            let mut ids = Vec::with_capacity(pieces.len());
            for piece in pieces {
                let id = CellId(self.cells.len() as u32);
                let name = if single {
                    old_names[i].clone()
                } else {
                    namer.name(self.cells.len())
                };
                self.cells.push(piece);
                self.cell_names.push(name);
                ids.push(id);
            }
            pieces_of.push(ids);
        }
        for g in &mut self.groups_ma {
            g.members = g
                .members
                .iter()
                .flat_map(|c| pieces_of[c.0 as usize].iter().copied())
                .collect();
        }
    }

    /// Keeps only the nodes `keep` marks, renumbering cells and node groups
    /// (a node group member that is dropped leaves the group; a group left
    /// empty is removed). Every node of a kept cell must be kept.
    pub(crate) fn retain_nodes(&mut self, keep: &[bool]) {
        let mut new_id = vec![None; self.coords.len()];
        let mut coords = Vec::new();
        let mut names = Vec::new();
        for (i, k) in keep.iter().enumerate() {
            if *k {
                new_id[i] = Some(NodeId(coords.len() as u32));
                coords.push(self.coords[i]);
                names.push(std::mem::take(&mut self.node_names[i]));
            }
        }
        self.coords = coords;
        self.node_names = names;
        for c in &mut self.cells {
            for n in &mut c.nodes {
                if let Some(m) = new_id[n.0 as usize] {
                    *n = m;
                }
            }
        }
        for g in &mut self.groups_no {
            g.members = g
                .members
                .iter()
                .filter_map(|n| new_id[n.0 as usize])
                .collect();
        }
        self.groups_no.retain(|g| !g.members.is_empty());
    }

    /// Nodes that at least one cell uses.
    pub(crate) fn used_nodes(&self) -> Vec<bool> {
        let mut used = vec![false; self.coords.len()];
        for c in &self.cells {
            for n in &c.nodes {
                used[n.0 as usize] = true;
            }
        }
        used
    }
}
