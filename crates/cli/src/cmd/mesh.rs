//! `aster mesh`.

pub fn run_placeholder() -> u8 {
    eprintln!("aster mesh: not implemented yet");
    2
}

pub fn run(
    _file: &std::path::Path,
    _json: bool,
    _to: Option<&str>,
    _out: Option<&std::path::Path>,
) -> u8 {
    run_placeholder()
}
