//! code_aster 17's pairing of 3D contact faces for `DEFI_CONT`'s mortar
//! contact (`bibfor/mesh/mesh_pairing_module.F90`, `mesh_cell_module.F90`,
//! 2025 sources) and the quadrature on the intersection polygon
//! (`getQuadCont`, `latrco`, `lcptga`).
//!
//! For a slave face and a master face, both linearised on their corners
//! (TRIA3, QUAD4), as `cellInteProj` does it:
//!
//! - the normals at the linearised cells' barycentres; pairs of orthogonal
//!   faces (|n_s·n_m| ≤ 1e-8) are dropped, and with `COEF_MULT_APPA` faces
//!   whose barycentres are farther than 2 × ratio × the larger diameter
//!   (`cellProjOnCell`);
//! - each slave corner is cast along the full slave face's outward normal
//!   there onto the master's linearised face (`nodeProjOnCell`,
//!   `poinProjByVect`: Newton on (ξ, η, β) from ξ = 0, β = 1, tolerance
//!   1e-8, at most 75 iterations);
//! - `inteCellChck`: the projection is empty when a projected edge is
//!   reversed, or when the master lies behind the slave (or in front of
//!   the master) at a corner;
//! - the polygon, in the master's parametric space (`addPoinInte3D`,
//!   `addPoinOnEdge`, `inteCellSegm`): the projected slave corners inside
//!   the master, the master corners inside the projected slave (tested on
//!   its triangles (1, 2, 3) then (1, 3, 4), which also give their slave
//!   coordinates), and the crossings of the projected slave edges with the
//!   master edges (mapped back along the slave edge by code_aster's
//!   formula);
//! - `intePoinSort`: the points sorted by the angle `atan2(ξ − ξ̄, η − η̄)`
//!   around their mean (code_aster's selection sort `ordr8`), a point
//!   dropped when its angle is within 1e-7 of the next one's; more than 8
//!   points: no pair;
//! - `intePoinInCell`: the slave coordinates brought back onto the slave
//!   cell (`cellPoinAdjust`), and the pair kept when the polygon's area in
//!   the slave's parametric space exceeds 1e-8 (`inteCellArea`).
//!
//! Quadrature (`getQuadCont`): a triangle is itself, a polygon of n > 3
//! points is cut into the n triangles (pᵢ, pᵢ₊₁, centre) (`latrco`), and each
//! triangle carries FPG4 (both faces linear, order 3) or FPG7 (order 5)
//! mapped into the slave's parametric space with weights 2 × area × w
//! (`lcptga`).

use crate::lac_mortar::{linear_kind, piece_points, Family};
use crate::shape::{cross, dot, interpolate, norm, scale, sub, SurfaceKind};

/// code_aster's pairing tolerance (`ContactPairing::compute`).
pub const PAIR_TOLE: f64 = 1e-8;

/// `MAX_NB_INTE`: the most intersection points a pair may have.
const MAX_NB_INTE: usize = 8;

/// A face as the pairing reads it: its kind, its nodes' positions (code_aster
/// order) and the sign making t₁ × t₂ point out of its body.
#[derive(Clone, Copy, Debug)]
pub struct Face<'a> {
    pub kind: SurfaceKind,
    pub x: &'a [[f64; 3]],
    pub sign: f64,
}

impl Face<'_> {
    fn line_kind(&self) -> SurfaceKind {
        linear_kind(self.kind)
    }

    fn corners(&self) -> &[[f64; 3]] {
        &self.x[..self.line_kind().node_count()]
    }

    /// Outward unit normal of the face itself at `xi` (`cellCompBaseAtPoint`).
    pub fn normal(&self, xi: [f64; 2]) -> Option<[f64; 3]> {
        face_normal(self.kind, self.x, xi, self.sign)
    }

    fn line_normal_at_bary(&self) -> Option<[f64; 3]> {
        let k = self.line_kind();
        face_normal(k, self.corners(), bary_para(k), self.sign)
    }
}

/// Outward unit normal sign × t₁ × t₂ / |t₁ × t₂| of a face at `xi`.
pub fn face_normal(kind: SurfaceKind, x: &[[f64; 3]], xi: [f64; 2], sign: f64) -> Option<[f64; 3]> {
    let t = interpolate(kind, x, xi).tangents;
    let raw = cross(t[0], t[1]);
    let l = norm(raw);
    (l > 0.0 && l.is_finite()).then(|| scale(raw, sign / l))
}

/// The mean of the reference nodes (`cellCompCenterPara`).
fn bary_para(kind: SurfaceKind) -> [f64; 2] {
    let p = kind.node_coords();
    let n = p.len() as f64;
    let s = p.iter().fold([0.0, 0.0], |a, q| [a[0] + q[0], a[1] + q[1]]);
    [s[0] / n, s[1] / n]
}

fn bary(x: &[[f64; 3]]) -> [f64; 3] {
    let n = x.len() as f64;
    let s = x
        .iter()
        .fold([0.0; 3], |a, q| [a[0] + q[0], a[1] + q[1], a[2] + q[2]]);
    [s[0] / n, s[1] / n, s[2] / n]
}

fn diameter(x: &[[f64; 3]]) -> f64 {
    let mut d = 0.0f64;
    for i in 0..x.len() {
        for j in i + 1..x.len() {
            d = d.max(norm(sub(x[i], x[j])));
        }
    }
    d
}

/// `poinProjByVect` on a linear face (TRIA3, QUAD4): the parametric point
/// x(ξ) with p = x(ξ) + β v, by code_aster's Newton iterations. `None`
/// when the system is singular or Newton does not converge.
pub fn proj_by_vect(
    kind: SurfaceKind,
    x: &[[f64; 3]],
    p: [f64; 3],
    v: [f64; 3],
    tole: f64,
) -> Option<[f64; 2]> {
    let mut xi = [0.0, 0.0];
    let mut beta = 1.0;
    let (tole_abso, tole_rela) = (tole / 100.0, tole);
    let mut dist_mini = f64::MAX;
    let mut iter = 0;
    loop {
        let cp = interpolate(kind, x, xi);
        let r0 = sub(p, cp.x);
        let dist = norm(r0);
        let r = sub(r0, scale(v, beta));
        let [t1, t2] = cp.tangents;
        let det = dot(t1, cross(t2, v));
        if det.abs() <= f64::EPSILON {
            return None;
        }
        let d1 = dot(r, cross(t2, v)) / det;
        let d2 = dot(t1, cross(r, v)) / det;
        let db = dot(t1, cross(t2, r)) / det;
        xi = [xi[0] + d1, xi[1] + d2];
        beta += db;
        if dist <= dist_mini {
            dist_mini = dist;
        }
        let refe = xi[0] * xi[0] + xi[1] * xi[1] + beta * beta;
        let step = (d1 * d1 + d2 * d2 + db * db).sqrt();
        let (test, tole_newt) = if refe <= tole_rela {
            (step, tole_abso)
        } else {
            (step / refe.sqrt(), tole_rela)
        };
        if test > tole_newt && iter < 75 {
            iter += 1;
            continue;
        }
        if test > tole_newt {
            return None;
        }
        return Some(xi);
    }
}

/// `cellPoinInside` for a linear face.
fn poin_inside(kind: SurfaceKind, tole: f64, p: [f64; 2]) -> bool {
    if kind.is_triangle() {
        p[0] >= -tole && p[1] >= -tole && p[1] + p[0] <= 1.0 + tole
    } else {
        p[0] >= -1.0 - tole && p[0] <= 1.0 + tole && p[1] >= -1.0 - tole && p[1] <= 1.0 + tole
    }
}

/// `cellPoinAdjustTria` / `cellPoinAdjustQuad`: a point outside the cell
/// brought onto its boundary (the distance test of code_aster only sets a
/// return code the pairing does not read).
fn poin_adjust(kind: SurfaceKind, p: &mut [f64; 2]) {
    const ATOL: f64 = 1e-12;
    if kind.is_triangle() {
        let mut k1pk2 = p[0] + p[1];
        let mut k2mk1 = p[1] - p[0];
        if p[0].abs() <= ATOL {
            p[0] = 0.0;
        }
        if p[1].abs() <= ATOL {
            p[1] = 0.0;
        }
        if (k1pk2 - 1.0).abs() <= ATOL {
            k1pk2 = 1.0;
        }
        if (k2mk1 + 1.0).abs() <= ATOL {
            k2mk1 = -1.0;
        }
        if (k2mk1 - 1.0).abs() <= ATOL {
            k2mk1 = 1.0;
        }
        if p[0] >= 0.0 && p[1] >= 0.0 && k1pk2 <= 1.0 {
            return;
        }
        let mut zone = 0;
        if p[0] < 0.0 {
            zone = if p[1] < 0.0 {
                1
            } else if p[1] <= 1.0 {
                2
            } else {
                3
            };
        }
        if p[1] < 0.0 {
            zone = if p[0] < 0.0 {
                1
            } else if p[0] <= 1.0 {
                8
            } else {
                7
            };
        }
        let (mut e1, mut e2) = (0.0, 0.0);
        if p[0] >= 0.0 {
            if k2mk1 > 1.0 {
                zone = 4;
            } else if k1pk2 > 1.0 && (-1.0..=1.0).contains(&k2mk1) {
                zone = 5;
                e1 = 0.5 * (1.0 + p[0] - p[1]);
                e2 = 0.5 * (1.0 - p[0] + p[1]);
            } else if p[1] >= 0.0 && k2mk1 < -1.0 {
                zone = 6;
            }
        }
        match zone {
            1 => *p = [0.0, 0.0],
            2 => p[0] = 0.0,
            3 | 4 => *p = [0.0, 1.0],
            5 => *p = [e1, e2],
            6 | 7 => *p = [1.0, 0.0],
            8 => p[1] = 0.0,
            _ => {}
        }
    } else {
        for c in p.iter_mut() {
            if (*c + 1.0).abs() <= ATOL {
                *c = -1.0;
            }
            if (*c - 1.0).abs() <= ATOL {
                *c = 1.0;
            }
        }
        p[0] = p[0].clamp(-1.0, 1.0);
        p[1] = p[1].clamp(-1.0, 1.0);
    }
}

/// The result of `poinIsInsideOtherCell`.
enum Inside {
    Yes([f64; 2]),
    No,
    Degenerate,
}

/// `poinIsInsideOtherCell`: whether the master point `p` (master
/// parametric) lies in the projected slave cell whose corners are `proj`
/// (master parametric), with its slave parametric coordinates.
fn inside_other(tole: f64, p: [f64; 2], kind: SurfaceKind, proj: &[[f64; 2]]) -> Inside {
    let tri = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| -> Option<Option<(f64, f64, bool)>> {
        let v0 = [b[0] - a[0], b[1] - a[1]];
        let v1 = [c[0] - a[0], c[1] - a[1]];
        let d00 = v0[0] * v0[0] + v0[1] * v0[1];
        let d10 = v0[0] * v1[0] + v0[1] * v1[1];
        let d11 = v1[0] * v1[0] + v1[1] * v1[1];
        let m = d00 * d11 - d10 * d10;
        if m.abs() <= tole {
            return None;
        }
        let v2 = [p[0] - a[0], p[1] - a[1]];
        let d02 = v0[0] * v2[0] + v0[1] * v2[1];
        let d12 = v1[0] * v2[0] + v1[1] * v2[1];
        if (v2[0] * v2[0] + v2[1] * v2[1]).sqrt() <= tole {
            return Some(Some((0.0, 0.0, true)));
        }
        let u = 1.0 / m * (d11 * d02 - d10 * d12);
        let v = 1.0 / m * (d00 * d12 - d10 * d02);
        Some((u >= -tole && v >= -tole && u + v <= 1.0 + tole).then_some((u, v, false)))
    };
    let triangle = kind.is_triangle();
    match tri(proj[0], proj[1], proj[2]) {
        None => return Inside::Degenerate,
        Some(Some((_, _, true))) => {
            return Inside::Yes(if triangle { [0.0, 0.0] } else { [-1.0, -1.0] })
        }
        Some(Some((u, v, false))) => {
            return Inside::Yes(if triangle {
                [u, v]
            } else {
                [-1.0 + u * 2.0 + v * 2.0, -1.0 + v * 2.0]
            })
        }
        Some(None) => {}
    }
    if triangle {
        return Inside::No;
    }
    match tri(proj[0], proj[2], proj[3]) {
        None => Inside::Degenerate,
        Some(Some((_, _, true))) => Inside::Yes([-1.0, -1.0]),
        Some(Some((u, v, false))) => Inside::Yes([-1.0 + u * 2.0, -1.0 + v * 2.0 + u * 2.0]),
        Some(None) => Inside::No,
    }
}

/// `inteCellSegm`: the crossings of segment `seg` with the edges of the
/// cell whose corners are `cell` (same parametric space).
fn segm_cell(tole: f64, seg: [[f64; 2]; 2], cell: &[[f64; 2]], out: &mut Vec<[f64; 2]>) {
    let (x1, y1) = (seg[0][0], seg[0][1]);
    let a = seg[1][0] - x1;
    let b = seg[1][1] - y1;
    let n = cell.len();
    for i in 0..n {
        let (x2, y2) = (cell[i][0], cell[i][1]);
        let c = cell[(i + 1) % n][0] - x2;
        let d = cell[(i + 1) % n][1] - y2;
        let det = b * c - a * d;
        let (t1, t2) = if (det * det).sqrt() > tole {
            (
                1.0 / det * (d * (x1 - x2) - c * (y1 - y2)),
                1.0 / det * (b * (x1 - x2) - a * (y1 - y2)),
            )
        } else {
            (-1.0, -1.0)
        };
        if t1 < 1.0 + tole && t1 > -tole && t2 < 1.0 + tole && t2 > -tole {
            out.push([
                (t2 * c + x2 + t1 * a + x1) / 2.0,
                (t2 * d + y2 + t1 * b + y1) / 2.0,
            ]);
        }
    }
}

/// `ordr8`: code_aster's selection sort (indices by ascending value).
fn ordr8(v: &[f64]) -> Vec<usize> {
    let mut ord: Vec<usize> = (0..v.len()).collect();
    for i in 0..v.len().saturating_sub(1) {
        let mut vmin = v[ord[i]];
        let mut imin = i;
        for j in i + 1..v.len() {
            if v[ord[j]] < vmin {
                vmin = v[ord[j]];
                imin = j;
            }
        }
        ord.swap(i, imin);
    }
    ord
}

/// `intePoinSort` (3D): the points sorted by angle around their mean in
/// the master's space, near-equal angles merged.
fn sort_points(tole: f64, targ: &[[f64; 2]], orig: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let n = targ.len();
    let mut b = [0.0, 0.0];
    for t in targ {
        b[0] += t[0] / n as f64;
        b[1] += t[1] / n as f64;
    }
    let angle: Vec<f64> = targ
        .iter()
        .map(|t| (t[0] - b[0]).atan2(t[1] - b[1]))
        .collect();
    let sorted = ordr8(&angle);
    let mut out = Vec::new();
    for i in 0..n {
        let next = if i + 1 == n { 0 } else { i + 1 };
        let d = ((angle[sorted[i]] - angle[sorted[next]]).powi(2)).sqrt();
        if d > 10.0 * tole {
            out.push(orig[sorted[i]]);
        }
    }
    out
}

/// `inteCellArea` (3D): the polygon's area (shoelace).
pub fn polygon_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    if n <= 2 {
        return 0.0;
    }
    let mut a = 0.0;
    for i in 0..n {
        let j = if i + 1 == n { 0 } else { i + 1 };
        a += p[i][0] * p[j][1] - p[j][0] * p[i][1];
    }
    (0.5 * a).abs()
}

/// `cellInteProj` of a slave face onto a master face (3D) followed by
/// `fastPair`'s test: the intersection polygon in the slave's parametric
/// space when the pair is kept (area > `tole`), else `None`.
pub fn intersect(
    slave: Face,
    master: Face,
    tole: f64,
    dist_ratio: Option<f64>,
) -> Option<Vec<[f64; 2]>> {
    let (sk, mk) = (slave.line_kind(), master.line_kind());
    let (sc, mc) = (slave.corners(), master.corners());
    let (s_para, m_para) = (sk.node_coords(), mk.node_coords());
    // cellProjOnCell: normals at the barycentres of the linearised cells.
    let n_targ = master.line_normal_at_bary()?;
    let n_orig = slave.line_normal_at_bary()?;
    if dot(n_targ, n_orig).abs() <= tole {
        return None;
    }
    if let Some(r) = dist_ratio {
        let d = norm(sub(bary(mc), bary(slave.x)));
        if d >= 2.0 * r * diameter(mc).max(diameter(slave.x)) {
            return None;
        }
    }
    // nodeProjOnCell: slave corners along the full face's normal there.
    let mut proj_para = Vec::with_capacity(sc.len());
    let mut proj_glob = Vec::with_capacity(sc.len());
    for (i, &p) in sc.iter().enumerate() {
        let n = slave.normal(s_para[i])?;
        let xi = proj_by_vect(mk, mc, p, n, tole)?;
        proj_glob.push(interpolate(mk, mc, xi).x);
        proj_para.push(xi);
    }
    // inteCellChck
    let nn = sc.len();
    for i in 0..nn {
        let j = (i + 1) % nn;
        let edge_orig = sub(sc[j], sc[i]);
        let edge_proj = sub(proj_glob[j], proj_glob[i]);
        let v = sub(proj_glob[i], sc[i]);
        let sig = dot(edge_proj, edge_orig);
        let a = dot(n_orig, v);
        let b = dot(n_targ, v);
        if sig < -tole || (a < -tole && b < -tole) || (a > tole && b > tole) {
            return None;
        }
    }
    // addPoinInte3D
    let mut targ: Vec<[f64; 2]> = Vec::new();
    let mut orig: Vec<[f64; 2]> = Vec::new();
    for i in 0..nn {
        if poin_inside(mk, tole, proj_para[i]) {
            targ.push(proj_para[i]);
            orig.push(s_para[i]);
        }
    }
    let mut degenerate = false;
    for &m in &m_para {
        match inside_other(tole, m, sk, &proj_para) {
            Inside::Yes(o) => {
                targ.push(m);
                orig.push(o);
            }
            Inside::No => {}
            Inside::Degenerate => degenerate = true,
        }
    }
    // addPoinOnEdge
    for i in 0..nn {
        let j = (i + 1) % nn;
        let sp = [proj_para[i], proj_para[j]];
        let so = [s_para[i], s_para[j]];
        let before = targ.len();
        segm_cell(tole, sp, &m_para, &mut targ);
        for k in before..targ.len() {
            let q = targ[k];
            let mut o = [0.0, 0.0];
            let mut t1 = 0.0;
            if (q[0] - sp[0][0]).abs() > tole {
                t1 = (sp[1][0] - sp[0][0]) / (q[0] - sp[0][0]);
                o[0] = (1.0 / t1) * (so[1][0] - so[0][0]) + so[0][0];
            } else {
                o[0] = so[0][0];
            }
            if (q[1] - sp[0][1]).abs() > tole {
                let t2 = (sp[1][1] - sp[0][1]) / (q[1] - sp[0][1]);
                o[1] = (1.0 / t2) * (so[1][1] - so[0][1]) + so[0][1];
                o[0] = (1.0 / t2) * (so[1][0] - so[0][0]) + so[0][0];
            } else if t1 < tole {
                o[1] = so[0][1];
            } else {
                o[1] = (1.0 / t1) * (so[1][1] - so[0][1]) + so[0][1];
            }
            orig.push(o);
        }
    }
    if targ.is_empty() || degenerate {
        return None;
    }
    let sorted = if targ.len() > 2 {
        sort_points(tole, &targ, &orig)
    } else {
        orig
    };
    if sorted.len() > MAX_NB_INTE {
        return None;
    }
    // intePoinInCell
    let poly: Vec<[f64; 2]> = sorted
        .into_iter()
        .map(|mut p| {
            poin_adjust(sk, &mut p);
            p
        })
        .collect();
    (polygon_area(&poly) > tole).then_some(poly)
}

/// `getQuadCont` (3D): the integration points of an intersection polygon
/// (slave parametric space) with their reference weights (to be multiplied
/// by the slave Jacobian); FPG4 per triangle when both faces are linear,
/// FPG7 otherwise.
pub fn quadrature(poly: &[[f64; 2]], both_linear: bool) -> Vec<([f64; 2], f64)> {
    let family = if both_linear {
        Family::Fpg4
    } else {
        Family::Fpg7
    };
    let n = poly.len();
    if n < 3 {
        return Vec::new();
    }
    if n == 3 {
        return piece_points(3, poly, family);
    }
    let mut c = [0.0, 0.0];
    for p in poly {
        c[0] += p[0];
        c[1] += p[1];
    }
    let c = [c[0] / n as f64, c[1] / n as f64];
    (0..n)
        .flat_map(|i| {
            let j = if i + 1 == n { 0 } else { i + 1 };
            piece_points(3, &[poly[i], poly[j], c], family)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(z: f64, x0: f64, x1: f64, y0: f64, y1: f64) -> Vec<[f64; 3]> {
        vec![[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]
    }

    #[test]
    fn overlapping_squares_give_their_common_rectangle() {
        // Slave: the top of a lower block (normal +z); master: the bottom of
        // an upper block (normal −z, hence sign −1 on counter-clockwise nodes).
        let s = quad(0.0, 0.0, 1.0, 0.0, 1.0);
        let m = quad(0.0, 0.5, 1.5, 0.25, 1.25);
        let poly = intersect(
            Face {
                kind: SurfaceKind::Quad4,
                x: &s,
                sign: 1.0,
            },
            Face {
                kind: SurfaceKind::Quad4,
                x: &m,
                sign: -1.0,
            },
            PAIR_TOLE,
            None,
        )
        .unwrap();
        // [0.5, 1] × [0.25, 1] in the slave's [-1, 1]² space: area 0.5·0.75·4.
        assert!((polygon_area(&poly) - 1.5).abs() < 1e-12, "{poly:?}");
        let w: f64 = quadrature(&poly, true).iter().map(|(_, w)| w).sum();
        assert!((w - 1.5).abs() < 1e-12);
    }

    #[test]
    fn back_facing_faces_are_not_paired() {
        let s = quad(0.0, 0.0, 1.0, 0.0, 1.0);
        let m = quad(0.0, 0.5, 1.5, 0.25, 1.25);
        let r = intersect(
            Face {
                kind: SurfaceKind::Quad4,
                x: &s,
                sign: 1.0,
            },
            Face {
                kind: SurfaceKind::Quad4,
                x: &m,
                sign: 1.0,
            },
            PAIR_TOLE,
            None,
        );
        // Same orientation: the projected corners lie on both sides' planes
        // (gap 0), so the check passes; but a master above with the same
        // normal as the slave is behind it.
        let m2 = quad(1.0, 0.5, 1.5, 0.25, 1.25);
        let r2 = intersect(
            Face {
                kind: SurfaceKind::Quad4,
                x: &s,
                sign: 1.0,
            },
            Face {
                kind: SurfaceKind::Quad4,
                x: &m2,
                sign: 1.0,
            },
            PAIR_TOLE,
            None,
        );
        assert!(r.is_some());
        assert!(r2.is_none());
    }

    #[test]
    fn triangle_in_square_is_whole() {
        let s = quad(0.0, 0.0, 1.0, 0.0, 1.0);
        let t = vec![[0.2, 0.2, 0.1], [0.2, 0.6, 0.1], [0.6, 0.2, 0.1]];
        // Master triangle above, facing down: t1 × t2 = (0,0.4,0)×(0.4,0,0) = −z.
        let poly = intersect(
            Face {
                kind: SurfaceKind::Quad4,
                x: &s,
                sign: 1.0,
            },
            Face {
                kind: SurfaceKind::Tria3,
                x: &t,
                sign: 1.0,
            },
            PAIR_TOLE,
            None,
        )
        .unwrap();
        assert_eq!(poly.len(), 3);
        // 0.08 in global units is 0.08 × 4 in the slave's parametric space.
        assert!((polygon_area(&poly) - 0.32).abs() < 1e-12);
    }

    #[test]
    fn fpg4_and_fpg7_integrate_their_orders() {
        let tri = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        for (fam, order) in [(Family::Fpg4, 3), (Family::Fpg7, 5)] {
            let pts = piece_points(3, &tri, fam);
            for a in 0..=order {
                for b in 0..=(order - a) {
                    let num: f64 = pts
                        .iter()
                        .map(|(p, w)| w * p[0].powi(a) * p[1].powi(b))
                        .sum();
                    // ∫ x^a y^b over the unit triangle = a! b! / (a + b + 2)!
                    let f = |n: i32| (1..=n).map(f64::from).product::<f64>();
                    let exact = f(a) * f(b) / f(a + b + 2);
                    assert!((num - exact).abs() < 1e-14, "{fam:?} {a} {b}");
                }
            }
        }
    }
}
