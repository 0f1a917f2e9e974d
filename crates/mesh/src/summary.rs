//! `INFO_MAILLAGE` and `aster mesh --json`: what a mesh holds, in brief.

use crate::{CellType, Mesh};
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;

/// Counts and group names of a mesh. Serializes as the CLI contract:
/// `{"nodes": N, "cells": {"QUAD4": n, …}, "groups_ma": […], "groups_no": […]}`
/// with cell types in code_aster's order and groups in file order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshSummary {
    pub nodes: usize,
    pub cells: CellCounts,
    pub groups_ma: Vec<String>,
    pub groups_no: Vec<String>,
}

/// Number of cells of each type present, in code_aster's type order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CellCounts(pub Vec<(CellType, usize)>);

impl Serialize for CellCounts {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (ty, n) in &self.0 {
            m.serialize_entry(ty.name(), n)?;
        }
        m.end()
    }
}

impl Mesh {
    pub fn cell_counts(&self) -> CellCounts {
        let mut counts = [0usize; CellType::ALL.len()];
        for c in &self.cells {
            counts[c.ty as usize] += 1;
        }
        CellCounts(
            CellType::ALL
                .into_iter()
                .zip(counts)
                .filter(|(_, n)| *n > 0)
                .collect(),
        )
    }

    pub fn summary(&self) -> MeshSummary {
        MeshSummary {
            nodes: self.node_count(),
            cells: self.cell_counts(),
            groups_ma: self.groups_ma.iter().map(|g| g.name.clone()).collect(),
            groups_no: self.groups_no.iter().map(|g| g.name.clone()).collect(),
        }
    }

    /// A human-readable report in the spirit of `INFO_MAILLAGE`.
    pub fn info(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        let _ = writeln!(s, "space dimension: {}", self.dim);
        let _ = writeln!(s, "nodes: {}", self.node_count());
        let _ = writeln!(s, "cells: {}", self.cells.len());
        for (ty, n) in self.cell_counts().0 {
            let _ = writeln!(s, "  {:<8} {n}", ty.name());
        }
        let _ = writeln!(s, "cell groups (GROUP_MA): {}", self.groups_ma.len());
        for g in &self.groups_ma {
            let _ = writeln!(s, "  {:<24} {} cells", g.name, g.members.len());
        }
        let _ = writeln!(s, "node groups (GROUP_NO): {}", self.groups_no.len());
        for g in &self.groups_no {
            let _ = writeln!(s, "  {:<24} {} nodes", g.name, g.members.len());
        }
        s
    }
}
