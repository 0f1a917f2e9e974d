//! `aster explain CMD[/KEYWORD/...]`: the keyword tree of a command, or the
//! facts of one keyword (status, type, default, allowed values, conditions).

pub fn run(path: &str) -> u8 {
    match aster_catalog::explain::explain(path) {
        Ok(text) => {
            print!("{text}");
            0
        }
        Err(e) => {
            eprintln!("aster explain: {e}");
            1
        }
    }
}
