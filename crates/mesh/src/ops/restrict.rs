//! `CREA_MAILLAGE(RESTREINT=…)`: the sub-mesh of some cell groups.
//!
//! code_aster keeps the cells of the listed `GROUP_MA` and the nodes they
//! use, in their original order; the listed cell groups (all of them with
//! `TOUT_GROUP_MA='OUI'`) and the listed node groups (all with
//! `TOUT_GROUP_NO='OUI'`) are kept, restricted to what remains. A group
//! left empty by the restriction is dropped.

use crate::error::MeshError;
use crate::{CellId, Mesh};

/// What `RESTREINT` keeps.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Restriction<'a> {
    /// Cell groups whose cells (and their nodes) are kept.
    pub groups_ma: &'a [&'a str],
    /// Node groups kept (restricted to the kept nodes).
    pub groups_no: &'a [&'a str],
    /// `TOUT_GROUP_MA='OUI'`: keep every cell group, restricted.
    pub all_groups_ma: bool,
    /// `TOUT_GROUP_NO='OUI'`: keep every node group, restricted.
    pub all_groups_no: bool,
}

impl Mesh {
    /// The restricted mesh; unknown group names are errors with a
    /// did-you-mean suggestion.
    pub fn restrict(&self, r: &Restriction<'_>) -> Result<Mesh, MeshError> {
        let cells = self.cells_of_groups(r.groups_ma)?;
        for g in r.groups_no {
            self.group_no_checked(g)?;
        }
        let mut keep_cell = vec![false; self.cells.len()];
        for c in &cells {
            keep_cell[c.0 as usize] = true;
        }
        let mut out = self.clone();
        out.groups_ma
            .retain(|g| r.all_groups_ma || r.groups_ma.contains(&g.name.as_str()));
        out.groups_no
            .retain(|g| r.all_groups_no || r.groups_no.contains(&g.name.as_str()));
        out.rewrite_cells(|id: CellId, cell| {
            if keep_cell[id.0 as usize] {
                vec![cell.clone()]
            } else {
                Vec::new()
            }
        });
        out.groups_ma.retain(|g| !g.members.is_empty());
        let used = out.used_nodes();
        out.retain_nodes(&used);
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::testmesh::two_quads;

    #[test]
    fn keeps_the_cells_of_the_groups_and_their_nodes() {
        let m = two_quads();
        let r = m
            .restrict(&Restriction {
                groups_ma: &["RIGHT"],
                groups_no: &["ALL_NODES"],
                ..Restriction::default()
            })
            .unwrap();
        assert_eq!(r.cells.len(), 1);
        assert_eq!(r.cell_names, vec!["M2"]);
        assert_eq!(r.node_count(), 4);
        assert_eq!(r.node_names, vec!["N2", "N3", "N5", "N6"]);
        // Connectivity renumbered onto the kept nodes.
        let xs: Vec<f64> = r.cells[0].nodes.iter().map(|n| r.coord(*n)[0]).collect();
        assert_eq!(xs, vec![1.0, 2.0, 2.0, 1.0]);
        let names: Vec<&str> = r.groups_ma.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, vec!["RIGHT"]);
        assert_eq!(r.group_no("ALL_NODES").unwrap().members.len(), 4);
        assert!(r.group_no("LEFT_EDGE").is_none());
    }

    #[test]
    fn tout_group_ma_keeps_every_non_empty_group() {
        let m = two_quads();
        let r = m
            .restrict(&Restriction {
                groups_ma: &["LEFT"],
                all_groups_ma: true,
                all_groups_no: true,
                ..Restriction::default()
            })
            .unwrap();
        let names: Vec<&str> = r.groups_ma.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, vec!["LEFT", "ALL"]);
        assert_eq!(r.group_ma("ALL").unwrap().members.len(), 1);
        assert_eq!(r.group_no("LEFT_EDGE").unwrap().members.len(), 2);
    }

    #[test]
    fn unknown_group_suggests() {
        let err = two_quads()
            .restrict(&Restriction {
                groups_ma: &["RIGTH"],
                ..Restriction::default()
            })
            .unwrap_err()
            .to_string();
        assert!(err.contains("RIGHT"), "{err}");
    }
}
