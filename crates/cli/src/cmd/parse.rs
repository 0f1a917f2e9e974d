//! `aster parse FILE... [--json]`: parse command files; exit 0 iff all parse.
//!
//! Each failing file gets its rendered error (`file:line:col: expected …`,
//! the source line and a caret) on stderr; the last line is
//! `parse: <n> ok, <m> failed`. With `--json` the AST of each file that
//! parses is printed on stdout as pretty JSON (schema: docs/syntax.md).

use std::io::Write;
use std::path::PathBuf;

pub fn run(files: &[PathBuf], json: bool) -> u8 {
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
            Ok((_, module)) => {
                ok += 1;
                if json {
                    match serde_json::to_string_pretty(&module) {
                        Ok(text) => {
                            let _ = writeln!(out, "{text}");
                        }
                        Err(e) => {
                            eprintln!("{}: cannot serialize the AST: {e}", file.display());
                        }
                    }
                }
            }
            Err(rendered) => {
                failed += 1;
                eprint!("{rendered}");
                if !rendered.ends_with('\n') {
                    eprintln!();
                }
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
