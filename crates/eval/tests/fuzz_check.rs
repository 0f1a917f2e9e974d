//! Fuzzing `aster check` (parse, evaluate, validate against the catalog):
//! generated programs — deep and wide expressions, huge repetitions,
//! integers at and beyond 64 bits, format specs, loops, recursion,
//! self-referential containers, command calls with hostile values — must
//! end in well under the time budget with a result or located errors,
//! never a panic, a stack overflow or a hang.
//!
//! proptest rather than `cargo fuzz`: libFuzzer needs a nightly compiler
//! and a sanitizer runtime, CI builds on stable; these generators run in
//! `cargo test` with a fixed number of cases (a fixed time budget), shrink
//! what they find, and every input they ever found to crash is kept in
//! `tests/crashes/` and replayed by [`crash_corpus_is_handled`].

use aster_eval::check_source;
use aster_syntax::CodeMap;
use proptest::prelude::*;
use std::time::{Duration, Instant};

/// This thread's CPU time since `start` (Linux `/proc/thread-self/schedstat`),
/// else wall time: time bounds that hold on a loaded machine.
struct Clock {
    wall: Instant,
    cpu: Option<Duration>,
}

fn thread_cpu() -> Option<Duration> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = s.split_whitespace().next()?.parse().ok()?;
    Some(Duration::from_nanos(ns))
}

impl Clock {
    fn start() -> Clock {
        Clock {
            wall: Instant::now(),
            cpu: thread_cpu(),
        }
    }
    fn elapsed(&self) -> Duration {
        match (self.cpu, thread_cpu()) {
            (Some(a), Some(b)) => b.saturating_sub(a),
            _ => self.wall.elapsed(),
        }
    }
}

/// Checks `src` on a thread with a main thread's 8 MB stack: no panic, no
/// overflow, under `budget`; every error located in the file.
///
/// A loop that uses up the whole step budget costs 1 to 3.5 s of CPU on a
/// 2-core machine (3.4 s measured under load for `while 'x': n = n + 1`),
/// and a generated program may hold several such loops: the budgets are
/// about "no hang", not speed (speed lives in the benchmarks).
fn exercise(src: String, budget: Duration) {
    let shown = src.chars().take(400).collect::<String>();
    let handle = std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let t = Clock::start();
            let map = CodeMap::new("f.comm", src.as_str());
            let report = check_source(&map, false);
            let took = t.elapsed();
            for d in report.diagnostics.errors() {
                assert!(
                    d.span.end as usize <= src.len(),
                    "span outside the file: {}",
                    d.render(&map)
                );
                assert!(d.render(&map).starts_with("f.comm:"), "{}", d.render(&map));
            }
            took
        })
        .expect("thread");
    match handle.join() {
        Ok(took) => assert!(took < budget, "{took:?} for:\n{shown}"),
        Err(_) => panic!("panicked on:\n{shown}"),
    }
}

fn atom() -> impl Strategy<Value = String> {
    prop_oneof![
        "-?[0-9]{1,22}",
        "[0-9]{1,3}\\.[0-9]{0,3}(e[+-]?[0-9]{1,3})?",
        Just("2**63".to_string()),
        Just("(-2**63)".to_string()),
        Just("10**18".to_string()),
        Just("10**9".to_string()),
        Just("1e308".to_string()),
        Just("1e-310".to_string()),
        Just("float('inf')".to_string()),
        Just("float('nan')".to_string()),
        Just("'ab'".to_string()),
        Just("'%s'".to_string()),
        Just("[1, 2]".to_string()),
        Just("[]".to_string()),
        Just("()".to_string()),
        Just("{}".to_string()),
        Just("{'k': 1}".to_string()),
        Just("None".to_string()),
        Just("True".to_string()),
        Just("a".to_string()),
        Just("x".to_string()),
        Just("n".to_string()),
    ]
}

fn binop() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "+", "-", "*", "/", "//", "%", "**", "<<", ">>", "&", "|", "^", "==", "<", "!=", "and",
        "or", "in", "is",
    ])
}

fn call() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "int", "float", "str", "repr", "abs", "round", "len", "list", "tuple", "range", "sorted",
        "sum", "min", "max", "bool", "hex", "chr", "ord", "divmod", "print",
    ])
}

fn spec() -> impl Strategy<Value = String> {
    prop_oneof![
        "[<>^=]?[+ -]?0?[0-9]{0,6}(\\.[0-9]{1,6})?[dfegsxr%]?",
        Just("99999999999999999999".to_string()),
        Just(".70000f".to_string()),
    ]
}

fn expr() -> impl Strategy<Value = String> {
    atom().prop_recursive(6, 48, 3, |e| {
        prop_oneof![
            (e.clone(), binop(), e.clone()).prop_map(|(a, o, b)| format!("({a} {o} {b})")),
            (prop::sample::select(vec!["-", "~", "not "]), e.clone())
                .prop_map(|(o, a)| format!("({o}{a})")),
            (call(), e.clone()).prop_map(|(f, a)| format!("{f}({a})")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("pow({a}, {b}, 7)")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("{a}[{b}]")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("{a}[{b}:]")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("[{a}, {b}]")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("{{{a}: {b}}}")),
            (spec(), e.clone()).prop_map(|(s, a)| format!("('%{s}' % ({a},))")),
            (spec(), e.clone()).prop_map(|(s, a)| format!("'{{:{s}}}'.format({a})")),
            (spec(), e.clone()).prop_map(|(s, a)| format!("f'{{{a}:{s}}}'")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("str({a}).center({b})")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("str({a}).join({b})")),
            (e.clone(), e.clone(), e.clone())
                .prop_map(|(a, b, c)| format!("({a} if {b} else {c})")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("(lambda y: {a})({b})")),
            (e.clone(), e.clone()).prop_map(|(a, b)| format!("[{a} for y in range({b})]")),
            e.clone().prop_map(|a| format!("round(1.0, {a})")),
        ]
    })
}

/// A statement using generated expressions.
fn stmt() -> impl Strategy<Value = String> {
    prop_oneof![
        expr().prop_map(|e| format!("x = {e}\n")),
        expr().prop_map(|e| format!("a = {e}\n")),
        expr().prop_map(|e| format!("print({e})\n")),
        expr().prop_map(|e| format!("for i in range({e}):\n    n = n + i\n")),
        expr().prop_map(|e| format!("while {e}:\n    n = n + 1\n")),
        expr().prop_map(|e| format!("def f(k):\n    return f(k) if {e} else k\nx = f(1)\n")),
        Just("a = [1]\na.append(a)\nprint(a, a == a)\n".to_string()),
        expr().prop_map(|e| format!("x = {e}\nx = x * x\n")),
        expr().prop_map(|e| format!(
            "L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A={e}, NOMBRE={e}))\n"
        )),
        expr()
            .prop_map(|e| format!("F = DEFI_FONCTION(NOM_PARA='X', VALE=(0.0, {e}, 1.0, {e}))\n")),
        expr().prop_map(|e| format!("FO = FORMULE(VALE='X * {e}', NOM_PARA='X')\nv = FO({e})\n")),
        expr().prop_map(|e| format!("M = DEFI_MATERIAU(ELAS=_F(E={e}, NU=0.3))\n")),
    ]
}

/// Hostile shapes far beyond the limits: deep nesting and long chains.
fn deep() -> impl Strategy<Value = String> {
    let shapes = prop::sample::select(vec![
        ("x = ", "1 + ", "1"),
        ("x = ", "not ", "1"),
        ("x = ", "lambda: ", "1"),
        ("x = ", "1 if 1 else ", "1"),
        ("x = ", "(", "1"),
        ("x = ", "[", "1"),
        ("x = ", "-", "1"),
        ("x = a", ".b", ""),
        ("x = f", "()", ""),
        ("x = a", "[0]", ""),
        ("x = ", "2 ** ", "2"),
        ("x = ", "[y for y in ", "[1]"),
        ("x = ", "f(", "1"),
        ("x = ", "{1: ", "1"),
        ("if 1:\n    pass\n", "elif 1:\n    pass\n", ""),
    ]);
    (shapes, 0usize..30_000)
        .prop_map(|((head, rep, tail), n)| format!("n = 0\na = 1\n{head}{}{tail}\n", rep.repeat(n)))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn generated_programs_end_in_a_result_or_located_errors(
        stmts in prop::collection::vec(stmt(), 1..6)
    ) {
        exercise(format!("n = 0\na = 1\nx = 2\n{}", stmts.concat()), Duration::from_secs(20));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(60))]

    #[test]
    fn deep_and_long_input_is_refused_or_checked_quickly(src in deep()) {
        exercise(src, Duration::from_secs(20));
    }
}

/// Inputs the fuzzers (and the reproducers) found to crash, hang
/// or blow up memory: each must now be handled quickly.
#[test]
fn crash_corpus_is_handled() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/crashes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("tests/crashes")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "comm"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for path in files {
        let src = std::fs::read_to_string(&path).expect("read");
        exercise(src, Duration::from_secs(20));
    }
}
