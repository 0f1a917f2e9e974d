//! The study's clock: CPU time of the calling thread (user + system), from
//! `CLOCK_THREAD_CPUTIME_ID`.
//!
//! Why CPU time rather than wall time: the study runs on machines shared
//! with builds, where a run's wall time can double when another process
//! takes the core; its CPU time barely moves. Why the thread's: a study
//! runs its points one after the other on one thread, with faer's
//! parallelism turned off ([`run_sequentially`]), so the thread's CPU time
//! is the run's whole cost — and other threads of the process (a test
//! harness running tests in parallel) do not leak into it.

use rustix::time::{clock_gettime, ClockId};

/// Makes faer (factorisations and solves) run on the calling thread, so
/// that [`cpu_now`] sees all of a run's work. Affects the whole process.
pub fn run_sequentially() {
    faer::set_global_parallelism(faer::Par::Seq);
}

/// CPU seconds consumed by the calling thread so far.
pub fn cpu_now() -> f64 {
    let t = clock_gettime(ClockId::ThreadCPUTime);
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// CPU seconds since `start` (a value of [`cpu_now`]).
pub fn cpu_since(start: f64) -> f64 {
    (cpu_now() - start).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpu_time_follows_work() {
        let start = cpu_now();
        let mut acc = 0.0f64;
        let mut i = 0u64;
        while cpu_since(start) < 0.02 {
            acc += (i as f64).sqrt();
            i += 1;
        }
        assert!(acc > 0.0 && i > 1000, "{i} iterations in 20 ms of CPU");
        let spent = cpu_since(start);
        assert!((0.02..1.0).contains(&spent), "{spent}");
    }
}
