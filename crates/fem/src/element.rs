//! Element computations: strain-displacement matrices at Gauss points,
//! stiffness matrices, stresses and spring forces.

use crate::error::FemError;
use crate::material::{Elastic, Hypothesis};
use crate::model::{ElementKind, Frame, Model};
use crate::shape::{self, GaussPoint};
use aster_mesh::{CellId, CellType, Mesh};
use nalgebra::{DMatrix, DVector, Matrix2, Matrix3};

/// One Gauss point of a continuum element.
pub struct GaussData {
    /// Strain-displacement matrix (ncomp × element DOFs), engineering shear.
    pub b: DMatrix<f64>,
    /// Integration weight × |det J| (× r in AXIS).
    pub w: f64,
    /// Physical coordinates of the point.
    pub x: [f64; 3],
}

impl GaussData {
    /// The first `n` strain components B·uₑ at the point (engineering
    /// shear), the rest zero.
    pub fn strain(&self, ue: &[f64], n: usize) -> [f64; 6] {
        let mut eps = [0.0; 6];
        for (k, e) in eps.iter_mut().enumerate().take(n) {
            *e = (0..ue.len()).map(|a| self.b[(k, a)] * ue[a]).sum();
        }
        eps
    }
}

/// DOF indices of an element's nodes (node-major: the first
/// [`Model::element_comps`] components of each node).
pub fn element_dofs(model: &Model, cell: CellId) -> Vec<usize> {
    let mut v = Vec::new();
    element_dofs_into(model, cell, &mut v);
    v
}

/// [`element_dofs`] into a reused buffer.
pub fn element_dofs_into(model: &Model, cell: CellId, v: &mut Vec<usize>) {
    let nodes = &model.mesh().cell(cell).nodes;
    let ncomp = model.element_comps(cell);
    for &n in nodes {
        // Every node of a model element is numbered (Model::new).
        let first = model.dofs().node_first(n).unwrap_or(0);
        // A COQUE_3D centre carries its three rotations alone.
        let k = if ncomp == 6 {
            model.dofs().node_comps(n).len().min(6)
        } else {
            ncomp
        };
        v.extend(first..first + k);
    }
}

/// Shape values, physical derivatives, det J and physical coordinates.
type PointData = (Vec<f64>, Vec<[f64; 3]>, f64, [f64; 3]);

/// Jacobian, physical derivatives and |det J| at one reference point.
/// Clockwise cells have det J < 0: derivatives stay exact (J⁻¹ handles the
/// sign) and the measure uses |det J|, as code_aster does.
pub(crate) fn physical_derivatives(
    mesh: &Mesh,
    cell: CellId,
    dim: usize,
    gp: &GaussPoint,
) -> Result<PointData, String> {
    let c = mesh.cell(cell);
    let s = shape::shape(c.ty, gp.xi);
    let mut x = [0.0; 3];
    for (i, &n) in c.nodes.iter().enumerate() {
        let p = mesh.coord(n);
        for k in 0..3 {
            x[k] += s.n[i] * p[k];
        }
    }
    let mut dn = vec![[0.0; 3]; c.nodes.len()];
    let det: f64;
    if dim == 2 {
        let mut j = Matrix2::zeros();
        for (i, &n) in c.nodes.iter().enumerate() {
            let p = mesh.coord(n);
            for a in 0..2 {
                for b in 0..2 {
                    j[(a, b)] += s.dn[i][a] * p[b];
                }
            }
        }
        det = j.determinant();
        let inv = j.try_inverse().ok_or("degenerate (zero Jacobian)")?;
        for i in 0..c.nodes.len() {
            for b in 0..2 {
                dn[i][b] = inv[(b, 0)] * s.dn[i][0] + inv[(b, 1)] * s.dn[i][1];
            }
        }
    } else {
        let mut j = Matrix3::zeros();
        for (i, &n) in c.nodes.iter().enumerate() {
            let p = mesh.coord(n);
            for a in 0..3 {
                for b in 0..3 {
                    j[(a, b)] += s.dn[i][a] * p[b];
                }
            }
        }
        det = j.determinant();
        let inv = j.try_inverse().ok_or("degenerate (zero Jacobian)")?;
        for i in 0..c.nodes.len() {
            for b in 0..3 {
                dn[i][b] = (0..3).map(|a| inv[(b, a)] * s.dn[i][a]).sum();
            }
        }
    }
    if !det.is_finite() || det == 0. {
        return Err("degenerate (zero Jacobian)".into());
    }
    Ok((s.n, dn, det, x))
}

/// Gauss data of a continuum element.
pub fn continuum_gauss(
    mesh: &Mesh,
    cell: CellId,
    hyp: Hypothesis,
) -> Result<Vec<GaussData>, String> {
    let scheme = shape::stiffness_scheme(mesh.cell(cell).ty, Some(hyp));
    continuum_gauss_on(mesh, cell, hyp, &scheme)
}

/// [`continuum_gauss`] with the model's scheme for the cell
/// ([`Model::stiffness_scheme`]: reduced for the `_SI` cells).
pub fn model_gauss(model: &Model, cell: CellId, hyp: Hypothesis) -> Result<Vec<GaussData>, String> {
    continuum_gauss_on(model.mesh(), cell, hyp, &model.stiffness_scheme(cell))
}

/// [`continuum_gauss`] on a given scheme.
fn continuum_gauss_on(
    mesh: &Mesh,
    cell: CellId,
    hyp: Hypothesis,
    scheme: &[GaussPoint],
) -> Result<Vec<GaussData>, String> {
    let c = mesh.cell(cell);
    let dim = hyp.dim();
    let nn = c.nodes.len();
    let ncomp = hyp.ncomp();
    let mut out = Vec::with_capacity(scheme.len());
    let mut sign = 0.0f64;
    for gp in scheme {
        let (n, dn, det, x) = physical_derivatives(mesh, cell, dim, gp)?;
        if sign != 0. && sign * det < 0. {
            return Err("distorted: its Jacobian changes sign inside the cell".into());
        }
        sign = det.signum();
        let mut b = DMatrix::zeros(ncomp, nn * dim);
        let mut w = gp.weight * det.abs();
        if dim == 2 {
            for i in 0..nn {
                let (cx, cy) = (2 * i, 2 * i + 1);
                b[(0, cx)] = dn[i][0];
                b[(1, cy)] = dn[i][1];
                b[(3, cx)] = dn[i][1];
                b[(3, cy)] = dn[i][0];
            }
            if hyp == Hypothesis::Axisymmetric {
                let r = x[0];
                if r <= 0. {
                    return Err(format!(
                        "has a Gauss point at radius {r}: AXIS needs the mesh in x ≥ 0"
                    ));
                }
                for i in 0..nn {
                    b[(2, 2 * i)] = n[i] / r;
                }
                w *= r;
            }
        } else {
            for i in 0..nn {
                let (cx, cy, cz) = (3 * i, 3 * i + 1, 3 * i + 2);
                b[(0, cx)] = dn[i][0];
                b[(1, cy)] = dn[i][1];
                b[(2, cz)] = dn[i][2];
                b[(3, cx)] = dn[i][1];
                b[(3, cy)] = dn[i][0];
                b[(4, cx)] = dn[i][2];
                b[(4, cz)] = dn[i][0];
                b[(5, cy)] = dn[i][2];
                b[(5, cz)] = dn[i][1];
            }
        }
        out.push(GaussData { b, w, x });
    }
    Ok(out)
}

/// Continuum stiffness Σ Bᵀ D B w.
pub fn continuum_stiffness(
    gauss: &[GaussData],
    material: &Elastic,
    hyp: Hypothesis,
) -> DMatrix<f64> {
    let d = material.hooke(hyp);
    let ndof = gauss.first().map(|g| g.b.ncols()).unwrap_or(0);
    let mut k = DMatrix::zeros(ndof, ndof);
    for g in gauss {
        let db = &d * &g.b;
        k.gemm_tr(g.w, &g.b, &db, 1.0);
    }
    k
}

/// Rotation from global to local axes of a SEG2 spring (rows = local axes).
pub(crate) fn spring_rotation(mesh: &Mesh, cell: CellId, dim: usize, frame: Frame) -> DMatrix<f64> {
    if frame == Frame::Global {
        return DMatrix::identity(dim, dim);
    }
    let c = mesh.cell(cell);
    if c.ty != CellType::SEG2 {
        return DMatrix::identity(dim, dim);
    }
    let (a, b) = (mesh.coord(c.nodes[0]), mesh.coord(c.nodes[1]));
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if len == 0. {
        return DMatrix::identity(dim, dim);
    }
    if dim == 2 {
        let (cx, cy) = (d[0] / len, d[1] / len);
        DMatrix::from_row_slice(2, 2, &[cx, cy, -cy, cx])
    } else {
        // Nautical angles α (about Z), β (about the rotated Y), γ = 0.
        let alpha = d[1].atan2(d[0]);
        let beta = -(d[2] / len).clamp(-1., 1.).asin();
        let (sa, ca, sb, cb) = (alpha.sin(), alpha.cos(), beta.sin(), beta.cos());
        DMatrix::from_row_slice(
            3,
            3,
            &[cb * ca, cb * sa, -sb, -sa, ca, 0., sb * ca, sb * sa, cb],
        )
    }
}

/// Global stiffness of a spring element (SEG2: 2·dim, POI1: dim DOFs) and
/// the global→local rotation used for its forces.
pub fn spring_stiffness(
    mesh: &Mesh,
    cell: CellId,
    stiffness: &[f64],
    frame: Frame,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let dim = stiffness.len();
    let r = if dim == 6 {
        // DIS_TR: the same rotation on the translations and the rotations.
        let r3 = spring_rotation(mesh, cell, 3, frame);
        let mut r = DMatrix::zeros(6, 6);
        r.view_mut((0, 0), (3, 3)).copy_from(&r3);
        r.view_mut((3, 3), (3, 3)).copy_from(&r3);
        r
    } else {
        spring_rotation(mesh, cell, dim, frame)
    };
    let kl = DMatrix::from_diagonal(&DVector::from_column_slice(stiffness));
    let kg = r.transpose() * kl * &r;
    let nn = mesh.cell(cell).nodes.len();
    if nn == 1 {
        return (kg, r);
    }
    let mut k = DMatrix::zeros(2 * dim, 2 * dim);
    for i in 0..dim {
        for j in 0..dim {
            let v = kg[(i, j)];
            k[(i, j)] = v;
            k[(dim + i, dim + j)] = v;
            k[(i, dim + j)] = -v;
            k[(dim + i, j)] = -v;
        }
    }
    (k, r)
}

/// Stiffness matrix of any element of the model (None for boundary cells).
pub fn element_stiffness(model: &Model, index: usize) -> Result<Option<DMatrix<f64>>, FemError> {
    let el = &model.elements()[index];
    match &el.kind {
        ElementKind::Continuum {
            hypothesis,
            material,
        } => {
            if model.is_mixed(el.cell) {
                return Err(crate::mixed_upg::refused(
                    model,
                    el.cell,
                    "this computation",
                ));
            }
            let g = model_gauss(model, el.cell, *hypothesis).map_err(|m| {
                FemError::Model(format!("cell {} is {m}", model.cell_name(el.cell)))
            })?;
            Ok(Some(continuum_stiffness(&g, material, *hypothesis)))
        }
        ElementKind::Spring { stiffness, frame } => Ok(Some(
            spring_stiffness(model.mesh(), el.cell, stiffness, *frame).0,
        )),
        ElementKind::Boundary => Ok(None),
        ElementKind::Shell {
            material,
            section,
            theory,
        } => shell_stiffness(model.mesh(), el.cell, material, section, *theory)
            .map(Some)
            .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))),
        ElementKind::Beam { material, section } => {
            beam_stiffness(model.mesh(), el.cell, material, section)
                .map(Some)
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))
        }
        ElementKind::Bar { material, area } => {
            bar_stiffness(model.mesh(), el.cell, material, *area)
                .map(Some)
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))
        }
        ElementKind::Coque3d { material, section } => {
            coque3d_stiffness(model.mesh(), el.cell, material, section)
                .map(Some)
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))
        }
        ElementKind::Grid { material, section } => {
            grid_stiffness(model.mesh(), el.cell, material, section)
                .map(Some)
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))
        }
    }
}

/// The node coordinates of a cell.
pub fn cell_coords(mesh: &Mesh, cell: CellId) -> Vec<[f64; 3]> {
    mesh.cell(cell)
        .nodes
        .iter()
        .map(|&n| mesh.coord(n))
        .collect()
}

/// The global stiffness of a reinforcement grid ([`crate::grid`]).
pub fn grid_stiffness(
    mesh: &Mesh,
    cell: CellId,
    material: &Elastic,
    section: &crate::grid::GridSection,
) -> Result<DMatrix<f64>, String> {
    crate::grid::stiffness(
        mesh.cell(cell).ty,
        &cell_coords(mesh, cell),
        section,
        material.e,
    )
}

/// The edge nodes of a COQUE_3D cell (its geometry: eight on a QUAD9,
/// six on a TRIA7; the centre's position plays no part).
pub fn coque3d_coords(mesh: &Mesh, cell: CellId) -> Result<Vec<[f64; 3]>, String> {
    let c = mesh.cell(cell);
    if !matches!(c.ty, CellType::QUAD9 | CellType::TRIA7) {
        return Err(format!("no COQUE_3D element on a {}", c.ty.name()));
    }
    Ok(c.nodes[..c.nodes.len() - 1]
        .iter()
        .map(|&n| mesh.coord(n))
        .collect())
}

/// The global stiffness of a COQUE_3D cell (DX…DRZ of the edge nodes,
/// then DRX DRY DRZ of the centre: 51×51 on a QUAD9, 39×39 on a TRIA7).
pub fn coque3d_stiffness(
    mesh: &Mesh,
    cell: CellId,
    material: &Elastic,
    section: &crate::coque3d::Coque3dSection,
) -> Result<DMatrix<f64>, String> {
    let xyz = coque3d_coords(mesh, cell)?;
    let k = crate::coque3d::stiffness(&xyz, material, section)?;
    let n = 6 * xyz.len() + 3;
    Ok(DMatrix::from_row_slice(n, n, &k))
}

/// The global stiffness of a beam (`POU_D_E` on SEG2), node-major DX DY
/// DZ DRX DRY DRZ.
pub fn beam_stiffness(
    mesh: &Mesh,
    cell: CellId,
    material: &Elastic,
    section: &crate::beam::BeamSection,
) -> Result<DMatrix<f64>, String> {
    crate::beam::stiffness(&beam_coords(mesh, cell)?, material, section)
}

/// The global stiffness of a bar (`BARRE` on SEG2), node-major DX DY DZ.
pub fn bar_stiffness(
    mesh: &Mesh,
    cell: CellId,
    material: &Elastic,
    area: f64,
) -> Result<DMatrix<f64>, String> {
    crate::bar::stiffness(&beam_coords(mesh, cell)?, material, area)
}

/// The two node coordinates of a beam (or bar) cell.
pub fn beam_coords(mesh: &Mesh, cell: CellId) -> Result<[[f64; 3]; 2], String> {
    let c = mesh.cell(cell);
    if c.ty != CellType::SEG2 {
        return Err(format!("no beam element on a {}", c.ty.name()));
    }
    Ok([mesh.coord(c.nodes[0]), mesh.coord(c.nodes[1])])
}

/// The global stiffness of a plate facet of the family `theory` (on
/// TRIA3 or QUAD4, [`crate::plate::stiffness`]), node-major DX DY DZ DRX
/// DRY DRZ.
pub fn shell_stiffness(
    mesh: &Mesh,
    cell: CellId,
    material: &Elastic,
    section: &crate::dkt::ShellSection,
    theory: crate::plate::PlateTheory,
) -> Result<DMatrix<f64>, String> {
    let c = mesh.cell(cell);
    match c.ty {
        CellType::TRIA3 | CellType::QUAD4 => {
            let xyz: Vec<[f64; 3]> = c.nodes.iter().map(|&n| mesh.coord(n)).collect();
            crate::plate::stiffness(theory, &xyz, material, section)
        }
        ty => Err(format!("no shell element on a {}", ty.name())),
    }
}

/// Shape data of a cell type at its stiffness Gauss points, computed once
/// per assembly instead of once per element.
pub struct RefData {
    pub ty: CellType,
    pub hyp: Hypothesis,
    pub weights: Vec<f64>,
    pub n: Vec<Vec<f64>>,
    pub dn: Vec<Vec<[f64; 3]>>,
}

impl RefData {
    pub fn new(ty: CellType, hyp: Hypothesis) -> RefData {
        let scheme = shape::stiffness_scheme(ty, Some(hyp));
        let mut n = Vec::with_capacity(scheme.len());
        let mut dn = Vec::with_capacity(scheme.len());
        for gp in &scheme {
            let s = shape::shape(ty, gp.xi);
            n.push(s.n);
            dn.push(s.dn);
        }
        RefData {
            ty,
            hyp,
            weights: scheme.iter().map(|g| g.weight).collect(),
            n,
            dn,
        }
    }
}

/// Largest element: HEXA27 with 81 DOFs.
pub const MAX_EL_DOFS: usize = 81;

/// Most nodes of a continuum cell (HEXA27).
const MAX_EL_NODES: usize = 27;

/// Allocation-free continuum stiffness into `out` (row-major, ndof×ndof),
/// for the hot assembly loop. Same formulation as [`continuum_stiffness`].
pub fn continuum_stiffness_fast(
    mesh: &Mesh,
    nodes: &[aster_mesh::NodeId],
    rd: &RefData,
    hyp: Hypothesis,
    d: &[[f64; 6]; 6],
    out: &mut [f64],
) -> Result<usize, String> {
    // Stack buffers sized for the element: the linear cells (≤ 24 DOFs)
    // keep the small ones they had before the quadratic 3D families.
    if nodes.len() * hyp.dim() <= 24 {
        stiffness_fast::<24>(mesh, nodes, rd, hyp, d, out)
    } else {
        stiffness_fast::<MAX_EL_DOFS>(mesh, nodes, rd, hyp, d, out)
    }
}

fn stiffness_fast<const N: usize>(
    mesh: &Mesh,
    nodes: &[aster_mesh::NodeId],
    rd: &RefData,
    hyp: Hypothesis,
    d: &[[f64; 6]; 6],
    out: &mut [f64],
) -> Result<usize, String> {
    let dim = hyp.dim();
    let nn = nodes.len();
    let ndof = nn * dim;
    let ncomp = hyp.ncomp();
    out[..ndof * ndof].iter_mut().for_each(|v| *v = 0.);
    let mut xs = [[0.0f64; 3]; MAX_EL_NODES];
    for (i, &n) in nodes.iter().enumerate() {
        xs[i] = mesh.coord(n);
    }
    let mut sign = 0.0f64;
    let mut b = [[0.0f64; N]; 6];
    let mut db = [[0.0f64; N]; 6];
    for (g, &wref) in rd.weights.iter().enumerate() {
        let dnr = &rd.dn[g];
        let mut j = [[0.0f64; 3]; 3];
        for i in 0..nn {
            for a in 0..dim {
                for c in 0..dim {
                    j[a][c] += dnr[i][a] * xs[i][c];
                }
            }
        }
        let (det, inv) = if dim == 2 {
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            (
                det,
                [
                    [j[1][1] / det, -j[0][1] / det, 0.],
                    [-j[1][0] / det, j[0][0] / det, 0.],
                    [0., 0., 0.],
                ],
            )
        } else {
            let m = Matrix3::from_fn(|r, c| j[r][c]);
            let det = m.determinant();
            let inv = m.try_inverse().unwrap_or_else(Matrix3::zeros);
            (
                det,
                [
                    [inv[(0, 0)], inv[(0, 1)], inv[(0, 2)]],
                    [inv[(1, 0)], inv[(1, 1)], inv[(1, 2)]],
                    [inv[(2, 0)], inv[(2, 1)], inv[(2, 2)]],
                ],
            )
        };
        if !det.is_finite() || det == 0. {
            return Err("degenerate (zero Jacobian)".into());
        }
        if sign != 0. && sign * det < 0. {
            return Err("distorted: its Jacobian changes sign inside the cell".into());
        }
        sign = det.signum();
        let mut w = wref * det.abs();
        for row in b.iter_mut().take(ncomp) {
            row[..ndof].iter_mut().for_each(|v| *v = 0.);
        }
        if dim == 2 {
            for i in 0..nn {
                let dx = inv[0][0] * dnr[i][0] + inv[0][1] * dnr[i][1];
                let dy = inv[1][0] * dnr[i][0] + inv[1][1] * dnr[i][1];
                b[0][2 * i] = dx;
                b[1][2 * i + 1] = dy;
                b[3][2 * i] = dy;
                b[3][2 * i + 1] = dx;
            }
            if hyp == Hypothesis::Axisymmetric {
                let r: f64 = (0..nn).map(|i| rd.n[g][i] * xs[i][0]).sum();
                if r <= 0. {
                    return Err(format!(
                        "has a Gauss point at radius {r}: AXIS needs the mesh in x ≥ 0"
                    ));
                }
                for i in 0..nn {
                    b[2][2 * i] = rd.n[g][i] / r;
                }
                w *= r;
            }
        } else {
            for i in 0..nn {
                let dv: [f64; 3] =
                    std::array::from_fn(|a| (0..3).map(|c| inv[a][c] * dnr[i][c]).sum());
                let (cx, cy, cz) = (3 * i, 3 * i + 1, 3 * i + 2);
                b[0][cx] = dv[0];
                b[1][cy] = dv[1];
                b[2][cz] = dv[2];
                b[3][cx] = dv[1];
                b[3][cy] = dv[0];
                b[4][cx] = dv[2];
                b[4][cz] = dv[0];
                b[5][cy] = dv[2];
                b[5][cz] = dv[1];
            }
        }
        for k in 0..ncomp {
            for c in 0..ndof {
                let mut s = 0.;
                for l in 0..ncomp {
                    s += d[k][l] * b[l][c];
                }
                db[k][c] = s * w;
            }
        }
        for r in 0..ndof {
            for k in 0..ncomp {
                let bkr = b[k][r];
                if bkr == 0. {
                    continue;
                }
                let row = &mut out[r * ndof..(r + 1) * ndof];
                for (o, v) in row.iter_mut().zip(&db[k][..ndof]) {
                    *o += bkr * v;
                }
            }
        }
    }
    Ok(ndof)
}

/// Hooke's matrix as a fixed array (upper-left ncomp×ncomp used).
pub fn hooke_array(material: &Elastic, hyp: Hypothesis) -> [[f64; 6]; 6] {
    let h = material.hooke(hyp);
    let mut d = [[0.0; 6]; 6];
    for i in 0..h.nrows() {
        for j in 0..h.ncols() {
            d[i][j] = h[(i, j)];
        }
    }
    d
}
