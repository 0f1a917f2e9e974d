//! Reinforcement grids: code_aster's `GRILLE_MEMBRANE` (`MEGMTR3`,
//! `MEGMTR6`, `MEGMQU4`, `MEGMQU8`: DX DY DZ) and `GRILLE_EXCENTRE`
//! (`MEGCTR3`, `MEGCQU4`: DX … DRZ, the grid offset from the cell's
//! surface), linear elastic.
//!
//! A grid is a layer of bars smeared over a surface cell: it carries a
//! stiffness along one direction only, the bars' direction `d`, with the
//! section per unit width `SECTION` (`AFFE_CARA_ELEM/GRILLE`). What it
//! computes, following code_aster's `te0431` (`RIGI_MECA`), `te0433`
//! (`SIEF_ELGA`, `EPSI_ELGA`) and `te0430` (`FORC_NODA`), all through
//! `nmgrib`:
//! - `d` from the angles (α, β) of `cargri`: (cos β cos α, cos β sin α,
//!   −sin β) (`ANGL_REP_1`; `VECT_1`, `VECT_2` and `ANGL_REP_2` are turned
//!   into these angles by `AFFE_CARA_ELEM`, `aceagb`);
//! - at each Gauss point of the `RIGI` family (TRIA3 and TRIA6 FPG3,
//!   QUAD4 FPG4, QUAD8 FPG9), the covariant base a₁, a₂ of the surface and
//!   its unit normal n (`subaco`), the metric and its inverse (`sumetr`,
//!   `subacv`); the strain along the direction projected on the tangent
//!   plane, d_t = d − (d·n) n:
//!   ε = Σ_β (d_t·∂u/∂ξ_β)(a^β·d) / (1 − (d·n)²) — the row B of `nmgrib`;
//! - `GRILLE_EXCENTRE`: the grid lies at e = `EXCENTREMENT`·z of the
//!   facet's frame (`dxtpgl`, `dxqpgl`); its points move as u + θ × e, so
//!   the row of the rotations is B·[e]×ᵀ (`nmgrib`'s matrix p);
//! - K = Σ_g Bᵀ E B · w_g · J_g · SECTION (the Young's modulus E of
//!   `ELAS`, nothing of ν), SIEF_ELGA's one component SIXX = E ε, the
//!   nodal forces Σ_g Bᵀ σ w_g J_g SECTION.
//!
//! Numerics only: the runner maps `AFFE_MODELE/MODELISATION` and
//! `AFFE_CARA_ELEM/GRILLE` onto [`crate::model::ElementKind::Grid`].

use crate::shape::{self, GaussPoint};
use aster_mesh::CellType;
use nalgebra::DMatrix;

/// A grid's section (`AFFE_CARA_ELEM/GRILLE`, code_aster's `CACOQU`
/// components `SECT_L`, `ALPHA`, `BETA`, `DIST_N`).
#[derive(Clone, Debug, PartialEq)]
pub struct GridSection {
    /// `SECTION`: the bars' area per unit width.
    pub section: f64,
    /// The bars' direction, as `cargri` computes it from the angles.
    pub direction: [f64; 3],
    /// `GRILLE_EXCENTRE`: the offset along the facet's normal
    /// (`EXCENTREMENT`, 0 by default); `None` for `GRILLE_MEMBRANE`.
    pub offset: Option<f64>,
}

impl GridSection {
    /// The section of angles (α, β) in degrees (`ANGL_REP_1`).
    pub fn from_angles(section: f64, alpha_deg: f64, beta_deg: f64, offset: Option<f64>) -> Self {
        GridSection {
            section,
            direction: direction(alpha_deg, beta_deg),
            offset,
        }
    }

    /// Checks the section and the cell type.
    pub fn check(&self, ty: CellType) -> Result<(), String> {
        if !(self.section.is_finite() && self.section >= 0.) {
            return Err(format!(
                "grid SECTION = {}: it must be positive",
                self.section
            ));
        }
        let ok = match self.offset {
            None => matches!(
                ty,
                CellType::TRIA3 | CellType::TRIA6 | CellType::QUAD4 | CellType::QUAD8
            ),
            Some(_) => matches!(ty, CellType::TRIA3 | CellType::QUAD4),
        };
        if !ok {
            return Err(format!(
                "a {}: the {} element exists on {} cells only",
                ty.name(),
                if self.offset.is_some() {
                    "GRILLE_EXCENTRE"
                } else {
                    "GRILLE_MEMBRANE"
                },
                if self.offset.is_some() {
                    "TRIA3 and QUAD4"
                } else {
                    "TRIA3, TRIA6, QUAD4 and QUAD8"
                }
            ));
        }
        Ok(())
    }

    /// DOFs per node: 3, or 6 for the offset grid.
    pub fn dofs_per_node(&self) -> usize {
        if self.offset.is_some() {
            6
        } else {
            3
        }
    }
}

/// `cargri`'s direction of angles (α, β) in degrees.
pub fn direction(alpha_deg: f64, beta_deg: f64) -> [f64; 3] {
    let (a, b) = (alpha_deg.to_radians(), beta_deg.to_radians());
    [b.cos() * a.cos(), b.cos() * a.sin(), -b.sin()]
}

/// `angvx`: the angles (α, β) in degrees of a direction `v` (the inverse
/// of [`direction`]), as `AFFE_CARA_ELEM` stores `VECT_1`.
pub fn angles_of(v: [f64; 3]) -> Result<(f64, f64), String> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(n > 1e-6 && n.is_finite()) {
        return Err("the grid's direction vector is zero".into());
    }
    let alpha = if v[0] == 0. && v[1] == 0. {
        0.
    } else {
        v[1].atan2(v[0])
    };
    let beta = (-v[2]).atan2((v[0] * v[0] + v[1] * v[1]).sqrt());
    Ok((alpha.to_degrees(), beta.to_degrees()))
}

/// `aceagb`'s direction from `VECT_2` (the bars are across it): x = y × n,
/// n the cell's normal at its barycentre from the corners (P1 functions).
pub fn direction_across(corners: &[[f64; 3]], y: [f64; 3]) -> Result<[f64; 3], String> {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let add = |a: [f64; 3], b: [f64; 3]| [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
    let (t1, t2) = match corners {
        [a, b, c] => (sub(*b, *a), sub(*c, *a)),
        [a, b, c, d] => (add(sub(*b, *a), sub(*c, *d)), add(sub(*c, *b), sub(*d, *a))),
        _ => return Err("a grid cell has 3 or 4 corners".into()),
    };
    let n = unit(cross(t1, t2)).ok_or("the cell is degenerate: no normal")?;
    let y = unit(y).ok_or("VECT_2 is zero")?;
    unit(cross(y, n)).ok_or_else(|| "VECT_2 is normal to the cell".to_string())
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    (n > 1e-6 && n.is_finite()).then(|| [a[0] / n, a[1] / n, a[2] / n])
}

/// The grids' `RIGI` Gauss family: TRIA3 and TRIA6 FPG3, QUAD4 FPG4,
/// QUAD8 FPG9 (`meca_grille_*.py`), in `elraga` order.
pub fn scheme(ty: CellType) -> Vec<GaussPoint> {
    match ty {
        CellType::TRIA3 | CellType::TRIA6 => shape::rigi_scheme(CellType::TRIA6),
        other => shape::rigi_scheme(other),
    }
}

/// One Gauss point of a grid: its strain row B (node-major, 3 or 6 DOFs
/// per node) and its weight w·J·SECTION.
#[derive(Clone, Debug)]
pub struct GridPoint {
    pub b: Vec<f64>,
    pub w: f64,
}

/// `nmgrib` at each point of [`scheme`] on the cell of type `ty` and nodes
/// `xyz`.
pub fn points(
    ty: CellType,
    xyz: &[[f64; 3]],
    section: &GridSection,
) -> Result<Vec<GridPoint>, String> {
    section.check(ty)?;
    let nno = xyz.len();
    if nno != ty.node_count() {
        return Err(format!("a {} has {} nodes", ty.name(), ty.node_count()));
    }
    let d = section.direction;
    // GRILLE_EXCENTRE: the offset vector e along the facet's z axis.
    let e = match section.offset {
        Some(off) => {
            let pgl = crate::plate::frame(xyz)?;
            Some([off * pgl[(2, 0)], off * pgl[(2, 1)], off * pgl[(2, 2)]])
        }
        None => None,
    };
    let nddl = section.dofs_per_node();
    let mut out = Vec::new();
    for gp in scheme(ty) {
        let s = shape::shape(ty, gp.xi);
        // Covariant base (subaco).
        let mut a1 = [0.0; 3];
        let mut a2 = [0.0; 3];
        for (i, p) in xyz.iter().enumerate() {
            for k in 0..3 {
                a1[k] += s.dn[i][0] * p[k];
                a2[k] += s.dn[i][1] * p[k];
            }
        }
        let n = unit(cross(a1, a2)).ok_or("the cell is degenerate (zero Jacobian)")?;
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        // Metric, its inverse (sumetr, subacv).
        let m = [[dot(a1, a1), dot(a1, a2)], [dot(a2, a1), dot(a2, a2)]];
        let det = (m[0][0] * m[1][1] - m[0][1] * m[1][0]).abs();
        let jac = det.sqrt();
        if !(jac > 0. && jac.is_finite()) {
            return Err("the cell is degenerate (zero Jacobian)".into());
        }
        let inv = [
            [m[1][1] / det, -m[1][0] / det],
            [-m[1][0] / det, m[0][0] / det],
        ];
        let cova = [a1, a2];
        let mut cnva = [[0.0; 3]; 2];
        for k in 0..3 {
            cnva[0][k] = inv[0][0] * a1[k] + inv[0][1] * a2[k];
            cnva[1][k] = inv[1][0] * a1[k] + inv[1][1] * a2[k];
        }
        let r1 = [dot(cova[0], d), dot(cova[1], d)];
        let projn = dot(n, d);
        let denomi = 1. - projn * projn;
        if denomi.abs() <= f64::EPSILON {
            return Err(
                "the grid's direction is normal to the cell (code_aster's ELEMENTS_3)".into(),
            );
        }
        // b(i, node) = Σ r1(α) r1(γ) a(β, γ) dff(β, node) cnva(i, α) / denomi.
        let mut bt = vec![[0.0; 3]; nno];
        for (node, row) in bt.iter_mut().enumerate() {
            for i in 0..3 {
                let mut v = 0.;
                for al in 0..2 {
                    for be in 0..2 {
                        for ga in 0..2 {
                            v += r1[al] * r1[ga] * inv[be][ga] * s.dn[node][be] * cnva[al][i];
                        }
                    }
                }
                row[i] = v / denomi;
            }
        }
        let mut b = vec![0.0; nno * nddl];
        for (node, t) in bt.iter().enumerate() {
            let o = node * nddl;
            b[o..o + 3].copy_from_slice(t);
            if let Some(e) = e {
                // u + θ × e: rows of the rotations (nmgrib's p).
                b[o + 3] = -t[1] * e[2] + t[2] * e[1];
                b[o + 4] = t[0] * e[2] - t[2] * e[0];
                b[o + 5] = -t[0] * e[1] + t[1] * e[0];
            }
        }
        out.push(GridPoint {
            b,
            w: gp.weight * jac * section.section,
        });
    }
    Ok(out)
}

/// The stiffness Σ Bᵀ E B w (`te0431`, `RIGI_MECA`).
pub fn stiffness(
    ty: CellType,
    xyz: &[[f64; 3]],
    section: &GridSection,
    young: f64,
) -> Result<DMatrix<f64>, String> {
    let pts = points(ty, xyz, section)?;
    let n = xyz.len() * section.dofs_per_node();
    let mut k = DMatrix::zeros(n, n);
    for p in &pts {
        for i in 0..n {
            if p.b[i] == 0. {
                continue;
            }
            let f = p.b[i] * young * p.w;
            for j in 0..n {
                k[(i, j)] += f * p.b[j];
            }
        }
    }
    Ok(k)
}

/// The strain ε = B uₑ at each point (`EPSI_ELGA`'s EXX).
pub fn strains(
    ty: CellType,
    xyz: &[[f64; 3]],
    section: &GridSection,
    ue: &[f64],
) -> Result<Vec<f64>, String> {
    let pts = points(ty, xyz, section)?;
    Ok(pts
        .iter()
        .map(|p| p.b.iter().zip(ue).map(|(b, u)| b * u).sum())
        .collect())
}

/// The nodal forces Σ Bᵀ σ w of the stresses `sigma` at the points
/// (`te0430`, `FORC_NODA`).
pub fn nodal_forces(
    ty: CellType,
    xyz: &[[f64; 3]],
    section: &GridSection,
    sigma: &[f64],
) -> Result<Vec<f64>, String> {
    let pts = points(ty, xyz, section)?;
    let mut f = vec![0.0; xyz.len() * section.dofs_per_node()];
    for (p, s) in pts.iter().zip(sigma) {
        for (fi, b) in f.iter_mut().zip(&p.b) {
            *fi += b * s * p.w;
        }
    }
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<[f64; 3]> {
        vec![[0., 0., 0.], [2., 0., 0.], [2., 1., 0.], [0., 1., 0.]]
    }

    #[test]
    fn a_grid_along_x_carries_e_s_per_unit_width_along_x_only() {
        let sec = GridSection::from_angles(0.01, 0., 0., None);
        let xyz = square();
        let k = stiffness(CellType::QUAD4, &xyz, &sec, 2e11).unwrap();
        // Stretch along x: ε = 1e-3 everywhere, σ = E ε, the force on the
        // right edge = E·ε·SECTION·width (1 m).
        let eps = 1e-3;
        let ue: Vec<f64> = xyz.iter().flat_map(|p| [eps * p[0], 0., 0.]).collect();
        let s = strains(CellType::QUAD4, &xyz, &sec, &ue).unwrap();
        assert_eq!(s.len(), 4);
        for v in &s {
            assert!((v - eps).abs() < 1e-15);
        }
        let f = &k * nalgebra::DVector::from_column_slice(&ue);
        let right = f[3] + f[6];
        assert!((right - 2e11 * eps * 0.01 * 1.).abs() < 1e-6 * 2e8);
        // Across (y) and a shear cost nothing.
        for ue in [
            xyz.iter()
                .flat_map(|p| [0., eps * p[1], 0.])
                .collect::<Vec<_>>(),
            xyz.iter().flat_map(|p| [eps * p[1], 0., 0.]).collect(),
            xyz.iter().flat_map(|p| [0., 0., eps * p[0]]).collect(),
        ] {
            let g = &k * nalgebra::DVector::from_column_slice(&ue);
            assert!(g.amax() < 1e-9 * 2e8, "{g}");
        }
    }

    #[test]
    fn an_inclined_grid_sees_the_strain_along_its_direction() {
        // A uniform strain tensor ε: the grid at angle α reads d·ε·d.
        let (exx, eyy, exy) = (1e-3, 2e-3, 0.5e-3);
        for ty in [CellType::TRIA3, CellType::QUAD4] {
            let xyz: Vec<[f64; 3]> = if ty == CellType::TRIA3 {
                vec![[0., 0., 0.], [1., 0.2, 0.], [0.3, 1.1, 0.]]
            } else {
                vec![
                    [0., 0., 0.],
                    [1.2, 0.1, 0.],
                    [1.0, 0.9, 0.],
                    [-0.1, 1.0, 0.],
                ]
            };
            let ue: Vec<f64> = xyz
                .iter()
                .flat_map(|p| [exx * p[0] + exy * p[1], exy * p[0] + eyy * p[1], 0.])
                .collect();
            for alpha in [0., 30., 75.] {
                let sec = GridSection::from_angles(1., alpha, 0., None);
                let a = f64::to_radians(alpha);
                let expect =
                    exx * a.cos().powi(2) + eyy * a.sin().powi(2) + 2. * exy * a.sin() * a.cos();
                for v in strains(ty, &xyz, &sec, &ue).unwrap() {
                    assert!((v - expect).abs() < 1e-14, "{ty:?} {alpha}: {v} {expect}");
                }
            }
        }
        // A direction out of the plane is projected on it: (1,0,1)/√2
        // reads the strain along x.
        let sec = GridSection {
            section: 1.,
            direction: [0.5f64.sqrt(), 0., 0.5f64.sqrt()],
            offset: None,
        };
        let xyz = square();
        let ue: Vec<f64> = xyz.iter().flat_map(|p| [exx * p[0], 0., 0.]).collect();
        for v in strains(CellType::QUAD4, &xyz, &sec, &ue).unwrap() {
            assert!((v - exx).abs() < 1e-15);
        }
    }

    #[test]
    fn an_offset_grid_reads_the_curvature_times_its_offset() {
        // Rotations DRY = κ x (a curvature κ about y): the plate's
        // points at z = e move by u = θ × e = (κ x e, 0, 0), ε = κ e.
        let (kappa, off) = (1e-3, 0.05);
        let sec = GridSection::from_angles(0.2, 0., 0., Some(off));
        let xyz = square();
        let ue: Vec<f64> = xyz
            .iter()
            .flat_map(|p| [0., 0., -0.5 * kappa * p[0] * p[0], 0., kappa * p[0], 0.])
            .collect();
        for v in strains(CellType::QUAD4, &xyz, &sec, &ue).unwrap() {
            assert!((v - kappa * off).abs() < 1e-15, "{v}");
        }
        // The stiffness is symmetric, positive along the bars' strain.
        let k = stiffness(CellType::QUAD4, &xyz, &sec, 2e11).unwrap();
        assert!((&k - k.transpose()).amax() < 1e-6);
        let e = (nalgebra::DVector::from_column_slice(&ue).transpose()
            * &k
            * nalgebra::DVector::from_column_slice(&ue))[(0, 0)];
        // ½ uᵀKu = ½ E (κ e)² SECTION × area (2 m²).
        assert!((e - 2e11 * (kappa * off).powi(2) * 0.2 * 2.).abs() < 1e-9 * e);
        assert!(GridSection::from_angles(0.2, 0., 0., Some(0.))
            .check(CellType::QUAD8)
            .is_err());
    }

    #[test]
    fn angles_and_vectors_agree_with_aceagb() {
        for (a, b) in [(0., 0.), (30., 0.), (15., 70.), (-120., -20.)] {
            let d = direction(a, b);
            let (a2, b2) = angles_of(d).unwrap();
            assert!((a2 - a).abs() < 1e-12 && (b2 - b).abs() < 1e-12);
        }
        // VECT_2 = z on a vertical face x = 0 (normal ±x): bars along ∓y.
        let face = [[0., 0., 0.], [0., 1., 0.], [0., 1., 1.], [0., 0., 1.]];
        let d = direction_across(&face, [0., 0., 1.]).unwrap();
        assert!((d[1].abs() - 1.).abs() < 1e-15 && d[0] == 0. && d[2] == 0.);
        assert!(direction_across(&face, [1., 0., 0.]).is_err());
    }
}
