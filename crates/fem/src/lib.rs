//! Numerics: elements, assembly, linear solves, the incremental Newton
//! solver, kinematic conditions and unilateral conditions shared with contact.

pub mod dof;
pub mod error;
pub mod unilateral;

pub use dof::{Comp, Dof, DofNumbering};
pub use error::FemError;
pub use unilateral::{
    FixedRows, GeometryUpdate, InequalityRow, RowOutcome, State, UnilateralMethod, UnilateralSource,
};
