//! The finite-strain measures of a displacement as element fields at the
//! Gauss points: `CALC_CHAMP(DEFORMATION='EPSG_ELGA')` (Green–Lagrange) and
//! `'EPSL_ELGA'` (logarithmic), as code_aster computes them (`te0025` in
//! 3D, `te0087` in 2D → `epsvmc`: `eps1mc` + `eps2mc` for EPSG, `epslmc` →
//! `nmepsi` + `deflog` for EPSL).
//!
//! Both are kinematic: they depend on the displacement only (the total one
//! of the step, on the initial geometry), not on the behaviour the result
//! was computed with, so they are defined for a small-strain result too.
//! Components EPXX EPYY EPZZ EPXY [EPXZ EPYZ], tensor shears (EPXY = E₁₂).
//!
//! - EPSG: E = ½(H + Hᵀ + HᵀH), H = ∇u (code_aster's `eps1mc`, the
//!   linear part with halved engineering shears, plus `eps2mc`, the
//!   quadratic one). AXIS: E₃₃ = u_r/r + ½(u_r/r)²; D_PLAN: E₃₃ = 0.
//! - EPSL: ε = ½ ln FᵀF ([`super::log::LogStrain`], `deflog`: in 2D the
//!   in-plane block is diagonalised and z is an eigendirection, λ₃ = F₃₃²),
//!   Mandel shears divided by √2. AXIS: ε₃₃ = ln(1 + u_r/r); D_PLAN: 0.
//!
//! C_PLAN: code_aster's `epsvmc` overwrites EPZZ with
//! −(d₃₁(ε₁ − εᵗʰ₁) + d₃₂(ε₂ − εᵗʰ₂) + 2 d₃₄(ε₄ − εᵗʰ₄))/d₃₃ + εᵗʰ₃, d the
//! plane-strain Hooke matrix (`dmatmc` with `l_modi_cp` → `dmatdp`), a
//! function of the material, not of the kinematics (the in-plane
//! components are those of F₃₃ = 1). For an isotropic material without
//! thermal strain this is EPZZ = −ν/(1 − ν)(EPXX + EPYY), what is computed
//! here; orthotropic C_PLAN cells and C_PLAN cells with a thermal strain
//! are refused, as is the under-integrated HEXA8 of 3D_SI.

use super::element::{displacement_gradient, gradient, point_geoms};
use super::log::LogStrain;
use crate::element::{element_dofs, model_gauss};
use crate::error::FemError;
use crate::material::Hypothesis;
use crate::model::{ElementKind, Model};
use crate::post::CellValues;
use aster_mesh::CellId;

/// Which finite-strain measure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StrainMeasure {
    /// Green–Lagrange, E = ½(FᵀF − I): `EPSG_*`.
    GreenLagrange,
    /// Logarithmic (Hencky), ε = ½ ln FᵀF: `EPSL_*`.
    Logarithmic,
}

impl StrainMeasure {
    /// code_aster's ELGA option.
    pub fn option(self) -> &'static str {
        match self {
            StrainMeasure::GreenLagrange => "EPSG_ELGA",
            StrainMeasure::Logarithmic => "EPSL_ELGA",
        }
    }
}

const NAMES_3D: [&str; 6] = ["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ"];
const NAMES_2D: [&str; 4] = ["EPXX", "EPYY", "EPZZ", "EPXY"];

/// The strain measure at the `RIGI` Gauss points of the continuum cells
/// `keep` accepts, for the total displacement `u` (model DOFs);
/// `thermal`: the result has thermal strains. Errors (`FemError::Model`):
/// a C_PLAN cell that is orthotropic or with `thermal`, an
/// under-integrated (3D_SI) cell; (`FemError::Integration`) a crushed
/// point (an eigenvalue of FᵀF ≤ 0, no logarithmic strain); each names
/// the cell.
pub fn finite_strain_elga_on(
    model: &Model,
    u: &[f64],
    measure: StrainMeasure,
    thermal: bool,
    keep: impl Fn(CellId) -> bool,
) -> Result<Vec<CellValues>, FemError> {
    let mut out = Vec::with_capacity(model.elements().len());
    for el in model.elements() {
        let ElementKind::Continuum {
            hypothesis,
            material,
        } = &el.kind
        else {
            continue;
        };
        if !keep(el.cell) {
            continue;
        }
        let hyp = *hypothesis;
        let name = model.cell_name(el.cell);
        // C_PLAN: EPZZ from the plane-strain Hooke matrix (epsvmc).
        let plane_stress_zz = if hyp == Hypothesis::PlaneStress {
            if material.orthotropic.is_some() || thermal {
                let why = if thermal {
                    "a thermal strain"
                } else {
                    "an orthotropic material"
                };
                return Err(FemError::Model(format!(
                    "{} of the plane stress (C_PLAN) cell {name} with {why} is not computed (code_aster's EPZZ there comes from the material's plane-strain Hooke matrix and the thermal strains)",
                    measure.option()
                )));
            }
            Some(material.hooke(Hypothesis::PlaneStrain))
        } else {
            None
        };
        if model.is_stabilised(el.cell) {
            return Err(FemError::Model(format!(
                "{} of the under-integrated HEXA8 of 3D_SI (cell {name}) is not computed",
                measure.option()
            )));
        }
        let ue: Vec<f64> = element_dofs(model, el.cell).iter().map(|&i| u[i]).collect();
        let gauss = model_gauss(model, el.cell, hyp)
            .map_err(|m| FemError::Model(format!("cell {name} is {m}")))?;
        let n = hyp.ncomp();
        let mut points = Vec::with_capacity(gauss.len());
        for (g, pg) in point_geoms(&gauss, hyp).iter().enumerate() {
            let e = match measure {
                StrainMeasure::GreenLagrange => {
                    let h = displacement_gradient(pg, hyp, &ue);
                    0.5 * (h + h.transpose() + h.transpose() * h)
                }
                StrainMeasure::Logarithmic => {
                    let f = gradient(pg, hyp, &ue);
                    let log = LogStrain::new(&f, hyp.dim()).map_err(|c| {
                        FemError::Integration(format!(
                            "EPSL_ELGA of cell {name}, Gauss point {}: the cell is crushed (eigenvalue {:.3e} of FᵀF), no logarithmic strain",
                            g + 1,
                            c.smallest
                        ))
                    })?;
                    super::log::from_mandel(&log.eps)
                }
            };
            let mut v: Vec<f64> = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
                .iter()
                .take(n)
                .map(|&(i, j)| e[(i, j)])
                .collect();
            if hyp == Hypothesis::PlaneStrain {
                // epsvmc: EPZZ = 0 in D_PLAN whatever the measure.
                v[2] = 0.0;
            }
            if let Some(d) = &plane_stress_zz {
                // Engineering shear 2 EPXY on d's shear column.
                v[2] = -(d[(2, 0)] * v[0] + d[(2, 1)] * v[1] + d[(2, 3)] * 2.0 * v[3]) / d[(2, 2)];
            }
            points.push(v);
        }
        out.push(CellValues {
            cell: el.cell,
            names: if hyp == Hypothesis::Solid3D {
                NAMES_3D.to_vec()
            } else {
                NAMES_2D.to_vec()
            },
            points,
        });
    }
    Ok(out)
}
