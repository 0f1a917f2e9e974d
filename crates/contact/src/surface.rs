//! A zone resolved against a mesh: its master and slave surface cells with
//! their outward orientation, its slave nodes, and the node→cell adjacency
//! that pairing and normals need.

use std::collections::{BTreeSet, HashMap};

use aster_mesh::{CellId, Mesh, NodeId};

use crate::error::{did_you_mean, ContactError};
use crate::shape::{cross, dot, interpolate, norm, scale, sub, SurfaceKind};
use crate::zone::{NormalSource, ZoneGeometry};

/// One cell of a contact surface.
#[derive(Clone, Debug)]
pub struct SurfaceCell {
    pub id: CellId,
    pub kind: SurfaceKind,
    pub nodes: Vec<NodeId>,
    /// +1 when the geometric normal (2D: (t_y, -t_x); 3D: t₁ × t₂) points out
    /// of the body the cell bounds, -1 otherwise. Found from the volume
    /// cell that holds the surface cell (+1 if there is none: then the mesh
    /// orientation, as `MODI_MAILLAGE(ORIE_PEAU=…)` leaves it, is trusted).
    pub sign: f64,
    /// A COQUE_3D QUAD9 or TRIA7 seen through its edge nodes
    /// ([`crate::zone::ZoneGeometry::coque3d_cells`]): a `Quad8` (`Tria6`)
    /// kind that is not a QUAD8 (TRIA6) cell.
    pub centre_dropped: bool,
}

/// A zone whose groups are resolved to cells and nodes.
#[derive(Clone, Debug)]
pub struct ResolvedZone {
    pub index: usize,
    pub geometry: ZoneGeometry,
    pub master: Vec<SurfaceCell>,
    pub slave: Vec<SurfaceCell>,
    /// Slave nodes taking part in contact (SANS_GROUP_NO/SANS_GROUP_MA
    /// removed), sorted.
    pub slave_nodes: Vec<NodeId>,
    /// Master nodes, sorted.
    pub master_nodes: Vec<NodeId>,
    /// The nodes of SANS_GROUP_NO and SANS_GROUP_MA, sorted.
    pub excluded_nodes: Vec<NodeId>,
    pub master_cells_of_node: HashMap<NodeId, Vec<usize>>,
    pub slave_cells_of_node: HashMap<NodeId, Vec<usize>>,
    /// Space dimension of the problem (2 or 3).
    pub space_dim: usize,
    /// The time of the current pairing (for offsets given as functions of
    /// time).
    pub time: f64,
}

impl ResolvedZone {
    /// code_aster's `CONTACT_INIT='INTERPENETRE'` threshold of a continuous
    /// zone: a point starts in contact when its signed initial gap is at
    /// most this. `cazocc` stores `DIST_MAXI` (−1 when absent),
    /// `contSetInit` (at DEFI_CONTACT) replaces a negative value by the
    /// shortest edge of the zone's own slave and master cells on the
    /// initial coordinates (`compMinMaxEdges` on their list; 0 when they
    /// have none), and `mmopti` compares the gap with 1e-6 × that value.
    pub fn contact_init_threshold(&self, mesh: &Mesh) -> f64 {
        1e-6 * self.contact_init_distance(mesh)
    }

    /// The distance `CONTACT_INIT_DIST` of the zone (see
    /// [`Self::contact_init_threshold`]): `DIST_MAXI`, or the shortest edge
    /// of the zone's slave and master cells.
    pub fn contact_init_distance(&self, mesh: &Mesh) -> f64 {
        match self.geometry.dist_maxi {
            Some(d) if d >= 0.0 => d,
            _ => {
                let cells: Vec<CellId> = self
                    .slave
                    .iter()
                    .chain(&self.master)
                    .map(|c| c.id)
                    .collect();
                mesh.edge_length_range(&cells).map_or(0.0, |(lo, _)| lo)
            }
        }
    }

    /// A zone of a problem whose dimension is the mesh's (3 when its nodes
    /// have three coordinates).
    pub fn new(index: usize, geometry: &ZoneGeometry, mesh: &Mesh) -> Result<Self, ContactError> {
        let space_dim = if mesh.dim >= 3 { 3 } else { 2 };
        Self::new_in(index, geometry, mesh, space_dim)
    }

    /// A zone of a problem of dimension `space_dim` (the model's, as
    /// code_aster's `model_ndim`: a plane model on a mesh whose nodes have
    /// three coordinates is 2D).
    pub fn new_in(
        index: usize,
        geometry: &ZoneGeometry,
        mesh: &Mesh,
        space_dim: usize,
    ) -> Result<Self, ContactError> {
        let space_dim = if space_dim >= 3 { 3 } else { 2 };
        let parents = ParentIndex::new(mesh, space_dim);
        // Nodal pairing (APPARIEMENT='NODAL') pairs nodes with nodes: point
        // cells (POI1) are contact nodes without a surface of their own.
        let nodal = geometry.appariement == crate::zone::Appariement::Nodal;
        let mut master_points = Vec::new();
        let mut slave_points = Vec::new();
        let master = surface_cells(
            mesh,
            geometry,
            &geometry.master_group,
            "GROUP_MA_MAIT",
            space_dim,
            &parents,
            nodal.then_some(&mut master_points),
        )?;
        let slave = surface_cells(
            mesh,
            geometry,
            &geometry.slave_group,
            "GROUP_MA_ESCL",
            space_dim,
            &parents,
            nodal.then_some(&mut slave_points),
        )?;

        // code_aster's CONTACT3_32 (no circular beam section) and
        // CONTACT3_39 (no shell thickness) on a slave cell.
        let offsets = [
            (
                &geometry.beam_radius,
                "DIST_POUTRE",
                "a circular beam section (SECTION='CERCLE')",
                "CONTACT3_32",
            ),
            (
                &geometry.shell_half_thickness,
                "DIST_COQUE",
                "a shell thickness (COQUE/EPAIS)",
                "CONTACT3_39",
            ),
        ];
        for (offset, keyword, what, id) in offsets {
            let Some(offset) = offset else { continue };
            if let Some(c) = slave.iter().find(|c| !offset.contains_key(&c.id)) {
                let name = mesh
                    .cell_names
                    .get(c.id.0 as usize)
                    .cloned()
                    .unwrap_or_else(|| format!("#{}", c.id.0 + 1));
                return Err(ContactError::Invalid {
                    keyword,
                    message: format!(
                        "slave cell {name} has no {what} in the zone's CARA_ELEM: {keyword} needs one (code_aster's {id})"
                    ),
                });
            }
        }
        let mut excluded = BTreeSet::new();
        for g in &geometry.excluded_node_groups {
            let group = mesh.group_no(g).ok_or_else(|| ContactError::UnknownGroup {
                keyword: "SANS_GROUP_NO",
                name: g.clone(),
                suggestion: did_you_mean(g, mesh.groups_no.iter().map(|g| g.name.as_str())),
            })?;
            excluded.extend(group.members.iter().copied());
        }
        for g in &geometry.excluded_cell_groups {
            let group = mesh.group_ma(g).ok_or_else(|| ContactError::UnknownGroup {
                keyword: "SANS_GROUP_MA",
                name: g.clone(),
                suggestion: did_you_mean(g, mesh.groups_ma.iter().map(|g| g.name.as_str())),
            })?;
            for c in &group.members {
                excluded.extend(mesh.cell(*c).nodes.iter().copied());
            }
        }

        let adjacency = |cells: &[SurfaceCell]| {
            let mut map: HashMap<NodeId, Vec<usize>> = HashMap::new();
            for (i, c) in cells.iter().enumerate() {
                for n in &c.nodes {
                    map.entry(*n).or_default().push(i);
                }
            }
            map
        };
        let master_cells_of_node = adjacency(&master);
        let slave_cells_of_node = adjacency(&slave);
        let mut master_nodes: Vec<NodeId> = master_cells_of_node.keys().copied().collect();
        master_nodes.extend(master_points);
        master_nodes.sort();
        master_nodes.dedup();
        let mut slave_nodes: Vec<NodeId> = slave_cells_of_node
            .keys()
            .copied()
            .chain(slave_points)
            .filter(|n| !excluded.contains(n))
            .collect();
        slave_nodes.sort();
        slave_nodes.dedup();

        Ok(ResolvedZone {
            time: 0.0,
            index,
            geometry: geometry.clone(),
            master,
            slave,
            slave_nodes,
            master_nodes,
            excluded_nodes: excluded.into_iter().collect(),
            master_cells_of_node,
            slave_cells_of_node,
            space_dim,
        })
    }

    /// Outward unit normal of a master (`master = true`) or slave cell at
    /// `xi`, on the geometry `x` (current node positions).
    pub fn cell_normal(
        &self,
        cell: &SurfaceCell,
        xi: [f64; 2],
        x: &[[f64; 3]],
        source: NormalSource,
    ) -> Result<[f64; 3], ContactError> {
        match source {
            NormalSource::Fixed(v) => Ok(v),
            NormalSource::Auto | NormalSource::VectY(_) => {
                let nodes: Vec<[f64; 3]> = cell.nodes.iter().map(|n| x[n.0 as usize]).collect();
                let p = interpolate(cell.kind, &nodes, xi);
                let t = p.tangents[0];
                let raw = match (source, cell.kind.dim(), self.space_dim) {
                    (NormalSource::VectY(v), 1, _) => cross(t, v),
                    // A face (code_aster's `aptgnn`, `mmnorm`): the second
                    // tangent is VECT_Y, the first the face's normal crossed
                    // with it, and the normal their cross product — the
                    // face's own (outward) normal without its component
                    // along VECT_Y, whatever the order of the face's nodes.
                    (NormalSource::VectY(v), _, _) => {
                        let n = scale(cross(p.tangents[0], p.tangents[1]), cell.sign);
                        let lv = norm(v);
                        if lv > 0.0 {
                            let w = scale(v, 1.0 / lv);
                            let along = dot(n, w);
                            [
                                n[0] - along * w[0],
                                n[1] - along * w[1],
                                n[2] - along * w[2],
                            ]
                        } else {
                            n
                        }
                    }
                    (_, 1, 2) => [t[1], -t[0], 0.0],
                    (_, 1, _) => {
                        return Err(ContactError::Invalid {
                            keyword: "VECT_MAIT",
                            message: "a segment in a 3D problem has no normal of its own; \
                                      give VECT_MAIT='VECT_Y' with MAIT_VECT_Y"
                                .into(),
                        })
                    }
                    (_, _, _) => cross(p.tangents[0], p.tangents[1]),
                };
                let n = norm(raw);
                if n > 0.0 && n.is_finite() {
                    let s = if matches!(source, NormalSource::Auto) {
                        cell.sign
                    } else {
                        1.0
                    };
                    Ok(scale(raw, s / n))
                } else {
                    Err(ContactError::Invalid {
                        keyword: "GROUP_MA_MAIT",
                        message: "a contact cell is degenerate (zero length or area)".into(),
                    })
                }
            }
        }
    }

    /// The structural offset of a slave point (`DIST_POUTRE`, `DIST_COQUE`):
    /// the radius of its slave beam cell plus half the thickness of its
    /// slave shell cell, or at a node the mean over the slave cells around
    /// it (code_aster's `cfdist`, `cfdism`); 0 without them.
    pub fn structural_gap(&self, point: &crate::pairing::SlavePoint) -> f64 {
        let g = &self.geometry;
        if g.beam_radius.is_none() && g.shell_half_thickness.is_none() {
            return 0.0;
        }
        let of = |ci: usize| {
            self.slave.get(ci).map_or(0.0, |c| {
                [&g.beam_radius, &g.shell_half_thickness]
                    .iter()
                    .filter_map(|m| m.as_ref().and_then(|m| m.get(&c.id)))
                    .sum::<f64>()
            })
        };
        match (point.cell, point.node()) {
            (Some((ci, _)), _) => of(ci),
            (None, Some(n)) => match self.slave_cells_of_node.get(&n) {
                Some(cells) if !cells.is_empty() => {
                    cells.iter().map(|&ci| of(ci)).sum::<f64>() / cells.len() as f64
                }
                _ => 0.0,
            },
            _ => 0.0,
        }
    }

    /// Averaged outward normal of a side at one of its nodes.
    pub fn nodal_normal(
        &self,
        node: NodeId,
        master: bool,
        x: &[[f64; 3]],
    ) -> Result<[f64; 3], ContactError> {
        let fixed = if master {
            self.geometry.vect_mait
        } else {
            self.geometry.vect_escl
        };
        // A fixed normal (VECT_MAIT/VECT_ESCL='FIXE') needs no cell: it is
        // the normal of a contact point (POI1) too.
        if let NormalSource::Fixed(v) = fixed {
            let l = norm(v);
            if l > 0.0 && l.is_finite() {
                return Ok(scale(v, 1.0 / l));
            }
        }
        let (cells, map, source) = if master {
            (
                &self.master,
                &self.master_cells_of_node,
                self.geometry.vect_mait,
            )
        } else {
            (
                &self.slave,
                &self.slave_cells_of_node,
                self.geometry.vect_escl,
            )
        };
        let mut sum = [0.0; 3];
        for &ci in map.get(&node).map(|v| v.as_slice()).unwrap_or(&[]) {
            let cell = &cells[ci];
            let local = cell.nodes.iter().position(|n| *n == node).unwrap_or(0);
            let xi = cell.kind.node_coords()[local];
            let n = self.cell_normal(cell, xi, x, source)?;
            sum = [sum[0] + n[0], sum[1] + n[1], sum[2] + n[2]];
        }
        let l = norm(sum);
        if l > 0.0 {
            Ok(scale(sum, 1.0 / l))
        } else if !map.contains_key(&node) {
            Err(ContactError::Invalid {
                keyword: if master {
                    "GROUP_MA_MAIT"
                } else {
                    "GROUP_MA_ESCL"
                },
                message: format!(
                    "a contact point (POI1) has no normal of its own: give {}='FIXE'",
                    if master { "VECT_MAIT" } else { "VECT_ESCL" }
                ),
            })
        } else {
            Err(ContactError::Invalid {
                keyword: if master {
                    "GROUP_MA_MAIT"
                } else {
                    "GROUP_MA_ESCL"
                },
                message: "the normals of the cells around a contact node cancel out".into(),
            })
        }
    }
}

/// Volume (3D) or face (2D) cells by node, to orient surface cells.
struct ParentIndex {
    cells_of_node: HashMap<NodeId, Vec<CellId>>,
}

impl ParentIndex {
    fn new(mesh: &Mesh, space_dim: usize) -> Self {
        let mut cells_of_node: HashMap<NodeId, Vec<CellId>> = HashMap::new();
        for (i, c) in mesh.cells.iter().enumerate() {
            if c.ty.dim() as usize == space_dim {
                for n in &c.nodes {
                    cells_of_node.entry(*n).or_default().push(CellId(i as u32));
                }
            }
        }
        ParentIndex { cells_of_node }
    }

    /// A cell holding all `nodes`.
    fn parent(&self, nodes: &[NodeId]) -> Option<CellId> {
        let first = self.cells_of_node.get(nodes.first()?)?;
        first.iter().copied().find(|c| {
            nodes[1..]
                .iter()
                .all(|n| self.cells_of_node.get(n).is_some_and(|v| v.contains(c)))
        })
    }
}

fn surface_cells(
    mesh: &Mesh,
    geometry: &ZoneGeometry,
    group: &str,
    keyword: &'static str,
    space_dim: usize,
    parents: &ParentIndex,
    mut points: Option<&mut Vec<NodeId>>,
) -> Result<Vec<SurfaceCell>, ContactError> {
    let g = mesh
        .group_ma(group)
        .ok_or_else(|| ContactError::UnknownGroup {
            keyword,
            name: group.to_string(),
            suggestion: did_you_mean(group, mesh.groups_ma.iter().map(|g| g.name.as_str())),
        })?;
    let expected = if space_dim == 2 {
        "SEG2 or SEG3 in a 2D problem"
    } else {
        "TRIA3, TRIA6, TRIA7, QUAD4, QUAD8 or QUAD9 in a 3D problem"
    };
    let mut out = Vec::with_capacity(g.members.len());
    for &id in &g.members {
        let Some(cell) = mesh.cells.get(id.0 as usize) else {
            return Err(ContactError::Invalid {
                keyword,
                message: format!(
                    "group '{group}' refers to cell #{} which does not exist",
                    id.0
                ),
            });
        };
        let name = mesh
            .cell_names
            .get(id.0 as usize)
            .cloned()
            .unwrap_or_else(|| format!("#{}", id.0));
        if cell.ty == aster_mesh::CellType::POI1 {
            if let (Some(points), Some(&n)) = (points.as_deref_mut(), cell.nodes.first()) {
                points.push(n);
                continue;
            }
        }
        let centre_dropped = matches!(
            cell.ty,
            aster_mesh::CellType::QUAD9 | aster_mesh::CellType::TRIA7
        ) && geometry.coque3d_cells.contains(&id);
        let ty = match cell.ty {
            aster_mesh::CellType::QUAD9 if centre_dropped => aster_mesh::CellType::QUAD8,
            aster_mesh::CellType::TRIA7 if centre_dropped => aster_mesh::CellType::TRIA6,
            ty => ty,
        };
        let kind = SurfaceKind::of(ty)
            .filter(|k| k.dim() + 1 == space_dim || (space_dim == 3 && k.dim() == 1))
            .ok_or(ContactError::BadCell {
                keyword,
                group: group.to_string(),
                cell: name.clone(),
                found: cell.ty.name(),
                expected,
            })?;
        if cell.nodes.len() < kind.node_count()
            || cell.nodes.iter().any(|n| n.0 as usize >= mesh.coords.len())
        {
            return Err(ContactError::Invalid {
                keyword,
                message: format!("cell {name} of group '{group}' has missing nodes"),
            });
        }
        let nodes = cell.nodes[..kind.node_count()].to_vec();
        let sign = orientation(mesh, kind, &nodes, space_dim, parents);
        out.push(SurfaceCell {
            id,
            kind,
            nodes,
            sign,
            centre_dropped,
        });
    }
    Ok(out)
}

fn orientation(
    mesh: &Mesh,
    kind: SurfaceKind,
    nodes: &[NodeId],
    space_dim: usize,
    parents: &ParentIndex,
) -> f64 {
    if kind.dim() + 1 != space_dim {
        return 1.0;
    }
    let Some(parent) = parents.parent(nodes) else {
        return 1.0;
    };
    let pts: Vec<[f64; 3]> = nodes.iter().map(|n| mesh.coord(*n)).collect();
    let p = interpolate(kind, &pts, kind.centre());
    let t = p.tangents[0];
    let raw = if space_dim == 2 {
        [t[1], -t[0], 0.0]
    } else {
        cross(p.tangents[0], p.tangents[1])
    };
    let pc = &mesh.cell(parent).nodes;
    let mut c = [0.0; 3];
    for n in pc {
        let x = mesh.coord(*n);
        c = [c[0] + x[0], c[1] + x[1], c[2] + x[2]];
    }
    let c = scale(c, 1.0 / pc.len() as f64);
    if dot(raw, sub(p.x, c)) >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_mesh::{Cell, CellType, Group};

    /// Two coincident flat TRIA7 (nodes 0–6 and 7–13, each centre last).
    fn two_tria7() -> Mesh {
        let tri = [
            [0., 0.],
            [1., 0.],
            [0., 1.],
            [0.5, 0.],
            [0.5, 0.5],
            [0., 0.5],
            [1. / 3., 1. / 3.],
        ];
        let coords: Vec<[f64; 3]> = (0..2)
            .flat_map(|_| tri.iter().map(|p| [p[0], p[1], 0.]))
            .collect();
        let cell = |o: u32| Cell {
            ty: CellType::TRIA7,
            nodes: (o..o + 7).map(NodeId).collect(),
        };
        Mesh {
            dim: 3,
            node_names: (1..=14).map(|i| format!("N{i}")).collect(),
            cell_names: vec!["M1".into(), "M2".into()],
            coords,
            cells: vec![cell(0), cell(7)],
            groups_ma: vec![
                Group {
                    name: "M".into(),
                    members: vec![CellId(0)],
                },
                Group {
                    name: "S".into(),
                    members: vec![CellId(1)],
                },
            ],
            groups_no: vec![],
        }
    }

    /// code_aster's `cflecq` drops the centre of a COQUE_3D TRIA7 from the
    /// contact nodes and `mmtypm` sees the face as a TR6; a TRIA7 of
    /// another element keeps its seven nodes.
    #[test]
    fn coque3d_tria7_faces_are_seen_as_tria6() {
        let mesh = two_tria7();
        let mut g = ZoneGeometry::new("M", "S");
        let plain = ResolvedZone::new(0, &g, &mesh).unwrap();
        assert_eq!(plain.master[0].kind, SurfaceKind::Tria7);
        assert_eq!(plain.slave_nodes.len(), 7);
        g.coque3d_cells = [CellId(0), CellId(1)].into_iter().collect();
        let z = ResolvedZone::new(0, &g, &mesh).unwrap();
        for c in z.master.iter().chain(&z.slave) {
            assert_eq!(c.kind, SurfaceKind::Tria6);
            assert!(c.centre_dropped);
            assert_eq!(c.nodes.len(), 6);
        }
        assert_eq!(z.master_nodes, (0..6).map(NodeId).collect::<Vec<_>>());
        assert_eq!(z.slave_nodes, (7..13).map(NodeId).collect::<Vec<_>>());
    }
}
