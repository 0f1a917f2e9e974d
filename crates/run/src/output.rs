//! IMPR_RESU: writing meshes and results through the mesh crate's writers.

use crate::executor::Executor;
use aster_eval::{CommandCall, CommandOutput, ExecError};

pub fn impr_resu(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    Err(ex.unsupported("IMPR_RESU", call.span))
}
