//! ASTER text meshes (`.mail`): reading and writing.

mod read;

pub use read::{parse_mail, read_mail};
