//! The Hertz scene (placeholder until the solver lands).

use crate::error::StudyError;
use crate::outcome::{Failure, FailureKind, Measures};
use crate::scene::{Params, Scene};
use crate::spec::Point;
use std::collections::BTreeMap;

pub struct Hertz {}

impl Hertz {
    pub fn from_params(table: &BTreeMap<String, f64>) -> Result<Hertz, StudyError> {
        Params::new("hertz", table, &[])?;
        Ok(Hertz {})
    }
}

impl Scene for Hertz {
    fn quantity(&self) -> String {
        "contact force (N)".into()
    }
    fn describe(&self) -> String {
        "Hertz".into()
    }
    fn run(&self, _p: &Point) -> Result<Measures, Failure> {
        Err(Failure::new(
            FailureKind::Unsupported,
            "solver not available yet",
        ))
    }
}
