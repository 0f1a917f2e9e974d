//! `aster run CASE [--mesh PATH] [--out DIR]`: runs a `.comm` or `.export`,
//! prints each TEST_RESU check as code_aster does and a last line
//! `TEST_RESU: <n> OK, <m> NOOK`. Exit 0 iff every check is OK, 1 if any is
//! NOOK, 2 when the run stops on an error.

use std::path::Path;

pub fn run(case: &Path, mesh: Option<&Path>, out: &Path) -> u8 {
    let prepared = match aster_run::program::prepare(case, mesh, out) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    let outcome = aster_run::program::run(&prepared, Box::new(std::io::stdout()));
    if let Some(e) = &outcome.error {
        // Errors of the program carry `file:line:col: error:` already.
        if e.message.contains(": error: ") {
            eprintln!("{e}");
        } else {
            eprintln!("error: {e}");
        }
    }
    // The summary line always ends the output, so a stopped run still
    // reports the checks it made.
    println!("{}", outcome.tally.summary());
    if outcome.error.is_some() {
        2
    } else if outcome.tally.nook > 0 {
        1
    } else {
        0
    }
}
