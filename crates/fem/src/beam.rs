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
/// local z), torsion constant Jx, and the shear coefficients of a
/// Timoshenko beam.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BeamSection {
    pub area: f64,
    pub iy: f64,
    pub iz: f64,
    pub jx: f64,
    /// code_aster's shear coefficients `AY`, `AZ` (the shear areas are
    /// A/AY along local y and A/AZ along local z) of a Timoshenko beam
    /// (`POU_D_T`, `ptka01` with φ ≠ 0); `None`: Euler–Bernoulli's
    /// kinematics (`POU_D_E`, no shear strain).
    pub shear: Option<[f64; 2]>,
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
            shear: None,
        }
    }

    /// code_aster's shear coefficient of a tube (`affgen` → `coecis`'s
    /// function of α = Ri/Re, linear between its points: 1.16667 for a
    /// solid circle … 2 for a thin tube), the same along y and z.
    pub fn circle_shear(r: f64, ep: f64) -> [f64; 2] {
        let c = interpolate(&CIRCLE_ALPHA, &CIRCLE_SHEAR, ((r - ep) / r).clamp(0., 1.));
        [c, c]
    }

    /// code_aster's shear coefficients of a rectangle (`affgen`): 1.2 for
    /// a solid one; for a hollow one `coecis`'s table interpolated at
    /// (α, β) = ((HY−2EPY)/HY, (HZ−2EPZ)/HZ) for AY and at (β, α) for AZ
    /// (linear in both; code_aster stops when α or β exceeds 0.95).
    pub fn rectangle_shear(
        hy: f64,
        hz: f64,
        walls: Option<(f64, f64)>,
    ) -> Result<[f64; 2], String> {
        let (epy, epz) = walls.unwrap_or((hy / 2., hz / 2.));
        let (hyi, hzi) = (hy - 2. * epy, hz - 2. * epz);
        let eps = 1e-3;
        if (hyi / hy).abs() <= eps || (hzi / hz).abs() <= eps {
            return Ok([1.2, 1.2]);
        }
        let (alpha, beta) = (hyi / hy, hzi / hz);
        if !(0. ..=0.95).contains(&alpha) || !(0. ..=0.95).contains(&beta) {
            return Err(format!(
                "hollow RECTANGLE with (HY-2EPY)/HY = {alpha} and (HZ-2EPZ)/HZ = {beta}: code_aster's shear coefficients are tabulated for ratios up to 0.95 (MODELISA10_15)"
            ));
        }
        Ok([rectangle_table(alpha, beta), rectangle_table(beta, alpha)])
    }

    /// This section as an Euler–Bernoulli beam's (no shear coefficients).
    pub fn euler(self) -> BeamSection {
        BeamSection {
            shear: None,
            ..self
        }
    }

    /// The shear factors (φy, φz) = (12·E·Iz·AY/(G·A·L²), 12·E·Iy·AZ/(G·A·L²))
    /// of `ptka01`/`ptma01` (zero for an Euler–Bernoulli beam).
    pub fn phi(&self, material: &Elastic, len: f64) -> (f64, f64) {
        let Some([ay, az]) = self.shear else {
            return (0., 0.);
        };
        let g = material.e / (2. * (1. + material.nu));
        let c = 12. * material.e / (g * self.area * len * len);
        (c * self.iz * ay, c * self.iy * az)
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
        BeamSection {
            area,
            iy,
            iz,
            jx,
            shear: None,
        }
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
        if let Some([ay, az]) = self.shear {
            if !(ay.is_finite() && ay > 0. && az.is_finite() && az > 0.) {
                return Err(format!(
                    "beam section has AY = {ay}, AZ = {az}: the shear coefficients must be positive"
                ));
            }
        }
        Ok(())
    }
}

/// `coecis`'s points of the tube's shear coefficient: α = Ri/Re.
const CIRCLE_ALPHA: [f64; 14] = [
    0., 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99, 1.,
];
const CIRCLE_SHEAR: [f64; 14] = [
    1.16667, 1.17442, 1.19877, 1.28947, 1.41882, 1.56277, 1.69984, 1.81536, 1.90233, 1.95983,
    1.99081, 1.99781, 1.99992, 2.,
];

/// `coecis`'s abscissae of the hollow rectangle's table, in both α and β.
const RECT_RATIO: [f64; 12] = [0., 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95];

/// `coecis`'s table: a row per α (the nappe's parameter), a column per β.
const RECT_SHEAR: [[f64; 12]; 12] = [
    [1.2; 12],
    [
        1.2, 1.2091, 1.22903, 1.29961, 1.41338, 1.57689, 1.80293, 2.11482, 2.56072, 3.26505,
        4.71451, 6.68937,
    ],
    [
        1.2, 1.21234, 1.23638, 1.31674, 1.44242, 1.62077, 1.86614, 2.20702, 2.70395, 3.51953,
        5.35808, 8.19368,
    ],
    [
        1.2, 1.21725, 1.24671, 1.3388, 1.47742, 1.67093, 1.93642, 2.30888, 2.8664, 3.82993,
        6.21611, 10.2937,
    ],
    [
        1.2, 1.22028, 1.25225, 1.34797, 1.48853, 1.6827, 1.9487, 2.32387, 2.89403, 3.90732,
        6.53601, 11.2361,
    ],
    [
        1.2, 1.22125, 1.25299, 1.34528, 1.47872, 1.66196, 1.91269, 2.26723, 2.81021, 3.79004,
        6.40058, 11.1893,
    ],
    [
        1.2, 1.22011, 1.24905, 1.33181, 1.45075, 1.61403, 1.83775, 2.1543, 2.64029, 3.52423,
        5.91643, 10.3749,
    ],
    [
        1.2, 1.21699, 1.24091, 1.30911, 1.40786, 1.54462, 1.73307, 2.00002, 2.40936, 3.15426,
        5.18602, 9.01404,
    ],
    [
        1.2, 1.21234, 1.22963, 1.27969, 1.35418, 1.45982, 1.60759, 1.81808, 2.13953, 2.71977,
        4.29975, 7.29574,
    ],
    [
        1.2, 1.20699, 1.21695, 1.24713, 1.29483, 1.36597, 1.46914, 1.61905, 1.84773, 2.25238,
        3.33064, 5.37206,
    ],
    [
        1.2, 1.20223, 1.20561, 1.21707, 1.23759, 1.27159, 1.3254, 1.40907, 1.54135, 1.77105,
        2.33808, 3.36741,
    ],
    [
        1.2, 1.20064, 1.20171, 1.20582, 1.2142, 1.22956, 1.25619, 1.30111, 1.37761, 1.51661,
        1.84134, 2.37116,
    ],
];

/// Linear interpolation in a table of increasing abscissae `xs` (`x` in
/// their range).
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let k = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1);
    let (x0, x1) = (xs[k - 1], xs[k]);
    ys[k - 1] + (ys[k] - ys[k - 1]) * (x - x0) / (x1 - x0)
}

/// `fointe` on `coecis`'s nappe: linear in α between the rows, each row
/// linear in β.
fn rectangle_table(alpha: f64, beta: f64) -> f64 {
    let row = |k: usize| interpolate(&RECT_RATIO, &RECT_SHEAR[k], beta);
    let k = RECT_RATIO
        .partition_point(|&v| v <= alpha)
        .clamp(1, RECT_RATIO.len() - 1);
    let (a0, a1) = (RECT_RATIO[k - 1], RECT_RATIO[k]);
    row(k - 1) + (row(k) - row(k - 1)) * (alpha - a0) / (a1 - a0)
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

/// The 12×12 local stiffness (`ptka01` without offset), DOFs per node u v
/// w θx θy θz: with the shear factors φ of [`BeamSection::phi`] (φ = 0 for
/// an Euler–Bernoulli beam) the bending blocks are 12EI/((1+φ)L³),
/// 6EI/((1+φ)L²), (4+φ)EI/((1+φ)L), (2−φ)EI/((1+φ)L).
pub fn local_stiffness(material: &Elastic, s: &BeamSection, len: f64) -> DMatrix<f64> {
    let e = material.e;
    let g = e / (2. * (1. + material.nu));
    let (phiy, phiz) = s.phi(material, len);
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
    // Bending in (x, y): v, θz with Iz and φy.
    let eiz = e * s.iz / (1. + phiy);
    set(1, 1, 12. * eiz / l3);
    set(1, 5, 6. * eiz / l2);
    set(1, 7, -12. * eiz / l3);
    set(1, 11, 6. * eiz / l2);
    set(5, 5, (4. + phiy) * eiz / l);
    set(5, 7, -6. * eiz / l2);
    set(5, 11, (2. - phiy) * eiz / l);
    set(7, 7, 12. * eiz / l3);
    set(7, 11, -6. * eiz / l2);
    set(11, 11, (4. + phiy) * eiz / l);
    // Bending in (x, z): w, θy with Iy and φz.
    let eiy = e * s.iy / (1. + phiz);
    set(2, 2, 12. * eiy / l3);
    set(2, 4, -6. * eiy / l2);
    set(2, 8, -12. * eiy / l3);
    set(2, 10, -6. * eiy / l2);
    set(4, 4, (4. + phiz) * eiy / l);
    set(4, 8, 6. * eiy / l2);
    set(4, 10, (2. - phiz) * eiy / l);
    set(8, 8, 12. * eiy / l3);
    set(8, 10, 6. * eiy / l2);
    set(10, 10, (4. + phiz) * eiy / l);
    // Torsion.
    let gj = g * s.jx / l;
    set(3, 3, gj);
    set(3, 9, -gj);
    set(9, 9, gj);
    k
}

/// The 12×12 local mass (`ptma01`, constant section, no offset), DOFs
/// per node u v w θx θy θz: consistent (`lumped = false`, `MASS_MECA`) or
/// diagonal (`MASS_MECA_DIAG`). The consistent bending blocks are
/// `ptma01`'s with the shear factors φ and the rotary inertia I/(A·L²) of
/// a Timoshenko beam; for an Euler–Bernoulli beam (`pomass` sets AY = AZ
/// = 0 for POU_D_E) `ptma01` takes φ = 0 **and** I = 0: the cubic
/// Hermite blocks without rotary inertia.
pub fn local_mass(
    rho: f64,
    material: &Elastic,
    s: &BeamSection,
    len: f64,
    lumped: bool,
) -> DMatrix<f64> {
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
    let (phiy, phiz) = s.phi(material, l);
    let (iy, iz) = if s.shear.is_some() {
        (s.iy, s.iz)
    } else {
        (0., 0.)
    };
    let l2 = l * l;
    // ptma01's bending block of one plane: (m_vv, m_vθ, m_vv', m_vθ',
    // m_θθ, m_θθ') with φ and r = I/(A·L²).
    let block = |phi: f64, r: f64| {
        let c = zcont / (1. + phi).powi(2);
        let p2 = phi * phi;
        [
            c * (13. / 35. + phi * 7. / 10. + p2 / 3. + r * 6. / 5.),
            c * l * (11. / 210. + phi * 11. / 120. + p2 / 24. + r / 10. - phi * r / 2.),
            c * (9. / 70. + phi * 3. / 10. + p2 / 6. - r * 6. / 5.),
            c * l * (-13. / 420. - phi * 3. / 40. - p2 / 24. + r / 10. - phi * r / 2.),
            c * l2 * (1. / 105. + phi / 60. + p2 / 120. + r * (2. / 15. + phi / 6. + p2 / 3.)),
            c * l2 * (-1. / 140. - phi / 60. - p2 / 120. - r * (1. / 30. + phi / 6. - p2 / 6.)),
        ]
    };
    // Plane (x, y): v, θz with φy and Iz.
    let [a, b, c, d, e, f] = block(phiy, iz / (s.area * l2));
    set(1, 1, a);
    set(1, 5, b);
    set(1, 7, c);
    set(1, 11, d);
    set(5, 5, e);
    set(5, 7, -d);
    set(5, 11, f);
    set(7, 7, a);
    set(7, 11, -b);
    set(11, 11, e);
    // Plane (x, z): w, θy with φz and Iy (the coupling signs of the
    // stiffness).
    let [a, b, c, d, e, f] = block(phiz, iy / (s.area * l2));
    set(2, 2, a);
    set(2, 4, -b);
    set(2, 8, c);
    set(2, 10, -d);
    set(4, 4, e);
    set(4, 8, d);
    set(4, 10, f);
    set(8, 8, a);
    set(8, 10, b);
    set(10, 10, e);
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
    material: &Elastic,
    section: &BeamSection,
    lumped: bool,
) -> Result<DMatrix<f64>, String> {
    section.check()?;
    let (pgl, len) = frame(xyz[0], xyz[1])?;
    let r = rotation(&pgl);
    Ok(r.transpose() * local_mass(rho, material, section, len, lumped) * r)
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

/// Generalised strains at the two nodes of a beam, in its local frame
/// (code_aster's `DEGE_ELNO`, `te0158`): `jpd1ff`'s operator (with the
/// shear factors φ of a Timoshenko beam, d = 1/(1+φ); φ = 0 for POU_D_E)
/// at the three Gauss points ξ = −√0.6, 0, √0.6 of the RIGI family, then
/// the quadratic through them evaluated at the nodes (ξ = ∓1, i.e. ∓√(5/3)
/// in the points' scale). EPXX = du/dx, GAXY, GAXZ the shear strains (zero
/// in Euler–Bernoulli's kinematics), GAT = dθx/dx, KY = dθy/dx, KZ =
/// dθz/dx.
pub fn generalised_strains(
    xyz: &[[f64; 3]; 2],
    material: &Elastic,
    section: &BeamSection,
    ue: &[f64],
) -> Result<[[f64; 6]; 2], String> {
    if ue.len() != 12 {
        return Err(format!("a beam has 12 DOFs, got {}", ue.len()));
    }
    let (pgl, len) = frame(xyz[0], xyz[1])?;
    let ul = rotation(&pgl) * DVector::from_column_slice(ue);
    let (phiy, phiz) = section.phi(material, len);
    let (dy, dz) = (1. / (1. + phiy), 1. / (1. + phiz));
    let a = 0.5 * len;
    let s = 0.6f64.sqrt();
    let mut dege = [[0.; 6]; 3];
    for (kp, k) in [-s, 0., s].into_iter().enumerate() {
        // jpd1ff (0-based columns).
        let mut b = [[0.; 12]; 6];
        let k2 = k * k;
        b[0][0] = -0.5 / a;
        b[0][6] = 0.5 / a;
        b[1][1] = (3. * dy * k2 - 2. - dy) / (4. * a) - 3. * dy * (k2 - 1.) / (4. * a);
        b[1][5] = (3. * dy * k2 - 2. * k - dy) / 4. - (3. * dy * (k2 - 1.) + 2. * (1. - k)) / 4.;
        b[1][7] = -b[1][1];
        b[1][11] = (3. * dy * k2 + 2. * k - dy) / 4. - (3. * dy * (k2 - 1.) + 2. * (1. + k)) / 4.;
        b[2][2] = (3. * dz * k2 - 2. - dz) / (4. * a) - 3. * dz * (k2 - 1.) / (4. * a);
        b[2][4] = -(3. * dz * k2 - 2. * k - dz) / 4. + (3. * dz * (k2 - 1.) + 2. * (1. - k)) / 4.;
        b[2][8] = -b[2][2];
        b[2][10] = -(3. * dz * k2 + 2. * k - dz) / 4. + (3. * dz * (k2 - 1.) + 2. * (1. + k)) / 4.;
        b[3][3] = -0.5 / a;
        b[3][9] = 0.5 / a;
        b[4][2] = -(6. * dz * k) / (4. * a * a);
        b[4][4] = (6. * dz * k - 2.) / (4. * a);
        b[4][8] = -b[4][2];
        b[4][10] = (6. * dz * k + 2.) / (4. * a);
        b[5][1] = (6. * dy * k) / (4. * a * a);
        b[5][5] = (6. * dy * k - 2.) / (4. * a);
        b[5][7] = -b[5][1];
        b[5][11] = (6. * dy * k + 2.) / (4. * a);
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
    fn timoshenko_cantilever_adds_the_shear_deflection() {
        // A tip force P along local y: v = PL³/3EIz + P·L·AY/(G·A), the
        // rotation PL²/2EIz unchanged (ptka01 with φy is exact for it).
        let s = BeamSection {
            shear: Some([1.2, 1.5]),
            ..BeamSection::rectangle(0.1, 0.05, None)
        };
        let (l, p) = (0.5, 1000.0);
        let k = stiffness(&[[0., 0., 0.], [l, 0., 0.]], &steel(), &s).unwrap();
        let kf = k.view((6, 6), (6, 6)).into_owned();
        let mut f = DVector::zeros(6);
        f[1] = p;
        f[2] = p;
        let u = kf.lu().solve(&f).unwrap();
        let g = 2e11 / 2.6;
        let v = p * l.powi(3) / (3. * 2e11 * s.iz) + p * l * 1.2 / (g * s.area);
        let w = p * l.powi(3) / (3. * 2e11 * s.iy) + p * l * 1.5 / (g * s.area);
        assert!((u[1] - v).abs() < 1e-12 * v, "{} vs {v}", u[1]);
        assert!((u[2] - w).abs() < 1e-12 * w, "{} vs {w}", u[2]);
        assert!((u[5] - p * l * l / (2. * 2e11 * s.iz)).abs() < 1e-9 * u[5].abs());
        // The Euler-Bernoulli section of it has no shear term.
        let k = stiffness(&[[0., 0., 0.], [l, 0., 0.]], &steel(), &s.euler()).unwrap();
        let u = k.view((6, 6), (6, 6)).into_owned().lu().solve(&f).unwrap();
        assert!((u[1] - p * l.powi(3) / (3. * 2e11 * s.iz)).abs() < 1e-12 * u[1]);
    }

    #[test]
    fn shear_coefficients_are_code_aster_s_tables() {
        // Solid sections: 1.2 for a rectangle, 1.16667 for a circle.
        assert_eq!(
            BeamSection::rectangle_shear(0.1, 0.05, None).unwrap(),
            [1.2, 1.2]
        );
        assert_eq!(BeamSection::circle_shear(0.05, 0.05), [1.16667; 2]);
        // A tube with Ri/Re = 0.75: halfway between 0.7 and 0.8.
        let [c, _] = BeamSection::circle_shear(0.05, 0.0125);
        assert!((c - (1.90233 + 1.95983) / 2.).abs() < 1e-12);
        // Hollow: AY at (α, β) = (0.8, 0.75), AZ at (0.75, 0.8).
        let [ay, az] = BeamSection::rectangle_shear(0.1, 0.08, Some((0.01, 0.01))).unwrap();
        assert!((ay - (1.84773 + 2.25238) / 2.).abs() < 1e-12, "{ay}");
        assert!((az - (2.71977 + 2.25238) / 2.).abs() < 1e-12, "{az}");
        // Thin walls beyond the table: code_aster stops (MODELISA10_15).
        assert!(BeamSection::rectangle_shear(0.1, 0.1, Some((0.001, 0.001))).is_err());
    }

    #[test]
    fn timoshenko_mass_has_rotary_inertia_and_the_same_translation_mass() {
        let s = BeamSection {
            shear: Some([1.2, 1.2]),
            ..BeamSection::rectangle(0.1, 0.05, None)
        };
        let (rho, l) = (7800., 0.5);
        let mt = local_mass(rho, &steel(), &s, l, false);
        let me = local_mass(rho, &steel(), &s.euler(), l, false);
        // A translation along y carries ρAL in both.
        let mut v = DVector::zeros(12);
        v[1] = 1.;
        v[7] = 1.;
        let total = rho * s.area * l;
        assert!(((v.transpose() * &mt * &v)[(0, 0)] - total).abs() < 1e-9 * total);
        assert!(((v.transpose() * &me * &v)[(0, 0)] - total).abs() < 1e-9 * total);
        // A uniform rotation of the sections θz (no deflection): ptma01's
        // θθ terms with φy and the rotary inertia Iz/(A·L²).
        let mut r = DVector::zeros(12);
        r[5] = 1.;
        r[11] = 1.;
        let rot = |m: &DMatrix<f64>| (r.transpose() * m * &r)[(0, 0)];
        let (phiy, _) = s.phi(&steel(), l);
        let c = total / (1. + phiy).powi(2);
        let zial = s.iz / (s.area * l * l);
        let e = c
            * l
            * l
            * (1. / 105.
                + phiy / 60.
                + phiy * phiy / 120.
                + zial * (2. / 15. + phiy / 6. + phiy * phiy / 3.));
        let f = c
            * l
            * l
            * (-1. / 140.
                - phiy / 60.
                - phiy * phiy / 120.
                - zial * (1. / 30. + phiy / 6. - phiy * phiy / 6.));
        assert!((rot(&mt) - 2. * (e + f)).abs() < 1e-12 * rot(&mt));
        // POU_D_E's: the Hermite blocks alone, ρAL³·2·(1/105 − 1/140).
        let hermite = 2. * total * l * l * (1. / 105. - 1. / 140.);
        assert!((rot(&me) - hermite).abs() < 1e-12 * hermite);
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
