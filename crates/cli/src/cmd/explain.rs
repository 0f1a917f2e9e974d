//! `aster explain`.

pub fn run_placeholder() -> u8 {
    eprintln!("aster explain: not implemented yet");
    2
}

pub fn run(_path: &str) -> u8 {
    run_placeholder()
}
