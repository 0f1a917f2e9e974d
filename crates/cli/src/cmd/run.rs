//! `aster run`.

pub fn run_placeholder() -> u8 {
    eprintln!("aster run: not implemented yet");
    2
}

pub fn run(_case: &std::path::Path, _mesh: Option<&std::path::Path>, _out: &std::path::Path) -> u8 {
    run_placeholder()
}
