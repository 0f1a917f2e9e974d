//! Layered plate sections (code_aster's `DEFI_COMPOSITE`, material
//! `ELAS_COQMU`) for the `DKT`, `DST` and `Q4G` facets: the homogenised
//! membrane, coupling, bending and transverse shear matrices of a stack of
//! orthotropic plies, as `op0056` computes them, turned into each facet's
//! frame as `dxmate` does, and the stresses by ply (`dxdmul`, the ply part
//! of `dktsie`/`dstsie`).
//!
//! - Each ply k (thickness eₖ, orientation θₖ from the reference direction
//!   of `AFFE_CARA_ELEM/COQUE`, `ELAS_ORTH` E_L E_T NU_LT G_LT G_LN G_TN) has
//!   the reduced plane-stress stiffness Qₖ(θₖ) (`op0056`'s q11…q33) and the
//!   transverse shear moduli Gₖ(θₖ) (g11 g22 g12; G_LN defaults to G_LT,
//!   G_TN to 10⁶·G_LT as there); zₖ is its mid-height from the
//!   mid-surface of the stack (−H/2 at the bottom of the first ply).
//! - A = Σ Qₖ eₖ, B = Σ Qₖ eₖ zₖ, D = Σ Qₖ eₖ (zₖ² + eₖ²/12) (classical
//!   laminate theory).
//! - The shear compliance `dci` is `op0056`'s c11: the shear stresses
//!   through the stack of a plate in cylindrical bending (the equilibrium
//!   of the ply stresses Qₖ Aₖ, Aₖ = Qₖ D⁻¹, integrated ply by ply with
//!   its `idi`/`ezd` sums and the x1…x4 weights), and `dc` its inverse —
//!   code_aster's shear stiffness of multilayer plates, not the 5/6·G·h of
//!   a homogeneous one.
//! - In a facet whose x axis makes the angle (c, s) with the projected
//!   reference direction (`coqrep`), A, B, D turn as T₁ᵀ·X·T₁ and the shear
//!   matrices as T₂ᵀ·X·T₂ (`dxmate`'s `t1ve`, `t2ui`).
//! - The density of the stack is Σ ρₖ eₖ / H and its thickness H
//!   (`HOM_19`, `HOM_20`, read by `dxroep` for the masses).
//!
//! Numerics only: the plies are plain values; the runner reads
//! `DEFI_COMPOSITE` and `AFFE_CARA_ELEM/COQUE`.

use nalgebra::Matrix3;

/// One ply of a stack (`DEFI_COMPOSITE/COUCHE`): its thickness, its
/// orientation in degrees from the reference direction, and its
/// `ELAS_ORTH` constants.
#[derive(Clone, Debug, PartialEq)]
pub struct Ply {
    pub thickness: f64,
    pub orientation: f64,
    pub e_l: f64,
    pub e_t: f64,
    pub nu_lt: f64,
    pub g_lt: f64,
    /// `G_LN` (code_aster's default: G_LT).
    pub g_ln: Option<f64>,
    /// `G_TN` (code_aster's default: 10⁶·G_LT).
    pub g_tn: Option<f64>,
    pub rho: Option<f64>,
}

/// A ply of a [`Laminate`] with what `op0056` stores for it (`C<i>_V<j>`).
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    pub thickness: f64,
    /// Its mid-height from the mid-surface of the stack (`ordi`).
    pub z: f64,
    /// Qₖ in the reference frame (engineering shear).
    pub q: [[f64; 3]; 3],
    /// Aₖ = Qₖ D⁻¹ (`C<i>_V16…24`).
    pub a: [[f64; 3]; 3],
}

/// A homogenised stack of plies (code_aster's `ELAS_COQMU` material).
#[derive(Clone, Debug, PartialEq)]
pub struct Laminate {
    pub layers: Vec<Layer>,
    /// Membrane A, coupling B and bending D (reference frame).
    pub dm: [[f64; 3]; 3],
    pub dmf: [[f64; 3]; 3],
    pub df: [[f64; 3]; 3],
    /// The shear compliance (`HOM_21…23`) and stiffness (`HOM_24…26`).
    pub dci: [[f64; 2]; 2],
    pub dc: [[f64; 2]; 2],
    /// The total thickness H.
    pub thickness: f64,
    /// Σ ρₖ eₖ / H when every ply has RHO; `None` when none has.
    pub density: Option<f64>,
}

fn inv2(m: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    if det.abs() < f64::MIN_POSITIVE {
        return [[0.; 2]; 2];
    }
    [
        [m[1][1] / det, -m[0][1] / det],
        [-m[1][0] / det, m[0][0] / det],
    ]
}

/// Bᵀ·A·C for 2×2 matrices (`utbtab` when B = C, `utctab` otherwise).
fn btac(b: &[[f64; 2]; 2], a: &[[f64; 2]; 2], c: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..2)
                .map(|k| (0..2).map(|l| b[k][i] * a[k][l] * c[l][j]).sum::<f64>())
                .sum()
        })
    })
}

/// Tᵀ·X·T for 3×3 matrices (`utbtab`).
fn tt3(x: &[[f64; 3]; 3], t: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..3)
                .map(|k| (0..3).map(|l| t[k][i] * x[k][l] * t[l][j]).sum::<f64>())
                .sum()
        })
    })
}

/// `da1i` of a ply from its Aₖ (`op0056`, `dxdmul`).
fn da1(a: &[[f64; 3]; 3]) -> [[f64; 2]; 2] {
    [
        [a[0][0] + a[2][2], a[0][2] + a[2][1]],
        [a[2][0] + a[1][2], a[1][1] + a[2][2]],
    ]
}

impl Laminate {
    /// The stack of `plies`, bottom first (`op0056`).
    pub fn new(plies: &[Ply]) -> Result<Laminate, String> {
        if plies.is_empty() {
            return Err("a composite needs one layer at least".into());
        }
        for (k, p) in plies.iter().enumerate() {
            let vals = [p.thickness, p.e_l, p.e_t, p.g_lt];
            if vals.iter().any(|v| !(v.is_finite() && *v > 0.)) {
                return Err(format!(
                    "layer {}: EPAIS, E_L, E_T and G_LT must be positive",
                    k + 1
                ));
            }
            if !p.nu_lt.is_finite() || p.nu_lt * p.nu_lt * p.e_t / p.e_l >= 1. {
                return Err(format!(
                    "layer {}: NU_LT² E_T/E_L must be below 1 (got NU_LT = {})",
                    k + 1,
                    p.nu_lt
                ));
            }
        }
        let with_rho = plies.iter().filter(|p| p.rho.is_some()).count();
        if with_rho != 0 && with_rho != plies.len() {
            return Err(
                "RHO is given for some layers only: give it for all of them or none (code_aster's MODELISA5_63)"
                    .into(),
            );
        }
        let total: f64 = plies.iter().map(|p| p.thickness).sum();
        let mut bottom = -0.5 * total;
        let mut dm = [[0.; 3]; 3];
        let mut dmf = [[0.; 3]; 3];
        let mut df = [[0.; 3]; 3];
        let mut rho = 0.;
        let mut layers = Vec::with_capacity(plies.len());
        let mut shear = Vec::with_capacity(plies.len());
        for p in plies {
            let (el, et, nult, glt) = (p.e_l, p.e_t, p.nu_lt, p.g_lt);
            let gln = p.g_ln.unwrap_or(glt);
            let gtn = p.g_tn.unwrap_or(1e6 * glt);
            let qll = el / (1. - nult * nult * et / el);
            let qtt = qll * et / el;
            let qlt = qtt * nult;
            let (s, c) = p.orientation.to_radians().sin_cos();
            let (c2, s2) = (c * c, s * s);
            let (c3, s3, c4, s4) = (c2 * c, s2 * s, c2 * c2, s2 * s2);
            let q11 = c4 * qll + s4 * qtt + 2. * c2 * s2 * qlt + 4. * c2 * s2 * glt;
            let q22 = s4 * qll + c4 * qtt + 2. * c2 * s2 * qlt + 4. * c2 * s2 * glt;
            let q12 = c2 * s2 * (qll + qtt - 4. * glt) + (s4 + c4) * qlt;
            let q13 = c3 * s * qll - c * s3 * qtt + (c * s3 - c3 * s) * (qlt + 2. * glt);
            let q23 = c * s3 * qll - c3 * s * qtt - (c * s3 - c3 * s) * (qlt + 2. * glt);
            let q33 = c2 * s2 * (qll + qtt - 2. * qlt) + (c2 - s2) * (c2 - s2) * glt;
            let q = [[q11, q12, q13], [q12, q22, q23], [q13, q23, q33]];
            let e = p.thickness;
            bottom += e;
            let z = bottom - 0.5 * e;
            rho += p.rho.unwrap_or(0.) * e / total;
            for i in 0..3 {
                for j in 0..3 {
                    dm[i][j] += q[i][j] * e;
                    dmf[i][j] += q[i][j] * e * z;
                    df[i][j] += q[i][j] * e * (z * z + e * e / 12.);
                }
            }
            let g = [
                [c2 * gln + s2 * gtn, c * s * (gln - gtn)],
                [c * s * (gln - gtn), s2 * gln + c2 * gtn],
            ];
            shear.push(g);
            layers.push(Layer {
                thickness: e,
                z,
                q,
                a: [[0.; 3]; 3],
            });
        }
        let hf = Matrix3::from_fn(|i, j| df[i][j]);
        let hfinv = hf
            .try_inverse()
            .ok_or("the bending stiffness of the composite is singular")?;
        // The shear compliance c11 (`op0056`).
        let mut c11 = [[0.; 2]; 2];
        let mut ezd = [[0.; 2]; 2];
        for (layer, hti) in layers.iter_mut().zip(&shear) {
            let qi = Matrix3::from_fn(|i, j| layer.q[i][j]);
            let ai = qi * hfinv;
            layer.a = std::array::from_fn(|i| std::array::from_fn(|j| ai[(i, j)]));
            let (e, z) = (layer.thickness, layer.z);
            let d = da1(&layer.a);
            let mut idi = [[0.; 2]; 2];
            for k in 0..2 {
                for j in 0..2 {
                    idi[k][j] = ezd[k][j] - (z - e / 2.).powi(2) * d[k][j] / 2.;
                    ezd[k][j] += e * z * d[k][j];
                }
            }
            let hinv = inv2(hti);
            let c1 = btac(&idi, &hinv, &idi);
            let c2 = btac(&idi, &hinv, &d);
            let c3 = btac(&d, &hinv, &idi);
            let c4 = btac(&d, &hinv, &d);
            let x1 = e / 4.;
            let x2 = (3. * z * z * e + e.powi(3) / 4.) / 24.;
            let x4 = (5. * z.powi(4) * e + 2.5 * z * z * e.powi(3) + e.powi(5) / 16.) / 80.;
            for k in 0..2 {
                for j in 0..2 {
                    c11[k][j] += x1 * c1[k][j] + x2 * c2[k][j] + x2 * c3[k][j] + x4 * c4[k][j];
                }
            }
        }
        // Only c11's 11, 22 and 12 terms are stored (`HOM_21…23`).
        let dci = [[c11[0][0], c11[0][1]], [c11[0][1], c11[1][1]]];
        let dc = inv2(&dci);
        Ok(Laminate {
            layers,
            dm,
            dmf,
            df,
            dci,
            dc,
            thickness: total,
            density: (with_rho > 0).then_some(rho),
        })
    }

    /// Whether the membrane and bending are uncoupled (B = 0, a stack
    /// symmetric about its mid-surface): `dxmate`'s `coupmf` is false.
    pub fn is_uncoupled(&self) -> bool {
        let scale = self.dm.iter().flatten().fold(0f64, |m, v| m.max(v.abs())) * self.thickness;
        // dxmate's test is |B_ij| > 1e-10 in absolute terms.
        self.dmf
            .iter()
            .flatten()
            .all(|v| v.abs() <= 1e-10_f64.max(1e-12 * scale))
    }
}

/// A layered section in the frame of one facet: the stack's matrices
/// turned by `dxmate`'s `t1ve` and `t2ui`.
#[derive(Clone, Debug, PartialEq)]
pub struct LayeredSection {
    pub laminate: std::sync::Arc<Laminate>,
    /// (c, s) of the projected reference direction in the facet (`coqrep`).
    pub cos_sin: (f64, f64),
    pub dm: [[f64; 3]; 3],
    pub df: [[f64; 3]; 3],
    pub dci: [[f64; 2]; 2],
    pub dc: [[f64; 2]; 2],
    t1ve: [[f64; 3]; 3],
}

/// The ply stresses' data at one level of a ply (`dxdmul`): the ply's
/// stiffness in the facet's frame, the shear distribution d1i, d2i and the
/// height.
pub struct PlyLevel {
    pub h: [[f64; 3]; 3],
    pub d1i: [[f64; 2]; 2],
    pub d2i: [[f64; 4]; 2],
    pub z: f64,
}

impl LayeredSection {
    /// The section of `laminate` on the facet of frame `pgl` (rows x, y,
    /// z) whose reference direction is `direction` (`coqrep`).
    pub fn new(
        laminate: std::sync::Arc<Laminate>,
        pgl: &Matrix3<f64>,
        direction: [f64; 3],
    ) -> Result<LayeredSection, String> {
        let d = nalgebra::Vector3::from(direction);
        let n = pgl.row(2).transpose();
        let proj = d - n * d.dot(&n);
        let norm = proj.norm();
        if norm <= f64::EPSILON * d.norm().max(1.0) {
            return Err(
                "a layered shell whose reference direction (ANGL_REP/VECTEUR) is normal to its plane: the plies' frame is undefined (code_aster's PLATE1_40)"
                    .into(),
            );
        }
        let proj = proj / norm;
        let c0 = pgl.row(0).transpose().dot(&proj);
        let s0 = pgl.row(1).transpose().dot(&proj);
        let c = c0 / (c0 * c0 + s0 * s0).sqrt();
        let s = s0 / (c * c + s0 * s0).sqrt();
        let t1ve = [
            [c * c, s * s, c * s],
            [s * s, c * c, -c * s],
            [-2. * c * s, 2. * c * s, c * c - s * s],
        ];
        let t2 = [[c, s], [-s, c]];
        Ok(LayeredSection {
            dm: tt3(&laminate.dm, &t1ve),
            df: tt3(&laminate.df, &t1ve),
            dci: btac(&t2, &laminate.dci, &t2),
            dc: btac(&t2, &laminate.dc, &t2),
            cos_sin: (c, s),
            t1ve,
            laminate,
        })
    }

    /// `dxdmul` for ply `layer` (0-based) at its bottom (`level` −1),
    /// middle (0) or top (1), in a section offset by `offset`
    /// (`EXCENTREMENT`): the level's height is then measured from the
    /// reference surface, x3 = z + e (the strains ε + x3·κ of the
    /// reference surface), and `dxdmul` computes the shear distribution
    /// d1i, d2i with that x3 against the plies' unshifted bottoms, as
    /// code_aster does.
    pub fn ply_level(&self, layer: usize, level: i32, offset: f64) -> Option<PlyLevel> {
        let lay = self.laminate.layers.get(layer)?;
        let x3 = lay.z + offset + f64::from(level) * lay.thickness / 2.;
        let mut d1i = [[0.; 2]; 2];
        let mut d2i = [[0.; 4]; 2];
        let mut dx1 = [[0.; 2]; 2];
        let mut dx2 = [[0.; 4]; 2];
        for l in &self.laminate.layers[..=layer] {
            let ai = tt3(&l.a, &self.t1ve);
            let da1i = da1(&ai);
            let da2i = [
                [
                    ai[0][0] - ai[2][2],
                    ai[0][2] - ai[2][1],
                    ai[0][1] * 2.,
                    ai[2][0] * 2.,
                ],
                [
                    ai[2][0] - ai[1][2],
                    ai[2][2] - ai[1][1],
                    ai[2][1] * 2.,
                    ai[1][0] * 2.,
                ],
            ];
            let f = ((l.z - l.thickness / 2.).powi(2) - x3 * x3) / 4.;
            for k in 0..2 {
                for j in 0..2 {
                    d1i[k][j] = dx1[k][j] + f * da1i[k][j];
                    dx1[k][j] -= l.thickness * l.z * da1i[k][j] / 2.;
                }
                for j in 0..4 {
                    d2i[k][j] = dx2[k][j] + f * da2i[k][j];
                    dx2[k][j] -= l.thickness * l.z * da2i[k][j] / 2.;
                }
            }
        }
        Some(PlyLevel {
            h: tt3(&lay.q, &self.t1ve),
            d1i,
            d2i,
            z: x3,
        })
    }
}

/// `dsxhlt`: the operator of the bending moments' second derivatives
/// (`lambda`) on the curvature derivatives, with the facet's inverse
/// Jacobian `vj` (carat3(9…12)).
pub(crate) fn dsxhlt(df: &[[f64; 3]; 3], vj: [f64; 4]) -> [[f64; 6]; 4] {
    let hl = [
        [
            df[0][0],
            -df[2][2],
            0.,
            df[0][2],
            -df[1][2],
            df[0][1] - df[2][2],
        ],
        [
            df[0][2],
            -df[1][2],
            df[2][2] - df[0][1],
            df[2][2],
            -df[1][1],
            0.,
        ],
        [df[0][1], 0., df[1][2], df[1][2], 0., df[1][1]],
        [0., df[0][2], df[0][0], 0., df[0][1], df[0][2]],
    ];
    let [v11, v12, v21, v22] = vj;
    let t2 = [
        [v11 * v11, v12 * v12, 2. * v11 * v12],
        [v21 * v21, v22 * v22, 2. * v21 * v22],
        [v11 * v21, v12 * v22, v11 * v22 + v12 * v21],
    ];
    let mut out = [[0.; 6]; 4];
    for i in 0..4 {
        for j in 0..3 {
            for k in 0..3 {
                out[i][j] += hl[i][k] * t2[k][j];
                out[i][j + 3] += hl[i][k + 3] * t2[k][j];
            }
        }
    }
    out
}
