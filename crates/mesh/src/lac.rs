//! `CREA_MAILLAGE/DECOUPE_LAC`: prepares a mesh for code_aster's LAC
//! contact (`DEFI_CONTACT(ZONE=_F(ALGO_CONT='LAC'))`).
//!
//! LAC enforces contact weakly with one pressure per **patch**: a slave
//! face of the original mesh. The pressure unknown (LAGS_C) lives on nodes
//! inside the patch, so linear cells are cut to make room for them
//! (code_aster's `cppagn` family):
//!
//! - SEG3 face of a TRIA6/QUAD8 cell: nothing changes; the patch is the
//!   face, its pressure node the face's middle node (node 3).
//! - SEG2 face of a TRIA3 cell: a node is added at the face's middle; the
//!   face becomes two SEG2, the triangle two triangles (`cptr03`).
//! - SEG2 face of a QUAD4 cell: two nodes at the face's thirds and two
//!   inside the quadrangle (at the thirds of its middle line); the face
//!   becomes three SEG2 and the quadrangle four QUAD4 (`cpqu04`); both face
//!   nodes carry the patch's pressure.
//!
//! Cell ids are kept: the first piece of a cut cell keeps the id (and the
//! name) of the cell it comes from, the other pieces are appended. Cell
//! groups holding a cut cell hold all its pieces; node groups are copied
//! unchanged (as code_aster does). 3D slave faces (TRIA3/6, QUAD4/8/9) and
//! the volume cells holding them are cut by module `lac3d`.

use std::collections::{BTreeSet, HashMap, HashSet};

use crate::error::{suggest, GroupKind, MeshError};
use crate::lac3d::{DecoupeHexa, LinearCells, ReferenceCells};
use crate::model::{Cell, CellId, CellType, Mesh, NodeId};

/// One LAC patch: the pieces of an original slave face.
#[derive(Clone, Debug, PartialEq)]
pub struct LacPatch {
    /// The slave face this patch was made from (its id is kept by the
    /// first piece).
    pub face: CellId,
    /// The slave cells of the patch (the face's pieces, in order along it).
    pub cells: Vec<CellId>,
    /// The nodes carrying the patch's pressure (LAGS_C).
    pub pressure_nodes: Vec<NodeId>,
}

/// The patches of one slave group (one `GROUP_MA_ESCL` of DECOUPE_LAC, the
/// slave side of one LAC contact zone).
#[derive(Clone, Debug, PartialEq)]
pub struct LacZonePatches {
    pub group: String,
    pub patches: Vec<LacPatch>,
}

/// What DECOUPE_LAC records beside the mesh (code_aster's `.PATCH`,
/// `.CONOPA`, `.COMAPA`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LacPatches {
    pub zones: Vec<LacZonePatches>,
}

impl LacPatches {
    /// The patches of the slave group `group`.
    pub fn zone(&self, group: &str) -> Option<&LacZonePatches> {
        self.zones.iter().find(|z| z.group == group)
    }
}

/// How DECOUPE_LAC cuts: `DECOUPE_HEXA` and the reference cells that place
/// the new nodes of 3D cuts (`aster-fem` gives every type; the default,
/// [`LinearCells`], knows the linear volumes only).
#[derive(Clone, Copy)]
pub struct LacOptions<'a> {
    pub hexa: DecoupeHexa,
    pub reference: &'a dyn ReferenceCells,
}

impl Default for LacOptions<'_> {
    fn default() -> Self {
        LacOptions {
            hexa: DecoupeHexa::Pyra,
            reference: &LinearCells,
        }
    }
}

/// Cuts the slave faces of `slave_groups` for LAC contact (see the module
/// documentation), with the default options. Errors name the group and cell
/// that cannot be cut.
pub fn decoupe_lac(mesh: &Mesh, slave_groups: &[&str]) -> Result<(Mesh, LacPatches), MeshError> {
    decoupe_lac_with(mesh, slave_groups, LacOptions::default())
}

/// [`decoupe_lac`] with explicit options (`DECOUPE_HEXA`, reference cells).
pub fn decoupe_lac_with(
    mesh: &Mesh,
    slave_groups: &[&str],
    options: LacOptions<'_>,
) -> Result<(Mesh, LacPatches), MeshError> {
    let mut cutter = Cutter::new(mesh.clone());
    let mut patches = LacPatches::default();
    for &group in slave_groups {
        let g = mesh
            .group_ma(group)
            .ok_or_else(|| MeshError::UnknownGroup {
                kind: GroupKind::Cells,
                name: group.to_string(),
                suggestion: suggest(group, mesh.groups_ma.iter().map(|g| g.name.as_str())),
            })?;
        let mut seen = HashSet::new();
        let mut zone = LacZonePatches {
            group: group.to_string(),
            patches: Vec::new(),
        };
        for &face in &g.members {
            if seen.insert(face) {
                zone.patches.push(cutter.cut_face(face, group, options)?);
            }
        }
        patches.zones.push(zone);
    }
    Ok((cutter.finish(), patches))
}

/// The mesh being cut, with the node → body cell (2D and 3D cells)
/// adjacency kept up to date.
pub(crate) struct Cutter {
    pub(crate) mesh: Mesh,
    pub(crate) cells_of_node: HashMap<NodeId, Vec<CellId>>,
    /// Pieces appended for each cut cell (transitively resolved at the end).
    children: HashMap<CellId, Vec<CellId>>,
    node_names: HashSet<String>,
    cell_names: HashSet<String>,
    next_node: usize,
    next_cell: usize,
}

impl Cutter {
    fn new(mesh: Mesh) -> Cutter {
        let mut cells_of_node: HashMap<NodeId, Vec<CellId>> = HashMap::new();
        for (i, c) in mesh.cells.iter().enumerate() {
            if c.ty.dim() >= 2 {
                for n in &c.nodes {
                    cells_of_node.entry(*n).or_default().push(CellId(i as u32));
                }
            }
        }
        Cutter {
            node_names: mesh.node_names.iter().cloned().collect(),
            cell_names: mesh.cell_names.iter().cloned().collect(),
            mesh,
            cells_of_node,
            children: HashMap::new(),
            next_node: 1,
            next_cell: 1,
        }
    }

    pub(crate) fn cell_name(&self, id: CellId) -> String {
        self.mesh
            .cell_names
            .get(id.0 as usize)
            .cloned()
            .unwrap_or_else(|| format!("#{}", id.0 + 1))
    }

    fn cut_face(
        &mut self,
        face: CellId,
        group: &str,
        options: LacOptions<'_>,
    ) -> Result<LacPatch, MeshError> {
        let cell = self.mesh.cell(face).clone();
        let name = self.cell_name(face);
        let refuse = |what: String| {
            MeshError::Operation(format!(
                "DECOUPE_LAC: cell {name} ({}) of GROUP_MA_ESCL '{group}': {what}",
                cell.ty.name()
            ))
        };
        match cell.ty {
            CellType::SEG2 | CellType::SEG3 => {}
            CellType::TRIA3
            | CellType::TRIA6
            | CellType::QUAD4
            | CellType::QUAD8
            | CellType::TRIA7
            | CellType::QUAD9 => {
                let solid = self.mesh.cells.iter().any(|c| c.ty.dim() == 3);
                if solid {
                    return self.cut_face_3d(face, options.hexa, options.reference, &refuse);
                }
                return Err(refuse(
                    "in a 2D mesh the slave surface is made of edges (SEG2/SEG3); this group \
                     holds the body's cells — give the group of its contact edges"
                        .into(),
                ));
            }
            _ => {
                return Err(refuse(
                    "a LAC slave surface is made of edges (2D) or faces (3D)".into(),
                ))
            }
        }
        let (p, q) = (cell.nodes[0], cell.nodes[1]);
        let parent = self.parent_of(p, q).ok_or_else(|| {
            refuse("it is not a side of any 2D cell (a slave surface must bound a body)".into())
        })?;
        let pcell = self.mesh.cell(parent).clone();
        match (cell.ty, pcell.ty) {
            (CellType::SEG3, CellType::TRIA6 | CellType::QUAD8) => Ok(LacPatch {
                face,
                cells: vec![face],
                pressure_nodes: vec![cell.nodes[2]],
            }),
            (CellType::SEG2, CellType::TRIA3) => Ok(self.cut_tria3(face, p, q, parent, &pcell)),
            (CellType::SEG2, CellType::QUAD4) => Ok(self.cut_quad4(face, p, q, parent, &pcell)),
            (_, pt) => Err(refuse(format!(
                "its cell {} is a {}: LAC takes SEG2 edges of TRIA3/QUAD4 cells and SEG3 edges \
                 of TRIA6/QUAD8 cells",
                self.cell_name(parent),
                pt.name()
            ))),
        }
    }

    /// The 2D cell having `p` and `q` as consecutive corners.
    fn parent_of(&self, p: NodeId, q: NodeId) -> Option<CellId> {
        let cells = self.cells_of_node.get(&p)?;
        cells.iter().copied().find(|c| {
            let cell = self.mesh.cell(*c);
            edge_index(cell, p, q).is_some()
        })
    }

    pub(crate) fn add_node(&mut self, x: [f64; 3]) -> NodeId {
        let id = NodeId(self.mesh.coords.len() as u32);
        let name = loop {
            let n = format!("NL{}", self.next_node);
            self.next_node += 1;
            if self.node_names.insert(n.clone()) {
                break n;
            }
        };
        self.mesh.coords.push(x);
        self.mesh.node_names.push(name);
        id
    }

    /// Replaces cell `id` by `pieces` of type `ty`: the first keeps the id,
    /// the others are appended (and recorded as its children).
    fn replace(&mut self, id: CellId, ty: CellType, pieces: Vec<Vec<NodeId>>) -> Vec<CellId> {
        self.replace_mixed(id, pieces.into_iter().map(|p| (ty, p)).collect())
    }

    /// [`Cutter::replace`] with a type per piece.
    pub(crate) fn replace_mixed(
        &mut self,
        id: CellId,
        pieces: Vec<(CellType, Vec<NodeId>)>,
    ) -> Vec<CellId> {
        let mut ids = Vec::new();
        for n in &self.mesh.cell(id).nodes {
            if let Some(v) = self.cells_of_node.get_mut(n) {
                v.retain(|c| *c != id);
            }
        }
        for (k, (ty, nodes)) in pieces.into_iter().enumerate() {
            let cid = if k == 0 {
                self.mesh.cells[id.0 as usize] = Cell {
                    ty,
                    nodes: nodes.clone(),
                };
                id
            } else {
                let cid = CellId(self.mesh.cells.len() as u32);
                let name = loop {
                    let n = format!("ML{}", self.next_cell);
                    self.next_cell += 1;
                    if self.cell_names.insert(n.clone()) {
                        break n;
                    }
                };
                self.mesh.cells.push(Cell {
                    ty,
                    nodes: nodes.clone(),
                });
                self.mesh.cell_names.push(name);
                self.children.entry(id).or_default().push(cid);
                cid
            };
            if ty.dim() >= 2 {
                for n in &nodes {
                    self.cells_of_node.entry(*n).or_default().push(cid);
                }
            }
            ids.push(cid);
        }
        ids
    }

    fn cut_tria3(
        &mut self,
        face: CellId,
        p: NodeId,
        q: NodeId,
        parent: CellId,
        pcell: &Cell,
    ) -> LacPatch {
        let m = self.add_node(lerp(self.mesh.coord(p), self.mesh.coord(q), 0.5));
        let i = edge_index(pcell, p, q).unwrap_or(0);
        let mut first = pcell.nodes.clone();
        first[(i + 1) % 3] = m;
        let mut second = pcell.nodes.clone();
        second[i] = m;
        self.replace(parent, CellType::TRIA3, vec![first, second]);
        let cells = self.replace(face, CellType::SEG2, vec![vec![p, m], vec![m, q]]);
        LacPatch {
            face,
            cells,
            pressure_nodes: vec![m],
        }
    }

    fn cut_quad4(
        &mut self,
        face: CellId,
        p: NodeId,
        q: NodeId,
        parent: CellId,
        pcell: &Cell,
    ) -> LacPatch {
        let i = edge_index(pcell, p, q).unwrap_or(0);
        let [a, b, c, d] = [0, 1, 2, 3].map(|k| pcell.nodes[(i + k) % 4]);
        let [xa, xb, xc, xd] = [a, b, c, d].map(|n| self.mesh.coord(n));
        let e = self.add_node(lerp(xa, xb, 1.0 / 3.0));
        let f = self.add_node(lerp(xa, xb, 2.0 / 3.0));
        // The bilinear map at (∓1/3, 0), edge AB at η = −1.
        let mix = |wa: f64, wb: f64, wc: f64, wd: f64| {
            let mut x = [0.0; 3];
            for k in 0..3 {
                x[k] = (wa * xa[k] + wb * xb[k] + wc * xc[k] + wd * xd[k]) / 6.0;
            }
            x
        };
        let g = self.add_node(mix(2.0, 1.0, 1.0, 2.0));
        let h = self.add_node(mix(1.0, 2.0, 2.0, 1.0));
        self.replace(
            parent,
            CellType::QUAD4,
            vec![
                vec![a, e, g, d],
                vec![e, f, h, g],
                vec![f, b, c, h],
                vec![g, h, c, d],
            ],
        );
        // The face keeps its own direction.
        let (pieces, pressure_nodes) = if p == a {
            (vec![vec![a, e], vec![e, f], vec![f, b]], vec![e, f])
        } else {
            (vec![vec![b, f], vec![f, e], vec![e, a]], vec![f, e])
        };
        let cells = self.replace(face, CellType::SEG2, pieces);
        LacPatch {
            face,
            cells,
            pressure_nodes,
        }
    }

    /// The mesh with every cell group extended by the pieces of its cells.
    fn finish(mut self) -> Mesh {
        let descendants = |id: CellId, out: &mut Vec<CellId>| {
            let mut stack = vec![id];
            while let Some(c) = stack.pop() {
                if let Some(ch) = self.children.get(&c) {
                    for k in ch {
                        out.push(*k);
                        stack.push(*k);
                    }
                }
            }
        };
        let mut groups = std::mem::take(&mut self.mesh.groups_ma);
        for g in &mut groups {
            let mut extra = Vec::new();
            for m in &g.members {
                descendants(*m, &mut extra);
            }
            let known: BTreeSet<CellId> = g.members.iter().copied().collect();
            for c in extra {
                if !known.contains(&c) {
                    g.members.push(c);
                }
            }
        }
        self.mesh.groups_ma = groups;
        self.mesh
    }
}

/// Local index i such that the cell's corners i, i+1 (cyclic) are `p`, `q`
/// in either order.
fn edge_index(cell: &Cell, p: NodeId, q: NodeId) -> Option<usize> {
    let corners = match cell.ty {
        CellType::TRIA3 | CellType::TRIA6 | CellType::TRIA7 => 3,
        CellType::QUAD4 | CellType::QUAD8 | CellType::QUAD9 => 4,
        _ => return None,
    };
    (0..corners).find(|&i| {
        let (a, b) = (cell.nodes[i], cell.nodes[(i + 1) % corners]);
        (a == p && b == q) || (a == q && b == p)
    })
}

fn lerp(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [
        a[0] + t * (b[0] - a[0]),
        a[1] + t * (b[1] - a[1]),
        a[2] + t * (b[2] - a[2]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Group;

    /// Two cells side by side on [0,2]×[0,1] (TRIA3 pair or one QUAD4 on
    /// the left), bottom edge(s) in group "ESCL".
    fn mesh(quad: bool) -> Mesh {
        let coords = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let cells = if quad {
            vec![
                Cell {
                    ty: CellType::QUAD4,
                    nodes: vec![NodeId(0), NodeId(1), NodeId(2), NodeId(3)],
                },
                Cell {
                    ty: CellType::SEG2,
                    nodes: vec![NodeId(1), NodeId(0)],
                },
            ]
        } else {
            vec![
                Cell {
                    ty: CellType::TRIA3,
                    nodes: vec![NodeId(0), NodeId(1), NodeId(2)],
                },
                Cell {
                    ty: CellType::TRIA3,
                    nodes: vec![NodeId(0), NodeId(2), NodeId(3)],
                },
                Cell {
                    ty: CellType::SEG2,
                    nodes: vec![NodeId(0), NodeId(1)],
                },
            ]
        };
        let n = cells.len();
        Mesh {
            dim: 2,
            node_names: (1..=4).map(|i| format!("N{i}")).collect(),
            cell_names: (1..=n).map(|i| format!("M{i}")).collect(),
            coords,
            groups_ma: vec![
                Group {
                    name: "ESCL".into(),
                    members: vec![CellId(n as u32 - 1)],
                },
                Group {
                    name: "BODY".into(),
                    members: (0..n as u32 - 1).map(CellId).collect(),
                },
            ],
            cells,
            groups_no: vec![],
        }
    }

    fn area(m: &Mesh, c: CellId) -> f64 {
        let cell = m.cell(c);
        let p: Vec<[f64; 3]> = cell.nodes.iter().map(|n| m.coord(*n)).collect();
        let k = p.len();
        (0..k)
            .map(|i| p[i][0] * p[(i + 1) % k][1] - p[(i + 1) % k][0] * p[i][1])
            .sum::<f64>()
            / 2.0
    }

    #[test]
    fn tria3_face_is_halved_with_a_pressure_node_in_the_middle() {
        let (m, patches) = decoupe_lac(&mesh(false), &["ESCL"]).unwrap();
        assert_eq!(m.coords.len(), 5);
        assert_eq!(m.cells.len(), 5);
        let z = patches.zone("ESCL").unwrap();
        assert_eq!(z.patches.len(), 1);
        let p = &z.patches[0];
        assert_eq!(p.cells.len(), 2);
        assert_eq!(m.coord(p.pressure_nodes[0]), [0.5, 0.0, 0.0]);
        // The face's pieces follow it; the body keeps its area and orientation.
        assert_eq!(m.cell(p.cells[0]).nodes, vec![NodeId(0), NodeId(4)]);
        assert_eq!(m.cell(p.cells[1]).nodes, vec![NodeId(4), NodeId(1)]);
        let body = &m.group_ma("BODY").unwrap().members;
        assert_eq!(body.len(), 3);
        let total: f64 = body.iter().map(|c| area(&m, *c)).sum();
        assert!((total - 1.0).abs() < 1e-14);
        assert!(body.iter().all(|c| area(&m, *c) > 0.0));
        assert_eq!(m.group_ma("ESCL").unwrap().members.len(), 2);
    }

    #[test]
    fn quad4_face_is_cut_in_three_and_the_cell_in_four() {
        let (m, patches) = decoupe_lac(&mesh(true), &["ESCL"]).unwrap();
        assert_eq!(m.coords.len(), 8);
        assert_eq!(m.cells.len(), 2 + 5);
        let p = &patches.zones[0].patches[0];
        assert_eq!(p.cells.len(), 3);
        let xs: Vec<[f64; 3]> = p.pressure_nodes.iter().map(|n| m.coord(*n)).collect();
        // The face runs from N2 to N1: its first third is at x = 2/3.
        assert!((xs[0][0] - 2.0 / 3.0).abs() < 1e-15 && (xs[1][0] - 1.0 / 3.0).abs() < 1e-15);
        let body = &m.group_ma("BODY").unwrap().members;
        assert_eq!(body.len(), 4);
        let total: f64 = body.iter().map(|c| area(&m, *c)).sum();
        assert!((total - 1.0).abs() < 1e-14);
        assert!(body.iter().all(|c| area(&m, *c) > 0.0));
        // Interior nodes on the middle line at the thirds.
        assert_eq!(m.coord(NodeId(6)), [1.0 / 3.0, 0.5, 0.0]);
    }

    #[test]
    fn unknown_group_and_3d_faces_are_refused() {
        let e = decoupe_lac(&mesh(false), &["ESC"]).unwrap_err().to_string();
        assert!(e.contains("ESCL"), "{e}");
        let e = decoupe_lac(&mesh(false), &["BODY"])
            .unwrap_err()
            .to_string();
        assert!(e.contains("give the group of its contact edges"), "{e}");
        // In a mesh with solids, a face that bounds none is refused.
        let mut m = mesh(false);
        m.coords.push([0.0, 0.0, 1.0]);
        m.node_names.push("N5".into());
        m.cells.push(Cell {
            ty: CellType::TETRA4,
            nodes: vec![NodeId(0), NodeId(1), NodeId(3), NodeId(4)],
        });
        m.cell_names.push("M4".into());
        let e = decoupe_lac(&m, &["BODY"]).unwrap_err().to_string();
        assert!(
            e.contains("cell M1 (TRIA3)") && e.contains("not a face of any volume"),
            "{e}"
        );
    }
}
