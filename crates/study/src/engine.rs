//! The sweep: runs every point, times it, records measures or the reason it
//! failed, then resolves errors against the reference.

use crate::clock::{cpu_now, cpu_since};
use crate::memory;
use crate::method::Method;
use crate::outcome::{Failure, FailureKind, Measures, Status};
use crate::scene::Scene;
use crate::spec::{Point, Reference, Setting, StudySpec};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// Whether to draw a progress bar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// On stderr, when stderr is a terminal.
    Auto,
    Hidden,
}

/// One run of the sweep and its verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct RunRecord {
    pub point: Point,
    pub status: Status,
    /// Why the run failed or is wrong (`None` when converged).
    pub kind: Option<FailureKind>,
    pub reason: Option<String>,
    /// What the run measured, if it got that far.
    pub measures: Option<Measures>,
    /// Wall time of the kept run, seconds.
    pub wall_seconds: f64,
    /// CPU time of the kept run (the fastest of `repeat` in CPU time),
    /// seconds: the study's measure of speed (see [`crate::clock`]).
    pub cpu_seconds: f64,
    /// Peak resident memory during the run, KiB (see [`crate::memory`]).
    pub peak_rss_kib: Option<u64>,
    /// Relative error |value − reference| / |reference|, when both exist.
    pub error: Option<f64>,
    /// The reference value the error was computed against.
    pub reference: Option<f64>,
}

impl RunRecord {
    /// The run's time for comparisons (Pareto front, fastest method): its
    /// CPU time.
    pub fn seconds(&self) -> f64 {
        self.cpu_seconds
    }

    /// Share of the run's CPU time spent outside the linear solver, when
    /// the scene reported the solver's time.
    pub fn outside_solver_fraction(&self) -> Option<f64> {
        let s = self.measures.as_ref()?.solver_seconds?;
        (self.cpu_seconds > 0.0).then(|| ((self.cpu_seconds - s) / self.cpu_seconds).max(0.0))
    }
}

/// A finished study.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyResult {
    pub spec: StudySpec,
    pub quantity: String,
    pub scene: String,
    pub records: Vec<RunRecord>,
}

/// Runs every point of the spec on the scene. Never fails: each run's
/// failure (including a panic) is recorded in its [`RunRecord`].
pub fn run_study(spec: &StudySpec, scene: &dyn Scene, progress: Progress) -> StudyResult {
    // One thread does all of a run's work: its CPU time is the run's cost.
    crate::clock::run_sequentially();
    let points = spec.points();
    let bar = progress_bar(points.len() as u64, progress);
    let mut records = Vec::with_capacity(points.len());
    for point in &points {
        bar.set_message(format!("{} refine {}", point.method.label(), point.refine));
        records.push(run_point(scene, point, spec.repeat));
        bar.inc(1);
    }
    bar.finish_and_clear();
    resolve_errors(spec, &mut records);
    StudyResult {
        spec: spec.clone(),
        quantity: scene.quantity(),
        scene: scene.describe(),
        records,
    }
}

fn progress_bar(len: u64, progress: Progress) -> ProgressBar {
    if progress == Progress::Hidden || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{bar:30} {pos}/{len} runs, {elapsed} elapsed, eta {eta}: {msg}",
    ) {
        bar.set_style(style);
    }
    bar
}

/// One execution of a point: CPU and wall seconds, peak RSS, outcome.
struct Attempt {
    cpu: f64,
    wall: f64,
    peak: Option<u64>,
    outcome: Result<Measures, Failure>,
}

fn run_point(scene: &dyn Scene, point: &Point, repeat: u32) -> RunRecord {
    let mut best: Option<Attempt> = None;
    for _ in 0..repeat.max(1) {
        let reset = memory::reset_peak();
        let start = Instant::now();
        let cpu_start = cpu_now();
        let outcome = catch_unwind(AssertUnwindSafe(|| scene.run(point))).unwrap_or_else(|p| {
            let message = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "unknown panic payload".into());
            Err(Failure::new(
                FailureKind::Panic,
                format!("panicked: {message}"),
            ))
        });
        let cpu = cpu_since(cpu_start);
        let wall = start.elapsed().as_secs_f64();
        let peak = if reset { memory::peak_kib() } else { None };
        let failed = outcome.is_err();
        if best.as_ref().is_none_or(|b| cpu < b.cpu) {
            best = Some(Attempt {
                cpu,
                wall,
                peak,
                outcome,
            });
        }
        // A failing point is not repeated: its failure is the answer.
        if failed {
            break;
        }
    }
    let Attempt {
        cpu: cpu_seconds,
        wall: wall_seconds,
        peak: peak_rss_kib,
        outcome,
    } = best.unwrap_or(Attempt {
        cpu: 0.0,
        wall: 0.0,
        peak: None,
        outcome: Err(Failure::new(FailureKind::Other, "not run")),
    });
    match outcome {
        Ok(m) => RunRecord {
            point: *point,
            status: Status::Converged,
            kind: None,
            reason: None,
            measures: Some(m),
            wall_seconds,
            cpu_seconds,
            peak_rss_kib,
            error: None,
            reference: None,
        },
        Err(f) => RunRecord {
            point: *point,
            status: f.kind.status(),
            kind: Some(f.kind),
            reason: Some(f.message),
            measures: f.measures.map(|m| *m),
            wall_seconds,
            cpu_seconds,
            peak_rss_kib,
            error: None,
            reference: None,
        },
    }
}

/// Fills `error` and `reference`, and turns converged runs whose error
/// exceeds the tolerance into wrong answers.
fn resolve_errors(spec: &StudySpec, records: &mut [RunRecord]) {
    let references: Vec<Option<f64>> = match spec.reference {
        Reference::Analytic => records
            .iter()
            .map(|r| {
                let m = r.measures.as_ref()?;
                m.own_reference.or(m.reference)
            })
            .collect(),
        Reference::Finest => {
            let Some(&first) = spec.methods.first() else {
                return;
            };
            // A run whose scene gives its own reference models another
            // problem (LIAISON_UNIL on a rigid base): it is compared with it.
            records
                .iter()
                .map(|r| {
                    r.measures
                        .as_ref()
                        .and_then(|m| m.own_reference)
                        .or_else(|| finest_value(records, first, r.point.setting()))
                })
                .collect()
        }
    };
    for (r, reference) in records.iter_mut().zip(references) {
        r.reference = reference;
        let (Some(m), Some(reference)) = (&r.measures, reference) else {
            continue;
        };
        let error = if reference != 0.0 {
            (m.value - reference).abs() / reference.abs()
        } else {
            (m.value - reference).abs()
        };
        r.error = Some(error);
        if r.status == Status::Converged && error > spec.tolerance {
            r.status = Status::Wrong;
            r.kind = Some(FailureKind::Inaccurate);
            r.reason = Some(format!(
                "error {:.2}% above the {:.2}% tolerance (value {:.6e}, reference {:.6e})",
                100.0 * error,
                100.0 * spec.tolerance,
                m.value,
                reference
            ));
        }
    }
}

/// The value of the converged run of `method` on the finest mesh for this
/// setting (stiffness ratio, step count, friction coefficient).
fn finest_value(records: &[RunRecord], method: Method, setting: Setting) -> Option<f64> {
    records
        .iter()
        .filter(|r| {
            r.status == Status::Converged
                && r.point.method == method
                && r.point.setting() == setting
        })
        .max_by_key(|r| r.point.refine)
        .and_then(|r| r.measures.as_ref().map(|m| m.value))
}
