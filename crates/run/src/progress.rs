//! Live progress of a run: one line per command with its time and, while
//! STAT_NON_LINE/DYNA_NON_LINE solve, a code_aster-style table per
//! increment (instant, Newton iteration, RESI_GLOB_RELA, RESI_GLOB_MAXI,
//! contact iterations, re-pairings, time). Written to stderr (unless `-q`)
//! and to the `.mess` file of the `.export`. The numerics report through
//! [`aster_fem::progress`]; they know nothing of this text.

use crate::pyfmt::c_exp;
use aster_fem::progress::{Event, Observer};
use std::cell::RefCell;
use std::io::Write;
use std::rc::Rc;
use std::time::Instant;

struct Out {
    stderr: bool,
    mess: Option<std::fs::File>,
}

/// Where progress goes (cheap to clone; nowhere by default).
#[derive(Clone, Default)]
pub struct Progress(Option<Rc<RefCell<Out>>>);

impl Progress {
    /// Progress to stderr when `stderr`, and to `mess` when given.
    pub fn new(stderr: bool, mess: Option<std::fs::File>) -> Progress {
        if !stderr && mess.is_none() {
            return Progress(None);
        }
        Progress(Some(Rc::new(RefCell::new(Out { stderr, mess }))))
    }

    pub fn is_on(&self) -> bool {
        self.0.is_some()
    }

    /// Writes one line (a newline is added).
    pub fn line(&self, text: &str) {
        let Some(out) = &self.0 else { return };
        let Ok(mut out) = out.try_borrow_mut() else {
            return;
        };
        // One `write` per line (stderr and the file are unbuffered:
        // `writeln!` would make two).
        let mut line = String::with_capacity(text.len() + 1);
        line.push_str(text);
        line.push('\n');
        if out.stderr {
            let _ = std::io::stderr().write_all(line.as_bytes());
        }
        if let Some(f) = out.mess.as_mut() {
            let _ = f.write_all(line.as_bytes());
        }
    }

    /// The observer of the numerics' solves writing the increment tables.
    pub fn observer(&self) -> Box<dyn Observer> {
        Box::new(Table {
            out: self.clone(),
            increment: None,
            started: Instant::now(),
        })
    }
}

/// The line of one finished command.
pub fn command_line(command: &str, result: Option<&str>, seconds: f64, at: &str) -> String {
    let what = match result {
        Some(r) => format!("{r} = {command}"),
        None => command.to_string(),
    };
    format!("{what:<36} {seconds:>9.3} s  {at}")
}

/// The rule of the table.
const RULE: &str =
    "  +-----------+----------------+----------------+-----------+-----------+-----------+";

/// The head of one increment's table.
pub fn table_head(time: f64) -> String {
    format!(
        "  instant {}\n{RULE}\n  |  NEWTON   | RESI_GLOB_RELA | RESI_GLOB_MAXI |  CONTACT  | PAIRINGS  |   TIME    |\n  | ITERATION |                |                | ITERATION |           |  (s)      |\n{RULE}",
        c_exp(time, 0, 6)
    )
}

/// One row: an iteration of the increment (`*`: the pass moved the
/// contact active set or the pairing, another pass follows).
pub fn table_row(it: &aster_fem::progress::Iteration, seconds: f64) -> String {
    format!(
        "  | {:>8}{} | {} | {} | {:>9} | {:>9} | {:>9.3} |",
        it.newton,
        if it.active_set_changed { "*" } else { " " },
        c_exp(it.resi_glob_rela, 14, 5),
        c_exp(it.resi_glob_maxi, 14, 5),
        it.contact_iterations,
        it.pairings,
        seconds
    )
}

/// Writes the tables of the increments as they converge.
struct Table {
    out: Progress,
    /// The instant whose table is open.
    increment: Option<f64>,
    started: Instant,
}

impl Observer for Table {
    fn event(&mut self, event: &Event) {
        // Nothing to format when the progress goes nowhere (`-q`).
        if !self.out.is_on() {
            return;
        }
        match event {
            Event::Iteration(it) => {
                if self.increment != Some(it.time) {
                    self.increment = Some(it.time);
                    self.started = Instant::now();
                    self.out.line(&table_head(it.time));
                }
                self.out
                    .line(&table_row(it, self.started.elapsed().as_secs_f64()));
            }
            Event::Converged { time, iterations } => {
                self.out.line(RULE);
                self.out.line(&format!(
                    "  instant {} converged in {iterations} Newton iteration(s)",
                    c_exp(*time, 0, 6)
                ));
                self.increment = None;
            }
            Event::Cut { from, to, pieces } => {
                self.out.line(RULE);
                self.out.line(&format!(
                    "  increment {} -> {} failed: cut in {pieces}",
                    c_exp(*from, 0, 6),
                    c_exp(*to, 0, 6)
                ));
                self.increment = None;
            }
            Event::Redo {
                from,
                to,
                penetration,
            } => {
                self.out.line(RULE);
                self.out.line(&format!(
                    "  increment {} -> {} redone: penetration {} beyond PENE_MAXI, penalty doubled",
                    c_exp(*from, 0, 6),
                    c_exp(*to, 0, 6),
                    c_exp(*penetration, 0, 6)
                ));
                self.increment = None;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_fem::progress::Iteration;

    #[test]
    fn increment_table() {
        let it = |newton, rela, maxi, contact, pairings, changed| Iteration {
            time: 0.5,
            newton,
            resi_glob_rela: rela,
            resi_glob_maxi: maxi,
            contact_iterations: contact,
            pairings,
            active_set_changed: changed,
        };
        let mut text = table_head(0.5);
        text.push('\n');
        for (i, row) in [
            it(1, 1.0, 2.5e3, 0, 0, true),
            it(1, 3.2e-3, 8.0, 1, 0, false),
            it(2, 4.1e-9, 1.0e-5, 1, 1, false),
        ]
        .iter()
        .enumerate()
        {
            text.push_str(&table_row(row, 0.25 * i as f64));
            text.push('\n');
        }
        text.push_str(&command_line(
            "STAT_NON_LINE",
            Some("RESU"),
            1.5,
            "case.comm:12:8",
        ));
        insta::assert_snapshot!(text);
    }
}
