//! A 3D crack front as code_aster's `DEFI_FOND_FISS` builds it from a
//! meshed crack (`op0060`): the front's nodes in order (`fonmai`), the
//! local basis at each node (`BASEFOND`: `fonnor` with `fonno1`…`fonno8`),
//! the cell size at each node (`FOND.TAILLE_R`, `fonno7`) and the lip
//! nodes in the plane normal to the front at each node (`SUPNORM.NOEU`,
//! `INFNORM.NOEU`: `fonnof`, `cgnop0`, `oreino`), which `POST_K1_K2_K3`
//! reads on a regular ("REGLE") mesh.
//!
//! Fronts of `SEG2` or `SEG3` cells with lips on both sides (`SYME='NON'`)
//! only. On a `SEG3` front (`fonnor2`'s `QUADRATIQUE`) each cell's middle
//! node lies between its ends in the node list, the segments below run
//! between the cells' ends, fan cells are face neighbours when they share
//! 6 nodes (3 on a linear front), a middle node takes its segment's basis
//! and the mean of its ends' sizes.
//!
//!
//! - each front segment [a, b]: the 3D cells holding a and b (the fan
//!   around the segment); the two cells of the fan with a single face
//!   neighbour in the fan are the ones on the lips (`fonno2`); of their
//!   faces holding a and b, the ones no other fan cell shares are the lip
//!   faces (`fonno3`, `fonno4`). On each lip face, ordered a, b, …: the
//!   in-plane direction perpendicular to ab and pointing away from the
//!   face (`gdire3`) and the normal `dir × (b − a)` (`fonno5`); the
//!   segment's basis is the normalised sum over the two faces (`fonno6`),
//!   its normal turned, on the first segment, towards the centroid of the
//!   cell that holds an upper-lip face (`fonno8`), and kept on that side
//!   for the next segments;
//! - a node's basis: the normalised sum of its segments' bases; at the two
//!   ends the direction is turned into the free surface the front ends on
//!   (`fonext`, see [`turn_end`]);
//! - the size at a node (`fonno7`): the largest projection on the node's
//!   direction of the 3D cells' edges from the node within 70° of it.

pub(crate) use aster_mesh::vec3::{add, cross, dot, normalize, sub};
use aster_mesh::{CellId, CellType, Mesh, NodeId};
use std::collections::HashMap;

/// The crack front and what DEFI_FOND_FISS stores for it.
#[derive(Clone, Debug, PartialEq)]
pub struct Front3d {
    /// The front's nodes from the origin to the end (`FOND.NOEU`).
    pub nodes: Vec<NodeId>,
    /// The unit normal to the crack at each node, from the lower lip
    /// towards the upper one (`BASEFOND` 1–3).
    pub normal: Vec<[f64; 3]>,
    /// The unit direction of propagation at each node (`BASEFOND` 4–6).
    pub dir: Vec<[f64; 3]>,
    /// The cell size at each node (`FOND.TAILLE_R`).
    pub size: Vec<f64>,
    /// At each node, up to 20 nodes of the upper lip in the plane normal
    /// to the front, from the front outwards (`SUPNORM.NOEU`); empty when
    /// fewer than 3 lie there.
    pub sup_normal: Vec<Vec<NodeId>>,
    /// The same on the lower lip (`INFNORM.NOEU`).
    pub inf_normal: Vec<Vec<NodeId>>,
    /// A front of SEG3 cells (each cell's middle node between its ends).
    pub quadratic: bool,
    /// The first upper-lip cell is quadratic (`LEVRESUP.MAIL`, which
    /// CALC_G reads as its `milieu`: theta fields at the middle nodes).
    pub quadratic_lips: bool,
}

/// What the front is built from.
pub struct FrontInput<'a> {
    pub mesh: &'a Mesh,
    /// The front's segments (SEG2 cells).
    pub segments: &'a [CellId],
    /// The origin (`GROUP_NO_ORIG`); its end, when given (`GROUP_NO_EXTR`).
    pub origin: NodeId,
    pub end: Option<NodeId>,
    /// The lips' cells (`LEVRE_SUP`, `LEVRE_INF`).
    pub lip_sup: &'a [CellId],
    pub lip_inf: &'a [CellId],
    /// `PREC_NORM`: the half-thickness of the normal plane, relative to
    /// the distance to the next front node.
    pub prec_norm: f64,
}

/// The corner faces of a 3D cell, as cycles of local node indices
/// (code_aster's `confac`, up to the order of the faces).
fn faces(ty: CellType) -> &'static [&'static [usize]] {
    use CellType::*;
    match ty {
        TETRA4 | TETRA10 => &[&[0, 1, 2], &[0, 1, 3], &[1, 2, 3], &[2, 0, 3]],
        PYRAM5 | PYRAM13 => &[
            &[0, 1, 2, 3],
            &[0, 1, 4],
            &[1, 2, 4],
            &[2, 3, 4],
            &[3, 0, 4],
        ],
        PENTA6 | PENTA15 | PENTA18 => &[
            &[0, 1, 2],
            &[3, 4, 5],
            &[0, 1, 4, 3],
            &[1, 2, 5, 4],
            &[2, 0, 3, 5],
        ],
        HEXA8 | HEXA20 | HEXA27 => &[
            &[0, 3, 2, 1],
            &[0, 1, 5, 4],
            &[1, 2, 6, 5],
            &[2, 3, 7, 6],
            &[0, 4, 7, 3],
            &[4, 5, 6, 7],
        ],
        _ => &[],
    }
}

/// The corner edges of a 3D cell (code_aster's `conare`); none for the
/// others.
fn edges(ty: CellType) -> &'static [[usize; 2]] {
    if ty.dim() == 3 {
        ty.corner_edges()
    } else {
        &[]
    }
}

fn corners(ty: CellType) -> usize {
    crate::shape::corner_count(ty)
}

struct Geometry<'a> {
    mesh: &'a Mesh,
    /// The 3D cells holding each node, in increasing cell order.
    cells_of: HashMap<NodeId, Vec<CellId>>,
}

impl<'a> Geometry<'a> {
    fn new(mesh: &'a Mesh) -> Self {
        let mut cells_of: HashMap<NodeId, Vec<CellId>> = HashMap::new();
        for (i, c) in mesh.cells.iter().enumerate() {
            if c.ty.dim() != 3 {
                continue;
            }
            for &n in &c.nodes {
                let v = cells_of.entry(n).or_default();
                if v.last() != Some(&CellId(i as u32)) {
                    v.push(CellId(i as u32));
                }
            }
        }
        Geometry { mesh, cells_of }
    }

    fn cells(&self, n: NodeId) -> &[CellId] {
        self.cells_of.get(&n).map(Vec::as_slice).unwrap_or(&[])
    }

    fn name(&self, n: NodeId) -> String {
        self.mesh
            .node_names
            .get(n.0 as usize)
            .cloned()
            .unwrap_or_else(|| format!("N{}", n.0 + 1))
    }
}

/// `fonmai2` + `ornofd`: the front's nodes in order from the origin; on a
/// front of SEG3 cells (`quadratic`), each cell's middle node (its third)
/// between its two ends.
fn order_front(input: &FrontInput) -> Result<(Vec<NodeId>, bool), String> {
    let mesh = input.mesh;
    // code_aster reads the type of the first cell (`typm`) for all of them.
    let quadratic = match input.segments.first().map(|&c| mesh.cell(c).ty) {
        Some(CellType::SEG3) => true,
        Some(CellType::SEG2) | None => false,
        Some(ty) => {
            return Err(format!(
                "the front cell {} is a {}: aster builds fronts of SEG2 or SEG3 cells",
                mesh.cell_name(input.segments[0]),
                ty.name()
            ))
        }
    };
    let want = if quadratic {
        CellType::SEG3
    } else {
        CellType::SEG2
    };
    // (end, end, middle)
    let mut segs: Vec<[NodeId; 3]> = Vec::new();
    for &c in input.segments {
        let cell = mesh.cell(c);
        if cell.ty != want {
            return Err(format!(
                "the front cell {} is a {}, the first one a {}: aster builds fronts of one cell type",
                mesh.cell_name(c),
                cell.ty.name(),
                want.name()
            ));
        }
        let mid = if quadratic {
            cell.nodes[2]
        } else {
            cell.nodes[0]
        };
        segs.push([cell.nodes[0], cell.nodes[1], mid]);
    }
    let mut used = vec![false; segs.len()];
    let mut nodes = vec![input.origin];
    let mut cur = input.origin;
    loop {
        let next = segs.iter().enumerate().find_map(|(i, s)| {
            if used[i] {
                None
            } else if s[0] == cur {
                Some((i, s[1], s[2]))
            } else if s[1] == cur {
                Some((i, s[0], s[2]))
            } else {
                None
            }
        });
        let Some((i, n, mid)) = next else { break };
        used[i] = true;
        if quadratic {
            nodes.push(mid);
        }
        nodes.push(n);
        cur = n;
    }
    if nodes.len() == 1 {
        return Err("no front segment holds the origin node".to_string());
    }
    if used.iter().any(|u| !u) {
        return Err("the front's segments do not form one line from the origin".to_string());
    }
    if nodes.first() == nodes.last() {
        return Err("a closed front (TYPE_FOND='FERME')".to_string());
    }
    if let Some(end) = input.end {
        if nodes.last() != Some(&end) {
            return Err(
                "the front's line from the origin does not end at GROUP_NO_EXTR".to_string(),
            );
        }
    }
    Ok((nodes, quadratic))
}

/// The lip faces at a segment [a, b] and the two lip cells (`fonno1`…`fonno4`):
/// the faces as node lists, each with the lip cell it belongs to.
fn lip_faces(
    g: &Geometry,
    a: NodeId,
    b: NodeId,
    shared_min: usize,
) -> Result<(Vec<Vec<NodeId>>, [CellId; 2]), String> {
    let mesh = g.mesh;
    let fan: Vec<CellId> = g
        .cells(a)
        .iter()
        .copied()
        .filter(|&c| mesh.cell(c).nodes.contains(&b))
        .collect();
    let shared = |x: CellId, y: CellId| {
        let nx = &mesh.cell(x).nodes;
        let ny = &mesh.cell(y).nodes;
        nx.iter()
            .map(|n| ny.iter().filter(|m| *m == n).count())
            .sum::<usize>()
    };
    // fonno2: the cells with a single face neighbour in the fan (sharing
    // at least `shared_min` nodes: `nbmax`, 3 on a linear front, 6 on a
    // quadratic one, whose cells share their 3 edge nodes).
    let mut ends = Vec::new();
    for &p in &fan {
        let np = mesh.cell(p).nodes.len();
        let count = fan
            .iter()
            .filter(|&&q| {
                let s = shared(p, q);
                (s != np && s >= shared_min) || fan.len() == 1
            })
            .count();
        if count == 1 {
            ends.push(p);
        }
    }
    let [c1, c2] = ends[..] else {
        return Err(format!(
            "the 3D cells around the front segment {}–{} do not open on two lips ({} cells at the lips)",
            g.name(a),
            g.name(b),
            ends.len()
        ));
    };
    // fonno3: the faces of both cells holding a and b.
    let mut rows: Vec<(Vec<NodeId>, CellId)> = Vec::new();
    for c in [c1, c2] {
        let cell = mesh.cell(c);
        for f in faces(cell.ty) {
            let nodes: Vec<NodeId> = f.iter().map(|&i| cell.nodes[i]).collect();
            if nodes.contains(&a) && nodes.contains(&b) {
                rows.push((nodes, c));
            }
        }
    }
    // fonno4: the faces another fan cell shares are inside the body.
    let mut inner = vec![false; rows.len()];
    let mut any = false;
    for &m in &fan {
        if m == c1 || m == c2 {
            continue;
        }
        let mn = &mesh.cell(m).nodes;
        for (r, (f, _)) in rows.iter().enumerate() {
            let count = mn
                .iter()
                .map(|n| f.iter().filter(|x| *x == n).count())
                .sum::<usize>();
            if count >= 3 {
                inner[r] = true;
                any = true;
            }
        }
    }
    if !any && fan.len() == 2 {
        for p in 0..rows.len() {
            for q in 0..rows.len() {
                if p == q {
                    continue;
                }
                let count = rows[p]
                    .0
                    .iter()
                    .map(|n| rows[q].0.iter().filter(|x| *x == n).count())
                    .sum::<usize>();
                if count >= 3 {
                    inner[q] = true;
                }
            }
        }
    }
    let lips: Vec<Vec<NodeId>> = rows
        .iter()
        .zip(&inner)
        .filter(|(_, i)| !**i)
        .map(|((f, _), _)| f.clone())
        .collect();
    if lips.len() != 2 {
        return Err(format!(
            "{} lip faces at the front segment {}–{} (two expected: one on each lip)",
            lips.len(),
            g.name(a),
            g.name(b)
        ));
    }
    Ok((lips, [c1, c2]))
}

/// `fonno5` + `gdire3`: the direction and normal of a lip face at [a, b].
fn face_basis(mesh: &Mesh, face: &[NodeId], a: NodeId, b: NodeId) -> ([f64; 3], [f64; 3]) {
    let n = face.len();
    let ia = face.iter().position(|&x| x == a).unwrap_or(0);
    let ordered: Vec<NodeId> = if face[(ia + 1) % n] == b {
        (0..n).map(|k| face[(ia + k) % n]).collect()
    } else {
        (0..n).map(|k| face[(ia + n - k) % n]).collect()
    };
    let p1 = mesh.coord(ordered[0]);
    let p2 = mesh.coord(ordered[1]);
    let p3 = mesh.coord(if n == 3 { ordered[2] } else { ordered[3] });
    let v1 = normalize(sub(p2, p1));
    // gdire3
    let x12 = sub(p2, p1);
    let x13 = sub(p3, p1);
    let norm2 = dot(x12, x12);
    let ps = dot(x12, x13);
    let mut d = normalize([
        x13[0] - ps * x12[0] / norm2,
        x13[1] - ps * x12[1] / norm2,
        x13[2] - ps * x12[2] / norm2,
    ]);
    if dot(x13, d) >= 1e-6 {
        d = [-d[0], -d[1], -d[2]];
    }
    let nor = normalize(cross(d, v1));
    (d, nor)
}

/// `fonno8`: from the first front node to the centroid of the lip cell
/// that holds an upper-lip face.
fn upper_side(input: &FrontInput, cells: [CellId; 2], first: NodeId) -> [f64; 3] {
    let mesh = input.mesh;
    let mut chosen = cells[1];
    'search: for c in cells {
        let cn = &mesh.cell(c).nodes;
        for &l in input.lip_sup {
            let ln = &mesh.cell(l).nodes;
            let count = ln
                .iter()
                .map(|n| cn.iter().filter(|x| *x == n).count())
                .sum::<usize>();
            if count >= ln.len() {
                chosen = c;
                break 'search;
            }
        }
    }
    let cell = mesh.cell(chosen);
    let nc = corners(cell.ty);
    let mut g = [0.0; 3];
    for &n in &cell.nodes[..nc] {
        g = add(g, mesh.coord(n));
    }
    let p = mesh.coord(first);
    [
        g[0] / nc as f64 - p[0],
        g[1] / nc as f64 - p[1],
        g[2] / nc as f64 - p[2],
    ]
}

/// What `fonext` remembers about an end node across the cells around it.
struct EndState {
    /// The direction before the first change (`VDIROL`).
    dir_old: [f64; 3],
    /// Changed once already (`LBORD`).
    changed: bool,
    /// The side of the first free face's normal (`NVDIR`).
    side: i32,
}

/// `fonext` + `xfabor`, `xnorme`, `xextre`: at a front end, the direction
/// turned into the free faces the front ends on: for each 3D cell holding
/// the end node, its faces holding the end but not its neighbour on the
/// front that no other 3D cell shares (free), their outward normal n
/// unless within 0.95 of the crack's normal (the lips); the direction
/// becomes the sum over them of ±(normal × n), each on the side of the
/// former direction, normalised.
fn turn_end(g: &Geometry, end: NodeId, neighbour: NodeId, normal: [f64; 3], dir: &mut [f64; 3]) {
    let mesh = g.mesh;
    let mut state = EndState {
        dir_old: *dir,
        changed: false,
        side: 0,
    };
    for &c in g.cells(end) {
        let cell = mesh.cell(c);
        let nn = cell.nodes.len();
        let mut centre = [0.0; 3];
        for &n in &cell.nodes {
            centre = add(centre, mesh.coord(n));
        }
        let centre = [
            centre[0] / nn as f64,
            centre[1] / nn as f64,
            centre[2] / nn as f64,
        ];
        let mut normals: Vec<[f64; 3]> = Vec::new();
        let mut seen = 0usize;
        for f in faces(cell.ty) {
            let nodes: Vec<NodeId> = f.iter().map(|&i| cell.nodes[i]).collect();
            if nodes.contains(&neighbour) || !nodes.contains(&end) {
                continue;
            }
            let shared = g
                .cells(nodes[0])
                .iter()
                .filter(|&&o| {
                    let on = &mesh.cell(o).nodes;
                    on.contains(&nodes[1]) && on.contains(&nodes[2])
                })
                .count();
            if shared != 1 {
                continue;
            }
            let pa = mesh.coord(nodes[0]);
            let mut n = cross(sub(mesh.coord(nodes[1]), pa), sub(mesh.coord(nodes[2]), pa));
            if dot(n, sub(centre, pa)) > 0.0 {
                n = [-n[0], -n[1], -n[2]];
            }
            seen += 1;
            if dot(normalize(n), normal).abs() >= 0.95 {
                continue;
            }
            normals.push(n);
        }
        if normals.is_empty() {
            continue;
        }
        // xextre
        let points = if seen >= 2 { 2 } else { 1 };
        let mut change = true;
        let mut vecmax = false;
        for i in 0..points {
            if !state.changed {
                state.dir_old = *dir;
            }
            let old = state.dir_old;
            let mut n = if points > 1 {
                normals.get(i).copied().unwrap_or(normals[0])
            } else {
                normals[0]
            };
            if normals.len() == 1 {
                n = normals[0];
                let side = if dot(n, old) < 0.0 { 0 } else { 1 };
                if !state.changed {
                    state.side = side;
                } else if state.side < side {
                    vecmax = true;
                    state.side = side;
                } else if state.side > side {
                    change = false;
                }
            }
            if change {
                let v = cross(normal, n);
                let sens = if dot(v, old) < 0.0 { -1.0 } else { 1.0 };
                let v = normalize(v);
                let v = [sens * v[0], sens * v[1], sens * v[2]];
                if !state.changed || vecmax {
                    *dir = v;
                    state.changed = true;
                } else {
                    *dir = add(*dir, v);
                }
            }
        }
    }
    *dir = normalize(*dir);
}

/// `fonno7`: the cell size at a node along its direction.
fn node_size(g: &Geometry, node: NodeId, dir: [f64; 3]) -> f64 {
    let mesh = g.mesh;
    let p = mesh.coord(node);
    let cos70 = 70.0_f64.to_radians().cos();
    let mut hmax = f64::EPSILON;
    for &c in g.cells(node) {
        let cell = mesh.cell(c);
        for e in edges(cell.ty) {
            let (n1, n2) = (cell.nodes[e[0]], cell.nodes[e[1]]);
            let other = if n1 == node {
                n2
            } else if n2 == node {
                n1
            } else {
                continue;
            };
            let v = sub(mesh.coord(other), p);
            let pr = dot(v, dir);
            let nv = dot(v, v).sqrt();
            if nv == 0.0 || (pr / nv).abs() < cos70 {
                continue;
            }
            if pr.abs() >= hmax {
                hmax = pr.abs();
            }
        }
    }
    hmax
}

/// The nodes of some cells, in increasing order (`gmgnre`).
fn lip_nodes(mesh: &Mesh, cells: &[CellId]) -> Vec<NodeId> {
    let mut v: Vec<NodeId> = cells
        .iter()
        .flat_map(|&c| mesh.cell(c).nodes.iter().copied())
        .collect();
    v.sort();
    v.dedup();
    v
}

/// `fonnof` on one lip: the lip nodes in the plane through the front node
/// `x0` of normal `tangent` (within `prec`), on the side of the nearest
/// one, ordered along the line from the front node (`oreino`).
fn normal_line(
    mesh: &Mesh,
    lip: &[NodeId],
    node: NodeId,
    tangent: [f64; 3],
    prec: f64,
) -> Vec<NodeId> {
    let x0 = mesh.coord(node);
    let inplane: Vec<NodeId> = lip
        .iter()
        .copied()
        .filter(|&n| dot(sub(mesh.coord(n), x0), tangent).abs() <= prec)
        .collect();
    if inplane.len() <= 2 {
        return Vec::new();
    }
    let mut dmin = 100.0;
    let mut nearest = None;
    for &n in &inplane {
        if n == node {
            continue;
        }
        let d = dot(sub(mesh.coord(n), x0), sub(mesh.coord(n), x0)).sqrt();
        if d < dmin {
            dmin = d;
            nearest = Some(n);
        }
    }
    let Some(nearest) = nearest else {
        return Vec::new();
    };
    let vt = sub(mesh.coord(nearest), x0);
    let mut list = vec![node];
    let mut dmax = 0.0;
    let mut far = node;
    for &n in &inplane {
        if n == node {
            continue;
        }
        let v = sub(mesh.coord(n), x0);
        if dot(v, vt) >= 0.0 {
            list.push(n);
            let d = dot(v, v).sqrt();
            if d > dmax {
                dmax = d;
                far = n;
            }
        }
    }
    // oreino: sorted by the abscissa along the line to the farthest node.
    let ab = sub(mesh.coord(far), x0);
    let ab2 = dot(ab, ab);
    if ab2 > 0.0 {
        let mut keyed: Vec<(f64, NodeId)> = list
            .iter()
            .map(|&n| (dot(sub(mesh.coord(n), x0), ab) / ab2, n))
            .collect();
        keyed.sort_by(|x, y| x.0.total_cmp(&y.0));
        list = keyed.into_iter().map(|(_, n)| n).collect();
    }
    list.truncate(20);
    list
}

/// Builds the front (see the module's documentation).
pub fn define_front(input: &FrontInput) -> Result<Front3d, String> {
    let mesh = input.mesh;
    let g = Geometry::new(mesh);
    let (nodes, quadratic) = order_front(input)?;
    let nn = nodes.len();
    // fonnor2: a segment spans `step` nodes (its middle node between on a
    // quadratic front); the cells around it share `nbmax` nodes with a
    // face neighbour.
    let (step, nbmax) = if quadratic { (2, 6) } else { (1, 3) };
    let nseg = (nn - 1) / step;
    let mut normal = vec![[0.0; 3]; nn];
    let mut dir = vec![[0.0; 3]; nn];
    let mut sens = 1.0;
    for iseg in 0..nseg {
        let (ia, ib) = (step * iseg, step * (iseg + 1));
        let (a, b) = (nodes[ia], nodes[ib]);
        let (lips, cells) = lip_faces(&g, a, b, nbmax)?;
        let (d1, n1) = face_basis(mesh, &lips[0], a, b);
        let (d2, n2) = face_basis(mesh, &lips[1], a, b);
        // fonno6, SYME='NON': the two lips' directions agree within 5°.
        let alpha = dot(d1, d2).clamp(-1.0, 1.0).acos().to_degrees();
        if alpha.abs() > 5.0 {
            return Err(format!(
                "the lips' directions at the front segment {}–{} differ by {alpha:.1}° (code_aster's RUPTURE0_34: at most 5°)",
                g.name(a),
                g.name(b)
            ));
        }
        let vd = normalize(add(d1, d2));
        let sn = add(n1, n2);
        let nn_ = dot(sn, sn).sqrt();
        let mut vn = [sens * sn[0] / nn_, sens * sn[1] / nn_, sens * sn[2] / nn_];
        if iseg == 0 && !input.lip_sup.is_empty() {
            let v = upper_side(input, cells, nodes[0]);
            if dot(vn, v) < 0.0 {
                sens = -1.0;
                vn = [-vn[0], -vn[1], -vn[2]];
            }
        }
        normal[ia] = normalize(add(normal[ia], vn));
        dir[ia] = normalize(add(dir[ia], vd));
        normal[ib] = normalize(add(normal[ib], vn));
        dir[ib] = normalize(add(dir[ib], vd));
        if quadratic {
            // The middle node takes the segment's basis.
            normal[ia + 1] = vn;
            dir[ia + 1] = vd;
        }
    }
    // fonext, called on the first and the last segment (for a front of one
    // segment, code_aster's call turns the first node's direction with the
    // free faces around the last one: reproduced).
    if nseg == 1 {
        let (n0, mut d0) = (normal[0], dir[0]);
        turn_end(&g, nodes[nn - 1], nodes[0], n0, &mut d0);
        dir[0] = d0;
    } else {
        let (n0, mut d0) = (normal[0], dir[0]);
        turn_end(&g, nodes[0], nodes[step], n0, &mut d0);
        dir[0] = d0;
        let (nl, mut dl) = (normal[nn - 1], dir[nn - 1]);
        turn_end(&g, nodes[nn - 1], nodes[nn - 1 - step], nl, &mut dl);
        dir[nn - 1] = dl;
    }
    // fonno7 at the segments' ends; a middle node's size is the mean of
    // its two ends' (fonnor2).
    let mut size = vec![0.0; nn];
    for i in (0..nn).step_by(step) {
        size[i] = node_size(&g, nodes[i], dir[i]);
    }
    if quadratic {
        for i in (1..nn).step_by(2) {
            size[i] = (size[i + 1] + size[i - 1]) / 2.0;
        }
    }
    // fonnof
    let sup = lip_nodes(mesh, input.lip_sup);
    let inf = lip_nodes(mesh, input.lip_inf);
    let mut sup_normal = vec![Vec::new(); nn];
    let mut inf_normal = vec![Vec::new(); nn];
    for i in 0..nn {
        let tangent = cross(normal[i], dir[i]);
        let dist = |j: usize| {
            let v = sub(mesh.coord(nodes[i]), mesh.coord(nodes[j]));
            dot(v, v).sqrt()
        };
        let d = if i == 0 {
            dist(1)
        } else if i == nn - 1 {
            dist(nn - 2)
        } else {
            dist(i - 1).min(dist(i + 1))
        };
        let prec = d * input.prec_norm;
        if !input.lip_inf.is_empty() {
            let l = normal_line(mesh, &inf, nodes[i], tangent, prec);
            if l.is_empty() {
                continue;
            }
            inf_normal[i] = l;
        }
        sup_normal[i] = normal_line(mesh, &sup, nodes[i], tangent, prec);
    }
    let quadratic_lips = input.lip_sup.first().is_some_and(|&c| {
        let cell = mesh.cell(c);
        cell.nodes.len() != crate::shape::corner_count(cell.ty)
    });
    Ok(Front3d {
        nodes,
        normal,
        dir,
        size,
        sup_normal,
        inf_normal,
        quadratic,
        quadratic_lips,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_mesh::Cell;

    /// A line of 7 nodes along x (node k at x = k) and the given segments.
    fn line(cells: &[(CellType, &[u32])]) -> Mesh {
        Mesh {
            dim: 3,
            coords: (0..7).map(|k| [k as f64, 0.0, 0.0]).collect(),
            node_names: (1..=7).map(|k| format!("N{k}")).collect(),
            cells: cells
                .iter()
                .map(|(ty, n)| Cell {
                    ty: *ty,
                    nodes: n.iter().map(|&i| NodeId(i)).collect(),
                })
                .collect(),
            cell_names: (1..=cells.len()).map(|k| format!("M{k}")).collect(),
            ..Mesh::default()
        }
    }

    fn order(mesh: &Mesh, origin: u32, end: Option<u32>) -> Result<(Vec<u32>, bool), String> {
        let segments: Vec<CellId> = (0..mesh.cells.len() as u32).map(CellId).collect();
        let input = FrontInput {
            mesh,
            segments: &segments,
            origin: NodeId(origin),
            end: end.map(NodeId),
            lip_sup: &[],
            lip_inf: &[],
            prec_norm: 0.1,
        };
        order_front(&input).map(|(n, q)| (n.iter().map(|x| x.0).collect(), q))
    }

    /// ornofd on SEG3 cells: the ends walked from the origin whatever the
    /// cells' order and orientation, each cell's middle node (its third)
    /// between them.
    #[test]
    fn a_quadratic_front_is_ordered_with_its_middle_nodes() {
        use CellType::SEG3;
        let mesh = line(&[(SEG3, &[4, 6, 5]), (SEG3, &[0, 2, 1]), (SEG3, &[4, 2, 3])]);
        assert_eq!(
            order(&mesh, 0, Some(6)),
            Ok((vec![0, 1, 2, 3, 4, 5, 6], true))
        );
        assert_eq!(order(&mesh, 6, None), Ok((vec![6, 5, 4, 3, 2, 1, 0], true)));
        assert!(order(&mesh, 0, Some(4)).is_err());
    }

    /// code_aster reads the first cell's type for the whole front: SEG2
    /// and SEG3 cells together are refused.
    #[test]
    fn a_front_of_two_cell_types_is_refused() {
        use CellType::{SEG2, SEG3};
        let mesh = line(&[(SEG3, &[0, 2, 1]), (SEG2, &[2, 3])]);
        let e = order(&mesh, 0, None).unwrap_err();
        assert!(e.contains("M2") && e.contains("SEG2"), "{e}");
        let mesh = line(&[(SEG2, &[0, 1]), (SEG2, &[2, 1])]);
        assert_eq!(order(&mesh, 0, None), Ok((vec![0, 1, 2], false)));
    }

    fn front_of(mesh: &Mesh) -> Front3d {
        let cells = |g: &str| {
            mesh.group_ma(g)
                .map(|g| g.members.clone())
                .unwrap_or_default()
        };
        let node = |g: &str| mesh.group_no(g).map(|g| g.members[0]).unwrap();
        let (front, sup, inf) = (cells("FRONT"), cells("LIP_SUP"), cells("LIP_INF"));
        define_front(&FrontInput {
            mesh,
            segments: &front,
            origin: node("ORIG"),
            end: Some(node("EXTR")),
            lip_sup: &sup,
            lip_inf: &inf,
            prec_norm: 0.1,
        })
        .unwrap()
    }

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
    }

    /// comm/crack_front_3d.mail (a straight front of 2 SEG2 along z in the
    /// crack plane y = 0, propagating along x) and the same made quadratic
    /// (LINE_QUAD): the quadratic front interleaves the middle nodes, its
    /// ends have the linear front's bases and sizes, a middle node the
    /// segment's basis and the mean of its ends' sizes; every node has its
    /// normal lip lines, the ends' holding the linear ones' nodes in order
    /// with the middle nodes between.
    #[test]
    fn a_quadratic_front_keeps_the_linear_ones_bases_and_sizes() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../comm/crack_front_3d.mail"
        );
        let lin = aster_mesh::read_mesh(std::path::Path::new(path)).unwrap();
        let mut quad = lin.clone();
        let all: Vec<CellId> = (0..quad.cells.len() as u32).map(CellId).collect();
        quad.line_to_quad(&all);
        let (fl, fq) = (front_of(&lin), front_of(&quad));
        assert_eq!(fl.nodes.len(), 3);
        assert_eq!(fq.nodes.len(), 5);
        for i in 0..3 {
            assert_eq!(fq.nodes[2 * i], fl.nodes[i]);
            assert!(close(fq.normal[2 * i], fl.normal[i]), "{i}");
            assert!(close(fq.dir[2 * i], fl.dir[i]), "{i}");
            assert_eq!(fq.size[2 * i], fl.size[i]);
            for l in [&fl.sup_normal[i], &fl.inf_normal[i]] {
                assert!(l.len() >= 3);
            }
            for (ll, lq) in [
                (&fl.sup_normal[i], &fq.sup_normal[2 * i]),
                (&fl.inf_normal[i], &fq.inf_normal[2 * i]),
            ] {
                // The linear mesh's nodes of the quadratic line (20 nodes
                // at most) are the linear line's first ones, in order.
                let corner: Vec<NodeId> = lq
                    .iter()
                    .copied()
                    .filter(|n| (n.0 as usize) < lin.node_count())
                    .collect();
                assert_eq!(lq.len(), 20, "{i}");
                assert!(corner.len() >= 10 && ll.starts_with(&corner), "{i}");
            }
        }
        for m in [1, 3] {
            let p = quad.coord(fq.nodes[m]);
            let mid =
                |k: usize| (quad.coord(fq.nodes[m - 1])[k] + quad.coord(fq.nodes[m + 1])[k]) / 2.0;
            assert!((0..3).all(|k| (p[k] - mid(k)).abs() < 1e-12));
            assert!(close(fq.normal[m], [0.0, 1.0, 0.0]), "{:?}", fq.normal[m]);
            assert!(close(fq.dir[m], [1.0, 0.0, 0.0]), "{:?}", fq.dir[m]);
            assert_eq!(fq.size[m], (fq.size[m - 1] + fq.size[m + 1]) / 2.0);
            assert!(fq.sup_normal[m].len() >= 3 && fq.inf_normal[m].len() >= 3);
        }
    }
}
