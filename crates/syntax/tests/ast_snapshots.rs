//! AST snapshots (the `--json` form) of the project's own inputs, plus
//! targeted assertions on precedence, literals and Python 2 forms.

use aster_syntax::ast::*;
use aster_syntax::{decode, parse_module};
use std::path::Path;

fn input(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/inputs")
        .join(name);
    decode(&std::fs::read(&path).unwrap_or_default())
}

fn parse_ok(src: &str) -> Module {
    match parse_module(src) {
        Ok(m) => m,
        Err(e) => panic!("parse failed at {:?}: {}", e.span, e.message),
    }
}

fn json(name: &str) -> serde_json::Value {
    serde_json::to_value(parse_ok(&input(name))).unwrap_or_default()
}

#[test]
fn commands_ast() {
    insta::assert_json_snapshot!("commands", json("commands.comm"));
}

#[test]
fn python3_ast() {
    insta::assert_json_snapshot!("python3", json("python3.comm"));
}

#[test]
fn python2_ast() {
    insta::assert_json_snapshot!("python2", json("python2.comm"));
}

#[test]
fn crlf_and_tabs_ast() {
    insta::assert_json_snapshot!("crlf_tabs", json("crlf_tabs.comm"));
}

/// The single expression of a one-statement module.
fn expr(src: &str) -> Expr {
    let m = parse_ok(src);
    match m.body.into_iter().next().map(|s| s.into_kind()) {
        Some(StmtKind::Expr { value }) => value,
        Some(StmtKind::Assign { value, .. }) => value,
        other => panic!("not an expression statement: {other:?}"),
    }
}

/// A compact S-expression of an expression, to assert structure.
fn sexp(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Name { id } => id.to_string(),
        ExprKind::Int { value } => value.to_string(),
        ExprKind::Float { value } => format!("{value:?}"),
        ExprKind::BinOp { left, op, right } => format!("({op:?} {} {})", sexp(left), sexp(right)),
        ExprKind::UnaryOp { op, operand } => format!("({op:?} {})", sexp(operand)),
        ExprKind::BoolOp { op, values } => format!(
            "({op:?} {})",
            values.iter().map(sexp).collect::<Vec<_>>().join(" ")
        ),
        ExprKind::Compare { left, ops } => format!(
            "(Cmp {}{})",
            sexp(left),
            ops.iter()
                .map(|(o, e)| format!(" {o:?} {}", sexp(e)))
                .collect::<String>()
        ),
        ExprKind::IfExp { test, body, orelse } => {
            format!("(If {} {} {})", sexp(test), sexp(body), sexp(orelse))
        }
        other => format!("{other:?}"),
    }
}

#[test]
fn operator_precedence_follows_python() {
    let cases = [
        ("-2 ** -1", "(Neg (Pow 2 (Neg 1)))"),
        ("a + b * c - d", "(Sub (Add a (Mul b c)) d)"),
        ("a ** b ** c", "(Pow a (Pow b c))"),
        ("not a == b", "(Not (Cmp a Eq b))"),
        ("a < b <= c", "(Cmp a Lt b LtE c)"),
        ("(a < b) < c", "(Cmp (Cmp a Lt b) Lt c)"),
        ("a or b and c or d", "(Or a (And b c) d)"),
        ("(a or b) or c", "(Or (Or a b) c)"),
        (
            "a | b ^ c & d << 1",
            "(BitOr a (BitXor b (BitAnd c (LShift d 1))))",
        ),
        ("x if a else y if b else z", "(If a x (If b y z))"),
        ("a not in b is not c", "(Cmp a NotIn b IsNot c)"),
        ("a <> b", "(Cmp a NotEq b)"),
        ("-1.E-3", "(Neg 0.001)"),
    ];
    for (src, want) in cases {
        assert_eq!(sexp(&expr(src)), want, "{src}");
    }
}

#[test]
fn numbers_and_strings() {
    let cases: [(&str, ExprKind); 9] = [
        ("1.", ExprKind::Float { value: 1.0 }),
        (".5", ExprKind::Float { value: 0.5 }),
        ("1e+16", ExprKind::Float { value: 1e16 }),
        ("0777", ExprKind::Int { value: 511 }),
        ("10L", ExprKind::Int { value: 10 }),
        ("0x1f", ExprKind::Int { value: 31 }),
        (
            "'a' \"b\" '''c'''",
            ExprKind::Str {
                value: "abc".into(),
            },
        ),
        (
            "r'\\n' 'x\\n'",
            ExprKind::Str {
                value: "\\nx\n".into(),
            },
        ),
        (
            "(\n 'a'\n 'b'  # comment\n)",
            ExprKind::Str { value: "ab".into() },
        ),
    ];
    for (src, want) in cases {
        assert_eq!(expr(src).kind, want, "{src}");
    }
}

#[test]
fn fstring_fields_have_file_spans() {
    let src = "s = f'x={x + 1:>{w}} {y!r}'\n";
    let e = expr(src);
    let ExprKind::FString { parts } = &e.kind else {
        panic!("not an f-string: {e:?}")
    };
    assert_eq!(parts.len(), 4);
    let FStringPart::Field {
        value, format_spec, ..
    } = &parts[1]
    else {
        panic!("{parts:?}")
    };
    assert_eq!(
        &src[value.span.start as usize..value.span.end as usize],
        "x + 1"
    );
    assert_eq!(format_spec.len(), 2);
    let FStringPart::Field { conversion, .. } = &parts[3] else {
        panic!("{parts:?}")
    };
    assert_eq!(*conversion, Some('r'));
}

#[test]
fn spans_cover_their_source() {
    let src = "MA = LIRE_MAILLAGE(UNITE=20)\n";
    let m = parse_ok(src);
    let StmtKind::Assign { targets, value } = &m.body[0].kind else {
        panic!()
    };
    let text = |s: aster_syntax::Span| &src[s.start as usize..s.end as usize];
    assert_eq!(text(m.body[0].span), "MA = LIRE_MAILLAGE(UNITE=20)");
    assert_eq!(text(targets[0].span), "MA");
    assert_eq!(text(value.span), "LIRE_MAILLAGE(UNITE=20)");
    let ExprKind::Call { args, .. } = &value.kind else {
        panic!()
    };
    assert_eq!(text(args[0].span), "UNITE=20");
}

#[test]
fn python2_statements() {
    let m = parse_ok("print 'a', b,\nprint >>f, x\nexec code in g, l\n");
    match &m.body[0].kind {
        StmtKind::Print {
            dest: None,
            values,
            newline: false,
        } => assert_eq!(values.len(), 2),
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        &m.body[1].kind,
        StmtKind::Print { dest: Some(_), .. }
    ));
    match &m.body[2].kind {
        StmtKind::Exec {
            code,
            globals: Some(_),
            locals: Some(_),
        } => {
            assert!(matches!(code.kind, ExprKind::Name { .. }))
        }
        other => panic!("{other:?}"),
    }
    // `print(x)` stays a call (Python 3).
    assert!(matches!(expr("print(x)").kind, ExprKind::Call { .. }));
}

/// The lead's ZZZZ237 scenes (`comm/`), both modelisations.
fn scene(name: &str) -> serde_json::Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../comm")
        .join(name);
    let source = decode(&std::fs::read(&path).unwrap_or_default());
    serde_json::to_value(parse_ok(&source)).unwrap_or_default()
}

#[test]
fn zzzz237a_scene_ast() {
    insta::assert_json_snapshot!("zzzz237a", scene("zzzz237a.comm"));
}

#[test]
fn zzzz237b_scene_ast() {
    insta::assert_json_snapshot!("zzzz237b", scene("zzzz237b.comm"));
}
