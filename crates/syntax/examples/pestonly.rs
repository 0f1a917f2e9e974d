use aster_syntax::parser::{CommParser, Rule};
use pest::Parser;
fn main() {
    let dir = std::env::args().nth(1).unwrap_or_default();
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map(|rd| rd.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    files.retain(|p: &std::path::PathBuf| p.extension().is_some_and(|x| x == "comm"));
    let sources: Vec<String> = files
        .iter()
        .filter_map(|p| aster_syntax::read_source(p).ok())
        .collect();
    let t = std::time::Instant::now();
    let mut n = 0;
    for s in &sources {
        if let Ok(p) = CommParser::parse(Rule::module, &aster_syntax::logical::mark_line_ends(s)) {
            n += p.tokens().len();
        }
    }
    println!("{n} tokens {:?}", t.elapsed());
}
