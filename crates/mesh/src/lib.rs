//! Meshes as code_aster sees them: nodes, cells with code_aster type names
//! and node ordering, and named groups of cells (GROUP_MA) and nodes
//! (GROUP_NO).

mod model;

pub use model::*;
