//! `aster run CASE [--mesh PATH] [--out DIR] [--report json|junit FILE] [-q] [--vtu DIR]`:
//! runs a `.comm` or `.export`, prints each TEST_RESU check as code_aster
//! does and a last line `TEST_RESU: <n> OK, <m> NOOK`. Live progress (one
//! line per command, a table per non-linear increment) goes to stderr
//! unless `-q`. Exit 0 iff every check is OK, 1 if any is NOOK, 2 when the
//! run stops on an error.

use std::path::{Path, PathBuf};

/// The default output directory: `<case stem>-out` in the current
/// directory.
pub fn default_out(case: &Path) -> PathBuf {
    let stem = case
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "case".into());
    PathBuf::from(format!("{stem}-out"))
}

enum ReportFormat {
    Json,
    Junit,
}

pub fn run(
    case: &Path,
    mesh: Option<&Path>,
    out: Option<&Path>,
    report: &[String],
    quiet: bool,
    vtu: Option<&Path>,
) -> u8 {
    let report = match report {
        [] => None,
        [format, file] => match format.as_str() {
            "json" => Some((ReportFormat::Json, PathBuf::from(file))),
            "junit" => Some((ReportFormat::Junit, PathBuf::from(file))),
            other => {
                eprintln!(
                    "aster run: unknown report format `{other}` (expected `json` or `junit`)"
                );
                return 2;
            }
        },
        _ => {
            eprintln!("aster run: --report takes a format and a file: `--report json FILE`");
            return 2;
        }
    };
    let out = out.map_or_else(|| default_out(case), Path::to_path_buf);
    let mut prepared = match aster_run::program::prepare(case, mesh, &out) {
        Ok(c) => c,
        Err(e) => {
            crate::style::eprint_diagnostic(&format!("error: {e}"));
            if let Some((format, file)) = &report {
                write_report(format, file, case, &Default::default(), Some(&e.message));
            }
            return 2;
        }
    };
    prepared.progress_stderr = !quiet;
    prepared.vtu_dir = vtu.map(Path::to_path_buf);
    prepared.exit_after = true;
    let outcome = aster_run::program::run(&prepared, Box::new(crate::style::Listing::stdout()));
    if let Some(e) = &outcome.error {
        // Errors of the program carry `file:line:col: error:` already.
        if e.message.contains(": error: ") {
            crate::style::eprint_diagnostic(&e.to_string());
        } else {
            crate::style::eprint_diagnostic(&format!("error: {e}"));
        }
    }
    if let Some((format, file)) = &report {
        let error = outcome.error.as_ref().map(|e| e.message.as_str());
        if !write_report(format, file, case, &outcome.journal, error) {
            return 2;
        }
    }
    // The summary line always ends the output, so a stopped run still
    // reports the checks it made.
    println!("{}", outcome.tally.summary());
    if outcome.error.is_some() {
        2
    } else if outcome.tally.nook > 0 {
        1
    } else {
        0
    }
}

fn write_report(
    format: &ReportFormat,
    file: &Path,
    case: &Path,
    journal: &aster_run::journal::Journal,
    error: Option<&str>,
) -> bool {
    let name = case
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let text = match format {
        ReportFormat::Json => match serde_json::to_string_pretty(&journal.to_json(&name, error)) {
            Ok(t) => t + "\n",
            Err(e) => {
                eprintln!("aster run: cannot write the report: {e}");
                return false;
            }
        },
        ReportFormat::Junit => journal.to_junit(&name, error),
    };
    if let Err(e) = std::fs::write(file, text) {
        eprintln!(
            "aster run: {}: cannot write the report: {e}",
            file.display()
        );
        return false;
    }
    true
}
