//! `aster fmt FILE`: print a command file in canonical form (code_aster 17
//! style, comments kept). Exit 0 on success, 1 if the file does not parse,
//! 2 if it cannot be read.

use aster_syntax::CodeMap;

pub fn run(file: &std::path::Path) -> u8 {
    let source = match aster_syntax::read_source(file) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{}: {e}", file.display());
            return 2;
        }
    };
    match aster_syntax::fmt::format_source(&source) {
        Ok(text) => {
            print!("{text}");
            0
        }
        Err(e) => {
            let map = CodeMap::new(file.display().to_string(), source);
            eprint!("{}", e.render(&map));
            1
        }
    }
}
