//! `aster check FILE...`: parse, evaluate (commands are not executed) and
//! validate every command against the catalog. `--emit commands` prints the
//! evaluated program as JSON; `--format json|sarif|github` prints the
//! diagnostics for tools ([`super::diag_out`]).
//!
//! Exit codes: 0 every file clean (warnings allowed), 1 some file has an
//! error (or cannot be read), 3 no error but some file uses a construct
//! aster does not support (the file may be valid code_aster), 2 a usage
//! error.

use super::diag_out::{self, Located};
use super::json_out::{self, JsonOptions};
use aster_eval::{check_source, Level};
use aster_syntax::CodeMap;
use std::path::{Path, PathBuf};

/// The exit code when nothing is wrong but something is not supported.
pub const EXIT_UNSUPPORTED: u8 = 3;

/// How diagnostics are printed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// rustc-style text with the source line and a caret, on stderr.
    Human,
    /// JSON Lines on stdout: one object per file (schema in docs/check.md).
    Json,
    /// One SARIF 2.1.0 log on stdout.
    Sarif,
    /// GitHub Actions workflow commands (`::error file=…::…`) on stdout.
    Github,
}

/// Reads a command file; old files are Latin-1, so bytes that are not UTF-8
/// are decoded as such rather than rejected.
pub(crate) fn read(path: &Path) -> Result<String, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
    })
}

/// A file that cannot be read, as a diagnostic of the machine formats.
fn unreadable(path: &str, message: String) -> Located {
    Located {
        code: "E-io".into(),
        level: Level::Error,
        kind: "io",
        file: path.to_string(),
        line: 1,
        column: 1,
        end_line: 1,
        end_column: 1,
        message,
        suggestion: None,
        notes: Vec::new(),
    }
}

pub fn run(files: &[PathBuf], emit: Option<&str>, format: Format, json: JsonOptions) -> u8 {
    if emit.is_none() && (json.compact || json.no_defaults) {
        eprintln!("aster check: --compact and --no-defaults shape the output of --emit commands: give --emit commands too");
        return 2;
    }
    if let Some(what) = emit {
        if what != "commands" {
            eprintln!("aster check: unknown --emit `{what}` (expected `commands`)");
            return 2;
        }
        if format != Format::Human {
            eprintln!("aster check: --emit prints the program, --format the diagnostics: give one");
            return 2;
        }
    }
    if files.is_empty() {
        eprintln!("aster check: no file given");
        return 2;
    }
    let (mut clean, mut with_errors, mut unsupported) = (0usize, 0usize, 0usize);
    let mut emitted = Vec::new();
    let mut all: Vec<(String, Vec<Located>)> = Vec::new();
    for f in files {
        let path = f.display().to_string();
        let diags = match read(f) {
            Ok(source) => {
                let map = CodeMap::new(path.clone(), source);
                let report = check_source(&map, emit.is_some());
                if format == Format::Human {
                    for d in &report.diagnostics.0 {
                        crate::style::eprint_diagnostic(&d.render(&map));
                    }
                }
                if emit.is_some() {
                    match json_out::commands_object(&path, &map, &report.calls, json) {
                        Ok(v) => emitted.push(v),
                        Err(e) => {
                            eprintln!("aster check: cannot write JSON: {e}");
                            return 2;
                        }
                    }
                }
                report
                    .diagnostics
                    .0
                    .iter()
                    .map(|d| Located::new(d, &map, &path))
                    .collect()
            }
            Err(e) => {
                if format == Format::Human {
                    eprintln!("{e}");
                }
                vec![unreadable(&path, e)]
            }
        };
        let count = |l: Level| diags.iter().filter(|d| d.level == l).count();
        let (errors, nosup, warnings) = (
            count(Level::Error),
            count(Level::Unsupported),
            count(Level::Warning),
        );
        match diag_out::status(&diags) {
            "error" => with_errors += 1,
            "unsupported" => unsupported += 1,
            _ => clean += 1,
        }
        match format {
            Format::Human if errors > 0 => {
                eprintln!("{path}: {errors} error(s), {warnings} warning(s)")
            }
            Format::Human if nosup > 0 => {
                eprintln!("{path}: not supported by aster ({warnings} warning(s))")
            }
            Format::Human if emit.is_none() => eprintln!("{path}: ok ({warnings} warning(s))"),
            Format::Human => {}
            Format::Json => println!("{}", diag_out::json_line(&path, &diags)),
            Format::Github => {
                for d in &diags {
                    println!("{}", diag_out::github_line(d));
                }
            }
            Format::Sarif => {}
        }
        if format == Format::Sarif {
            all.push((path, diags));
        }
    }
    // The summary line CI's ratchet reads (`check: N clean`); only worth
    // printing for batches.
    if files.len() > 1 && emit.is_none() {
        eprintln!("check: {clean} clean, {with_errors} with errors, {unsupported} not supported");
    }
    if format == Format::Sarif {
        match serde_json::to_string_pretty(&diag_out::sarif(&all)) {
            Ok(j) => println!("{j}"),
            Err(e) => {
                eprintln!("aster check: cannot write SARIF: {e}");
                return 2;
            }
        }
    }
    if emit.is_some() {
        let stdout = std::io::stdout();
        let mut out = stdout.lock();
        for v in &emitted {
            if let Err(e) = json_out::write_object(&mut out, v, json.compact) {
                eprintln!("aster check: cannot write JSON: {e}");
                return 2;
            }
        }
    }
    if with_errors > 0 {
        1
    } else if unsupported > 0 {
        EXIT_UNSUPPORTED
    } else {
        0
    }
}
