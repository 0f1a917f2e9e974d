//! The bridge to the parser and the evaluator.

use crate::executor::Executor;
use crate::program::RunFailure;
use std::path::Path;

pub fn run_source(path: &Path, source: &str, executor: &mut Executor) -> Result<(), RunFailure> {
    let _ = (source, executor);
    Err(RunFailure {
        message: format!(
            "{}: the evaluator is not available in this build yet",
            path.display()
        ),
    })
}
