//! Euler–Bernoulli straight beam: code_aster's `POU_D_E` modelisation on
//! SEG2 (`MECA_POU_D_E`), two nodes with six DOFs each (DX DY DZ DRX DRY
//! DRZ), linear elastic, small displacements.
//!
//! What it computes, following code_aster's routines:
//! - the local frame (`angvx` + `matrot` with γ = 0): x along node 1 →
//!   node 2; α = atan2(x_Y, x_X) (0 for a vertical beam), β = −atan2(x_Z,
//!   √(x_X² + x_Y²)); the rows of `pgl` are the local axes in global
//!   coordinates, y = (−sin α, cos α, 0), z = (sin β cos α, sin β sin α,
//!   cos β);
//! - the local stiffness (`ptka01` with no shear deformation, φ = 0, and no
//!   shear-centre offset): EA/L on the axial DOFs, GJx/L on the torsion
//!   DOFs (G = E/(2(1+ν))), the cubic bending blocks 12EI/L³, 6EI/L²,
//!   4EI/L, 2EI/L in the planes (x, y) with Iz and (x, z) with Iy
//!   (the sign of the coupling of w and θy is negative, as `ptka01` writes
//!   it);
//! - the mass (`MASS_MECA`, `te0141` → `pomass` → `ptma01` with
//!   `kanl = 1`): for POU_D_E `ptma01` sets the shear coefficients and
//!   with them the bending second moments to zero, so the consistent mass
//!   has **no rotary inertia of bending**: ρAL/3, ρAL/6 on the axial DOFs,
//!   the cubic Hermite blocks ρAL·(13/35, 11L/210, 9/70, −13L/420, L²/105,
//!   −L²/140) in both bending planes, and the torsion inertia of the polar
//!   moment Iy + Iz (not Jx): ρ(Iy+Iz)L/3, ρ(Iy+Iz)L/6;
//! - the lumped mass (`MASS_MECA_DIAG`, `kanl = 0`): ρAL/2 on each
//!   translation, ρ(Iy+Iz)L/2 on each torsion, ρAL³/105 + 2ρIyL/15 on θy
//!   and ρAL³/105 + 2ρIzL/15 on θz (here the second moments do count);
//! - the generalised efforts at the nodes (`EFGE_ELNO`): f = K_local·u_local,
//!   reported as −f at node 1 and +f at node 2 (N VY VZ MT MFY MFZ), the
//!   efforts the part beyond each node exerts, as code_aster's `pouex7`.
//!
//! Numerics only: the runner maps `AFFE_MODELE/MODELISATION='POU_D_E'`
//! and `AFFE_CARA_ELEM/POUTRE` onto [`crate::model::ElementKind::Beam`] and
//! [`BeamSection`].

use crate::material::Elastic;
use nalgebra::{DMatrix, DVector};

/// Section of a straight beam (`CARA_ELEM/POUTRE`, constant along the
/// element): area A, second moments Iy (about local y) and Iz (about
/// local z), torsion constant Jx.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BeamSection {
    pub area: f64,
    pub iy: f64,
    pub iz: f64,
    pub jx: f64,
}

impl BeamSection {
    /// code_aster's `SECTION='CERCLE'` (`affgen`): outer radius `r`, wall
    /// thickness `ep` (`ep = r` for a solid section).
    pub fn circle(r: f64, ep: f64) -> BeamSection {
        let ri = r - ep;
        let area = std::f64::consts::PI * (r * r - ri * ri);
        let i = std::f64::consts::PI * (r.powi(4) - ri.powi(4)) / 4.;
        BeamSection {
            area,
            iy: i,
            iz: i,
            jx: 2. * i,
        }
    }

    /// code_aster's `SECTION='RECTANGLE'` (`affgen`): sides `hy` (along
    /// local y) and `hz` (along local z), wall thicknesses `epy`, `epz`
    /// (`None`: a solid section). Torsion constant: the series formula
    /// a·b³·(16/3 − 3.36·b/a·(1 − b⁴/(12a⁴))) (a ≥ b the half sides) for a
    /// solid section, Bredt's 2·ey·ez·(hy−ey)²·(hz−ez)²/(hy·ey + hz·ez −
    /// ey² − ez²) for a hollow one.
    pub fn rectangle(hy: f64, hz: f64, walls: Option<(f64, f64)>) -> BeamSection {
        let (epy, epz) = walls.unwrap_or((hy / 2., hz / 2.));
        let (hyi, hzi) = (hy - 2. * epy, hz - 2. * epz);
        let area = hy * hz - hyi * hzi;
        let iy = (hy * hz.powi(3) - hyi * hzi.powi(3)) / 12.;
        let iz = (hz * hy.powi(3) - hzi * hyi.powi(3)) / 12.;
        let eps = 1e-3;
        let jx = if (hyi / hy).abs() <= eps || (hzi / hz).abs() <= eps {
            let (mut a, mut b) = (hy / 2., hz / 2.);
            if a / b < 1. {
                std::mem::swap(&mut a, &mut b);
            }
            let a4 = a.powi(4) * 12.;
            a * b.powi(3) * (16. / 3. - 3.36 * b * (1. - b.powi(4) / a4) / a)
        } else {
            let ct = 2. * epy * epz * (hy - epy).powi(2) * (hz - epz).powi(2);
            let cd = hy * epy + hz * epz - epy * epy - epz * epz;
            ct / cd
        };
        BeamSection { area, iy, iz, jx }
    }

    /// Checks that every characteristic is positive and finite.
    pub fn check(&self) -> Result<(), String> {
        for (name, v) in [
            ("A", self.area),
            ("IY", self.iy),
            ("IZ", self.iz),
            ("JX", self.jx),
        ] {
            if !(v.is_finite() && v > 0.) {
                return Err(format!(
                    "beam section has {name} = {v}: it must be positive"
                ));
            }
        }
        Ok(())
    }
}

/// The local frame of a beam from node `a` to node `b` (rows: local x, y,
/// z in global coordinates) and its length.
pub fn frame(a: [f64; 3], b: [f64; 3]) -> Result<([[f64; 3]; 3], f64), String> {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if !(len > 0. && len.is_finite()) {
        return Err("the beam has zero length: its local frame is undefined".into());
    }
    let tiny = f64::MIN_POSITIVE;
    let alpha = if d[0].abs() <= tiny && d[1].abs() <= tiny {
        0.
    } else {
        d[1].atan2(d[0])
    };
    let p = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let beta = -d[2].atan2(p);
    let (sa, ca, sb, cb) = (alpha.sin(), alpha.cos(), beta.sin(), beta.cos());
    Ok((
        [
            [cb * ca, cb * sa, -sb],
            [-sa, ca, 0.],
            [sb * ca, sb * sa, cb],
        ],
        len,
    ))
}

/// The 12×12 local stiffness (`ptka01`, φ = 0), DOFs per node u v w θx θy θz.
pub fn local_stiffness(material: &Elastic, s: &BeamSection, len: f64) -> DMatrix<f64> {
    let e = material.e;
    let g = e / (2. * (1. + material.nu));
    let (l, l2, l3) = (len, len * len, len * len * len);
    let mut k = DMatrix::zeros(12, 12);
    let mut set = |i: usize, j: usize, v: f64| {
        k[(i, j)] = v;
        k[(j, i)] = v;
    };
    let ea = e * s.area / l;
    set(0, 0, ea);
    set(0, 6, -ea);
    set(6, 6, ea);
    // Bending in (x, y): v, θz with Iz.
    let eiz = e * s.iz;
    set(1, 1, 12. * eiz / l3);
    set(1, 5, 6. * eiz / l2);
    set(1, 7, -12. * eiz / l3);
    set(1, 11, 6. * eiz / l2);
    set(5, 5, 4. * eiz / l);
    set(5, 7, -6. * eiz / l2);
    set(5, 11, 2. * eiz / l);
    set(7, 7, 12. * eiz / l3);
    set(7, 11, -6. * eiz / l2);
    set(11, 11, 4. * eiz / l);
    // Bending in (x, z): w, θy with Iy.
    let eiy = e * s.iy;
    set(2, 2, 12. * eiy / l3);
    set(2, 4, -6. * eiy / l2);
    set(2, 8, -12. * eiy / l3);
    set(2, 10, -6. * eiy / l2);
    set(4, 4, 4. * eiy / l);
    set(4, 8, 6. * eiy / l2);
    set(4, 10, 2. * eiy / l);
    set(8, 8, 12. * eiy / l3);
    set(8, 10, 6. * eiy / l2);
    set(10, 10, 4. * eiy / l);
    // Torsion.
    let gj = g * s.jx / l;
    set(3, 3, gj);
    set(3, 9, -gj);
    set(9, 9, gj);
    k
}

/// The 12×12 local mass (`ptma01` for POU_D_E, constant section, no
/// offset), DOFs per node u v w θx θy θz: consistent (`lumped = false`,
/// `MASS_MECA`) or diagonal (`MASS_MECA_DIAG`).
pub fn local_mass(rho: f64, s: &BeamSection, len: f64, lumped: bool) -> DMatrix<f64> {
    let l = len;
    let zcont = rho * s.area * l;
    let mut m = DMatrix::zeros(12, 12);
    if lumped {
        let half = zcont / 2.;
        let torsion = rho * l * (s.iy + s.iz) / 2.;
        let c = zcont * l * l / 105.;
        for node in 0..2 {
            let o = 6 * node;
            for k in 0..3 {
                m[(o + k, o + k)] = half;
            }
            m[(o + 3, o + 3)] = torsion;
            m[(o + 4, o + 4)] = c + rho * 2. * s.iy * l / 15.;
            m[(o + 5, o + 5)] = c + rho * 2. * s.iz * l / 15.;
        }
        return m;
    }
    let mut set = |i: usize, j: usize, v: f64| {
        m[(i, j)] = v;
        m[(j, i)] = v;
    };
    set(0, 0, zcont / 3.);
    set(0, 6, zcont / 6.);
    set(6, 6, zcont / 3.);
    let (a, b, c, d) = (13. / 35., 11. * l / 210., 9. / 70., 13. * l / 420.);
    let (e, f) = (l * l / 105., l * l / 140.);
    // Plane (x, y): v, θz.
    set(1, 1, zcont * a);
    set(1, 5, zcont * b);
    set(1, 7, zcont * c);
    set(1, 11, -zcont * d);
    set(5, 5, zcont * e);
    set(5, 7, zcont * d);
    set(5, 11, -zcont * f);
    set(7, 7, zcont * a);
    set(7, 11, -zcont * b);
    set(11, 11, zcont * e);
    // Plane (x, z): w, θy (the coupling signs of the stiffness).
    set(2, 2, zcont * a);
    set(2, 4, -zcont * b);
    set(2, 8, zcont * c);
    set(2, 10, zcont * d);
    set(4, 4, zcont * e);
    set(4, 8, -zcont * d);
    set(4, 10, -zcont * f);
    set(8, 8, zcont * a);
    set(8, 10, zcont * b);
    set(10, 10, zcont * e);
    // Torsion: the polar moment Iy + Iz.
    let t = rho * l * (s.iy + s.iz) / 3.;
    set(3, 3, t);
    set(3, 9, t / 2.);
    set(9, 9, t);
    m
}

/// The global mass of a beam of density `rho`, node-major DX DY DZ DRX
/// DRY DRZ ([`local_mass`] turned by the beam's frame).
pub fn mass(
    xyz: &[[f64; 3]; 2],
    rho: f64,
    section: &BeamSection,
    lumped: bool,
) -> Result<DMatrix<f64>, String> {
    section.check()?;
    let (pgl, len) = frame(xyz[0], xyz[1])?;
    let r = rotation(&pgl);
    Ok(r.transpose() * local_mass(rho, section, len, lumped) * r)
}

/// The 12×12 global→local rotation: `pgl` on each 3-block.
fn rotation(pgl: &[[f64; 3]; 3]) -> DMatrix<f64> {
    let mut r = DMatrix::zeros(12, 12);
    for blk in 0..4 {
        for i in 0..3 {
            for j in 0..3 {
                r[(3 * blk + i, 3 * blk + j)] = pgl[i][j];
            }
        }
    }
    r
}

/// The global stiffness, node-major DX DY DZ DRX DRY DRZ.
pub fn stiffness(
    xyz: &[[f64; 3]; 2],
    material: &Elastic,
    section: &BeamSection,
) -> Result<DMatrix<f64>, String> {
    section.check()?;
    let (pgl, len) = frame(xyz[0], xyz[1])?;
    let r = rotation(&pgl);
    Ok(r.transpose() * local_stiffness(material, section, len) * r)
}

/// Generalised efforts at the two nodes (`EFGE_ELNO`), in the local frame:
/// N VY VZ MT MFY MFZ, from the element's global displacements `ue`
/// (node-major, six per node).
pub fn efforts(
    xyz: &[[f64; 3]; 2],
    material: &Elastic,
    section: &BeamSection,
    ue: &[f64],
) -> Result<[[f64; 6]; 2], String> {
    if ue.len() != 12 {
        return Err(format!("a beam has 12 DOFs, got {}", ue.len()));
    }
    section.check()?;
    let (pgl, len) = frame(xyz[0], xyz[1])?;
    let r = rotation(&pgl);
    let ul = &r * DVector::from_column_slice(ue);
    let f = local_stiffness(material, section, len) * ul;
    let mut out = [[0.; 6]; 2];
    for c in 0..6 {
        out[0][c] = -f[c];
        out[1][c] = f[6 + c];
    }
    Ok(out)
}

/// Generalised strains at the two nodes of a POU_D_E beam, in its local
/// frame (code_aster's `DEGE_ELNO`, `te0158`): `jpd1ff`'s operator (φy =
/// φz = 0) at the three Gauss points ξ = −√0.6, 0, √0.6 of the RIGI family,
/// then the quadratic through them evaluated at the nodes (ξ = ∓1, i.e.
/// ∓√(5/3) in the points' scale). EPXX = du/dx, GAXY = GAXZ = 0 (no
/// shear strain in Euler–Bernoulli's kinematics), GAT = dθx/dx, KY =
/// dθy/dx, KZ = dθz/dx.
pub fn generalised_strains(xyz: &[[f64; 3]; 2], ue: &[f64]) -> Result<[[f64; 6]; 2], String> {
    if ue.len() != 12 {
        return Err(format!("a beam has 12 DOFs, got {}", ue.len()));
    }
    let (pgl, len) = frame(xyz[0], xyz[1])?;
    let ul = rotation(&pgl) * DVector::from_column_slice(ue);
    let a = 0.5 * len;
    let s = 0.6f64.sqrt();
    let mut dege = [[0.; 6]; 3];
    for (kp, k) in [-s, 0., s].into_iter().enumerate() {
        // jpd1ff with dy = dz = 1 (0-based columns).
        let mut b = [[0.; 12]; 6];
        b[0][0] = -0.5 / a;
        b[0][6] = 0.5 / a;
        b[1][1] = (3. * k * k - 3.) / (4. * a) - 3. * (k * k - 1.) / (4. * a);
        b[1][5] = (3. * k * k - 2. * k - 1.) / 4. - (3. * (k * k - 1.) + 2. * (1. - k)) / 4.;
        b[1][7] = -b[1][1];
        b[1][11] = (3. * k * k + 2. * k - 1.) / 4. - (3. * (k * k - 1.) + 2. * (1. + k)) / 4.;
        b[2][2] = b[1][1];
        b[2][4] = -b[1][5];
        b[2][8] = -b[2][2];
        b[2][10] = -b[1][11];
        b[3][3] = -0.5 / a;
        b[3][9] = 0.5 / a;
        b[4][2] = -(6. * k) / (4. * a * a);
        b[4][4] = (6. * k - 2.) / (4. * a);
        b[4][8] = -b[4][2];
        b[4][10] = (6. * k + 2.) / (4. * a);
        b[5][1] = (6. * k) / (4. * a * a);
        b[5][5] = (6. * k - 2.) / (4. * a);
        b[5][7] = -b[5][1];
        b[5][11] = (6. * k + 2.) / (4. * a);
        for (i, row) in b.iter().enumerate() {
            dege[kp][i] = (0..12).map(|j| row[j] * ul[j]).sum();
        }
    }
    let mut out = [[0.; 6]; 2];
    for (node, ksi) in [-(5f64 / 3.).sqrt(), (5f64 / 3.).sqrt()]
        .into_iter()
        .enumerate()
    {
        let l = [ksi * (ksi - 1.) / 2., 1. - ksi * ksi, ksi * (ksi + 1.) / 2.];
        for i in 0..6 {
            out[node][i] = (0..3).map(|kp| dege[kp][i] * l[kp]).sum();
        }
    }
    Ok(out)
}

/// Names of the components of [`generalised_strains`] (`DEGE_ELNO`).
pub const STRAIN_NAMES: [&str; 6] = ["EPXX", "GAXY", "GAXZ", "GAT", "KY", "KZ"];

/// Names of the components of [`efforts`].
pub const EFFORT_NAMES: [&str; 6] = ["N", "VY", "VZ", "MT", "MFY", "MFZ"];

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Elastic {
        Elastic::new(2e11, 0.3).unwrap()
    }

    #[test]
    fn cantilever_tip_load_matches_closed_form() {
        // Clamped at node 1, a force P along global Z at node 2 of a beam
        // along X: w = PL³/3EI, θy = −PL²/2EI (θy turns z into x).
        let s = BeamSection::rectangle(0.1, 0.05, None);
        let (l, p) = (2.0, 1000.0);
        let k = stiffness(&[[0., 0., 0.], [l, 0., 0.]], &steel(), &s).unwrap();
        let kf = k.view((6, 6), (6, 6)).into_owned();
        let mut f = DVector::zeros(6);
        f[2] = p;
        let u = kf.lu().solve(&f).unwrap();
        let ei = 2e11 * s.iy;
        assert!((u[2] - p * l.powi(3) / (3. * ei)).abs() < 1e-12 * u[2].abs().max(1.));
        assert!((u[4] + p * l * l / (2. * ei)).abs() < 1e-9 * u[4].abs());
    }

    #[test]
    fn vertical_beam_frame_is_code_aster_s() {
        let (pgl, len) = frame([0., 0., 1.], [0., 0., 0.]).unwrap();
        assert_eq!(len, 1.);
        // x down, y = global Y, z = global X (β = π/2).
        assert!((pgl[0][2] + 1.).abs() < 1e-15);
        assert!((pgl[1][1] - 1.).abs() < 1e-15);
        assert!((pgl[2][0] - 1.).abs() < 1e-15);
    }
}
