//! `aster study SPEC [--out DIR]`: run a speed/accuracy sweep and write its
//! CSV, charts (SVG and PNG) and summary.

use aster_study::{run_and_write, stats, Progress, Status, StudySpec};
use std::path::Path;

/// Exit 0 when the study ran (failing runs are results, not errors), 2 when
/// the spec is bad or the outputs cannot be written.
pub fn run(spec_path: &Path, out: &Path) -> u8 {
    let spec = match StudySpec::from_file(spec_path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    let (result, outputs) = match run_and_write(&spec, out, Progress::Auto) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    let count = |s: Status| result.records.iter().filter(|r| r.status == s).count();
    println!(
        "study {}: {} runs, {} converged, {} wrong answers, {} failed, {} unsupported",
        spec.name,
        result.records.len(),
        count(Status::Converged),
        count(Status::Wrong),
        count(Status::Failed),
        count(Status::Unsupported)
    );
    match stats::fastest_within(&result, spec.accuracy_target) {
        Some(r) => println!(
            "fastest within {}%: {} (refine {}) in {:.4} s CPU, error {:.3}%",
            100.0 * spec.accuracy_target,
            r.point.method.label(),
            r.point.refine,
            r.seconds(),
            100.0 * r.error.unwrap_or(f64::NAN)
        ),
        None => println!("no converged run within {}%", 100.0 * spec.accuracy_target),
    }
    println!("wrote {}", outputs.csv.display());
    for c in &outputs.charts {
        println!("wrote {}", c.display());
    }
    println!("wrote {}", outputs.summary.display());
    0
}
