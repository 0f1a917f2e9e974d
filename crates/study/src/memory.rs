//! Peak memory of a run, from Linux's `/proc/self/status` (`VmHWM`, the
//! peak resident set size). Before each run the peak is reset by writing
//! `5` to `/proc/self/clear_refs`, so `VmHWM` after the run is the peak
//! *during* it (it includes what the process held before: the baseline).
//! Elsewhere, or when the reset is refused, the figure is `None` rather
//! than a wrong number.

use std::fs;

/// Resets the peak-RSS counter; returns whether it worked.
pub fn reset_peak() -> bool {
    fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// The peak resident set size in KiB (`VmHWM`).
pub fn peak_kib() -> Option<u64> {
    status_field("VmHWM:")
}

/// The current resident set size in KiB (`VmRSS`).
pub fn current_kib() -> Option<u64> {
    status_field("VmRSS:")
}

fn status_field(name: &str) -> Option<u64> {
    let status = fs::read_to_string("/proc/self/status").ok()?;
    parse_kib(&status, name)
}

fn parse_kib(status: &str, name: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with(name))?;
    line[name.len()..]
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_status_lines() {
        let s = "Name:\taster\nVmHWM:\t   12345 kB\nVmRSS:\t  2048 kB\n";
        assert_eq!(parse_kib(s, "VmHWM:"), Some(12345));
        assert_eq!(parse_kib(s, "VmRSS:"), Some(2048));
        assert_eq!(parse_kib(s, "VmPeak:"), None);
    }

    #[test]
    fn peak_follows_a_large_allocation() {
        if !reset_peak() {
            eprintln!("skipped: /proc/self/clear_refs not writable here");
            return;
        }
        let before = peak_kib().unwrap_or(0);
        let big = vec![1u8; 64 << 20];
        let after = peak_kib().unwrap_or(0);
        assert!(big.iter().step_by(4096).all(|&b| b == 1));
        assert!(after >= before + 60_000, "peak {before} -> {after} KiB");
    }
}
