//! A Markdown summary of a study: counts, the fastest method at equal
//! accuracy, convergence rates and every failure with its reason.

use crate::engine::StudyResult;
use crate::method::short_number;
use crate::outcome::Status;
use crate::spec::Reference;
use crate::stats;
use std::fmt::Write;

pub fn markdown(result: &StudyResult) -> String {
    let spec = &result.spec;
    let mut s = String::new();
    let _ = writeln!(s, "# Study `{}`\n", spec.name);
    let _ = writeln!(s, "- scene: {}", result.scene);
    let _ = writeln!(s, "- compared quantity: {}", result.quantity);
    let reference = match spec.reference {
        Reference::Analytic => "the analytic value".to_string(),
        Reference::Finest => format!(
            "the finest converged run of {} (same stiffness ratio, steps and μ)",
            spec.methods.first().map(|m| m.label()).unwrap_or_default()
        ),
    };
    let _ = writeln!(s, "- reference: {reference}");
    let _ = writeln!(
        s,
        "- a converged run whose error exceeds {}% counts as a wrong answer",
        short_number(100.0 * spec.tolerance)
    );
    let count = |st: Status| result.records.iter().filter(|r| r.status == st).count();
    let _ = writeln!(
        s,
        "- {} runs: {} converged, {} wrong answers, {} failed, {} unsupported\n",
        result.records.len(),
        count(Status::Converged),
        count(Status::Wrong),
        count(Status::Failed),
        count(Status::Unsupported)
    );

    let target = spec.accuracy_target;
    let _ = writeln!(
        s,
        "## Fastest at equal accuracy (error ≤ {}%)\n",
        short_number(100.0 * target)
    );
    match stats::fastest_within(result, target) {
        Some(r) => {
            let _ = write!(
                s,
                "**{}** (refine {}, {}): {:.4} s, error {:.3}%",
                r.point.method.label(),
                r.point.refine,
                r.point.setting().full_label(),
                r.seconds(),
                100.0 * r.error.unwrap_or(f64::NAN)
            );
            match r.outside_solver_fraction() {
                Some(f) => {
                    let _ = writeln!(
                        s,
                        "; {:.0}% of its time outside the linear solver.\n",
                        100.0 * f
                    );
                }
                None => {
                    let _ = writeln!(s, "; the scene does not report the linear solver's time.\n");
                }
            }
        }
        None => {
            let _ = writeln!(s, "No converged run reaches this accuracy.\n");
        }
    }
    let _ = writeln!(
        s,
        "| method | fastest run within target | CPU time (s) | error | outside solver |"
    );
    let _ = writeln!(s, "| --- | --- | --- | --- | --- |");
    for (m, best) in stats::fastest_per_method(result, target) {
        match best {
            Some(r) => {
                let _ = writeln!(
                    s,
                    "| {} | refine {}, {} | {:.4} | {:.3}% | {} |",
                    m.label(),
                    r.point.refine,
                    r.point.setting().full_label(),
                    r.seconds(),
                    100.0 * r.error.unwrap_or(f64::NAN),
                    r.outside_solver_fraction()
                        .map(|f| format!("{:.0}%", 100.0 * f))
                        .unwrap_or_else(|| "—".into())
                );
            }
            None => {
                let _ = writeln!(s, "| {} | none | — | — | — |", m.label());
            }
        }
    }

    let conv = stats::convergence_series(result);
    if !conv.is_empty() {
        let _ = writeln!(s, "\n## Convergence in mesh size\n");
        let _ = writeln!(
            s,
            "| method | ratio | steps | μ | slope of log(error)/log(h) | finest error |"
        );
        let _ = writeln!(s, "| --- | --- | --- | --- | --- | --- |");
        for c in conv {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {:.3e} |",
                c.method.label(),
                short_number(c.setting.stiffness_ratio),
                c.setting.steps,
                short_number(c.setting.coulomb),
                c.slope
                    .map(|x| format!("{x:.2}"))
                    .unwrap_or_else(|| "—".into()),
                c.points.first().map(|p| p.1).unwrap_or(f64::NAN)
            );
        }
    }

    let failures: Vec<_> = result
        .records
        .iter()
        .filter(|r| r.status != Status::Converged)
        .collect();
    let _ = writeln!(
        s,
        "\n## Runs that failed or gave a wrong answer ({})\n",
        failures.len()
    );
    if !failures.is_empty() {
        let _ = writeln!(
            s,
            "| run | method | refine | ratio | steps | μ | status | reason |"
        );
        let _ = writeln!(s, "| --- | --- | --- | --- | --- | --- | --- | --- |");
        for r in failures {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} ({}) | {} |",
                r.point.index,
                r.point.method.label(),
                r.point.refine,
                short_number(r.point.stiffness_ratio),
                r.point.steps,
                short_number(r.point.coulomb),
                r.status,
                r.kind.map(|k| k.name()).unwrap_or(""),
                r.reason.as_deref().unwrap_or("").replace('|', "\\|")
            );
        }
    }
    s
}
