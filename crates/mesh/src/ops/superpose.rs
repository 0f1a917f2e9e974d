//! `ASSE_MAILLAGE(OPERATION='SUPERPOSE')` (code_aster's `asmasu`): two
//! meshes side by side in one.

use crate::{Cell, CellId, Group, Mesh, NodeId};

impl Mesh {
    /// The nodes and cells of `self` then of `other`, renumbered and renamed
    /// `N1…` and `M1…` in that order; the groups of `self`, then those of
    /// `other` shifted — a group of `other` whose name is taken gets its
    /// first seven characters padded with `_` and a digit 0–9 in eighth
    /// place (the first free one), as code_aster renames it.
    pub fn superpose(&self, other: &Mesh) -> Mesh {
        let (na, ma) = (self.coords.len() as u32, self.cells.len() as u32);
        let mut out = Mesh {
            dim: self.dim.max(other.dim),
            ..Mesh::default()
        };
        out.coords = self.coords.iter().chain(&other.coords).copied().collect();
        out.node_names = (1..=out.coords.len()).map(|i| format!("N{i}")).collect();
        out.cells = self.cells.clone();
        out.cells.extend(other.cells.iter().map(|c| Cell {
            ty: c.ty,
            nodes: c.nodes.iter().map(|n| NodeId(n.0 + na)).collect(),
        }));
        out.cell_names = (1..=out.cells.len()).map(|i| format!("M{i}")).collect();
        out.groups_ma = self.groups_ma.clone();
        for g in &other.groups_ma {
            let name = free_name(&g.name, |n| out.groups_ma.iter().any(|h| h.name == n));
            out.groups_ma.push(Group {
                name,
                members: g.members.iter().map(|c| CellId(c.0 + ma)).collect(),
            });
        }
        out.groups_no = self.groups_no.clone();
        for g in &other.groups_no {
            let name = free_name(&g.name, |n| out.groups_no.iter().any(|h| h.name == n));
            out.groups_no.push(Group {
                name,
                members: g.members.iter().map(|n| NodeId(n.0 + na)).collect(),
            });
        }
        out
    }
}

/// `name` if free, else code_aster's renaming (`asmasu`): the first seven
/// characters, blanks after them made `_`, and the first digit 0–9 that
/// gives a free name (the last one tried if none does).
fn free_name(name: &str, taken: impl Fn(&str) -> bool) -> String {
    if !taken(name) {
        return name.to_string();
    }
    let head: String = name.chars().take(7).collect();
    let head = head.trim_end();
    let stem = format!("{head:_<7}");
    let mut candidate = format!("{stem}9");
    for k in 0..=9 {
        let c = format!("{stem}{k}");
        if !taken(&c) {
            candidate = c;
            break;
        }
    }
    candidate
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_mail;
    use std::path::Path;

    #[test]
    fn nodes_cells_and_groups_follow_each_other() {
        let a = parse_mail(
            "COOR_2D\nA1 0 0\nA2 1 0\nFINSF\nSEG2\nS N1 N2\nFINSF\nFIN\n"
                .replace("N1", "A1")
                .replace("N2", "A2")
                .as_str(),
            Path::new("a.mail"),
        )
        .unwrap();
        let mut a = a;
        a.groups_ma.push(Group {
            name: "BORD".into(),
            members: vec![CellId(0)],
        });
        let mut b = a.clone();
        b.coords[1] = [2.0, 0.0, 0.0];
        b.groups_ma.push(Group {
            name: "BORD___0".into(),
            members: vec![CellId(0)],
        });
        let m = a.superpose(&b);
        assert_eq!(m.node_names, ["N1", "N2", "N3", "N4"]);
        assert_eq!(m.cell_names, ["M1", "M2"]);
        assert_eq!(m.cells[1].nodes, [NodeId(2), NodeId(3)]);
        let names: Vec<&str> = m.groups_ma.iter().map(|g| g.name.as_str()).collect();
        // b's BORD is renamed BORD___0, then b's BORD___0 (taken) BORD___1.
        assert_eq!(names, ["BORD", "BORD___0", "BORD___1"]);
        assert_eq!(m.groups_ma[1].members, [CellId(1)]);
    }

    #[test]
    fn renaming_keeps_seven_characters() {
        assert_eq!(free_name("LONGNAME_X", |n| n == "LONGNAME_X"), "LONGNAM0");
        assert_eq!(free_name("A", |n| n == "A" || n == "A______0"), "A______1");
        assert_eq!(free_name("FREE", |_| false), "FREE");
    }
}
