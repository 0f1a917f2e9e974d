//! The bridge to the parser and the evaluator.

use crate::executor::Executor;
use crate::program::RunFailure;
use aster_syntax::CodeMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Parses and runs a study: command files run in order in one interpreter
/// (`POURSUITE` continuing with the concepts of the file before), and the
/// Python modules they may import (a module's name is its file's stem).
/// Every file is parsed before anything runs. `declared`: the module list
/// is the study's whole list (an `.export` gave it).
pub fn run_sources(
    comms: &[(PathBuf, String)],
    modules: &[(PathBuf, String)],
    declared: bool,
    executor: &mut Executor,
) -> Result<(), RunFailure> {
    let mut map: Option<CodeMap> = None;
    let mut bases = Vec::new();
    for (path, source) in comms.iter().chain(modules) {
        let name = path.display().to_string();
        let base = match map.as_mut() {
            None => {
                map = Some(CodeMap::new(name, source.as_str()));
                0
            }
            Some(m) => m.add_file(name, source.as_str()),
        };
        bases.push(base);
    }
    let Some(map) = map else {
        return Err(RunFailure {
            message: "no command file".to_string(),
        });
    };
    let mut parsed = Vec::new();
    for ((_, source), base) in comms.iter().chain(modules).zip(&bases) {
        let module = aster_syntax::parse_module_at(source, *base).map_err(|e| RunFailure {
            message: e.render(&map).trim_end().to_string(),
        })?;
        parsed.push(module);
    }
    let (files, mods) = parsed.split_at(comms.len());
    let study = aster_eval::Study {
        files: files.iter().collect(),
        modules: modules
            .iter()
            .zip(mods)
            .map(|((path, _), m)| (module_name(path), m))
            .collect(),
        declared,
    };
    // Everything that would be refused is refused now, before any command
    // runs (crate::preflight).
    // The run validates again only the calls whose inputs differ from the
    // static pass's (`aster_eval::ValidationMemo`).
    let mut memo = aster_eval::ValidationMemo::recording();
    let pre = crate::preflight::check_study_memo(&map, &study, &executor.options, Some(&mut memo));
    memo.freeze();
    if !pre.findings.0.is_empty() {
        return Err(RunFailure {
            message: pre.render(&map),
        });
    }
    executor.read_meshes = pre.meshes;
    executor.set_codemap(Rc::new(map.clone()));
    let options = aster_eval::RunOptions { keep_going: false };
    let result = aster_eval::run_study_memo(&map, &study, executor, options, Some(&mut memo));
    if std::env::var_os("ASTER_RUN_TIMING").is_some() {
        eprintln!(
            "[run] validations reused from the static pass: {}, done again: {}",
            memo.hits, memo.misses
        );
    }
    match result {
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

/// The name a command file imports a module by: its file's stem.
fn module_name(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}
