//! Small statistics over the runs: log-log slopes, the Pareto front, the
//! fastest run at a given accuracy.

use crate::engine::{RunRecord, StudyResult};
use crate::method::Method;
use crate::outcome::Status;
use crate::spec::Setting;

/// Least-squares slope of log(y) against log(x) over points with x, y > 0;
/// `None` with fewer than two distinct x.
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return None;
    }
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 1e-300).then(|| sxy / sxx)
}

/// Runs usable on an error chart: converged, with a positive error.
pub fn plotted(result: &StudyResult) -> impl Iterator<Item = &RunRecord> {
    result
        .records
        .iter()
        .filter(|r| r.status == Status::Converged && r.error.is_some_and(|e| e > 0.0))
}

/// The converged runs not dominated in (time, error): no other run is both
/// faster and more accurate. Sorted by time.
pub fn pareto_front(result: &StudyResult) -> Vec<&RunRecord> {
    let mut runs: Vec<&RunRecord> = result
        .records
        .iter()
        .filter(|r| r.status == Status::Converged && r.error.is_some())
        .collect();
    runs.sort_by(|a, b| a.seconds().total_cmp(&b.seconds()));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for r in runs {
        let e = r.error.unwrap_or(f64::INFINITY);
        if e < best {
            best = e;
            front.push(r);
        }
    }
    front
}

/// The fastest converged run whose error is within `target`.
pub fn fastest_within(result: &StudyResult, target: f64) -> Option<&RunRecord> {
    result
        .records
        .iter()
        .filter(|r| r.status == Status::Converged && r.error.is_some_and(|e| e <= target))
        .min_by(|a, b| a.seconds().total_cmp(&b.seconds()))
}

/// The fastest run within `target` for each method (spec order).
pub fn fastest_per_method(result: &StudyResult, target: f64) -> Vec<(Method, Option<&RunRecord>)> {
    result
        .spec
        .methods
        .iter()
        .map(|&m| {
            let best = result
                .records
                .iter()
                .filter(|r| {
                    r.point.method == m
                        && r.status == Status::Converged
                        && r.error.is_some_and(|e| e <= target)
                })
                .min_by(|a, b| a.seconds().total_cmp(&b.seconds()));
            (m, best)
        })
        .collect()
}

/// Convergence in mesh size of one method at one setting: the (h, error)
/// points and their fitted slope.
#[derive(Clone, Debug, PartialEq)]
pub struct Convergence {
    pub method: Method,
    pub setting: Setting,
    pub points: Vec<(f64, f64)>,
    pub slope: Option<f64>,
}

/// One convergence series per (method, setting) with at least two
/// plotted points of distinct h.
pub fn convergence_series(result: &StudyResult) -> Vec<Convergence> {
    let mut out = Vec::new();
    let settings = result.spec.settings();
    for &method in &result.spec.methods {
        for &setting in &settings {
            let mut points: Vec<(f64, f64)> = plotted(result)
                .filter(|r| r.point.method == method && r.point.setting() == setting)
                .filter_map(|r| Some((r.measures.as_ref()?.h, r.error?)))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            points.dedup_by(|a, b| a.0 == b.0);
            if points.len() >= 2 {
                let slope = loglog_slope(&points);
                out.push(Convergence {
                    method,
                    setting,
                    points,
                    slope,
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_a_power_law() {
        let pts: Vec<(f64, f64)> = [0.5, 0.25, 0.125]
            .iter()
            .map(|&h| (h, 3.0 * h * h))
            .collect();
        let s = loglog_slope(&pts).unwrap();
        assert!((s - 2.0).abs() < 1e-12, "{s}");
        assert_eq!(loglog_slope(&[(1.0, 1.0)]), None);
        assert_eq!(loglog_slope(&[(1.0, 1.0), (1.0, 2.0)]), None);
    }
}
