//! Running the `aster` binary from the CLI tests: one helper for all of
//! them.
#![allow(dead_code)]

use std::path::Path;
use std::process::Command;

/// Runs `aster ARGS` in the current folder: (exit code, stdout, stderr).
pub fn aster(args: &[&str]) -> (i32, String, String) {
    output(Command::new(env!("CARGO_BIN_EXE_aster")).args(args))
}

/// Runs `aster ARGS` in `dir`: (exit code, stdout, stderr).
pub fn aster_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    output(
        Command::new(env!("CARGO_BIN_EXE_aster"))
            .args(args)
            .current_dir(dir),
    )
}

fn output(command: &mut Command) -> (i32, String, String) {
    let out = command.output().expect("run aster");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}
