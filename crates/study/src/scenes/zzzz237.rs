//! The ZZZZ237 two-block scene (placeholder until the solver lands).

use crate::error::StudyError;
use crate::outcome::{Failure, FailureKind, Measures};
use crate::scene::{Params, Scene};
use crate::spec::Point;
use std::collections::BTreeMap;

pub struct TwoBlocks {}

impl TwoBlocks {
    pub fn from_params(table: &BTreeMap<String, f64>) -> Result<TwoBlocks, StudyError> {
        Params::new("zzzz237", table, &[])?;
        Ok(TwoBlocks {})
    }
}

impl Scene for TwoBlocks {
    fn quantity(&self) -> String {
        "contact force (N)".into()
    }
    fn describe(&self) -> String {
        "ZZZZ237 two blocks".into()
    }
    fn run(&self, _p: &Point) -> Result<Measures, Failure> {
        Err(Failure::new(
            FailureKind::Unsupported,
            "solver not available yet",
        ))
    }
}
