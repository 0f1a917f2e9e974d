//! `aster lsp`: the language server on stdin/stdout (crate `aster-lsp`).

pub fn run() -> u8 {
    match aster_lsp::run_stdio() {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("aster lsp: {e}");
            2
        }
    }
}
