//! `aster check FILE...`: parse, evaluate (commands are not executed) and
//! validate every command against the catalog. Exit 0 iff no error.
//! `--emit commands` prints the evaluated program as JSON.

use aster_eval::{check_source, CommandCall, Severity};
use aster_syntax::CodeMap;
use std::path::{Path, PathBuf};

/// Reads a command file; old files are Latin-1, so bytes that are not UTF-8
/// are decoded as such rather than rejected.
fn read(path: &Path) -> Result<String, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
    })
}

#[derive(serde::Serialize)]
struct Emitted<'a> {
    file: String,
    commands: &'a [CommandCall],
}

pub fn run(files: &[PathBuf], emit: Option<&str>) -> u8 {
    if let Some(what) = emit {
        if what != "commands" {
            eprintln!("aster check: unknown --emit `{what}` (expected `commands`)");
            return 2;
        }
    }
    if files.is_empty() {
        eprintln!("aster check: no file given");
        return 2;
    }
    let mut failed = false;
    let (mut clean, mut with_errors) = (0usize, 0usize);
    let mut emitted = Vec::new();
    for f in files {
        let source = match read(f) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{e}");
                failed = true;
                with_errors += 1;
                continue;
            }
        };
        let map = CodeMap::new(f.display().to_string(), source);
        let report = check_source(&map, emit.is_some());
        let (mut errors, mut warnings) = (0, 0);
        for d in &report.diagnostics.0 {
            match d.severity {
                Severity::Error => errors += 1,
                Severity::Warning => warnings += 1,
            }
            eprint!("{}", d.render(&map));
        }
        if errors > 0 {
            failed = true;
            with_errors += 1;
            eprintln!("{}: {errors} error(s), {warnings} warning(s)", f.display());
        } else {
            clean += 1;
            if emit.is_none() {
                eprintln!("{}: ok ({warnings} warning(s))", f.display());
            }
        }
        if emit.is_some() {
            emitted.push((f.display().to_string(), report.calls));
        }
    }
    // The summary line CI's ratchet reads; only worth printing for batches.
    if files.len() > 1 && emit.is_none() {
        eprintln!("check: {clean} clean, {with_errors} with errors");
    }
    if emit.is_some() {
        let out: Vec<Emitted> = emitted
            .iter()
            .map(|(f, c)| Emitted {
                file: f.clone(),
                commands: c,
            })
            .collect();
        let json = if out.len() == 1 {
            serde_json::to_string_pretty(&out[0])
        } else {
            serde_json::to_string_pretty(&out)
        };
        match json {
            Ok(j) => println!("{j}"),
            Err(e) => {
                eprintln!("aster check: cannot write JSON: {e}");
                return 2;
            }
        }
    }
    u8::from(failed)
}
