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
    /// The command files, in order (one for a `.comm`; an `.export` may
    /// give several: `X.comm`, `X.com1`…, run as one study).
    pub comms: Vec<PathBuf>,
    /// The study's Python modules (`F nom module.py D 0`).
    pub modules: Vec<PathBuf>,
    /// The case is an `.export`: its module list is the study's whole list.
    pub from_export: bool,
    /// Files the report is also written to (`F resu … R 8`, `F mess … R 6`
    /// of the `.export`: their file name, inside the output directory).
    pub report_files: Vec<PathBuf>,
    /// The `.export`'s `mess` file (in the output directory): it also
    /// receives the live progress.
    pub mess: Option<PathBuf>,
    /// Write the live progress ([`crate::progress`]) to stderr too.
    pub progress_stderr: bool,
    /// Write every result (all steps, all fields) as VTU/PVD there when
    /// the run ends (`aster run --vtu DIR`).
    pub vtu_dir: Option<PathBuf>,
    pub options: RunOptions,
    /// The process ends with the run (`aster run`): the executor's concepts
    /// (meshes, results, fields) are left to the operating system instead
    /// of being freed one allocation at a time (docs/performance.md).
    pub exit_after: bool,
}

impl Case {
    /// The first command file.
    pub fn comm(&self) -> &Path {
        &self.comms[0]
    }
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
    let mut modules = Vec::new();
    let mut report_files = Vec::new();
    let mut mess = None;
    let from_export = case.extension().is_some_and(|e| e == "export");
    let comms = if from_export {
        let export = Export::read(case).map_err(fail)?;
        if let Some(f) = export
            .files
            .iter()
            .find(|f| matches!(f.kind.as_str(), "base" | "bhdf"))
        {
            return Err(fail(format!(
                "{}: `{} {}` (a code_aster database {}) is not supported: aster keeps no database; \
                 a study's command files (`F comm … D 1`, in order) run in one process instead",
                case.display(),
                f.kind,
                f.path.display(),
                if f.data { "to start from" } else { "to save" },
            )));
        }
        let comms: Vec<PathBuf> = export
            .comm_files()
            .iter()
            .map(|p| p.to_path_buf())
            .collect();
        if comms.is_empty() {
            return Err(fail(format!(
                "{}: no command file (`F comm FILE D 1`)",
                case.display()
            )));
        }
        modules = export.modules().iter().map(|p| p.to_path_buf()).collect();
        options.units = export.data_units();
        options.result_units = export
            .files
            .iter()
            .filter(|f| f.result && !matches!(f.kind.as_str(), "resu" | "mess"))
            .map(|f| (f.unit, f.path.clone()))
            .collect();
        for kind in ["resu", "mess"] {
            if let Some(name) = export.result_file(kind).and_then(Path::file_name) {
                report_files.push(out_dir.join(name));
                if kind == "mess" {
                    mess = Some(out_dir.join(name));
                }
            }
        }
        comms
    } else {
        vec![case.to_path_buf()]
    };
    let comm = comms[0].clone();
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
    for path in comms.iter().chain(&modules) {
        if !path.exists() {
            return Err(fail(format!("{}: no such file", path.display())));
        }
    }
    Ok(Case {
        comms,
        modules,
        from_export,
        report_files,
        mess,
        progress_stderr: false,
        vtu_dir: None,
        options,
        exit_after: false,
    })
}

/// What a run did: the verdicts so far, and the error that stopped it.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub tally: Tally,
    pub error: Option<RunFailure>,
    /// Each command and comparison (reports).
    pub journal: crate::journal::Journal,
}

/// Runs a case, writing its report (TEST_RESU lines, tables) to `report`
/// (and to the `.export`'s `resu`/`mess` files).
pub fn run(case: &Case, report: Box<dyn Write>) -> Outcome {
    let read = |paths: &[PathBuf]| -> Result<Vec<(PathBuf, String)>, RunFailure> {
        paths
            .iter()
            .map(|p| match aster_syntax::read_source(p) {
                Ok(text) => Ok((p.clone(), text)),
                Err(e) => Err(fail(format!("{}: cannot read: {e}", p.display()))),
            })
            .collect()
    };
    let sources = read(&case.comms).and_then(|c| Ok((c, read(&case.modules)?)));
    let (comms, modules) = match sources {
        Ok(s) => s,
        Err(e) => {
            return Outcome {
                tally: Tally::default(),
                error: Some(e),
                journal: Default::default(),
            }
        }
    };
    let mut copies = Vec::new();
    // The files the case writes go there (created even when the `.export`
    // names no result file, so `IMPR_*` and `--vtu` find it).
    {
        if let Err(e) = std::fs::create_dir_all(&case.options.out_dir) {
            return Outcome {
                tally: Tally::default(),
                error: Some(fail(format!(
                    "{}: cannot create: {e}",
                    case.options.out_dir.display()
                ))),
                journal: Default::default(),
            };
        }
    }
    for path in &case.report_files {
        match std::fs::File::create(path) {
            Ok(f) => copies.push(f),
            Err(e) => {
                return Outcome {
                    tally: Tally::default(),
                    error: Some(fail(format!("{}: cannot write: {e}", path.display()))),
                    journal: Default::default(),
                }
            }
        }
    }
    let report: Box<dyn Write> = if copies.is_empty() {
        report
    } else {
        Box::new(Tee {
            first: report,
            copies: copies.iter().filter_map(|f| f.try_clone().ok()).collect(),
        })
    };
    let mut executor = Executor::new(case.options.clone(), report);
    // The `.mess` file gets the progress too (the report's copy shares its
    // file offset, so the two interleave in order).
    let mess = case.mess.as_ref().and_then(|m| {
        case.report_files
            .iter()
            .position(|p| p == m)
            .and_then(|i| copies.get(i))
            .and_then(|f| f.try_clone().ok())
    });
    executor.progress = crate::progress::Progress::new(case.progress_stderr, mess);
    let observer = executor.progress.observer();
    let (mut error, _) = aster_fem::progress::observe(observer, || {
        crate::evaluate::run_sources(&comms, &modules, case.from_export, &mut executor).err()
    });
    // The results as they are when the run ends (also after an error: what
    // was computed up to it is what a user wants to look at).
    if let Some(dir) = &case.vtu_dir {
        match crate::vtu_export::write_results(&executor, dir) {
            Ok(files) if case.progress_stderr => {
                let pvd = files
                    .iter()
                    .filter(|f| f.extension().is_some_and(|e| e == "pvd"));
                for f in pvd {
                    eprintln!("vtu: {}", f.display());
                }
            }
            Ok(_) => {}
            Err(e) => error = error.or(Some(fail(e))),
        }
    }
    // The files end as the report does: the error, then the summary.
    for mut f in copies {
        let mut tail = String::new();
        if let Some(e) = &error {
            tail.push_str(&format!("{e}\n"));
        }
        tail.push_str(&format!("{}\n", executor.tally.summary()));
        let _ = f.write_all(tail.as_bytes());
    }
    let outcome = Outcome {
        tally: executor.tally,
        error,
        journal: std::mem::take(&mut executor.journal),
    };
    executor.flush_report();
    if case.exit_after {
        std::mem::forget(executor);
    }
    outcome
}

/// A report written to several places.
struct Tee {
    first: Box<dyn Write>,
    copies: Vec<std::fs::File>,
}

impl Write for Tee {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.first.write_all(buf)?;
        for c in &mut self.copies {
            c.write_all(buf)?;
        }
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.first.flush()?;
        for c in &mut self.copies {
            c.flush()?;
        }
        Ok(())
    }
}
