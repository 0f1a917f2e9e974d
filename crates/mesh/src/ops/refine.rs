//! Whole-mesh refinement and degree changes as code_aster 17's Python mesh
//! methods do them: `Mesh.refine(ntimes)` (`CREA_MAILLAGE(RAFFINEMENT=
//! _F(TOUT='OUI', NIVEAU=ntimes))`, `cmraff`), `Mesh.convertToQuadratic()`
//! and `Mesh.convertToLinear()` (`cmbqbq`), all three through code_aster's
//! `crea_maillage_module` (`Mmesh`, 2025 sources), reproduced here.
//!
//! `Mmesh` holds every cell as an entity (edge, face or volume) shared by the
//! cells that have it; with `convert_max` each new entity gets at once the
//! nodes of its richest type (SEG3, TRIA7, QUAD9, TETRA15, HEXA27, PENTA21,
//! PYRAM19): a new edge its middle node, a new face (after its edges) its
//! centre, a new volume (after its edges, then its faces) its centre. The
//! input cells are taken by classes of types (POI1, then SEG2, then
//! TRIA3/QUAD4, then the volumes), each in mesh order. Refining a cell
//! splits its edges, then (a volume) its faces, then the cell itself into
//! the sub-cells of `dividing_cell` (SEG2 → 2, TRIA3/QUAD4 → 4,
//! TETRA4/HEXA8/PENTA6 → 8, PYRAM5 → 6 PYRAM5 + 4 TETRA4), each a new
//! entity. The new mesh keeps the nodes its cells use (and the input's
//! nodes no cell used), numbered in the order they were made; its cells are
//! the leaves, the input's first, then the sub-cells in the order they were
//! made; a cell group holds the sub-cells of its cells (a group left empty is
//! dropped), a node group keeps its nodes (new nodes join no group). Nodes
//! and cells are named `N<number>` and `M<number>`, as code_aster 17 (whose
//! meshes have no names) shows them.
//!
//! New nodes are at the middle of the straight edge and at the centroid of
//! the face's or volume's corners: code_aster evaluates the parent's
//! quadratic shape functions there, the same point for the straight-sided
//! linear cells this module accepts (within rounding). Quadratic input
//! cells (whose middle nodes code_aster places on the curved parent) are
//! refused by [`Mesh::refine`] and [`Mesh::convert_to_quadratic`].

use crate::{Cell, CellId, CellType, Group, Mesh, MeshError, NodeId};
use std::collections::HashMap;

/// Corner pairs of a volume's edges in `numbering_edge`'s order (0-based).
fn volume_edges(ty: CellType) -> &'static [[usize; 2]] {
    match ty {
        CellType::TETRA4 => &[[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]],
        CellType::HEXA8 => &[
            [0, 1],
            [1, 2],
            [2, 3],
            [0, 3],
            [0, 4],
            [1, 5],
            [2, 6],
            [3, 7],
            [4, 5],
            [5, 6],
            [6, 7],
            [4, 7],
        ],
        CellType::PENTA6 => &[
            [0, 1],
            [1, 2],
            [0, 2],
            [0, 3],
            [1, 4],
            [2, 5],
            [3, 4],
            [4, 5],
            [3, 5],
        ],
        CellType::PYRAM5 => &[
            [0, 1],
            [1, 2],
            [2, 3],
            [0, 3],
            [0, 4],
            [1, 4],
            [2, 4],
            [3, 4],
        ],
        _ => &[],
    }
}

/// A volume's faces in `numbering_face`'s order: corners (0-based) and the
/// place (0-based) of the face's centre among the volume's nodes.
fn volume_faces(ty: CellType) -> &'static [(&'static [usize], usize)] {
    match ty {
        CellType::TETRA4 => &[
            (&[0, 2, 1], 10),
            (&[0, 1, 3], 11),
            (&[0, 3, 2], 12),
            (&[1, 2, 3], 13),
        ],
        CellType::HEXA8 => &[
            (&[0, 3, 2, 1], 20),
            (&[0, 1, 5, 4], 21),
            (&[1, 2, 6, 5], 22),
            (&[2, 3, 7, 6], 23),
            (&[0, 4, 7, 3], 24),
            (&[4, 5, 6, 7], 25),
        ],
        CellType::PENTA6 => &[
            (&[0, 1, 4, 3], 15),
            (&[1, 2, 5, 4], 16),
            (&[0, 3, 5, 2], 17),
            (&[0, 2, 1], 18),
            (&[3, 4, 5], 19),
        ],
        CellType::PYRAM5 => &[
            (&[0, 3, 2, 1], 13),
            (&[0, 1, 4], 14),
            (&[1, 2, 4], 15),
            (&[2, 3, 4], 16),
            (&[3, 0, 4], 17),
        ],
        _ => &[],
    }
}

/// The place (0-based) of a volume's centre among its nodes (TETRA15,
/// HEXA27, PENTA21, PYRAM19).
fn volume_centre(ty: CellType) -> usize {
    match ty {
        CellType::TETRA4 => 14,
        CellType::HEXA8 => 26,
        CellType::PENTA6 => 20,
        _ => 18,
    }
}

/// `dividing_cell`: the sub-cells of a cell, each its type and its nodes
/// (1-based places among the parent's richest-type nodes, as code_aster
/// writes them).
fn sub_cells(ty: CellType) -> &'static [(CellType, &'static [usize])] {
    use CellType::*;
    match ty {
        SEG2 => &[(SEG2, &[1, 3]), (SEG2, &[2, 3])],
        TRIA3 => &[
            (TRIA3, &[1, 4, 6]),
            (TRIA3, &[2, 5, 4]),
            (TRIA3, &[3, 6, 5]),
            (TRIA3, &[4, 5, 6]),
        ],
        QUAD4 => &[
            (QUAD4, &[1, 5, 9, 8]),
            (QUAD4, &[2, 6, 9, 5]),
            (QUAD4, &[3, 7, 9, 6]),
            (QUAD4, &[4, 8, 9, 7]),
        ],
        HEXA8 => &[
            (HEXA8, &[1, 9, 21, 12, 13, 22, 27, 25]),
            (HEXA8, &[2, 10, 21, 9, 14, 23, 27, 22]),
            (HEXA8, &[3, 11, 21, 10, 15, 24, 27, 23]),
            (HEXA8, &[4, 12, 21, 11, 16, 25, 27, 24]),
            (HEXA8, &[13, 22, 27, 25, 5, 17, 26, 20]),
            (HEXA8, &[14, 23, 27, 22, 6, 18, 26, 17]),
            (HEXA8, &[15, 24, 27, 23, 7, 19, 26, 18]),
            (HEXA8, &[16, 25, 27, 24, 8, 20, 26, 19]),
        ],
        TETRA4 => &[
            (TETRA4, &[1, 5, 7, 8]),
            (TETRA4, &[2, 6, 5, 9]),
            (TETRA4, &[3, 10, 7, 6]),
            (TETRA4, &[4, 8, 10, 9]),
            (TETRA4, &[5, 6, 7, 9]),
            (TETRA4, &[6, 9, 10, 7]),
            (TETRA4, &[8, 9, 5, 7]),
            (TETRA4, &[8, 10, 9, 7]),
        ],
        PENTA6 => &[
            (PENTA6, &[1, 7, 9, 10, 16, 18]),
            (PENTA6, &[7, 2, 8, 16, 11, 17]),
            (PENTA6, &[9, 7, 8, 18, 16, 17]),
            (PENTA6, &[9, 8, 3, 18, 17, 12]),
            (PENTA6, &[10, 16, 18, 4, 13, 15]),
            (PENTA6, &[16, 11, 17, 13, 5, 14]),
            (PENTA6, &[18, 16, 17, 15, 13, 14]),
            (PENTA6, &[18, 17, 12, 15, 14, 6]),
        ],
        PYRAM5 => &[
            (PYRAM5, &[1, 6, 14, 9, 10]),
            (PYRAM5, &[6, 2, 7, 14, 11]),
            (PYRAM5, &[3, 8, 14, 7, 12]),
            (PYRAM5, &[4, 9, 14, 8, 13]),
            (PYRAM5, &[10, 11, 12, 13, 5]),
            (PYRAM5, &[13, 12, 11, 10, 14]),
            (TETRA4, &[6, 10, 11, 14]),
            (TETRA4, &[7, 11, 12, 14]),
            (TETRA4, &[8, 12, 13, 14]),
            (TETRA4, &[9, 13, 10, 14]),
        ],
        _ => &[],
    }
}

/// The quadratic type `convertToQuadratic` gives a linear one.
fn quadratic_of(ty: CellType) -> CellType {
    match ty {
        CellType::SEG2 => CellType::SEG3,
        CellType::TRIA3 => CellType::TRIA6,
        CellType::QUAD4 => CellType::QUAD8,
        CellType::TETRA4 => CellType::TETRA10,
        CellType::PENTA6 => CellType::PENTA15,
        CellType::HEXA8 => CellType::HEXA20,
        CellType::PYRAM5 => CellType::PYRAM13,
        other => other,
    }
}

/// The class `init_mesh` reads a linear type in (POI1, segments, faces,
/// volumes); `None` for a type this module does not take.
fn read_class(ty: CellType) -> Option<u8> {
    match ty {
        CellType::POI1 => Some(0),
        CellType::SEG2 => Some(1),
        CellType::TRIA3 | CellType::QUAD4 => Some(2),
        CellType::TETRA4 | CellType::HEXA8 | CellType::PENTA6 | CellType::PYRAM5 => Some(3),
        _ => None,
    }
}

/// What a cell is in `Mmesh`.
#[derive(Clone, Copy, Debug)]
enum Entity {
    Point(u32),
    Edge(usize),
    Face(usize),
    Volume(usize),
}

struct Edge {
    /// The two ends as first given, then the middle node.
    nodes: [u32; 3],
}

struct Face {
    /// TRIA7 (corners, middles of 12 23 31, centre) or QUAD9 (corners,
    /// middles of 12 23 34 41, centre).
    nodes: Vec<u32>,
}

struct Volume {
    /// The nodes of its richest type.
    nodes: Vec<u32>,
    edges: Vec<usize>,
    faces: Vec<usize>,
}

struct MCell {
    /// The (linear) type of the cell.
    ty: CellType,
    entity: Entity,
    keep: bool,
    children: Vec<usize>,
}

/// code_aster's `Mmesh` with `convert_max`, for linear cells.
struct Mmesh {
    coords: Vec<[f64; 3]>,
    /// Input nodes no input cell uses (kept whatever happens).
    orphan: Vec<bool>,
    edges: Vec<Edge>,
    edge_at: HashMap<[u32; 2], usize>,
    faces: Vec<Face>,
    face_at: HashMap<Vec<u32>, usize>,
    volumes: Vec<Volume>,
    volume_at: HashMap<Vec<u32>, usize>,
    cells: Vec<MCell>,
}

fn sorted(nodes: &[u32]) -> Vec<u32> {
    let mut k = nodes.to_vec();
    k.sort_unstable();
    k
}

impl Mmesh {
    fn centroid(&self, nodes: &[u32]) -> [f64; 3] {
        let w = 1.0 / nodes.len() as f64;
        let mut x = [0.0; 3];
        for &n in nodes {
            let p = self.coords[n as usize];
            for k in 0..3 {
                x[k] += p[k] * w;
            }
        }
        x
    }

    fn add_node(&mut self, x: [f64; 3]) -> u32 {
        self.coords.push(x);
        self.coords.len() as u32 - 1
    }

    /// `add_edge`: the edge of these ends, made (with its middle node) if new.
    fn add_edge(&mut self, a: u32, b: u32) -> usize {
        let key = [a.min(b), a.max(b)];
        if let Some(&e) = self.edge_at.get(&key) {
            return e;
        }
        let m = self.add_node(self.centroid(&[a, b]));
        self.edges.push(Edge { nodes: [a, b, m] });
        let e = self.edges.len() - 1;
        self.edge_at.insert(key, e);
        e
    }

    /// `add_face`: the face of these corners (3 or 4), made if new: its
    /// edges, then its centre.
    fn add_face(&mut self, corners: &[u32]) -> usize {
        let key = sorted(corners);
        if let Some(&f) = self.face_at.get(&key) {
            return f;
        }
        let n = corners.len();
        let mut nodes = corners.to_vec();
        for i in 0..n {
            let e = self.add_edge(corners[i], corners[(i + 1) % n]);
            nodes.push(self.edges[e].nodes[2]);
        }
        nodes.push(self.add_node(self.centroid(corners)));
        self.faces.push(Face { nodes });
        let f = self.faces.len() - 1;
        self.face_at.insert(key, f);
        f
    }

    /// `add_volume`: the volume of these corners, made if new: its edges,
    /// then its faces, then its centre.
    fn add_volume(&mut self, ty: CellType, corners: &[u32]) -> usize {
        let key = sorted(corners);
        if let Some(&v) = self.volume_at.get(&key) {
            return v;
        }
        let mut nodes = vec![u32::MAX; volume_centre(ty) + 1];
        nodes[..corners.len()].copy_from_slice(corners);
        let mut edges = Vec::new();
        for (i, [a, b]) in volume_edges(ty).iter().enumerate() {
            let e = self.add_edge(corners[*a], corners[*b]);
            nodes[corners.len() + i] = self.edges[e].nodes[2];
            edges.push(e);
        }
        let mut faces = Vec::new();
        for (local, centre) in volume_faces(ty) {
            let fc: Vec<u32> = local.iter().map(|&i| corners[i]).collect();
            let f = self.add_face(&fc);
            nodes[*centre] = *self.faces[f].nodes.last().unwrap_or(&u32::MAX);
            faces.push(f);
        }
        nodes[volume_centre(ty)] = self.add_node(self.centroid(corners));
        self.volumes.push(Volume {
            nodes,
            edges,
            faces,
        });
        let v = self.volumes.len() - 1;
        self.volume_at.insert(key, v);
        v
    }

    /// `init_mesh` with `convert_max`: every input cell as an entity, read
    /// class by class.
    fn init(mesh: &Mesh, what: &str) -> Result<Mmesh, MeshError> {
        let mut classes: Vec<(u8, usize)> = Vec::with_capacity(mesh.cells.len());
        for (i, c) in mesh.cells.iter().enumerate() {
            let class = read_class(c.ty).ok_or_else(|| {
                MeshError::Operation(format!(
                    "{what}: cell {} is a {}: aster takes meshes of linear cells (POI1, SEG2, TRIA3, QUAD4, TETRA4, HEXA8, PENTA6, PYRAM5) — convertToLinear() first",
                    mesh.cell_name(CellId(i as u32)),
                    c.ty.name()
                ))
            })?;
            classes.push((class, i));
        }
        classes.sort();
        let mut mm = Mmesh {
            coords: mesh.coords.clone(),
            orphan: vec![true; mesh.coords.len()],
            edges: Vec::new(),
            edge_at: HashMap::new(),
            faces: Vec::new(),
            face_at: HashMap::new(),
            volumes: Vec::new(),
            volume_at: HashMap::new(),
            cells: Vec::with_capacity(mesh.cells.len()),
        };
        let mut entities = vec![Entity::Point(0); mesh.cells.len()];
        for (_, i) in classes {
            let c = &mesh.cells[i];
            let nodes: Vec<u32> = c.nodes.iter().map(|n| n.0).collect();
            entities[i] = match c.ty.dim() {
                0 => Entity::Point(nodes[0]),
                1 => Entity::Edge(mm.add_edge(nodes[0], nodes[1])),
                2 => Entity::Face(mm.add_face(&nodes)),
                _ => Entity::Volume(mm.add_volume(c.ty, &nodes)),
            };
        }
        for c in &mesh.cells {
            for n in &c.nodes {
                mm.orphan[n.0 as usize] = false;
            }
        }
        mm.cells = mesh
            .cells
            .iter()
            .zip(entities)
            .map(|(c, entity)| MCell {
                ty: c.ty,
                entity,
                keep: true,
                children: Vec::new(),
            })
            .collect();
        Ok(mm)
    }

    /// `refine_cell`: the cell's edges split, then (a volume) its faces,
    /// then the cell into its sub-cells.
    fn refine_cell(&mut self, i: usize) {
        let cell_ty = self.cells[i].ty;
        let entity = self.cells[i].entity;
        let (edges, faces, parent): (Vec<usize>, Vec<usize>, Vec<u32>) = match entity {
            Entity::Point(_) => return,
            Entity::Edge(e) => (Vec::new(), Vec::new(), self.edges[e].nodes.to_vec()),
            Entity::Face(f) => {
                let nodes = self.faces[f].nodes.clone();
                let n = nodes.len() / 2;
                // The face's edges, in its order (made with the face).
                let edges = (0..n)
                    .filter_map(|k| {
                        let (a, b) = (nodes[k], nodes[(k + 1) % n]);
                        self.edge_at.get(&[a.min(b), a.max(b)]).copied()
                    })
                    .collect();
                (edges, Vec::new(), nodes)
            }
            Entity::Volume(v) => (
                self.volumes[v].edges.clone(),
                self.volumes[v].faces.clone(),
                self.volumes[v].nodes.clone(),
            ),
        };
        for e in edges {
            let [a, b, m] = self.edges[e].nodes;
            self.add_edge(a, m);
            self.add_edge(b, m);
        }
        for f in faces {
            let nodes = self.faces[f].nodes.clone();
            let ty = if nodes.len() == 9 {
                CellType::QUAD4
            } else {
                CellType::TRIA3
            };
            for (_, loc) in sub_cells(ty) {
                let corners: Vec<u32> = loc.iter().map(|&k| nodes[k - 1]).collect();
                self.add_face(&corners);
            }
        }
        self.cells[i].keep = false;
        for (sub_ty, loc) in sub_cells(cell_ty) {
            let corners: Vec<u32> = loc.iter().map(|&k| parent[k - 1]).collect();
            let entity = match entity {
                Entity::Edge(_) => Entity::Edge(self.add_edge(corners[0], corners[1])),
                Entity::Face(_) => Entity::Face(self.add_face(&corners)),
                _ => Entity::Volume(self.add_volume(*sub_ty, &corners)),
            };
            self.cells.push(MCell {
                ty: *sub_ty,
                entity,
                keep: true,
                children: Vec::new(),
            });
            let child = self.cells.len() - 1;
            self.cells[i].children.push(child);
        }
    }

    /// The nodes of a cell of type `ty` (the linear type or its quadratic
    /// one) on its entity.
    fn cell_nodes(&self, entity: Entity, ty: CellType) -> Vec<u32> {
        let all: &[u32] = match entity {
            Entity::Point(n) => return vec![n],
            Entity::Edge(e) => &self.edges[e].nodes,
            Entity::Face(f) => &self.faces[f].nodes,
            Entity::Volume(v) => &self.volumes[v].nodes,
        };
        all[..ty.node_count()].to_vec()
    }

    /// The leaves under a cell, depth first (`sub_cells`).
    fn leaves(&self, i: usize, out: &mut Vec<usize>) {
        if self.cells[i].keep {
            out.push(i);
        } else {
            for &c in &self.cells[i].children {
                self.leaves(c, out);
            }
        }
    }

    /// `update` + `copy_mesh`: the kept cells (each as `convert` types it)
    /// and the nodes they use (with the input's orphans), numbered in the
    /// order they were made; groups carried over.
    fn output(&self, input: &Mesh, convert: impl Fn(CellType) -> CellType) -> Mesh {
        let cells: Vec<(usize, Cell)> = self
            .cells
            .iter()
            .enumerate()
            .filter(|(_, c)| c.keep)
            .map(|(i, c)| {
                let ty = convert(c.ty);
                let nodes = self.cell_nodes(c.entity, ty);
                (
                    i,
                    Cell {
                        ty,
                        nodes: nodes.into_iter().map(NodeId).collect(),
                    },
                )
            })
            .collect();
        let mut keep = self.orphan.clone();
        keep.resize(self.coords.len(), false);
        for (_, c) in &cells {
            for n in &c.nodes {
                keep[n.0 as usize] = true;
            }
        }
        let mut new_id = vec![None; self.coords.len()];
        let mut coords = Vec::new();
        for (i, k) in keep.iter().enumerate() {
            if *k {
                new_id[i] = Some(NodeId(coords.len() as u32));
                coords.push(self.coords[i]);
            }
        }
        let mut cell_id = vec![None; self.cells.len()];
        for (k, (i, _)) in cells.iter().enumerate() {
            cell_id[*i] = Some(CellId(k as u32));
        }
        let groups_ma = input
            .groups_ma
            .iter()
            .filter_map(|g| {
                let mut leaves = Vec::new();
                for c in &g.members {
                    self.leaves(c.0 as usize, &mut leaves);
                }
                let members: Vec<CellId> = leaves.iter().filter_map(|&l| cell_id[l]).collect();
                (!members.is_empty()).then(|| Group {
                    name: g.name.clone(),
                    members,
                })
            })
            .collect();
        let groups_no = input
            .groups_no
            .iter()
            .filter_map(|g| {
                let members: Vec<NodeId> = g
                    .members
                    .iter()
                    .filter_map(|n| new_id[n.0 as usize])
                    .collect();
                (!members.is_empty()).then(|| Group {
                    name: g.name.clone(),
                    members,
                })
            })
            .collect();
        let cells: Vec<Cell> = cells
            .into_iter()
            .map(|(_, mut c)| {
                for n in &mut c.nodes {
                    // Every node of a kept cell is kept.
                    *n = new_id[n.0 as usize].unwrap_or(*n);
                }
                c
            })
            .collect();
        Mesh {
            dim: input.dim,
            node_names: (1..=coords.len()).map(|i| format!("N{i}")).collect(),
            coords,
            cell_names: (1..=cells.len()).map(|i| format!("M{i}")).collect(),
            cells,
            groups_ma,
            groups_no,
        }
    }
}

impl Mesh {
    /// `Mesh.refine(ntimes)`: every cell (but points) split `ntimes` times,
    /// as code_aster does it (module doc). Refused (with the cell named) on
    /// a mesh with a cell that is not linear.
    pub fn refine(&self, ntimes: usize) -> Result<Mesh, MeshError> {
        let mut mm = Mmesh::init(self, "refine")?;
        for _ in 0..ntimes {
            let n = mm.cells.len();
            for i in 0..n {
                if mm.cells[i].keep && mm.cells[i].ty.dim() > 0 {
                    mm.refine_cell(i);
                }
            }
        }
        Ok(mm.output(self, |t| t))
    }

    /// `Mesh.convertToQuadratic()`: every linear cell made quadratic
    /// (SEG2→SEG3, TRIA3→TRIA6, QUAD4→QUAD8, TETRA4→TETRA10,
    /// PENTA6→PENTA15, HEXA8→HEXA20, PYRAM5→PYRAM13) with code_aster's
    /// numbering of the new nodes (module doc). Refused on a mesh with a
    /// cell that is not linear.
    pub fn convert_to_quadratic(&self) -> Result<Mesh, MeshError> {
        let mm = Mmesh::init(self, "convertToQuadratic")?;
        Ok(mm.output(self, quadratic_of))
    }

    /// `Mesh.convertToLinear()`: every quadratic cell made linear; the nodes
    /// no cell uses any more are removed, those no input cell used are kept
    /// (`update`'s orphans), in their order; a node group left empty is
    /// dropped; nodes and cells renamed `N<number>`, `M<number>`.
    pub fn convert_to_linear(&self) -> Mesh {
        let mut out = self.clone();
        let all: Vec<CellId> = (0..self.cells.len() as u32).map(CellId).collect();
        let orphans: Vec<bool> = self.used_nodes().into_iter().map(|u| !u).collect();
        out.linearise(&all, orphans);
        out.groups_no.retain(|g| !g.members.is_empty());
        out.groups_ma.retain(|g| !g.members.is_empty());
        out.node_names = (1..=out.coords.len()).map(|i| format!("N{i}")).collect();
        out.cell_names = (1..=out.cells.len()).map(|i| format!("M{i}")).collect();
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit(ty: CellType, coords: Vec<[f64; 3]>, dim: u8) -> Mesh {
        let n = coords.len();
        Mesh {
            dim,
            node_names: (1..=n).map(|i| format!("N{i}")).collect(),
            coords,
            cells: vec![Cell {
                ty,
                nodes: (0..n as u32).map(NodeId).collect(),
            }],
            cell_names: vec!["M1".into()],
            groups_ma: vec![Group {
                name: "ALL".into(),
                members: vec![CellId(0)],
            }],
            groups_no: vec![Group {
                name: "FIRST".into(),
                members: vec![NodeId(0)],
            }],
        }
    }

    fn measure(m: &Mesh) -> f64 {
        m.cells
            .iter()
            .map(|c| {
                let p: Vec<[f64; 3]> = c.nodes.iter().map(|n| m.coord(*n)).collect();
                let d =
                    |a: usize, b: usize| [p[b][0] - p[a][0], p[b][1] - p[a][1], p[b][2] - p[a][2]];
                let det = |u: [f64; 3], v: [f64; 3], w: [f64; 3]| {
                    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                        + u[2] * (v[0] * w[1] - v[1] * w[0])
                };
                match c.ty {
                    CellType::TETRA4 => det(d(0, 1), d(0, 2), d(0, 3)) / 6.0,
                    CellType::TRIA3 => {
                        let (u, v) = (d(0, 1), d(0, 2));
                        (u[0] * v[1] - u[1] * v[0]) / 2.0
                    }
                    _ => f64::NAN,
                }
            })
            .sum()
    }

    #[test]
    fn tetra_refined_twice_keeps_volume_orientation_and_counts() {
        let m = unit(
            CellType::TETRA4,
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            3,
        );
        for (n, nodes) in [(1, 10), (2, 35)] {
            let r = m.refine(n).unwrap();
            assert_eq!(r.cells.len(), 8usize.pow(n as u32));
            // Nodes of a tetrahedron split k times per edge: (k+1)(k+2)(k+3)/6.
            assert_eq!(r.coords.len(), nodes);
            assert!((measure(&r) - 1.0 / 6.0).abs() < 1e-15);
            // Every sub-tetrahedron positively oriented, as the parent.
            let pos = r.cells.iter().all(|c| {
                let one = Mesh {
                    cells: vec![c.clone()],
                    ..r.clone()
                };
                measure(&one) > 0.0
            });
            assert!(pos);
            assert_eq!(r.group_ma("ALL").unwrap().members.len(), r.cells.len());
            assert_eq!(r.group_no("FIRST").unwrap().members, vec![NodeId(0)]);
        }
    }

    #[test]
    fn tria_refined_new_nodes_at_edge_middles_in_code_aster_order() {
        let m = unit(
            CellType::TRIA3,
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            2,
        );
        let r = m.refine(1).unwrap();
        // Middles of 12, 23, 31 then the (unused, dropped) centre.
        assert_eq!(r.coords[3], [0.5, 0.0, 0.0]);
        assert_eq!(r.coords[4], [0.5, 0.5, 0.0]);
        assert_eq!(r.coords[5], [0.0, 0.5, 0.0]);
        assert_eq!(r.coords.len(), 6);
        let nodes = crate::ops::testmesh::one_based(&r);
        assert_eq!(
            nodes,
            vec![vec![1, 4, 6], vec![2, 5, 4], vec![3, 6, 5], vec![4, 5, 6]]
        );
        assert!((measure(&r) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn quadratic_cells_are_refused() {
        let mut m = unit(
            CellType::TRIA3,
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            2,
        );
        let q = m.convert_to_quadratic().unwrap();
        assert_eq!(q.cells[0].ty, CellType::TRIA6);
        assert_eq!(q.coords.len(), 6);
        assert!(q.refine(1).is_err());
        let back = q.convert_to_linear();
        m.cell_names = vec!["M1".into()];
        assert_eq!(back.cells, m.cells);
        assert_eq!(back.coords, m.coords);
    }
}
