//! Parse every file given on the command line (or every `.comm` of the
//! directories given) and report counts, failures and throughput:
//! `cargo run --release -p aster-syntax --example corpus -- ../shared/corpus/v17`.

use std::path::{Path, PathBuf};
use std::time::Instant;

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
    let mut failed = 0;
    for (path, source) in &sources {
        if let Err(e) = aster_syntax::parse_module(source) {
            failed += 1;
            let map = aster_syntax::CodeMap::new(path.display().to_string(), source.as_str());
            eprint!("{}", e.render(&map));
        }
    }
    let secs = start.elapsed().as_secs_f64();
    println!(
        "parsed {} files ({:.1} MB) in {:.3} s = {:.1} MB/s; {} ok, {} failed",
        sources.len(),
        bytes as f64 / 1e6,
        secs,
        bytes as f64 / 1e6 / secs,
        sources.len() - failed,
        failed
    );
}
