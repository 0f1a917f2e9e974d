//! Collocation projection of nodal fields from one mesh onto the nodes of
//! another (`PROJ_CHAMP(METHODE='COLLOCATION')`), as code_aster does it
//! (`pjefco`, `pj2dco`/`pj3dco`/`pj4dco`, `pj2dtr`/`pj3dtr`, `pjefmi`,
//! `pjfuco`, `cnsprj`).
//!
//! Each node of mesh 2 is first located in a sub-simplex of mesh 1's cells:
//! volumes are split into tetrahedra (HEXA 6, PENTA 3, PYRAM 2), faces into
//! triangles (QUAD 2). The first simplex that contains the node (barycentric
//! coordinates in [−1e-10, 1+1e-10]) is taken, else the nearest one (its
//! closest point; only those nearer than `DISTANCE_MAX` when given; in 2.5D
//! — faces in 3D — always the nearest). The barycentric coordinates map the
//! node to reference coordinates ξ₁ of the real cell; Newton on the real
//! cell's geometry (`reereg`, started at ξ = 0, stopped when |Δξ|² ≤ 1e-8,
//! at most 50 iterations) gives ξ₂; `pjefmi` keeps ξ₂ unless it lies outside
//! the reference cell by more than 1 % or maps farther from the node than ξ₁.
//! The value is then interpolated with the **full shape functions of the real
//! cell** at that point — not the P1 functions of the sub-simplex: a field
//! that the cell's shape functions represent (quadratic on a quadratic cell)
//! is projected exactly.

use crate::shape::{reference_nodes, shape};
use aster_mesh::{CellId, CellType, Mesh, NodeId};

/// Where code_aster locates the nodes (`CAS_FIGURE`, chosen by `pjefca`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Case {
    /// Faces of a plane mesh (z quasi zero), in the (x, y) plane.
    Plane,
    /// Volumes.
    Volume,
    /// Faces of a 3D mesh ("2.5D").
    Surface,
}

impl Case {
    /// code_aster's name (`'2D'`, `'3D'`, `'2.5D'`).
    pub fn name(self) -> &'static str {
        match self {
            Case::Plane => "2D",
            Case::Volume => "3D",
            Case::Surface => "2.5D",
        }
    }

    /// The cell types code_aster projects from in this case (`pjxxut`).
    pub fn accepts(self, ty: CellType) -> bool {
        match self {
            Case::Volume => ty.dim() == 3,
            Case::Plane | Case::Surface => ty.dim() == 2,
        }
    }
}

/// A projection that cannot be made, with code_aster's message id.
#[derive(Clone, Debug, PartialEq)]
pub struct ProjectionError {
    pub message: String,
    pub id: &'static str,
}

impl std::fmt::Display for ProjectionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({})", self.message, self.id)
    }
}

fn err(id: &'static str, message: impl Into<String>) -> ProjectionError {
    ProjectionError {
        message: message.into(),
        id,
    }
}

/// code_aster's `Z_QUASI_ZERO`: every z is 0, or |z| is below 1e-8 times
/// the larger of the x and y extents.
pub fn z_quasi_zero(mesh: &Mesh) -> bool {
    if mesh.coords.is_empty() {
        return true;
    }
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for c in &mesh.coords {
        for k in 0..3 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    if lo[2] == hi[2] && lo[2] == 0.0 {
        return true;
    }
    lo[2].abs().max(hi[2].abs()) < (hi[0] - lo[0]).max(hi[1] - lo[1]) * 1e-8
}

/// `pjefca`: the case of a set of cells — their largest topological
/// dimension, faces being plane or 2.5D as the mesh's z is quasi zero or not.
/// `None` for points and segments only ("1.5D") or no cell.
pub fn case_of(mesh: &Mesh, cells: &[CellId]) -> Option<Case> {
    let dim = cells.iter().map(|&c| mesh.cell(c).ty.dim()).max()?;
    match dim {
        3 => Some(Case::Volume),
        2 if z_quasi_zero(mesh) => Some(Case::Plane),
        2 => Some(Case::Surface),
        _ => None,
    }
}

/// How one node of mesh 2 is computed from mesh 1: Σ coefs[i] · v(nodes[i]).
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// The cell of mesh 1 the node was located in.
    pub cell: CellId,
    pub nodes: Vec<NodeId>,
    pub coefs: Vec<f64>,
}

/// The options of a projection (`DISTANCE_MAX`, `DISTANCE_ALARME`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Options {
    pub distance_max: Option<f64>,
    pub distance_alarme: Option<f64>,
}

/// The correspondence being built over the `VIS_A_VIS` occurrences.
pub struct Correspondence {
    /// Per node of mesh 2, its link (the last occurrence that gave one wins,
    /// as `pjfuco` merges them).
    pub links: Vec<Option<Link>>,
    /// Nodes of mesh 2 located farther than 10 % of a cell from any cell of
    /// mesh 1 (code_aster's alarm `PROJECTION9`), with their distance.
    pub far: Vec<(NodeId, f64)>,
    /// The nodes every earlier occurrence asked for (`pjreco`).
    seen: Vec<bool>,
    /// `DISTANCE_MAX` given (code_aster's `l_dmax`; a 2.5D occurrence may
    /// set it on for the rest of the command, as `pj4dco` does).
    l_dmax: bool,
    dmax: f64,
    dala: f64,
}

/// Whether a point is in a simplex: its barycentric coordinates if so.
type InsideTest = fn(&Mesh, &[NodeId; 4], [f64; 3]) -> Option<[f64; 4]>;

/// The nearest point of a simplex: its barycentrics and squared distance.
type NearestPoint = fn(&Mesh, &[NodeId; 4], [f64; 3]) -> ([f64; 4], f64);

/// A sub-simplex of a cell: its vertices (cell-local indices) and its cell.
struct Simplex {
    cell: CellId,
    /// Which split of the cell (0-based), to map barycentrics to ξ.
    local: [usize; 4],
    nodes: [NodeId; 4],
}

/// code_aster's splits (`pj3dco`/`pj3dtr`, `pj2dco`/`pj2dtr`), 0-based.
fn splits(ty: CellType) -> &'static [[usize; 4]] {
    use CellType::*;
    match ty {
        TETRA4 | TETRA10 => &[[0, 1, 2, 3]],
        PENTA6 | PENTA15 | PENTA18 => &[[0, 2, 5, 4], [0, 5, 3, 4], [0, 2, 4, 1]],
        HEXA8 | HEXA20 | HEXA27 => &[
            [0, 3, 7, 5],
            [0, 7, 5, 4],
            [0, 3, 5, 1],
            [1, 3, 7, 6],
            [1, 7, 5, 6],
            [1, 3, 6, 2],
        ],
        PYRAM5 | PYRAM13 => &[[0, 1, 2, 4], [0, 2, 3, 4]],
        TRIA3 | TRIA6 | TRIA7 => &[[0, 1, 2, 0]],
        QUAD4 | QUAD8 | QUAD9 => &[[0, 1, 2, 0], [0, 2, 3, 0]],
        _ => &[],
    }
}

impl Correspondence {
    pub fn new(mesh2: &Mesh, options: Options) -> Correspondence {
        Correspondence {
            links: vec![None; mesh2.node_count()],
            far: Vec::new(),
            seen: vec![false; mesh2.node_count()],
            l_dmax: options.distance_max.is_some(),
            dmax: options.distance_max.unwrap_or(0.0),
            dala: options.distance_alarme.unwrap_or(-1.0),
        }
    }

    /// One occurrence: the nodes `nodes2` of mesh 2 located in the cells
    /// `cells1` of mesh 1 (those of the case's dimension), merged into the
    /// correspondence.
    pub fn add(
        &mut self,
        mesh1: &Mesh,
        cells1: &[CellId],
        mesh2: &Mesh,
        nodes2: &[NodeId],
        case: Case,
    ) -> Result<(), ProjectionError> {
        let mut simplices = Vec::new();
        for &c in cells1 {
            let cell = mesh1.cell(c);
            if !case.accepts(cell.ty) {
                continue;
            }
            for s in splits(cell.ty) {
                simplices.push(Simplex {
                    cell: c,
                    local: *s,
                    nodes: s.map(|i| cell.nodes[i]),
                });
            }
        }
        if simplices.is_empty() {
            return Err(err(
                "PROJECTION4_55",
                format!("no {} cell of mesh 1 to project from", case.name()),
            ));
        }
        // pjreco: the nodes an earlier occurrence already asked for.
        let interc: Vec<bool> = {
            let mut v = vec![false; self.seen.len()];
            for n in nodes2 {
                v[n.0 as usize] = self.seen[n.0 as usize];
            }
            v
        };
        let mut located = Vec::new();
        for &n in nodes2 {
            let p = mesh2.coord(n);
            let found = match case {
                Case::Volume => self.locate3d(mesh1, &simplices, p),
                Case::Plane => self.locate2d(mesh1, &simplices, p),
                Case::Surface => {
                    let r = self.nearest_surface(mesh1, &simplices, p);
                    match r {
                        Some((s, bary, loin)) if loin && interc[n.0 as usize] => {
                            // pj4dco: a far node an earlier occurrence took
                            // is left to it — and l_dmax stays on.
                            let _ = (s, bary);
                            self.l_dmax = true;
                            None
                        }
                        Some((s, bary, _)) => Some((s, bary)),
                        None => None,
                    }
                }
            };
            match found {
                Some(f) => located.push((n, f)),
                None if self.l_dmax => {}
                None => {
                    return Err(err(
                        "PROJECTION4_56",
                        format!("node {} cannot be located", mesh2.node_name(n)),
                    ))
                }
            }
        }
        let mut any = false;
        let mut out: Vec<(NodeId, Link)> = Vec::new();
        for (n, (si, bary)) in located {
            any = true;
            let s = &simplices[si];
            let cell = mesh1.cell(s.cell);
            let refn = reference_nodes(cell.ty);
            let p = mesh2.coord(n);
            let (ndim, coords, xg) = match case {
                Case::Volume => (3, cell_coords(mesh1, &cell.nodes, 3), p),
                Case::Plane => (2, cell_coords(mesh1, &cell.nodes, 2), p),
                Case::Surface => {
                    let (c, g) = in_plane(mesh1, s, &cell.nodes, p);
                    (2, c, g)
                }
            };
            let nv = if ndim == 3 { 4 } else { 3 };
            let mut xr1 = [0.0; 3];
            for k in 0..nv {
                for d in 0..ndim {
                    xr1[d] += bary[k] * refn[s.local[k]][d];
                }
            }
            let xr2 = reereg(cell.ty, &coords, ndim, xg);
            let disprj = match xr2 {
                Some(x) => outside(cell.ty, x),
                None => 999.0,
            };
            let lext = disprj > 1e-2;
            let (xr3, distv) = pjefmi(cell.ty, &coords, ndim, xg, xr1, xr2, lext);
            if distv >= self.dala && disprj != 999.0 && disprj > 1e-1 {
                if case != Case::Surface && interc[n.0 as usize] {
                    // pj3dtr/pj2dtr: left to the earlier occurrence.
                    continue;
                }
                self.far.push((n, distv));
            }
            let sh = shape(cell.ty, xr3);
            out.push((
                n,
                Link {
                    cell: s.cell,
                    nodes: cell.nodes.clone(),
                    coefs: sh.n,
                },
            ));
        }
        if !any {
            return Err(err(
                "CALCULEL3_97",
                "no node of mesh 2 could be projected (DISTANCE_MAX?)",
            ));
        }
        for n in nodes2 {
            self.seen[n.0 as usize] = true;
        }
        for (n, l) in out {
            self.links[n.0 as usize] = Some(l);
        }
        Ok(())
    }

    /// pj3dap: the first tetrahedron containing p, else the nearest (within
    /// DISTANCE_MAX when given).
    fn locate3d(
        &self,
        mesh: &Mesh,
        simplices: &[Simplex],
        p: [f64; 3],
    ) -> Option<(usize, [f64; 4])> {
        self.locate(mesh, simplices, p, inside_tetra, nearest_tetra)
    }

    /// pj2dap: the first triangle containing p (in x, y), else the nearest.
    fn locate2d(
        &self,
        mesh: &Mesh,
        simplices: &[Simplex],
        p: [f64; 3],
    ) -> Option<(usize, [f64; 4])> {
        self.locate(mesh, simplices, p, inside_triangle2d, nearest_triangle2d)
    }

    /// The first simplex containing p (`inside`), else the nearest one
    /// (`nearest`: barycentrics and squared distance), within DISTANCE_MAX
    /// when given: pj3dap's and pj2dap's common search.
    fn locate(
        &self,
        mesh: &Mesh,
        simplices: &[Simplex],
        p: [f64; 3],
        inside: InsideTest,
        nearest: NearestPoint,
    ) -> Option<(usize, [f64; 4])> {
        for (i, s) in simplices.iter().enumerate() {
            if let Some(b) = inside(mesh, &s.nodes, p) {
                return Some((i, b));
            }
        }
        let mut dmin = if self.l_dmax { self.dmax } else { f64::MAX };
        let mut best = None;
        for (i, s) in simplices.iter().enumerate() {
            let (b, d2) = nearest(mesh, &s.nodes, p);
            if d2.sqrt() < dmin {
                dmin = d2.sqrt();
                best = Some((i, b));
            }
        }
        best
    }

    /// pj4dap: the nearest triangle in 3D, and whether the node is far
    /// (distance above 10 % of √area, or DISTANCE_ALARME not given…).
    fn nearest_surface(
        &self,
        mesh: &Mesh,
        simplices: &[Simplex],
        p: [f64; 3],
    ) -> Option<(usize, [f64; 4], bool)> {
        let mut dmin = if self.l_dmax { self.dmax } else { f64::MAX };
        let mut best = None;
        let mut area = 0.0;
        for (i, s) in simplices.iter().enumerate() {
            let (b, d2, surf) = nearest_triangle3d(mesh, &s.nodes, p);
            if d2.sqrt() < dmin {
                dmin = d2.sqrt();
                best = Some((i, b));
                area = surf;
            }
        }
        let (i, b) = best?;
        let loin = if self.dala >= 0.0 {
            false
        } else {
            area == 0.0 || dmin / area.sqrt() > 1e-1
        };
        Some((i, b, loin))
    }
}

fn cell_coords(mesh: &Mesh, nodes: &[NodeId], ndim: usize) -> Vec<[f64; 3]> {
    nodes
        .iter()
        .map(|&n| {
            let mut c = mesh.coord(n);
            if ndim == 2 {
                c[2] = 0.0;
            }
            c
        })
        .collect()
}

/// pj4d2d: the cell's nodes and the point in the frame of the sub-triangle's
/// plane (e₁ along its first edge, e₂ = n × e₁).
fn in_plane(mesh: &Mesh, s: &Simplex, nodes: &[NodeId], p: [f64; 3]) -> (Vec<[f64; 3]>, [f64; 3]) {
    use aster_mesh::vec3::{cross, dot, sub};
    let a = mesh.coord(s.nodes[0]);
    let b = mesh.coord(s.nodes[1]);
    let c = mesh.coord(s.nodes[2]);
    let ab = sub(b, a);
    let ac = sub(c, a);
    let v = cross(ab, ac);
    let nv = dot(v, v).sqrt();
    let v = v.map(|x| x / nv);
    let nab = dot(ab, ab).sqrt();
    let e1 = ab.map(|x| x / nab);
    let e2 = cross(v, e1);
    let coords = nodes
        .iter()
        .map(|&n| {
            let x = mesh.coord(n);
            [dot(x, e1), dot(x, e2), 0.0]
        })
        .collect();
    (coords, [dot(p, e1), dot(p, e2), 0.0])
}

/// pj3da1: barycentric coordinates of p in a tetrahedron, when inside
/// (1e-10 tolerance).
fn inside_tetra(mesh: &Mesh, t: &[NodeId; 4], p: [f64; 3]) -> Option<[f64; 4]> {
    use aster_mesh::vec3::{cross, dot, sub};
    let pts = t.map(|n| mesh.coord(n));
    let mut bary = [0.0; 4];
    // lino cycles (1,2,3,4), (2,3,4,1), (3,4,1,2), (4,1,2,3).
    for rot in 0..4 {
        let l = [rot % 4, (rot + 1) % 4, (rot + 2) % 4, (rot + 3) % 4];
        let (p1, p2, p3, p4) = (pts[l[0]], pts[l[1]], pts[l[2]], pts[l[3]]);
        let n = cross(sub(p2, p1), sub(p3, p1));
        let vol = dot(n, sub(p4, p1));
        if vol == 0.0 {
            return None;
        }
        bary[l[3]] = dot(n, sub(p, p1)) / vol;
    }
    let eps = 1e-10;
    bary.iter()
        .all(|&b| b >= -eps && b <= 1.0 + eps)
        .then_some(bary)
}

/// pj3da3: the orthogonal projection of m on the plane of (a, b, c) when it
/// falls inside the triangle: its barycentrics and squared distance.
fn face_projection(m: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<([f64; 3], f64)> {
    use aster_mesh::vec3::{dot, sub};
    let ab = sub(b, a);
    let ac = sub(c, a);
    let am = sub(m, a);
    let a11 = dot(ab, ab);
    let a22 = dot(ac, ac);
    let a12 = dot(ab, ac);
    let b1 = dot(ab, am);
    let b2 = dot(ac, am);
    let delta = a11 * a22 - a12 * a12;
    if delta == 0.0 {
        return None;
    }
    let lb = (a22 * b1 - a12 * b2) / delta;
    let lc = (a11 * b2 - a12 * b1) / delta;
    let la = 1.0 - lb - lc;
    if [la, lb, lc].iter().all(|&l| (0.0..=1.0).contains(&l)) {
        let mut d2 = 0.0;
        for k in 0..3 {
            let q = m[k] - (la * a[k] + lb * b[k] + lc * c[k]);
            d2 += q * q;
        }
        Some(([la, lb, lc], d2))
    } else {
        None
    }
}

/// pj3da4: the closest point of segment [a, b] to m: (λa, λb, squared
/// distance).
fn edge_projection(m: [f64; 3], a: [f64; 3], b: [f64; 3]) -> (f64, f64, f64) {
    use aster_mesh::vec3::{dot, sub};
    let ab = sub(b, a);
    let am = sub(m, a);
    let a1 = dot(am, ab);
    let a2 = dot(ab, ab);
    let mut lb = if a2 == 0.0 { 0.5 } else { a1 / a2 };
    lb = lb.clamp(0.0, 1.0);
    let la = 1.0 - lb;
    let mut d2 = 0.0;
    for k in 0..3 {
        let q = m[k] - (la * a[k] + lb * b[k]);
        d2 += q * q;
    }
    (la, lb, d2)
}

/// pj3da2: the closest point of a tetrahedron's boundary to m (faces, then
/// edges), as barycentrics, and the squared distance.
fn nearest_tetra(mesh: &Mesh, t: &[NodeId; 4], m: [f64; 3]) -> ([f64; 4], f64) {
    let p = t.map(|n| mesh.coord(n));
    let mut d2 = f64::MAX;
    let mut l = [0.0; 4];
    for (i, j, k) in [(0, 1, 2), (1, 2, 3), (2, 3, 0), (3, 0, 1)] {
        if let Some((b, dp)) = face_projection(m, p[i], p[j], p[k]) {
            if dp < d2 {
                d2 = dp;
                l = [0.0; 4];
                l[i] = b[0];
                l[j] = b[1];
                l[k] = b[2];
            }
        }
    }
    for (i, j) in [(0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (1, 3)] {
        let (la, lb, dp) = edge_projection(m, p[i], p[j]);
        if dp < d2 {
            d2 = dp;
            l = [0.0; 4];
            l[i] = la;
            l[j] = lb;
        }
    }
    (l, d2)
}

/// pj4da2: the closest point of a triangle in 3D, its squared distance and
/// the triangle's area.
fn nearest_triangle3d(mesh: &Mesh, t: &[NodeId; 4], m: [f64; 3]) -> ([f64; 4], f64, f64) {
    use aster_mesh::vec3::{cross, dot, sub};
    let p = [mesh.coord(t[0]), mesh.coord(t[1]), mesh.coord(t[2])];
    let mut d2 = f64::MAX;
    let mut l = [0.0; 4];
    if let Some((b, dp)) = face_projection(m, p[0], p[1], p[2]) {
        d2 = dp;
        l = [b[0], b[1], b[2], 0.0];
    }
    for (i, j) in [(0, 1), (1, 2), (0, 2)] {
        let (la, lb, dp) = edge_projection(m, p[i], p[j]);
        if dp < d2 {
            d2 = dp;
            l = [0.0; 4];
            l[i] = la;
            l[j] = lb;
        }
    }
    let v = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    (l, d2, dot(v, v).sqrt() / 2.0)
}

/// pj2da1: barycentrics of p in a triangle of the (x, y) plane, when inside.
fn inside_triangle2d(mesh: &Mesh, t: &[NodeId; 4], p: [f64; 3]) -> Option<[f64; 4]> {
    let [x1, y1, _] = mesh.coord(t[0]);
    let [x2, y2, _] = mesh.coord(t[1]);
    let [x3, y3, _] = mesh.coord(t[2]);
    let v2 = [x2 - x1, y2 - y1];
    let v3 = [x3 - x1, y3 - y1];
    let s = v2[0] * v3[1] - v2[1] * v3[0];
    if s == 0.0 {
        return None;
    }
    let q = [p[0] - x1, p[1] - y1];
    let l3 = (v2[0] * q[1] - v2[1] * q[0]) / s;
    let l2 = (q[0] * v3[1] - q[1] * v3[0]) / s;
    let l1 = 1.0 - l2 - l3;
    let eps = 1e-10;
    [l1, l2, l3]
        .iter()
        .all(|&l| l >= -eps && l <= 1.0 + eps)
        .then_some([l1, l2, l3, 0.0])
}

/// pj2da2: the closest point of a triangle's edges in the (x, y) plane.
fn nearest_triangle2d(mesh: &Mesh, t: &[NodeId; 4], m: [f64; 3]) -> ([f64; 4], f64) {
    let p = [t[0], t[1], t[2]].map(|n| {
        let c = mesh.coord(n);
        [c[0], c[1]]
    });
    let mut d2 = f64::MAX;
    let mut l = [0.0; 4];
    // Edges 2→3, 3→1, 1→2 as pj2da2 visits them: λ(start) = 1 − ksi.
    for (i, j) in [(1, 2), (2, 0), (0, 1)] {
        let v = [p[j][0] - p[i][0], p[j][1] - p[i][1]];
        let q = [m[0] - p[i][0], m[1] - p[i][1]];
        let xc = v[0] * v[0] + v[1] * v[1];
        let ksi = if xc == 0.0 {
            0.5
        } else {
            (q[0] * v[0] + q[1] * v[1]) / xc
        }
        .clamp(0.0, 1.0);
        let xp = ksi * p[j][0] + (1.0 - ksi) * p[i][0];
        let yp = ksi * p[j][1] + (1.0 - ksi) * p[i][1];
        let dist = (xp - m[0]) * (xp - m[0]) + (yp - m[1]) * (yp - m[1]);
        if dist < d2 {
            d2 = dist;
            l = [0.0; 4];
            l[i] = 1.0 - ksi;
            l[j] = ksi;
        }
    }
    (l, d2)
}

/// The point of a cell at reference coordinates ξ.
fn image(ty: CellType, coords: &[[f64; 3]], ndim: usize, xi: [f64; 3]) -> [f64; 3] {
    let s = shape(ty, xi);
    let mut x = [0.0; 3];
    for (n, c) in s.n.iter().zip(coords) {
        for d in 0..ndim {
            x[d] += n * c[d];
        }
    }
    x
}

/// `reereg`: Newton from ξ = 0 for the reference coordinates of xg in the
/// cell, stopped when the squared step is ≤ 1e-8 (the last step applied);
/// `None` after 50 iterations or on a singular Jacobian.
pub fn reereg(ty: CellType, coords: &[[f64; 3]], ndim: usize, xg: [f64; 3]) -> Option<[f64; 3]> {
    let mut xe = [0.0; 3];
    for _ in 0..50 {
        let s = shape(ty, xe);
        let mut point = [0.0; 3];
        // jac[k][d] = ∂x_d/∂ξ_k
        let mut jac = [[0.0; 3]; 3];
        for (i, c) in coords.iter().enumerate() {
            for d in 0..ndim {
                point[d] += s.n[i] * c[d];
                for k in 0..ndim {
                    jac[k][d] += s.dn[i][k] * c[d];
                }
            }
        }
        let r: Vec<f64> = (0..ndim).map(|d| point[d] - xg[d]).collect();
        let step = solve_transposed(&jac, ndim, &r)?;
        let mut err = 0.0;
        for k in 0..ndim {
            xe[k] -= step[k];
            err += step[k] * step[k];
        }
        if err <= 1e-8 {
            return Some(xe);
        }
    }
    None
}

/// Solves Σ_k jac[k][d] δ_k = r_d (the Jacobian ∂x/∂ξ applied to δ).
fn solve_transposed(jac: &[[f64; 3]; 3], ndim: usize, r: &[f64]) -> Option<[f64; 3]> {
    // a[d][k] = jac[k][d]
    let a = |d: usize, k: usize| jac[k][d];
    if ndim == 2 {
        let det = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
        if det == 0.0 {
            return None;
        }
        Some([
            (a(1, 1) * r[0] - a(0, 1) * r[1]) / det,
            (a(0, 0) * r[1] - a(1, 0) * r[0]) / det,
            0.0,
        ])
    } else {
        let det = a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1))
            - a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0))
            + a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
        if det == 0.0 {
            return None;
        }
        let mut x = [0.0; 3];
        for (k, xk) in x.iter_mut().enumerate() {
            // Cramer: replace column k by r.
            let m = |d: usize, j: usize| if j == k { r[d] } else { a(d, j) };
            *xk = (m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
                - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
                + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0)))
                / det;
        }
        Some(x)
    }
}

/// `pjeflo`: how far outside its reference cell ξ lies (0 inside), relative
/// to the reference cell's diameter.
pub fn outside(ty: CellType, xi: [f64; 3]) -> f64 {
    use CellType::*;
    let [x, y, z] = xi;
    let over = |v: &[f64], diam: f64| v.iter().fold(0.0f64, |m, &a| m.max(a)) / diam;
    match ty {
        HEXA8 | HEXA20 | HEXA27 => over(&[x.abs() - 1., y.abs() - 1., z.abs() - 1.], 2.),
        TETRA4 | TETRA10 => over(&[-x, -y, -z, x + y + z - 1.], 1.),
        PYRAM5 | PYRAM13 => over(
            &[
                -z,
                x + y + z - 1.,
                x - y + z - 1.,
                -x + y + z - 1.,
                -x - y + z - 1.,
            ],
            2.,
        ),
        PENTA6 | PENTA15 | PENTA18 => over(&[x.abs() - 1., -y, -z, y + z - 1.], 2.),
        TRIA3 | TRIA6 | TRIA7 => over(&[-x, -y, x + y - 1.], 1.),
        QUAD4 | QUAD8 | QUAD9 => over(&[-1. - x, -1. - y, x - 1., y - 1.], 2.),
        _ => 0.0,
    }
}

/// `pjefmi`: of ξ₁ (from the sub-simplex) and ξ₂ (Newton), the one whose
/// image is nearer the node (ξ₁ when ξ₂ is outside, `lext`), with that
/// distance.
fn pjefmi(
    ty: CellType,
    coords: &[[f64; 3]],
    ndim: usize,
    xg: [f64; 3],
    x1: [f64; 3],
    x2: Option<[f64; 3]>,
    lext: bool,
) -> ([f64; 3], f64) {
    let dist = |xi: [f64; 3]| {
        let p = image(ty, coords, ndim, xi);
        (0..ndim).map(|d| (p[d] - xg[d]).powi(2)).sum::<f64>()
    };
    let d1 = dist(x1);
    match x2 {
        Some(x2) if !lext => {
            let d2 = dist(x2);
            if d1 <= d2 {
                (x1, d1.sqrt())
            } else {
                (x2, d2.sqrt())
            }
        }
        _ => (x1, d1.sqrt()),
    }
}

/// `cnsprj`: the projected value of one component at a node of mesh 2
/// from the values at mesh 1's nodes (`None`: no value there). All present:
/// Σ cᵢ vᵢ. Some missing: Σ over the present nodes of positive coefficient,
/// divided by the sum of those coefficients; none of positive coefficient:
/// the mean of the present values. `None` when no node has a value.
pub fn interpolate(link: &Link, value: impl Fn(NodeId) -> Option<f64>) -> Option<f64> {
    let vals: Vec<Option<f64>> = link.nodes.iter().map(|&n| value(n)).collect();
    let present = vals.iter().filter(|v| v.is_some()).count();
    if present == 0 {
        return None;
    }
    if present == vals.len() {
        return Some(
            link.coefs
                .iter()
                .zip(&vals)
                .map(|(c, v)| c * v.unwrap_or(0.0))
                .sum(),
        );
    }
    let mut coetot = 0.0;
    let mut positive = 0;
    let mut sum = 0.0;
    let mut mean = 0.0;
    for (c, v) in link.coefs.iter().zip(&vals) {
        if let Some(v) = v {
            mean += v;
            if *c > 0.0 {
                positive += 1;
                coetot += c;
                sum += c * v;
            }
        }
    }
    if positive == 0 {
        return Some(mean / present as f64);
    }
    Some(sum / coetot)
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_mesh::Cell;

    fn mesh(coords: Vec<[f64; 3]>, cells: Vec<(CellType, Vec<u32>)>) -> Mesh {
        let n = coords.len();
        let m = cells.len();
        Mesh {
            dim: 3,
            coords,
            node_names: (1..=n).map(|i| format!("N{i}")).collect(),
            cells: cells
                .into_iter()
                .map(|(ty, nodes)| Cell {
                    ty,
                    nodes: nodes.into_iter().map(NodeId).collect(),
                })
                .collect(),
            cell_names: (1..=m).map(|i| format!("M{i}")).collect(),
            groups_ma: vec![],
            groups_no: vec![],
        }
    }

    /// A distorted HEXA20 (curved edges): the reference nodes mapped by a
    /// quadratic transformation.
    fn hexa20() -> (Mesh, impl Fn([f64; 3]) -> [f64; 3]) {
        let map = |x: [f64; 3]| {
            [
                2.0 + 1.5 * x[0] + 0.1 * x[1] * x[1],
                -1.0 + 1.2 * x[1] + 0.08 * x[0] * x[2],
                0.5 + 0.9 * x[2] + 0.05 * x[0] * x[0],
            ]
        };
        let coords = reference_nodes(CellType::HEXA20)
            .into_iter()
            .map(map)
            .collect();
        (
            mesh(coords, vec![(CellType::HEXA20, (0..20).collect())]),
            map,
        )
    }

    #[test]
    fn quadratic_cell_reproduces_its_own_fields() {
        // Nodal values of f(ξ) = a quadratic serendipity function: the
        // projection at a point of known ξ returns f(ξ) to round-off.
        let (m1, map) = hexa20();
        let f = |x: [f64; 3]| 1.0 + x[0] - 2.0 * x[1] * x[2] + 0.5 * x[0] * x[0];
        let refn = reference_nodes(CellType::HEXA20);
        let vals: Vec<f64> = refn.iter().map(|&x| f(x)).collect();
        let xi = [0.3, -0.55, 0.7];
        let target = mesh(vec![map(xi)], vec![(CellType::POI1, vec![0])]);
        let mut c = Correspondence::new(&target, Options::default());
        c.add(&m1, &[CellId(0)], &target, &[NodeId(0)], Case::Volume)
            .unwrap();
        let link = c.links[0].clone().unwrap();
        let v = interpolate(&link, |n| Some(vals[n.0 as usize])).unwrap();
        assert!((v - f(xi)).abs() < 1e-9, "{v} vs {}", f(xi));
    }

    #[test]
    fn newton_inverts_the_map() {
        let (m1, map) = hexa20();
        let coords: Vec<[f64; 3]> = m1.coords.clone();
        for xi in [[0.1, 0.2, -0.3], [-0.9, 0.95, 0.0], [0.0, 0.0, 0.0]] {
            let x = reereg(CellType::HEXA20, &coords, 3, map(xi)).unwrap();
            for k in 0..3 {
                assert!((x[k] - xi[k]).abs() < 1e-6, "{x:?} vs {xi:?}");
            }
        }
    }

    #[test]
    fn quad_split_and_outside_node() {
        // Two QUAD4 side by side in the plane; a node outside (x = 2.5) gets
        // the value extrapolated from the nearest cell, or none with
        // DISTANCE_MAX below its distance.
        let m1 = mesh(
            vec![
                [0., 0., 0.],
                [1., 0., 0.],
                [2., 0., 0.],
                [0., 1., 0.],
                [1., 1., 0.],
                [2., 1., 0.],
            ],
            vec![
                (CellType::QUAD4, vec![0, 1, 4, 3]),
                (CellType::QUAD4, vec![1, 2, 5, 4]),
            ],
        );
        let target = mesh(
            vec![[0.25, 0.75, 0.], [1.6, 0.3, 0.], [2.5, 0.5, 0.]],
            vec![(CellType::POI1, vec![0])],
        );
        let f = |p: [f64; 3]| 3.0 * p[0] - p[1] + 0.5;
        let cells = [CellId(0), CellId(1)];
        let nodes = [NodeId(0), NodeId(1), NodeId(2)];
        let mut c = Correspondence::new(&target, Options::default());
        c.add(&m1, &cells, &target, &nodes, Case::Plane).unwrap();
        for (i, l) in c.links.iter().enumerate() {
            let v = interpolate(l.as_ref().unwrap(), |n| Some(f(m1.coord(n)))).unwrap();
            let p = target.coords[i];
            if i < 2 {
                assert!((v - f(p)).abs() < 1e-12, "node {i}: {v}");
            } else {
                // 25 % outside in reference length: pjefmi keeps the
                // nearest point on the cell (x = 2).
                assert!((v - f([2.0, 0.5, 0.0])).abs() < 1e-12, "node {i}: {v}");
            }
        }
        let mut c = Correspondence::new(
            &target,
            Options {
                distance_max: Some(0.4),
                distance_alarme: None,
            },
        );
        c.add(&m1, &cells, &target, &nodes, Case::Plane).unwrap();
        assert!(c.links[2].is_none());
        assert!(c.links[1].is_some());
    }

    #[test]
    fn later_occurrences_override_except_far_nodes_asked_before() {
        // Two unit cubes 3 apart; node 0 inside the first, node 1 beside
        // the second.
        let cube = |x0: f64| -> Vec<[f64; 3]> {
            crate::refcells::HEXA8
                .iter()
                .map(|r| [x0 + (r[0] + 1.) / 2., (r[1] + 1.) / 2., (r[2] + 1.) / 2.])
                .collect()
        };
        let mut coords = cube(0.0);
        coords.extend(cube(3.0));
        let m1 = mesh(
            coords,
            vec![
                (CellType::HEXA8, (0..8).collect()),
                (CellType::HEXA8, (8..16).collect()),
            ],
        );
        let target = mesh(
            vec![[0.5, 0.5, 0.5], [2.5, 0.5, 0.5]],
            vec![(CellType::POI1, vec![0])],
        );
        let mut c = Correspondence::new(&target, Options::default());
        c.add(&m1, &[CellId(0)], &target, &[NodeId(0)], Case::Volume)
            .unwrap();
        assert_eq!(c.links[0].as_ref().unwrap().cell, CellId(0));
        // Occurrence 2 on the second cube: node 0, asked before and 250 %
        // outside, stays with occurrence 1; node 1 (new) is taken, far.
        c.add(
            &m1,
            &[CellId(1)],
            &target,
            &[NodeId(0), NodeId(1)],
            Case::Volume,
        )
        .unwrap();
        assert_eq!(c.links[0].as_ref().unwrap().cell, CellId(0));
        assert_eq!(c.links[1].as_ref().unwrap().cell, CellId(1));
        assert_eq!(c.far.len(), 1);
        // A third occurrence on the first cube takes node 0 again (inside).
        c.add(&m1, &[CellId(0)], &target, &[NodeId(0)], Case::Volume)
            .unwrap();
        assert_eq!(c.links[0].as_ref().unwrap().cell, CellId(0));
    }

    #[test]
    fn missing_values_follow_cnsprj() {
        let link = Link {
            cell: CellId(0),
            nodes: vec![NodeId(0), NodeId(1), NodeId(2)],
            coefs: vec![0.5, 0.3, 0.2],
        };
        let v = interpolate(&link, |n| (n.0 != 1).then_some(n.0 as f64 + 1.0)).unwrap();
        assert!((v - (0.5 * 1.0 + 0.2 * 3.0) / 0.7).abs() < 1e-15);
        assert_eq!(interpolate(&link, |_| None), None);
    }
}
