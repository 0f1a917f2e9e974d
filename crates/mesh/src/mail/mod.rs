//! ASTER text meshes (`.mail`): reading and writing.

mod read;
mod write;

pub use read::{parse_mail, read_mail};
pub use write::{mail_string, write_mail};
