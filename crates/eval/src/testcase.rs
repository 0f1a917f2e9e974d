//! `CA.TestCase()`: code_aster's unittest-style checker, used by command
//! files to assert on values (`test.assertEqual(n, 3)`,
//! `test.assertAlmostEqual(x, 1.0, delta=1e-6)`). An assertion on values
//! the checker knows is evaluated, and a failing one is reported, as it
//! would fail when the file runs; one on a value known only when the
//! commands run is left to the run. Failures do not stop the program:
//! code_aster records them and goes on.

use crate::builtins::order;
use crate::diag::{DiagKind, Diagnostic};
use crate::interp::{py_err, unsupported, CallArg, Interp, R};
use crate::value::Value;
use aster_syntax::Span;
use std::cmp::Ordering;

/// Whether a value (or anything inside it) is only known at run time.
fn unknown(v: &Value) -> bool {
    match v {
        Value::Unknown => true,
        Value::List(l) => l.borrow().iter().any(unknown),
        Value::Tuple(t) => t.iter().any(unknown),
        Value::Dict(d) => d.borrow().entries.iter().any(|e| unknown(&e.value)),
        _ => false,
    }
}

/// Calls `test.<method>(args)` on a TestCase object.
pub(crate) fn call(me: &mut Interp, method: &str, args: Vec<CallArg>, span: Span) -> R<Value> {
    let pos: Vec<&Value> = args
        .iter()
        .filter(|a| a.name.is_none())
        .map(|a| &a.value)
        .collect();
    let kw = |k: &str| {
        args.iter()
            .find(|a| a.name.as_ref().is_some_and(|(n, _)| n == k))
            .map(|a| &a.value)
    };
    let n_args = |n: usize| -> R<()> {
        if pos.len() < n {
            return py_err(span, format!("TestCase.{method}() takes {n} argument(s)"));
        }
        Ok(())
    };
    if method == "printSummary" {
        return Ok(Value::None);
    }
    let holds: Option<bool> = match method {
        "assertTrue" | "assertFalse" => {
            n_args(1)?;
            pos[0]
                .truthy()
                .map(|t| t == (method == "assertTrue"))
                .filter(|_| !unknown(pos[0]))
        }
        "assertIsNone" | "assertIsNotNone" => {
            n_args(1)?;
            let none = matches!(pos[0], Value::None);
            (!unknown(pos[0])).then_some(none == (method == "assertIsNone"))
        }
        "assertEqual"
        | "assertNotEqual"
        | "assertSequenceEqual"
        | "assertListEqual"
        | "assertTupleEqual" => {
            n_args(2)?;
            let eq = if method == "assertEqual" || method == "assertNotEqual" {
                pos[0].py_eq(pos[1])
            } else {
                let a = me.iterate(pos[0], span)?;
                let b = me.iterate(pos[1], span)?;
                a.len() == b.len() && a.iter().zip(&b).all(|(x, y)| x.py_eq(y))
            };
            Some(eq == (method != "assertNotEqual"))
        }
        "assertAlmostEqual" | "assertNotAlmostEqual" => {
            n_args(2)?;
            match (pos[0].as_f64(), pos[1].as_f64()) {
                (Some(a), Some(b)) => {
                    let close = match kw("delta").and_then(Value::as_f64) {
                        Some(delta) => (a - b).abs() <= delta,
                        None => {
                            let places = kw("places")
                                .or(pos.get(2).copied())
                                .and_then(Value::as_f64)
                                .unwrap_or(7.0);
                            a == b || ((a - b) * 10f64.powf(places)).round() == 0.0
                        }
                    };
                    Some(close == (method == "assertAlmostEqual"))
                }
                _ => None,
            }
        }
        "assertLess" | "assertLessEqual" | "assertGreater" | "assertGreaterEqual" => {
            n_args(2)?;
            match order(pos[0], pos[1]) {
                Ok(o) => Some(match method {
                    "assertLess" => o == Ordering::Less,
                    "assertLessEqual" => o != Ordering::Greater,
                    "assertGreater" => o == Ordering::Greater,
                    _ => o != Ordering::Less,
                }),
                Err(_) => None,
            }
        }
        "assertIn" | "assertNotIn" => {
            n_args(2)?;
            if unknown(pos[1]) {
                None
            } else {
                let items = me.iterate(pos[1], span)?;
                let found = items.iter().any(|x| x.py_eq(pos[0]));
                Some(found == (method == "assertIn"))
            }
        }
        other => return unsupported(span, format!("`TestCase.{other}`")),
    };
    // A value known only at run time: the run will tell.
    if pos.iter().any(|v| unknown(v)) {
        return Ok(Value::None);
    }
    if holds == Some(false) {
        let shown: Vec<String> = pos.iter().map(|v| v.repr()).collect();
        me.diags.push(Diagnostic::error(
            DiagKind::Python,
            span,
            format!(
                "TestCase assertion fails: {method}({}) is false",
                shown.join(", ")
            ),
        ));
    }
    Ok(Value::None)
}
