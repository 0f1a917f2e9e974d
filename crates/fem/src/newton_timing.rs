//! Where a non-linear solve's time goes (`ASTER_NEWTON_TIMING=1`): the
//! Newton iterations' time split into the behaviour integration (internal
//! forces and the material tangent at every Gauss point), the assembly of
//! the tangent matrix, the factorisations (symbolic and numeric), the
//! solves (triangular solves, the Schur complement of the constraint rows,
//! iterative refinement) and contact (rows, pairing, the friction force
//! sources' own terms); printed on stderr when the solve ends, with the
//! time per iteration and the fraction spent outside the linear solver.
//!
//! Each phase counts its own time only: a phase entered inside another
//! (a factorisation inside a contact source's solve) pauses the outer one.
//! Times are wall and process CPU (`CLOCK_PROCESS_CPUTIME_ID`: all threads,
//! so a factorisation on two cores counts twice its wall time); on a shared
//! machine the CPU figures are the steadier. When the variable is not set
//! nothing is measured (one flag read per phase).

use std::cell::RefCell;
use std::sync::OnceLock;
use std::time::Instant;

/// A part of a Newton iteration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Internal forces and the behaviour's integration at the Gauss points.
    Behaviour,
    /// The tangent matrix: element matrices scattered into the pattern,
    /// restriction to the free unknowns, extra (penalty, bordered) terms.
    Assembly,
    /// Symbolic and numeric factorisation.
    Factorisation,
    /// Triangular solves, Schur complement of the rows, refinement.
    Solve,
    /// The residuals of the bordered system in compensated arithmetic
    /// (refinement's backward error; part of the linear solver).
    Residuals,
    /// The columns K⁻¹aᵣ of the constraint rows not yet seen with the
    /// current factor (the Schur complement's solves; part of the linear
    /// solver).
    RowColumns,
    /// Contact and friction: rows, pairing, force sources' terms.
    Contact,
}

const PHASES: [(Phase, &str); 7] = [
    (
        Phase::Behaviour,
        "behaviour (internal forces, Gauss points)",
    ),
    (Phase::Assembly, "tangent assembly"),
    (Phase::Factorisation, "factorisation (symbolic + numeric)"),
    (
        Phase::Solve,
        "solve (substitutions, Schur rows, refinement)",
    ),
    (
        Phase::RowColumns,
        "solve: the rows' columns K^-1 a_r (new factor)",
    ),
    (
        Phase::Residuals,
        "solve: refinement's compensated residuals",
    ),
    (Phase::Contact, "contact and friction"),
];

fn index(p: Phase) -> usize {
    PHASES.iter().position(|(q, _)| *q == p).unwrap_or(0)
}

/// The timing is on (`ASTER_NEWTON_TIMING` set).
pub fn enabled() -> bool {
    static ON: OnceLock<bool> = OnceLock::new();
    *ON.get_or_init(|| std::env::var_os("ASTER_NEWTON_TIMING").is_some())
}

fn cpu_now() -> f64 {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ProcessCPUTime);
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

#[derive(Clone, Copy, Default)]
struct Times {
    wall: f64,
    cpu: f64,
}

#[derive(Default)]
struct State {
    /// Phases in progress, innermost last, with the time their current
    /// stretch started.
    stack: Vec<(usize, Instant, f64)>,
    totals: [Times; 7],
    /// Newton iterations (linear solves of the Newton loop) counted.
    iterations: usize,
    /// The whole solve, from its start.
    start: Option<(Instant, f64)>,
}

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

/// A phase in progress; it ends when dropped.
pub struct PhaseGuard {
    on: bool,
}

/// Starts timing `phase` (nothing when the timing is off).
pub fn phase(phase: Phase) -> PhaseGuard {
    if !enabled() {
        return PhaseGuard { on: false };
    }
    let (now, cpu) = (Instant::now(), cpu_now());
    STATE.with(|s| {
        let mut s = s.borrow_mut();
        if let Some(&(outer, since, cpu_since)) = s.stack.last() {
            let t = &mut s.totals[outer];
            t.wall += now.duration_since(since).as_secs_f64();
            t.cpu += cpu - cpu_since;
        }
        s.stack.push((index(phase), now, cpu));
    });
    PhaseGuard { on: true }
}

impl Drop for PhaseGuard {
    fn drop(&mut self) {
        if !self.on {
            return;
        }
        let (now, cpu) = (Instant::now(), cpu_now());
        STATE.with(|s| {
            let mut s = s.borrow_mut();
            if let Some((p, since, cpu_since)) = s.stack.pop() {
                let t = &mut s.totals[p];
                t.wall += now.duration_since(since).as_secs_f64();
                t.cpu += cpu - cpu_since;
            }
            if let Some(outer) = s.stack.last_mut() {
                outer.1 = now;
                outer.2 = cpu;
            }
        });
    }
}

/// Times `f` as `p`.
pub fn timed<T>(p: Phase, f: impl FnOnce() -> T) -> T {
    let _g = phase(p);
    f()
}

/// A Newton iteration was solved (counted for the per-iteration figures).
pub fn count_iteration() {
    if enabled() {
        STATE.with(|s| s.borrow_mut().iterations += 1);
    }
}

/// A non-linear solve starts: the counters are reset.
pub fn begin_solve() {
    if enabled() {
        STATE.with(|s| {
            *s.borrow_mut() = State {
                start: Some((Instant::now(), cpu_now())),
                ..State::default()
            }
        });
    }
}

/// A non-linear solve ended: its split, as printed on stderr.
pub fn end_solve(what: &str) {
    if !enabled() {
        return;
    }
    let report = STATE.with(|s| report(&s.borrow(), what));
    eprint!("{report}");
}

fn report(s: &State, what: &str) -> String {
    let Some((start, cpu0)) = s.start else {
        return String::new();
    };
    let total = Times {
        wall: start.elapsed().as_secs_f64(),
        cpu: cpu_now() - cpu0,
    };
    let n = s.iterations.max(1);
    let mut out = format!(
        "[newton] {what}: {} iterations, {:.3} s wall, {:.3} s CPU; per iteration (ms wall / ms CPU / share of CPU):\n",
        s.iterations, total.wall, total.cpu
    );
    let mut counted = Times::default();
    let line = |name: &str, t: Times| {
        format!(
            "[newton]   {name:<48} {:>9.3} {:>9.3} {:>6.1} %\n",
            t.wall * 1e3 / n as f64,
            t.cpu * 1e3 / n as f64,
            100.0 * t.cpu / total.cpu.max(1e-12)
        )
    };
    for (i, (_, name)) in PHASES.iter().enumerate() {
        let t = s.totals[i];
        counted.wall += t.wall;
        counted.cpu += t.cpu;
        out.push_str(&line(name, t));
    }
    let rest = Times {
        wall: (total.wall - counted.wall).max(0.0),
        cpu: (total.cpu - counted.cpu).max(0.0),
    };
    out.push_str(&line("other (residuals, active sets, bookkeeping)", rest));
    let linear = s.totals[index(Phase::Factorisation)].cpu
        + s.totals[index(Phase::Solve)].cpu
        + s.totals[index(Phase::RowColumns)].cpu
        + s.totals[index(Phase::Residuals)].cpu;
    out.push_str(&format!(
        "[newton]   outside the linear solver (factorisation + solve): {:.1} % of CPU\n",
        100.0 * (1.0 - linear / total.cpu.max(1e-12))
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_names_every_phase() {
        let mut s = State {
            start: Some((Instant::now(), cpu_now())),
            ..State::default()
        };
        s.totals[index(Phase::Solve)] = Times {
            wall: 0.5,
            cpu: 0.5,
        };
        s.iterations = 2;
        let r = report(&s, "test");
        assert!(r.contains("2 iterations"), "{r}");
        assert!(r.contains("outside the linear solver"), "{r}");
    }
}
