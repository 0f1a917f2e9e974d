//! `aster parse FILE... [--json]`: parse command files; exit 0 iff all parse.
//!
//! Each failing file gets its rendered error (`file:line:col: expected …`,
//! the source line and a caret) on stderr; the last line is
//! `parse: <n> ok, <m> failed`. With `--json` the AST of each file that
//! parses is printed on stdout, one object per file (`--compact`: one per
//! line), as [`super::json_out`] defines (schema: docs/json.md).

use super::json_out;
use std::io::Write;
use std::path::PathBuf;

pub fn run(files: &[PathBuf], json: bool, compact: bool) -> u8 {
    if compact && !json {
        eprintln!("aster parse: --compact shapes the output of --json: give --json too");
        return 2;
    }
    if files.is_empty() {
        eprintln!("aster parse: no input file (usage: aster parse FILE... [--json])");
        return 2;
    }
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let mut ok = 0usize;
    let mut failed = 0usize;
    for file in files {
        match aster_syntax::parse_file(file) {
            Ok((map, module)) => {
                ok += 1;
                if json {
                    let path = file.display().to_string();
                    let written = json_out::ast_object(&path, &map, &module)
                        .map_err(std::io::Error::other)
                        .and_then(|v| json_out::write_object(&mut out, &v, compact));
                    if let Err(e) = written {
                        eprintln!("{path}: cannot write the AST as JSON: {e}");
                    }
                }
            }
            Err(rendered) => {
                failed += 1;
                crate::style::eprint_diagnostic(&rendered);
            }
        }
    }
    let _ = out.flush();
    eprintln!("parse: {ok} ok, {failed} failed");
    if failed == 0 {
        0
    } else {
        1
    }
}
