//! Checks every `.comm` of a directory and counts the outcomes: clean,
//! not supported (by reason), other errors (by kind), crashes.
//!
//! ```text
//! cargo run --release -p aster-eval --example check_corpus -- ../shared/corpus/v17 [--list KIND]
//! ```
//! `--list KIND` prints the first diagnostic of each file whose first error
//! has that kind (e.g. `unknown_keyword`), to hunt false errors.

use aster_eval::{check_source, DiagKind};
use aster_syntax::CodeMap;
use std::collections::BTreeMap;
use std::time::Instant;

fn reason(message: &str) -> String {
    // "not supported: import of module `numpy`" → keep up to the first
    // detail that varies by file (names after a backquote are kept: they
    // are the useful part).
    let m = message.trim_start_matches("not supported: ");
    let cut = m.find(" (").unwrap_or(m.len());
    m[..cut].to_string()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(dir) = args.first() else {
        eprintln!("usage: check_corpus DIR [--list KIND]");
        std::process::exit(2);
    };
    let list = args
        .iter()
        .position(|a| a == "--list")
        .and_then(|i| args.get(i + 1))
        .cloned();
    let mut files: Vec<_> = match std::fs::read_dir(dir) {
        Ok(rd) => rd
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "comm"))
            .collect(),
        Err(e) => {
            eprintln!("{dir}: {e}");
            std::process::exit(2);
        }
    };
    files.sort();
    if std::env::var_os("PARSE_ONLY").is_some() {
        let start = Instant::now();
        let mut ok = 0;
        for f in &files {
            let bytes = std::fs::read(f).unwrap_or_default();
            let s: String = bytes.iter().map(|&b| b as char).collect();
            ok += usize::from(aster_syntax::parse_module(&s).is_ok());
        }
        println!(
            "parsed {ok}/{} in {:.2} s",
            files.len(),
            start.elapsed().as_secs_f64()
        );
        return;
    }
    let start = Instant::now();
    let (mut clean, mut warned, mut crashed) = (0, 0, 0);
    let mut unsupported: BTreeMap<String, usize> = BTreeMap::new();
    let mut errors: BTreeMap<String, usize> = BTreeMap::new();
    for f in &files {
        let bytes = std::fs::read(f).unwrap_or_default();
        let source = match String::from_utf8(bytes) {
            Ok(s) => s,
            Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
        };
        let map = CodeMap::new(f.display().to_string(), source);
        let report = match std::panic::catch_unwind(|| check_source(&map, false)) {
            Ok(r) => r,
            Err(_) => {
                crashed += 1;
                println!("CRASH {}", f.display());
                continue;
            }
        };
        let first = report.diagnostics.errors().next().cloned();
        match first {
            None => {
                clean += 1;
                if !report.diagnostics.0.is_empty() {
                    warned += 1;
                }
            }
            Some(ref d) if d.kind == DiagKind::NotSupported => {
                *unsupported.entry(reason(&d.message)).or_default() += 1;
            }
            Some(ref d) => {
                let key = format!("{:?}", d.kind);
                *errors.entry(d.kind.label().to_string()).or_default() += 1;
                if list
                    .as_deref()
                    .is_some_and(|l| key.eq_ignore_ascii_case(&l.replace('_', "")))
                {
                    println!("{}", d.headline(&map));
                    for n in &d.notes {
                        println!("    {n}");
                    }
                }
            }
        }
    }
    let elapsed = start.elapsed();
    let n = files.len();
    println!("files: {n}  time: {:.2} s", elapsed.as_secs_f64());
    println!("clean: {clean} (of which {warned} with warnings)");
    println!("not supported: {}", unsupported.values().sum::<usize>());
    let mut u: Vec<_> = unsupported.into_iter().collect();
    u.sort_by_key(|x| std::cmp::Reverse(x.1));
    for (r, c) in u.iter().take(40) {
        println!("  {c:5}  {r}");
    }
    println!("errors: {}", errors.values().sum::<usize>());
    let mut e: Vec<_> = errors.into_iter().collect();
    e.sort_by_key(|x| std::cmp::Reverse(x.1));
    for (r, c) in e {
        println!("  {c:5}  {r}");
    }
    println!("crashes: {crashed}");
}
