//! `DECOUPE_LAC` on 3D slave faces (code_aster's `cpte04`, `cpte10`,
//! `cphe08`/`cphe08_2`, `cphe20`/`cphe20_2`, `cphe27`, `cppt6_*`,
//! `cppt15_*`, `cppy5_*`, `cppy13_*`).
//!
//! Every cut is described in the reference space of the volume cell that
//! holds the slave face, then mapped with that cell's own shape functions
//! (code_aster places the new nodes with `reerel` on the face or the volume
//! at the same reference points):
//!
//! - **cone** cut (TRIA faces of every volume; QUAD faces with
//!   `DECOUPE_HEXA='PYRA'`, the default, and QUAD faces of pentahedra and
//!   pyramids): one node `c` at the face's centre (TRIA: the centroid,
//!   QUAD: ξ = η = 0); the face becomes one triangle per edge (`[a, b, c]`)
//!   and the volume one cell per *other* face, that face as base and `c` as
//!   apex (a triangle makes a tetrahedron, a quadrangle a pyramid): TETRA4
//!   → 3 TETRA4, HEXA8 → 5 PYRAM5, PENTA6 → 3 PYRAM5 + 1 TETRA4 (TRIA
//!   face) or 2 + 2 (QUAD face), PYRAM5 → 4 TETRA4 (base) or 1 PYRAM5 + 3
//!   TETRA4 (side). The pressure lives on `c`.
//! - **hexa** cut (`DECOUPE_HEXA='HEXA'`, HEXA8/HEXA20 only): four face
//!   nodes at the face's reference (±⅓, ±⅓) and four volume nodes half-way
//!   through the hexahedron above them; the face becomes 5 QUAD4 (four
//!   trapezoids and the inner quadrangle) and the hexahedron 6 HEXA8 (the
//!   inner one, four around it, one on top). The pressure lives on the
//!   four face nodes (code_aster ties them with identity relations).
//! - QUAD9 faces of HEXA27: nothing changes; the pressure lives on the
//!   face's centre node.
//!
//! Quadratic volumes (TETRA10, PENTA15, PYRAM13, HEXA20) are cut the same
//! way into quadratic cells: each new edge gets its middle node at the
//! middle of the edge in reference space (TRIA6/QUAD8 faces, TETRA10,
//! PYRAM13, HEXA20 volumes), which is where code_aster's tables put them.
//! Node and cell counts are code_aster's (`cppagn`): TETRA4 +1 node, +2
//! face cells, +2 volume cells; TETRA10 +5, +2, +2; HEXA8 PYRA +1, +3, +4;
//! HEXA20 PYRA +9, +3, +4; HEXA8 HEXA +8, +4, +5; HEXA20 HEXA +28, +4, +5.

use std::collections::HashMap;

use crate::lac::{Cutter, LacPatch};
use crate::ops::edges;
use crate::{CellId, CellType, MeshError, NodeId};

/// Reference cells of the volume types, code_aster's conventions: the
/// cutter needs where each node sits in reference space and the shape
/// functions that map reference points into the mesh. `aster-fem`
/// implements it for every type; [`LinearCells`] covers the linear ones.
pub trait ReferenceCells {
    /// Reference coordinates of the nodes, in code_aster's order (`None`
    /// for a type the implementation does not know).
    fn nodes(&self, ty: CellType) -> Option<Vec<[f64; 3]>>;
    /// Shape function values at the reference point `xi`.
    fn shape(&self, ty: CellType, xi: [f64; 3]) -> Option<Vec<f64>>;
}

/// The linear volumes (TETRA4, PENTA6, PYRAM5, HEXA8), with code_aster's
/// reference cells (`elrfno`/`elrfvf`): the tetrahedron's node 1 at
/// (0,1,0) and node 3 at the origin, the pentahedron extruded along ξ, the
/// pyramid's base |ξ| + |η| ≤ 1 with the apex at ζ = 1.
#[derive(Clone, Copy, Debug, Default)]
pub struct LinearCells;

impl ReferenceCells for LinearCells {
    fn nodes(&self, ty: CellType) -> Option<Vec<[f64; 3]>> {
        Some(match ty {
            CellType::TETRA4 => vec![[0., 1., 0.], [0., 0., 1.], [0., 0., 0.], [1., 0., 0.]],
            CellType::PENTA6 => vec![
                [-1., 1., 0.],
                [-1., 0., 1.],
                [-1., 0., 0.],
                [1., 1., 0.],
                [1., 0., 1.],
                [1., 0., 0.],
            ],
            CellType::PYRAM5 => vec![
                [1., 0., 0.],
                [0., 1., 0.],
                [-1., 0., 0.],
                [0., -1., 0.],
                [0., 0., 1.],
            ],
            CellType::HEXA8 => vec![
                [-1., -1., -1.],
                [1., -1., -1.],
                [1., 1., -1.],
                [-1., 1., -1.],
                [-1., -1., 1.],
                [1., -1., 1.],
                [1., 1., 1.],
                [-1., 1., 1.],
            ],
            _ => return None,
        })
    }

    fn shape(&self, ty: CellType, xi: [f64; 3]) -> Option<Vec<f64>> {
        let [x, y, z] = xi;
        Some(match ty {
            CellType::TETRA4 => vec![y, z, 1. - x - y - z, x],
            CellType::PENTA6 => {
                let (a, b) = ((1. - x) / 2., (1. + x) / 2.);
                let l = 1. - y - z;
                vec![a * y, a * z, a * l, b * y, b * z, b * l]
            }
            CellType::PYRAM5 => {
                // code_aster's rational pyramid (elrfvf 'PY5').
                let d = 4. * (1. - z);
                if d.abs() < 1e-14 {
                    vec![0., 0., 0., 0., 1.]
                } else {
                    let p = (-x + y + z - 1.) * (-x - y + z - 1.) / d;
                    let q = (-x - y + z - 1.) * (x - y + z - 1.) / d;
                    let r = (x + y + z - 1.) * (x - y + z - 1.) / d;
                    let s = (x + y + z - 1.) * (-x + y + z - 1.) / d;
                    vec![p, q, r, s, z]
                }
            }
            CellType::HEXA8 => {
                let c = self.nodes(CellType::HEXA8)?;
                c.iter()
                    .map(|p| (1. + p[0] * x) * (1. + p[1] * y) * (1. + p[2] * z) / 8.)
                    .collect()
            }
            _ => return None,
        })
    }
}

/// `DECOUPE_HEXA`: how a quadrangle of a hexahedron is cut.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DecoupeHexa {
    /// One centre node; the hexahedron becomes five pyramids (the default).
    #[default]
    Pyra,
    /// Four inner nodes; the hexahedron becomes six hexahedra.
    Hexa,
}

/// Local corner cycles of the faces of the linear volume types.
fn faces(linear: CellType) -> &'static [&'static [usize]] {
    match linear {
        CellType::TETRA4 => &[&[0, 1, 2], &[0, 1, 3], &[1, 2, 3], &[0, 2, 3]],
        CellType::PENTA6 => &[
            &[0, 1, 2],
            &[3, 4, 5],
            &[0, 1, 4, 3],
            &[1, 2, 5, 4],
            &[2, 0, 3, 5],
        ],
        CellType::PYRAM5 => &[
            &[0, 1, 2, 3],
            &[0, 1, 4],
            &[1, 2, 4],
            &[2, 3, 4],
            &[3, 0, 4],
        ],
        CellType::HEXA8 => &[
            &[0, 1, 2, 3],
            &[4, 5, 6, 7],
            &[0, 1, 5, 4],
            &[1, 2, 6, 5],
            &[2, 3, 7, 6],
            &[3, 0, 4, 7],
        ],
        _ => &[],
    }
}

/// The linear type of a volume and whether it is quadratic (TETRA10,
/// PENTA15, PYRAM13, HEXA20); `None` for types DECOUPE_LAC cannot cut.
fn volume_family(ty: CellType) -> Option<(CellType, bool)> {
    Some(match ty {
        CellType::TETRA4 => (CellType::TETRA4, false),
        CellType::TETRA10 => (CellType::TETRA4, true),
        CellType::PENTA6 => (CellType::PENTA6, false),
        CellType::PENTA15 => (CellType::PENTA6, true),
        CellType::PYRAM5 => (CellType::PYRAM5, false),
        CellType::PYRAM13 => (CellType::PYRAM5, true),
        CellType::HEXA8 => (CellType::HEXA8, false),
        CellType::HEXA20 => (CellType::HEXA8, true),
        _ => return None,
    })
}

/// A cut in the parent's reference space: linear pieces by their corner
/// reference points.
struct Plan {
    face_pieces: Vec<(CellType, Vec<[f64; 3]>)>,
    volume_pieces: Vec<(CellType, Vec<[f64; 3]>)>,
    pressure: Vec<[f64; 3]>,
}

fn mean(points: &[[f64; 3]]) -> [f64; 3] {
    let n = points.len() as f64;
    let mut m = [0.0; 3];
    for p in points {
        for c in 0..3 {
            m[c] += p[c] / n;
        }
    }
    m
}

fn mid(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [(a[0] + b[0]) / 2., (a[1] + b[1]) / 2., (a[2] + b[2]) / 2.]
}

/// Exact key of a reference point (every point of the cuts is a multiple
/// of 1/12 in each coordinate).
fn key(p: [f64; 3]) -> [i64; 3] {
    p.map(|v| (v * 3600.0).round() as i64)
}

/// Bilinear map of a quadrangle given by its four corners (QUAD4 order:
/// (−1,−1), (1,−1), (1,1), (−1,1)).
fn bilinear(c: &[[f64; 3]], s: f64, t: f64) -> [f64; 3] {
    let w = [
        (1. - s) * (1. - t) / 4.,
        (1. + s) * (1. - t) / 4.,
        (1. + s) * (1. + t) / 4.,
        (1. - s) * (1. + t) / 4.,
    ];
    let mut x = [0.0; 3];
    for (k, p) in c.iter().enumerate() {
        for d in 0..3 {
            x[d] += w[k] * p[d];
        }
    }
    x
}

/// The cone cut: centre node on the face, one piece per face edge and one
/// volume per other face of the parent.
fn cone_plan(linear: CellType, reference: &[[f64; 3]], face_local: &[usize]) -> Plan {
    let corners: Vec<[f64; 3]> = face_local.iter().map(|&k| reference[k]).collect();
    let centre = mean(&corners);
    let n = corners.len();
    let face_pieces = (0..n)
        .map(|k| {
            (
                CellType::TRIA3,
                vec![corners[k], corners[(k + 1) % n], centre],
            )
        })
        .collect();
    let mut sorted_face = face_local.to_vec();
    sorted_face.sort_unstable();
    let volume_pieces = faces(linear)
        .iter()
        .filter(|f| {
            let mut s = f.to_vec();
            s.sort_unstable();
            s != sorted_face
        })
        .map(|f| {
            let mut pts: Vec<[f64; 3]> = f.iter().map(|&k| reference[k]).collect();
            pts.push(centre);
            let ty = if f.len() == 3 {
                CellType::TETRA4
            } else {
                CellType::PYRAM5
            };
            (ty, pts)
        })
        .collect();
    Plan {
        face_pieces,
        volume_pieces,
        pressure: vec![centre],
    }
}

/// The hexa cut of a hexahedron's quadrangle (`DECOUPE_HEXA='HEXA'`).
fn hexa_plan(reference: &[[f64; 3]], face_local: &[usize]) -> Option<Plan> {
    let p: Vec<[f64; 3]> = face_local.iter().map(|&k| reference[k]).collect();
    // The corner across the hexahedron's edge from each face corner.
    let (_, hexa_edges) = edges(CellType::HEXA8)?;
    let q: Vec<[f64; 3]> = face_local
        .iter()
        .map(|&k| {
            hexa_edges.iter().find_map(|e| {
                let other = if e[0] == k {
                    e[1]
                } else if e[1] == k {
                    e[0]
                } else {
                    return None;
                };
                (!face_local.contains(&other)).then_some(reference[other])
            })
        })
        .collect::<Option<_>>()?;
    let corners = [[-1., -1.], [1., -1.], [1., 1.], [-1., 1.]];
    let f: Vec<[f64; 3]> = corners
        .iter()
        .map(|c| bilinear(&p, c[0] / 3., c[1] / 3.))
        .collect();
    let v: Vec<[f64; 3]> = corners
        .iter()
        .map(|c| {
            mid(
                bilinear(&p, c[0] / 3., c[1] / 3.),
                bilinear(&q, c[0] / 3., c[1] / 3.),
            )
        })
        .collect();
    let mut face_pieces = Vec::new();
    let mut volume_pieces = vec![(
        CellType::HEXA8,
        vec![f[0], f[1], f[2], f[3], v[0], v[1], v[2], v[3]],
    )];
    for k in 0..4 {
        let l = (k + 1) % 4;
        face_pieces.push((CellType::QUAD4, vec![p[k], p[l], f[l], f[k]]));
        volume_pieces.push((
            CellType::HEXA8,
            vec![p[k], p[l], f[l], f[k], q[k], q[l], v[l], v[k]],
        ));
    }
    face_pieces.push((CellType::QUAD4, f.clone()));
    volume_pieces.push((
        CellType::HEXA8,
        vec![v[0], v[1], v[2], v[3], q[0], q[1], q[2], q[3]],
    ));
    Some(Plan {
        face_pieces,
        volume_pieces,
        pressure: f,
    })
}

impl Cutter {
    /// The 3D cell holding every node of `face`.
    fn volume_of(&self, nodes: &[NodeId]) -> Option<CellId> {
        let first = nodes.first()?;
        self.cells_of_node.get(first)?.iter().copied().find(|c| {
            let cell = self.mesh.cell(*c);
            cell.ty.dim() == 3 && nodes.iter().all(|n| cell.nodes.contains(n))
        })
    }

    /// Cuts a 3D slave face and the volume cell holding it.
    pub(crate) fn cut_face_3d(
        &mut self,
        face: CellId,
        hexa: DecoupeHexa,
        reference: &dyn ReferenceCells,
        refuse: &dyn Fn(String) -> MeshError,
    ) -> Result<LacPatch, MeshError> {
        let cell = self.mesh.cell(face).clone();
        let parent = self.volume_of(&cell.nodes).ok_or_else(|| {
            refuse("it is not a face of any volume cell (a slave surface must bound a body)".into())
        })?;
        let pcell = self.mesh.cell(parent).clone();
        let parent_name = self.cell_name(parent);
        if (cell.ty, pcell.ty) == (CellType::QUAD9, CellType::HEXA27) {
            return Ok(LacPatch {
                face,
                cells: vec![face],
                pressure_nodes: vec![cell.nodes[8]],
            });
        }
        let wrong_pair = || {
            refuse(format!(
                "its volume cell {parent_name} is a {}: LAC cuts TRIA3/QUAD4 faces of linear \
                 volumes (TETRA4, PENTA6, PYRAM5, HEXA8), TRIA6/QUAD8 faces of quadratic ones \
                 (TETRA10, PENTA15, PYRAM13, HEXA20) and QUAD9 faces of HEXA27",
                pcell.ty.name()
            ))
        };
        let (linear, quad) = volume_family(pcell.ty).ok_or_else(wrong_pair)?;
        let corner_count = match (cell.ty, quad) {
            (CellType::TRIA3, false) | (CellType::TRIA6, true) => 3,
            (CellType::QUAD4, false) | (CellType::QUAD8, true) => 4,
            _ => return Err(wrong_pair()),
        };
        let ref_nodes = reference.nodes(pcell.ty).ok_or_else(|| {
            refuse(format!(
                "no reference cell for {} (internal: the cutter was given no shape functions \
                 for it)",
                pcell.ty.name()
            ))
        })?;
        let face_local: Vec<usize> = cell.nodes[..corner_count]
            .iter()
            .map(|n| pcell.nodes.iter().position(|m| m == n))
            .collect::<Option<_>>()
            .ok_or_else(wrong_pair)?;
        let mut sorted = face_local.clone();
        sorted.sort_unstable();
        let is_face = faces(linear).iter().any(|f| {
            let mut g = f.to_vec();
            g.sort_unstable();
            g == sorted
        });
        if !is_face {
            return Err(wrong_pair());
        }
        let plan = if corner_count == 4 && linear == CellType::HEXA8 && hexa == DecoupeHexa::Hexa {
            hexa_plan(&ref_nodes, &face_local).ok_or_else(wrong_pair)?
        } else {
            cone_plan(linear, &ref_nodes, &face_local)
        };

        // Nodes by reference point: the parent's own, then new ones.
        let mut at: HashMap<[i64; 3], NodeId> = ref_nodes
            .iter()
            .zip(&pcell.nodes)
            .map(|(p, n)| (key(*p), *n))
            .collect();
        let xs: Vec<[f64; 3]> = pcell.nodes.iter().map(|n| self.mesh.coord(*n)).collect();
        let mut node = |cutter: &mut Cutter, p: [f64; 3]| -> Result<NodeId, MeshError> {
            if let Some(n) = at.get(&key(p)) {
                return Ok(*n);
            }
            let w = reference
                .shape(pcell.ty, p)
                .ok_or_else(|| refuse(format!("no shape functions for {}", pcell.ty.name())))?;
            let mut x = [0.0; 3];
            for (k, xk) in xs.iter().enumerate() {
                for d in 0..3 {
                    x[d] += w.get(k).copied().unwrap_or(0.0) * xk[d];
                }
            }
            let id = cutter.add_node(x);
            at.insert(key(p), id);
            Ok(id)
        };
        let mut realise = |cutter: &mut Cutter,
                           pieces: &[(CellType, Vec<[f64; 3]>)]|
         -> Result<Vec<(CellType, Vec<NodeId>)>, MeshError> {
            let mut out = Vec::new();
            for (ty, corners) in pieces {
                let mut pts = corners.clone();
                let mut ty = *ty;
                if quad {
                    let (q, e) = edges(ty).ok_or_else(wrong_pair)?;
                    pts.extend(e.iter().map(|[a, b]| mid(corners[*a], corners[*b])));
                    ty = q;
                }
                let ids = pts
                    .iter()
                    .map(|p| node(cutter, *p))
                    .collect::<Result<Vec<_>, _>>()?;
                out.push((ty, ids));
            }
            Ok(out)
        };
        let face_cells = realise(self, &plan.face_pieces)?;
        let volume_cells = realise(self, &plan.volume_pieces)?;
        let pressure_nodes = plan
            .pressure
            .iter()
            .map(|p| node(self, *p))
            .collect::<Result<Vec<_>, _>>()?;
        self.replace_mixed(parent, volume_cells);
        let cells = self.replace_mixed(face, face_cells);
        Ok(LacPatch {
            face,
            cells,
            pressure_nodes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lac::{decoupe_lac_with, LacOptions};
    use crate::model::{Cell, Group, Mesh};

    /// One volume cell (nodes in code_aster order at `coords`) and one of
    /// its faces (local nodes `face`) in group "S"; the volume in "V".
    fn one_cell(ty: CellType, coords: Vec<[f64; 3]>, face_ty: CellType, face: &[usize]) -> Mesh {
        let n = coords.len();
        Mesh {
            dim: 3,
            node_names: (1..=n).map(|i| format!("N{i}")).collect(),
            coords,
            cells: vec![
                Cell {
                    ty,
                    nodes: (0..n as u32).map(NodeId).collect(),
                },
                Cell {
                    ty: face_ty,
                    nodes: face.iter().map(|&k| NodeId(k as u32)).collect(),
                },
            ],
            cell_names: vec!["M1".into(), "M2".into()],
            groups_ma: vec![
                Group {
                    name: "V".into(),
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

    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    /// Volume of a convex linear cell: cones from its centroid over its
    /// (triangulated) faces.
    fn volume(m: &Mesh, c: CellId) -> f64 {
        let cell = m.cell(c);
        let x: Vec<[f64; 3]> = cell.nodes.iter().map(|n| m.coord(*n)).collect();
        let g = mean(&x);
        faces(cell.ty)
            .iter()
            .map(|f| {
                (1..f.len() - 1)
                    .map(|k| {
                        let (a, b, d) = (x[f[0]], x[f[k]], x[f[k + 1]]);
                        dot(sub(a, g), cross(sub(b, g), sub(d, g))).abs() / 6.0
                    })
                    .sum::<f64>()
            })
            .sum()
    }

    /// Vector area of a linear face (½ Σ xₖ × xₖ₊₁).
    fn vector_area(m: &Mesh, c: CellId) -> [f64; 3] {
        let cell = m.cell(c);
        let k = if cell.ty == CellType::QUAD4 { 4 } else { 3 };
        let x: Vec<[f64; 3]> = cell.nodes[..k].iter().map(|n| m.coord(*n)).collect();
        let mut s = [0.0; 3];
        for i in 0..k {
            let c = cross(x[i], x[(i + 1) % k]);
            for d in 0..3 {
                s[d] += c[d] / 2.0;
            }
        }
        s
    }

    fn hexa_coords() -> Vec<[f64; 3]> {
        // A skewed brick, so that nothing is axis-aligned by accident.
        LinearCells
            .nodes(CellType::HEXA8)
            .unwrap()
            .iter()
            .map(|p| {
                [
                    1.0 + 2.0 * p[0] + 0.2 * p[2],
                    1.5 * p[1] + 0.1 * p[0],
                    0.7 * p[2] + 0.05 * p[1],
                ]
            })
            .collect()
    }

    /// Counts, conservation of volume and face area, orientation of the
    /// face pieces, pressure nodes inside the face.
    fn check(
        m0: &Mesh,
        hexa: DecoupeHexa,
        new_nodes: usize,
        face_pieces: usize,
        volume_pieces: usize,
        pressure: usize,
    ) -> Mesh {
        let opts = LacOptions {
            hexa,
            reference: &LinearCells,
        };
        let (m, patches) = decoupe_lac_with(m0, &["S"], opts).unwrap();
        assert_eq!(m.coords.len(), m0.coords.len() + new_nodes);
        let p = &patches.zones[0].patches[0];
        assert_eq!(p.cells.len(), face_pieces);
        assert_eq!(p.cells[0], CellId(1));
        assert_eq!(p.pressure_nodes.len(), pressure);
        let v = &m.group_ma("V").unwrap().members;
        assert_eq!(v.len(), volume_pieces);
        assert_eq!(m.cells.len(), 2 + face_pieces - 1 + volume_pieces - 1);
        let total: f64 = v.iter().map(|c| volume(&m, *c)).sum();
        let before = volume(m0, CellId(0));
        assert!(
            (total - before).abs() < 1e-12 * before,
            "{total} vs {before}"
        );
        assert!(v.iter().all(|c| volume(&m, *c) > 1e-3 * before));
        let a0 = vector_area(m0, CellId(1));
        let mut a = [0.0; 3];
        for c in &p.cells {
            let s = vector_area(&m, *c);
            assert!(dot(s, a0) > 0.0, "a face piece turned over");
            for d in 0..3 {
                a[d] += s[d];
            }
        }
        assert!(dot(sub(a, a0), sub(a, a0)).sqrt() < 1e-12 * dot(a0, a0).sqrt());
        // Pressure nodes are nodes of the face pieces, none of the original.
        for n in &p.pressure_nodes {
            assert!(n.0 as usize >= m0.coords.len());
            assert!(p.cells.iter().any(|c| m.cell(*c).nodes.contains(n)));
        }
        m
    }

    #[test]
    fn tetra4_face_gets_its_centroid_and_three_tetrahedra() {
        let x = vec![
            [0.1, 1.0, 0.0],
            [0.0, 0.2, 1.1],
            [0.0, 0.0, 0.0],
            [1.2, 0.1, 0.0],
        ];
        let m0 = one_cell(CellType::TETRA4, x.clone(), CellType::TRIA3, &[2, 3, 1]);
        let m = check(&m0, DecoupeHexa::Pyra, 1, 3, 3, 1);
        let g = m.coords[4];
        let c = mean(&[x[2], x[3], x[1]]);
        assert!(dot(sub(g, c), sub(g, c)) < 1e-28);
        assert!(m
            .cells
            .iter()
            .all(|c| matches!(c.ty, CellType::TETRA4 | CellType::TRIA3)));
    }

    #[test]
    fn hexa8_face_pyra_and_hexa_cuts() {
        let m0 = one_cell(
            CellType::HEXA8,
            hexa_coords(),
            CellType::QUAD4,
            &[0, 3, 2, 1],
        );
        // PYRA (default): centre node, 4 triangles, 5 pyramids.
        let m = check(&m0, DecoupeHexa::Pyra, 1, 4, 5, 1);
        let v = &m.group_ma("V").unwrap().members;
        assert!(v.iter().all(|c| m.cell(*c).ty == CellType::PYRAM5));
        // HEXA: 8 nodes, 5 quadrangles, 6 hexahedra; the face nodes at the
        // face's reference (±1/3, ±1/3).
        let m = check(&m0, DecoupeHexa::Hexa, 8, 5, 6, 4);
        let p = &decoupe_lac_with(
            &m0,
            &["S"],
            LacOptions {
                hexa: DecoupeHexa::Hexa,
                reference: &LinearCells,
            },
        )
        .unwrap()
        .1
        .zones[0]
            .patches[0];
        let corners: Vec<[f64; 3]> = [0, 3, 2, 1].iter().map(|&k| m0.coords[k]).collect();
        let want = bilinear(&corners, -1. / 3., -1. / 3.);
        let got = m.coord(p.pressure_nodes[0]);
        assert!(dot(sub(want, got), sub(want, got)) < 1e-28);
    }

    #[test]
    fn penta6_and_pyram5_faces_cut_into_cones() {
        let penta: Vec<[f64; 3]> = LinearCells
            .nodes(CellType::PENTA6)
            .unwrap()
            .iter()
            .map(|p| [p[1] + 0.1 * p[0], p[2], p[0] + 0.2 * p[1]])
            .collect();
        // Triangle face: 3 triangles, 3 pyramids + 1 tetrahedron.
        let m0 = one_cell(CellType::PENTA6, penta.clone(), CellType::TRIA3, &[0, 1, 2]);
        check(&m0, DecoupeHexa::Pyra, 1, 3, 4, 1);
        // Quadrangle face: 4 triangles, 2 pyramids + 2 tetrahedra.
        let m0 = one_cell(CellType::PENTA6, penta, CellType::QUAD4, &[0, 3, 4, 1]);
        check(&m0, DecoupeHexa::Hexa, 1, 4, 4, 1);
        let pyram: Vec<[f64; 3]> = LinearCells
            .nodes(CellType::PYRAM5)
            .unwrap()
            .iter()
            .map(|p| [p[0] + 0.1 * p[2], p[1], p[2] * 1.3])
            .collect();
        // Base: 4 tetrahedra; side: 1 pyramid + 3 tetrahedra.
        let m0 = one_cell(
            CellType::PYRAM5,
            pyram.clone(),
            CellType::QUAD4,
            &[0, 3, 2, 1],
        );
        check(&m0, DecoupeHexa::Pyra, 1, 4, 4, 1);
        let m0 = one_cell(CellType::PYRAM5, pyram, CellType::TRIA3, &[0, 4, 1]);
        check(&m0, DecoupeHexa::Pyra, 1, 3, 4, 1);
    }

    #[test]
    fn mismatched_face_and_volume_are_refused() {
        // A QUAD4 face whose nodes are not those of the hexahedron's face…
        let m0 = one_cell(CellType::HEXA8, hexa_coords(), CellType::TRIA3, &[0, 1, 2]);
        let e = decoupe_lac_with(&m0, &["S"], LacOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("HEXA8") && e.contains("TRIA3"), "{e}");
        // …and a quadratic volume without its shape functions.
        let mut m0 = one_cell(
            CellType::HEXA8,
            hexa_coords(),
            CellType::QUAD4,
            &[0, 1, 2, 3],
        );
        m0.cells[0].ty = CellType::HEXA20;
        m0.cells[1].ty = CellType::QUAD8;
        let e = decoupe_lac_with(&m0, &["S"], LacOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("HEXA20"), "{e}");
    }
}
