//! STAT_NON_LINE, MECA_STATIQUE and CALC_CHAMP: the bridge to aster-fem.

use crate::executor::Executor;
use aster_eval::{CommandCall, CommandOutput, ExecError};

/// What a result was computed from, kept for CALC_CHAMP.
#[derive(Debug)]
pub struct SolveSetup {}

pub fn stat_non_line(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    Err(ex.unsupported("STAT_NON_LINE", call.span))
}

pub fn meca_statique(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    Err(ex.unsupported("MECA_STATIQUE", call.span))
}

pub fn calc_champ(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    Err(ex.unsupported("CALC_CHAMP", call.span))
}
