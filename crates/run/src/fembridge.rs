//! The bridge to aster-fem: builds its model, loads and solver from a
//! [`SolveSetup`], runs it, and turns its results into stored fields.

use crate::concept::{EvolResult, Step};
use crate::executor::Executor;
use crate::solve::SolveSetup;
use aster_eval::{CommandCall, ExecError};

pub fn solve(ex: &mut Executor, setup: &SolveSetup, linear: bool) -> Result<Vec<Step>, ExecError> {
    let _ = (setup, linear);
    let _ = ex;
    Err(ExecError::new(
        "not supported yet: the numerical core (aster-fem) is not available in this build",
    ))
}

pub fn calc_champ(
    ex: &mut Executor,
    call: &CommandCall,
    result: &EvolResult,
    options: &[String],
    steps: &[u32],
) -> Result<EvolResult, ExecError> {
    let _ = (result, options, steps);
    Err(ex.unsupported("CALC_CHAMP", call.span))
}
