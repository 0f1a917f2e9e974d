//! Mesh operations the commands need: `DEFI_GROUP`, `MODI_MAILLAGE`,
//! `CREA_MAILLAGE`.

mod copy_cells;
mod degree;
mod geom_groups;
mod groups;
mod orient;
mod orient_along;
mod orient_crack;
mod perturb;
mod points;
mod quarter_points;
mod rebuild;
mod refine;
mod restrict;
mod superpose;
#[cfg(test)]
mod testmesh;

pub(crate) use degree::edges;
pub use degree::{CentreNodes, DegreeReport};
pub use geom_groups::NodeKind;
pub use groups::{positional_name, CellFilter};
pub use orient::OrientReport;
pub use orient_along::Along;
pub use orient_crack::CrackReport;
pub use quarter_points::CrackFront;
pub use restrict::Restriction;
