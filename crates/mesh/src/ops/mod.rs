//! Mesh operations the commands need: `DEFI_GROUP`, `MODI_MAILLAGE`,
//! `CREA_MAILLAGE`.

mod degree;
mod geom_groups;
mod groups;
mod orient;
mod points;
mod rebuild;
mod restrict;
#[cfg(test)]
mod testmesh;

pub use degree::{CentreNodes, DegreeReport};
pub use geom_groups::NodeKind;
pub use orient::OrientReport;
pub use restrict::Restriction;
