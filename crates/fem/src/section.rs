//! Section properties of a beam computed from a 2D mesh of its cross-section, as
//! code_aster's `MACR_CARA_POUTRE` computes them.
//!
//! - [`cara_geom`]: `POST_ELEM/CARA_GEOM` — per cell `te0285` (the cell's
//!   `MASS` family: QUAD4 FPG4, QUAD8/QUAD9 FPG9, TRIA3 FPG3, TRIA6 FPG6),
//!   summed by `pemica` (with its parallel-axis transport of the third
//!   moments, reproduced as written: it transports `∫x r²` with the
//!   y offset and `∫y r²` with the x offset), then `pecag2` (symmetries
//!   `SYME_X`/`SYME_Y`, inertias about `ORIG_INER`, principal axes by
//!   code_aster's generalised Jacobi rotation — [`jacobi`] — and the angle
//!   of the weaker axis `ALPHA` from `orien2`) and `pecag3` (the extents in
//!   the principal frame).
//! - [`beam_properties`]: `POST_ELEM/CARA_POUTRE` on the three Laplace
//!   problems of the macro, solved by the thermal solver
//!   ([`crate::thermal::stationary_with`]) on the section moved into its
//!   principal frame with the centroid at the origin (`CREA_MAILLAGE/REPERE`,
//!   `chcoma`):
//!   torsion −Δφ = 2, φ = 0 on the border, `JX = 2∫φ` (`pecap1`, `te0509`);
//!   shear −Δψ = y (resp. z) with ∂ψ/∂n = 0 and ψ = 0 at one node, then
//!   `pecap2`'s shear centre `EY`, `EZ`, shear coefficients `AY`, `AZ` and
//!   centre `PCTY`, `PCTZ`; warping (the section moved to the shear centre,
//!   `chcomb`) −Δω = 0 with ∂ω/∂n = (z, −y)·n on the border and ∫ω = 0 (a
//!   Lagrange multiplier, code_aster's `LIAISON_CHAMNO`), `JG = ∫ Σᵢ Nᵢ ωᵢ²`
//!   as `te0509` integrates it (the interpolated square of the nodal values,
//!   not the square of the interpolation: code_aster's value).
//!
//! Numbers differ from the exact section values by the discretisation only
//! (the linear FE torsion constant of a coarse mesh is above the exact one).

use crate::element::physical_derivatives;
use crate::error::FemError;
use crate::thermal::{self, Conduction, Imposed, ThermalHypothesis, ThermalProblem};
use aster_mesh::{CellId, Mesh, NodeId};

/// te0285's `CARA_GEOM` of one cell: area, centroid, inertias about the
/// cell's centroid (`ixx` = ∫y², `iyy` = ∫x², `ixy` = ∫xy) and the third
/// moments ∫x r², ∫y r² about it.
struct CellGeom {
    area: f64,
    c: [f64; 2],
    ixx: f64,
    iyy: f64,
    ixy: f64,
    ixr2: f64,
    iyr2: f64,
}

/// One Gauss point: shape functions, physical gradients (x, y), weight ×
/// |det J|, coordinates.
struct Point {
    n: Vec<f64>,
    dn: Vec<[f64; 3]>,
    w: f64,
    x: [f64; 3],
}

fn points(mesh: &Mesh, cell: CellId) -> Result<Vec<Point>, FemError> {
    let c = mesh.cell(cell);
    let scheme = thermal::volume_scheme(c.ty).ok_or_else(|| {
        FemError::Model(format!(
            "cell {} is a {:?}: no section element for it",
            mesh.cell_name(cell),
            c.ty
        ))
    })?;
    scheme
        .iter()
        .map(|gp| {
            let (n, dn, det, x) = physical_derivatives(mesh, cell, 2, gp)
                .map_err(|e| FemError::Model(format!("cell {} is {e}", mesh.cell_name(cell))))?;
            Ok(Point {
                n,
                dn,
                w: gp.weight * det.abs(),
                x,
            })
        })
        .collect()
}

/// Whether a cell is a surface cell a section is made of.
pub fn is_section_cell(mesh: &Mesh, cell: CellId) -> bool {
    let ty = mesh.cell(cell).ty;
    ty.dim() == 2 && thermal::volume_scheme(ty).is_some()
}

fn cell_geom(mesh: &Mesh, cell: CellId) -> Result<CellGeom, FemError> {
    let pts = points(mesh, cell)?;
    let (mut vol, mut sx, mut sy, mut yy, mut xy, mut xx) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for p in &pts {
        vol += p.w;
        sx += p.w * p.x[0];
        sy += p.w * p.x[1];
        yy += p.w * p.x[1] * p.x[1];
        xy += p.w * p.x[0] * p.x[1];
        xx += p.w * p.x[0] * p.x[0];
    }
    let (xg, yg) = (sx / vol, sy / vol);
    let (mut ixr2, mut iyr2) = (0.0, 0.0);
    for p in &pts {
        let (xp, yp) = (p.x[0] - xg, p.x[1] - yg);
        ixr2 += xp * (xp * xp + yp * yp) * p.w;
        iyr2 += yp * (xp * xp + yp * yp) * p.w;
    }
    Ok(CellGeom {
        area: vol,
        c: [xg, yg],
        ixx: yy - vol * yg * yg,
        iyy: xx - vol * xg * xg,
        ixy: xy - vol * xg * yg,
        ixr2,
        iyr2,
    })
}

/// code_aster's generalised Jacobi method (`jacobi`, B = I here) on a
/// symmetric 3×3 matrix stored as its upper triangle `a11 a12 a13 a22 a23
/// a33`: the eigenvalues and the eigenvectors (columns), unsorted.
pub fn jacobi(ar: [f64; 6]) -> ([f64; 3], [[f64; 3]; 3]) {
    const N: usize = 3;
    let (nperm, tol, toldyn): (i32, f64, f64) = (12, 1e-10, 1e-2);
    // 1-based packed storage as in the Fortran.
    let mut a = [0.0; 7];
    let mut b = [0.0; 7];
    a[1..].copy_from_slice(&ar);
    b[1..].copy_from_slice(&[1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
    let diag = |i: usize| (i - 1) * N - (i - 1) * i / 2 + i;
    let mut valaux = [0.0; 4];
    let mut valpro = [0.0; 4];
    for i in 1..=N {
        valaux[i] = a[diag(i)] / b[diag(i)];
        valpro[i] = valaux[i];
    }
    let mut v = [[0.0; 4]; 4];
    for (i, row) in v.iter_mut().enumerate().skip(1) {
        row[i] = 1.0;
    }
    let mut niter = 0;
    loop {
        niter += 1;
        let eps = (toldyn.powi(niter)).powi(2);
        for j in 1..N {
            let jm1 = j - 1;
            let ljk = jm1 * N - jm1 * j / 2;
            let jj = ljk + j;
            for k in j + 1..=N {
                let km1 = k - 1;
                let jk = ljk + k;
                let kk = km1 * N - km1 * k / 2 + k;
                let eptola = (a[jk] * a[jk]).abs();
                let epcoma = (a[jj] * a[kk]).abs() * eps;
                let eptolb = (b[jk] * b[jk]).abs();
                let epcomb = (b[jj] * b[kk]).abs() * eps;
                if eptola == 0.0 && eptolb == 0.0 {
                    continue;
                }
                if eptola <= epcoma && eptolb <= epcomb {
                    continue;
                }
                let akk = a[kk] * b[jk] - b[kk] * a[jk];
                let ajj = a[jj] * b[jk] - b[jj] * a[jk];
                let ab = a[jj] * b[kk] - a[kk] * b[jj];
                let verif = (ab * ab + 4.0 * akk * ajj) / 4.0;
                if verif < 0.0 {
                    continue;
                }
                let raci = verif.sqrt();
                let d1 = ab / 2.0 + raci;
                let d2 = ab / 2.0 - raci;
                let den = if d2.abs() > d1.abs() { d2 } else { d1 };
                let (ca, cg) = if den == 0.0 {
                    (0.0, -a[jk] / a[kk])
                } else {
                    (akk / den, -ajj / den)
                };
                let rot = |ij: usize, ik: usize, a: &mut [f64; 7], b: &mut [f64; 7]| {
                    let (aj, bj, ak, bk) = (a[ij], b[ij], a[ik], b[ik]);
                    a[ij] = aj + cg * ak;
                    b[ij] = bj + cg * bk;
                    a[ik] = ak + ca * aj;
                    b[ik] = bk + ca * bj;
                };
                for i in 1..j {
                    let im1 = i - 1;
                    let base = im1 * N - im1 * i / 2;
                    rot(base + j, base + k, &mut a, &mut b);
                }
                let lji = jm1 * N - jm1 * j / 2;
                let lki = km1 * N - km1 * k / 2;
                for i in k + 1..=N {
                    rot(lji + i, lki + i, &mut a, &mut b);
                }
                for i in j + 1..k {
                    let im1 = i - 1;
                    rot(lji + i, im1 * N - im1 * i / 2 + k, &mut a, &mut b);
                }
                let (ak, bk) = (a[kk], b[kk]);
                a[kk] = ak + 2.0 * ca * a[jk] + ca * ca * a[jj];
                b[kk] = bk + 2.0 * ca * b[jk] + ca * ca * b[jj];
                a[jj] = a[jj] + 2.0 * cg * a[jk] + cg * cg * ak;
                b[jj] = b[jj] + 2.0 * cg * b[jk] + cg * cg * bk;
                a[jk] = 0.0;
                b[jk] = 0.0;
                for row in v.iter_mut().skip(1) {
                    let (xj, xk) = (row[j], row[k]);
                    row[j] = xj + cg * xk;
                    row[k] = xk + ca * xj;
                }
            }
        }
        for i in 1..=N {
            valpro[i] = a[diag(i)] / b[diag(i)];
        }
        let mut conv = (1..=N).all(|i| (valpro[i] - valaux[i]).abs() <= (tol * valaux[i]).abs());
        if conv {
            let eps = tol * tol;
            'outer: for j in 1..N {
                let jm1 = j - 1;
                let ljk = jm1 * N - jm1 * j / 2;
                let jj = ljk + j;
                for k in j + 1..=N {
                    let km1 = k - 1;
                    let jk = ljk + k;
                    let kk = km1 * N - km1 * k / 2 + k;
                    if (a[jk] * a[jk]).abs() >= eps * (a[jj] * a[kk]).abs()
                        || (b[jk] * b[jk]).abs() >= eps * (b[jj] * b[kk]).abs()
                    {
                        conv = false;
                        break 'outer;
                    }
                }
            }
        }
        if conv || niter >= nperm {
            break;
        }
        valaux = valpro;
    }
    let mut vec = [[0.0; 3]; 3];
    for i in 1..=N {
        let bii = b[diag(i)];
        let bb = if bii >= 0.0 {
            bii.sqrt()
        } else {
            -bii.abs().sqrt()
        };
        for k in 1..=N {
            vec[i - 1][k - 1] = v[k][i] / bb;
        }
    }
    ([valpro[1], valpro[2], valpro[3]], vec)
}

/// `vpordo(0, 0)`: eigenvalues ascending (a selection sort that keeps the
/// last of equal values), their vectors with them.
fn sort_ascending(val: &mut [f64; 3], vec: &mut [[f64; 3]; 3]) {
    for i in 0..3 {
        let mut iperm = i;
        let mut rperm = val[i];
        for (j, &vj) in val.iter().enumerate().skip(i + 1) {
            if vj <= rperm {
                iperm = j;
                rperm = vj;
            }
        }
        if iperm != i {
            val.swap(i, iperm);
            vec.swap(i, iperm);
        }
    }
}

/// `orien1`'s first nautical angle of a vector (radians).
fn heading(v: [f64; 3]) -> f64 {
    if (v[0] * v[0] + v[1] * v[1]).sqrt() != 0.0 {
        v[1].atan2(v[0])
    } else {
        0.0
    }
}

/// Symmetries of `CARA_GEOM` (`SYME_X`: the mesh is half of the section,
/// symmetric about the x axis; `SYME_Y`: about the y axis).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Symmetry {
    pub x: bool,
    pub y: bool,
}

/// The `CARA_GEOM` values of one place, named as code_aster's table
/// columns (`A_M` … `RZ`), in its column order.
#[derive(Clone, Debug, PartialEq)]
pub struct CaraGeom {
    pub values: Vec<(&'static str, f64)>,
}

impl CaraGeom {
    pub fn get(&self, name: &str) -> f64 {
        self.values
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| *v)
            .unwrap_or(f64::NAN)
    }
}

/// `POST_ELEM/CARA_GEOM` of `cells` (surface cells), the extents over
/// `extent_nodes` (code_aster: every node of the mesh for `TOUT`, the
/// nodes of the cells of a group), with symmetries and `ORIG_INER`.
pub fn cara_geom(
    mesh: &Mesh,
    cells: &[CellId],
    extent_nodes: &[NodeId],
    sym: Symmetry,
    origin: Option<[f64; 2]>,
) -> Result<CaraGeom, FemError> {
    let per_cell: Vec<CellGeom> = cells
        .iter()
        .map(|&c| cell_geom(mesh, c))
        .collect::<Result<_, _>>()?;
    // pemica
    let mut vr = [0.0; 30];
    for g in &per_cell {
        vr[1] += g.area;
        vr[2] += g.c[0] * g.area;
        vr[3] += g.c[1] * g.area;
    }
    if vr[1].abs() > 1e-6 {
        vr[2] /= vr[1];
        vr[3] /= vr[1];
    }
    for g in &per_cell {
        let m = g.area;
        let dx = g.c[0] - vr[2];
        let dy = g.c[1] - vr[3];
        vr[5] += g.ixx + m * dy * dy;
        vr[6] += g.iyy + m * dx * dx;
        vr[7] += (g.ixx + g.iyy) + m * (dx * dx + dy * dy);
        vr[8] += g.ixy + m * dx * dy;
        vr[26] +=
            g.ixr2 + dy * (3.0 * g.ixx + g.iyy) + m * dy * (dx * dx + dy * dy) + 2.0 * dx * g.ixy;
        vr[27] +=
            g.iyr2 + dx * (3.0 * g.iyy + g.ixx) + m * dx * (dx * dx + dy * dy) + 2.0 * dy * g.ixy;
    }
    let epsi = 1e-12;
    if [vr[5], vr[6], vr[7], vr[8]].iter().all(|v| v.abs() < epsi) {
        vr[26] = 0.0;
        vr[27] = 0.0;
        vr[28] = 0.0;
        vr[29] = 0.0;
    } else {
        let (mut val, mut vec) = jacobi([vr[5], -vr[8], 0.0, vr[6], 0.0, vr[7]]);
        sort_ascending(&mut val, &mut vec);
        let a = heading(vec[0]);
        vr[28] = -a.sin() * vr[27] + a.cos() * vr[26];
        vr[29] = a.cos() * vr[27] + a.sin() * vr[26];
    }
    // pecag2
    let mut aire = vr[1];
    let (mut cdgx, mut cdgy) = (vr[2], vr[3]);
    let (mut ixx, mut iyy, mut izz, mut ixy) = (vr[5], vr[6], vr[7], vr[8]);
    let (ixr2, iyr2) = (vr[26], vr[27]);
    let (mut ixpri2, mut iypri2) = (vr[28], vr[29]);
    let mut out: Vec<(&'static str, f64)> = vec![
        ("A_M", aire),
        ("CDG_Y_M", cdgx),
        ("CDG_Z_M", cdgy),
        ("IY_G_M", ixx),
        ("IZ_G_M", iyy),
        ("IYZ_G_M", ixy),
    ];
    let (dx, dy) = (vr[2], vr[3]);
    if sym.x && !sym.y {
        cdgy = 0.0;
        ixx = 2.0 * ixx + 2.0 * aire * dy * dy;
        iyy *= 2.0;
        izz = 2.0 * izz + 2.0 * aire * dy * dy;
        aire *= 2.0;
    } else if sym.y && !sym.x {
        cdgx = 0.0;
        ixx *= 2.0;
        iyy = 2.0 * iyy + 2.0 * aire * dx * dx;
        izz = 2.0 * izz + 2.0 * aire * dx * dx;
        aire *= 2.0;
    } else if sym.x && sym.y {
        cdgx = 0.0;
        cdgy = 0.0;
        ixx = 4.0 * ixx + 4.0 * aire * dy * dy;
        iyy = 4.0 * iyy + 4.0 * aire * dx * dx;
        izz = 4.0 * izz + 4.0 * aire * (dx * dx + dy * dy);
        ixy = 0.0;
        aire *= 4.0;
    }
    let (yp, zp, ixxp, iyyp, ixyp, ixpr2p, iypr2p) = match origin {
        Some([xp, yp]) => {
            let (xgp, ygp) = (xp - cdgx, yp - cdgy);
            (
                xp,
                yp,
                ixx + aire * ygp * ygp,
                iyy + aire * xgp * xgp,
                ixy + aire * xgp * ygp,
                ixr2 - ygp * (3.0 * ixx + iyy)
                    - aire * ygp * (xgp * xgp + ygp * ygp)
                    - 2.0 * xgp * ixy,
                iyr2 - xgp * (3.0 * iyy + ixx)
                    - aire * xgp * (xgp * xgp + ygp * ygp)
                    - 2.0 * ygp * ixy,
            )
        }
        None => (cdgx, cdgy, ixx, iyy, ixy, ixr2, iyr2),
    };
    let (ixprin, iyprin, alpha);
    if [ixx, iyy, izz, ixy].iter().all(|v| v.abs() < epsi) {
        ixprin = 0.0;
        iyprin = 0.0;
        alpha = 0.0;
        ixpri2 = 0.0;
        iypri2 = 0.0;
    } else {
        let (val, vec) = jacobi([ixx, -ixy, 0.0, iyy, 0.0, izz]);
        if val[0] < val[1] {
            ixprin = val[0];
            iyprin = val[1];
            alpha = heading(vec[0]).to_degrees();
        } else {
            let a = heading(vec[1]);
            ixprin = val[1];
            iyprin = val[0];
            alpha = a.to_degrees();
            ixpri2 = -a.sin() * iyr2 + a.cos() * ixr2;
            iypri2 = a.cos() * iyr2 + a.sin() * ixr2;
        }
    }
    // pecag3: extents in the principal frame.
    let (cosa, sina) = (alpha.to_radians().cos(), alpha.to_radians().sin());
    let (mut xmax, mut xmin, mut ymax, mut ymin, mut rmax) =
        (-f64::MAX, f64::MAX, -f64::MAX, f64::MAX, -f64::MAX);
    for &n in extent_nodes {
        let p = mesh.coord(n);
        let (x0, y0) = (p[0] - cdgx, p[1] - cdgy);
        let x = x0 * cosa + y0 * sina;
        let y = y0 * cosa - x0 * sina;
        xmax = xmax.max(x);
        xmin = xmin.min(x);
        ymax = ymax.max(y);
        ymin = ymin.min(y);
        rmax = rmax.max((x * x + y * y).sqrt());
    }
    let rx = xmax.abs().max(xmin.abs());
    let ry = ymax.abs().max(ymin.abs());
    if sym.x {
        let x = cosa;
        if (x.abs() - 1.0).abs() <= 1e-5 {
            let t = ymin.abs().max(ymax.abs());
            ymin = -t;
            ymax = t;
        } else {
            let t = xmin.abs().max(xmax.abs());
            xmin = -t;
            xmax = t;
        }
    }
    if sym.y {
        let y = cosa;
        if (y.abs() - 1.0).abs() <= 1e-5 {
            let t = xmin.abs().max(xmax.abs());
            xmin = -t;
            xmax = t;
        } else {
            let t = ymin.abs().max(ymax.abs());
            ymin = -t;
            ymax = t;
        }
    }
    out.extend([
        ("Y_MAX", xmax),
        ("Z_MAX", ymax),
        ("Y_MIN", xmin),
        ("Z_MIN", ymin),
        ("R_MAX", rmax),
        ("A", aire),
        ("CDG_Y", cdgx),
        ("CDG_Z", cdgy),
        ("IY_G", ixx),
        ("IZ_G", iyy),
        ("IYZ_G", ixy),
        ("IY", ixprin),
        ("IZ", iyprin),
        ("ALPHA", alpha),
        ("Y_P", yp),
        ("Z_P", zp),
        ("IY_P", ixxp),
        ("IZ_P", iyyp),
        ("IYZ_P", ixyp),
        ("IYR2_G", ixr2),
        ("IZR2_G", iyr2),
        ("IYR2", ixpri2),
        ("IZR2", iypri2),
        ("IYR2_P", ixpr2p),
        ("IZR2_P", iypr2p),
        ("RY", rx),
        ("RZ", ry),
    ]);
    Ok(CaraGeom { values: out })
}

/// The section's torsion, shear and warping properties, with code_aster's
/// table signs (`EY` = −e_y…).
#[derive(Clone, Debug, PartialEq)]
pub struct BeamProperties {
    /// `None` for a section with holes ([`SectionBorder::holes`]).
    pub jx: Option<f64>,
    pub ay: f64,
    pub az: f64,
    pub ey: f64,
    pub ez: f64,
    pub pcty: f64,
    pub pctz: f64,
    pub jg: f64,
}

/// What the Laplace problems need: the section's surface cells, the nodes
/// of its outer border (φ = 0), its border segments (the warping flux) and
/// the node where the shear functions are fixed (`GROUP_NO`).
pub struct SectionBorder<'a> {
    pub cells: &'a [CellId],
    pub border_nodes: &'a [NodeId],
    pub border_segments: &'a [CellId],
    pub pinned: NodeId,
    /// The section has holes (`GROUP_MA_INTE`): code_aster's torsion
    /// problem then makes φ uniform on each hole's border with the flux
    /// 2·area/length through it; that is not reproduced, so `JX` is not
    /// computed. The shear and warping problems do not see the holes (the
    /// warping flux is imposed on the outer border only, as code_aster
    /// does).
    pub holes: bool,
}

/// A copy of `mesh` in the principal frame of `geom` with the centroid at
/// the origin (`chcoma`).
pub fn principal_mesh(mesh: &Mesh, geom: &CaraGeom) -> Mesh {
    let (yg, zg) = (geom.get("CDG_Y"), geom.get("CDG_Z"));
    let a = geom.get("ALPHA").to_radians();
    let (c, s) = (a.cos(), a.sin());
    let mut m = mesh.clone();
    for p in &mut m.coords {
        let (y, z) = (p[0] - yg, p[1] - zg);
        p[0] = c * y + s * z;
        p[1] = -s * y + c * z;
    }
    m
}

fn laplace<'m>(
    mesh: &'m Mesh,
    cells: &[CellId],
    imposed: Vec<(NodeId, Imposed)>,
    source: f64,
) -> ThermalProblem<'m> {
    let unit = Conduction {
        lambda: 1.0,
        rho_cp: 0.0,
    };
    ThermalProblem {
        mesh,
        hypothesis: ThermalHypothesis::Plane,
        cells: cells.iter().map(|&c| (c, unit)).collect(),
        skin: Vec::new(),
        imposed,
        varying_flux: Vec::new(),
        sources: if source != 0.0 {
            cells.iter().map(|&c| (c, source)).collect()
        } else {
            Vec::new()
        },
    }
}

/// ∫ f(x) Nᵢ over the cells (code_aster's `te0080` with a function of the
/// coordinates at the Gauss points), per mesh node.
fn source_load(
    mesh: &Mesh,
    cells: &[CellId],
    f: impl Fn([f64; 3]) -> f64,
) -> Result<Vec<f64>, FemError> {
    let mut load = vec![0.0; mesh.node_count()];
    for &c in cells {
        let nodes = &mesh.cell(c).nodes;
        for p in points(mesh, c)? {
            let v = f(p.x) * p.w;
            for (i, n) in nodes.iter().enumerate() {
                load[n.0 as usize] += v * p.n[i];
            }
        }
    }
    Ok(load)
}

/// `POST_ELEM/CARA_POUTRE` (`CARA_TORSION`, `CARA_CISAILLEMENT`,
/// `CARA_GAUCHI`) of the section `s` of `mesh`, whose `CARA_GEOM` is
/// `geom`.
pub fn beam_properties(
    mesh: &Mesh,
    geom: &CaraGeom,
    s: &SectionBorder,
) -> Result<BeamProperties, FemError> {
    let pm = principal_mesh(mesh, geom);
    let cells = s.cells;
    let Some(&first) = cells.first() else {
        return Err(FemError::Model("the section has no surface cell".into()));
    };
    // Torsion.
    let fixed: Vec<(NodeId, Imposed)> = s
        .border_nodes
        .iter()
        .map(|&n| (n, Imposed::Constant(0.0)))
        .collect();
    let phi = if s.holes {
        vec![0.0; pm.node_count()]
    } else {
        thermal::stationary_with(
            &laplace(&pm, cells, fixed, 2.0),
            &vec![0.0; pm.node_count()],
        )?
    };
    // Shear: −Δψ = y, −Δψ = z, ψ = 0 at the pinned node.
    let pin = || vec![(s.pinned, Imposed::Constant(0.0))];
    let psi_y = thermal::stationary_with(
        &laplace(&pm, cells, pin(), 0.0),
        &source_load(&pm, cells, |x| x[0])?,
    )?;
    let psi_z = thermal::stationary_with(
        &laplace(&pm, cells, pin(), 0.0),
        &source_load(&pm, cells, |x| x[1])?,
    )?;
    // te0509 integrals.
    let (mut sphi, mut w1, mut w2, mut u1y, mut u1z) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &c in cells {
        let nodes = &pm.cell(c).nodes;
        for p in points(&pm, c)? {
            let val = |f: &[f64], i: usize| f[nodes[i].0 as usize];
            let mut g1 = [0.0; 2];
            let mut g2 = [0.0; 2];
            for i in 0..nodes.len() {
                sphi += p.n[i] * val(&phi, i) * p.w;
                for k in 0..2 {
                    g1[k] += p.dn[i][k] * val(&psi_y, i);
                    g2[k] += p.dn[i][k] * val(&psi_z, i);
                }
            }
            let (x, y) = (p.x[0], p.x[1]);
            w2 -= (g1[1] * x - g1[0] * y) * p.w;
            w1 += (g2[1] * x - g2[0] * y) * p.w;
            u1y += (g1[0] * g1[0] + g1[1] * g1[1]) * p.w;
            u1z += (g2[0] * g2[0] + g2[1] * g2[1]) * p.w;
        }
    }
    let jx = (!s.holes).then_some(2.0 * sphi);
    // pecap2
    let (iy, iz, area) = (geom.get("IY"), geom.get("IZ"), geom.get("A"));
    let ey = w1 / iy;
    let ez = w2 / iz;
    let ay = u1y * area / iz / iz;
    let az = u1z * area / iy / iy;
    let a = geom.get("ALPHA").to_radians();
    let (xg, yg) = (geom.get("CDG_Y"), geom.get("CDG_Z"));
    let pctx = a.cos() * ey - a.sin() * ez + xg;
    let pcty = a.sin() * ey + a.cos() * ez + yg;
    // Warping, on the section moved to the shear centre (chcomb adds the
    // table's EY = −ey, EZ = −ez).
    let mut tm = pm.clone();
    for p in &mut tm.coords {
        p[0] -= ey;
        p[1] -= ez;
    }
    let mut flux = vec![0.0; tm.node_count()];
    for &seg in s.border_segments {
        let c = tm.cell(seg);
        let Some(scheme) = thermal::skin_scheme(c.ty) else {
            return Err(FemError::Model(format!(
                "border cell {} is a {:?}: not a segment",
                tm.cell_name(seg),
                c.ty
            )));
        };
        for gp in &scheme {
            let sh = crate::shape::shape(c.ty, gp.xi);
            let mut x = [0.0; 2];
            let mut t = [0.0; 2];
            for (i, &n) in c.nodes.iter().enumerate() {
                let q = tm.coord(n);
                for k in 0..2 {
                    x[k] += sh.n[i] * q[k];
                    t[k] += sh.dn[i][0] * q[k];
                }
            }
            // Outward normal of a counter-clockwise border, times the length
            // element: (t_y, −t_x).
            let q = x[1] * t[1] + (-x[0]) * (-t[0]);
            for (i, &n) in c.nodes.iter().enumerate() {
                flux[n.0 as usize] += gp.weight * q * sh.n[i];
            }
        }
    }
    let ones = source_load(&tm, cells, |_| 1.0)?;
    let (sum_f, sum_c): (f64, f64) = (0..tm.node_count())
        .filter(|&n| ones[n] != 0.0)
        .fold((0.0, 0.0), |(f, c), n| (f + flux[n], c + ones[n]));
    let lambda = sum_f / sum_c;
    let rhs: Vec<f64> = flux
        .iter()
        .zip(&ones)
        .map(|(f, c)| f - lambda * c)
        .collect();
    let anchor = tm.cell(first).nodes[0];
    let mut omega = thermal::stationary_with(
        &laplace(&tm, cells, vec![(anchor, Imposed::Constant(0.0))], 0.0),
        &rhs,
    )?;
    let mean: f64 = (0..tm.node_count())
        .filter(|&n| ones[n] != 0.0)
        .map(|n| ones[n] * omega[n])
        .sum::<f64>()
        / sum_c;
    for w in omega.iter_mut() {
        *w -= mean;
    }
    let mut jg = 0.0;
    for &c in cells {
        let nodes = &tm.cell(c).nodes;
        for p in points(&tm, c)? {
            for (i, n) in nodes.iter().enumerate() {
                let w = omega[n.0 as usize];
                jg += p.n[i] * w * w * p.w;
            }
        }
    }
    Ok(BeamProperties {
        jx,
        ay,
        az,
        ey: -ey,
        ez: -ez,
        pcty: -pctx,
        pctz: -pcty,
        jg,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An a × a square of n × n QUAD4 centred at (cx, cy), its border BORD
    /// (SEG2, counter-clockwise) and its first node P1.
    fn square(a: f64, n: usize, cx: f64, cy: f64) -> Mesh {
        let mut t = String::from("COOR_2D\n");
        let id = |i: usize, j: usize| j * (n + 1) + i + 1;
        for j in 0..=n {
            for i in 0..=n {
                let x = cx - a / 2.0 + a * i as f64 / n as f64;
                let y = cy - a / 2.0 + a * j as f64 / n as f64;
                t += &format!("N{} {x} {y}\n", id(i, j));
            }
        }
        t += "FINSF\nQUAD4\n";
        for j in 0..n {
            for i in 0..n {
                t += &format!(
                    "Q{}_{} N{} N{} N{} N{}\n",
                    i,
                    j,
                    id(i, j),
                    id(i + 1, j),
                    id(i + 1, j + 1),
                    id(i, j + 1)
                );
            }
        }
        let mut lp: Vec<(usize, usize)> = (0..n).map(|i| (i, 0)).collect();
        lp.extend((0..n).map(|j| (n, j)));
        lp.extend((1..=n).rev().map(|i| (i, n)));
        lp.extend((1..=n).rev().map(|j| (0, j)));
        t += "FINSF\nSEG2\n";
        let mut names = Vec::new();
        for k in 0..lp.len() {
            let (a, b) = (lp[k], lp[(k + 1) % lp.len()]);
            t += &format!("S{k} N{} N{}\n", id(a.0, a.1), id(b.0, b.1));
            names.push(format!("S{k}"));
        }
        t += &format!("FINSF\nGROUP_MA\nBORD\n{}\nFINSF\nFIN\n", names.join(" "));
        aster_mesh::parse_mail(&t, std::path::Path::new("square.mail")).unwrap()
    }

    fn surface(m: &Mesh) -> Vec<CellId> {
        (0..m.cells.len() as u32)
            .map(CellId)
            .filter(|&c| is_section_cell(m, c))
            .collect()
    }

    #[test]
    fn jacobi_finds_the_principal_axes_of_a_tilted_tensor() {
        // [[a, b], [b, a]] with b > 0: a − b along (1, −1), a + b along (1, 1).
        let (val, vec) = jacobi([3.0, 1.0, 0.0, 3.0, 0.0, 6.0]);
        let mut v = val;
        v.sort_by(f64::total_cmp);
        assert!(
            (v[0] - 2.0).abs() < 1e-12 && (v[1] - 4.0).abs() < 1e-12 && (v[2] - 6.0).abs() < 1e-12
        );
        for (k, e) in val.iter().enumerate() {
            let x = vec[k];
            let ax = [3.0 * x[0] + x[1], x[0] + 3.0 * x[1], 6.0 * x[2]];
            for i in 0..3 {
                assert!((ax[i] - e * x[i]).abs() < 1e-12, "{val:?} {vec:?}");
            }
            assert!((x.iter().map(|c| c * c).sum::<f64>() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn a_square_has_the_closed_form_geometry() {
        let m = square(2.0, 4, 3.0, -1.0);
        let cells = surface(&m);
        let nodes: Vec<NodeId> = (0..m.node_count() as u32).map(NodeId).collect();
        let g = cara_geom(&m, &cells, &nodes, Symmetry::default(), Some([0.0, 0.0])).unwrap();
        let close = |k: &str, v: f64| {
            assert!(
                (g.get(k) - v).abs() < 1e-12 * v.abs().max(1.0),
                "{k}: {} vs {v}",
                g.get(k)
            )
        };
        close("A", 4.0);
        close("CDG_Y", 3.0);
        close("CDG_Z", -1.0);
        close("IY_G", 16.0 / 12.0);
        close("IZ_G", 16.0 / 12.0);
        close("IYZ_G", 0.0);
        // About the origin: I + A d².
        close("IY_P", 16.0 / 12.0 + 4.0 * 1.0);
        close("IZ_P", 16.0 / 12.0 + 4.0 * 9.0);
        close("R_MAX", 2f64.sqrt());
        // Symmetric about y (SYME_Y): the mesh is half of a section twice as
        // wide, centred on x = 0.
        let h = cara_geom(&m, &cells, &nodes, Symmetry { x: false, y: true }, None).unwrap();
        assert!((h.get("A") - 8.0).abs() < 1e-12);
        assert!((h.get("IZ_G") - (2.0 * 16.0 / 12.0 + 2.0 * 4.0 * 9.0)).abs() < 1e-9);
    }

    #[test]
    fn a_square_section_has_saint_venant_torsion_and_timoshenko_shear() {
        let m = square(1.0, 16, 0.3, 0.2);
        let cells = surface(&m);
        let nodes: Vec<NodeId> = (0..m.node_count() as u32).map(NodeId).collect();
        let g = cara_geom(&m, &cells, &nodes, Symmetry::default(), None).unwrap();
        let segs = m.group_ma("BORD").unwrap().members.to_vec();
        let mut border: Vec<NodeId> = segs.iter().flat_map(|&c| m.cell(c).nodes.clone()).collect();
        border.sort();
        border.dedup();
        let p = beam_properties(
            &m,
            &g,
            &SectionBorder {
                cells: &cells,
                border_nodes: &border,
                border_segments: &segs,
                pinned: NodeId(0),
                holes: false,
            },
        )
        .unwrap();
        // Saint-Venant: J = 0.140577 a⁴ for a square; linear elements on
        // 16 × 16 give a little less.
        let jx = p.jx.unwrap();
        assert!(
            jx < 0.140577 && (jx - 0.140577).abs() < 0.01 * 0.140577,
            "{jx}"
        );
        // Shear coefficients 6/5 (ν = 0), the shear centre at the centroid.
        assert!(
            (p.ay - 1.2).abs() < 0.01 && (p.az - 1.2).abs() < 0.01,
            "{p:?}"
        );
        assert!(p.ey.abs() < 1e-9 && p.ez.abs() < 1e-9, "{p:?}");
        assert!(
            (p.pcty + 0.3).abs() < 1e-9 && (p.pctz + 0.2).abs() < 1e-9,
            "{p:?}"
        );
        // Warping of a square: small but not zero (0.000151 a⁶ exactly… the
        // discrete value is positive and of that order).
        assert!(p.jg > 0.0 && p.jg < 1e-3, "{p:?}");
        // Holes: no JX.
        let q = beam_properties(
            &m,
            &g,
            &SectionBorder {
                cells: &cells,
                border_nodes: &border,
                border_segments: &segs,
                pinned: NodeId(0),
                holes: true,
            },
        )
        .unwrap();
        assert_eq!(q.jx, None);
        assert_eq!(q.ay, p.ay);
    }
}
