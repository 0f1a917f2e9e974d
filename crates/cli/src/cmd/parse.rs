//! `aster parse`.

pub fn run_placeholder() -> u8 {
    eprintln!("aster parse: not implemented yet");
    2
}

pub fn run(_files: &[std::path::PathBuf], _json: bool) -> u8 {
    run_placeholder()
}
