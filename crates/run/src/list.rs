//! Lists of reals (`DEFI_LIST_REEL`) and of time instants (`DEFI_LIST_INST`).

use std::fmt;

/// One `INTERVALLE` occurrence: up to `end`, in `count` equal steps or with
/// a step `step`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Interval {
    Count { end: f64, count: usize },
    Step { end: f64, step: f64 },
}

#[derive(Clone, Debug, PartialEq)]
pub enum ListError {
    Empty,
    ZeroCount {
        index: usize,
    },
    BadStep {
        index: usize,
        start: f64,
        end: f64,
        step: f64,
    },
    NotIncreasing {
        index: usize,
        previous: f64,
        next: f64,
    },
    /// More values than [`MAX_VALUES`] (checked before building them).
    TooLong {
        index: usize,
        values: f64,
    },
}

/// The most values a list may hold (80 MB of reals): a step or a count
/// asking for more is refused before anything is allocated.
pub const MAX_VALUES: usize = 10_000_000;

impl fmt::Display for ListError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ListError::Empty => write!(f, "the list is empty"),
            ListError::ZeroCount { index } => {
                write!(f, "INTERVALLE[{}]: NOMBRE must be at least 1", index + 1)
            }
            ListError::BadStep {
                index,
                start,
                end,
                step,
            } => write!(
                f,
                "INTERVALLE[{}]: PAS={step} cannot go from {start} to JUSQU_A={end} \
                 (the step must be positive and the end after the start)",
                index + 1
            ),
            ListError::NotIncreasing {
                index,
                previous,
                next,
            } => write!(
                f,
                "values must be strictly increasing: value {} is {next} after {previous}",
                index + 1
            ),
            ListError::TooLong { index, values } => write!(
                f,
                "INTERVALLE[{}]: result too large: {values:.3e} values (at most {MAX_VALUES})",
                index + 1
            ),
        }
    }
}

/// `DEFI_LIST_REEL(DEBUT=…, INTERVALLE=…)`: the start then each interval's
/// points. Points are computed as start + i·(end − start)/n so the end of an
/// interval is exact (no accumulated rounding).
pub fn from_intervals(start: f64, intervals: &[Interval]) -> Result<Vec<f64>, ListError> {
    let mut out = vec![start];
    let mut from = start;
    for (index, interval) in intervals.iter().enumerate() {
        let (end, n) = match *interval {
            Interval::Count { end, count } => {
                if count == 0 {
                    return Err(ListError::ZeroCount { index });
                }
                (end, count)
            }
            Interval::Step { end, step } => {
                if step <= 0.0 || end <= from {
                    return Err(ListError::BadStep {
                        index,
                        start: from,
                        end,
                        step,
                    });
                }
                // Tolerate rounding: 1.0/0.1 is 9.999…
                let n = ((end - from) / step * (1.0 + 1e-12)).round().max(1.0);
                if n.is_nan() || n > MAX_VALUES as f64 {
                    return Err(ListError::TooLong { index, values: n });
                }
                (end, n as usize)
            }
        };
        if n > MAX_VALUES.saturating_sub(out.len()) {
            return Err(ListError::TooLong {
                index,
                values: n as f64,
            });
        }
        for i in 1..=n {
            out.push(if i == n {
                end
            } else {
                from + (end - from) * (i as f64) / (n as f64)
            });
        }
        from = end;
    }
    check_increasing(&out)?;
    Ok(out)
}

/// `DEFI_LIST_REEL(VALE=…)`.
pub fn from_values(values: &[f64]) -> Result<Vec<f64>, ListError> {
    if values.is_empty() {
        return Err(ListError::Empty);
    }
    check_increasing(values)?;
    Ok(values.to_vec())
}

fn check_increasing(values: &[f64]) -> Result<(), ListError> {
    for (i, w) in values.windows(2).enumerate() {
        if w[1] <= w[0] {
            return Err(ListError::NotIncreasing {
                index: i + 1,
                previous: w[0],
                next: w[1],
            });
        }
    }
    Ok(())
}

/// The instants a non-linear computation visits: those of the list between
/// `INST_INIT` (default: the first) and `INST_FIN` (default: the last). The
/// first instant is the initial state; each following one is a step.
/// Instants are matched with code_aster's relative precision on times.
pub fn select_instants(
    list: &[f64],
    init: Option<f64>,
    fin: Option<f64>,
) -> Result<Vec<f64>, String> {
    if list.is_empty() {
        return Err("the time list is empty".into());
    }
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * a.abs().max(b.abs()).max(1e-300);
    let lo = init.unwrap_or(list[0]);
    let hi = fin.unwrap_or(list[list.len() - 1]);
    if hi < lo && !close(hi, lo) {
        return Err(format!("INST_FIN={hi} is before INST_INIT={lo}"));
    }
    let mut out: Vec<f64> = Vec::new();
    if !list.iter().any(|&t| close(t, lo)) {
        // code_aster starts from an instant outside the list when it is
        // before the first one (the initial state is at INST_INIT).
        out.push(lo);
    }
    out.extend(
        list.iter()
            .copied()
            .filter(|&t| (t > lo || close(t, lo)) && (t < hi || close(t, hi))),
    );
    if !out.iter().any(|&t| close(t, hi)) {
        return Err(format!(
            "INST_FIN={hi} is not an instant of the list (from {} to {})",
            list[0],
            list[list.len() - 1]
        ));
    }
    if out.len() < 2 {
        return Err(format!(
            "no time step between INST_INIT={lo} and INST_FIN={hi}"
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_lists_are_refused_before_building() {
        let e = from_intervals(
            0.0,
            &[Interval::Step {
                end: 1.0,
                step: 1e-9,
            }],
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "INTERVALLE[1]: result too large: 1.000e9 values (at most 10000000)"
        );
        let e = from_intervals(
            0.0,
            &[Interval::Count {
                end: 1.0,
                count: 1_000_000_000,
            }],
        )
        .unwrap_err();
        assert!(matches!(e, ListError::TooLong { index: 0, .. }), "{e}");
    }

    #[test]
    fn twenty_steps_to_twenty() {
        let l = from_intervals(
            0.0,
            &[Interval::Count {
                end: 20.0,
                count: 20,
            }],
        )
        .unwrap();
        assert_eq!(l.len(), 21);
        assert_eq!(l[0], 0.0);
        assert_eq!(l[20], 20.0);
        assert_eq!(l[7], 7.0);
    }

    #[test]
    fn step_and_chained_intervals() {
        let l = from_intervals(
            0.0,
            &[
                Interval::Step {
                    end: 1.0,
                    step: 0.1,
                },
                Interval::Count { end: 3.0, count: 2 },
            ],
        )
        .unwrap();
        assert_eq!(l.len(), 13);
        assert_eq!(l[10], 1.0);
        assert_eq!(l[11], 2.0);
        assert_eq!(l[12], 3.0);
    }

    #[test]
    fn errors_teach() {
        let e = from_intervals(
            1.0,
            &[Interval::Step {
                end: 0.0,
                step: 0.5,
            }],
        )
        .unwrap_err();
        assert!(e.to_string().contains("JUSQU_A=0"), "{e}");
        let e = from_values(&[0.0, 2.0, 1.0]).unwrap_err();
        assert!(e.to_string().contains("value 3 is 1 after 2"), "{e}");
    }

    #[test]
    fn instant_selection() {
        let l: Vec<f64> = (0..=20).map(f64::from).collect();
        assert_eq!(select_instants(&l, None, None).unwrap().len(), 21);
        let s = select_instants(&l, Some(5.0), Some(10.0)).unwrap();
        assert_eq!(s, vec![5.0, 6.0, 7.0, 8.0, 9.0, 10.0]);
        assert!(select_instants(&l, None, Some(10.5)).is_err());
    }
}
