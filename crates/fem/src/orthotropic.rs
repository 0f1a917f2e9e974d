//! Orthotropic linear elasticity (`DEFI_MATERIAU/ELAS_ORTH`) in a material
//! frame (L, T, N) given by nautical angles (`AFFE_CARA_ELEM/MASSIF`).
//!
//! As code_aster: the stiffness in the material frame is
//! `separ_RI_elas_3D` (3D, D_PLAN, AXIS: the 3D matrix, restricted to
//! xx yy zz xy in 2D with the shear G_LT) or `separ_RI_elas_cp` (C_PLAN:
//! the plane-stress one of E_L, E_T, NU_LT, G_LT); it is turned to the
//! global axes as `matrHooke3d` (D = Tᵀ D_LTN T, T of `dpassa` from
//! `matrot`'s rotation) or, in 2D, `matrHookePlaneStrain` /
//! `matrHookePlaneStress` (`dpao2d`: the first angle α alone, about z).
//! Engineering shear strains throughout (the shears' rows and columns hold
//! G_LT, G_LN, G_TN for xy, xz, yz).

use crate::error::FemError;
use crate::material::Hypothesis;
use nalgebra::DMatrix;

/// An orthotropic elastic material and its frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orthotropic {
    pub e_l: f64,
    pub e_t: f64,
    pub e_n: f64,
    pub g_lt: f64,
    pub g_ln: f64,
    pub g_tn: f64,
    pub nu_lt: f64,
    pub nu_ln: f64,
    pub nu_tn: f64,
    /// Nautical angles α, β, γ (radians) of the material frame (L, T, N)
    /// in the global axes (`matrot`); zero: the global frame.
    pub angles: [f64; 3],
}

impl Orthotropic {
    /// Checks the moduli (positive, finite), the Poisson ratios (finite)
    /// and that the compliance is positive definite.
    pub fn validate(self) -> Result<Orthotropic, FemError> {
        let named = [
            ("E_L", self.e_l),
            ("E_T", self.e_t),
            ("E_N", self.e_n),
            ("G_LT", self.g_lt),
            ("G_LN", self.g_ln),
            ("G_TN", self.g_tn),
        ];
        for (name, v) in named {
            if !(v.is_finite() && v > 0.) {
                return Err(FemError::Model(format!(
                    "ELAS_ORTH: {name} must be positive and finite, got {v}"
                )));
            }
        }
        for (name, v) in [
            ("NU_LT", self.nu_lt),
            ("NU_LN", self.nu_ln),
            ("NU_TN", self.nu_tn),
        ] {
            if !v.is_finite() {
                return Err(FemError::Model(format!(
                    "ELAS_ORTH: {name} must be finite, got {v}"
                )));
            }
        }
        if let Some(a) = self.angles.iter().find(|a| !a.is_finite()) {
            return Err(FemError::Model(format!(
                "the material frame's angle {a} is not finite"
            )));
        }
        // The normal compliance block's leading minors: 1/E_L > 0,
        // (1 − ν_LT ν_TL)/(E_L E_T) > 0 and Δ/(E_L E_T E_N) > 0.
        let (nu21, _, _, delta) = self.ratios();
        if !(1. - self.nu_lt * nu21 > 0. && delta > 0.) {
            return Err(FemError::Model(format!(
                "ELAS_ORTH: the compliance is not positive definite (NU_LT={}, NU_LN={}, NU_TN={} with E_L={}, E_T={}, E_N={})",
                self.nu_lt, self.nu_ln, self.nu_tn, self.e_l, self.e_t, self.e_n
            )));
        }
        Ok(self)
    }

    /// ν_TL, ν_NL, ν_NT and Δ of `separ_RI_elas_3D`.
    fn ratios(&self) -> (f64, f64, f64, f64) {
        let nu21 = self.e_t * self.nu_lt / self.e_l;
        let nu31 = self.e_n * self.nu_ln / self.e_l;
        let nu32 = self.e_n * self.nu_tn / self.e_t;
        let delta = 1.
            - self.nu_tn * nu32
            - nu31 * self.nu_ln
            - nu21 * self.nu_lt
            - 2. * self.nu_tn * nu31 * self.nu_lt;
        (nu21, nu31, nu32, delta)
    }

    /// The normal block of the 3D stiffness in the material frame
    /// (`separ_RI_elas_3D`, ELAS_ORTH).
    fn normal_block(&self) -> [[f64; 3]; 3] {
        let (nu21, nu31, nu32, delta) = self.ratios();
        let (nu12, nu13, nu23) = (self.nu_lt, self.nu_ln, self.nu_tn);
        let (e1, e2, e3) = (self.e_l, self.e_t, self.e_n);
        let h1 = (1. - nu23 * nu32) * e1 / delta;
        let h2 = (nu21 + nu31 * nu23) * e1 / delta;
        let h3 = (nu31 + nu21 * nu32) * e1 / delta;
        let h4 = (1. - nu13 * nu31) * e2 / delta;
        let h5 = (nu32 + nu31 * nu12) * e2 / delta;
        let h6 = (1. - nu21 * nu12) * e3 / delta;
        [[h1, h2, h3], [h2, h4, h5], [h3, h5, h6]]
    }

    /// Hooke's matrix in the material frame (L, T, N), laid out as
    /// [`crate::Elastic::hooke`]'s: 6×6 in 3D, 4×4 in 2D (plane stress:
    /// the zz row and column zero).
    pub fn local_hooke(&self, hyp: Hypothesis) -> DMatrix<f64> {
        match hyp {
            Hypothesis::PlaneStress => {
                // separ_RI_elas_cp.
                let nu21 = self.e_t * self.nu_lt / self.e_l;
                let delta = 1. - self.nu_lt * nu21;
                let mut d = DMatrix::zeros(4, 4);
                d[(0, 0)] = self.e_l / delta;
                d[(0, 1)] = self.nu_lt * self.e_t / delta;
                d[(1, 0)] = d[(0, 1)];
                d[(1, 1)] = self.e_t / delta;
                d[(3, 3)] = self.g_lt;
                d
            }
            _ => {
                let n = hyp.ncomp();
                let h = self.normal_block();
                let mut d = DMatrix::zeros(n, n);
                for i in 0..3 {
                    for j in 0..3 {
                        d[(i, j)] = h[i][j];
                    }
                }
                let shears = [self.g_lt, self.g_ln, self.g_tn];
                for k in 3..n {
                    d[(k, k)] = shears[k - 3];
                }
                d
            }
        }
    }

    /// Hooke's matrix in the global axes: the material frame's turned by
    /// Tᵀ D T (`utbtab`); as code_aster, no rotation when the angles used
    /// are exactly zero (all three in 3D, α in 2D).
    pub fn hooke(&self, hyp: Hypothesis) -> DMatrix<f64> {
        let d = self.local_hooke(hyp);
        let t = match hyp {
            Hypothesis::Solid3D => {
                if self.angles == [0.; 3] {
                    return d;
                }
                strain_transfer_3d(&matrot(self.angles))
            }
            _ => {
                if self.angles[0] == 0. {
                    return d;
                }
                strain_transfer_2d(self.angles[0])
            }
        };
        t.transpose() * d * t
    }
}

/// code_aster's `matrot`: the rotation to the frame of nautical angles
/// α, β, γ (radians); its rows are the local axes in global coordinates.
pub fn matrot(angles: [f64; 3]) -> [[f64; 3]; 3] {
    let [a, b, g] = angles;
    let (ca, sa, cb, sb, cg, sg) = (a.cos(), a.sin(), b.cos(), b.sin(), g.cos(), g.sin());
    [
        [cb * ca, cb * sa, -sb],
        [sg * sb * ca - cg * sa, cg * ca + sg * sb * sa, sg * cb],
        [sg * sa + cg * sb * ca, cg * sb * sa - ca * sg, cg * cb],
    ]
}

/// code_aster's `angvx`: the nautical angles α, β (radians) that bring x
/// along `gx`.
pub fn angvx(gx: [f64; 3]) -> (f64, f64) {
    let tiny = f64::MIN_POSITIVE;
    let alpha = if gx[1].abs() <= tiny && gx[0].abs() <= tiny {
        0.
    } else {
        gx[1].atan2(gx[0])
    };
    let p = (gx[0] * gx[0] + gx[1] * gx[1]).sqrt();
    let beta = if gx[2].abs() <= tiny && p.abs() <= tiny {
        0.
    } else {
        -gx[2].atan2(p)
    };
    (alpha, beta)
}

/// code_aster's `angvxy`: the nautical angles (radians) of the frame whose
/// x is along `gx` and whose (x, y) plane holds `gy`.
pub fn angvxy(gx: [f64; 3], gy: [f64; 3]) -> [f64; 3] {
    let (alpha, beta) = angvx(gx);
    let r = matrot([alpha, beta, 0.]);
    let y: Vec<f64> = r
        .iter()
        .map(|row| row[0] * gy[0] + row[1] * gy[1] + row[2] * gy[2])
        .collect();
    let tiny = f64::MIN_POSITIVE;
    let gamma = if y[2].abs() <= tiny && y[1].abs() <= tiny {
        0.
    } else {
        y[2].atan2(y[1])
    };
    [alpha, beta, gamma]
}

/// code_aster's `eulnau`: the nautical angles (degrees, each in
/// [0°, 360°)) of the frame of Euler angles ψ, θ, φ (degrees; z-x-z
/// convention).
pub fn euler_to_nautical(euler: [f64; 3]) -> [f64; 3] {
    let deg = std::f64::consts::PI / 180.;
    let [psi, theta, phi] = euler.map(|a| a * deg);
    let (cphi, sphi) = (phi.cos(), phi.sin());
    let (cpsi, spsi) = (psi.cos(), psi.sin());
    let (cthe, sthe) = (theta.cos(), theta.sin());
    let x = [
        cphi * cpsi - sphi * cthe * spsi,
        cphi * spsi + sphi * cthe * cpsi,
        sphi * sthe,
    ];
    let y = [
        -sphi * cpsi - cphi * cthe * spsi,
        -sphi * spsi + cphi * cthe * cpsi,
        cphi * sthe,
    ];
    angvxy(x, y).map(|a| {
        let a = if a < 0. {
            a + 2. * std::f64::consts::PI
        } else {
            a
        };
        a / deg
    })
}

/// `dpassa`: the 6×6 map of global engineering strains (xx yy zz xy xz yz)
/// to those of the frame whose axes are the rows of `p`.
fn strain_transfer_3d(p: &[[f64; 3]; 3]) -> DMatrix<f64> {
    let mut t = DMatrix::zeros(6, 6);
    // Normal rows: ε'ᵢᵢ = Σ p_ik p_il ε_kl.
    for i in 0..3 {
        for k in 0..3 {
            t[(i, k)] = p[i][k] * p[i][k];
        }
        t[(i, 3)] = p[i][0] * p[i][1];
        t[(i, 4)] = p[i][0] * p[i][2];
        t[(i, 5)] = p[i][1] * p[i][2];
    }
    // Shear rows: γ'ᵢⱼ for (i, j) = (1, 2), (1, 3), (2, 3).
    for (row, (i, j)) in [(0usize, 1usize), (0, 2), (1, 2)].into_iter().enumerate() {
        let r = 3 + row;
        for k in 0..3 {
            t[(r, k)] = 2. * p[i][k] * p[j][k];
        }
        t[(r, 3)] = p[i][0] * p[j][1] + p[i][1] * p[j][0];
        t[(r, 4)] = p[i][0] * p[j][2] + p[i][2] * p[j][0];
        t[(r, 5)] = p[i][1] * p[j][2] + p[i][2] * p[j][1];
    }
    t
}

/// `dpao2d`: the 4×4 map of global strains (xx yy zz γxy) to those of the
/// frame turned by `alpha` about z.
fn strain_transfer_2d(alpha: f64) -> DMatrix<f64> {
    let (c, s) = (alpha.cos(), alpha.sin());
    DMatrix::from_row_slice(
        4,
        4,
        &[
            c * c,
            s * s,
            0.,
            s * c,
            s * s,
            c * c,
            0.,
            -s * c,
            0.,
            0.,
            1.,
            0.,
            -2. * c * s,
            2. * s * c,
            0.,
            c * c - s * s,
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn composite(angles: [f64; 3]) -> Orthotropic {
        Orthotropic {
            e_l: 36.17e9,
            e_t: 13.15e9,
            e_n: 11.0e9,
            g_lt: 4.06e9,
            g_ln: 3.9e9,
            g_tn: 3.8e9,
            nu_lt: 0.25,
            nu_ln: 0.28,
            nu_tn: 0.32,
            angles,
        }
        .validate()
        .unwrap()
    }

    /// The compliance in the material frame, engineering shears.
    fn compliance(o: &Orthotropic) -> DMatrix<f64> {
        let mut s = DMatrix::zeros(6, 6);
        s[(0, 0)] = 1. / o.e_l;
        s[(1, 1)] = 1. / o.e_t;
        s[(2, 2)] = 1. / o.e_n;
        s[(0, 1)] = -o.nu_lt / o.e_l;
        s[(1, 0)] = s[(0, 1)];
        s[(0, 2)] = -o.nu_ln / o.e_l;
        s[(2, 0)] = s[(0, 2)];
        s[(1, 2)] = -o.nu_tn / o.e_t;
        s[(2, 1)] = s[(1, 2)];
        s[(3, 3)] = 1. / o.g_lt;
        s[(4, 4)] = 1. / o.g_ln;
        s[(5, 5)] = 1. / o.g_tn;
        s
    }

    #[test]
    fn local_stiffness_inverts_the_compliance() {
        let o = composite([0.; 3]);
        let d = o.local_hooke(Hypothesis::Solid3D);
        let err = (&d * compliance(&o) - DMatrix::<f64>::identity(6, 6)).amax();
        assert!(err < 1e-13, "{err}");
    }

    #[test]
    fn rotated_stiffness_maps_a_uniaxial_stress_along_l() {
        // σ = s e_L ⊗ e_L in global axes gives ε = S σ with ε_LL = s/E_L,
        // ε_TT = −ν_LT s/E_L, ε_NN = −ν_LN s/E_L.
        let angles = [0.4, -0.3, 1.1];
        let o = composite(angles);
        let d = o.hooke(Hypothesis::Solid3D);
        let p = matrot(angles);
        let sig = 1e6;
        let l = p[0];
        let stress = DMatrix::from_column_slice(
            6,
            1,
            &[
                sig * l[0] * l[0],
                sig * l[1] * l[1],
                sig * l[2] * l[2],
                sig * l[0] * l[1],
                sig * l[0] * l[2],
                sig * l[1] * l[2],
            ],
        );
        let eps = d.lu().solve(&stress).unwrap();
        let strain_along = |a: [f64; 3], b: [f64; 3]| {
            a[0] * b[0] * eps[0]
                + a[1] * b[1] * eps[1]
                + a[2] * b[2] * eps[2]
                + 0.5 * (a[0] * b[1] + a[1] * b[0]) * eps[3]
                + 0.5 * (a[0] * b[2] + a[2] * b[0]) * eps[4]
                + 0.5 * (a[1] * b[2] + a[2] * b[1]) * eps[5]
        };
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        assert!(rel(strain_along(p[0], p[0]), sig / o.e_l) < 1e-12);
        assert!(rel(strain_along(p[1], p[1]), -o.nu_lt * sig / o.e_l) < 1e-12);
        assert!(rel(strain_along(p[2], p[2]), -o.nu_ln * sig / o.e_l) < 1e-12);
        assert!(strain_along(p[0], p[1]).abs() < 1e-12 * sig / o.e_l);
    }

    #[test]
    fn plane_strain_is_the_3d_matrix_restricted_when_turned_about_z() {
        let o = composite([0.7, 0., 0.]);
        let d3 = o.hooke(Hypothesis::Solid3D);
        let d2 = o.hooke(Hypothesis::PlaneStrain);
        for i in 0..4 {
            for j in 0..4 {
                assert!((d2[(i, j)] - d3[(i, j)]).abs() < 1e-12 * o.e_l, "{i} {j}");
            }
        }
    }

    #[test]
    fn plane_stress_condenses_the_3d_matrix() {
        // σzz = σxz = σyz = 0 in the 3D law turned about z.
        let o = composite([-0.5, 0., 0.]);
        let d3 = o.hooke(Hypothesis::Solid3D);
        let s3 = d3.try_inverse().unwrap();
        let idx = [0, 1, 3];
        let mut s = DMatrix::zeros(3, 3);
        for (a, &i) in idx.iter().enumerate() {
            for (b, &j) in idx.iter().enumerate() {
                s[(a, b)] = s3[(i, j)];
            }
        }
        let c = s.try_inverse().unwrap();
        let d2 = o.hooke(Hypothesis::PlaneStress);
        for (a, &i) in [0usize, 1, 3].iter().enumerate() {
            for (b, &j) in [0usize, 1, 3].iter().enumerate() {
                assert!((d2[(i, j)] - c[(a, b)]).abs() < 1e-12 * o.e_l, "{i} {j}");
            }
            assert_eq!(d2[(2, i)], 0.);
        }
    }

    #[test]
    fn euler_angles_give_code_aster_s_nautical_ones() {
        assert_eq!(euler_to_nautical([0.; 3]), [0.; 3]);
        // ψ alone turns about z: α = ψ.
        let n = euler_to_nautical([30., 0., 0.]);
        assert!((n[0] - 30.).abs() < 1e-12 && n[1].abs() < 1e-12 && n[2].abs() < 1e-12);
        // The frames agree: matrot's rows are the Euler frame's axes.
        let (psi, theta, phi) = (20f64, 35f64, 50f64);
        let n = euler_to_nautical([psi, theta, phi]);
        let p = matrot(n.map(f64::to_radians));
        let [psi, theta, phi] = [psi, theta, phi].map(f64::to_radians);
        let x = [
            phi.cos() * psi.cos() - phi.sin() * theta.cos() * psi.sin(),
            phi.cos() * psi.sin() + phi.sin() * theta.cos() * psi.cos(),
            phi.sin() * theta.sin(),
        ];
        let z = [
            theta.sin() * psi.sin(),
            -theta.sin() * psi.cos(),
            theta.cos(),
        ];
        for k in 0..3 {
            assert!((p[0][k] - x[k]).abs() < 1e-12);
            assert!((p[2][k] - z[k]).abs() < 1e-12);
        }
    }

    #[test]
    fn non_positive_compliance_is_refused() {
        let mut o = composite([0.; 3]);
        o.nu_lt = 2.0;
        assert!(o.validate().is_err());
        o.nu_lt = 0.25;
        o.g_tn = 0.;
        assert!(o.validate().is_err());
    }
}
