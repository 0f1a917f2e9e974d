//! Built-in scenes.

pub mod driver;
pub mod fake;
pub mod hertz;
pub mod zzzz237;
