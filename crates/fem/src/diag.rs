//! Timing diagnostics (`ASTER_FEM_TIMING=1`): CPU times and page faults.
//!
//! On a shared machine wall times mostly measure the others' load; user and
//! system CPU and the minor page faults (each fresh page costs system time:
//! ~0.8 s per GB first touched on the reference machine) say what this
//! process did.

/// The process's CPU times and minor page faults so far, for timing
/// diagnostics (`ASTER_FEM_TIMING`): " (user U s, sys S s, F faults)", or
/// nothing where /proc is absent.
pub(crate) fn process_usage() -> String {
    usage_of("/proc/self/stat")
}

/// [`process_usage`] for the calling thread only.
pub(crate) fn thread_usage() -> String {
    usage_of("/proc/thread-self/stat")
}

fn usage_of(path: &str) -> String {
    let Ok(stat) = std::fs::read_to_string(path) else {
        return String::new();
    };
    // Fields after the parenthesised command name: minflt is the 10th field
    // of the line, utime the 14th, stime the 15th (7, 11, 12 here).
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let num = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.);
    format!(
        " (user {:.2} s, sys {:.2} s, {} faults)",
        num(11) / 100.0,
        num(12) / 100.0,
        num(7)
    )
}
