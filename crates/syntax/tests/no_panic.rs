//! No input makes the parser (or the printer) panic: random bytes, random
//! Python-ish token soups, and mutations of real files (the project's
//! inputs, plus corpus files when `../shared` exists).

use aster_syntax::{decode, fmt::format_source, parse_module};
use proptest::prelude::*;
use std::path::Path;

/// Parsing returns Ok or Err; when Ok, the printer must work too.
fn exercise(source: &str) {
    if parse_module(source).is_ok() {
        let _ = format_source(source);
    }
}

fn seeds() -> Vec<String> {
    let mut out = Vec::new();
    let own = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/v17");
    for dir in [own.join("inputs"), own.join("errors"), corpus] {
        let Ok(rd) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut files: Vec<_> = rd.flatten().map(|e| e.path()).collect();
        files.sort();
        // A few corpus files are enough to give realistic material.
        for p in files.into_iter().step_by(97).take(40) {
            if let Ok(bytes) = std::fs::read(&p) {
                out.push(decode(&bytes));
            }
        }
    }
    out
}

const TOKENS: &[&str] = &[
    "(", ")", "[", "]", "{", "}", ",", ":", "=", "==", "+", "-", "**", "*", ".", ";", "\n", "    ",
    "\t", "\\\n", "#c\n", "'s'", "\"d\"", "'''t'''", "f'{x}'", "f'{", "1", "1.", ".5", "1e-3",
    "0x1F", "10L", "MA", "_F", "if", "else", "elif", "for", "in", "def", "return", "lambda", "not",
    "and", "print", "exec", "try", "except", "`", "<>", "$", "é", "\r\n",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        exercise(&decode(&bytes));
    }

    #[test]
    fn token_soup(idx in proptest::collection::vec(0..TOKENS.len(), 0..80)) {
        let s: String = idx.iter().map(|&i| TOKENS[i]).collect();
        exercise(&s);
    }

    #[test]
    fn mutated_files(seed in any::<prop::sample::Index>(),
                     edits in proptest::collection::vec((any::<prop::sample::Index>(), 0u8..4, any::<u8>()), 1..8)) {
        let seeds = seeds();
        prop_assume!(!seeds.is_empty());
        let mut bytes = seeds[seed.index(seeds.len())].clone().into_bytes();
        for (at, op, b) in edits {
            if bytes.is_empty() { break; }
            let i = at.index(bytes.len());
            match op {
                0 => { bytes.remove(i); }
                1 => bytes.insert(i, b),
                2 => bytes[i] = b,
                _ => { let j = (i + 1 + b as usize).min(bytes.len()); bytes.drain(i..j); }
            }
        }
        exercise(&decode(&bytes));
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let deep = format!("x = {}1{}\n", "(".repeat(5000), ")".repeat(5000));
    assert!(parse_module(&deep).is_err());
    let deep_list = format!("x = {}\n", "[".repeat(100_000));
    assert!(parse_module(&deep_list).is_err());
    let unary = format!("x = {}1\n", "-".repeat(100_000));
    assert!(parse_module(&unary).is_err());
}
