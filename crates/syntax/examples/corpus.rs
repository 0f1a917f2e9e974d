//! Parse every file given on the command line (or every `.comm` of the
//! directories given) and report counts, failures and throughput:
//! `cargo run --release -p aster-syntax --example corpus -- ../shared/corpus/v17`.
//! Throughput is reported for this thread's CPU time (Linux
//! `/proc/thread-self/schedstat`) and for wall-clock time: on a shared,
//! loaded machine only the CPU figure is meaningful.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// CPU time of this thread, or zero where `/proc` is unavailable.
fn cpu() -> Duration {
    let ns = std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|x| x.parse().ok()))
        .unwrap_or(0);
    Duration::from_nanos(ns)
}

fn collect(arg: &Path, out: &mut Vec<PathBuf>) {
    if arg.is_dir() {
        if let Ok(entries) = std::fs::read_dir(arg) {
            let mut files: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "comm"))
                .collect();
            files.sort();
            out.extend(files);
        }
    } else {
        out.push(arg.to_path_buf());
    }
}

fn main() {
    let mut files = Vec::new();
    for a in std::env::args().skip(1) {
        collect(Path::new(&a), &mut files);
    }
    let sources: Vec<(PathBuf, String)> = files
        .into_iter()
        .filter_map(|p| aster_syntax::read_source(&p).ok().map(|s| (p, s)))
        .collect();
    let bytes: usize = sources.iter().map(|(_, s)| s.len()).sum();
    let start = Instant::now();
    let cpu_start = cpu();
    let mut failed = 0;
    for (path, source) in &sources {
        if let Err(e) = aster_syntax::parse_module(source) {
            failed += 1;
            let map = aster_syntax::CodeMap::new(path.display().to_string(), source.as_str());
            eprint!("{}", e.render(&map));
        }
    }
    let cpu_secs = (cpu() - cpu_start).as_secs_f64();
    let secs = start.elapsed().as_secs_f64();
    let mb = bytes as f64 / 1e6;
    println!(
        "parsed {} files ({mb:.1} MB) in {cpu_secs:.3} s CPU = {:.1} MB/s ({secs:.3} s wall = {:.1} MB/s); {} ok, {} failed",
        sources.len(),
        mb / cpu_secs,
        mb / secs,
        sources.len() - failed,
        failed
    );
}
