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
//! Quadratic cells (SEG3, TRIA6, TRIA7, QUAD8, QUAD9, TETRA10, PENTA15,
//! PENTA18, HEXA20, HEXA27) are refined kept quadratic, as code_aster
//! does: read before the linear ones (`init_mesh`'s classes), made of
//! their richest type by adding the centre of a TRIA6/QUAD8 face (TR6/QU8
//! shape functions at the reference centre) and of a HEXA20 (H20 at 0),
//! split as their linear family, each sub-cell of its parent's type
//! (`conv_type`), the nodes it needs taken among its richest-type nodes.
//! On such a mesh every new node goes where code_aster's `barycenter_*`
//! put it, on the parent's curved geometry: the halves of an edge by its
//! SE3 functions at ∓½, a sub-face's new edges and centre by the parent
//! face's TR7/QU9 functions (`barycenter_fe`, `barycenter_face`), a
//! sub-hexahedron's centre by the parent's H27 functions; an edge or face
//! inside a parent volume gets the middle of its ends / the centroid of its
//! corners (code_aster's entities without parent). Tetrahedra's and prisms'
//! centres, which no cell keeps, are put at the centroid. A PYRAM13 (and a
//! PYRAM5 beside quadratic cells) is refused: code_aster's
//! `barycenter_volume` stops on a sub-pyramid. So is an edge met with two
//! different middle nodes (code_aster would keep two edges).
//!
//! A mesh of linear cells only keeps the placement this module had before
//! (bit for bit): new nodes at the middle of the straight edge and at the
//! centroid of the face's or volume's corners, the points code_aster's
//! shape functions give on straight-sided linear cells, within rounding.
//! An input cell neither refined nor converted (a POI1, or any cell at
//! level 0) keeps its own nodes; [`Mesh::convert_to_quadratic`] refuses
//! quadratic cells.

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

/// The linear type of a cell's family: the one `dividing_cell` splits it
/// as (SEG3 → SEG2, TRIA6/TRIA7 → TRIA3, QUAD8/QUAD9 → QUAD4, TETRA10 →
/// TETRA4, PENTA15/PENTA18 → PENTA6, HEXA20/HEXA27 → HEXA8, PYRAM13 →
/// PYRAM5).
fn family(ty: CellType) -> CellType {
    use CellType::*;
    match ty {
        SEG3 | SEG4 => SEG2,
        TRIA6 | TRIA7 => TRIA3,
        QUAD8 | QUAD9 => QUAD4,
        TETRA10 => TETRA4,
        PENTA15 | PENTA18 => PENTA6,
        HEXA20 | HEXA27 => HEXA8,
        PYRAM13 => PYRAM5,
        other => other,
    }
}

/// The class `init_mesh` reads a type in (its hard-coded order: POI1,
/// SEG3, TRIA7/QUAD9, HEXA27, TRIA6/QUAD8, the other quadratic volumes,
/// SEG2, TRIA3/QUAD4, the linear volumes); `None` for a type this module
/// does not take (SEG4; PYRAM13, whose sub-pyramids code_aster cannot place:
/// `barycenter_volume` stops on a pyramid with a parent).
fn read_class(ty: CellType) -> Option<u8> {
    use CellType::*;
    match ty {
        POI1 => Some(0),
        SEG3 => Some(2),
        TRIA7 | QUAD9 => Some(3),
        HEXA27 => Some(4),
        TRIA6 | QUAD8 => Some(5),
        TETRA10 | PENTA15 | PENTA18 | HEXA20 => Some(6),
        SEG2 => Some(7),
        TRIA3 | QUAD4 => Some(8),
        TETRA4 | HEXA8 | PENTA6 | PYRAM5 => Some(9),
        _ => None,
    }
}

/// code_aster's shape functions (`elrfvf`) that place the new nodes of a
/// curved refinement, written as it writes them (same operations in the
/// same order, so the same roundings).
mod shape {
    fn al31(u: f64) -> f64 {
        0.5 * u * (u - 1.0)
    }
    fn al32(u: f64) -> f64 {
        -(u + 1.0) * (u - 1.0)
    }
    fn al33(u: f64) -> f64 {
        0.5 * u * (u + 1.0)
    }

    pub fn tr3(x: f64, y: f64) -> Vec<f64> {
        vec![1.0 - x - y, x, y]
    }

    pub fn tr6(x: f64, y: f64) -> Vec<f64> {
        let al = 1.0 - x - y;
        vec![
            -al * (1.0 - 2.0 * al),
            -x * (1.0 - 2.0 * x),
            -y * (1.0 - 2.0 * y),
            4.0 * x * al,
            4.0 * x * y,
            4.0 * y * al,
        ]
    }

    pub fn tr7(x: f64, y: f64) -> Vec<f64> {
        vec![
            1.0 - 3.0 * (x + y) + 2.0 * (x * x + y * y) + 7.0 * x * y - 3.0 * x * y * (x + y),
            x * (-1.0 + 2.0 * x + 3.0 * y - 3.0 * y * (x + y)),
            y * (-1.0 + 3.0 * x + 2.0 * y - 3.0 * x * (x + y)),
            4.0 * x * (1.0 - x - 4.0 * y + 3.0 * y * (x + y)),
            4.0 * x * y * (-2.0 + 3.0 * (x + y)),
            4.0 * y * (1.0 - y - 4.0 * x + 3.0 * x * (x + y)),
            27.0 * x * y * (1.0 - x - y),
        ]
    }

    pub fn qu4(x: f64, y: f64) -> Vec<f64> {
        vec![
            0.25 * (1.0 - x) * (1.0 - y),
            0.25 * (1.0 + x) * (1.0 - y),
            0.25 * (1.0 + x) * (1.0 + y),
            0.25 * (1.0 - x) * (1.0 + y),
        ]
    }

    pub fn qu8(x: f64, y: f64) -> Vec<f64> {
        vec![
            0.25 * (1.0 - x) * (1.0 - y) * (-1.0 - x - y),
            0.25 * (1.0 + x) * (1.0 - y) * (-1.0 + x - y),
            0.25 * (1.0 + x) * (1.0 + y) * (-1.0 + x + y),
            0.25 * (1.0 - x) * (1.0 + y) * (-1.0 - x + y),
            0.5 * (1.0 - x * x) * (1.0 - y),
            0.5 * (1.0 - y * y) * (1.0 + x),
            0.5 * (1.0 - x * x) * (1.0 + y),
            0.5 * (1.0 - y * y) * (1.0 - x),
        ]
    }

    pub fn qu9(x: f64, y: f64) -> Vec<f64> {
        vec![
            al31(x) * al31(y),
            al33(x) * al31(y),
            al33(x) * al33(y),
            al31(x) * al33(y),
            al32(x) * al31(y),
            al33(x) * al32(y),
            al32(x) * al33(y),
            al31(x) * al32(y),
            al32(x) * al32(y),
        ]
    }

    pub fn he8(x: f64, y: f64, z: f64) -> Vec<f64> {
        let f = |a: f64, b: f64, c: f64| (1.0 + a * x) * (1.0 + b * y) * (1.0 + c * z) * 0.125;
        vec![
            f(-1.0, -1.0, -1.0),
            f(1.0, -1.0, -1.0),
            f(1.0, 1.0, -1.0),
            f(-1.0, 1.0, -1.0),
            f(-1.0, -1.0, 1.0),
            f(1.0, -1.0, 1.0),
            f(1.0, 1.0, 1.0),
            f(-1.0, 1.0, 1.0),
        ]
    }

    /// At the centre only (the one point refine evaluates it at): −1/4 at
    /// the corners, 1/4 at the middles, exactly as `elrfvf` gives them.
    pub fn h20_centre() -> Vec<f64> {
        let mut w = vec![(1.0 - 0.0) * (1.0 - 0.0) * (1.0 - 0.0) * (-2.0) * 0.125; 8];
        w.extend([(1.0 - 0.0) * (1.0 - 0.0) * (1.0 - 0.0) * 0.25; 12]);
        w
    }

    pub fn h27(x: f64, y: f64, z: f64) -> Vec<f64> {
        let (a, b, c) = (
            [al31(x), al32(x), al33(x)],
            [al31(y), al32(y), al33(y)],
            [al31(z), al32(z), al33(z)],
        );
        // (x, y, z) = (-1|0|1) per node, code_aster's HEXA27 order.
        const P: [[usize; 3]; 27] = [
            [0, 0, 0],
            [2, 0, 0],
            [2, 2, 0],
            [0, 2, 0],
            [0, 0, 2],
            [2, 0, 2],
            [2, 2, 2],
            [0, 2, 2],
            [1, 0, 0],
            [2, 1, 0],
            [1, 2, 0],
            [0, 1, 0],
            [0, 0, 1],
            [2, 0, 1],
            [2, 2, 1],
            [0, 2, 1],
            [1, 0, 2],
            [2, 1, 2],
            [1, 2, 2],
            [0, 1, 2],
            [1, 1, 0],
            [1, 0, 1],
            [2, 1, 1],
            [1, 2, 1],
            [0, 1, 1],
            [1, 1, 2],
            [1, 1, 1],
        ];
        P.iter().map(|p| a[p[0]] * b[p[1]] * c[p[2]]).collect()
    }

    /// `barycenter_fe`: the reference point of the middle of edge
    /// `edge` (1-based) of sub-triangle / sub-quadrangle `sub` (1-based)
    /// in its parent face.
    pub fn edge_in_face(tria: bool, sub: usize, edge: usize) -> (f64, f64) {
        const TRIA: [[(f64, f64); 3]; 4] = [
            [(0.25, 0.0), (0.25, 0.25), (0.0, 0.25)],
            [(0.75, 0.25), (0.5, 0.25), (0.75, 0.0)],
            [(0.0, 0.75), (0.25, 0.5), (0.25, 0.75)],
            [(0.5, 0.25), (0.25, 0.5), (0.25, 0.25)],
        ];
        const QUAD: [[(f64, f64); 4]; 4] = [
            [(-0.5, -1.0), (0.0, -0.5), (-0.5, 0.0), (-1.0, -0.5)],
            [(1.0, -0.5), (0.5, 0.0), (0.0, -0.5), (0.5, -1.0)],
            [(0.5, 1.0), (0.0, 0.5), (0.5, 0.0), (1.0, 0.5)],
            [(-1.0, 0.5), (-0.5, 0.0), (0.0, 0.5), (-0.5, 1.0)],
        ];
        if tria {
            TRIA[sub - 1][edge - 1]
        } else {
            QUAD[sub - 1][edge - 1]
        }
    }

    /// `barycenter_face`: the reference point of the centre of sub-face
    /// `sub` (1-based) in its parent face.
    pub fn face_in_face(tria: bool, sub: usize) -> (f64, f64) {
        if tria {
            [
                (0.5 / 3.0, 0.5 / 3.0),
                (2.0 / 3.0, 0.5 / 3.0),
                (0.5 / 3.0, 2.0 / 3.0),
                (1.0 / 3.0, 1.0 / 3.0),
            ][sub - 1]
        } else {
            [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)][sub - 1]
        }
    }

    /// `barycenter_volume`: the reference point of the centre of
    /// sub-hexahedron `sub` (1-based) in its parent.
    pub fn hexa_in_hexa(sub: usize) -> (f64, f64, f64) {
        [
            (-0.5, -0.5, -0.5),
            (0.5, -0.5, -0.5),
            (0.5, 0.5, -0.5),
            (-0.5, 0.5, -0.5),
            (-0.5, -0.5, 0.5),
            (0.5, -0.5, 0.5),
            (0.5, 0.5, 0.5),
            (-0.5, 0.5, 0.5),
        ][sub - 1]
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

/// Where a new edge lies, which says where its middle node goes on a curved
/// mesh (`convert_edge`).
#[derive(Clone, Copy, Debug)]
enum EdgeAt {
    /// Made for itself (`barycenter_edge` without parent): the middle of its
    /// ends.
    Plain,
    /// Half `isub` (1: at its first end, 2: at its second) of an edge.
    Half { parent: usize, isub: usize },
    /// Edge `edge` of sub-face `sub` of a face (`barycenter_fe`): on the
    /// parent face.
    InFace {
        face: usize,
        sub: usize,
        edge: usize,
        tria: bool,
    },
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
    /// The type of the cell (a sub-cell has its parent's, `conv_type`).
    ty: CellType,
    entity: Entity,
    keep: bool,
    children: Vec<usize>,
    /// An input cell's own nodes (kept as they are when the cell is neither
    /// converted nor refined).
    own: Option<Vec<u32>>,
}

/// code_aster's `Mmesh` with `convert_max`.
struct Mmesh {
    coords: Vec<[f64; 3]>,
    /// Input nodes no input cell uses (kept whatever happens).
    orphan: Vec<bool>,
    /// A quadratic input cell: new nodes are placed by the parents' shape
    /// functions as code_aster does, instead of at the centroids of the
    /// corners (the same points on straight linear cells, within rounding).
    curved: bool,
    /// An edge met with two different middle nodes (ends, middles).
    conflict: Option<[u32; 4]>,
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

/// The cells `refine` (`quadratic`) or `convertToQuadratic` takes: every
/// cell read by a class, linear ones only for `convertToQuadratic`, and no
/// PYRAM5 beside a quadratic cell. Whether the mesh has a quadratic cell
/// (and its new nodes go where code_aster's shape functions put them).
fn check_types(mesh: &Mesh, what: &str, quadratic: bool) -> Result<bool, MeshError> {
    let curved = mesh.cells.iter().any(|c| family(c.ty) != c.ty);
    for (i, c) in mesh.cells.iter().enumerate() {
        let name = || mesh.cell_name(CellId(i as u32));
        if read_class(c.ty).is_none() || !quadratic && family(c.ty) != c.ty {
            return Err(MeshError::Operation(if quadratic {
                format!(
                    "{what}: cell {} is a {}: aster refines POI1, SEG2, SEG3, TRIA3, TRIA6, TRIA7, QUAD4, QUAD8, QUAD9, TETRA4, TETRA10, PENTA6, PENTA15, PENTA18, HEXA8, HEXA20, HEXA27 and PYRAM5 cells (code_aster cannot place the centres of a quadratic pyramid's sub-pyramids: barycenter_volume stops on a pyramid with a parent)",
                    name(),
                    c.ty.name()
                )
            } else {
                format!(
                    "{what}: cell {} is a {}: aster takes meshes of linear cells (POI1, SEG2, TRIA3, QUAD4, TETRA4, HEXA8, PENTA6, PYRAM5) — convertToLinear() first",
                    name(),
                    c.ty.name()
                )
            }));
        }
        if curved && c.ty == CellType::PYRAM5 {
            return Err(MeshError::Operation(format!(
                "{what}: cell {} is a PYRAM5 in a mesh with quadratic cells, whose new nodes code_aster places on the parent cells: it cannot place the centres of a pyramid's sub-pyramids (barycenter_volume stops on a pyramid with a parent)",
                name()
            )));
        }
    }
    Ok(curved)
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

    /// Σ wᵢ xᵢ in code_aster's order (`barycenter_*`).
    fn combine(&self, nodes: &[u32], w: &[f64]) -> [f64; 3] {
        let mut x = [0.0; 3];
        for (&n, &w) in nodes.iter().zip(w) {
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

    /// Where the middle of a new edge goes.
    fn edge_point(&self, a: u32, b: u32, at: EdgeAt) -> [f64; 3] {
        if !self.curved {
            return self.centroid(&[a, b]);
        }
        match at {
            EdgeAt::Plain => self.combine(&[a, b], &[0.5, 0.5]),
            EdgeAt::Half { parent, isub } => {
                let w = if isub == 1 {
                    [0.375, -0.125, 0.75]
                } else {
                    [-0.125, 0.375, 0.75]
                };
                self.combine(&self.edges[parent].nodes, &w)
            }
            EdgeAt::InFace {
                face,
                sub,
                edge,
                tria,
            } => {
                let (x, y) = shape::edge_in_face(tria, sub, edge);
                let nodes = &self.faces[face].nodes;
                let w = if nodes.len() == 7 {
                    shape::tr7(x, y)
                } else {
                    shape::qu9(x, y)
                };
                self.combine(nodes, &w)
            }
        }
    }

    /// Where the centre of a new face goes: `nodes` its corners then, when
    /// it was given quadratic, its middles; `sub` its parent face and its
    /// place there.
    fn face_point(&self, nodes: &[u32], n: usize, sub: Option<(usize, usize)>) -> [f64; 3] {
        if !self.curved {
            return self.centroid(&nodes[..n]);
        }
        match sub {
            None => {
                let quadratic = nodes.len() == 2 * n;
                let w = match (n, quadratic) {
                    (3, false) => shape::tr3(1.0 / 3.0, 1.0 / 3.0),
                    (3, true) => shape::tr6(1.0 / 3.0, 1.0 / 3.0),
                    (_, false) => shape::qu4(0.0, 0.0),
                    (_, true) => shape::qu8(0.0, 0.0),
                };
                self.combine(nodes, &w)
            }
            Some((parent, isub)) => {
                let (x, y) = shape::face_in_face(n == 3, isub);
                let nodes = &self.faces[parent].nodes;
                let w = if n == 3 {
                    shape::tr7(x, y)
                } else {
                    shape::qu9(x, y)
                };
                self.combine(nodes, &w)
            }
        }
    }

    /// Where the centre of a new volume goes: `nodes` its richest-type
    /// nodes but the centre, `quadratic` when it was given quadratic.
    /// Tetrahedra's and prisms' centres are used by no cell (their
    /// sub-cells and quadratic types do not take them) and are removed at
    /// the end: they are put at the centroid.
    fn volume_point(
        &self,
        ty: CellType,
        nodes: &[u32],
        quadratic: bool,
        sub: Option<(usize, usize)>,
    ) -> [f64; 3] {
        let n = ty.node_count();
        if !self.curved || ty != CellType::HEXA8 {
            return self.centroid(&nodes[..n]);
        }
        match sub {
            None if quadratic => self.combine(&nodes[..20], &shape::h20_centre()),
            None => self.combine(&nodes[..8], &shape::he8(0.0, 0.0, 0.0)),
            Some((parent, isub)) => {
                let (x, y, z) = shape::hexa_in_hexa(isub);
                self.combine(&self.volumes[parent].nodes, &shape::h27(x, y, z))
            }
        }
    }

    /// `add_edge`: the edge of these ends, made (with its middle node, the
    /// given one or a new one placed by `at`) if new.
    fn add_edge(&mut self, a: u32, b: u32, mid: Option<u32>, at: EdgeAt) -> usize {
        let key = [a.min(b), a.max(b)];
        if let Some(&e) = self.edge_at.get(&key) {
            let known = self.edges[e].nodes[2];
            if let Some(m) = mid.filter(|&m| m != known) {
                self.conflict.get_or_insert([a, b, known, m]);
            }
            return e;
        }
        let m = match mid {
            Some(m) => m,
            None => {
                let x = self.edge_point(a, b, at);
                self.add_node(x)
            }
        };
        self.edges.push(Edge { nodes: [a, b, m] });
        let e = self.edges.len() - 1;
        self.edge_at.insert(key, e);
        e
    }

    /// `add_face`: the face of these nodes (3 or 4 corners, then the
    /// middles and the centre a quadratic face has), made if new: its
    /// edges, then its centre. `n` is the number of corners; `sub` the
    /// parent face and the place in it of a sub-face.
    fn add_face(&mut self, nodes: &[u32], n: usize, sub: Option<(usize, usize)>) -> usize {
        let corners = &nodes[..n];
        let key = sorted(corners);
        if let Some(&f) = self.face_at.get(&key) {
            return f;
        }
        let mut all = corners.to_vec();
        for i in 0..n {
            let at = match sub {
                Some((face, s)) => EdgeAt::InFace {
                    face,
                    sub: s,
                    edge: i + 1,
                    tria: n == 3,
                },
                None => EdgeAt::Plain,
            };
            let e = self.add_edge(
                corners[i],
                corners[(i + 1) % n],
                nodes.get(n + i).copied(),
                at,
            );
            all.push(self.edges[e].nodes[2]);
        }
        let centre = match nodes.get(2 * n) {
            Some(&c) => c,
            None => {
                let given = if nodes.len() >= 2 * n { 2 * n } else { n };
                let x = self.face_point(&all[..given], n, sub);
                self.add_node(x)
            }
        };
        all.push(centre);
        self.faces.push(Face { nodes: all });
        let f = self.faces.len() - 1;
        self.face_at.insert(key, f);
        f
    }

    /// `add_volume`: the volume of these nodes (the corners, then those of
    /// its quadratic type), made if new: its edges, then its faces, then its
    /// centre. `ty` is the cell's type; `sub` the parent volume and the
    /// place in it of a sub-volume.
    fn add_volume(&mut self, ty: CellType, given: &[u32], sub: Option<(usize, usize)>) -> usize {
        let lin = family(ty);
        let nc = lin.node_count();
        let corners = &given[..nc];
        let key = sorted(corners);
        if let Some(&v) = self.volume_at.get(&key) {
            return v;
        }
        let quadratic = ty != lin;
        let mut nodes = vec![u32::MAX; volume_centre(lin) + 1];
        nodes[..nc].copy_from_slice(corners);
        let mut edges = Vec::new();
        for (i, [a, b]) in volume_edges(lin).iter().enumerate() {
            let mid = given.get(nc + i).copied().filter(|_| quadratic);
            let e = self.add_edge(corners[*a], corners[*b], mid, EdgeAt::Plain);
            nodes[nc + i] = self.edges[e].nodes[2];
            edges.push(e);
        }
        let mut faces = Vec::new();
        for (local, centre) in volume_faces(lin) {
            let mut fnodes: Vec<u32> = local.iter().map(|&i| corners[i]).collect();
            let n = fnodes.len();
            if quadratic {
                for k in 0..n {
                    let (a, b) = (fnodes[k], fnodes[(k + 1) % n]);
                    let e = self.edge_at.get(&[a.min(b), a.max(b)]).copied();
                    fnodes.push(e.map_or(u32::MAX, |e| self.edges[e].nodes[2]));
                }
                if let Some(&c) = given.get(*centre) {
                    fnodes.push(c);
                }
            }
            let f = self.add_face(&fnodes, n, None);
            nodes[*centre] = *self.faces[f].nodes.last().unwrap_or(&u32::MAX);
            faces.push(f);
        }
        let c = volume_centre(lin);
        nodes[c] = match given.get(c) {
            Some(&g) => g,
            None => {
                let x = self.volume_point(lin, &nodes[..c], quadratic, sub);
                self.add_node(x)
            }
        };
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
    /// class by class. `quadratic`: whether quadratic cells are taken.
    fn init(mesh: &Mesh, what: &str, quadratic: bool) -> Result<Mmesh, MeshError> {
        let curved = check_types(mesh, what, quadratic)?;
        let mut classes: Vec<(u8, usize)> = mesh
            .cells
            .iter()
            .enumerate()
            .filter_map(|(i, c)| read_class(c.ty).map(|class| (class, i)))
            .collect();
        classes.sort();
        let mut mm = Mmesh {
            coords: mesh.coords.clone(),
            orphan: vec![true; mesh.coords.len()],
            curved,
            conflict: None,
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
                1 => Entity::Edge(mm.add_edge(
                    nodes[0],
                    nodes[1],
                    nodes.get(2).copied(),
                    EdgeAt::Plain,
                )),
                2 => Entity::Face(mm.add_face(&nodes, family(c.ty).node_count(), None)),
                _ => Entity::Volume(mm.add_volume(c.ty, &nodes, None)),
            };
        }
        if let Some([a, b, m1, m2]) = mm.conflict {
            let name = |n: u32| mesh.node_name(NodeId(n));
            return Err(MeshError::Operation(format!(
                "{what}: the edge {}–{} has two middle nodes, {} and {}: aster refines conforming meshes",
                name(a),
                name(b),
                name(m1),
                name(m2)
            )));
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
                own: Some(c.nodes.iter().map(|n| n.0).collect()),
            })
            .collect();
        Ok(mm)
    }

    /// `refine_cell`: the cell's edges split, then (a volume) its faces,
    /// then the cell into its sub-cells, each of the cell's type
    /// (`conv_type`; a pyramid's tetrahedra are TETRA4).
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
            self.add_edge(a, m, None, EdgeAt::Half { parent: e, isub: 1 });
            self.add_edge(b, m, None, EdgeAt::Half { parent: e, isub: 2 });
        }
        for f in faces {
            let nodes = self.faces[f].nodes.clone();
            let ty = if nodes.len() == 9 {
                CellType::QUAD4
            } else {
                CellType::TRIA3
            };
            for (k, (_, loc)) in sub_cells(ty).iter().enumerate() {
                let corners: Vec<u32> = loc.iter().map(|&k| nodes[k - 1]).collect();
                self.add_face(&corners, corners.len(), Some((f, k + 1)));
            }
        }
        self.cells[i].keep = false;
        let lin = family(cell_ty);
        for (k, (sub_ty, loc)) in sub_cells(lin).iter().enumerate() {
            let corners: Vec<u32> = loc.iter().map(|&k| parent[k - 1]).collect();
            let entity = match entity {
                Entity::Edge(e) => Entity::Edge(self.add_edge(
                    corners[0],
                    corners[1],
                    None,
                    EdgeAt::Half {
                        parent: e,
                        isub: k + 1,
                    },
                )),
                Entity::Face(f) => {
                    Entity::Face(self.add_face(&corners, corners.len(), Some((f, k + 1))))
                }
                _ => Entity::Volume(self.add_volume(
                    *sub_ty,
                    &corners,
                    Some((self.volume_of(entity), k + 1)),
                )),
            };
            let ty = if *sub_ty == lin { cell_ty } else { *sub_ty };
            self.cells.push(MCell {
                ty,
                entity,
                keep: true,
                children: Vec::new(),
                own: None,
            });
            let child = self.cells.len() - 1;
            self.cells[i].children.push(child);
        }
    }

    fn volume_of(&self, entity: Entity) -> usize {
        match entity {
            Entity::Volume(v) => v,
            _ => usize::MAX,
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
                let nodes = match &c.own {
                    Some(own) if ty == c.ty => own.clone(),
                    _ => self.cell_nodes(c.entity, ty),
                };
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
    /// as code_aster does it (module doc), quadratic cells kept quadratic.
    /// Refused (with the cell named) on a mesh with a cell it does not take
    /// ([`Mesh::refine_refusal`]) or with an edge of two middle nodes.
    pub fn refine(&self, ntimes: usize) -> Result<Mesh, MeshError> {
        let mut mm = Mmesh::init(self, "refine", true)?;
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

    /// Why [`Mesh::refine`] would refuse this mesh (a cell it does not
    /// take), checked without refining.
    pub fn refine_refusal(&self) -> Option<String> {
        check_types(self, "refine", true).err().map(|e| {
            let e = e.to_string();
            e.strip_prefix("refine: ").map_or(e.clone(), str::to_string)
        })
    }

    /// `Mesh.convertToQuadratic()`: every linear cell made quadratic
    /// (SEG2→SEG3, TRIA3→TRIA6, QUAD4→QUAD8, TETRA4→TETRA10,
    /// PENTA6→PENTA15, HEXA8→HEXA20, PYRAM5→PYRAM13) with code_aster's
    /// numbering of the new nodes (module doc). Refused on a mesh with a
    /// cell that is not linear.
    pub fn convert_to_quadratic(&self) -> Result<Mesh, MeshError> {
        let mm = Mmesh::init(self, "convertToQuadratic", false)?;
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
    fn quadratic_cells_refined_only_by_refine() {
        let m = unit(
            CellType::TRIA3,
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            2,
        );
        let q = m.convert_to_quadratic().unwrap();
        assert_eq!(q.cells[0].ty, CellType::TRIA6);
        assert_eq!(q.coords.len(), 6);
        assert!(q.convert_to_quadratic().is_err());
        let r = q.refine(1).unwrap();
        assert!(r.cells.iter().all(|c| c.ty == CellType::TRIA6));
        let back = q.convert_to_linear();
        assert_eq!(back.cells, m.cells);
        assert_eq!(back.coords, m.coords);
    }

    /// The unit cell of a linear type (code_aster's corner order).
    fn unit_linear(ty: CellType) -> Mesh {
        let (coords, dim) = match ty {
            CellType::SEG2 => (vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], 1),
            CellType::TRIA3 => (vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], 2),
            CellType::QUAD4 => (
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 1.0, 0.0],
                    [0.0, 1.0, 0.0],
                ],
                2,
            ),
            CellType::TETRA4 => (
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                ],
                3,
            ),
            CellType::PENTA6 => (
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                    [1.0, 0.0, 1.0],
                    [0.0, 1.0, 1.0],
                ],
                3,
            ),
            _ => (
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 1.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                    [1.0, 0.0, 1.0],
                    [1.0, 1.0, 1.0],
                    [0.0, 1.0, 1.0],
                ],
                3,
            ),
        };
        unit(ty, coords, dim)
    }

    /// The unit cell of a quadratic type, from its linear one.
    fn unit_quadratic(ty: CellType) -> Mesh {
        let q = to_type(&unit_linear(family(ty)), ty);
        assert_eq!(q.cells[0].ty, ty);
        q
    }

    /// A linear mesh made of `ty` as `convertToQuadratic` and `CREA_MAILLAGE`
    /// (`HEXA20_27`, …) make it.
    fn to_type(lin: &Mesh, ty: CellType) -> Mesh {
        use crate::ops::degree::CentreNodes;
        let mut q = lin.convert_to_quadratic().unwrap();
        let op = match ty {
            CellType::TRIA7 => Some(CentreNodes::Tria6To7),
            CellType::QUAD9 => Some(CentreNodes::Quad8To9),
            CellType::HEXA27 => Some(CentreNodes::Hexa20To27),
            CellType::PENTA18 => Some(CentreNodes::Penta15To18),
            _ => None,
        };
        if let Some(op) = op {
            let all: Vec<CellId> = (0..q.cells.len() as u32).map(CellId).collect();
            q.add_centre_nodes(&all, op);
        }
        q
    }

    /// The measure of a cell from its corners (segments, triangles, quadrangles
    /// and hexahedra with straight edges: split in triangles / tetrahedra).
    fn straight_measure(m: &Mesh) -> f64 {
        let tets: &[[usize; 4]] = &[
            [0, 1, 3, 4],
            [1, 2, 3, 6],
            [1, 3, 4, 6],
            [3, 4, 6, 7],
            [1, 4, 5, 6],
        ];
        let pent: &[[usize; 4]] = &[[0, 1, 2, 3], [1, 2, 3, 4], [2, 3, 4, 5]];
        m.cells
            .iter()
            .map(|c| {
                let p = |i: usize| m.coord(c.nodes[i]);
                let d = |a: usize, b: usize| {
                    let (x, y) = (p(a), p(b));
                    [y[0] - x[0], y[1] - x[1], y[2] - x[2]]
                };
                let det = |u: [f64; 3], v: [f64; 3], w: [f64; 3]| {
                    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                        + u[2] * (v[0] * w[1] - v[1] * w[0])
                };
                let tet = |t: &[usize; 4]| det(d(t[0], t[1]), d(t[0], t[2]), d(t[0], t[3])) / 6.0;
                let tri = |a: usize, b: usize, c: usize| {
                    let (u, v) = (d(a, b), d(a, c));
                    (u[0] * v[1] - u[1] * v[0]) / 2.0
                };
                match family(c.ty) {
                    CellType::SEG2 => d(0, 1)[0].abs(),
                    CellType::TRIA3 => tri(0, 1, 2),
                    CellType::QUAD4 => tri(0, 1, 2) + tri(0, 2, 3),
                    CellType::TETRA4 => tet(&[0, 1, 2, 3]),
                    CellType::PENTA6 => pent.iter().map(tet).sum(),
                    _ => tets.iter().map(tet).sum(),
                }
            })
            .sum()
    }

    #[test]
    fn quadratic_counts_per_level_volumes_and_middle_nodes() {
        use CellType::*;
        for ty in [
            SEG3, TRIA6, TRIA7, QUAD8, QUAD9, TETRA10, PENTA15, PENTA18, HEXA20, HEXA27,
        ] {
            let q = unit_quadratic(ty);
            let lin = unit_linear(family(ty));
            for n in 1..=2 {
                let r = q.refine(n).unwrap();
                // The same cells and points as the linear cell refined n
                // times, then made of this type.
                let same = to_type(&lin.refine(n).unwrap(), ty);
                assert_eq!(r.cells.len(), same.cells.len(), "{ty:?} {n}");
                assert!(r.cells.iter().all(|c| c.ty == ty), "{ty:?}");
                assert_eq!(r.coords.len(), same.coords.len(), "{ty:?} {n}");
                let near = |a: &[f64; 3], b: &[f64; 3]| (0..3).all(|i| (a[i] - b[i]).abs() < 1e-15);
                for a in &r.coords {
                    let hits = same.coords.iter().filter(|b| near(a, b)).count();
                    assert_eq!(hits, 1, "{ty:?} {n}: {a:?}");
                }
                let v = straight_measure(&r);
                assert!((v - straight_measure(&lin)).abs() < 1e-14, "{ty:?} {v}");
                // Straight cells: each middle node halfway between its ends.
                for c in &r.cells {
                    let nc = family(ty).node_count();
                    for (k, [a, b]) in ty.corner_edges().iter().enumerate() {
                        let (x, y, m) = (
                            r.coord(c.nodes[*a]),
                            r.coord(c.nodes[*b]),
                            r.coord(c.nodes[nc + k]),
                        );
                        for i in 0..3 {
                            assert!((m[i] - 0.5 * (x[i] + y[i])).abs() < 1e-15, "{ty:?}");
                        }
                    }
                }
                assert_eq!(r.group_ma("ALL").unwrap().members.len(), r.cells.len());
                assert_eq!(r.group_no("FIRST").unwrap().members, vec![NodeId(0)]);
            }
        }
    }

    #[test]
    fn quad8_refined_once_numbers_and_connects_as_code_aster() {
        let r = unit_quadratic(CellType::QUAD8).refine(1).unwrap();
        // 9 input nodes kept (the centre made first, N9), then the halves
        // of edges 12 23 34 41 (first end's half first), then each
        // sub-quadrangle's new inner edges; the sub-centres are dropped.
        assert_eq!(r.coords.len(), 21);
        assert_eq!(r.coords[8], [0.5, 0.5, 0.0]);
        let halves = [
            [0.25, 0.0],
            [0.75, 0.0],
            [1.0, 0.25],
            [1.0, 0.75],
            [0.75, 1.0],
            [0.25, 1.0],
            [0.0, 0.75],
            [0.0, 0.25],
            [0.5, 0.25],
            [0.25, 0.5],
            [0.75, 0.5],
            [0.5, 0.75],
        ];
        for (k, h) in halves.iter().enumerate() {
            assert_eq!(r.coords[9 + k], [h[0], h[1], 0.0], "N{}", 10 + k);
        }
        assert_eq!(
            crate::ops::testmesh::one_based(&r),
            vec![
                vec![1, 5, 9, 8, 10, 18, 19, 17],
                vec![2, 6, 9, 5, 12, 20, 18, 11],
                vec![3, 7, 9, 6, 14, 21, 20, 13],
                vec![4, 8, 9, 7, 16, 19, 21, 15],
            ]
        );
    }

    #[test]
    fn hexa20_refined_once_numbers_and_connects_as_code_aster() {
        let q = unit_quadratic(CellType::HEXA20);
        let r = q.refine(1).unwrap();
        assert_eq!((r.coords.len(), r.cells.len()), (81, 8));
        // N1–N20 the input's, N21–N26 the face centres (faces 1432 1265
        // 2376 3487 1584 5678), N27 the centre, then the halves of the 12
        // edges in order.
        assert_eq!(r.coords[..20], q.coords[..]);
        let centres = [
            [0.5, 0.5, 0.0],
            [0.5, 0.0, 0.5],
            [1.0, 0.5, 0.5],
            [0.5, 1.0, 0.5],
            [0.0, 0.5, 0.5],
            [0.5, 0.5, 1.0],
            [0.5, 0.5, 0.5],
        ];
        assert_eq!(r.coords[20..27], centres[..]);
        for (e, [a, b]) in volume_edges(CellType::HEXA8).iter().enumerate() {
            let (x, y) = (q.coords[*a], q.coords[*b]);
            for (k, w) in [(0, 0.75), (1, 0.25)] {
                let h: Vec<f64> = (0..3).map(|i| w * x[i] + (1.0 - w) * y[i]).collect();
                assert_eq!(r.coords[27 + 2 * e + k].to_vec(), h, "edge {e}");
            }
        }
        // Child k is the octant of dividing_cell's sub_loc, its 20 nodes
        // in HEXA20 order: its corners at the parent's HEXA27 places.
        let sub: [[usize; 8]; 8] = [
            [1, 9, 21, 12, 13, 22, 27, 25],
            [2, 10, 21, 9, 14, 23, 27, 22],
            [3, 11, 21, 10, 15, 24, 27, 23],
            [4, 12, 21, 11, 16, 25, 27, 24],
            [13, 22, 27, 25, 5, 17, 26, 20],
            [14, 23, 27, 22, 6, 18, 26, 17],
            [15, 24, 27, 23, 7, 19, 26, 18],
            [16, 25, 27, 24, 8, 20, 26, 19],
        ];
        let h27: Vec<[f64; 3]> = r.coords[..27].to_vec();
        for (c, loc) in r.cells.iter().zip(sub) {
            for (k, &l) in loc.iter().enumerate() {
                assert_eq!(r.coord(c.nodes[k]), h27[l - 1]);
            }
            assert_eq!(
                c.nodes[..8]
                    .iter()
                    .map(|n| n.0 as usize + 1)
                    .collect::<Vec<_>>(),
                loc
            );
        }
        assert_eq!(r.group_ma("ALL").unwrap().members.len(), 8);
    }

    #[test]
    fn curved_edges_stay_on_the_parent_parabola() {
        // A QUAD8 whose edge 12 bulges: its middle node N5 at y = 0.1, the
        // edge the parabola y = 0.4 x (1 - x).
        let mut q = unit_quadratic(CellType::QUAD8);
        q.coords[4] = [0.5, 0.1, 0.0];
        for n in 1..=3 {
            let r = q.refine(n).unwrap();
            let on_edge: Vec<[f64; 3]> = r
                .coords
                .iter()
                .copied()
                .filter(|p| p[1] < 0.1 + 1e-12 && (p[1] - 0.4 * p[0] * (1.0 - p[0])).abs() < 1e-15)
                .collect();
            // 2^(n+1) + 1 nodes along the curved edge, all on the parabola.
            assert_eq!(on_edge.len(), (1 << (n + 1)) + 1, "level {n}");
            // The area is the parent's: 1 − 0.4/6 (the parabola cuts into
            // the square), each child integrated with its own quadratic map.
            let area: f64 = r.cells.iter().map(|c| quad8_area(&r, c)).sum();
            assert!(
                (area - (1.0 - 0.4 / 6.0)).abs() < 1e-14,
                "level {n}: {area}"
            );
        }
    }

    /// The area of a plane QUAD8 by 3×3 Gauss points.
    fn quad8_area(m: &Mesh, c: &Cell) -> f64 {
        let g = [-(0.6f64).sqrt(), 0.0, (0.6f64).sqrt()];
        let w = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
        let mut a = 0.0;
        for (i, &x) in g.iter().enumerate() {
            for (j, &y) in g.iter().enumerate() {
                // Central differences, exact on a map quadratic in each
                // variable.
                let h = 0.5;
                let map = |x: f64, y: f64| {
                    let f = shape::qu8(x, y);
                    let mut p = [0.0; 2];
                    for (k, n) in c.nodes.iter().enumerate() {
                        let q = m.coord(*n);
                        p[0] += f[k] * q[0];
                        p[1] += f[k] * q[1];
                    }
                    p
                };
                let (px, mx, py, my) = (map(x + h, y), map(x - h, y), map(x, y + h), map(x, y - h));
                let dx = [(px[0] - mx[0]) / (2.0 * h), (px[1] - mx[1]) / (2.0 * h)];
                let dy = [(py[0] - my[0]) / (2.0 * h), (py[1] - my[1]) / (2.0 * h)];
                a += w[i] * w[j] * (dx[0] * dy[1] - dx[1] * dy[0]);
            }
        }
        a
    }

    #[test]
    fn cells_refine_cannot_place_are_refused() {
        let mut q = unit_quadratic(CellType::QUAD8);
        // An edge with two middle nodes: a SEG3 on edge 12 with its own.
        q.coords.push([0.5, 0.0, 0.0]);
        q.node_names.push("N9".into());
        q.cells.push(Cell {
            ty: CellType::SEG3,
            nodes: vec![NodeId(0), NodeId(1), NodeId(8)],
        });
        q.cell_names.push("M2".into());
        let e = q.refine(1).unwrap_err().to_string();
        assert!(e.contains("N1–N2 has two middle nodes, N9 and N5"), "{e}");
        // A PYRAM5 beside quadratic cells.
        q.cells[1] = Cell {
            ty: CellType::PYRAM5,
            nodes: (0..5).map(NodeId).collect(),
        };
        assert!(q
            .refine_refusal()
            .unwrap()
            .starts_with("cell M2 is a PYRAM5 in a mesh with quadratic cells"));
        assert!(q.refine(1).is_err());
        q.cells[1].ty = CellType::POI1;
        q.cells[1].nodes.truncate(1);
        assert!(q.refine_refusal().is_none());
    }
}
