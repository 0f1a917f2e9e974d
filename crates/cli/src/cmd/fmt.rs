//! `aster fmt`.

pub fn run_placeholder() -> u8 {
    eprintln!("aster fmt: not implemented yet");
    2
}

pub fn run(_file: &std::path::Path) -> u8 {
    run_placeholder()
}
