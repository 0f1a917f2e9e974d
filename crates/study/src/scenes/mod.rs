//! Built-in scenes.

pub mod driver;
pub mod fake;
pub mod friction;
pub mod hertz;
pub mod zzzz237;
