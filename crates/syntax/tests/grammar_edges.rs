//! Edge cases of the tuned grammar: the keyword trie, names tried before
//! string prefixes, comments as whitespace, and the operator fold.

use aster_syntax::ast::{BinOp, Expr, ExprKind, StmtKind, UnaryOp};
use aster_syntax::parse_module;

/// The value of the single statement `x = <expr>` (or of an expression statement).
fn value(src: &str) -> Expr {
    let module = match parse_module(src) {
        Ok(m) => m,
        Err(e) => panic!("{src:?} should parse: {}", e.message),
    };
    match module.body.into_iter().next().map(|s| s.into_kind()) {
        Some(StmtKind::Assign { value, .. }) | Some(StmtKind::Expr { value }) => value,
        other => panic!("{src:?}: unexpected statement {other:?}"),
    }
}

/// A compact prefix form of an expression, to compare trees by eye.
fn sexpr(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Name { id } => id.to_string(),
        ExprKind::Int { value } => value.to_string(),
        ExprKind::Str { value } => format!("{value:?}"),
        ExprKind::Bool { value } => value.to_string(),
        ExprKind::None => "None".into(),
        ExprKind::BinOp { left, op, right } => {
            format!("({op:?} {} {})", sexpr(left), sexpr(right))
        }
        ExprKind::UnaryOp { op, operand } => format!("({op:?} {})", sexpr(operand)),
        ExprKind::BoolOp { op, values } => {
            let v: Vec<String> = values.iter().map(sexpr).collect();
            format!("({op:?} {})", v.join(" "))
        }
        ExprKind::Compare { left, ops } => {
            let v: Vec<String> = ops
                .iter()
                .map(|(op, e)| format!("{op:?} {}", sexpr(e)))
                .collect();
            format!("(Compare {} {})", sexpr(left), v.join(" "))
        }
        ExprKind::Call { func, args } => format!("(call {} {})", sexpr(func), args.len()),
        ExprKind::Attribute { value, attr } => format!("{}.{}", sexpr(value), attr.name),
        ExprKind::IfExp { test, body, orelse } => {
            format!("(if {} {} {})", sexpr(test), sexpr(body), sexpr(orelse))
        }
        other => format!("{other:?}"),
    }
}

#[test]
fn keywords_are_not_names() {
    for src in [
        "if = 3\n",
        "x = lambda\n",
        "None = 1\n",
        "f(True=1)\n",
        "x = a.class\n",
        "def for(): pass\n",
        "x = yield.y\n",
    ] {
        assert!(parse_module(src).is_err(), "{src:?} should not parse");
    }
}

#[test]
fn names_that_start_like_keywords_are_names() {
    for name in [
        "iff", "in_", "is2", "andy", "notre", "orx", "Nonez", "Truex", "False_", "ifs", "elifant",
        "asserts", "y", "r", "b", "f", "u", "rb", "br", "ur", "fr", "Rb",
    ] {
        let e = value(&format!("x = {name}\n"));
        assert_eq!(sexpr(&e), name, "{name}");
    }
}

#[test]
fn string_prefixes_are_strings_not_names() {
    let cases = [
        ("r'a\\n'", "\"a\\\\n\""),
        ("u\"x\"", "\"x\""),
        ("R'''y'''", "\"y\""),
        ("'a' \"b\"", "\"ab\""),
    ];
    for (src, expected) in cases {
        assert_eq!(sexpr(&value(&format!("x = {src}\n"))), expected, "{src}");
    }
    assert!(matches!(value("x = b'x'\n").kind, ExprKind::Bytes { .. }));
    assert!(matches!(value("x = rb'x'\n").kind, ExprKind::Bytes { .. }));
    assert!(matches!(
        value("x = f'{a}'\n").kind,
        ExprKind::FString { .. }
    ));
}

#[test]
fn literals_true_false_none() {
    assert_eq!(sexpr(&value("x = True\n")), "true");
    assert_eq!(sexpr(&value("x = False\n")), "false");
    assert_eq!(sexpr(&value("x = None\n")), "None");
}

#[test]
fn comments_are_whitespace_everywhere() {
    let src = "# head\nx = f(  # after paren\n    a=1,  # after comma\n    # own line\n    b=2,\n)  # end\n# tail";
    let e = value(src);
    assert_eq!(sexpr(&e), "(call f 2)");
}

#[test]
fn operator_precedence_follows_python() {
    let cases = [
        ("-2 ** -1", "(Neg (Pow 2 (Neg 1)))"),
        ("a + b * c", "(Add a (Mul b c))"),
        ("a * b + c", "(Add (Mul a b) c)"),
        ("a - b - c", "(Sub (Sub a b) c)"),
        ("a ** b ** c", "(Pow a (Pow b c))"),
        ("not a == b", "(Not (Compare a Eq b))"),
        ("a and not b or c", "(Or (And a (Not b)) c)"),
        ("a or b or c", "(Or a b c)"),
        ("a < b <= c", "(Compare a Lt b LtE c)"),
        (
            "a | b ^ c & d << 1",
            "(BitOr a (BitXor b (BitAnd c (LShift d 1))))",
        ),
        ("-a * b", "(Mul (Neg a) b)"),
        ("~a.b(1)", "(Invert (call a.b 1))"),
        ("a if b else c", "(if b a c)"),
        ("a not in b", "(Compare a NotIn b)"),
        ("a is not b", "(Compare a IsNot b)"),
    ];
    for (src, expected) in cases {
        assert_eq!(sexpr(&value(&format!("x = {src}\n"))), expected, "{src}");
    }
    // Spans of folded operations cover their operands.
    let e = value("x = 1 + 2 * 3\n");
    assert_eq!((e.span.start, e.span.end), (4, 13));
    assert!(matches!(e.kind, ExprKind::BinOp { op: BinOp::Add, .. }));
    let e = value("x = -y\n");
    assert!(matches!(
        e.kind,
        ExprKind::UnaryOp {
            op: UnaryOp::Neg,
            ..
        }
    ));
    assert_eq!((e.span.start, e.span.end), (4, 6));
}

/// An expression consumes the whitespace and comments after it (so that the
/// rule that follows need not skip them again); no span includes them.
#[test]
fn spans_stop_before_trailing_comments() {
    let src = "F(A=(1, 2)  # one\n  , B=g(x) # two\n  , C=[3] \\\n)\nX = 1.5  # three\n";
    let module = match parse_module(src) {
        Ok(m) => m,
        Err(e) => panic!("should parse: {}", e.message),
    };
    let text = |span: aster_syntax::Span| &src[span.start as usize..span.end as usize];
    let Some(StmtKind::Expr { value }) = module.body.first().map(|s| &s.kind) else {
        panic!("expected a call statement");
    };
    let ExprKind::Call { args, .. } = &value.kind else {
        panic!("expected a call");
    };
    let args: Vec<&str> = args.iter().map(|a| text(a.span)).collect();
    assert_eq!(args, ["A=(1, 2)", "B=g(x)", "C=[3]"]);
    let spans: Vec<&str> = module.body.iter().map(|s| text(s.span)).collect();
    assert_eq!(spans[1], "X = 1.5");
}

/// Python's tokenizer reads `1if x else 2` as `1 if x else 2`; so do we.
#[test]
fn numbers_end_before_keywords() {
    assert_eq!(sexpr(&value("x = 1if y else 2\n")), "(if y 1 2)");
}

/// Adjacent literals are one string, across lines inside brackets; a literal
/// after anything but a literal is an error at that literal.
#[test]
fn adjacent_strings_concatenate_only_with_each_other() {
    assert_eq!(sexpr(&value("x = 'a' \"b\" r'\\c'\n")), "\"ab\\\\c\"");
    assert_eq!(sexpr(&value("f(K='a'\n  'b', L=1)\n")), "(call f 2)");
    for (src, col) in [("x = a 'b'\n", 7), ("x = 'a'.upper() 'b'\n", 17)] {
        match parse_module(src) {
            Ok(_) => panic!("{src:?} should not parse"),
            Err(e) => {
                assert_eq!(e.span.start as usize + 1, col, "{src:?}: {}", e.message);
                assert!(e.message.contains("before this string"), "{}", e.message);
            }
        }
    }
}

/// Upper-case two-letter prefixes are read as a name by the grammar (see
/// `upper_second`) and joined with their literal by the builder; a real name
/// before a literal stays an error.
#[test]
fn upper_case_two_letter_prefixes_are_strings() {
    assert_eq!(
        sexpr(&value("x = RB'a\\\\b'\n")),
        "Bytes { value: [97, 92, 92, 98] }"
    );
    assert_eq!(
        sexpr(&value("x = FR'{y}' 'z'\n")),
        sexpr(&value("x = fr'{y}' 'z'\n"))
    );
    assert_eq!(
        sexpr(&value("x = BR'a' + RB\n")),
        sexpr(&value("x = b'a' + RB\n"))
    );
    assert!(parse_module("x = RX'a'\n").is_err());
    assert!(parse_module("x = RB 'a'\n").is_err());
}
