//! Shape functions of the contact surface cells (code_aster node order),
//! their reference domains, and orthogonal projection onto a cell.

pub(crate) use aster_mesh::vec3::{cross, dot, norm, scale, sub};
use aster_mesh::CellType;

/// A surface cell type contact can pair on: edges in 2D, faces in 3D.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SurfaceKind {
    Seg2,
    Seg3,
    Tria3,
    Tria6,
    Quad4,
    Quad8,
    Quad9,
    Tria7,
}

impl SurfaceKind {
    pub fn of(ty: CellType) -> Option<SurfaceKind> {
        Some(match ty {
            CellType::SEG2 => SurfaceKind::Seg2,
            CellType::SEG3 => SurfaceKind::Seg3,
            CellType::TRIA3 => SurfaceKind::Tria3,
            CellType::TRIA6 => SurfaceKind::Tria6,
            CellType::QUAD4 => SurfaceKind::Quad4,
            CellType::QUAD8 => SurfaceKind::Quad8,
            CellType::QUAD9 => SurfaceKind::Quad9,
            CellType::TRIA7 => SurfaceKind::Tria7,
            _ => return None,
        })
    }

    /// Parametric dimension (1 for edges, 2 for faces).
    pub fn dim(self) -> usize {
        match self {
            SurfaceKind::Seg2 | SurfaceKind::Seg3 => 1,
            _ => 2,
        }
    }

    pub fn node_count(self) -> usize {
        match self {
            SurfaceKind::Seg2 => 2,
            SurfaceKind::Seg3 => 3,
            SurfaceKind::Tria3 => 3,
            SurfaceKind::Tria6 => 6,
            SurfaceKind::Quad4 => 4,
            SurfaceKind::Quad8 => 8,
            SurfaceKind::Quad9 => 9,
            SurfaceKind::Tria7 => 7,
        }
    }

    /// The mesh cell type of this kind.
    pub fn cell_type(self) -> CellType {
        match self {
            SurfaceKind::Seg2 => CellType::SEG2,
            SurfaceKind::Seg3 => CellType::SEG3,
            SurfaceKind::Tria3 => CellType::TRIA3,
            SurfaceKind::Tria6 => CellType::TRIA6,
            SurfaceKind::Tria7 => CellType::TRIA7,
            SurfaceKind::Quad4 => CellType::QUAD4,
            SurfaceKind::Quad8 => CellType::QUAD8,
            SurfaceKind::Quad9 => CellType::QUAD9,
        }
    }

    /// Whether the reference domain is the unit triangle.
    pub fn is_triangle(self) -> bool {
        matches!(
            self,
            SurfaceKind::Tria3 | SurfaceKind::Tria6 | SurfaceKind::Tria7
        )
    }

    /// Shape function values and derivatives (∂/∂ξ, ∂/∂η) at `xi`.
    /// Segments use ξ ∈ [-1, 1]; triangles the unit triangle; quadrangles [-1, 1]².
    pub fn eval(self, xi: [f64; 2]) -> (Vec<f64>, Vec<[f64; 2]>) {
        let (x, y) = (xi[0], xi[1]);
        match self {
            SurfaceKind::Seg2 => (
                vec![(1.0 - x) / 2.0, (1.0 + x) / 2.0],
                vec![[-0.5, 0.0], [0.5, 0.0]],
            ),
            SurfaceKind::Seg3 => (
                vec![-x * (1.0 - x) / 2.0, x * (1.0 + x) / 2.0, 1.0 - x * x],
                vec![[x - 0.5, 0.0], [x + 0.5, 0.0], [-2.0 * x, 0.0]],
            ),
            SurfaceKind::Tria3 => (
                vec![1.0 - x - y, x, y],
                vec![[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]],
            ),
            SurfaceKind::Tria6 => {
                let l = [1.0 - x - y, x, y];
                let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
                let mut n = Vec::with_capacity(6);
                let mut d = Vec::with_capacity(6);
                for i in 0..3 {
                    n.push(l[i] * (2.0 * l[i] - 1.0));
                    let f = 4.0 * l[i] - 1.0;
                    d.push([f * dl[i][0], f * dl[i][1]]);
                }
                for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                    n.push(4.0 * l[i] * l[j]);
                    d.push([
                        4.0 * (dl[i][0] * l[j] + l[i] * dl[j][0]),
                        4.0 * (dl[i][1] * l[j] + l[i] * dl[j][1]),
                    ]);
                }
                (n, d)
            }
            SurfaceKind::Quad4 => {
                let c = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
                let n = c
                    .iter()
                    .map(|p| (1.0 + p[0] * x) * (1.0 + p[1] * y) / 4.0)
                    .collect();
                let d = c
                    .iter()
                    .map(|p| [p[0] * (1.0 + p[1] * y) / 4.0, p[1] * (1.0 + p[0] * x) / 4.0])
                    .collect();
                (n, d)
            }
            SurfaceKind::Quad8 => {
                let c = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
                let mut n = Vec::with_capacity(8);
                let mut d = Vec::with_capacity(8);
                for p in c {
                    let (a, b) = (1.0 + p[0] * x, 1.0 + p[1] * y);
                    let s = p[0] * x + p[1] * y - 1.0;
                    n.push(a * b * s / 4.0);
                    d.push([p[0] * b * (s + a) / 4.0, p[1] * a * (s + b) / 4.0]);
                }
                // Mid-side nodes 5..8 on edges 1-2, 2-3, 3-4, 4-1.
                for p in [[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]] {
                    if p[0] == 0.0 {
                        n.push((1.0 - x * x) * (1.0 + p[1] * y) / 2.0);
                        d.push([-x * (1.0 + p[1] * y), p[1] * (1.0 - x * x) / 2.0]);
                    } else {
                        n.push((1.0 + p[0] * x) * (1.0 - y * y) / 2.0);
                        d.push([p[0] * (1.0 - y * y) / 2.0, -y * (1.0 + p[0] * x)]);
                    }
                }
                (n, d)
            }
            // Faces with a centre node: code_aster's functions, shared
            // with the volume elements they bound.
            SurfaceKind::Quad9 | SurfaceKind::Tria7 => {
                let s = aster_fem::shape::shape(self.cell_type(), [x, y, 0.0]);
                (s.n, s.dn.iter().map(|d| [d[0], d[1]]).collect())
            }
        }
    }

    /// ∂²N/∂ξ² of a segment's shape functions at any ξ (code_aster's
    /// `mmdond`: 0 on SEG2, constant on SEG3); `None` for a face.
    pub fn segment_second_derivatives(self) -> Option<Vec<f64>> {
        match self {
            SurfaceKind::Seg2 => Some(vec![0.0, 0.0]),
            SurfaceKind::Seg3 => Some(vec![1.0, 1.0, -2.0]),
            _ => None,
        }
    }

    /// Number of corner nodes (numbered first, as in code_aster).
    pub fn corner_count(self) -> usize {
        match self {
            SurfaceKind::Seg2 | SurfaceKind::Seg3 => 2,
            SurfaceKind::Tria3 | SurfaceKind::Tria6 | SurfaceKind::Tria7 => 3,
            _ => 4,
        }
    }

    /// Whether the contact pressure is interpolated with the corner
    /// (linear) functions only: on quadratic faces. TRIA6 and QUAD8
    /// functions integrate to zero (TRIA6) or a negative value (QUAD8) at
    /// the corners, so a weighted gap per corner node would have no
    /// measure; QUAD9 and TRIA7 have 9 and 7 pressure unknowns per face,
    /// more than a 2×2 Gauss or a Simpson rule (no point inside the
    /// edges' span for the centre) can determine. The pressure lives on the
    /// corners; mid-side nodes take the mean of their edge's corners and a
    /// centre node that of all corners. Segments keep their own functions
    /// (SEG3: positive nodal integrals, and one point per node with every
    /// rule).
    pub fn linear_pressure(self) -> bool {
        matches!(
            self,
            SurfaceKind::Tria6 | SurfaceKind::Tria7 | SurfaceKind::Quad8 | SurfaceKind::Quad9
        )
    }

    /// Functions interpolating the contact pressure at `xi`, one per node
    /// (zero on the nodes that carry no pressure of their own).
    pub fn pressure_eval(self, xi: [f64; 2]) -> Vec<f64> {
        if !self.linear_pressure() {
            return self.eval(xi).0;
        }
        let lin = if self.is_triangle() {
            SurfaceKind::Tria3
        } else {
            SurfaceKind::Quad4
        };
        let mut n = lin.eval(xi).0;
        n.resize(self.node_count(), 0.0);
        n
    }

    /// The nodes (local indices) whose pressures a node's pressure is the
    /// mean of: itself when it carries one, else the corners of its edge
    /// (or of the face, for a centre node).
    pub fn pressure_support(self, local: usize) -> Vec<usize> {
        let nc = self.corner_count();
        if !self.linear_pressure() || local < nc {
            return vec![local];
        }
        if local < 2 * nc {
            let k = local - nc;
            vec![k, (k + 1) % nc]
        } else {
            (0..nc).collect()
        }
    }

    /// How far `xi` lies outside the reference domain, in reference
    /// coordinates (0 inside).
    pub fn outside_distance(self, xi: [f64; 2]) -> f64 {
        match self {
            SurfaceKind::Seg2 | SurfaceKind::Seg3 => (xi[0].abs() - 1.0).max(0.0),
            SurfaceKind::Quad4 | SurfaceKind::Quad8 | SurfaceKind::Quad9 => {
                let dx = (xi[0].abs() - 1.0).max(0.0);
                let dy = (xi[1].abs() - 1.0).max(0.0);
                (dx * dx + dy * dy).sqrt()
            }
            SurfaceKind::Tria3 | SurfaceKind::Tria6 | SurfaceKind::Tria7 => {
                let c = self.clamp(xi);
                ((xi[0] - c[0]).powi(2) + (xi[1] - c[1]).powi(2)).sqrt()
            }
        }
    }

    /// The closest point of the reference domain to `xi`.
    pub fn clamp(self, xi: [f64; 2]) -> [f64; 2] {
        match self {
            SurfaceKind::Seg2 | SurfaceKind::Seg3 => [xi[0].clamp(-1.0, 1.0), 0.0],
            SurfaceKind::Quad4 | SurfaceKind::Quad8 | SurfaceKind::Quad9 => {
                [xi[0].clamp(-1.0, 1.0), xi[1].clamp(-1.0, 1.0)]
            }
            SurfaceKind::Tria3 | SurfaceKind::Tria6 | SurfaceKind::Tria7 => {
                let (x, y) = (xi[0], xi[1]);
                if x >= 0.0 && y >= 0.0 && x + y <= 1.0 {
                    return [x, y];
                }
                // Closest point on each of the three edges; keep the best.
                let edges = [
                    ([0.0, 0.0], [1.0, 0.0]),
                    ([1.0, 0.0], [0.0, 1.0]),
                    ([0.0, 1.0], [0.0, 0.0]),
                ];
                let mut best = [0.0, 0.0];
                let mut best_d = f64::INFINITY;
                for (a, b) in edges {
                    let e = [b[0] - a[0], b[1] - a[1]];
                    let t = (((x - a[0]) * e[0] + (y - a[1]) * e[1]) / (e[0] * e[0] + e[1] * e[1]))
                        .clamp(0.0, 1.0);
                    let p = [a[0] + t * e[0], a[1] + t * e[1]];
                    let d = (x - p[0]).powi(2) + (y - p[1]).powi(2);
                    if d < best_d {
                        best_d = d;
                        best = p;
                    }
                }
                best
            }
        }
    }

    /// The centre of the reference domain (start of the projection).
    pub fn centre(self) -> [f64; 2] {
        match self {
            SurfaceKind::Tria3 | SurfaceKind::Tria6 | SurfaceKind::Tria7 => [1.0 / 3.0, 1.0 / 3.0],
            _ => [0.0, 0.0],
        }
    }

    /// Reference coordinates of the nodes, in code_aster order.
    pub fn node_coords(self) -> Vec<[f64; 2]> {
        match self {
            SurfaceKind::Seg2 => vec![[-1.0, 0.0], [1.0, 0.0]],
            SurfaceKind::Seg3 => vec![[-1.0, 0.0], [1.0, 0.0], [0.0, 0.0]],
            SurfaceKind::Tria3 => vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            SurfaceKind::Tria6 => vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [0.0, 1.0],
                [0.5, 0.0],
                [0.5, 0.5],
                [0.0, 0.5],
            ],
            SurfaceKind::Quad4 => vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
            SurfaceKind::Quad8 => vec![
                [-1.0, -1.0],
                [1.0, -1.0],
                [1.0, 1.0],
                [-1.0, 1.0],
                [0.0, -1.0],
                [1.0, 0.0],
                [0.0, 1.0],
                [-1.0, 0.0],
            ],
            SurfaceKind::Quad9 | SurfaceKind::Tria7 => {
                aster_fem::shape::reference_nodes(self.cell_type())
                    .into_iter()
                    .map(|p| [p[0], p[1]])
                    .collect()
            }
        }
    }
}

/// code_aster's `SIMPSON` rule on a face with `p` subdivisions (`mmgaus`):
/// on triangles the points of the grid of step 1/(2p) with weights
/// 1 (vertices), 3/4 (even/odd edge points), 6/8 (even/odd interior
/// points) over 30p²; on quadrangles the product of composite Simpson on
/// each side. Weights sum to the reference measure. `None` on segments
/// (their rule is the segment one).
pub fn face_simpson(kind: SurfaceKind, p: u8) -> Option<Vec<([f64; 2], f64)>> {
    let p = p.max(1) as usize;
    let h = 2 * p;
    if kind.dim() != 2 {
        return None;
    }
    let mut out = Vec::new();
    if kind.is_triangle() {
        for j in 0..=h {
            for i in 0..=h - j {
                let on_edge = i == 0 || j == 0 || i + j == h;
                let corner = (i == 0 && (j == 0 || j == h)) || (j == 0 && i == h);
                // Along an edge the parity of the running index decides.
                let along = if i == 0 || i + j == h { j } else { i };
                let c = if corner {
                    1.0
                } else if on_edge {
                    if along % 2 == 0 {
                        3.0
                    } else {
                        4.0
                    }
                } else if i % 2 == 0 && j % 2 == 0 {
                    6.0
                } else {
                    8.0
                };
                let xi = [i as f64 / h as f64, j as f64 / h as f64];
                out.push((xi, c / (30.0 * (p * p) as f64)));
            }
        }
    } else {
        let one: Vec<(f64, f64)> = (0..=h)
            .map(|i| {
                let c = if i == 0 || i == h {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                (-1.0 + i as f64 / p as f64, c / (3.0 * p as f64))
            })
            .collect();
        for &(y, wy) in &one {
            for &(x, wx) in &one {
                out.push(([x, y], wx * wy));
            }
        }
    }
    Some(out)
}

/// code_aster's `NCOTES` rule of degree `order` on a face: closed
/// Newton–Cotes on the equispaced grid (triangles: (i/n, j/n), i + j ≤ n;
/// quadrangles: the product of the segment rule). The weights are the
/// integrals of the grid's Lagrange polynomials, found by matching the
/// moments of every monomial of degree ≤ n. `None` on segments.
pub fn face_newton_cotes(kind: SurfaceKind, order: u8) -> Option<Vec<([f64; 2], f64)>> {
    let n = order.clamp(1, 8) as usize;
    if kind.dim() != 2 {
        return None;
    }
    if kind.is_triangle() {
        let pts: Vec<[f64; 2]> = (0..=n)
            .flat_map(|j| (0..=n - j).map(move |i| [i as f64 / n as f64, j as f64 / n as f64]))
            .collect();
        let monos: Vec<(i32, i32)> = (0..=n as i32)
            .flat_map(|d| (0..=d).map(move |a| (a, d - a)))
            .collect();
        let fact = |k: i32| (1..=k).map(f64::from).product::<f64>();
        let exact: Vec<f64> = monos
            .iter()
            .map(|&(a, b)| fact(a) * fact(b) / fact(a + b + 2))
            .collect();
        let m = nalgebra::DMatrix::from_fn(monos.len(), pts.len(), |r, c| {
            pts[c][0].powi(monos[r].0) * pts[c][1].powi(monos[r].1)
        });
        let w = m.lu().solve(&nalgebra::DVector::from_vec(exact))?;
        Some(pts.into_iter().zip(w.iter().copied()).collect())
    } else {
        let xs: Vec<f64> = (0..=n).map(|i| -1.0 + 2.0 * i as f64 / n as f64).collect();
        let exact: Vec<f64> = (0..=n)
            .map(|a| {
                if a % 2 == 1 {
                    0.0
                } else {
                    2.0 / (a as f64 + 1.0)
                }
            })
            .collect();
        let m = nalgebra::DMatrix::from_fn(n + 1, n + 1, |r, c| xs[c].powi(r as i32));
        let w = m.lu().solve(&nalgebra::DVector::from_vec(exact))?;
        let mut out = Vec::with_capacity((n + 1) * (n + 1));
        for (j, &y) in xs.iter().enumerate() {
            for (i, &x) in xs.iter().enumerate() {
                out.push(([x, y], w[i] * w[j]));
            }
        }
        Some(out)
    }
}

/// A point interpolated on a cell: position, tangents and shape values.
#[derive(Clone, Debug)]
pub struct CellPoint {
    pub xi: [f64; 2],
    pub x: [f64; 3],
    pub tangents: [[f64; 3]; 2],
    pub shape: Vec<f64>,
}

/// Position and tangents at `xi` of a cell with node positions `nodes`.
pub fn interpolate(kind: SurfaceKind, nodes: &[[f64; 3]], xi: [f64; 2]) -> CellPoint {
    let (n, d) = kind.eval(xi);
    let mut x = [0.0; 3];
    let mut t = [[0.0; 3]; 2];
    for (i, p) in nodes.iter().enumerate().take(n.len()) {
        for c in 0..3 {
            x[c] += n[i] * p[c];
            t[0][c] += d[i][0] * p[c];
            t[1][c] += d[i][1] * p[c];
        }
    }
    CellPoint {
        xi,
        x,
        tangents: t,
        shape: n,
    }
}

/// Orthogonal projection of `p` onto the (curved) cell: Newton's method on
/// the stationarity of the distance, with the curvature term (second
/// derivatives by central differences of the tangents — exact zero on
/// affine cells) and a Gauss–Newton step whenever the full Hessian is not
/// positive definite. Unconstrained: the result may lie outside the
/// reference domain; callers apply `TOLE_PROJ_EXT`. `None` when the cell is
/// degenerate.
pub fn project(kind: SurfaceKind, nodes: &[[f64; 3]], p: [f64; 3]) -> Option<CellPoint> {
    let mut xi = kind.centre();
    let dim = kind.dim();
    let h = 1e-5;
    for _ in 0..50 {
        let cp = interpolate(kind, nodes, xi);
        let r = sub(cp.x, p);
        let t = cp.tangents;
        let grad = [dot(t[0], r), dot(t[1], r)];
        let mut hess = [
            [dot(t[0], t[0]), dot(t[0], t[1])],
            [dot(t[1], t[0]), dot(t[1], t[1])],
        ];
        let gn = hess;
        for l in 0..dim {
            let mut a = xi;
            let mut b = xi;
            a[l] += h;
            b[l] -= h;
            let (ta, tb) = (
                interpolate(kind, nodes, a).tangents,
                interpolate(kind, nodes, b).tangents,
            );
            for k in 0..dim {
                let d2 = scale(sub(ta[k], tb[k]), 1.0 / (2.0 * h));
                hess[k][l] += dot(d2, r);
            }
        }
        let solve = |m: [[f64; 2]; 2]| -> Option<[f64; 2]> {
            if dim == 1 {
                (m[0][0] > 0.0).then(|| [-grad[0] / m[0][0], 0.0])
            } else {
                let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
                (m[0][0] > 0.0 && det > 1e-14 * m[0][0] * m[1][1]).then(|| {
                    [
                        -(m[1][1] * grad[0] - m[0][1] * grad[1]) / det,
                        -(m[0][0] * grad[1] - m[1][0] * grad[0]) / det,
                    ]
                })
            }
        };
        let mut step = solve(hess).or_else(|| solve(gn))?;
        // Keep steps moderate on curved cells (the quadratic model is only
        // local); affine cells converge in one step whatever its length.
        let len = (step[0] * step[0] + step[1] * step[1]).sqrt();
        if len > 4.0 {
            step = [4.0 * step[0] / len, 4.0 * step[1] / len];
        }
        xi = [xi[0] + step[0], xi[1] + step[1]];
        if !(xi[0].is_finite() && xi[1].is_finite()) {
            return None;
        }
        if len < 1e-14 {
            break;
        }
        // Far outside the cell: no tolerance accepts it; stop walking.
        if kind.outside_distance(xi) > 8.0 {
            break;
        }
    }
    Some(interpolate(kind, nodes, xi))
}

/// Projection of `p` onto the (curved) cell along the fixed direction `dir`
/// (`TYPE_PROJECTION='FIXE'` with `DIRE_APPA`, code_aster's `mmnewd`): the
/// point x(ξ) of the cell with x(ξ) + β·dir = p, by Newton's method on
/// (ξ, β) from the cell centre. The system is solved in the least-squares
/// sense (exact when the direction crosses the cell's plane or line; a
/// segment is taken in the plane of the problem, its z components being
/// 0). Unconstrained: the result may lie outside the reference domain;
/// callers apply `TOLE_PROJ_EXT`. `None` when the direction is parallel to
/// the cell.
pub fn project_along(
    kind: SurfaceKind,
    nodes: &[[f64; 3]],
    p: [f64; 3],
    dir: [f64; 3],
) -> Option<CellPoint> {
    let dim = kind.dim();
    let mut xi = kind.centre();
    for _ in 0..50 {
        let cp = interpolate(kind, nodes, xi);
        // Unknowns: ξ (dim of them) and β; residual r = p − x(ξ) − β d
        // with β eliminated by least squares at each step.
        let cols: Vec<[f64; 3]> = (0..dim).map(|k| cp.tangents[k]).chain([dir]).collect();
        let n = cols.len();
        let r = sub(p, cp.x);
        let mut a = [[0.0f64; 3]; 3];
        let mut b = [0.0f64; 3];
        for i in 0..n {
            for j in 0..n {
                a[i][j] = dot(cols[i], cols[j]);
            }
            b[i] = dot(cols[i], r);
        }
        let sol = solve_small(&a, &b, n)?;
        let step = [sol[0], if dim == 2 { sol[1] } else { 0.0 }];
        xi = [xi[0] + step[0], xi[1] + step[1]];
        if !(xi[0].is_finite() && xi[1].is_finite()) {
            return None;
        }
        let len = (step[0] * step[0] + step[1] * step[1]).sqrt();
        if len < 1e-14 {
            break;
        }
        if kind.outside_distance(xi) > 8.0 {
            break;
        }
    }
    Some(interpolate(kind, nodes, xi))
}

/// code_aster's projection of a point on a master cell (`mmnewt` with the
/// line search `mmreli`, as `approj` calls it for `MAIT_ESCL` pairing):
/// Newton on the stationarity of the distance from ξ = 0 (a vertex for
/// triangles), with the curvature term except on QUAD4/QUAD8 (Gauss–Newton
/// there), a backtracking line search on ½‖r‖², stopped when the step is
/// below `PROJ_NEWT_RESI` = 1e-4 relative to ξ (1e-6 absolute when
/// ‖ξ‖² ≤ 1e-4), at most `PROJ_NEWT_ITER` = 200 iterations (then the
/// iterate of smallest distance). Unlike [`project`] it is not the exact
/// nearest stationary point: far outside a curved cell it may stop at
/// another one, and code_aster's exclusion by `TOLE_PROJ_EXT` depends on
/// where it stops. `None` on a singular iteration (code_aster stops there
/// with APPARIEMENT_13).
pub fn project_mmnewt(kind: SurfaceKind, nodes: &[[f64; 3]], p: [f64; 3]) -> Option<CellPoint> {
    const ITER_MAXI: usize = 200;
    const TOLE: f64 = 1e-4;
    let faces = kind.dim() == 2;
    let curvature = !matches!(kind, SurfaceKind::Quad4 | SurfaceKind::Quad8);
    // ½‖r‖², r = ((p − x(ξ))·t₁, (p − x(ξ))·t₂): mmresi.
    let half_residual = |xi: [f64; 2]| {
        let cp = interpolate(kind, nodes, xi);
        let v = sub(p, cp.x);
        let r1 = dot(v, cp.tangents[0]);
        let r2 = if faces { dot(v, cp.tangents[1]) } else { 0.0 };
        0.5 * (r1 * r1 + r2 * r2)
    };
    let h = 1e-5;
    let mut xi = [0.0, 0.0];
    let mut best = (f64::INFINITY, xi);
    // mmnewt keeps the line-search step between iterations (mmreli leaves
    // it unchanged when none of its trials is accepted).
    let mut alpha = 1.0;
    let mut iter = 0;
    loop {
        let cp = interpolate(kind, nodes, xi);
        let v = sub(p, cp.x);
        let dist = norm(v);
        let t = cp.tangents;
        let r = [dot(v, t[0]), if faces { dot(v, t[1]) } else { 0.0 }];
        let mut m = [
            [-dot(t[0], t[0]), -dot(t[1], t[0])],
            [-dot(t[0], t[1]), -dot(t[1], t[1])],
        ];
        if curvature {
            // Second derivatives of x(ξ): central differences of the
            // tangents, exact for the (at most quadratic) shape functions.
            for l in 0..kind.dim() {
                let mut a = xi;
                let mut b = xi;
                a[l] += h;
                b[l] -= h;
                let (ta, tb) = (
                    interpolate(kind, nodes, a).tangents,
                    interpolate(kind, nodes, b).tangents,
                );
                for (k, row) in m.iter_mut().enumerate().take(kind.dim()) {
                    let d2 = scale(sub(ta[k], tb[k]), 1.0 / (2.0 * h));
                    row[l] += dot(d2, v);
                }
            }
        }
        let (d1, d2) = if faces {
            let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
            if det == 0.0 {
                return None;
            }
            (
                (m[1][1] * -r[0] - m[0][1] * -r[1]) / det,
                (m[0][0] * -r[1] - m[1][0] * -r[0]) / det,
            )
        } else {
            if m[0][0] == 0.0 {
                return None;
            }
            (-r[0] / m[0][0], 0.0)
        };
        alpha = mmreli(&half_residual, xi, [d1, d2], alpha);
        xi = [xi[0] + alpha * d1, xi[1] + alpha * d2];
        if !(xi[0].is_finite() && xi[1].is_finite()) {
            return None;
        }
        if dist <= best.0 {
            // As mmnewt: the distance before the step, the point after it.
            best = (dist, xi);
        }
        let refe = xi[0] * xi[0] + xi[1] * xi[1];
        let step = (d1 * d1 + d2 * d2).sqrt();
        let (test, tole) = if refe <= TOLE {
            (step, TOLE / 100.0)
        } else {
            (step / refe.sqrt(), TOLE)
        };
        if test > tole && iter < ITER_MAXI {
            iter += 1;
            continue;
        }
        if test > tole {
            xi = best.1;
        }
        break;
    }
    Some(interpolate(kind, nodes, xi))
}

/// Solves the n×n (n ≤ 3) symmetric system `a x = b` by Gaussian
/// elimination with partial pivoting; `None` when singular.
fn solve_small(a: &[[f64; 3]; 3], b: &[f64; 3], n: usize) -> Option<[f64; 3]> {
    let mut m = *a;
    let mut v = *b;
    let scale = (0..n).map(|i| m[i][i].abs()).fold(0.0f64, f64::max);
    if scale == 0.0 {
        return None;
    }
    for c in 0..n {
        let piv = (c..n).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        if m[piv][c].abs() <= 1e-14 * scale {
            return None;
        }
        m.swap(c, piv);
        v.swap(c, piv);
        for r in c + 1..n {
            let f = m[r][c] / m[c][c];
            for k in c..n {
                m[r][k] -= f * m[c][k];
            }
            v[r] -= f * v[c];
        }
    }
    let mut x = [0.0; 3];
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|k| m[c][k] * x[k]).sum();
        x[c] = (v[c] - s) / m[c][c];
    }
    Some(x)
}

/// code_aster's line search of the projection (`mmreli`): Armijo test with
/// ω = 1e-4 on ½‖r‖², a quadratic then two cubic backtracks, each step
/// kept within [0.1, 0.5] of the previous; `previous` when none passes.
fn mmreli(g: &dyn Fn([f64; 2]) -> f64, xi: [f64; 2], d: [f64; 2], previous: f64) -> f64 {
    const OMEGA: f64 = 1e-4;
    const AMIN: f64 = 0.1;
    const AMAX: f64 = 0.5;
    let at = |a: f64| g([xi[0] + a * d[0], xi[1] + a * d[1]]);
    let g0 = g(xi);
    let gp0 = -2.0 * g0;
    let mut alpha1 = 1.0;
    let ga1 = at(alpha1);
    if ga1 <= g0 + OMEGA * gp0 {
        return alpha1;
    }
    let mut res1 = ga1 - g0 - gp0 * alpha1;
    let mut alpha2 = (-gp0 / (2.0 * res1)).clamp(AMIN * alpha1, AMAX * alpha1);
    let ga2 = at(alpha2);
    if ga2 <= g0 + OMEGA * gp0 * alpha2 {
        return alpha2;
    }
    let mut res2 = ga2 - g0 - gp0 * alpha2;
    for _ in 0..2 {
        let unsdet = 1.0 / (alpha1 - alpha2);
        let a = unsdet * (res1 / (alpha1 * alpha1) - res2 / (alpha2 * alpha2));
        let b = unsdet * (-alpha2 * res1 / (alpha1 * alpha1) + alpha1 * res2 / (alpha2 * alpha2));
        alpha1 = alpha2;
        res1 = res2;
        if a.abs() <= f64::EPSILON {
            return alpha2;
        }
        alpha2 = (-b + (b * b - 3.0 * a * gp0).sqrt()) / (3.0 * a);
        if alpha2 < AMIN * alpha1 {
            alpha2 = AMIN * alpha1;
        }
        if alpha2 > AMAX * alpha1 {
            alpha2 = AMAX * alpha1;
        }
        let ga2 = at(alpha2);
        if ga2 <= g0 + OMEGA * gp0 * alpha2 {
            return alpha2;
        }
        res2 = ga2 - g0 - gp0 * alpha2;
    }
    previous
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_along_a_direction_hits_the_cell_on_that_line() {
        // A tilted segment from (0,0) to (2,1); from p = (1.5, 3) straight
        // down (0,-1) it is hit at x = 1.5, y = 0.75 (ξ = 0.5).
        let seg = [[0.0, 0.0, 0.0], [2.0, 1.0, 0.0]];
        let cp = project_along(SurfaceKind::Seg2, &seg, [1.5, 3.0, 0.0], [0.0, -1.0, 0.0]).unwrap();
        assert!(
            (cp.x[0] - 1.5).abs() < 1e-12 && (cp.x[1] - 0.75).abs() < 1e-12,
            "{:?}",
            cp.x
        );
        assert!((cp.xi[0] - 0.5).abs() < 1e-12);
        // The orthogonal projection lands elsewhere.
        let o = project(SurfaceKind::Seg2, &seg, [1.5, 3.0, 0.0]).unwrap();
        assert!((o.x[0] - 1.5).abs() > 0.1);
        // A curved QUAD8 face z = 0.1 (1 − x²) hit vertically at (0.3, −0.2).
        let mut q8 = vec![];
        for (x, y) in [
            (-1.0, -1.0),
            (1.0, -1.0),
            (1.0, 1.0),
            (-1.0, 1.0),
            (0.0, -1.0),
            (1.0, 0.0),
            (0.0, 1.0),
            (-1.0, 0.0),
        ] {
            q8.push([x, y, 0.1 * (1.0 - x * x)]);
        }
        let cp =
            project_along(SurfaceKind::Quad8, &q8, [0.3, -0.2, 5.0], [0.0, 0.0, -1.0]).unwrap();
        assert!(
            (cp.x[0] - 0.3).abs() < 1e-12 && (cp.x[1] + 0.2).abs() < 1e-12,
            "{:?}",
            cp.x
        );
        assert!((cp.x[2] - 0.1 * (1.0 - 0.09)).abs() < 1e-12);
        // Parallel to the segment: no hit.
        assert!(project_along(SurfaceKind::Seg2, &seg, [1.5, 3.0, 0.0], [2.0, 1.0, 0.0]).is_none());
    }

    const KINDS: [SurfaceKind; 8] = [
        SurfaceKind::Seg2,
        SurfaceKind::Seg3,
        SurfaceKind::Tria3,
        SurfaceKind::Tria6,
        SurfaceKind::Tria7,
        SurfaceKind::Quad4,
        SurfaceKind::Quad8,
        SurfaceKind::Quad9,
    ];

    #[test]
    fn shape_functions_are_nodal_and_partition_unity() {
        for k in KINDS {
            let nodes = k.node_coords();
            for (i, xi) in nodes.iter().enumerate() {
                let (n, _) = k.eval(*xi);
                for (j, v) in n.iter().enumerate() {
                    let expected = if i == j { 1.0 } else { 0.0 };
                    assert!((v - expected).abs() < 1e-14, "{k:?} N{j} at node {i} = {v}");
                }
            }
            let (n, d) = k.eval([0.21, 0.13]);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            let s: [f64; 2] = d.iter().fold([0.0, 0.0], |a, v| [a[0] + v[0], a[1] + v[1]]);
            assert!(s[0].abs() < 1e-14 && s[1].abs() < 1e-14, "{k:?} {s:?}");
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let h = 1e-6;
        for k in KINDS {
            let xi = [0.23, 0.17];
            let (_, d) = k.eval(xi);
            for dir in 0..k.dim() {
                let mut p = xi;
                let mut m = xi;
                p[dir] += h;
                m[dir] -= h;
                let (np, _) = k.eval(p);
                let (nm, _) = k.eval(m);
                for j in 0..np.len() {
                    let fd = (np[j] - nm[j]) / (2.0 * h);
                    assert!(
                        (fd - d[j][dir]).abs() < 1e-8,
                        "{k:?} dN{j}/d{dir}: {fd} vs {}",
                        d[j][dir]
                    );
                }
            }
        }
    }

    #[test]
    fn projection_onto_curved_seg3_is_orthogonal() {
        // Arc-like SEG3: ends (-1,0), (1,0), middle (0,0.5).
        let nodes = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.5, 0.0]];
        let p = [0.4, 2.0, 0.0];
        let cp = project(SurfaceKind::Seg3, &nodes, p).unwrap();
        let r = sub(p, cp.x);
        assert!(dot(r, cp.tangents[0]).abs() < 1e-10);
    }

    #[test]
    fn projection_onto_warped_quad4() {
        let nodes = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.1],
            [2.0, 1.0, -0.1],
            [0.0, 1.0, 0.2],
        ];
        let p = [1.3, 0.4, 3.0];
        let cp = project(SurfaceKind::Quad4, &nodes, p).unwrap();
        let r = sub(p, cp.x);
        assert!(dot(r, cp.tangents[0]).abs() < 1e-10);
        assert!(dot(r, cp.tangents[1]).abs() < 1e-10);
        assert_eq!(SurfaceKind::Quad4.outside_distance(cp.xi), 0.0);
    }

    #[test]
    fn pressure_functions_have_positive_nodal_measures() {
        // ∫ over the reference cell of each node's pressure function: the
        // weight of the node's contact row must be positive for the nodes
        // that carry a pressure.
        for k in KINDS {
            let pts = crate::integration::gauss(k, 6);
            let mut w = vec![0.0; k.node_count()];
            for (xi, wt) in pts {
                for (i, v) in k.pressure_eval(xi).iter().enumerate() {
                    w[i] += wt * v;
                }
            }
            for i in 0..k.node_count() {
                let carries = k.pressure_support(i) == vec![i];
                if carries {
                    assert!(w[i] > 0.0, "{k:?} node {i}: {}", w[i]);
                } else {
                    assert_eq!(w[i], 0.0, "{k:?} node {i}");
                }
            }
        }
        assert_eq!(SurfaceKind::Tria6.pressure_support(4), vec![1, 2]);
        assert_eq!(SurfaceKind::Quad8.pressure_support(7), vec![3, 0]);
        assert_eq!(SurfaceKind::Quad9.pressure_support(8), vec![0, 1, 2, 3]);
        assert_eq!(SurfaceKind::Seg3.pressure_support(2), vec![2]);
    }

    fn integrate(rule: &[([f64; 2], f64)], f: impl Fn(f64, f64) -> f64) -> f64 {
        rule.iter().map(|(p, w)| w * f(p[0], p[1])).sum()
    }

    #[test]
    fn face_simpson_matches_code_aster_weights() {
        // One subdivision on a triangle: vertices 1/30, mid-edges 4/30.
        let r = face_simpson(SurfaceKind::Tria6, 1).unwrap();
        assert_eq!(r.len(), 6);
        for (p, w) in &r {
            let vertex = (p[0] == 0.0 || p[0] == 1.0) && (p[1] == 0.0 || p[1] == 1.0);
            let want = if vertex { 1.0 / 30.0 } else { 4.0 / 30.0 };
            assert!((w - want).abs() < 1e-15, "{p:?}");
        }
        for p in 1..=4 {
            let t = face_simpson(SurfaceKind::Tria3, p).unwrap();
            assert_eq!(t.len(), (2 * p as usize + 1) * (2 * p as usize + 2) / 2);
            assert!((integrate(&t, |_, _| 1.0) - 0.5).abs() < 1e-14);
            assert!((integrate(&t, |x, y| x + 2.0 * y) - 0.5).abs() < 1e-14);
            let q = face_simpson(SurfaceKind::Quad8, p).unwrap();
            assert!((integrate(&q, |_, _| 1.0) - 4.0).abs() < 1e-14);
            // Simpson is exact for cubics in each direction.
            assert!((integrate(&q, |x, y| x * x * y * y) - 4.0 / 9.0).abs() < 1e-14);
        }
        assert!(face_simpson(SurfaceKind::Seg3, 1).is_none());
    }

    #[test]
    fn face_newton_cotes_matches_code_aster_weights() {
        // Degree 3 on the triangle (mmgaus): vertices 1/60, edge points
        // 3/80, centre 9/40.
        let r = face_newton_cotes(SurfaceKind::Tria3, 3).unwrap();
        assert_eq!(r.len(), 10);
        for (p, w) in &r {
            let want = if (p[0] - 1.0 / 3.0).abs() < 1e-12 && (p[1] - 1.0 / 3.0).abs() < 1e-12 {
                9.0 / 40.0
            } else if [p[0], p[1], 1.0 - p[0] - p[1]]
                .iter()
                .filter(|v| v.abs() < 1e-12)
                .count()
                == 2
            {
                1.0 / 60.0
            } else {
                3.0 / 80.0
            };
            assert!((w - want).abs() < 1e-13, "{p:?}: {w}");
        }
        for n in 1..=8u8 {
            let t = face_newton_cotes(SurfaceKind::Tria6, n).unwrap();
            let d = n as i32;
            // ∫ x^d over the unit triangle = d! / (d + 2)! = 1/((d+1)(d+2)).
            let want = 1.0 / f64::from((d + 1) * (d + 2));
            assert!(
                (integrate(&t, |x, _| x.powi(d)) - want).abs() < 1e-10,
                "{n}"
            );
            let q = face_newton_cotes(SurfaceKind::Quad4, n).unwrap();
            assert!((integrate(&q, |_, _| 1.0) - 4.0).abs() < 1e-12, "{n}");
        }
    }

    #[test]
    fn clamp_triangle_outside() {
        let k = SurfaceKind::Tria3;
        assert_eq!(k.clamp([2.0, 0.0]), [1.0, 0.0]);
        assert!((k.outside_distance([1.0, 1.0]) - (0.5f64).sqrt()).abs() < 1e-14);
        assert_eq!(k.outside_distance([0.2, 0.2]), 0.0);
    }

    #[test]
    fn mmnewt_projection_agrees_with_the_exact_one_inside_a_curved_cell() {
        // A SEG3 arc and points above it: code_aster's iteration stops at
        // a relative step of 1e-4, after which Newton's quadratic
        // convergence leaves it far below that.
        let nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.3, 0.0]];
        for p in [[0.4, 1.0, 0.0], [1.3, 0.8, 0.0], [1.9, 0.5, 0.0]] {
            let a = project(SurfaceKind::Seg3, &nodes, p).unwrap();
            let b = project_mmnewt(SurfaceKind::Seg3, &nodes, p).unwrap();
            assert!((a.xi[0] - b.xi[0]).abs() < 1e-8, "{:?} {:?}", a.xi, b.xi);
        }
        // Affine QUAD4 (Gauss-Newton there): exact in one step.
        let quad = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let b = project_mmnewt(SurfaceKind::Quad4, &quad, [1.5, 0.25, 3.0]).unwrap();
        assert!((b.xi[0] - 0.5).abs() < 1e-12 && (b.xi[1] + 0.5).abs() < 1e-12);
    }
}
