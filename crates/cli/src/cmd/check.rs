//! `aster check`.

pub fn run_placeholder() -> u8 {
    eprintln!("aster check: not implemented yet");
    2
}

pub fn run(_files: &[std::path::PathBuf], _emit: Option<&str>) -> u8 {
    run_placeholder()
}
