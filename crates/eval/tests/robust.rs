//! Hostile and careless programs: each used to crash, hang, exhaust memory
//! or print a wrong value. Now: Python's value, or a located error, fast.

use aster_eval::*;
use aster_syntax::CodeMap;
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

#[derive(Default)]
struct Printer {
    printed: Vec<String>,
}

impl CommandSink for Printer {
    fn execute(&mut self, _: &CommandCall) -> Result<CommandOutput, ExecError> {
        Ok(CommandOutput::Concept)
    }
    fn print(&mut self, line: &str) {
        self.printed.push(line.to_string());
    }
}

/// Runs `src` on a thread with a main thread's 8 MB stack; the printed
/// lines, or the rendered errors.
fn run(src: &str) -> Result<Vec<String>, String> {
    let src = src.to_string();
    std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let map = CodeMap::new("t.comm", src.as_str());
            let module = aster_syntax::parse_module(&src).map_err(|e| e.message)?;
            let mut p = Printer::default();
            let t = Clock::start();
            let r = run_program(&map, &module, &mut p, RunOptions::default());
            assert!(
                t.elapsed() < Duration::from_secs(3),
                "{src}: {:?}",
                t.elapsed()
            );
            r.map_err(|d| d.render(&map))?;
            Ok(p.printed)
        })
        .expect("thread")
        .join()
        .expect("no panic")
}

/// What `print(expr)` prints.
fn py(expr: &str) -> String {
    match run(&format!("print(({expr}))\n")) {
        Ok(lines) => lines.join("\n"),
        Err(e) => panic!("{expr}: {e}"),
    }
}

/// The error of `src`: it must be located (`t.comm:line:col`) and contain `what`.
fn refused(src: &str, what: &str, at: &str) {
    let e = run(src).expect_err(src);
    assert!(e.contains(what), "{src}\n{e}");
    assert!(e.contains(&format!("t.comm:{at}")), "{src}\n{e}");
}

#[test]
fn integers_are_exact_like_python() {
    assert_eq!(py("1 << 63"), "9223372036854775808");
    assert_eq!(py("1 << 64"), "18446744073709551616");
    assert_eq!(py("-(-2**63)"), "9223372036854775808");
    assert_eq!(py("abs(-2**63)"), "9223372036854775808");
    assert_eq!(py("123456789012345678 % 10"), "8");
    assert_eq!(py("(2**62 + 1) % 2"), "1");
    assert_eq!(py("-7 % 3, 7 % -3, -7 // 2, 7 // -2"), "(2, -2, -4, -4)");
    assert_eq!(
        py("int(1e300)"),
        "1000000000000000052504760255204420248704468581108159154915854115511802457988908195786371375080447864043704443832883878176942523235360430575644792184786706982848387200926575803737830233794788090059368953234970799945081119038967640880074652742780142494579258788820056842838115669472196386865459400540160"
    );
    assert_eq!(py("pow(3, 10**18, 7)"), "4");
    assert_eq!(py("pow(3, 10**18, -7)"), "-3");
    assert_eq!(
        py("(-9223372036854775807 - 1) // -1"),
        "9223372036854775808"
    );
    assert_eq!(py("(-9223372036854775807 - 1) % -1"), "0");
    assert_eq!(py("2**64 - 2**64 + 5"), "5");
    assert_eq!(py("type(2**64 - 2**64)"), "<built-in function int>");
    assert_eq!(py("2**100 // 3**20"), "363558641556578823726");
    assert_eq!(
        py("-(2**70) >> 3, ~(2**70)"),
        "(-147573952589676412928, -1180591620717411303425)"
    );
    assert_eq!(
        py("2**53 + 1 == 2.0**53, 2**53 + 1 > 2.0**53"),
        "(False, True)"
    );
    assert_eq!(py("10**20 / 10**10"), "10000000000.0");
    assert_eq!(
        py("round(12345, -2), round(12350, -2), round(-5, -1)"),
        "(12300, 12400, 0)"
    );
    assert_eq!(
        py("int('123456789012345678901234567890') + 1"),
        "123456789012345678901234567891"
    );
    assert_eq!(
        py("'%d' % 2**70, '{:d}'.format(-2**70)"),
        "('1180591620717411303424', '-1180591620717411303424')"
    );
    assert_eq!(py("[1, 2, 3][2**70:]"), "[]");
}

#[test]
fn integer_errors_are_located() {
    refused("x = 1\ny = 2**10**9\n", "integer result too large", "2:5");
    refused("x = 1 << -1\n", "negative shift count", "1:5");
    refused(
        "x = 10**400 * 1.0\n",
        "int too large to convert to float",
        "1:5",
    );
    refused("x = 1 // 0\n", "division or modulo by zero", "1:5");
    refused("x = [1, 2][2**64]\n", "out of range", "1:5");
}

#[test]
fn format_precision_beyond_rusts_limit_is_pythons_string() {
    let s = py("'%.70000f' % 1.0");
    assert_eq!(s.len(), 70_002);
    assert!(s.starts_with("1.000") && s.bytes().skip(2).all(|b| b == b'0'));
    assert_eq!(py("len('{:.70000f}'.format(1.0))"), "70002");
    assert_eq!(py("f'{1.0:.70000g}'"), "1");
    assert_eq!(py("len(f'{0.1:.70000e}')"), "70006");
    assert_eq!(
        py("'{:.30f}'.format(0.1)"),
        "0.100000000000000005551115123126"
    );
    assert_eq!(py("round(1.0, 70000), round(123.456, -400)"), "(1.0, 0.0)");
}

#[test]
fn self_referential_containers_print_and_compare_like_python() {
    let out = run("a = [1]\na.append(a)\nprint(a)\nprint(a == a)\nd = {}\nd['k'] = d\nprint(d)\n")
        .unwrap();
    assert_eq!(out, ["[1, [...]]", "True", "{'k': {...}}"]);
    refused(
        "a = [1]\na.append(a)\nb = [1]\nb.append(b)\nc = a == b\n",
        "maximum recursion depth",
        "5:5",
    );
}

#[test]
fn deep_recursion_is_an_error_not_a_crash() {
    refused(
        "def f(n):\n    return f(n + 1)\nf(0)\n",
        "maximum recursion depth",
        "2:12",
    );
    // A sum at the syntax limit, inside a recursion: one budget for both.
    let sum = vec!["n"; 900].join(" + ");
    refused(
        &format!("def f(n):\n    return f({sum})\nf(0)\n"),
        "maximum recursion depth",
        "2:",
    );
}

#[test]
fn unbounded_work_is_refused_quickly() {
    // `[] * 10**18` is empty at once (it used to loop 10^18 times).
    assert_eq!(py("[] * 10**18, () * 10**18, '' * 10**18"), "([], (), '')");
    refused("x = 'a' * 10**10\n", "result too large", "1:5");
    refused("x = [0] * 10**9\n", "result too large", "1:5");
    refused("x = [0] * 10**30\n", "result too large", "1:5");
    refused("x = 'a'.center(10**10)\n", "result too large", "1:5");
    refused(
        "x = '{:99999999999999999999}'.format(1)\n",
        "result too large",
        "1:5",
    );
    refused("x = '%099999999999d' % 1\n", "result too large", "1:5");
    refused(
        "n = 0\nfor i in range(100000):\n    for j in range(100000):\n        n += 1\n",
        "this `for` loop runs too long",
        "3:5",
    );
    refused(
        "while True:\n    pass\n",
        "this `while` loop runs too long",
        "1:1",
    );
    refused(
        "x = [i * j for i in range(10000) for j in range(10000)]\n",
        "this comprehension runs too long",
        "1:",
    );
    // Doubling a string: its copies spend the budget (blamed on the loop).
    refused(
        "s = 'ab'\nfor i in range(100):\n    s = s + s\n",
        "this `for` loop runs too long",
        "2:1",
    );
    refused(
        "s = 'ab' * (2 * 10**7)\nt = s + s\n",
        "result too large",
        "2:5",
    );
    refused("x = list(range(10**9))\n", "range() too long", "1:10");
}

#[test]
fn nested_values_are_bounded() {
    // A list nested 100,000 deep: printing it is Python's RecursionError,
    // dropping it is fine.
    refused(
        "a = []\nfor i in range(100000):\n    a = [a]\nprint(a)\n",
        "maximum recursion depth",
        "4:1",
    );
    run("a = []\nfor i in range(500000):\n    a = [a]\n").unwrap();
}

#[test]
fn non_finite_keyword_values_are_refused_at_the_keyword() {
    refused(
        "M = DEFI_MATERIAU(ELAS=_F(E=float('inf'), NU=0.3))\n",
        "is not a finite number",
        "1:",
    );
    refused(
        "F = DEFI_FONCTION(NOM_PARA='X', VALE=(0.0, 1.0, 1.0, float('nan')))\n",
        "`DEFI_FONCTION/VALE`: value nan is not a finite number",
        "1:",
    );
}
