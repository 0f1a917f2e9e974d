//! Running a case: resolving the command file and its units (`.comm` or
//! `.export`, `--mesh`, files beside the case), then parsing, evaluating and
//! executing it.

use crate::executor::{Executor, RunOptions};
use crate::export::Export;
use crate::test_resu::Tally;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A case ready to run.
#[derive(Clone, Debug)]
pub struct Case {
    pub comm: PathBuf,
    pub options: RunOptions,
}

/// Why a case stopped.
#[derive(Clone, Debug, PartialEq)]
pub struct RunFailure {
    pub message: String,
}

impl std::fmt::Display for RunFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

fn fail(message: impl Into<String>) -> RunFailure {
    RunFailure {
        message: message.into(),
    }
}

/// Resolves a case: CASE is a `.comm` or a `.export`; the mesh (unit 20) is
/// the export's, else `mesh`, else `<stem>.mmed|.med|.mail` beside the file.
pub fn prepare(case: &Path, mesh: Option<&Path>, out_dir: &Path) -> Result<Case, RunFailure> {
    if !case.exists() {
        return Err(fail(format!("{}: no such file", case.display())));
    }
    let mut options = RunOptions {
        out_dir: out_dir.to_path_buf(),
        ..RunOptions::default()
    };
    let comm = if case.extension().is_some_and(|e| e == "export") {
        let export = Export::read(case).map_err(fail)?;
        let comms = export.comm_files();
        let comm = match comms.as_slice() {
            [c] => c.to_path_buf(),
            [] => {
                return Err(fail(format!(
                    "{}: no command file (`F comm FILE D 1`)",
                    case.display()
                )))
            }
            _ => {
                return Err(fail(format!(
                    "{}: several command files are not supported yet",
                    case.display()
                )))
            }
        };
        options.units = export.data_units();
        options.result_units = export
            .files
            .iter()
            .filter(|f| f.result)
            .map(|f| (f.unit, f.path.clone()))
            .collect();
        comm
    } else {
        case.to_path_buf()
    };
    if let std::collections::btree_map::Entry::Vacant(slot) = options.units.entry(20) {
        let found = match mesh {
            Some(m) => Some(m.to_path_buf()),
            None => ["mmed", "med", "mail"]
                .iter()
                .map(|ext| comm.with_extension(ext))
                .find(|p| p.exists()),
        };
        if let Some(m) = found {
            slot.insert(m);
        }
    }
    for (unit, path) in &options.units {
        if !path.exists() {
            return Err(fail(format!(
                "unit {unit}: {}: no such file",
                path.display()
            )));
        }
    }
    Ok(Case { comm, options })
}

/// What a run did: the verdicts so far, and the error that stopped it.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub tally: Tally,
    pub error: Option<RunFailure>,
}

/// Runs a case, writing its report (TEST_RESU lines, tables) to `report`.
pub fn run(case: &Case, report: Box<dyn Write>) -> Outcome {
    // Old files may be Latin-1: decode byte per byte when not UTF-8.
    let source = match std::fs::read(&case.comm) {
        Ok(bytes) => match String::from_utf8(bytes) {
            Ok(s) => s,
            Err(e) => e.into_bytes().iter().map(|&c| c as char).collect(),
        },
        Err(e) => {
            return Outcome {
                tally: Tally::default(),
                error: Some(fail(format!("{}: cannot read: {e}", case.comm.display()))),
            }
        }
    };
    let mut executor = Executor::new(case.options.clone(), report);
    let error = crate::evaluate::run_source(&case.comm, &source, &mut executor).err();
    Outcome {
        tally: executor.tally,
        error,
    }
}
