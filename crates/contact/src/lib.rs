//! Contact: pairing of slave points with master cells, gaps and contact
//! conditions (code_aster's `DEFI_CONTACT`, formulations DISCRETE and
//! CONTINUE, frictionless).
//!
//! Data flow: a [`ContactDefinition`] (what `DEFI_CONTACT` says) is resolved
//! against a mesh into [`ResolvedZone`]s; [`pair_point`] pairs slave points
//! on the current geometry; [`contact_row`] linearises non-penetration into
//! fem's [`aster_fem::InequalityRow`]; [`ZoneContact`] is a
//! [`aster_fem::UnilateralSource`] that fem's Newton solver queries; the
//! [`dual`] module holds the multiplier-space algorithms (active set, GCP,
//! augmented Lagrangian, semi-smooth Newton) for any factorised stiffness.

// Index loops mirror the formulas (λᵢ, Sᵢⱼ, Nᵢ) and read better than
// iterator chains in numerical code.
#![allow(clippy::needless_range_loop)]

mod augmented;
pub mod dual;
mod error;
pub mod friction;
mod geomloop;
mod glissiere;
mod integration;
pub mod lac;
pub mod lac_mortar;
pub mod mortar_classique;
pub mod mortar_friction;
pub mod mortar_friction_penalty;
pub mod mortar_lagrangian;
pub mod mortar_nitsche;
pub mod mortar_pairing3d;
pub mod mortar_penalty;
mod mortar_point;
pub mod mortar_tangent;
mod pairing;
mod penalty;
pub mod quad8;
mod rows;
mod shape;
mod surface;
mod zone;

pub use error::ContactError;
pub use geomloop::{GeomDecision, GeomLoopState};
pub use integration::{integration_points, integration_points_measured, Measure};
pub use pairing::{
    nodal_points, pair_point, ContactPair, Exclusion, PairStatus, Pairing, SlavePoint,
};
pub use rows::contact_row;
pub use shape::{interpolate, project, project_along, CellPoint, SurfaceKind};
pub use surface::{ResolvedZone, SurfaceCell};
pub use zone::*;
mod post;
mod source;
mod step;

pub use post::{ContNoeu, CONT_NOEU_COMPONENTS, CONT_NOEU_PROJ_COMPONENTS};
pub use source::{current_positions, ZoneContact, ZoneLaw};
pub use step::{index_row, positions, solve_step, solve_step_cached, StepReport};
pub mod hertz;
mod linear;
pub mod scenes;

pub use linear::{run_linear, FactorizedStiffness, Instant};
