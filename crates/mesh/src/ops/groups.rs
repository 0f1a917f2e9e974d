//! Group look-ups and `DEFI_GROUP` operations (`CREA_GROUP_NO`,
//! `CREA_GROUP_MA`, `DETR_GROUP_*`), as plain functions on [`Mesh`]: the
//! runner maps command keywords onto them.
//!
//! Creating a group whose name exists replaces it (code_aster warns and
//! overwrites); the functions return the names they replaced so the caller
//! can warn too.

use crate::error::{suggest, GroupKind, MeshError};
use crate::{CellId, Group, Mesh, NodeId};

impl Mesh {
    /// The cell group `name`, or an error with a did-you-mean suggestion.
    pub fn group_ma_checked(&self, name: &str) -> Result<&Group<CellId>, MeshError> {
        self.group_ma(name).ok_or_else(|| MeshError::UnknownGroup {
            kind: GroupKind::Cells,
            name: name.to_string(),
            suggestion: suggest(name, self.groups_ma.iter().map(|g| g.name.as_str())),
        })
    }

    /// The node group `name`, or an error with a did-you-mean suggestion.
    pub fn group_no_checked(&self, name: &str) -> Result<&Group<NodeId>, MeshError> {
        self.group_no(name).ok_or_else(|| MeshError::UnknownGroup {
            kind: GroupKind::Nodes,
            name: name.to_string(),
            suggestion: suggest(name, self.groups_no.iter().map(|g| g.name.as_str())),
        })
    }

    /// A node by name (`NOEUD=`), with code_aster 17's positional names
    /// ([`positional_name`]).
    pub fn node_by_name(&self, name: &str) -> Result<NodeId, MeshError> {
        // A node's `N<k>` is code_aster 17's k-th node, whatever the file
        // names it (GMSH tags); a cell's file name comes first.
        let k = name
            .strip_prefix('N')
            .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|d| d.parse::<usize>().ok())
            .filter(|&k| k >= 1 && k <= self.node_names.len());
        k.map(|k| k - 1)
            .or_else(|| positional_name(&self.node_names, name, 'N'))
            .map(|i| NodeId(i as u32))
            .ok_or_else(|| self.name_error(name, "node", &self.node_names))
    }

    /// A cell by name (`MAILLE=`), with code_aster 17's positional names
    /// ([`positional_name`]).
    pub fn cell_by_name(&self, name: &str) -> Result<CellId, MeshError> {
        positional_name(&self.cell_names, name, 'M')
            .map(|i| CellId(i as u32))
            .ok_or_else(|| self.name_error(name, "cell", &self.cell_names))
    }

    fn name_error(&self, name: &str, kind: &'static str, names: &[String]) -> MeshError {
        MeshError::UnknownName {
            kind,
            name: name.to_string(),
            suggestion: suggest(name, names.iter().map(String::as_str)),
        }
    }

    /// The nodes of some cells, each once, in increasing node number.
    pub fn nodes_of_cells(&self, cells: &[CellId]) -> Vec<NodeId> {
        let mut seen = vec![false; self.coords.len()];
        for c in cells {
            if let Some(cell) = self.cells.get(c.0 as usize) {
                for n in &cell.nodes {
                    if let Some(s) = seen.get_mut(n.0 as usize) {
                        *s = true;
                    }
                }
            }
        }
        seen.iter()
            .enumerate()
            .filter(|(_, &s)| s)
            .map(|(i, _)| NodeId(i as u32))
            .collect()
    }

    /// The cells of the named groups, in group order, each once.
    pub fn cells_of_groups(&self, groups: &[&str]) -> Result<Vec<CellId>, MeshError> {
        let mut out = Vec::new();
        let mut seen = vec![false; self.cells.len()];
        for g in groups {
            for &c in &self.group_ma_checked(g)?.members {
                if !std::mem::replace(&mut seen[c.0 as usize], true) {
                    out.push(c);
                }
            }
        }
        Ok(out)
    }

    /// The nodes of the named node groups, in group order, each once.
    pub fn nodes_of_groups(&self, groups: &[&str]) -> Result<Vec<NodeId>, MeshError> {
        let mut out = Vec::new();
        let mut seen = vec![false; self.coords.len()];
        for g in groups {
            for &n in &self.group_no_checked(g)?.members {
                if !std::mem::replace(&mut seen[n.0 as usize], true) {
                    out.push(n);
                }
            }
        }
        Ok(out)
    }

    /// Add or replace a node group; `true` when it replaced one.
    pub fn set_group_no(&mut self, name: &str, members: Vec<NodeId>) -> bool {
        set_group(&mut self.groups_no, name, members)
    }

    /// Add or replace a cell group; `true` when it replaced one.
    pub fn set_group_ma(&mut self, name: &str, members: Vec<CellId>) -> bool {
        set_group(&mut self.groups_ma, name, members)
    }

    /// `CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI')`: a node group for every cell
    /// group, same name, holding the nodes of its cells. Returns the names
    /// of node groups that existed and were replaced.
    pub fn crea_group_no_tout_group_ma(&mut self) -> Vec<String> {
        let made: Vec<(String, Vec<NodeId>)> = self
            .groups_ma
            .iter()
            .map(|g| (g.name.clone(), self.nodes_of_cells(&g.members)))
            .collect();
        made.into_iter()
            .filter_map(|(name, nodes)| self.set_group_no(&name, nodes).then_some(name))
            .collect()
    }

    /// `CREA_GROUP_NO=_F(GROUP_MA=(…))`: one node group per cell group, same name.
    pub fn crea_group_no_each_group_ma(
        &mut self,
        groups: &[&str],
    ) -> Result<Vec<String>, MeshError> {
        let mut made = Vec::new();
        for g in groups {
            let nodes = self.nodes_of_cells(&self.group_ma_checked(g)?.members);
            made.push((g.to_string(), nodes));
        }
        Ok(made
            .into_iter()
            .filter_map(|(name, nodes)| self.set_group_no(&name, nodes).then_some(name))
            .collect())
    }

    /// `CREA_GROUP_NO=_F(NOM=name, GROUP_MA=(…))`: the nodes of the cells of those groups.
    pub fn crea_group_no_from_group_ma(
        &mut self,
        name: &str,
        groups: &[&str],
    ) -> Result<bool, MeshError> {
        let cells = self.cells_of_groups(groups)?;
        let nodes = self.nodes_of_cells(&cells);
        Ok(self.set_group_no(name, nodes))
    }

    /// `CREA_GROUP_NO=_F(NOM=name, NOEUD=(…))`.
    pub fn crea_group_no_from_nodes(
        &mut self,
        name: &str,
        nodes: &[&str],
    ) -> Result<bool, MeshError> {
        let mut ids = Vec::with_capacity(nodes.len());
        for n in nodes {
            let id = self.node_by_name(n)?;
            if !ids.contains(&id) {
                ids.push(id);
            }
        }
        Ok(self.set_group_no(name, ids))
    }

    /// `CREA_GROUP_NO=_F(NOM=name, GROUP_NO=(…))` or `UNION=(…)`: the union, in order.
    pub fn crea_group_no_union(&mut self, name: &str, groups: &[&str]) -> Result<bool, MeshError> {
        let nodes = self.nodes_of_groups(groups)?;
        Ok(self.set_group_no(name, nodes))
    }

    /// Intersection or difference of node groups (checked names).
    fn combine_groups_no(&self, groups: &[&str], how: Combine) -> Result<Vec<NodeId>, MeshError> {
        let ids = combine(
            groups,
            self.coords.len(),
            |g| {
                self.group_no_checked(g)
                    .map(|g| g.members.iter().map(|n| n.0).collect())
            },
            how,
        )?;
        Ok(ids.into_iter().map(NodeId).collect())
    }

    /// Intersection or difference of cell groups (checked names).
    fn combine_groups_ma(&self, groups: &[&str], how: Combine) -> Result<Vec<CellId>, MeshError> {
        let ids = combine(
            groups,
            self.cells.len(),
            |g| {
                self.group_ma_checked(g)
                    .map(|g| g.members.iter().map(|c| c.0).collect())
            },
            how,
        )?;
        Ok(ids.into_iter().map(CellId).collect())
    }

    /// `CREA_GROUP_NO=_F(NOM=name, INTERSEC=(…))`: nodes in every group, in the first group's order.
    pub fn crea_group_no_intersec(
        &mut self,
        name: &str,
        groups: &[&str],
    ) -> Result<bool, MeshError> {
        let nodes = self.combine_groups_no(groups, Combine::Intersection)?;
        Ok(self.set_group_no(name, nodes))
    }

    /// `CREA_GROUP_NO=_F(NOM=name, DIFFE=(…))`: nodes of the first group in none of the others.
    pub fn crea_group_no_diffe(&mut self, name: &str, groups: &[&str]) -> Result<bool, MeshError> {
        let nodes = self.combine_groups_no(groups, Combine::Difference)?;
        Ok(self.set_group_no(name, nodes))
    }

    /// `CREA_GROUP_MA=_F(NOM=name, MAILLE=(…))`.
    pub fn crea_group_ma_from_cells(
        &mut self,
        name: &str,
        cells: &[&str],
    ) -> Result<bool, MeshError> {
        let mut ids = Vec::with_capacity(cells.len());
        for c in cells {
            let id = self.cell_by_name(c)?;
            if !ids.contains(&id) {
                ids.push(id);
            }
        }
        Ok(self.set_group_ma(name, ids))
    }

    /// `CREA_GROUP_MA=_F(NOM=name, TOUT='OUI')`.
    pub fn crea_group_ma_tout(&mut self, name: &str) -> bool {
        let all = (0..self.cells.len() as u32).map(CellId).collect();
        self.set_group_ma(name, all)
    }

    /// `CREA_GROUP_MA=_F(NOM=name, GROUP_MA=(…))` or `UNION=(…)`.
    pub fn crea_group_ma_union(&mut self, name: &str, groups: &[&str]) -> Result<bool, MeshError> {
        let cells = self.cells_of_groups(groups)?;
        Ok(self.set_group_ma(name, cells))
    }

    /// `CREA_GROUP_MA=_F(NOM=name, INTERSEC=(…))`.
    pub fn crea_group_ma_intersec(
        &mut self,
        name: &str,
        groups: &[&str],
    ) -> Result<bool, MeshError> {
        let cells = self.combine_groups_ma(groups, Combine::Intersection)?;
        Ok(self.set_group_ma(name, cells))
    }

    /// `CREA_GROUP_MA=_F(NOM=name, DIFFE=(…))`.
    pub fn crea_group_ma_diffe(&mut self, name: &str, groups: &[&str]) -> Result<bool, MeshError> {
        let cells = self.combine_groups_ma(groups, Combine::Difference)?;
        Ok(self.set_group_ma(name, cells))
    }

    /// `DETR_GROUP_MA=_F(NOM=(…))`: unknown names are errors.
    pub fn detr_group_ma(&mut self, names: &[&str]) -> Result<(), MeshError> {
        for n in names {
            self.group_ma_checked(n)?;
        }
        self.groups_ma.retain(|g| !names.contains(&g.name.as_str()));
        Ok(())
    }

    /// `DETR_GROUP_NO=_F(NOM=(…))`: unknown names are errors.
    pub fn detr_group_no(&mut self, names: &[&str]) -> Result<(), MeshError> {
        for n in names {
            self.group_no_checked(n)?;
        }
        self.groups_no.retain(|g| !names.contains(&g.name.as_str()));
        Ok(())
    }
}

fn set_group<T>(groups: &mut Vec<Group<T>>, name: &str, members: Vec<T>) -> bool {
    match groups.iter_mut().find(|g| g.name == name) {
        Some(g) => {
            g.members = members;
            true
        }
        None => {
            groups.push(Group {
                name: name.to_string(),
                members,
            });
            false
        }
    }
}

enum Combine {
    Intersection,
    Difference,
}

/// Intersection or difference of groups, in the first group's order.
fn combine(
    groups: &[&str],
    universe: usize,
    members: impl Fn(&str) -> Result<Vec<u32>, MeshError>,
    how: Combine,
) -> Result<Vec<u32>, MeshError> {
    let Some((first, rest)) = groups.split_first() else {
        return Err(MeshError::Operation(
            "INTERSEC/DIFFE need at least one group".into(),
        ));
    };
    let base = members(first)?;
    let mut count = vec![0usize; universe];
    for g in rest {
        let mut here = vec![false; universe];
        for m in members(g)? {
            here[m as usize] = true;
        }
        for (c, h) in count.iter_mut().zip(here) {
            *c += h as usize;
        }
    }
    Ok(base
        .into_iter()
        .filter(|&m| match how {
            Combine::Intersection => count[m as usize] == rest.len(),
            Combine::Difference => count[m as usize] == 0,
        })
        .collect())
}

/// `DEFI_GROUP/CREA_GROUP_MA/TYPE_MAILLE`: which cells a new group keeps
/// (code_aster's `cgmftm`, `utflm2`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CellFilter {
    /// `'1D'`, `'2D'`, `'3D'`: cells of this topological dimension.
    Dim(u8),
    /// A cell type name (`'QUAD4'`…): cells of this type.
    Type(crate::CellType),
}

impl CellFilter {
    /// The filter `TYPE_MAILLE` names; `None` for `'TOUT'` (no filter) or
    /// a name that is neither a dimension nor a cell type.
    pub fn from_keyword(value: &str) -> Option<CellFilter> {
        match value {
            "0D" => Some(CellFilter::Dim(0)),
            "1D" => Some(CellFilter::Dim(1)),
            "2D" => Some(CellFilter::Dim(2)),
            "3D" => Some(CellFilter::Dim(3)),
            other => crate::CellType::from_name(other).map(CellFilter::Type),
        }
    }

    fn keeps(self, ty: crate::CellType) -> bool {
        match self {
            CellFilter::Dim(d) => ty.dim() == d,
            CellFilter::Type(t) => ty == t,
        }
    }
}

impl Mesh {
    /// The cells of `cells` the filter keeps, in the given order. When it
    /// keeps none, code_aster's `cgmftm` leaves the list as it was (the
    /// group is then made of every given cell, after the alarm
    /// `SOUSTRUC_36` saying it is empty): `None` says so, and the caller
    /// keeps `cells`.
    pub fn filter_cells(&self, cells: &[CellId], filter: CellFilter) -> Option<Vec<CellId>> {
        let kept: Vec<CellId> = cells
            .iter()
            .copied()
            .filter(|&c| filter.keeps(self.cell(c).ty))
            .collect();
        (!kept.is_empty()).then_some(kept)
    }
}

#[cfg(test)]
mod filter_tests {
    use super::CellFilter;
    use crate::ops::testmesh::two_quads;
    use crate::{CellId, CellType};

    #[test]
    fn type_maille_keeps_a_dimension_or_a_type() {
        let m = two_quads();
        let all = [CellId(2), CellId(0), CellId(1)];
        assert_eq!(
            m.filter_cells(&all, CellFilter::from_keyword("2D").unwrap()),
            Some(vec![CellId(0), CellId(1)])
        );
        assert_eq!(
            m.filter_cells(&all, CellFilter::from_keyword("1D").unwrap()),
            Some(vec![CellId(2)])
        );
        assert_eq!(
            m.filter_cells(&all, CellFilter::Type(CellType::QUAD4)),
            Some(vec![CellId(0), CellId(1)])
        );
        // Nothing kept: code_aster keeps the unfiltered list.
        assert_eq!(m.filter_cells(&all, CellFilter::Dim(3)), None);
        assert_eq!(CellFilter::from_keyword("TOUT"), None);
        assert_eq!(
            CellFilter::from_keyword("SEG3"),
            Some(CellFilter::Type(CellType::SEG3))
        );
    }
}

/// The position of a node or cell name, with code_aster 17's positional
/// names: its meshes keep no names, `N12` (`M12`, `prefix`) is the twelfth
/// node (cell) in the file's order, whatever the file calls it. A mesh whose
/// names are `N1`, `N2`… in order (a MED file without names, most ASTER
/// files) reads the same either way; an ASTER file naming its nodes `NO1`…
/// still has `N1`; a GMSH file, converted with its node tags as names
/// (`PRE_GMSH`), has `N8` the eighth node, not tag 8 (ssns107c, whose
/// reference values sit at the positional nodes). Other names (`NO1`,
/// `A`) are the file's. `None`: no such node (cell).
pub fn positional_name(names: &[String], name: &str, prefix: char) -> Option<usize> {
    let numbered = |n: &str| -> Option<usize> {
        let digits = n.strip_prefix(prefix)?;
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        digits.parse().ok()
    };
    let index = numbered(name)
        .and_then(|k| k.checked_sub(1))
        .filter(|&i| i < names.len());
    // The file's own name first (the project's meshes and most real ones
    // agree either way); the positional reading where the file has no
    // such name (`M1` on a mesh naming its cells `MA1`…).
    names.iter().position(|n| n == name).or(index)
}

#[cfg(test)]
mod positional_tests {
    use super::positional_name;

    fn names(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn the_file_s_name_first_then_the_position() {
        // A GMSH file converted with its tags: N8 is the eighth node.
        let gmsh = names(&["N2", "N3", "N4", "N5", "N6", "N8", "N12", "N17"]);
        // The file's name first, the position where it has none.
        assert_eq!(positional_name(&gmsh, "N8", 'N'), Some(5));
        assert_eq!(positional_name(&gmsh, "N7", 'N'), Some(6));
        assert_eq!(positional_name(&gmsh, "N12", 'N'), Some(6));
        assert_eq!(positional_name(&gmsh, "N99", 'N'), None);
        // An ASTER file's own names, and M1 for its first cell.
        let aster = names(&["MA1", "MA2", "MA3"]);
        assert_eq!(positional_name(&aster, "MA2", 'M'), Some(1));
        assert_eq!(positional_name(&aster, "M1", 'M'), Some(0));
        assert_eq!(positional_name(&aster, "M", 'M'), None);
        assert_eq!(positional_name(&aster, "M0", 'M'), None);
    }
}
