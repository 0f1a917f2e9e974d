//! Golden files of syntax errors: every input in `tests/errors/` must fail,
//! and its rendered message (`file:line:col: message`, source line, caret)
//! is snapshotted. A new input without a snapshot fails until reviewed.

use aster_syntax::{parse_module, CodeMap};
use std::path::Path;

fn rendered(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/errors")
        .join(name);
    let source = match std::fs::read_to_string(&path) {
        Ok(s) => s,
        Err(e) => return format!("cannot read {}: {e}", path.display()),
    };
    let map = CodeMap::new(name, source);
    match parse_module(map.source()) {
        Ok(_) => format!("{name}: parsed without error, but an error was expected"),
        Err(e) => e.render(&map),
    }
}

macro_rules! error_case {
    ($($test:ident),* $(,)?) => {
        $(
            #[test]
            fn $test() {
                let name = concat!(stringify!($test), ".comm");
                insta::assert_snapshot!(stringify!($test), rendered(name));
            }
        )*
        /// Every file in tests/errors has a test above.
        #[test]
        fn every_error_input_is_tested() {
            let known = [$(concat!(stringify!($test), ".comm")),*];
            let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/errors");
            let mut missing = Vec::new();
            if let Ok(entries) = std::fs::read_dir(&dir) {
                for e in entries.flatten() {
                    let n = e.file_name().to_string_lossy().to_string();
                    if n.ends_with(".comm") && !known.contains(&n.as_str()) {
                        missing.push(n);
                    }
                }
            }
            assert!(missing.is_empty(), "untested error inputs: {missing:?}");
        }
    };
}

error_case!(
    error_assign_to_call,
    error_bad_dedent,
    error_bad_indent,
    error_bad_number,
    error_break_outside_loop,
    error_expected_indent,
    error_incomplete_expression,
    error_keyword_repeated,
    error_lone_cr,
    error_mismatched_bracket,
    error_missing_colon,
    error_missing_comma,
    error_missing_paren,
    error_positional_after_keyword,
    error_return_outside_function,
    error_stray_char,
    error_tab_error,
    error_unclosed_bracket,
    error_unexpected_indent,
    error_unmatched_paren,
    error_unterminated_string,
    error_unterminated_triple_string,
);

/// Positions are exact: line and column of the offending character.
#[test]
fn error_positions_are_exact() {
    let cases: [(&str, usize, usize); 6] = [
        ("a = (1,\n", 1, 5),
        ("x = 1\n  y = 2\n", 2, 3),
        ("f(a=1, a=2)\n", 1, 8),
        ("s = 'abc\n", 1, 5),
        ("x = 1 ? 2\n", 1, 7),
        ("while x\n    pass\n", 1, 8),
    ];
    for (src, line, col) in cases {
        let map = CodeMap::new("t.comm", src);
        let e = match parse_module(src) {
            Ok(_) => panic!("{src:?} should not parse"),
            Err(e) => e,
        };
        let lc = map.line_col(e.span.start as usize);
        assert_eq!((lc.line, lc.column), (line, col), "{src:?}: {}", e.message);
    }
}
