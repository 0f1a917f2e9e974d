//! Numerics for aster: elements, assembly, sparse solves (faer), the
//! incremental Newton solver (`STAT_NON_LINE`), kinematic conditions
//! (eliminated and dualised), unilateral conditions shared with contact,
//! mass matrices and implicit time integration (`DYNA_NON_LINE`), and
//! post-processing (FORC_NODA, REAC_NODA, ELNO/NOEU stresses, SIEQ).
//!
//! The API uses plain Rust types and no command keywords: the runner maps
//! code_aster commands onto [`Model`], [`Loads`] and [`StaticNonLinear`].

// Index loops mirror the formulas (Bᵢⱼ, Kᵢⱼ…) and read better than iterator
// chains in element and matrix code.
#![allow(clippy::needless_range_loop)]

pub mod assembly;
pub mod autodiff;
pub mod bar;
pub mod beam;
pub mod behaviour;
pub mod cohesive;
pub mod coque3d;
pub mod coupling;
mod diag;
pub mod dkq;
pub mod dkt;
pub mod dof;
pub mod dst;
pub mod dynamics;
pub mod element;
pub mod elga;
pub mod energy;
pub mod energy_balance;
pub mod error;
pub mod error_estimate;
pub mod follower;
pub mod force_source;
pub mod fpg;
pub mod fracture;
pub mod grid;
mod held;
pub mod hexs8;
pub mod inertia;
pub mod joint;
pub mod laminate;
pub mod linalg;
pub mod line_search;
pub mod loads;
pub mod mass;
pub mod material;
pub mod mixed_upg;
pub mod modal;
pub mod model;
pub mod newton_timing;
pub mod nonlinear;
pub mod ordering;
pub mod orthotropic;
mod parallel;
pub mod plate;
pub mod post;
pub mod progress;
pub mod projection;
pub mod q4g;
pub mod refcells;
pub mod scenes;
pub mod section;
pub mod shape;
pub mod skin_norm;
pub(crate) mod solver_constrained;
mod split_llt;
pub mod strain;
pub mod thermal;
pub mod thermal_nl;
pub mod unilateral;

pub use beam::BeamSection;
pub use behaviour::{
    Behaviours, CurveEnd, EcroNl, JohnsonCook, Lemaitre, LocalSearch, NodalHistory, TempFn,
    ThermoHardening, ThermoMaterial, TractionCurve, TractionNappe, Uniaxial, UniaxialHardening,
    VonMises,
};
pub use dkt::ShellSection;
pub use dof::{Comp, Dof, DofNumbering};
pub use dynamics::{DynamicNonLinear, Scheme};
pub use error::FemError;
pub use force_source::{
    Contribution, ForceSource, LoopVerdict, PenaltyAdaptation, PenaltyVerdict, Unknown,
};
pub use line_search::{LineSearch, LineSearchMethod, Rule as LineSearchRule};
pub use loads::{EdgeRule, Load, LoadItem, Loads, Multiplier};
pub use mass::{DiscreteMass, Lumping, MassData, Rayleigh};
pub use material::{Elastic, Hypothesis};
pub use model::{Element, ElementKind, Frame, Model};
pub use nonlinear::{
    meca_statique, Attempt, Convergence, IncrementTerms, InitialState, MatrixKind, Motion,
    NewtonOptions, NonLinearResult, Prediction, StaticNonLinear, Step, Subdivision,
};
pub use plate::PlateTheory;
pub use post::{CellValues, NodalValues};
pub use strain::Kinematics;
pub use unilateral::{
    AugmentedTerm, FixedRows, GeometryUpdate, InequalityRow, OuterLoops, RowOutcome, State,
    UnilateralMethod, UnilateralSource,
};
