//! Mesh operations the commands need: `DEFI_GROUP`, `MODI_MAILLAGE`.

mod groups;
mod orient;

pub use orient::OrientReport;
