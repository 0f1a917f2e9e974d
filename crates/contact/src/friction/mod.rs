//! Coulomb friction (`DEFI_CONTACT(FROTTEMENT='COULOMB')`), beside the
//! frictionless formulations and sharing their pairing:
//!
//! - [`continuous`]: code_aster's continuous formulation (`FORMULATION=
//!   'CONTINUE'`): a contact element per slave integration point with the
//!   contact pressure `LAGS_C` and the friction multipliers `LAGS_F1`,
//!   `LAGS_F2` as unknowns of the slave nodes, augmented Lagrangian or
//!   penalised, solved by fem's generalised Newton method
//!   ([`aster_fem::ForceSource`]).
//! - [`discrete`]: the discrete penalised formulation (`FORMULATION=
//!   'DISCRETE'`, `ALGO_FROT='PENALISATION'`): per slave node, a normal
//!   penalty `E_N` and a tangential one `E_T` capped at μ times the normal
//!   force, on the slip increment of the step.
//!
//! The keywords are mapped onto the plain types of this module by the
//! runner; the numerics know no keyword.

pub mod adaptation;
pub mod continuous;
pub mod cycling;
pub mod discrete;

pub use continuous::ContinuousFriction;
pub use discrete::DiscreteFriction;

use crate::error::ContactError;
use crate::zone::{GeomLoop, Resolution};

/// `ALGO_FROT` of a continuous zone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FrictionAlgo {
    /// `STANDARD`: augmented Lagrangian with `COEF_FROT` (default 100).
    Standard { coef_frot: f64 },
    /// `PENALISATION` with `COEF_PENA_FROT`.
    Penalisation { coef_pena_frot: f64 },
}

/// `CONTACT_INIT`: the contact status of the points at the first step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ContactInit {
    /// `NON`: every point starts open.
    Non,
    /// `OUI`: every point starts in contact.
    Oui,
    /// `INTERPENETRE` (code_aster's default): points with a gap ≤ 1e-6 ×
    /// the smallest master edge start in contact.
    #[default]
    Interpenetre,
}

/// The friction settings of one continuous zone.
#[derive(Clone, Debug, PartialEq)]
pub struct ContinueZoneFriction {
    /// `COULOMB` (μ); a zone with μ = 0 is frictionless (code_aster gives it
    /// contact-only elements, without `LAGS_F`).
    pub coulomb: f64,
    pub algo: FrictionAlgo,
    /// `SEUIL_INIT`: the friction threshold (a contact pressure) of the
    /// first step; `None`: 0 (code_aster's automatic threshold from the
    /// initial `LAGS_C`, zero without an initial state).
    pub seuil_init: Option<f64>,
    pub contact_init: ContactInit,
    /// `SANS_GROUP_NO_FR`: slave nodes whose friction multipliers are
    /// fixed to zero.
    pub excluded_node_groups: Vec<String>,
    /// `DIRE_EXCL_FROT` (3D): only the friction component along this
    /// direction (projected on the tangent plane) is excluded.
    pub dire_excl_frot: Option<[f64; 3]>,
    /// `GLIS_MAXI` of a penalised-friction zone (code_aster's `cazocc`
    /// keeps 1e3 when it is not given): the slip its coefficient is
    /// adapted to beside augmented contact (`mm_cycl_algo`, `mmchml_c`;
    /// [`adaptation::pena_frot_update`]).
    pub glis_maxi: f64,
}

impl ContinueZoneFriction {
    /// A zone with μ and code_aster's defaults (`ALGO_FROT='STANDARD'`,
    /// `COEF_FROT=100`, `CONTACT_INIT='INTERPENETRE'`).
    pub fn new(coulomb: f64) -> Self {
        ContinueZoneFriction {
            coulomb,
            algo: FrictionAlgo::Standard { coef_frot: 100.0 },
            seuil_init: None,
            contact_init: ContactInit::Interpenetre,
            excluded_node_groups: Vec::new(),
            dire_excl_frot: None,
            glis_maxi: 1e3,
        }
    }

    /// Whether the zone carries friction (μ > 0, as code_aster's
    /// `FROTTEMENT_ZONE`).
    pub fn frictional(&self) -> bool {
        self.coulomb > f64::EPSILON
    }
}

/// The friction part of a continuous `DEFI_CONTACT`: one entry per zone and
/// the friction loop.
#[derive(Clone, Debug, PartialEq)]
pub struct ContinueFriction {
    pub zones: Vec<ContinueZoneFriction>,
    /// `ALGO_RESO_FROT` (default `NEWTON`).
    pub algo_reso_frot: Resolution,
    /// `RESI_FROT` (default 1e-4): with `NEWTON`, the largest change of
    /// `LAGS_C` in the last iteration relative to the largest `LAGS_C`;
    /// with `POINT_FIXE`, the change of the threshold between two loops.
    pub resi_frot: f64,
    /// `ITER_FROT_MAXI` (default 10, `POINT_FIXE`).
    pub iter_frot_maxi: usize,
    /// code_aster's contact-side cycling treatment (`mm_cycl_algo` for
    /// `TYPE_ADAPT` 4, 5, 6, 7, 11; the default `ADAPTATION='CYCLAGE'` is
    /// 4): module [`cycling`].
    pub cycling: bool,
    /// code_aster's adaptation of `COEF_FROT` point by point (`TYPE_ADAPT`
    /// 1, 2, 5, 6: `ADAPTATION='ADAPT_COEF'` or `'TOUT'` with Newton
    /// friction): module [`adaptation`].
    pub adapt_coef: bool,
}

impl ContinueFriction {
    pub fn new(zones: Vec<ContinueZoneFriction>) -> Self {
        ContinueFriction {
            zones,
            algo_reso_frot: Resolution::Newton,
            resi_frot: 1e-4,
            iter_frot_maxi: 10,
            cycling: true,
            adapt_coef: false,
        }
    }

    pub(crate) fn check(&self, nzones: usize) -> Result<(), ContactError> {
        if self.zones.len() != nzones {
            return Err(ContactError::Invalid {
                keyword: "ZONE",
                message: format!(
                    "{} zones but friction settings for {}",
                    nzones,
                    self.zones.len()
                ),
            });
        }
        for z in &self.zones {
            if !(z.coulomb.is_finite() && z.coulomb >= 0.0) {
                return Err(ContactError::Invalid {
                    keyword: "COULOMB",
                    message: format!("must be a number ≥ 0, got {}", z.coulomb),
                });
            }
            let (k, v) = match z.algo {
                FrictionAlgo::Standard { coef_frot } => ("COEF_FROT", coef_frot),
                FrictionAlgo::Penalisation { coef_pena_frot } => ("COEF_PENA_FROT", coef_pena_frot),
            };
            if !(v.is_finite() && v > 0.0) {
                return Err(ContactError::Invalid {
                    keyword: k,
                    message: format!("must be a positive number, got {v}"),
                });
            }
            if let Some(d) = z.dire_excl_frot {
                crate::zone::normalised(d, "DIRE_EXCL_FROT")?;
            }
        }
        if !(self.resi_frot.is_finite() && self.resi_frot > 0.0) {
            return Err(ContactError::Invalid {
                keyword: "RESI_FROT",
                message: format!("must be a positive number, got {}", self.resi_frot),
            });
        }
        Ok(())
    }
}

/// The friction settings of one discrete zone (`ALGO_FROT='PENALISATION'`,
/// the only discrete friction algorithm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscreteZoneFriction {
    /// `COULOMB` (μ).
    pub coulomb: f64,
    /// `E_T`: tangential penalty (force per unit slip).
    pub e_t: f64,
    /// `COEF_MATR_FROT` (default 0): the weight of the sliding part of the
    /// tangent matrix while RESI_GLOB_RELA ≥ 1e-3 (code_aster's `cffpm2`).
    pub coef_matr_frot: f64,
}

/// The friction part of a discrete `DEFI_CONTACT`.
#[derive(Clone, Debug, PartialEq)]
pub struct DiscreteFrictionDef {
    pub zones: Vec<DiscreteZoneFriction>,
}

impl DiscreteFrictionDef {
    pub(crate) fn check(&self, nzones: usize) -> Result<(), ContactError> {
        if self.zones.len() != nzones {
            return Err(ContactError::Invalid {
                keyword: "ZONE",
                message: format!(
                    "{} zones but friction settings for {}",
                    nzones,
                    self.zones.len()
                ),
            });
        }
        for z in &self.zones {
            if !(z.coulomb.is_finite() && z.coulomb >= 0.0) {
                return Err(ContactError::Invalid {
                    keyword: "COULOMB",
                    message: format!("must be a number ≥ 0, got {}", z.coulomb),
                });
            }
            if !(z.e_t.is_finite() && z.e_t > 0.0) {
                return Err(ContactError::Invalid {
                    keyword: "E_T",
                    message: format!("must be a positive number, got {}", z.e_t),
                });
            }
            if !(z.coef_matr_frot.is_finite() && (0.0..=1.0).contains(&z.coef_matr_frot)) {
                return Err(ContactError::Invalid {
                    keyword: "COEF_MATR_FROT",
                    message: format!("must be in [0, 1], got {}", z.coef_matr_frot),
                });
            }
        }
        Ok(())
    }
}

/// The geometric loop of a continuous frictional definition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FrictionGeometry {
    /// `ALGO_RESO_GEOM='NEWTON'`: pair again after every Newton iteration;
    /// converged when the contact points move by less than `resi_geom` ×
    /// the longest master edge between two iterations.
    Newton { resi_geom: f64 },
    /// `ALGO_RESO_GEOM='POINT_FIXE'`: pair at the start of each step and
    /// again after Newton converged, as `REAC_GEOM` says.
    FixedPoint(GeomLoop),
}
