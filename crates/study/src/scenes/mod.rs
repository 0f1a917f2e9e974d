//! Built-in scenes.

pub mod fake;
pub mod hertz;
pub mod zzzz237;
