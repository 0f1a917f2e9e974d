//! A-posteriori error estimator in residual (`ERME_ELEM`), as code_aster's
//! `CALC_ERREUR` computes it: te0377 (plane and axisymmetric cells), te0375
//! (3D cells), with their helpers `ermev2`/`ermev3` (the interior residual
//! div σ + f and the norm of σ), `ermes2`/`ermes3` (the jump of σ·n across a
//! face, from the neighbour's nodal stresses), `ermeb2`/`ermeb3` (the
//! boundary residual against the imposed traction), `calnor` (normals and
//! Jacobians at a face's nodes), `intenc`/`intega` (Newton–Cotes rules on
//! the nodes of a face), `uthk` (the cell's and the face's diameter) and
//! `resvoi` (the neighbours: the model's cells that hold every vertex of a
//! face).
//!
//! The stresses are the cell's nodal stresses (`SIGM_ELNO`), interpolated
//! with the shape functions: the residual σ_h is the smoothed field, not the
//! Gauss-point one. Per cell K of diameter h_K (its longest edge or
//! diagonal):
//!
//! - plane and axisymmetric (energy norm, `typnor='NRJ'`):
//!   η_K² = (h_K² ‖div σ + f‖²_K + ½ Σ_interior h_F ‖[σ·n]‖²_F
//!   \+ Σ_loaded h_F ‖g − σ·n‖²_F) / C, C = 24 E/(1 − ν) for linear cells,
//!   96 E/(1 − ν) for quadratic ones (E, ν of the cell);
//! - 3D (`H1` form): η_K = (h_K ‖div σ + f‖_K + ½ Σ √h_F ‖[σ·n]‖_F
//!   \+ Σ √h_F ‖g − σ·n‖_F) / √24 (√96 quadratic).
//!
//! `NUEST` = 100 √(η²/(η² + ‖σ‖²_K)) (‖σ‖² = Σ σᵢⱼ² in 3D, without the
//! shear doubling in 2D: `ermev2` sums σxx² σyy² σzz² σxy²) and `SIGCAL` =
//! ‖σ‖_K; each term alone (`TERMRE` interior, `TERMNO` boundary, `TERMSA`
//! jumps) with its relative value, and `TAILLE` = h_K.
//!
//! code_aster's details kept: the face integrals use the nodes as points
//! (2D: weights 1, 1 on linear edges, 1/3, 1/3, 4/3 on quadratic ones; 3D:
//! the `NOEU` family, the reference face's measure over its nodes); the
//! boundary term counts only faces whose neighbour is a skin cell of the
//! model carrying a non-zero load — an unloaded or free face contributes
//! nothing; in 2D pressures take precedence over forces as soon as the
//! loads hold a pressure anywhere (`ermeb2` reads the pressure map first),
//! in 3D a cell's force over its pressure; the mid-node of the neighbour's
//! edge in 2D is its node `nbsv + jnov` (`ermes2`), and the normal of a
//! 2D edge takes the orientation of the cell's last Gauss point (`utjac`).

use crate::{ElementKind, FemError, Hypothesis, Model};
use aster_mesh::{CellId, CellType, NodeId};
use std::collections::{BTreeMap, HashMap};

/// The imposed traction on a skin cell (constant over it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkinLoad {
    /// A force per unit length (2D) or area (3D), global components.
    Force([f64; 3]),
    /// A pressure: traction −p n.
    Pressure(f64),
}

/// What the estimator reads besides the model.
#[derive(Clone, Debug, Default)]
pub struct EstimatorInput {
    /// Per continuum cell, its nodal stresses SIXX SIYY SIZZ SIXY SIXZ SIYZ
    /// in the cell's node order (`SIGM_ELNO`).
    pub stress: BTreeMap<CellId, Vec<[f64; 6]>>,
    /// Per continuum cell, the force per unit volume (gravity ρ g and
    /// `FORCE_INTERNE`), constant over the cell.
    pub volume_force: BTreeMap<CellId, [f64; 3]>,
    /// Per skin cell of the model, the forces applied on it.
    pub skin_forces: BTreeMap<CellId, [f64; 3]>,
    /// Per skin cell of the model, the pressure applied on it.
    pub skin_pressures: BTreeMap<CellId, f64>,
}

/// The `ERME_ELEM` components of one cell, in code_aster's order.
pub const COMPONENTS: [&str; 10] = [
    "ERREST", "NUEST", "SIGCAL", "TERMRE", "TERMR2", "TERMNO", "TERMN2", "TERMSA", "TERMS2",
    "TAILLE",
];

/// code_aster's `r8prem`.
const R8PREM: f64 = f64::EPSILON;

/// The residual estimator on every continuum cell of the model
/// ([`COMPONENTS`] per cell, ascending cells).
pub fn residual_estimate(
    model: &Model,
    input: &EstimatorInput,
) -> Result<Vec<(CellId, [f64; 10])>, FemError> {
    let mesh = model.mesh();
    // The cells of the model (code_aster's ligrel) by node: the neighbour
    // candidates of `resvoi` (the 3D models' edge cells hold no face).
    let in_model: Vec<CellId> = model.elements().iter().map(|e| e.cell).collect();
    let mut by_node: HashMap<NodeId, Vec<CellId>> = HashMap::new();
    for &c in &in_model {
        for &n in &mesh.cell(c).nodes {
            by_node.entry(n).or_default().push(c);
        }
    }
    for v in by_node.values_mut() {
        v.sort();
        v.dedup();
    }
    let pressure_first = !input.skin_pressures.is_empty();
    let mut out = Vec::new();
    for el in model.elements() {
        let ElementKind::Continuum {
            hypothesis,
            material,
        } = &el.kind
        else {
            continue;
        };
        let cell = el.cell;
        let c = mesh.cell(cell);
        let name = || model.cell_name(cell);
        let sig = input.stress.get(&cell).ok_or_else(|| {
            FemError::Model(format!("cell {} has no nodal stresses (SIGM_ELNO)", name()))
        })?;
        if sig.len() != c.nodes.len() {
            return Err(FemError::Model(format!(
                "cell {}: {} nodal stresses for {} nodes",
                name(),
                sig.len(),
                c.nodes.len()
            )));
        }
        let f = input.volume_force.get(&cell).copied().unwrap_or([0.0; 3]);
        let scheme = if model.is_stabilised(cell) {
            // MECA_HEXS8: RIGI=FPG1.
            vec![crate::shape::GaussPoint {
                xi: [0.0; 3],
                weight: 8.0,
            }]
        } else {
            model.stiffness_scheme(cell)
        };
        let neighbours = neighbours(mesh, cell, &by_node)?;
        let values = if *hypothesis == Hypothesis::Solid3D {
            cell_3d(model, cell, sig, f, &scheme, &neighbours, input)?
        } else {
            if !(material.e.is_finite() && material.nu.is_finite()) {
                return Err(FemError::Model(format!(
                    "cell {}: the energy norm of te0377 needs an isotropic ELAS (E, NU)",
                    name()
                )));
            }
            cell_2d(
                model,
                cell,
                *hypothesis == Hypothesis::Axisymmetric,
                (material.e, material.nu),
                sig,
                f,
                &scheme,
                &neighbours,
                input,
                pressure_first,
            )?
        };
        out.push((cell, values));
    }
    out.sort_by_key(|(c, _)| *c);
    Ok(out)
}

/// The vertices (0-based) of each face of a cell, as `resvoi` numbers the
/// faces: 2D edge i from vertex i to i + 1; 3D its `som` table.
fn face_vertices(ty: CellType) -> Option<Vec<Vec<usize>>> {
    use CellType::*;
    let v: Vec<Vec<usize>> = match ty {
        TRIA3 | TRIA6 | TRIA7 => vec![vec![0, 1], vec![1, 2], vec![2, 0]],
        QUAD4 | QUAD8 | QUAD9 => vec![vec![0, 1], vec![1, 2], vec![2, 3], vec![3, 0]],
        HEXA8 | HEXA20 | HEXA27 => vec![
            vec![0, 1, 2, 3],
            vec![0, 4, 5, 1],
            vec![1, 5, 6, 2],
            vec![2, 6, 7, 3],
            vec![3, 7, 4, 0],
            vec![4, 7, 6, 5],
        ],
        PENTA6 | PENTA15 | PENTA18 => vec![
            vec![0, 1, 2],
            vec![3, 5, 4],
            vec![0, 3, 4, 1],
            vec![1, 4, 5, 2],
            vec![0, 2, 5, 3],
        ],
        TETRA4 | TETRA10 => vec![vec![0, 1, 2], vec![1, 3, 2], vec![2, 3, 0], vec![0, 3, 1]],
        PYRAM5 | PYRAM13 => vec![
            vec![0, 4, 1],
            vec![1, 4, 2],
            vec![2, 4, 3],
            vec![3, 4, 0],
            vec![0, 1, 2, 3],
        ],
        _ => return None,
    };
    Some(v)
}

/// `resvoi`: per face, the one model cell other than `cell` that holds all
/// its vertices (`None`: a free face). Two such cells: code_aster stops
/// (INDICATEUR_12), so does this.
fn neighbours(
    mesh: &aster_mesh::Mesh,
    cell: CellId,
    by_node: &HashMap<NodeId, Vec<CellId>>,
) -> Result<Vec<Option<CellId>>, FemError> {
    let c = mesh.cell(cell);
    let faces = face_vertices(c.ty).ok_or_else(|| {
        FemError::Model(format!(
            "cell {} ({}): no residual estimator for this cell type",
            mesh.cell_name(cell),
            c.ty.name()
        ))
    })?;
    let mut out = Vec::new();
    for f in faces {
        let nodes: Vec<NodeId> = f.iter().map(|&i| c.nodes[i]).collect();
        let empty = Vec::new();
        let first = by_node.get(&nodes[0]).unwrap_or(&empty);
        let found: Vec<CellId> = first
            .iter()
            .copied()
            .filter(|&m| m != cell)
            .filter(|&m| {
                nodes[1..]
                    .iter()
                    .all(|n| by_node.get(n).is_some_and(|v| v.binary_search(&m).is_ok()))
            })
            .collect();
        if found.len() > 1 {
            return Err(FemError::Model(format!(
                "cell {}: a face has {} neighbours in the model (code_aster's INDICATEUR_12: the estimator needs at most one)",
                mesh.cell_name(cell),
                found.len()
            )));
        }
        out.push(found.first().copied());
    }
    Ok(out)
}

/// `uthk` on 2D cells: the longest edge of a triangle, the longest edge or
/// diagonal of a quadrangle.
fn diameter_2d(ty: CellType, x: &[[f64; 3]]) -> f64 {
    let d = |a: usize, b: usize| (x[a][0] - x[b][0]).powi(2) + (x[a][1] - x[b][1]).powi(2);
    let pairs: &[(usize, usize)] =
        if matches!(ty, CellType::TRIA3 | CellType::TRIA6 | CellType::TRIA7) {
            &[(1, 0), (2, 1), (0, 2)]
        } else {
            &[(0, 2), (1, 3), (0, 1), (0, 3), (1, 2), (2, 3)]
        };
    pairs
        .iter()
        .map(|&(a, b)| d(a, b))
        .fold(f64::MIN, f64::max)
        .sqrt()
}

/// `uthk` on 3D cells and faces (0-based corner pairs).
fn diameter_3d(ty: CellType, x: &[[f64; 3]]) -> f64 {
    use CellType::*;
    let d = |a: usize, b: usize| (0..3).map(|k| (x[a][k] - x[b][k]).powi(2)).sum::<f64>();
    let pairs: &[(usize, usize)] = match ty {
        TETRA4 | TETRA10 => &[(1, 0), (2, 0), (3, 0), (2, 1), (3, 1), (3, 2)],
        HEXA8 | HEXA20 | HEXA27 => &[
            (0, 6),
            (1, 7),
            (2, 4),
            (3, 5),
            (0, 2),
            (1, 3),
            (2, 7),
            (6, 3),
            (4, 6),
            (5, 7),
            (4, 1),
            (5, 0),
            (5, 2),
            (6, 1),
            (4, 3),
            (0, 7),
            (1, 2),
            (1, 5),
            (2, 6),
            (5, 6),
            (4, 5),
            (6, 7),
            (3, 2),
            (1, 0),
            (0, 3),
            (3, 7),
            (0, 4),
            (4, 7),
        ],
        PENTA6 | PENTA15 | PENTA18 => &[
            (0, 5),
            (2, 3),
            (1, 3),
            (0, 4),
            (1, 5),
            (2, 4),
            (3, 4),
            (4, 5),
            (5, 3),
            (5, 2),
            (3, 0),
            (4, 1),
            (0, 2),
            (2, 1),
            (1, 0),
        ],
        PYRAM5 | PYRAM13 => &[
            (0, 2),
            (1, 3),
            (1, 0),
            (2, 1),
            (3, 2),
            (0, 3),
            (4, 0),
            (4, 1),
            (4, 2),
            (4, 3),
        ],
        // Faces: FQ (4 corners), FT (3).
        QUAD4 | QUAD8 | QUAD9 => &[(0, 2), (1, 3), (0, 1), (0, 3), (1, 2), (2, 3)],
        _ => &[(1, 0), (2, 1), (0, 2)],
    };
    pairs
        .iter()
        .map(|&(a, b)| d(a, b))
        .fold(f64::MIN, f64::max)
        .sqrt()
}

/// The Jacobian matrix rows ∂x/∂ξₖ and the physical derivatives of the
/// shape functions at a point (`dfdm2d`/`dfdm3d`), with |det J|.
#[allow(clippy::type_complexity)]
fn derivatives(
    ty: CellType,
    x: &[[f64; 3]],
    xi: [f64; 3],
    dim: usize,
) -> Result<(Vec<f64>, Vec<[f64; 3]>, f64, f64), FemError> {
    let s = crate::shape::shape(ty, xi);
    let mut j = [[0.0; 3]; 3];
    for (i, dn) in s.dn.iter().enumerate() {
        for a in 0..dim {
            for b in 0..dim {
                j[a][b] += dn[a] * x[i][b];
            }
        }
    }
    let (det, inv) = if dim == 2 {
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let inv = [
            [j[1][1] / det, -j[0][1] / det, 0.0],
            [-j[1][0] / det, j[0][0] / det, 0.0],
            [0.0; 3],
        ];
        (det, inv)
    } else {
        let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
            - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
            + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
        let mut inv = [[0.0; 3]; 3];
        for a in 0..3 {
            for b in 0..3 {
                let (a1, a2) = ((b + 1) % 3, (b + 2) % 3);
                let (b1, b2) = ((a + 1) % 3, (a + 2) % 3);
                inv[a][b] = (j[a1][b1] * j[a2][b2] - j[a1][b2] * j[a2][b1]) / det;
            }
        }
        (det, inv)
    };
    if !(det.is_finite() && det != 0.0) {
        return Err(FemError::Model("degenerate cell (zero Jacobian)".into()));
    }
    // dN/dx_b = Σ_a (J⁻¹)_{b a} dN/dξ_a.
    let d: Vec<[f64; 3]> =
        s.dn.iter()
            .map(|dn| {
                let mut g = [0.0; 3];
                for b in 0..dim {
                    for a in 0..dim {
                        g[b] += inv[b][a] * dn[a];
                    }
                }
                g
            })
            .collect();
    Ok((s.n, d, det.abs(), det.signum()))
}

fn relative(e: f64, norsig: f64, strict: bool) -> f64 {
    let s = e * e + norsig;
    let nonzero = if strict { s.abs() > R8PREM } else { s != 0.0 };
    if nonzero {
        100.0 * (e * e / s).sqrt()
    } else {
        0.0
    }
}

fn is_solid(ty: CellType) -> bool {
    ty.dim() == 3
}

fn is_plane(ty: CellType) -> bool {
    matches!(
        ty,
        CellType::TRIA3
            | CellType::TRIA6
            | CellType::TRIA7
            | CellType::QUAD4
            | CellType::QUAD8
            | CellType::QUAD9
    )
}

/// te0377 on one plane or axisymmetric cell.
#[allow(clippy::too_many_arguments)]
fn cell_2d(
    model: &Model,
    cell: CellId,
    axis: bool,
    (e, nu): (f64, f64),
    sig: &[[f64; 6]],
    f: [f64; 3],
    scheme: &[crate::shape::GaussPoint],
    neighbours: &[Option<CellId>],
    input: &EstimatorInput,
    pressure_first: bool,
) -> Result<[f64; 10], FemError> {
    let mesh = model.mesh();
    let c = mesh.cell(cell);
    let x: Vec<[f64; 3]> = c.nodes.iter().map(|&n| mesh.coord(n)).collect();
    let hk = diameter_2d(c.ty, &x);
    let nbs = if matches!(c.ty, CellType::TRIA3 | CellType::TRIA6 | CellType::TRIA7) {
        3
    } else {
        4
    };
    let quadratic = !matches!(c.ty, CellType::TRIA3 | CellType::QUAD4);
    let cell_err = |m: String| FemError::Model(format!("cell {}: {m}", model.cell_name(cell)));
    // 2.5: the interior residual and the norm of σ.
    let (mut ter1, mut norsig, mut orien) = (0.0, 0.0, 1.0);
    for gp in scheme {
        let (n, d, det, sign) =
            derivatives(c.ty, &x, gp.xi, 2).map_err(|e| cell_err(e.to_string()))?;
        orien = sign;
        let mut poids = det * gp.weight;
        let (mut d11, mut d12, mut d22, mut d21) = (0.0, 0.0, 0.0, 0.0);
        let (mut s11, mut s22, mut s33, mut s12) = (0.0, 0.0, 0.0, 0.0);
        let mut r = 0.0;
        for i in 0..n.len() {
            let s = &sig[i];
            r += x[i][0] * n[i];
            d11 += s[0] * d[i][0];
            d12 += s[3] * d[i][1];
            d22 += s[1] * d[i][1];
            d21 += s[3] * d[i][0];
            s11 += s[0] * n[i];
            s22 += s[1] * n[i];
            s33 += s[2] * n[i];
            s12 += s[3] * n[i];
        }
        let (mut dsx, mut dsy) = (d11 + d12, d21 + d22);
        if axis {
            if r.abs() <= R8PREM {
                return Err(cell_err(
                    "a Gauss point on the axis (r = 0): code_aster's ermev2 stops there".into(),
                ));
            }
            dsx += (s11 - s33) / r;
            dsy += s12 / r;
            poids *= r;
        }
        let (rx, ry) = (f[0] + dsx, f[1] + dsy);
        ter1 += (rx * rx + ry * ry) * poids;
        norsig += (s11 * s11 + s22 * s22 + s33 * s33 + s12 * s12) * poids;
    }
    ter1 *= hk * hk;
    // 3: the faces.
    let (mut ter2, mut ter3) = (0.0, 0.0);
    for (ifa, nb) in neighbours.iter().enumerate() {
        let Some(nb) = *nb else { continue };
        // calnor('2D'): normals, tangents and Jacobians at the edge's nodes.
        let ino = ifa;
        let jno = (ifa + 1) % nbs;
        let (x1, y1, x2, y2) = (x[ino][0], x[ino][1], x[jno][0], x[jno][1]);
        let hf = ((x1 - x2).powi(2) + (y1 - y2).powi(2)).sqrt();
        let nnoa = if quadratic { 3 } else { 2 };
        let (mut x3, mut y3) = ((x1 + x2) * 0.5, (y1 + y2) * 0.5);
        if quadratic {
            let m = nbs + ifa;
            let (xm, ym) = (x[m][0], x[m][1]);
            let ratio = ((xm - x1).powi(2) + (ym - y1).powi(2)).sqrt()
                / ((x2 - x1).powi(2) + (y2 - y1).powi(2)).sqrt();
            if (0.4..=0.6).contains(&ratio) {
                x3 = xm;
                y3 = ym;
            }
        }
        let mut jac = [0.0; 3];
        let mut nx = [0.0; 3];
        let mut ny = [0.0; 3];
        let p1 = (
            -((y2 - y1) * 0.5 - (y1 + y2 - 2.0 * y3)),
            (x2 - x1) * 0.5 - (x1 + x2 - 2.0 * x3),
        );
        let p2 = (
            -((y2 - y1) * 0.5 + (y1 + y2 - 2.0 * y3)),
            (x2 - x1) * 0.5 + (x1 + x2 - 2.0 * x3),
        );
        for (k, (px, py), xr) in [(0, p1, x1), (1, p2, x2)] {
            let l = (px * px + py * py).sqrt();
            jac[k] = if axis { l * xr } else { l };
            nx[k] = -(px * orien) / l;
            ny[k] = -(py * orien) / l;
        }
        if nnoa == 3 {
            jac[2] = hf * 0.5;
            if axis {
                jac[2] *= (x2 + x1) * 0.5;
            }
            nx[2] = -orien * (y1 - y2) / hf;
            ny[2] = -orien * (x2 - x1) / hf;
        }
        let mine: Vec<usize> = if nnoa == 3 {
            vec![ino, jno, nbs + ifa]
        } else {
            vec![ino, jno]
        };
        let nbc = mesh.cell(nb);
        // intenc: Σ w jac ((v − σ·n)²).
        let intenc = |ch: &[[f64; 2]], s: &[[f64; 3]]| {
            let w: &[f64] = if nnoa == 3 {
                &[1.0 / 3.0, 1.0 / 3.0, 4.0 / 3.0]
            } else {
                &[1.0, 1.0]
            };
            (0..nnoa)
                .map(|k| {
                    let [s11, s22, s12] = s[k];
                    w[k] * jac[k]
                        * ((ch[k][0] - s11 * nx[k] - s12 * ny[k]).powi(2)
                            + (ch[k][1] - s12 * nx[k] - s22 * ny[k]).powi(2))
                })
                .sum::<f64>()
        };
        if is_plane(nbc.ty) {
            // ermes2: the jump of σ with the neighbour at the same nodes.
            let sv = input.stress.get(&nb).ok_or_else(|| {
                cell_err(format!(
                    "its neighbour {} has no nodal stresses",
                    model.cell_name(nb)
                ))
            })?;
            let find = |node: NodeId| nbc.nodes.iter().position(|&m| m == node);
            let (Some(inov), Some(jnov)) = (find(c.nodes[ino]), find(c.nodes[jno])) else {
                return Err(cell_err("neighbour without the edge's vertices".into()));
            };
            let nbsv = if matches!(nbc.ty, CellType::TRIA3 | CellType::TRIA6 | CellType::TRIA7) {
                3
            } else {
                4
            };
            let mut theirs = vec![inov, jnov];
            if nnoa == 3 {
                let mnov = nbsv + jnov;
                if mnov >= sv.len() {
                    return Err(cell_err(format!(
                        "its neighbour {} is linear where it is quadratic",
                        model.cell_name(nb)
                    )));
                }
                theirs.push(mnov);
            }
            let jump: Vec<[f64; 3]> = mine
                .iter()
                .zip(&theirs)
                .map(|(&a, &b)| {
                    [
                        sig[a][0] - sv[b][0],
                        sig[a][1] - sv[b][1],
                        sig[a][3] - sv[b][3],
                    ]
                })
                .collect();
            let inte = intenc(&[[0.0; 2]; 3], &jump);
            ter2 += 0.5 * hf * inte;
        } else if matches!(nbc.ty, CellType::SEG2 | CellType::SEG3 | CellType::SEG4) {
            // ermeb2: the traction against σ·n where a load acts.
            let mut ch = [[0.0; 2]; 3];
            let mut loaded = false;
            if pressure_first {
                if let Some(&p) = input.skin_pressures.get(&nb) {
                    if p.abs() > 1e-15 {
                        loaded = true;
                        for k in 0..nnoa {
                            ch[k] = [-p * nx[k], -p * ny[k]];
                        }
                    }
                }
            } else if let Some(&fv) = input.skin_forces.get(&nb) {
                if fv[0].abs() > 1e-15 || fv[1].abs() > 1e-15 {
                    loaded = true;
                    for item in ch.iter_mut().take(nnoa) {
                        *item = [fv[0], fv[1]];
                    }
                }
            }
            let s: Vec<[f64; 3]> = if loaded {
                mine.iter()
                    .map(|&a| [sig[a][0], sig[a][1], sig[a][3]])
                    .collect()
            } else {
                vec![[0.0; 3]; nnoa]
            };
            ter3 += hf * intenc(&ch, &s);
        } else {
            return Err(cell_err(format!(
                "its neighbour {} is a {} (code_aster's INDICATEUR_10)",
                model.cell_name(nb),
                nbc.ty.name()
            )));
        }
    }
    let coeff = ((if quadratic { 96.0 } else { 24.0 }) * e / (1.0 - nu)).sqrt();
    let errest = (ter1 + ter2 + ter3).sqrt() / coeff;
    let mut v = [0.0; 10];
    v[0] = errest;
    v[1] = relative(errest, norsig, true);
    v[2] = norsig.sqrt();
    for (k, t) in [(3, ter1), (5, ter3), (7, ter2)] {
        let e = t.sqrt() / coeff;
        v[k] = e;
        v[k + 1] = relative(e, norsig, true);
    }
    v[9] = hk;
    Ok(v)
}

/// The face nodes (0-based) of a 3D cell in te0375's `noe` order (faces
/// described with an inward orientation; corners, then mid-edge nodes,
/// then the centre), and the face's reference type.
fn face_nodes_3d(ty: CellType, ifa: usize) -> Option<(Vec<usize>, CellType)> {
    use CellType::*;
    let table: &[&[usize]] = match ty {
        HEXA8 | HEXA20 | HEXA27 => &[
            &[1, 4, 3, 2, 12, 11, 10, 9, 21],
            &[1, 2, 6, 5, 9, 14, 17, 13, 22],
            &[2, 3, 7, 6, 10, 15, 18, 14, 23],
            &[3, 4, 8, 7, 11, 16, 19, 15, 24],
            &[4, 1, 5, 8, 12, 13, 20, 16, 25],
            &[5, 6, 7, 8, 17, 18, 19, 20, 26],
        ],
        PENTA6 | PENTA15 | PENTA18 => &[
            &[1, 3, 2, 9, 8, 7],
            &[4, 5, 6, 13, 14, 15],
            &[1, 2, 5, 4, 7, 11, 13, 10, 16],
            &[2, 3, 6, 5, 8, 12, 14, 11, 17],
            &[1, 4, 6, 3, 10, 15, 12, 9, 18],
        ],
        TETRA4 | TETRA10 => &[
            &[1, 3, 2, 7, 6, 5],
            &[2, 3, 4, 6, 10, 9],
            &[3, 1, 4, 7, 8, 10],
            &[1, 2, 4, 5, 9, 8],
        ],
        PYRAM5 | PYRAM13 => &[
            &[1, 2, 5, 6, 11, 10],
            &[2, 3, 5, 7, 12, 11],
            &[3, 4, 5, 8, 13, 12],
            &[4, 1, 5, 9, 10, 13],
            &[1, 4, 3, 2, 9, 8, 7, 6],
        ],
        _ => return None,
    };
    let row = table.get(ifa)?;
    let tri = row.len() == 6;
    let corners = if tri { 3 } else { 4 };
    let (count, fty) = if matches!(ty, TETRA4 | PYRAM5 | PENTA6 | HEXA8) {
        (corners, if tri { TRIA3 } else { QUAD4 })
    } else if !tri && matches!(ty, HEXA27 | PENTA18) {
        (9, QUAD9)
    } else {
        (2 * corners, if tri { TRIA6 } else { QUAD8 })
    };
    Some((row[..count].iter().map(|i| i - 1).collect(), fty))
}

/// te0375 on one 3D cell.
#[allow(clippy::too_many_arguments)]
fn cell_3d(
    model: &Model,
    cell: CellId,
    sig: &[[f64; 6]],
    f: [f64; 3],
    scheme: &[crate::shape::GaussPoint],
    neighbours: &[Option<CellId>],
    input: &EstimatorInput,
) -> Result<[f64; 10], FemError> {
    let mesh = model.mesh();
    let c = mesh.cell(cell);
    let cell_err = |m: String| FemError::Model(format!("cell {}: {m}", model.cell_name(cell)));
    let quadratic = !matches!(
        c.ty,
        CellType::HEXA8 | CellType::PENTA6 | CellType::TETRA4 | CellType::PYRAM5
    );
    let x: Vec<[f64; 3]> = c.nodes.iter().map(|&n| mesh.coord(n)).collect();
    let hk = diameter_3d(c.ty, &x);
    let (mut ter1, mut norsig) = (0.0, 0.0);
    for gp in scheme {
        let (n, d, det, _) =
            derivatives(c.ty, &x, gp.xi, 3).map_err(|e| cell_err(e.to_string()))?;
        let poids = det * gp.weight;
        let mut ds = [0.0; 3];
        let mut sp = [0.0; 6];
        for i in 0..n.len() {
            let s = &sig[i];
            ds[0] += s[0] * d[i][0] + s[3] * d[i][1] + s[4] * d[i][2];
            ds[1] += s[3] * d[i][0] + s[1] * d[i][1] + s[5] * d[i][2];
            ds[2] += s[4] * d[i][0] + s[5] * d[i][1] + s[2] * d[i][2];
            for k in 0..6 {
                sp[k] += s[k] * n[i];
            }
        }
        let r: f64 = (0..3).map(|k| (f[k] + ds[k]).powi(2)).sum();
        ter1 += r * poids;
        norsig += (sp[0] * sp[0]
            + sp[1] * sp[1]
            + sp[2] * sp[2]
            + 2.0 * (sp[3] * sp[3] + sp[4] * sp[4] + sp[5] * sp[5]))
            * poids;
    }
    let ter1 = hk * ter1.sqrt();
    let (mut ter2, mut ter3) = (0.0, 0.0);
    for (ifa, nb) in neighbours.iter().enumerate() {
        let Some(nb) = *nb else { continue };
        let (fnodes, fty) = face_nodes_3d(c.ty, ifa)
            .ok_or_else(|| cell_err("no face table for this cell".into()))?;
        let mut fx: Vec<[f64; 3]> = fnodes.iter().map(|&i| x[i]).collect();
        let hf = diameter_3d(fty, &fx);
        // calnor's Barsoum treatment: a mid-edge node far from the middle
        // of its edge is put back there for the normal.
        if matches!(fty, CellType::TRIA6 | CellType::QUAD8) {
            let m = fx.len() / 2;
            for ino in 0..m {
                let jno = (ino + 1) % m;
                let mno = m + ino;
                let d = |a: [f64; 3], b: [f64; 3]| {
                    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
                };
                let ratio = d(fx[mno], fx[ino]) / d(fx[jno], fx[ino]);
                if !(0.4..=0.6).contains(&ratio) {
                    fx[mno] = std::array::from_fn(|k| 0.5 * (fx[ino][k] + fx[jno][k]));
                }
            }
        }
        // calnor('3D') at the face's nodes (the NOEU family): the normal
        // −(∂x/∂ξ × ∂x/∂η)/|…|, the Jacobian |…|; weights: the reference
        // face's measure over its nodes.
        let refs = crate::shape::reference_nodes(fty);
        let measure = if matches!(fty, CellType::QUAD4 | CellType::QUAD8 | CellType::QUAD9) {
            4.0
        } else {
            0.5
        };
        let weight = measure / refs.len() as f64;
        let mut jac = Vec::new();
        let mut normal = Vec::new();
        for r in &refs {
            let s = crate::shape::shape(fty, *r);
            let mut a = [0.0; 3];
            let mut b = [0.0; 3];
            for (i, dn) in s.dn.iter().enumerate() {
                for k in 0..3 {
                    a[k] += dn[0] * fx[i][k];
                    b[k] += dn[1] * fx[i][k];
                }
            }
            let cr = [
                -(a[1] * b[2] - a[2] * b[1]),
                -(a[2] * b[0] - a[0] * b[2]),
                -(a[0] * b[1] - a[1] * b[0]),
            ];
            let j = (cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]).sqrt();
            if j.is_nan() || j <= 0.0 {
                return Err(cell_err("a degenerate face".into()));
            }
            jac.push(j);
            normal.push([cr[0] / j, cr[1] / j, cr[2] / j]);
        }
        let intega = |ch: &[[f64; 3]], s: &[[f64; 6]]| {
            (0..fnodes.len())
                .map(|k| {
                    let [s11, s22, s33, s12, s13, s23] = s[k];
                    let [nx, ny, nz] = normal[k];
                    ((ch[k][0] - s11 * nx - s12 * ny - s13 * nz).powi(2)
                        + (ch[k][1] - s12 * nx - s22 * ny - s23 * nz).powi(2)
                        + (ch[k][2] - s13 * nx - s23 * ny - s33 * nz).powi(2))
                        * weight
                        * jac[k]
                })
                .sum::<f64>()
        };
        let nbc = mesh.cell(nb);
        if is_solid(nbc.ty) {
            let sv = input.stress.get(&nb).ok_or_else(|| {
                cell_err(format!(
                    "its neighbour {} has no nodal stresses",
                    model.cell_name(nb)
                ))
            })?;
            let mut jump = Vec::new();
            for &i in &fnodes {
                let node = c.nodes[i];
                let Some(v) = nbc.nodes.iter().position(|&m| m == node) else {
                    return Err(cell_err("neighbour without the face's nodes".into()));
                };
                jump.push(std::array::from_fn::<f64, 6, _>(|k| sig[i][k] - sv[v][k]));
            }
            let inte = intega(&vec![[0.0; 3]; fnodes.len()], &jump);
            ter2 += 0.5 * hf.sqrt() * inte.sqrt();
        } else if is_plane(nbc.ty) {
            let force = input
                .skin_forces
                .get(&nb)
                .copied()
                .filter(|v| v.iter().any(|x| x.abs() > 1e-15));
            let pressure = input
                .skin_pressures
                .get(&nb)
                .copied()
                .filter(|p| p.abs() > 1e-15);
            let ch: Vec<[f64; 3]> = (0..fnodes.len())
                .map(|k| match (force, pressure) {
                    (Some(v), _) => v,
                    (None, Some(p)) => normal[k].map(|n| -p * n),
                    (None, None) => [0.0; 3],
                })
                .collect();
            let s: Vec<[f64; 6]> = if force.is_some() || pressure.is_some() {
                fnodes.iter().map(|&i| sig[i]).collect()
            } else {
                vec![[0.0; 6]; fnodes.len()]
            };
            ter3 += hf.sqrt() * intega(&ch, &s).sqrt();
        } else {
            return Err(cell_err(format!(
                "its neighbour {} is a {} (code_aster's INDICATEUR_10)",
                model.cell_name(nb),
                nbc.ty.name()
            )));
        }
    }
    let coeff = (if quadratic { 96.0_f64 } else { 24.0 }).sqrt();
    let errest = (ter1 + ter2 + ter3) / coeff;
    let mut v = [0.0; 10];
    v[0] = errest;
    v[1] = relative(errest, norsig, false);
    v[2] = norsig.sqrt();
    for (k, t) in [(3, ter1), (5, ter3), (7, ter2)] {
        let e = t / coeff;
        v[k] = e;
        v[k + 1] = relative(e, norsig, false);
    }
    v[9] = hk;
    Ok(v)
}
