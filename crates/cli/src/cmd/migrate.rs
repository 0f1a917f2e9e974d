//! `aster migrate FILE... [--write]`: code_aster 11/14/15 command files in
//! code_aster 17 spelling ([`aster_eval::migrate`]): a unified diff on
//! stdout by default, the files rewritten in place with `--write`. Legacy
//! constructs without a local rewrite are listed on stderr, located.
//!
//! Exit codes: 0 every legacy construct rewritten, 1 some left as they
//! were, 2 a file that cannot be read, parsed or written.

use aster_syntax::CodeMap;
use std::path::PathBuf;

pub fn run(files: &[PathBuf], write: bool) -> u8 {
    let mut code = 0u8;
    for path in files {
        let name = path.display().to_string();
        let source = match super::check::read(path) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("error: {e}");
                code = 2;
                continue;
            }
        };
        let m = match aster_eval::migrate::migrate(&name, &source) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("error: {e}");
                code = 2;
                continue;
            }
        };
        let map = CodeMap::new(name.as_str(), source.as_str());
        for d in &m.left {
            crate::style::eprint_diagnostic(&format!(
                "{}  = note: aster migrate has no rewrite for this: left as written\n",
                d.render(&map)
            ));
        }
        if !m.left.is_empty() {
            code = code.max(1);
        }
        if write {
            if m.text != source {
                if let Err(e) = std::fs::write(path, encode_like(&m.text, path)) {
                    eprintln!("error: {name}: cannot write: {e}");
                    code = 2;
                    continue;
                }
            }
            eprintln!("{name}: {} edit(s), {} left", m.edits, m.left.len());
        } else {
            print!("{}", diff(&name, &source, &m.text));
        }
    }
    code
}

/// The unified diff of a file's migration (nothing when unchanged).
pub fn diff(name: &str, old: &str, new: &str) -> String {
    if old == new {
        return String::new();
    }
    similar::TextDiff::from_lines(old, new)
        .unified_diff()
        .context_radius(3)
        .header(&format!("a/{name}"), &format!("b/{name}"))
        .to_string()
}

/// The text in the file's own encoding: a file that was not UTF-8 (old
/// files are Latin-1) is written back as Latin-1 when every character fits.
pub fn encode_like(text: &str, path: &std::path::Path) -> Vec<u8> {
    let was_utf8 = std::fs::read(path).is_ok_and(|b| std::str::from_utf8(&b).is_ok());
    if !was_utf8 && text.chars().all(|c| (c as u32) < 256) {
        return text.chars().map(|c| c as u8).collect();
    }
    text.as_bytes().to_vec()
}
