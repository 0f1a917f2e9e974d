//! `aster fmt FILE... [--check | --write]`: command files in canonical form
//! (code_aster 17 style, comments kept).
//!
//! - no flag: print each file's canonical form on stdout;
//! - `--check`: change nothing; print a unified diff of every file that is
//!   not canonical and name it on stderr (`would reformat: FILE`);
//! - `--write`: rewrite the files that are not canonical in place, in their
//!   own encoding (a Latin-1 file stays Latin-1 when every character fits).
//!
//! Exit codes: 0 every file canonical (or printed/rewritten), 1 a file that
//! does not parse or, with `--check`, that would be reformatted, 2 a file
//! that cannot be read or written.

use aster_syntax::CodeMap;
use std::path::PathBuf;

/// What `aster fmt` does with the canonical text.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Print,
    Check,
    Write,
}

pub fn run(files: &[PathBuf], mode: Mode) -> u8 {
    let mut code = 0u8;
    let (mut changed, mut unchanged) = (0usize, 0usize);
    for path in files {
        let name = path.display().to_string();
        let source = match aster_syntax::read_source(path) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{name}: {e}");
                code = 2;
                continue;
            }
        };
        let text = match aster_syntax::fmt::format_source(&source) {
            Ok(text) => text,
            Err(e) => {
                let map = CodeMap::new(name.as_str(), source.as_str());
                crate::style::eprint_diagnostic(&e.render(&map));
                code = code.max(1);
                continue;
            }
        };
        if text == source {
            unchanged += 1;
        } else {
            changed += 1;
        }
        match mode {
            Mode::Print => print!("{text}"),
            Mode::Check => {
                if text != source {
                    print!("{}", super::migrate::diff(&name, &source, &text));
                    eprintln!("would reformat: {name}");
                    code = code.max(1);
                }
            }
            Mode::Write => {
                if text != source {
                    if let Err(e) = std::fs::write(path, super::migrate::encode_like(&text, path)) {
                        eprintln!("{name}: cannot write: {e}");
                        code = 2;
                    }
                }
            }
        }
    }
    match mode {
        Mode::Print => {}
        Mode::Check => {
            eprintln!("{changed} file(s) would be reformatted, {unchanged} already canonical")
        }
        Mode::Write => eprintln!("{changed} file(s) reformatted, {unchanged} left unchanged"),
    }
    code
}
