//! CPU time of each phase of `parse_module` over a directory of `.comm`
//! files (limit check, pest parse alone, pairs → AST, validation, drop):
//! `cargo run --release -p aster-syntax --example parse_phases -- ../shared/corpus/v17`.
//! Times are this thread's CPU time (Linux `/proc/thread-self/schedstat`),
//! so they stay meaningful on a loaded machine.

use aster_syntax::parser::{CommParser, Rule};
use pest::Parser;
use std::path::PathBuf;
use std::time::Duration;

/// CPU time of this thread, or zero where `/proc` is unavailable.
fn cpu() -> Duration {
    let ns = std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|x| x.parse().ok()))
        .unwrap_or(0);
    Duration::from_nanos(ns)
}

fn timed<T>(label: &str, mb: f64, f: impl FnOnce() -> T) -> T {
    let start = cpu();
    let out = f();
    let secs = (cpu() - start).as_secs_f64();
    println!("{label:<14} {secs:7.3} s CPU  {:7.1} MB/s", mb / secs);
    out
}

fn main() {
    let Some(dir) = std::env::args().nth(1) else {
        eprintln!("usage: phases DIR");
        std::process::exit(2);
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map(|rd| rd.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    files.retain(|p| p.extension().is_some_and(|x| x == "comm"));
    files.sort();
    let sources: Vec<String> = files
        .iter()
        .filter_map(|p| aster_syntax::read_source(p).ok())
        .collect();
    let mb = sources.iter().map(String::len).sum::<usize>() as f64 / 1e6;
    println!("{} files, {mb:.1} MB", sources.len());
    timed("check_limits", mb, || {
        for s in &sources {
            let _ = aster_syntax::diagnose::check_limits(s);
        }
    });
    let marked: Vec<String> = sources
        .iter()
        .map(|s| aster_syntax::logical::mark_line_ends(s))
        .collect();
    timed("mark line ends", mb, || {
        for s in &sources {
            let _ = aster_syntax::logical::mark_line_ends(s);
        }
    });
    timed("pest parse", mb, || {
        for s in &marked {
            let _ = CommParser::parse(Rule::module, s);
        }
    });
    let modules = timed("parse + build", mb, || {
        sources
            .iter()
            .filter_map(|s| aster_syntax::parser::parse_module_unchecked(s).ok())
            .collect::<Vec<_>>()
    });
    timed("validate", mb, || {
        for m in &modules {
            let _ = aster_syntax::validate::check(m);
        }
    });
    timed("drop", mb, || drop(modules));
    timed("parse_module", mb, || {
        for s in &sources {
            let _ = aster_syntax::parse_module(s);
        }
    });
}
