//! code_aster's mortar pairing and integration for LAC contact (2D and 3D):
//! the intersection of a slave cell with the projection of a master cell
//! (`prjint` and its helpers `apinte_*`, `apelem_*`, `ptinma`, `insema`,
//! `lcodrm`), the intersection's images in the master cell (`aprtpm`),
//! the patch measures (`clpoma`), the integrated gap (`gapint`) and the
//! contact force of a pair (`lcvect`: `lcsees`, `lcsema`).
//!
//! Conventions, as code_aster's:
//!
//! - Intersections are computed in the **slave parametric space** of the
//!   *linearised* slave cell (SEG2, TRIA3, or a QUAD4 drawn in the TRIA3
//!   space of its first three nodes and mapped back to the quadrangle's
//!   own coordinates), against the master cell's corners projected
//!   orthogonally onto the slave's plane. Quadratic cells are linearised
//!   on their corners for the intersection only; everything else uses the
//!   full cell.
//! - The intersection polygon is triangulated as a fan (`lctria`) and each
//!   triangle integrated with the TRIA3 family FPG6 (3D) or the segment
//!   with FPG3 (2D) (`lcptga`); the force uses the element's family
//!   (FPG6 in 3D, FPG3 on SEG2 and FPG4 on SEG3 slaves in 2D) on the
//!   slave triangle and, separately, on its image in the master space.
//! - Master points of the gap are found along the slave normal (`mmnewd`).
//! - Normals: `mmnorm` is the *interior* normal (t₂ × t₁ in 3D, (−t_y, t_x)
//!   in 2D) of a cell oriented outwards; cells are oriented outwards here
//!   with `SurfaceCell::sign` (code_aster relies on `ORIE_PEAU`).
//! - Tolerance `pair_tole` (`RESI_APPA`, default 1e-8) for the pairing;
//!   1e-8 for the paired measure of a patch (`lac_gapi`).

use crate::shape::{cross, dot, interpolate, norm, scale, sub, SurfaceKind};

/// code_aster's `RESI_APPA` default (tolerance of the LAC pairing), and
/// the fixed threshold of a paired measure (`lac_gapi`).
pub const PAIR_TOLE: f64 = 1e-8;

/// A cell as the mortar routines see it: its kind, its node positions and
/// the sign making its geometric normal point out of its body.
#[derive(Clone, Copy, Debug)]
pub struct MortarCell<'a> {
    pub kind: SurfaceKind,
    pub x: &'a [[f64; 3]],
    pub sign: f64,
}

impl<'a> MortarCell<'a> {
    /// The linearised cell (corners only): SEG2, TRIA3 or QUAD4.
    pub fn linear(self) -> MortarCell<'a> {
        let kind = linear_kind(self.kind);
        MortarCell {
            kind,
            x: &self.x[..kind.node_count()],
            sign: self.sign,
        }
    }

    fn dim(self) -> usize {
        self.kind.dim() + 1
    }

    /// code_aster's `mmnorm` oriented: the unit normal pointing into the
    /// cell's body at `xi`.
    pub fn interior_normal(self, xi: [f64; 2]) -> [f64; 3] {
        let cp = interpolate(self.kind, self.x, xi);
        let t = cp.tangents;
        let raw = if self.dim() == 2 {
            [-t[0][1], t[0][0], 0.0]
        } else {
            cross(t[1], t[0])
        };
        let l = norm(raw);
        if l > 0.0 {
            scale(raw, self.sign / l)
        } else {
            raw
        }
    }

    /// Position at `xi` (`reerel`).
    pub fn point(self, xi: [f64; 2]) -> [f64; 3] {
        interpolate(self.kind, self.x, xi).x
    }

    /// Surface jacobian at `xi` (`mmmjac`): |t| (×|r| in AXIS, r = 1e-7
    /// on the axis) for segments, |t₁ × t₂| for faces.
    pub fn jacobian(self, xi: [f64; 2], axis: bool) -> f64 {
        let cp = interpolate(self.kind, self.x, xi);
        let t = cp.tangents;
        if self.dim() == 2 {
            let j = norm(t[0]);
            if axis {
                let r = if cp.x[0] == 0.0 { 1e-7 } else { cp.x[0] };
                j * r.abs()
            } else {
                j
            }
        } else {
            // sumetr: √(det of the metric).
            let (g11, g12, g22) = (dot(t[0], t[0]), dot(t[0], t[1]), dot(t[1], t[1]));
            (g11 * g22 - g12 * g12).sqrt()
        }
    }
}

/// SEG3 → SEG2, TRIA6/7 → TRIA3, QUAD8/9 → QUAD4.
pub fn linear_kind(kind: SurfaceKind) -> SurfaceKind {
    match kind {
        SurfaceKind::Seg2 | SurfaceKind::Seg3 => SurfaceKind::Seg2,
        SurfaceKind::Tria3 | SurfaceKind::Tria6 | SurfaceKind::Tria7 => SurfaceKind::Tria3,
        SurfaceKind::Quad4 | SurfaceKind::Quad8 | SurfaceKind::Quad9 => SurfaceKind::Quad4,
    }
}

/// Fortran's `sign(a, b)`: |a| with the sign of b (+ for b = ±0).
fn fsign(a: f64, b: f64) -> f64 {
    if b >= 0.0 {
        a.abs()
    } else {
        -a.abs()
    }
}

// ---------------------------------------------------------------------
// Integration families (elraga), code_aster's constants.

/// Gauss points of a family on the reference TRIA3: (ξ, η), weight.
pub fn tria_family(family: Family) -> Vec<([f64; 2], f64)> {
    match family {
        Family::Fpg3 => {
            let (a, b, w) = (1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0);
            vec![([a, a], w), ([b, a], w), ([a, b], w)]
        }
        Family::Fpg6 => {
            let p1 = 0.111690794839005;
            let p2 = 0.054975871827661;
            let xa = 0.445948490915965;
            let xb = 0.091576213509771;
            // elraga writes the coordinates through t(u) = 2u − 1.
            let t = |u: f64| (2.0 * u - 1.0 + 1.0) / 2.0;
            vec![
                ([t(xb), t(xb)], p2),
                ([t(1.0 - 2.0 * xb), t(xb)], p2),
                ([t(xb), t(1.0 - 2.0 * xb)], p2),
                ([t(xa), t(1.0 - 2.0 * xa)], p1),
                ([t(xa), t(xa)], p1),
                ([t(1.0 - 2.0 * xa), t(xa)], p1),
            ]
        }
        // FPG4 and FPG7 of TRIA3 (orders 3 and 5), for the mortar contact of
        // DEFI_CONT in 3D (`getQuadCont`).
        Family::Fpg4 => {
            let (a, b, w) = (0.2, 0.6, 25.0 / 96.0);
            vec![
                ([a, a], w),
                ([b, a], w),
                ([a, b], w),
                ([1.0 / 3.0, 1.0 / 3.0], -27.0 / 96.0),
            ]
        }
        Family::Fpg7 => {
            let r15 = 15f64.sqrt();
            let p1 = (155.0 + r15) / 2400.0;
            let p2 = (155.0 - r15) / 2400.0;
            let a2 = (6.0 + r15) / 21.0;
            let b2 = (6.0 - r15) / 21.0;
            vec![
                ([1.0 / 3.0, 1.0 / 3.0], 9.0 / 80.0),
                ([a2, a2], p1),
                ([1.0 - 2.0 * a2, a2], p1),
                ([a2, 1.0 - 2.0 * a2], p1),
                ([b2, b2], p2),
                ([1.0 - 2.0 * b2, b2], p2),
                ([b2, 1.0 - 2.0 * b2], p2),
            ]
        }
        Family::Fpg9 => Vec::new(),
    }
}

/// Gauss points of a family on the reference segment [−1, 1].
pub fn segment_family(family: Family) -> Vec<(f64, f64)> {
    match family {
        Family::Fpg3 => {
            let a = 0.774596669241483;
            vec![
                (-a, 0.555555555555556),
                (0.0, 0.888888888888889),
                (a, 0.555555555555556),
            ]
        }
        Family::Fpg4 => {
            let (a, b) = (0.339981043584856, 0.861136311594053);
            let (wa, wb) = (0.652145154862546, 0.347854845137454);
            vec![(a, wa), (-a, wa), (b, wb), (-b, wb)]
        }
        Family::Fpg6 | Family::Fpg7 | Family::Fpg9 => Vec::new(),
    }
}

/// FPG9 on the reference QUAD4 (3 × 3 Gauss).
fn quad_fpg9() -> Vec<([f64; 2], f64)> {
    let a = 0.774596669241483;
    let (w1, w2, w3) = (25.0 / 81.0, 40.0 / 81.0, 64.0 / 81.0);
    vec![
        ([-a, -a], w1),
        ([a, -a], w1),
        ([a, a], w1),
        ([-a, a], w1),
        ([0.0, -a], w2),
        ([a, 0.0], w2),
        ([0.0, a], w2),
        ([-a, 0.0], w2),
        ([0.0, 0.0], w3),
    ]
}

/// code_aster's integration families used by LAC.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    Fpg3,
    Fpg4,
    Fpg6,
    Fpg7,
    Fpg9,
}

/// The element family of a LAC contact element (`lcelem`): FPG6 on faces,
/// FPG3 on SEG2 and FPG4 on SEG3 slave segments.
pub fn element_family(slave: SurfaceKind) -> Family {
    match slave {
        SurfaceKind::Seg2 => Family::Fpg3,
        SurfaceKind::Seg3 => Family::Fpg4,
        _ => Family::Fpg6,
    }
}

/// Measure of a cell (`clpoma`, no radius): SEG and TRIA3 FPG3, TRIA6
/// FPG6, QUAD FPG9, on the given positions.
pub fn cell_measure(cell: MortarCell) -> f64 {
    let pts: Vec<([f64; 2], f64)> = match cell.kind {
        SurfaceKind::Seg2 | SurfaceKind::Seg3 => segment_family(Family::Fpg3)
            .into_iter()
            .map(|(x, w)| ([x, 0.0], w))
            .collect(),
        SurfaceKind::Tria3 => tria_family(Family::Fpg3),
        SurfaceKind::Tria6 | SurfaceKind::Tria7 => tria_family(Family::Fpg6),
        SurfaceKind::Quad4 | SurfaceKind::Quad8 | SurfaceKind::Quad9 => quad_fpg9(),
    };
    pts.iter()
        .map(|(xi, w)| w * cell.jacobian(*xi, false))
        .sum()
}

/// Fan triangulation of a convex polygon of `n` points (`lctria`), as
/// code_aster numbers it (0-based).
pub fn fan(n: usize) -> Vec<[usize; 3]> {
    match n {
        3 => vec![[0, 1, 2]],
        4 => vec![[0, 1, 2], [2, 3, 0]],
        5 => vec![[0, 1, 2], [2, 3, 4], [4, 0, 2]],
        6 => vec![[0, 1, 2], [2, 3, 4], [4, 5, 0], [0, 2, 4]],
        7 => vec![[0, 1, 2], [2, 3, 4], [4, 5, 6], [6, 0, 2], [2, 4, 6]],
        8 => vec![
            [0, 1, 2],
            [2, 3, 4],
            [4, 5, 6],
            [6, 7, 0],
            [0, 2, 4],
            [4, 6, 0],
        ],
        _ => Vec::new(),
    }
}

/// Integration points of a piece (`lcptga`): a triangle (3D) or a segment
/// (2D, its first two points) given in a parametric space, with the
/// family's points mapped onto it and weights scaled by its measure.
pub fn piece_points(dim: usize, corners: &[[f64; 2]], family: Family) -> Vec<([f64; 2], f64)> {
    if dim == 3 {
        let [a, b, c] = [corners[0], corners[1], corners[2]];
        let area = ((a[0] * b[1] - b[0] * a[1] + b[0] * c[1] - c[0] * b[1] + c[0] * a[1]
            - a[0] * c[1])
            / 2.0)
            .abs();
        tria_family(family)
            .into_iter()
            .map(|(p, w)| {
                let l = 1.0 - p[0] - p[1];
                (
                    [
                        l * a[0] + p[0] * b[0] + p[1] * c[0],
                        l * a[1] + p[0] * b[1] + p[1] * c[1],
                    ],
                    2.0 * area * w,
                )
            })
            .collect()
    } else {
        let (a, b) = (corners[0][0], corners[1][0]);
        let len = (b - a).abs();
        segment_family(family)
            .into_iter()
            .map(|(x, w)| {
                (
                    [(1.0 - x) / 2.0 * a + (1.0 + x) / 2.0 * b, 0.0],
                    0.5 * len * w,
                )
            })
            .collect()
    }
}

/// The pieces of an intersection polygon, as point index lists: the fan's
/// triangles (3D) or the segment (2D).
pub fn pieces(dim: usize, n: usize) -> Vec<Vec<usize>> {
    if dim == 3 {
        fan(n).into_iter().map(|t| t.to_vec()).collect()
    } else {
        vec![vec![0, 1]]
    }
}

// ---------------------------------------------------------------------
// Projections.

/// Orthogonal projection of `p` on the plane (3D) or line (2D) of a linear
/// TRIA3/SEG2 (`mmnewt` on a linear cell converges in one exact step):
/// parametric coordinates.
fn project_linear(dim: usize, x: &[[f64; 3]], p: [f64; 3]) -> Option<[f64; 2]> {
    if dim == 2 {
        let d = sub(x[1], x[0]);
        let dd = dot(d, d);
        if dd == 0.0 {
            return None;
        }
        // SEG2: x = x₀ (1 − ξ)/2 + x₁ (1 + ξ)/2.
        Some([-1.0 + 2.0 * dot(sub(p, x[0]), d) / dd, 0.0])
    } else {
        let (t1, t2) = (sub(x[1], x[0]), sub(x[2], x[0]));
        let r = sub(p, x[0]);
        let (a, b, c) = (dot(t1, t1), dot(t1, t2), dot(t2, t2));
        let det = a * c - b * b;
        if det == 0.0 {
            return None;
        }
        let (f, g) = (dot(r, t1), dot(r, t2));
        Some([(c * f - b * g) / det, (a * g - b * f) / det])
    }
}

/// Point of `cell` on the line through `p` along `dir` (`mmnewd`): Newton
/// on x(ξ) + β·dir = p from ξ = 0, β = 1, code_aster's stopping test
/// (relative 1e-8 on (ξ, β)), the best iterate if it does not converge;
/// `None` on a singular system.
pub fn project_along(
    cell: MortarCell,
    p: [f64; 3],
    dir: [f64; 3],
    iter_maxi: usize,
    tole: f64,
) -> Option<[f64; 2]> {
    let dim = cell.dim();
    let tole_rela = tole;
    let tole_abso = tole / 100.0;
    let (mut k1, mut k2, mut beta) = (0.0, 0.0, 1.0);
    let mut best = (f64::MAX, 0.0, 0.0);
    let mut iter = 0;
    loop {
        let cp = interpolate(cell.kind, cell.x, [k1, k2]);
        let v = sub(p, cp.x);
        let dist = norm(v);
        let r = [
            v[0] - beta * dir[0],
            v[1] - beta * dir[1],
            v[2] - beta * dir[2],
        ];
        let (t1, t2) = (cp.tangents[0], cp.tangents[1]);
        let (d1, d2, db);
        if dim == 2 {
            let det = t1[0] * dir[1] - dir[0] * t1[1];
            if det == 0.0 {
                return None;
            }
            d1 = (r[0] * dir[1] - r[1] * dir[0]) / det;
            d2 = 0.0;
            db = (r[1] * t1[0] - r[0] * t1[1]) / det;
        } else {
            // Columns t1, t2, dir; Cramer's rule.
            let det = dot(t1, cross(t2, dir));
            if det == 0.0 {
                return None;
            }
            d1 = dot(r, cross(t2, dir)) / det;
            d2 = dot(t1, cross(r, dir)) / det;
            db = dot(t1, cross(t2, r)) / det;
        }
        k1 += d1;
        k2 += d2;
        beta += db;
        if dist <= best.0 {
            best = (dist, k1, k2);
        }
        let refe = k1 * k1 + k2 * k2 + beta * beta;
        let step = (d1 * d1 + d2 * d2 + db * db).sqrt();
        let (test, tol) = if refe <= tole_rela {
            (step, tole_abso)
        } else {
            (step / refe.sqrt(), tole_rela)
        };
        if !(k1.is_finite() && k2.is_finite() && beta.is_finite()) {
            return None;
        }
        if test > tol && iter < iter_maxi {
            iter += 1;
            continue;
        }
        if test > tol {
            return Some([best.1, best.2]);
        }
        return Some([k1, k2]);
    }
}

/// Inverse bilinear map of a QUAD4 given by its corners in a plane
/// (`reereg('C', 'QU4')`: Newton from the origin, stops when the squared
/// step is below 1e-8, 50 iterations); `None` if it fails.
fn inverse_quad4(corners: &[[f64; 2]; 4], p: [f64; 2]) -> Option<[f64; 2]> {
    let c = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    let mut xe = [0.0_f64; 2];
    for _ in 0..50 {
        let mut x = [0.0; 2];
        let mut j = [[0.0; 2]; 2];
        for k in 0..4 {
            let n = (1.0 + c[k][0] * xe[0]) * (1.0 + c[k][1] * xe[1]) / 4.0;
            let d0 = c[k][0] * (1.0 + c[k][1] * xe[1]) / 4.0;
            let d1 = c[k][1] * (1.0 + c[k][0] * xe[0]) / 4.0;
            for i in 0..2 {
                x[i] += n * corners[k][i];
                j[i][0] += d0 * corners[k][i];
                j[i][1] += d1 * corners[k][i];
            }
        }
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det.abs() <= f64::MIN_POSITIVE || !det.is_finite() {
            return None;
        }
        let (r0, r1) = (x[0] - p[0], x[1] - p[1]);
        let s0 = (j[1][1] * r0 - j[0][1] * r1) / det;
        let s1 = (-j[1][0] * r0 + j[0][0] * r1) / det;
        xe = [xe[0] - s0, xe[1] - s1];
        if s0 * s0 + s1 * s1 <= 1e-8 {
            return Some(xe);
        }
    }
    None
}

// ---------------------------------------------------------------------
// The intersection (prjint).

/// `ptinma`: whether a point lies in a linear cell given by its
/// parametric vertices (`1` in, `0` out, `-1` degenerate).
fn point_in_cell(dim: usize, poly: &[[f64; 2]], p: [f64; 2], tol: f64) -> i8 {
    if dim == 2 {
        let (lo, hi) = (poly[0][0].min(poly[1][0]), poly[0][0].max(poly[1][0]));
        return if p[0] >= lo - tol && p[0] <= hi + tol {
            1
        } else {
            0
        };
    }
    let triangles: &[[usize; 3]] = if poly.len() == 4 {
        &[[0, 1, 2], [0, 2, 3]]
    } else {
        &[[0, 1, 2]]
    };
    let mut test = 0;
    for t in triangles {
        let (o, a, b) = (poly[t[0]], poly[t[1]], poly[t[2]]);
        let v0 = [a[0] - o[0], a[1] - o[1]];
        let v1 = [b[0] - o[0], b[1] - o[1]];
        let d00 = v0[0] * v0[0] + v0[1] * v0[1];
        let d10 = v0[0] * v1[0] + v0[1] * v1[1];
        let d11 = v1[0] * v1[0] + v1[1] * v1[1];
        let m = d00 * d11 - d10 * d10;
        if m.abs() <= tol {
            return -1;
        }
        let v2 = [p[0] - o[0], p[1] - o[1]];
        let d02 = v0[0] * v2[0] + v0[1] * v2[1];
        let d12 = v1[0] * v2[0] + v1[1] * v2[1];
        if (v2[0] * v2[0] + v2[1] * v2[1]).sqrt() <= tol {
            return 1;
        }
        let u = 1.0 / m * (d11 * d02 - d10 * d12);
        let v = 1.0 / m * (d00 * d12 - d10 * d02);
        if u >= -tol && v >= -tol && u + v <= 1.0 + tol {
            return 1;
        }
        test = 0;
    }
    test
}

/// `insema`: intersections of the segment p1–p2 with the edges of the
/// slave polygon; marks the slave edges hit.
fn segment_cuts(
    poly: &[[f64; 2]],
    p1: [f64; 2],
    p2: [f64; 2],
    tol: f64,
    out: &mut Vec<[f64; 2]>,
    neigh: &mut [bool; 4],
) {
    let n = poly.len();
    let (x1, y1) = (p1[0], p1[1]);
    let (a, b) = (p2[0] - p1[0], p2[1] - p1[1]);
    for i in 0..n {
        let (x2, y2) = (poly[i][0], poly[i][1]);
        let (c, d) = (poly[(i + 1) % n][0] - x2, poly[(i + 1) % n][1] - y2);
        let det = b * c - a * d;
        let (t1, t2) = if (det * det).sqrt() > tol {
            (
                1.0 / det * (d * (x1 - x2) - c * (y1 - y2)),
                1.0 / det * (b * (x1 - x2) - a * (y1 - y2)),
            )
        } else {
            (-1.0, -1.0)
        };
        if t1 < 1.0 + tol && t1 > -tol && t2 < 1.0 + tol && t2 > -tol {
            out.push([
                (t2 * c + x2 + t1 * a + x1) / 2.0,
                (t2 * d + y2 + t1 * b + y1) / 2.0,
            ]);
            neigh[i] = true;
        }
    }
}

/// `lcodrm`: sorts the points by angle around their barycentre and drops
/// those whose angle repeats the next one's (3D); keeps the extreme
/// points (2D).
fn sort_points(dim: usize, pts: &mut Vec<[f64; 2]>, tol: f64) {
    let n = pts.len();
    if dim == 3 {
        let mut bary = [0.0; 2];
        for p in pts.iter() {
            bary[0] += p[0] / n as f64;
            bary[1] += p[1] / n as f64;
        }
        let angle: Vec<f64> = pts
            .iter()
            .map(|p| (p[0] - bary[0]).atan2(p[1] - bary[1]))
            .collect();
        // ordr8: selection sort of an index (stable on ties as written).
        let mut ord: Vec<usize> = (0..n).collect();
        for i in 0..n.saturating_sub(1) {
            let mut imin = i;
            let mut vmin = angle[ord[i]];
            for j in i + 1..n {
                if angle[ord[j]] < vmin {
                    vmin = angle[ord[j]];
                    imin = j;
                }
            }
            ord.swap(i, imin);
        }
        let mut sorted = Vec::new();
        for i in 0..n {
            let d = (angle[ord[i]] - angle[ord[(i + 1) % n]]).abs();
            if d > 10.0 * tol {
                sorted.push(pts[ord[i]]);
            }
        }
        *pts = sorted;
    } else {
        let mut lo = pts[0][0];
        let mut hi = pts[0][0];
        for p in pts.iter().skip(1) {
            if p[0] <= lo && p[0] >= -1.0 {
                lo = p[0];
            } else if p[0] >= hi && p[0] <= 1.0 {
                hi = p[0];
            }
        }
        *pts = vec![[lo, 0.0], [hi, 0.0]];
    }
}

/// Points in a cell's parametric space.
pub type ParamPoints = Vec<[f64; 2]>;

/// The intersection of a slave cell with a master cell in the slave's
/// parametric space (`prjint`): its points (sorted) and its measure in
/// that space. `Err(())` when code_aster gives up on the pair with an
/// alarm (a point cannot be mapped back into the quadrangle, or more than
/// eight points).
#[derive(Clone, Debug, PartialEq)]
pub struct Intersection {
    pub points: Vec<[f64; 2]>,
    pub weight: f64,
}

// `Err(())`: a projection failed (code_aster's `ierr`); the caller skips the pair.
#[allow(clippy::result_unit_err)]
pub fn intersect(slave: MortarCell, master: MortarCell, tol: f64) -> Result<Intersection, ()> {
    let dim = slave.dim();
    let none = Intersection {
        points: Vec::new(),
        weight: 0.0,
    };
    let sl = slave.linear();
    let ma = master.linear();
    // Normals at the centres (apinte_norm): exterior ones.
    let centre = |k: SurfaceKind| {
        if k.is_triangle() {
            [1.0 / 3.0, 1.0 / 3.0]
        } else {
            [0.0, 0.0]
        }
    };
    let mast_norm = scale(ma.interior_normal(centre(ma.kind)), -1.0);
    let slav_norm = scale(sl.interior_normal(centre(sl.kind)), -1.0);
    // The slave's projection plane: its first three nodes (TRIA3) or line.
    let plane = &sl.x[..if dim == 3 { 3 } else { 2 }];
    let plane_point = |xi: [f64; 2]| {
        if dim == 3 {
            let l = 1.0 - xi[0] - xi[1];
            [
                l * plane[0][0] + xi[0] * plane[1][0] + xi[1] * plane[2][0],
                l * plane[0][1] + xi[0] * plane[1][1] + xi[1] * plane[2][1],
                l * plane[0][2] + xi[0] * plane[1][2] + xi[1] * plane[2][2],
            ]
        } else {
            let (a, b) = ((1.0 - xi[0]) / 2.0, (1.0 + xi[0]) / 2.0);
            [
                a * plane[0][0] + b * plane[1][0],
                a * plane[0][1] + b * plane[1][1],
                0.0,
            ]
        }
    };
    // Master corners in the slave space (apinte_prsl).
    let mut proj = Vec::with_capacity(ma.x.len());
    for &p in ma.x {
        match project_linear(dim, plane, p) {
            Some(xi) => proj.push(xi),
            None => return Ok(none),
        }
    }
    // Facing test (apinte_chck).
    for (k, &p) in ma.x.iter().enumerate() {
        let pm = sub(plane_point(proj[k]), p);
        let dist = norm(pm);
        let dist_sign = -fsign(dist, dot(pm, slav_norm));
        let tevapr = dot(pm, mast_norm);
        if (dist_sign < -tol && tevapr > -tol) || (dist_sign > tol && tevapr < tol) {
            return Ok(none);
        }
    }
    // Slave vertices in its space (apelem_getvertex).
    let mut poly: Vec<[f64; 2]> = if dim == 2 {
        vec![[-1.0, 0.0], [1.0, 0.0]]
    } else {
        vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
    };
    if sl.kind == SurfaceKind::Quad4 {
        match project_linear(3, plane, sl.x[3]) {
            Some(xi) => poly.push(xi),
            None => return Ok(none),
        }
    }
    let nv = poly.len();
    let mut pts: Vec<[f64; 2]> = Vec::new();
    let mut neigh = [false; 4];
    // Master corners inside the slave (apelem_inside).
    for &q in &proj {
        let inside = match sl.kind {
            SurfaceKind::Seg2 => q[0] >= -1.0 - tol && q[0] <= 1.0 + tol,
            SurfaceKind::Tria3 => q[0] >= -tol && q[1] >= -tol && q[0] + q[1] <= 1.0 + tol,
            _ => point_in_cell(3, &poly, q, tol) == 1,
        };
        if inside {
            pts.push(q);
        }
    }
    // Slave vertices inside the master.
    for i in 0..nv {
        match point_in_cell(dim, &proj, poly[i], tol) {
            1 => {
                pts.push(poly[i]);
                neigh[i] = true;
                if dim == 3 {
                    neigh[(i + nv - 1) % nv] = true;
                }
            }
            -1 => return Ok(none),
            _ => {}
        }
    }
    // Master edges against slave edges (insema).
    if dim == 3 {
        let m = proj.len();
        for i in 0..m {
            segment_cuts(&poly, proj[i], proj[(i + 1) % m], tol, &mut pts, &mut neigh);
        }
    }
    // Back to the quadrangle's own coordinates.
    if sl.kind == SurfaceKind::Quad4 {
        let corners = [poly[0], poly[1], poly[2], poly[3]];
        for p in pts.iter_mut() {
            match inverse_quad4(&corners, *p) {
                Some(xe) => *p = xe,
                None => return Err(()),
            }
        }
    }
    if (dim == 3 && pts.len() > 2) || (dim == 2 && pts.len() >= 2) {
        sort_points(dim, &mut pts, tol);
    }
    if pts.len() > 8 {
        return Err(());
    }
    // apinte_weight.
    let weight = if dim == 3 && pts.len() > 2 {
        let n = pts.len();
        let s: f64 = (0..n)
            .map(|i| pts[i][0] * pts[(i + 1) % n][1] - pts[(i + 1) % n][0] * pts[i][1])
            .sum();
        (0.5 * s).abs()
    } else if dim == 2 && pts.len() >= 2 {
        (pts[1][0] - pts[0][0]).abs()
    } else {
        0.0
    };
    Ok(Intersection {
        points: pts,
        weight,
    })
}

/// A paired slave and master cell (a LAC contact element): the
/// intersection in the slave space, its image in the master space, and
/// the master points of the gap's integration points.
#[derive(Clone, Debug, PartialEq)]
pub struct MortarPair {
    /// Indices into the zone's slave and master cells.
    pub slave: usize,
    pub master: usize,
    pub slave_points: Vec<[f64; 2]>,
    pub master_points: Vec<[f64; 2]>,
    pub gauss_master: Vec<[f64; 2]>,
}

/// The images in the master space of the intersection points (projected
/// along the slave normal) and of the gap's integration points (along the
/// exterior slave normal) (`aprtpm`); `None` if a projection fails.
pub fn master_images(
    slave: MortarCell,
    master: MortarCell,
    slave_points: &[[f64; 2]],
    tole: f64,
) -> Option<(ParamPoints, ParamPoints)> {
    let dim = slave.dim();
    let mut master_points = Vec::with_capacity(slave_points.len());
    for &xi in slave_points {
        let p = slave.point(xi);
        let n = slave.interior_normal(xi);
        master_points.push(project_along(master, p, n, 100, tole)?);
    }
    let mut gauss = Vec::new();
    for piece in pieces(dim, slave_points.len()) {
        let corners: Vec<[f64; 2]> = piece.iter().map(|&k| slave_points[k]).collect();
        let family = if dim == 3 { Family::Fpg6 } else { Family::Fpg3 };
        for (xi, _) in piece_points(dim, &corners, family) {
            let p = slave.point(xi);
            let n = scale(slave.interior_normal(xi), -1.0);
            gauss.push(project_along(master, p, n, 200, tole)?);
        }
    }
    Some((master_points, gauss))
}

/// The integrated gap of a pair (`gapint`): Σ w·J·d over the gap's
/// integration points, d the signed distance (negative when apart, as
/// code_aster's `dist_sign`), and the measure Σ w·J — on the positions the
/// cells are given with.
pub fn gap_integral(
    slave: MortarCell,
    master: MortarCell,
    pair: &MortarPair,
    axis: bool,
) -> (f64, f64) {
    let dim = slave.dim();
    let family = if dim == 3 { Family::Fpg6 } else { Family::Fpg3 };
    let (mut gap, mut weight) = (0.0, 0.0);
    let mut g = 0;
    for piece in pieces(dim, pair.slave_points.len()) {
        let corners: Vec<[f64; 2]> = piece.iter().map(|&k| pair.slave_points[k]).collect();
        for (xi, w) in piece_points(dim, &corners, family) {
            let jw = w * slave.jacobian(xi, axis);
            let p = slave.point(xi);
            let n = scale(slave.interior_normal(xi), -1.0);
            let Some(&eta) = pair.gauss_master.get(g) else {
                break;
            };
            g += 1;
            let pm = sub(master.point(eta), p);
            let dist_sign = -fsign(norm(pm), dot(pm, n));
            gap += jw * dist_sign;
            weight += jw;
        }
    }
    (gap, weight)
}

/// The contact force direction of a pair (`lcvect`): per slave and master
/// node, Σ w·J₀·N·n with n the *exterior* normal of its own cell at its own
/// integration point (or the node's smoothed normal), J₀ the jacobian on
/// the reference positions. The force on the structure is −λ times it
/// (λ ≥ 0 the patch pressure).
pub struct PairForce {
    pub slave: Vec<[f64; 3]>,
    pub master: Vec<[f64; 3]>,
}

/// Inputs of [`pair_force`] besides the pair: both cells on the current
/// and on the reference positions, and optional smoothed exterior nodal
/// normals (LISSAGE) per node of each cell.
pub struct ForceCells<'a> {
    pub slave: MortarCell<'a>,
    pub slave_ref: MortarCell<'a>,
    pub master: MortarCell<'a>,
    pub master_ref: MortarCell<'a>,
    pub slave_normals: Option<&'a [[f64; 3]]>,
    pub master_normals: Option<&'a [[f64; 3]]>,
    pub axis: bool,
    /// `TYPE_JACOBIEN='ACTUALISE'`: jacobians on the current positions.
    pub updated_jacobian: bool,
}

pub fn pair_force(cells: &ForceCells, pair: &MortarPair) -> PairForce {
    let dim = cells.slave.dim();
    let family = element_family(cells.slave.kind);
    let mut out = PairForce {
        slave: vec![[0.0; 3]; cells.slave.x.len()],
        master: vec![[0.0; 3]; cells.master.x.len()],
    };
    for piece in pieces(dim, pair.slave_points.len()) {
        let cs: Vec<[f64; 2]> = piece.iter().map(|&k| pair.slave_points[k]).collect();
        let cm: Vec<[f64; 2]> = piece.iter().map(|&k| pair.master_points[k]).collect();
        let ps = piece_points(dim, &cs, family);
        let pm = piece_points(dim, &cm, family);
        for ((xs, ws), (xm, wm)) in ps.into_iter().zip(pm) {
            let side = |cell: MortarCell,
                        reference: MortarCell,
                        normals: Option<&[[f64; 3]]>,
                        xi: [f64; 2],
                        w: f64,
                        acc: &mut [[f64; 3]]| {
                let (shape, _) = cell.kind.eval(xi);
                let jac = if cells.updated_jacobian {
                    cell.jacobian(xi, cells.axis)
                } else {
                    reference.jacobian(xi, cells.axis)
                };
                let n = scale(cell.interior_normal(xi), -1.0);
                for (k, nk) in shape.iter().enumerate().take(acc.len()) {
                    let normal = normals.and_then(|v| v.get(k).copied()).unwrap_or(n);
                    for d in 0..3 {
                        acc[k][d] += w * jac * nk * normal[d];
                    }
                }
            };
            side(
                cells.slave,
                cells.slave_ref,
                cells.slave_normals,
                xs,
                ws,
                &mut out.slave,
            );
            side(
                cells.master,
                cells.master_ref,
                cells.master_normals,
                xm,
                wm,
                &mut out.master,
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cell(kind: SurfaceKind, x: &[[f64; 3]]) -> MortarCell<'_> {
        MortarCell { kind, x, sign: 1.0 }
    }

    #[test]
    fn families_integrate_polynomials_exactly() {
        // FPG6 on the triangle: degree 4; FPG3 degree 2.
        let f = |p: [f64; 2]| p[0].powi(4) + p[0] * p[1].powi(3);
        let exact = 1.0 / 30.0 + 1.0 / 120.0;
        let s: f64 = tria_family(Family::Fpg6)
            .iter()
            .map(|(p, w)| w * f(*p))
            .sum();
        assert!((s - exact).abs() < 1e-14, "{s}");
        let s: f64 = tria_family(Family::Fpg3)
            .iter()
            .map(|(p, w)| w * p[0] * p[1])
            .sum();
        assert!((s - 1.0 / 24.0).abs() < 1e-15);
        // Segments: FPG3 degree 5, FPG4 degree 7.
        let s: f64 = segment_family(Family::Fpg4)
            .iter()
            .map(|(x, w)| w * x.powi(6))
            .sum();
        assert!((s - 2.0 / 7.0).abs() < 1e-14);
        let s: f64 = quad_fpg9()
            .iter()
            .map(|(p, w)| w * p[0].powi(4) * p[1].powi(2))
            .sum();
        assert!((s - 0.4 * 2.0 / 3.0).abs() < 1e-14);
    }

    #[test]
    fn fan_covers_the_polygon() {
        for n in 3..=8 {
            let poly: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let a = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                    [a.cos(), a.sin()]
                })
                .collect();
            let area: f64 = fan(n)
                .iter()
                .map(|t| {
                    piece_points(3, &[poly[t[0]], poly[t[1]], poly[t[2]]], Family::Fpg6)
                        .iter()
                        .map(|(_, w)| w)
                        .sum::<f64>()
                })
                .sum();
            let exact = 0.5 * n as f64 * (2.0 * std::f64::consts::PI / n as f64).sin();
            assert!((area - exact).abs() < 1e-13, "{n}: {area} vs {exact}");
        }
    }

    #[test]
    fn square_against_a_shifted_square_clips_to_their_overlap() {
        // Slave: unit square at z = 0, outward normal −z (the body above).
        let s = [[0., 0., 0.], [0., 1., 0.], [1., 1., 0.], [1., 0., 0.]];
        // Master: square [0.5, 1.5] × [0.25, 1.25] at z = −0.1, normal +z.
        let m = [
            [0.5, 0.25, -0.1],
            [1.5, 0.25, -0.1],
            [1.5, 1.25, -0.1],
            [0.5, 1.25, -0.1],
        ];
        let sc = cell(SurfaceKind::Quad4, &s);
        let mc = cell(SurfaceKind::Quad4, &m);
        assert!(dot(sc.interior_normal([0., 0.]), [0., 0., 1.]) > 0.99);
        let i = intersect(sc, mc, PAIR_TOLE).unwrap();
        assert_eq!(i.points.len(), 4);
        // Overlap 0.5 × 0.75 in physical space; the QUAD4's reference
        // square has 4 × the unit square's area.
        assert!((i.weight - 4.0 * 0.375).abs() < 1e-12, "{}", i.weight);
        let (mp, gauss) = master_images(sc, mc, &i.points, PAIR_TOLE).unwrap();
        assert_eq!(gauss.len(), 12);
        let pair = MortarPair {
            slave: 0,
            master: 0,
            slave_points: i.points.clone(),
            master_points: mp,
            gauss_master: gauss,
        };
        // Apart by 0.1 over 0.375: ∫ d = −0.0375.
        let (gap, w) = gap_integral(sc, mc, &pair, false);
        assert!(
            (w - 0.375).abs() < 1e-12 && (gap + 0.0375).abs() < 1e-12,
            "{gap} {w}"
        );
        // The force: each side's normal times its own measure, 0.375.
        let f = pair_force(
            &ForceCells {
                slave: sc,
                slave_ref: sc,
                master: mc,
                master_ref: mc,
                slave_normals: None,
                master_normals: None,
                axis: false,
                updated_jacobian: false,
            },
            &pair,
        );
        let fs: f64 = f.slave.iter().map(|v| v[2]).sum();
        let fm: f64 = f.master.iter().map(|v| v[2]).sum();
        assert!(
            (fs + 0.375).abs() < 1e-12 && (fm - 0.375).abs() < 1e-12,
            "{fs} {fm}"
        );
        // Master cell facing away: no intersection.
        let away = [m[0], m[3], m[2], m[1]];
        let i = intersect(sc, cell(SurfaceKind::Quad4, &away), PAIR_TOLE).unwrap();
        assert!(i.points.is_empty() && i.weight == 0.0);
    }

    #[test]
    fn triangle_inside_quadrangle_and_segments() {
        // Slave TRIA3 strictly inside a large master quad: the whole
        // triangle, area ½ in its space.
        let s = [[0.2, 0.2, 0.0], [0.2, 0.6, 0.0], [0.6, 0.2, 0.0]];
        let m = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
        let i = intersect(
            cell(SurfaceKind::Tria3, &s),
            cell(SurfaceKind::Quad4, &m),
            PAIR_TOLE,
        )
        .unwrap();
        assert_eq!(i.points.len(), 3);
        assert!((i.weight - 0.5).abs() < 1e-14);
        // 2D: slave segment [0, 2] (outward −y), master [1.5, 3] below.
        let s = [[0., 0., 0.], [2., 0., 0.]];
        let m = [[3., -0.01, 0.], [1.5, -0.01, 0.]];
        let sc = cell(SurfaceKind::Seg2, &s);
        assert!(dot(sc.interior_normal([0., 0.]), [0., 1., 0.]) > 0.99);
        let i = intersect(sc, cell(SurfaceKind::Seg2, &m), PAIR_TOLE).unwrap();
        // ξ of x = 1.5 on the slave (from x = 0 to 2) is 0.5: [0.5, 1].
        assert_eq!(i.points.len(), 2);
        assert!((i.points[0][0] - 0.5).abs() < 1e-14 && (i.points[1][0] - 1.0).abs() < 1e-14);
        assert!((i.weight - 0.5).abs() < 1e-14);
    }

    #[test]
    fn projection_along_a_direction_hits_a_curved_cell() {
        // TRIA6 master on z = x²/10 over the unit triangle; a point above
        // cast along −z lands on the surface.
        let f = |x: f64, y: f64| [x, y, x * x / 10.0];
        let m = [
            f(0., 0.),
            f(1., 0.),
            f(0., 1.),
            f(0.5, 0.),
            f(0.5, 0.5),
            f(0., 0.5),
        ];
        let c = cell(SurfaceKind::Tria6, &m);
        let xi = project_along(c, [0.3, 0.2, 5.0], [0.0, 0.0, 1.0], 100, PAIR_TOLE).unwrap();
        let p = c.point(xi);
        assert!((p[0] - 0.3).abs() < 1e-12 && (p[1] - 0.2).abs() < 1e-12);
        assert!((p[2] - 0.009).abs() < 1e-12);
    }

    #[test]
    fn inverse_bilinear_recovers_the_reference_point() {
        let c = [[0., 0.], [2., 0.], [2.5, 1.5], [-0.2, 1.0]];
        let xi = [0.3, -0.4];
        let mut x = [0.0; 2];
        let r = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        for k in 0..4 {
            let n = (1.0 + r[k][0] * xi[0]) * (1.0 + r[k][1] * xi[1]) / 4.0;
            x[0] += n * c[k][0];
            x[1] += n * c[k][1];
        }
        let back = inverse_quad4(&c, x).unwrap();
        assert!((back[0] - xi[0]).abs() < 1e-9 && (back[1] - xi[1]).abs() < 1e-9);
    }
}
