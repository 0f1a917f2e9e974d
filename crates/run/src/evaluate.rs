//! The bridge to the parser and the evaluator.

use crate::executor::Executor;
use crate::program::RunFailure;
use aster_syntax::CodeMap;
use std::path::Path;
use std::rc::Rc;

/// Parses and runs a command file with the executor. Legacy-syntax warnings
/// go to stderr; the first error stops the run.
pub fn run_source(path: &Path, source: &str, executor: &mut Executor) -> Result<(), RunFailure> {
    let map = CodeMap::new(path.display().to_string(), source);
    let module = aster_syntax::parse_module(source).map_err(|e| RunFailure {
        message: e.render(&map).trim_end().to_string(),
    })?;
    // Everything that would be refused is refused now, before any command
    // runs (crate::preflight).
    let pre = crate::preflight::check(&map, &module, &executor.options);
    if !pre.findings.0.is_empty() {
        return Err(RunFailure {
            message: pre.render(&map),
        });
    }
    executor.read_meshes = pre.meshes;
    executor.set_codemap(Rc::new(map.clone()));
    let options = aster_eval::RunOptions { keep_going: false };
    match aster_eval::run_program(&map, &module, executor, options) {
        Ok(summary) => {
            for w in &summary.warnings.0 {
                eprintln!("{}", w.headline(&map));
            }
            Ok(())
        }
        Err(diags) => {
            for w in diags.0.iter().filter(|d| !d.is_error()) {
                eprintln!("{}", w.headline(&map));
            }
            let errors: String = diags.errors().map(|d| d.render(&map)).collect();
            Err(RunFailure {
                message: errors.trim_end().to_string(),
            })
        }
    }
}
