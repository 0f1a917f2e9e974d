//! Linear elasticity (isotropic, or orthotropic through
//! [`crate::orthotropic`]) and the modelling hypotheses.

use crate::error::FemError;
use nalgebra::DMatrix;

/// Modelling hypothesis of a continuum element (code_aster's modelisation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Hypothesis {
    /// `D_PLAN`: εzz = 0.
    PlaneStrain,
    /// `C_PLAN`: σzz = 0.
    PlaneStress,
    /// `AXIS`: x is the radius r, y the axis z; εθθ = u_r / r; integrals
    /// are per radian (weight r dr dz, no 2π), as code_aster's.
    Axisymmetric,
    /// `3D`.
    Solid3D,
}

impl Hypothesis {
    /// Space dimension of the unknowns.
    pub fn dim(self) -> usize {
        match self {
            Hypothesis::Solid3D => 3,
            _ => 2,
        }
    }

    /// Number of stress components (SIXX SIYY SIZZ SIXY, + SIXZ SIYZ in 3D).
    pub fn ncomp(self) -> usize {
        match self {
            Hypothesis::Solid3D => 6,
            _ => 4,
        }
    }

    /// Stress component names in code_aster's order.
    pub fn stress_names(self) -> &'static [&'static str] {
        match self {
            Hypothesis::Solid3D => &["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"],
            _ => &["SIXX", "SIYY", "SIZZ", "SIXY"],
        }
    }

    /// code_aster's modelisation name.
    pub fn aster_name(self) -> &'static str {
        match self {
            Hypothesis::PlaneStrain => "D_PLAN",
            Hypothesis::PlaneStress => "C_PLAN",
            Hypothesis::Axisymmetric => "AXIS",
            Hypothesis::Solid3D => "3D",
        }
    }
}

/// Linear elastic material: isotropic (`DEFI_MATERIAU(ELAS=_F(E, NU))`)
/// or orthotropic (`ELAS_ORTH`, in its frame): then `e` and `nu` are NaN
/// (the isotropic laws and elements built on them refuse such a material
/// before solving: [`Elastic::is_isotropic`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastic {
    pub e: f64,
    pub nu: f64,
    pub orthotropic: Option<crate::orthotropic::Orthotropic>,
}

impl Elastic {
    pub fn new(e: f64, nu: f64) -> Result<Elastic, FemError> {
        if !(e.is_finite() && e > 0.) {
            return Err(FemError::Model(format!(
                "Young's modulus E must be positive and finite, got {e}"
            )));
        }
        if !(nu.is_finite() && nu > -1. && nu < 0.5) {
            return Err(FemError::Model(format!(
                "Poisson's ratio NU must lie in (-1, 0.5), got {nu}"
            )));
        }
        Ok(Elastic {
            e,
            nu,
            orthotropic: None,
        })
    }

    /// An orthotropic material (checked by
    /// [`crate::orthotropic::Orthotropic::validate`]).
    pub fn orthotropic(o: crate::orthotropic::Orthotropic) -> Result<Elastic, FemError> {
        Ok(Elastic {
            e: f64::NAN,
            nu: f64::NAN,
            orthotropic: Some(o.validate()?),
        })
    }

    /// Whether the material is isotropic (E, NU).
    pub fn is_isotropic(&self) -> bool {
        self.orthotropic.is_none()
    }

    /// Hooke's matrix in Voigt notation (engineering shear strains) for the
    /// hypothesis: 4×4 on (xx, yy, zz, xy) in 2D, 6×6 on
    /// (xx, yy, zz, xy, xz, yz) in 3D. In plane stress the zz row and column
    /// are zero (σzz = 0, εzz is not a kinematic unknown).
    /// An orthotropic material's is turned from its frame to the global axes.
    pub fn hooke(&self, hyp: Hypothesis) -> DMatrix<f64> {
        if let Some(o) = &self.orthotropic {
            return o.hooke(hyp);
        }
        let (e, nu) = (self.e, self.nu);
        let mu = e / (2. * (1. + nu));
        let lambda = e * nu / ((1. + nu) * (1. - 2. * nu));
        match hyp {
            Hypothesis::PlaneStress => {
                let c = e / (1. - nu * nu);
                let mut d = DMatrix::zeros(4, 4);
                d[(0, 0)] = c;
                d[(1, 1)] = c;
                d[(0, 1)] = c * nu;
                d[(1, 0)] = c * nu;
                d[(3, 3)] = mu;
                d
            }
            _ => {
                let n = hyp.ncomp();
                let mut d = DMatrix::zeros(n, n);
                for i in 0..3 {
                    for j in 0..3 {
                        d[(i, j)] = if i == j { lambda + 2. * mu } else { lambda };
                    }
                }
                for i in 3..n {
                    d[(i, i)] = mu;
                }
                d
            }
        }
    }
}
