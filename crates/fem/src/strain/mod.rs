//! Strain measures and kinematics of STAT_NON_LINE
//! (`COMPORTEMENT/DEFORMATION`), beside the behaviours they feed.
//!
//! | `Kinematics` | code_aster | element | stress kept by the behaviour | SIEF_ELGA |
//! | --- | --- | --- | --- | --- |
//! | `Small` | `PETIT` | B on the initial geometry | σ | σ |
//! | `SmallUpdated` | `PETIT_REAC` (`nmpl2d`/`nmpl3d`) | B on the updated geometry x = X + u, Δε = B(x) Δu, no geometric stiffness | σ | σ |
//! | `GreenLagrange` | `GREEN_LAGRANGE` (`GROT_GDEP` of code_aster ≤ 15, `nmgr2d`/`nmgr3d`) | total Lagrangian, E = ½(FᵀF − I) | S (PK2) | Cauchy F S Fᵀ / J |
//! | `Logarithmic` | `GDEF_LOG` (`nmdlog`, Miehe–Apel–Lambrecht) | total Lagrangian, ε = ½ ln FᵀF, S = Pᵀ T | T (dual of ε) | Cauchy |
//! | `SimoMiehe` | `SIMO_MIEHE` (`nmgpfi`) | updated Lagrangian, Kirchhoff τ | elastic strain (Iᵈ − bₑ)/2 | Cauchy τ / J |
//!
//! The behaviours are written in small strains (`behaviour::vmis`) and used
//! unchanged on the strain measure for `SmallUpdated`, `GreenLagrange` and
//! `Logarithmic`; `SimoMiehe` has its own multiplicative plasticity
//! (`behaviour::simo_miehe`).

pub(crate) mod element;
pub mod fields;
pub mod log;

pub use element::GaussState;
pub use fields::{finite_strain_elga_on, StrainMeasure};

/// How strains follow the displacement (`COMPORTEMENT/DEFORMATION`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Kinematics {
    /// `PETIT`: small strains on the initial geometry.
    #[default]
    Small,
    /// `PETIT_REAC`: small strain increments on the updated geometry.
    SmallUpdated,
    /// `GREEN_LAGRANGE`: Green–Lagrange strain, total Lagrangian.
    GreenLagrange,
    /// `GDEF_LOG`: logarithmic strain, total Lagrangian.
    Logarithmic,
    /// `SIMO_MIEHE`: multiplicative plasticity, updated Lagrangian.
    SimoMiehe,
}

impl Kinematics {
    /// code_aster's keyword.
    pub fn aster_name(self) -> &'static str {
        match self {
            Kinematics::Small => "PETIT",
            Kinematics::SmallUpdated => "PETIT_REAC",
            Kinematics::GreenLagrange => "GREEN_LAGRANGE",
            Kinematics::Logarithmic => "GDEF_LOG",
            Kinematics::SimoMiehe => "SIMO_MIEHE",
        }
    }

    /// Whether the nodal forces of a result come from its stresses on the
    /// deformed geometry (code_aster's FORC_NODA for any DEFORMATION other
    /// than PETIT).
    pub fn deformed_geometry(self) -> bool {
        self != Kinematics::Small
    }
}
