//! MED files (HDF5): reading meshes, writing meshes and result fields.

pub mod celltypes;
mod fields;
mod read;
mod write;

pub use fields::{read_med_steps, read_med_steps_covered, StepCovered};
pub use read::{read_med, read_med_bytes, read_med_named, MedInfo};
pub use write::{med_bytes, med_bytes_on, write_med, write_med_on, Entities};
