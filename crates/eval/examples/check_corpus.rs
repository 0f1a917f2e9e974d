//! Checks every `.comm` of a directory and counts the outcomes: clean,
//! not supported (by reason), other errors (by kind), crashes.
//!
//! ```text
//! cargo run --release -p aster-eval --example check_corpus -- ../shared/corpus/v17 [--list KIND]
//! ```
//! `--phases` times parsing, then evaluation + validation of the parsed
//! modules (the part this crate owns), separately.
//! `--list KIND` prints the first diagnostic of each file whose first error
//! has that kind (e.g. `unknown_keyword`), to hunt false errors.

use aster_eval::check_source;
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
    if args.iter().any(|a| a == "--phases") {
        phases(&files);
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
            Some(ref d) if d.kind.is_not_supported() => {
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

/// Parse every file, then evaluate + validate the parsed modules: the two
/// phases timed apart (the checker's own cost is the second).
fn phases(files: &[std::path::PathBuf]) {
    let maps: Vec<CodeMap> = files
        .iter()
        .map(|f| {
            let bytes = std::fs::read(f).unwrap_or_default();
            let source = match String::from_utf8(bytes) {
                Ok(s) => s,
                Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
            };
            CodeMap::new(f.display().to_string(), source)
        })
        .collect();
    let _ = aster_catalog::catalog();
    let start = cpu_seconds();
    let modules: Vec<_> = maps
        .iter()
        .map(|m| aster_syntax::parse_module(m.source()).ok())
        .collect();
    let parse = cpu_seconds() - start;
    let rounds: usize = std::env::var("ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(1);
    let start = cpu_seconds();
    let mut clean = 0;
    for _ in 0..rounds {
        clean = 0;
        for (map, module) in maps.iter().zip(&modules) {
            if let Some(module) = module {
                clean += usize::from(aster_eval::check_module(map, module, false).ok());
            }
        }
    }
    let eval = (cpu_seconds() - start) / rounds as f64;
    println!(
        "files: {}  CPU time: parse {parse:.2} s, evaluate+validate {eval:.2} s  (clean: {clean})",
        maps.len()
    );
}

/// User + system CPU time of this process (Linux `/proc/self/stat`, in
/// clock ticks of 1/100 s); wall time elsewhere. CPU time, because the
/// machines this is measured on are shared.
fn cpu_seconds() -> f64 {
    let ticks = std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // Fields after the command name (which is in parentheses).
            let rest = s.rsplit_once(')')?.1;
            let f: Vec<&str> = rest.split_whitespace().collect();
            let utime: f64 = f.get(11)?.parse().ok()?;
            let stime: f64 = f.get(12)?.parse().ok()?;
            Some(utime + stime)
        });
    match ticks {
        Some(t) => t / 100.0,
        None => {
            static T0: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
            T0.get_or_init(Instant::now).elapsed().as_secs_f64()
        }
    }
}
