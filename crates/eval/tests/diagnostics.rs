//! One erroneous file per kind of diagnostic (tests/errors/*.comm): the
//! rendered diagnostics are snapshotted, and each file must produce the
//! kind of error it is named after.

use aster_eval::{check_source, DiagKind};
use aster_syntax::CodeMap;
use std::path::Path;

fn check(name: &str) -> (String, Vec<DiagKind>, bool) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/errors")
        .join(name);
    let source =
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let map = CodeMap::new(format!("tests/errors/{name}"), source);
    let report = check_source(&map, false);
    let kinds = report.diagnostics.0.iter().map(|d| d.kind).collect();
    (report.diagnostics.render(&map), kinds, report.ok())
}

macro_rules! case {
    ($test:ident, $file:literal, $kind:expr) => {
        #[test]
        fn $test() {
            let (text, kinds, ok) = check($file);
            assert!(!ok, "{} should not check clean:\n{text}", $file);
            assert!(
                kinds.contains(&$kind),
                "{}: expected {:?}, got {kinds:?}\n{text}",
                $file,
                $kind
            );
            insta::assert_snapshot!(stringify!($test), text);
        }
    };
}

case!(
    unknown_keyword,
    "unknown_keyword.comm",
    DiagKind::UnknownKeyword
);
case!(
    missing_keyword,
    "missing_keyword.comm",
    DiagKind::MissingKeyword
);
case!(
    wrong_concept_type,
    "wrong_concept_type.comm",
    DiagKind::WrongType
);
case!(wrong_type, "wrong_type.comm", DiagKind::WrongType);
case!(not_into, "not_into.comm", DiagKind::NotInto);
case!(too_many_values, "too_many_values.comm", DiagKind::Count);
case!(out_of_range, "out_of_range.comm", DiagKind::OutOfRange);
case!(rule_violated, "rule_violated.comm", DiagKind::Rule);
case!(
    not_applicable,
    "not_applicable.comm",
    DiagKind::KeywordNotApplicable
);
case!(
    unknown_command,
    "unknown_command.comm",
    DiagKind::UnknownCommand
);
case!(not_supported, "not_supported.comm", DiagKind::NotSupported);
case!(undefined_name, "undefined_name.comm", DiagKind::Python);
case!(bad_reuse, "bad_reuse.comm", DiagKind::Reuse);
case!(syntax_error, "syntax_error.comm", DiagKind::Syntax);

#[test]
fn legacy_file_checks_with_warnings() {
    let (text, kinds, ok) = check("legacy_v11.comm");
    assert!(ok, "legacy file must check clean:\n{text}");
    assert!(
        kinds.iter().all(|k| *k == DiagKind::Legacy),
        "{kinds:?}\n{text}"
    );
    assert!(kinds.len() >= 6, "{text}");
    insta::assert_snapshot!("legacy_v11", text);
}

/// `aster check` reports every independent error of a file, and no
/// consequence of one (`recover`).
#[test]
fn checking_goes_on_after_an_error_without_consequences() {
    let (text, kinds, ok) = check("keep_going.comm");
    assert!(!ok);
    let lines: Vec<u32> = text
        .lines()
        .filter(|l| l.starts_with("tests/errors/keep_going.comm:") && l.contains("error"))
        .filter_map(|l| l.split(':').nth(1)?.parse().ok())
        .collect();
    // The import (4), the undefined name (8), FOO_BAR (12), BAD (14), the
    // loop (18), the undefined macro (25) and the second typo (28).
    assert_eq!(lines, [4, 8, 12, 14, 18, 25, 28], "{text}");
    assert!(kinds.contains(&DiagKind::UnknownCommand), "{kinds:?}");
    assert!(kinds.contains(&DiagKind::UnknownKeyword), "{kinds:?}");
    insta::assert_snapshot!("keep_going", text);
}

/// A did-you-mean never proposes a keyword already written in the same
/// `_F`: with GROUP_MA_ESCL and GROUP_MA_MAIT both given, GROUP_MA_ESC gets
/// the list of accepted keywords rather than a misleading suggestion.
#[test]
fn did_you_mean_skips_keywords_written_beside() {
    let source = "MO = AFFE_MODELE(MAILLAGE=LIRE_MAILLAGE(), AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
C = DEFI_CONTACT(MODELE=MO, ZONE=_F(GROUP_MA_MAIT='HE', GROUP_MA_ESCL='AB', GROUP_MA_ESC='X'))\n";
    let map = CodeMap::new("t.comm", source);
    let report = check_source(&map, false);
    let d = report
        .diagnostics
        .0
        .iter()
        .find(|d| d.kind == DiagKind::UnknownKeyword)
        .expect("GROUP_MA_ESC is unknown");
    assert!(
        d.notes.iter().all(|n| !n.starts_with("help: did you mean")),
        "{:?}",
        d.notes
    );
    assert!(
        d.notes
            .iter()
            .any(|n| n.starts_with("note: keywords accepted here")),
        "{:?}",
        d.notes
    );
    // Alone, the same typo gets its suggestion.
    let source = source.replace("GROUP_MA_ESCL='AB', ", "");
    let map = CodeMap::new("t.comm", source);
    let report = check_source(&map, false);
    let d = report
        .diagnostics
        .0
        .iter()
        .find(|d| d.kind == DiagKind::UnknownKeyword)
        .expect("GROUP_MA_ESC is unknown");
    assert!(
        d.notes.iter().any(|n| n.contains("`GROUP_MA_ESCL`")),
        "{:?}",
        d.notes
    );
    assert!(
        d.notes.iter().all(|n| !n.contains("`GROUP_MA_MAIT`")),
        "{:?}",
        d.notes
    );
}
