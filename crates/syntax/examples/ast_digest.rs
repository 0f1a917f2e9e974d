//! One line per `.comm` file: a digest of its AST as JSON (spans included),
//! or the error message. Diffing the output of two builds shows whether a
//! grammar or builder change altered any tree:
//! `cargo run --release -p aster-syntax --example ast_digest -- ../shared/corpus/v17 > a.txt`.
//! With `--json`, the JSON itself is printed instead of its digest.

use std::hash::{Hash, Hasher};
use std::path::PathBuf;

fn main() {
    let mut files: Vec<PathBuf> = Vec::new();
    let json_out = std::env::args().any(|a| a == "--json");
    for arg in std::env::args().skip(1).filter(|a| a != "--json") {
        let path = PathBuf::from(&arg);
        if path.is_dir() {
            if let Ok(entries) = std::fs::read_dir(&path) {
                files.extend(
                    entries
                        .flatten()
                        .map(|e| e.path())
                        .filter(|p| p.extension().is_some_and(|x| x == "comm")),
                );
            }
        } else {
            files.push(path);
        }
    }
    files.sort();
    for path in files {
        let Ok(source) = aster_syntax::read_source(&path) else {
            println!("{}: unreadable", path.display());
            continue;
        };
        let line = match aster_syntax::parse_module(&source) {
            Ok(module) => match serde_json::to_string(&module) {
                Ok(json) if json_out => json,
                Ok(json) => {
                    // SipHash with fixed keys: the same digest in every build.
                    let mut hasher = std::collections::hash_map::DefaultHasher::new();
                    json.hash(&mut hasher);
                    format!("{:016x}", hasher.finish())
                }
                Err(e) => format!("json error: {e}"),
            },
            Err(e) => format!("error at {}: {}", e.span.start, e.message),
        };
        println!("{}: {line}", path.display());
    }
}
