//! Built-in functions, the `math` module, methods of str/list/dict, and the
//! arithmetic of the subset.

use crate::diag::DiagKind;
use crate::format;
use crate::int;
use crate::interp::{from_host, py_err, to_host, unsupported, CallArg, Halt, Interp, R};
use crate::limits::{too_large, MAX_ITEMS, MAX_STR_BYTES};
use crate::value::*;
use aster_syntax::ast::BinOp;
use aster_syntax::Span;
use std::cmp::Ordering;
use std::rc::Rc;

const BUILTINS: &[&str] = &[
    "range",
    "len",
    "abs",
    "min",
    "max",
    "sum",
    "float",
    "int",
    "str",
    "round",
    "list",
    "tuple",
    "dict",
    "zip",
    "enumerate",
    "sorted",
    "print",
    "bool",
    "pow",
    "repr",
    "reversed",
    "any",
    "all",
    "isinstance",
    "map",
    "filter",
    "divmod",
    "complex",
    "set",
    "type",
    "hasattr",
    "getattr",
    "open",
    "input",
    "eval",
    "exec",
    "globals",
    "locals",
    "__import__",
    "iter",
    "next",
    "ord",
    "chr",
    "format",
];

pub fn builtin(name: &str) -> Option<Value> {
    BUILTINS
        .iter()
        .find(|b| **b == name)
        .map(|b| Value::Builtin(Builtin::Fn(b)))
        .or(match name {
            "True" => Some(Value::Bool(true)),
            "False" => Some(Value::Bool(false)),
            "None" => Some(Value::None),
            _ => None,
        })
}

pub const MATH_NAMES: &[&str] = &[
    "pi",
    "e",
    "inf",
    "nan",
    "tau",
    "sqrt",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "sinh",
    "cosh",
    "tanh",
    "exp",
    "log",
    "log10",
    "log2",
    "pow",
    "fabs",
    "floor",
    "ceil",
    "degrees",
    "radians",
    "hypot",
    "fmod",
    "trunc",
    "isnan",
    "isinf",
    "copysign",
    "asinh",
    "acosh",
    "atanh",
    "factorial",
    "expm1",
    "log1p",
];

pub fn math_attr(name: &str) -> Option<Value> {
    Some(match name {
        "pi" => Value::Float(std::f64::consts::PI),
        "e" => Value::Float(std::f64::consts::E),
        "tau" => Value::Float(std::f64::consts::TAU),
        "inf" => Value::Float(f64::INFINITY),
        "nan" => Value::Float(f64::NAN),
        n => {
            let found = MATH_NAMES.iter().find(|m| **m == n)?;
            Value::Builtin(Builtin::Fn(math_fn_name(found)))
        }
    })
}

/// Math functions are dispatched as `math.NAME` builtins.
fn math_fn_name(n: &'static str) -> &'static str {
    const PREFIXED: &[&str] = &[
        "math.sqrt",
        "math.sin",
        "math.cos",
        "math.tan",
        "math.asin",
        "math.acos",
        "math.atan",
        "math.atan2",
        "math.sinh",
        "math.cosh",
        "math.tanh",
        "math.exp",
        "math.log",
        "math.log10",
        "math.log2",
        "math.pow",
        "math.fabs",
        "math.floor",
        "math.ceil",
        "math.degrees",
        "math.radians",
        "math.hypot",
        "math.fmod",
        "math.trunc",
        "math.isnan",
        "math.isinf",
        "math.copysign",
        "math.asinh",
        "math.acosh",
        "math.atanh",
        "math.factorial",
        "math.expm1",
        "math.log1p",
    ];
    PREFIXED
        .iter()
        .find(|p| &p[5..] == n)
        .copied()
        .unwrap_or("math.?")
}

fn num(v: &Value, span: Span) -> R<f64> {
    match v.as_f64() {
        Some(f) if f.is_infinite() && matches!(v, Value::Big(_)) => {
            py_err(span, "int too large to convert to float")
        }
        Some(f) => Ok(f),
        None => py_err(span, format!("a number is required, not {}", v.type_name())),
    }
}

fn positional(args: &[CallArg], name: &str, span: Span) -> R<Vec<Value>> {
    if let Some(a) = args.iter().find(|a| a.name.is_some()) {
        let k = a.name.as_ref().map(|n| n.0.as_str()).unwrap_or("");
        if !matches!(
            (name, k),
            ("sorted", "key" | "reverse")
                | ("print", _)
                | ("max" | "min", "key")
                | ("round", "ndigits")
                | ("dict", _)
        ) {
            return py_err(
                span,
                format!("{name}() got an unexpected keyword argument '{k}'"),
            );
        }
    }
    Ok(args
        .iter()
        .filter(|a| a.name.is_none())
        .map(|a| a.value.clone())
        .collect())
}

fn kwarg<'v>(args: &'v [CallArg], k: &str) -> Option<&'v Value> {
    args.iter()
        .find(|a| a.name.as_ref().is_some_and(|n| n.0 == k))
        .map(|a| &a.value)
}

fn arity(v: &[Value], n: usize, name: &str, span: Span) -> R<()> {
    if v.len() != n {
        return py_err(
            span,
            format!("{name}() takes {n} argument(s) ({} given)", v.len()),
        );
    }
    Ok(())
}

/// Python's `int(f)`: exact, however large.
fn to_int(f: f64, span: Span) -> R<Value> {
    int::from_f64(f).or_else(|m| py_err(span, m))
}

/// A count (of repetitions, a width) as Python reads it: big integers
/// saturate, so that they are refused as too large.
fn count(v: &Value) -> Option<i128> {
    int::as_count(v)
}

/// `n` copies of `items` (list or tuple repetition), its size checked first.
fn repeat_items(items: &[Value], n: i128) -> Result<Vec<Value>, String> {
    if n <= 0 || items.is_empty() {
        return Ok(Vec::new());
    }
    let total = (items.len() as u128).saturating_mul(n as u128);
    if total > MAX_ITEMS as u128 {
        return Err(too_large(total, MAX_ITEMS, "items"));
    }
    let mut v = Vec::with_capacity(total as usize);
    for _ in 0..n {
        v.extend(items.iter().cloned());
    }
    Ok(v)
}

/// A string of `n` bytes at most [`MAX_STR_BYTES`].
fn check_str_len(n: u128) -> Result<(), String> {
    if n > MAX_STR_BYTES as u128 {
        return Err(too_large(n, MAX_STR_BYTES, "characters"));
    }
    Ok(())
}

/// A list or tuple of `n` items at most [`MAX_ITEMS`].
fn check_items(n: usize) -> Result<(), String> {
    if n > MAX_ITEMS {
        return Err(too_large(n as u128, MAX_ITEMS, "items"));
    }
    Ok(())
}

pub fn call(me: &mut Interp, name: &str, args: Vec<CallArg>, span: Span) -> R<Value> {
    if let Some(m) = name.strip_prefix("math.") {
        let v = positional(&args, name, span)?;
        if v.iter().any(|x| matches!(x, Value::Unknown)) {
            return Ok(Value::Unknown);
        }
        return math_call(m, &v, span);
    }
    if name.starts_with("os.") {
        let v = positional(&args, name, span)?;
        if v.iter().any(|x| matches!(x, Value::Unknown)) {
            return Ok(Value::Unknown);
        }
        return crate::os_module::call(name, &v, span);
    }
    let v = positional(&args, name, span)?;
    if v.iter().any(|x| matches!(x, Value::Unknown))
        && !matches!(
            name,
            "print" | "len" | "list" | "tuple" | "str" | "repr" | "isinstance" | "type"
        )
    {
        return Ok(Value::Unknown);
    }
    Ok(match name {
        "range" => {
            let ints: Vec<i64> = v
                .iter()
                .map(|x| match x {
                    Value::Int(i) => Ok(*i),
                    Value::Bool(b) => Ok(*b as i64),
                    Value::Big(_) => py_err(
                        span,
                        too_large(int::bits(x) as u128, 64, "bits for a range bound"),
                    ),
                    other => py_err(
                        span,
                        format!("range() needs integers, not {}", other.type_name()),
                    ),
                })
                .collect::<R<_>>()?;
            let (a, b, s) = match ints.as_slice() {
                [b] => (0, *b, 1),
                [a, b] => (*a, *b, 1),
                [a, b, s] => (*a, *b, *s),
                _ => return py_err(span, "range() takes 1 to 3 arguments"),
            };
            if s == 0 {
                return py_err(span, "range() step must not be zero");
            }
            // In i128: no overflow for any i64 bounds and step.
            let (a, b, s) = (a as i128, b as i128, s as i128);
            let n = if s > 0 {
                (b - a + s - 1).max(0) / s
            } else {
                (a - b - s - 1).max(0) / -s
            };
            if n > MAX_ITEMS as i128 {
                return py_err(
                    span,
                    format!(
                        "range() too long: {n} items (the limit is {MAX_ITEMS}; ranges are built as lists)"
                    ),
                );
            }
            me.charge(n as u64, span, "this range()")?;
            Value::list((0..n).map(|k| Value::Int((a + k * s) as i64)).collect())
        }
        "len" => {
            arity(&v, 1, name, span)?;
            match &v[0] {
                Value::Str(s) => Value::Int(s.chars().count() as i64),
                Value::List(l) => Value::Int(l.borrow().len() as i64),
                Value::Tuple(t) => Value::Int(t.len() as i64),
                Value::Dict(d) => Value::Int(d.borrow().entries.len() as i64),
                Value::Unknown => Value::Unknown,
                t @ (Value::Table(_) | Value::Column(_)) => {
                    crate::table::len(t).unwrap_or(Value::Unknown)
                }
                other => {
                    return py_err(
                        span,
                        format!("object of type '{}' has no len()", other.type_name()),
                    )
                }
            }
        }
        "abs" => {
            arity(&v, 1, name, span)?;
            match &v[0] {
                x @ (Value::Int(_) | Value::Bool(_) | Value::Big(_)) => int::abs(x),
                Value::Float(f) => Value::Float(f.abs()),
                Value::Complex(a, b) => Value::Float(a.hypot(*b)),
                other => {
                    return py_err(
                        span,
                        format!("bad operand type for abs(): '{}'", other.type_name()),
                    )
                }
            }
        }
        "min" | "max" => {
            let items = if v.len() == 1 {
                me.iterate(&v[0], span)?
            } else {
                v
            };
            if items.iter().any(|x| matches!(x, Value::Unknown)) {
                return Ok(Value::Unknown);
            }
            let key = kwarg(&args, "key").cloned();
            let mut best: Option<(Value, Value)> = None;
            for it in items {
                let k = match &key {
                    Some(f) => me.call_value(
                        f.clone(),
                        vec![CallArg {
                            name: None,
                            value: it.clone(),
                            span,
                        }],
                        span,
                        None,
                    )?,
                    None => it.clone(),
                };
                let better = match &best {
                    None => true,
                    Some((bk, _)) => {
                        let o = order(&k, bk).or_else(|m| py_err(span, m))?;
                        if name == "min" {
                            o.is_lt()
                        } else {
                            o.is_gt()
                        }
                    }
                };
                if better {
                    best = Some((k, it));
                }
            }
            match best {
                Some((_, x)) => x,
                None => return py_err(span, format!("{name}() arg is an empty sequence")),
            }
        }
        "sum" => {
            let items = me.iterate(v.first().unwrap_or(&Value::None), span)?;
            let mut acc = v.get(1).cloned().unwrap_or(Value::Int(0));
            for it in items {
                acc = binop(BinOp::Add, acc, it).or_else(|m| py_err(span, m))?;
            }
            acc
        }
        "float" => match v.first() {
            None => Value::Float(0.0),
            Some(Value::Str(s)) => match s.trim().to_lowercase().as_str() {
                "inf" | "+inf" => Value::Float(f64::INFINITY),
                "-inf" => Value::Float(f64::NEG_INFINITY),
                "nan" => Value::Float(f64::NAN),
                t => Value::Float(t.parse().or_else(|_| {
                    py_err(span, format!("could not convert string to float: '{s}'"))
                })?),
            },
            Some(x) => Value::Float(num(x, span)?),
        },
        "int" => match v.first() {
            None => Value::Int(0),
            Some(Value::Str(s)) => match int::parse(s) {
                Some(i) => i,
                None => {
                    let shown: String = s.chars().take(60).collect();
                    return py_err(
                        span,
                        format!("invalid literal for int() with base 10: '{shown}'"),
                    );
                }
            },
            Some(x @ (Value::Int(_) | Value::Big(_))) => x.clone(),
            Some(x) => to_int(num(x, span)?, span)?,
        },
        "bool" => Value::Bool(match v.first() {
            None => false,
            Some(x) => me.truth(x, span)?,
        }),
        "complex" => {
            let a = v.first().map(|x| num(x, span)).transpose()?.unwrap_or(0.0);
            let b = v.get(1).map(|x| num(x, span)).transpose()?.unwrap_or(0.0);
            Value::Complex(a, b)
        }
        "str" => Value::str(
            &v.first()
                .map(|x| x.try_str())
                .transpose()
                .or_else(|m| py_err(span, m))?
                .unwrap_or_default(),
        ),
        "repr" => Value::str(
            &v.first()
                .map(|x| x.try_repr())
                .transpose()
                .or_else(|m| py_err(span, m))?
                .unwrap_or_default(),
        ),
        "round" => {
            let first = v.first().unwrap_or(&Value::None);
            let nd = v.get(1).or(kwarg(&args, "ndigits"));
            if int::is_int(first) {
                // An integer rounded to digits at or after the point is itself.
                match nd.map(count) {
                    None | Some(None) => return Ok(int::plain(first)),
                    Some(Some(n)) if n >= 0 => return Ok(int::plain(first)),
                    Some(Some(n)) => {
                        return int::round_int(first, (-n).min(u32::MAX as i128) as u32)
                            .or_else(|m| py_err(span, m))
                    }
                }
            }
            let x = num(first, span)?;
            match nd {
                None | Some(Value::None) => to_int(round_half_even(x), span)?,
                Some(n) => {
                    let Some(n) = count(n) else {
                        return py_err(span, "round(): ndigits must be an integer");
                    };
                    if !x.is_finite() || n > 400 {
                        // Beyond a float's digits: the number itself.
                        Value::Float(x)
                    } else if n >= 0 {
                        // Python rounds the exact binary value (round(2.675, 2)
                        // is 2.67): so does Rust's decimal formatting.
                        let digits = n as usize;
                        Value::Float(format!("{x:.digits$}").parse().unwrap_or(x))
                    } else if n < -308 {
                        // 10^-n is beyond the floats: everything rounds to zero.
                        Value::Float(0.0 * x.signum())
                    } else {
                        let p = 10f64.powi(-n as i32);
                        Value::Float(round_half_even(x / p) * p)
                    }
                }
            }
        }
        "list" | "tuple" | "set" => {
            let items = match v.first() {
                None => Vec::new(),
                Some(x) => me.iterate(x, span)?,
            };
            match name {
                "tuple" => Value::tuple(items),
                "set" => {
                    let mut out: Vec<Value> = Vec::new();
                    for x in items {
                        if !out.iter().any(|y| y.py_eq(&x)) {
                            out.push(x);
                        }
                    }
                    Value::list(out)
                }
                _ => Value::list(items),
            }
        }
        "dict" => {
            let mut d = Dict::default();
            if let Some(src) = v.first() {
                match src {
                    Value::Dict(s) => d.entries = s.borrow().entries.clone(),
                    other => {
                        for pair in me.iterate(other, span)? {
                            let kv = me.iterate(&pair, span)?;
                            if kv.len() != 2 {
                                return py_err(span, "dict() needs pairs");
                            }
                            d.insert(kv[0].clone(), kv[1].clone(), span);
                        }
                    }
                }
            }
            for a in &args {
                if let Some((k, _)) = &a.name {
                    d.insert(Value::str(k), a.value.clone(), a.span);
                }
            }
            Value::Dict(Rc::new(std::cell::RefCell::new(d)))
        }
        "zip" => {
            let lists: Vec<Vec<Value>> = v.iter().map(|x| me.iterate(x, span)).collect::<R<_>>()?;
            let n = lists.iter().map(|l| l.len()).min().unwrap_or(0);
            Value::list(
                (0..n)
                    .map(|i| Value::tuple(lists.iter().map(|l| l[i].clone()).collect()))
                    .collect(),
            )
        }
        "enumerate" => {
            let items = me.iterate(v.first().unwrap_or(&Value::None), span)?;
            let start = match v.get(1) {
                Some(Value::Int(s)) => *s,
                _ => 0,
            };
            Value::list(
                items
                    .into_iter()
                    .enumerate()
                    .map(|(i, x)| Value::tuple(vec![Value::Int(start + i as i64), x]))
                    .collect(),
            )
        }
        "reversed" => {
            let mut items = me.iterate(v.first().unwrap_or(&Value::None), span)?;
            items.reverse();
            Value::list(items)
        }
        "sorted" => {
            let items = me.iterate(v.first().unwrap_or(&Value::None), span)?;
            let key = kwarg(&args, "key").cloned();
            let rev = kwarg(&args, "reverse")
                .and_then(|r| r.truthy())
                .unwrap_or(false);
            Value::list(sort_values(me, items, key, rev, span)?)
        }
        "any" | "all" => {
            let items = me.iterate(v.first().unwrap_or(&Value::None), span)?;
            let mut acc = name == "all";
            for x in items {
                let t = me.truth(&x, span)?;
                if name == "any" && t {
                    acc = true;
                    break;
                }
                if name == "all" && !t {
                    acc = false;
                    break;
                }
            }
            Value::Bool(acc)
        }
        "map" | "filter" => {
            let f = v.first().cloned().unwrap_or(Value::None);
            let lists: Vec<Vec<Value>> = v[1.min(v.len())..]
                .iter()
                .map(|x| me.iterate(x, span))
                .collect::<R<_>>()?;
            let n = lists.iter().map(|l| l.len()).min().unwrap_or(0);
            let mut out = Vec::new();
            for i in 0..n {
                let cargs: Vec<CallArg> = lists
                    .iter()
                    .map(|l| CallArg {
                        name: None,
                        value: l[i].clone(),
                        span,
                    })
                    .collect();
                if name == "filter" {
                    let keep = if matches!(f, Value::None) {
                        me.truth(&lists[0][i], span)?
                    } else {
                        let r = me.call_value(f.clone(), cargs, span, None)?;
                        me.truth(&r, span)?
                    };
                    if keep {
                        out.push(lists[0][i].clone());
                    }
                } else {
                    out.push(me.call_value(f.clone(), cargs, span, None)?);
                }
            }
            Value::list(out)
        }
        "pow" => match v.as_slice() {
            [a, b] => binop(BinOp::Pow, a.clone(), b.clone()).or_else(|m| py_err(span, m))?,
            [a, b, m] => int::pow_mod(a, b, m).or_else(|e| py_err(span, e))?,
            _ => return py_err(span, "pow() takes 2 or 3 arguments"),
        },
        "divmod" => {
            if v.len() != 2 {
                return py_err(span, "divmod() takes 2 arguments");
            }
            let q =
                binop(BinOp::FloorDiv, v[0].clone(), v[1].clone()).or_else(|m| py_err(span, m))?;
            let r = binop(BinOp::Mod, v[0].clone(), v[1].clone()).or_else(|m| py_err(span, m))?;
            Value::tuple(vec![q, r])
        }
        "isinstance" => {
            arity(&v, 2, name, span)?;
            let tn = v[0].type_name();
            let names: Vec<Value> = match &v[1] {
                Value::Tuple(t) => t.to_vec(),
                other => vec![other.clone()],
            };
            Value::Bool(names.iter().any(|n| match n {
                Value::Builtin(Builtin::Fn(b)) => *b == tn,
                _ => false,
            }))
        }
        "type" => {
            arity(&v, 1, name, span)?;
            match builtin(v[0].type_name()) {
                Some(b) => b,
                None => Value::str(v[0].type_name()),
            }
        }
        // `getattr(obj, 'NAME')` is `obj.NAME`; the default of the
        // three-argument form answers only when the attribute is missing.
        "getattr" => {
            if !(2..=3).contains(&v.len()) {
                return py_err(span, "getattr() takes 2 or 3 arguments");
            }
            let Value::Str(attr) = &v[1] else {
                return py_err(span, "getattr(): attribute name must be a string");
            };
            match (me.attribute(v[0].clone(), attr, span), v.get(2)) {
                (Ok(x), _) => x,
                (Err(Halt::Diag(d)), Some(dflt)) if d.kind == DiagKind::Python => dflt.clone(),
                (Err(e), _) => return Err(e),
            }
        }
        "format" => {
            let spec = match v.get(1) {
                Some(Value::Str(s)) => s.to_string(),
                _ => String::new(),
            };
            let x = v.first().cloned().unwrap_or(Value::None);
            Value::str(&format::format_spec(&x, &spec).or_else(|m| py_err(span, m))?)
        }
        "ord" => match v.first() {
            Some(Value::Str(s)) if s.chars().count() == 1 => {
                Value::Int(s.chars().next().map(|c| c as i64).unwrap_or(0))
            }
            _ => return py_err(span, "ord() expects a character"),
        },
        "chr" => match v.first() {
            Some(Value::Int(i)) => match u32::try_from(*i).ok().and_then(char::from_u32) {
                Some(c) => Value::str(&c.to_string()),
                None => return py_err(span, "chr() arg not in range(0x110000)"),
            },
            _ => return py_err(span, "chr() expects an integer"),
        },
        "print" => {
            let sep = kwarg(&args, "sep")
                .map(|s| s.try_str())
                .transpose()
                .or_else(|m| py_err(span, m))?
                .unwrap_or(" ".into());
            let line = v
                .iter()
                .map(|x| x.try_str())
                .collect::<Result<Vec<_>, _>>()
                .or_else(|m| py_err(span, m))?
                .join(&sep);
            if kwarg(&args, "file").is_some() {
                return unsupported(span, "print(file=...)");
            }
            me.sink.print(&line);
            Value::None
        }
        "open" | "input" | "eval" | "exec" | "globals" | "locals" | "__import__" | "iter"
        | "next" | "hasattr" => return unsupported(span, format!("the builtin `{name}`")),
        other => return unsupported(span, format!("the builtin `{other}`")),
    })
}

fn round_half_even(x: f64) -> f64 {
    let r = x.round();
    if (x - x.trunc()).abs() == 0.5 {
        2.0 * (x / 2.0).round()
    } else {
        r
    }
}

fn sort_values(
    me: &mut Interp,
    items: Vec<Value>,
    key: Option<Value>,
    rev: bool,
    span: Span,
) -> R<Vec<Value>> {
    let mut keyed = Vec::with_capacity(items.len());
    for it in items {
        let k = match &key {
            Some(f) if !matches!(f, Value::None) => me.call_value(
                f.clone(),
                vec![CallArg {
                    name: None,
                    value: it.clone(),
                    span,
                }],
                span,
                None,
            )?,
            _ => it.clone(),
        };
        keyed.push((k, it));
    }
    let mut failure = None;
    keyed.sort_by(|a, b| match order(&a.0, &b.0) {
        Ok(o) => o,
        Err(m) => {
            failure = Some(m);
            Ordering::Equal
        }
    });
    if let Some(m) = failure {
        return py_err(span, m);
    }
    if rev {
        keyed.reverse();
    }
    Ok(keyed.into_iter().map(|(_, v)| v).collect())
}

fn math_call(m: &str, v: &[Value], span: Span) -> R<Value> {
    let x = |i: usize| -> R<f64> { num(v.get(i).unwrap_or(&Value::None), span) };
    let domain = |ok: bool, r: f64| -> R<Value> {
        if ok {
            Ok(Value::Float(r))
        } else {
            py_err(span, format!("math domain error in {m}()"))
        }
    };
    Ok(match m {
        "sqrt" => return domain(x(0)? >= 0.0, x(0)?.sqrt()),
        "sin" => Value::Float(x(0)?.sin()),
        "cos" => Value::Float(x(0)?.cos()),
        "tan" => Value::Float(x(0)?.tan()),
        "asin" => return domain(x(0)?.abs() <= 1.0, x(0)?.asin()),
        "acos" => return domain(x(0)?.abs() <= 1.0, x(0)?.acos()),
        "atan" => Value::Float(x(0)?.atan()),
        "atan2" => Value::Float(x(0)?.atan2(x(1)?)),
        "sinh" => Value::Float(x(0)?.sinh()),
        "cosh" => Value::Float(x(0)?.cosh()),
        "tanh" => Value::Float(x(0)?.tanh()),
        "asinh" => Value::Float(x(0)?.asinh()),
        "acosh" => Value::Float(x(0)?.acosh()),
        "atanh" => Value::Float(x(0)?.atanh()),
        "exp" => Value::Float(x(0)?.exp()),
        "expm1" => Value::Float(x(0)?.exp_m1()),
        "log1p" => Value::Float(x(0)?.ln_1p()),
        "log" => {
            let a = x(0)?;
            if a <= 0.0 {
                return py_err(span, "math domain error in log()");
            }
            match v.get(1) {
                Some(b) => Value::Float(a.ln() / num(b, span)?.ln()),
                None => Value::Float(a.ln()),
            }
        }
        "log10" => return domain(x(0)? > 0.0, x(0)?.log10()),
        "log2" => return domain(x(0)? > 0.0, x(0)?.log2()),
        "pow" => Value::Float(x(0)?.powf(x(1)?)),
        "fabs" => Value::Float(x(0)?.abs()),
        "floor" => to_int(x(0)?.floor(), span)?,
        "ceil" => to_int(x(0)?.ceil(), span)?,
        "trunc" => to_int(x(0)?.trunc(), span)?,
        "degrees" => Value::Float(x(0)?.to_degrees()),
        "radians" => Value::Float(x(0)?.to_radians()),
        "hypot" => Value::Float(
            v.iter()
                .map(|a| num(a, span))
                .collect::<R<Vec<f64>>>()?
                .iter()
                .map(|a| a * a)
                .sum::<f64>()
                .sqrt(),
        ),
        "fmod" => Value::Float(x(0)? % x(1)?),
        "copysign" => Value::Float(x(0)?.copysign(x(1)?)),
        "isnan" => Value::Bool(x(0)?.is_nan()),
        "isinf" => Value::Bool(x(0)?.is_infinite()),
        "factorial" => match v.first() {
            Some(Value::Int(n)) if *n >= 0 && *n <= 20 => Value::Int((1..=*n).product()),
            Some(x @ Value::Int(n)) if *n > 20 => int::factorial(x).or_else(|m| py_err(span, m))?,
            Some(Value::Big(_)) => return py_err(span, int::too_large()),
            _ => {
                return py_err(
                    span,
                    "factorial() not defined for negative values or non-integers",
                )
            }
        },
        other => return unsupported(span, format!("math.{other}")),
    })
}

/// Methods of built-in values, and of concepts (through the sink).
pub fn method(me: &mut Interp, recv: Value, m: &str, args: Vec<CallArg>, span: Span) -> R<Value> {
    let v: Vec<Value> = args
        .iter()
        .filter(|a| a.name.is_none())
        .map(|a| a.value.clone())
        .collect();
    let arg = |i: usize| v.get(i).cloned().unwrap_or(Value::None);
    let s_arg = |i: usize| -> R<String> {
        match v.get(i) {
            Some(Value::Str(s)) => Ok(s.to_string()),
            _ => py_err(span, format!("{m}() expects a string argument")),
        }
    };
    match &recv {
        Value::Table(t) => return crate::table::method(t, m, &v, span),
        Value::Column(c) => return crate::table::column_method(c, m, &v, span),
        Value::Str(s) => {
            let s: &str = s;
            return Ok(match m {
                "upper" => Value::str(&s.to_uppercase()),
                "lower" => Value::str(&s.to_lowercase()),
                "strip" | "lstrip" | "rstrip" => {
                    let chars: Option<Vec<char>> = match v.first() {
                        Some(Value::Str(c)) => Some(c.chars().collect()),
                        _ => None,
                    };
                    let pred = |c: char| match &chars {
                        Some(cs) => cs.contains(&c),
                        None => c.is_whitespace(),
                    };
                    Value::str(match m {
                        "strip" => s.trim_matches(pred),
                        "lstrip" => s.trim_start_matches(pred),
                        _ => s.trim_end_matches(pred),
                    })
                }
                "split" => {
                    let parts: Vec<Value> = match v.first() {
                        Some(Value::Str(sep)) => s.split(&**sep).map(Value::str).collect(),
                        _ => s.split_whitespace().map(Value::str).collect(),
                    };
                    Value::list(parts)
                }
                "join" => {
                    let items = me.iterate(&arg(0), span)?;
                    let mut parts = Vec::new();
                    let mut total = 0u128;
                    for it in items {
                        match it {
                            Value::Str(x) => {
                                total += (x.len() + s.len()) as u128;
                                check_str_len(total).or_else(|m| py_err(span, m))?;
                                parts.push(x.to_string())
                            }
                            other => {
                                return py_err(
                                    span,
                                    format!("join() expects strings, found {}", other.type_name()),
                                )
                            }
                        }
                    }
                    Value::str(&parts.join(s))
                }
                "replace" => {
                    let (old, new) = (s_arg(0)?, s_arg(1)?);
                    // The result's size, before building it.
                    let hits = if old.is_empty() {
                        s.chars().count() + 1
                    } else {
                        s.matches(old.as_str()).count()
                    };
                    let size = s.len() as u128 + hits as u128 * new.len() as u128;
                    check_str_len(size).or_else(|m| py_err(span, m))?;
                    Value::str(&s.replace(&old, &new))
                }
                "startswith" | "endswith" => {
                    let pats: Vec<String> = match arg(0) {
                        Value::Tuple(t) => t.iter().map(|x| x.to_string()).collect(),
                        x => vec![x.to_string()],
                    };
                    Value::Bool(pats.iter().any(|p| {
                        if m == "startswith" {
                            s.starts_with(p.as_str())
                        } else {
                            s.ends_with(p.as_str())
                        }
                    }))
                }
                "find" | "index" => {
                    let p = s_arg(0)?;
                    match s.find(&p) {
                        Some(i) => Value::Int(s[..i].chars().count() as i64),
                        None if m == "find" => Value::Int(-1),
                        None => return py_err(span, "substring not found"),
                    }
                }
                "count" => Value::Int(s.matches(&s_arg(0)?).count() as i64),
                "zfill" => {
                    let w = count(&arg(0)).unwrap_or(0).max(0);
                    check_str_len(w as u128).or_else(|m| py_err(span, m))?;
                    let w = w as usize;
                    Value::str(&format!(
                        "{}{s}",
                        "0".repeat(w.saturating_sub(s.chars().count()))
                    ))
                }
                "ljust" | "rjust" | "center" => {
                    let w = count(&arg(0)).unwrap_or(0).max(0);
                    check_str_len(w as u128).or_else(|m| py_err(span, m))?;
                    let spec = format!(
                        "{}{w}",
                        match m {
                            "ljust" => '<',
                            "rjust" => '>',
                            _ => '^',
                        }
                    );
                    Value::str(&format::format_spec(&recv, &spec).or_else(|e| py_err(span, e))?)
                }
                "title" | "capitalize" => {
                    let mut out = String::new();
                    let mut start = true;
                    for c in s.chars() {
                        if start {
                            out.extend(c.to_uppercase())
                        } else {
                            out.extend(c.to_lowercase())
                        }
                        start = m == "title" && !c.is_alphanumeric();
                        if m == "capitalize" {
                            start = false;
                        }
                    }
                    Value::str(&out)
                }
                "isdigit" => Value::Bool(!s.is_empty() && s.chars().all(|c| c.is_ascii_digit())),
                "isalpha" => Value::Bool(!s.is_empty() && s.chars().all(|c| c.is_alphabetic())),
                "format" => Value::str(&str_format(s, &args, span)?),
                _ => return py_err(span, format!("'str' object has no attribute '{m}'")),
            });
        }
        Value::List(l) => {
            return Ok(match m {
                "append" => {
                    l.borrow_mut().push(arg(0));
                    Value::None
                }
                "extend" => {
                    let items = me.iterate(&arg(0), span)?;
                    check_items(l.borrow().len() + items.len()).or_else(|m| py_err(span, m))?;
                    l.borrow_mut().extend(items);
                    Value::None
                }
                "insert" => {
                    let n = l.borrow().len() as i64;
                    let i = match count(&arg(0)) {
                        Some(i) => {
                            let n = n as i128;
                            if i < 0 {
                                (n + i).max(0)
                            } else {
                                i.min(n)
                            }
                        }
                        None => return py_err(span, "insert() needs an index"),
                    };
                    l.borrow_mut().insert(i as usize, arg(1));
                    Value::None
                }
                "pop" => {
                    let n = l.borrow().len();
                    if n == 0 {
                        return py_err(span, "pop from empty list");
                    }
                    let i = match v.first() {
                        Some(k) => me.index_of(k, n, span)?,
                        None => n - 1,
                    };
                    l.borrow_mut().remove(i)
                }
                "remove" => {
                    let x = arg(0);
                    let pos = l.borrow().iter().position(|y| y.py_eq(&x));
                    match pos {
                        Some(i) => {
                            l.borrow_mut().remove(i);
                            Value::None
                        }
                        None => return py_err(span, "list.remove(x): x not in list"),
                    }
                }
                "index" => {
                    let x = arg(0);
                    match l.borrow().iter().position(|y| y.py_eq(&x)) {
                        Some(i) => Value::Int(i as i64),
                        None => return py_err(span, format!("{} is not in list", x.repr())),
                    }
                }
                "count" => {
                    let x = arg(0);
                    Value::Int(l.borrow().iter().filter(|y| y.py_eq(&x)).count() as i64)
                }
                "reverse" => {
                    l.borrow_mut().reverse();
                    Value::None
                }
                "sort" => {
                    let items = l.borrow().to_vec();
                    let key = kwarg(&args, "key").cloned();
                    let rev = kwarg(&args, "reverse")
                        .and_then(|r| r.truthy())
                        .unwrap_or(false);
                    let sorted = sort_values(me, items, key, rev, span)?;
                    *l.borrow_mut() = Items(sorted);
                    Value::None
                }
                "copy" => Value::list(l.borrow().to_vec()),
                _ => return py_err(span, format!("'list' object has no attribute '{m}'")),
            });
        }
        Value::Tuple(t) => {
            return Ok(match m {
                "index" => match t.iter().position(|y| y.py_eq(&arg(0))) {
                    Some(i) => Value::Int(i as i64),
                    None => return py_err(span, "tuple.index(x): x not in tuple"),
                },
                "count" => Value::Int(t.iter().filter(|y| y.py_eq(&arg(0))).count() as i64),
                _ => return py_err(span, format!("'tuple' object has no attribute '{m}'")),
            });
        }
        Value::Dict(d) => {
            return Ok(match m {
                "keys" => Value::list(d.borrow().entries.iter().map(|e| e.key.clone()).collect()),
                "values" => {
                    Value::list(d.borrow().entries.iter().map(|e| e.value.clone()).collect())
                }
                "items" => Value::list(
                    d.borrow()
                        .entries
                        .iter()
                        .map(|e| Value::tuple(vec![e.key.clone(), e.value.clone()]))
                        .collect(),
                ),
                "get" => d.borrow().get(&arg(0)).cloned().unwrap_or(arg(1)),
                "copy" => Value::Dict(Rc::new(std::cell::RefCell::new(d.borrow().clone()))),
                "update" => {
                    if let Value::Dict(src) = arg(0) {
                        let entries = src.borrow().entries.clone();
                        for e in entries {
                            d.borrow_mut().insert(e.key, e.value, e.span);
                        }
                    }
                    for a in &args {
                        if let Some((k, _)) = &a.name {
                            d.borrow_mut()
                                .insert(Value::str(k), a.value.clone(), a.span);
                        }
                    }
                    Value::None
                }
                "pop" => {
                    let r = d.borrow_mut().remove(&arg(0));
                    match (r, v.get(1)) {
                        (Some(x), _) => x,
                        (None, Some(dflt)) => dflt.clone(),
                        (None, None) => {
                            return py_err(span, format!("KeyError: {}", arg(0).repr()))
                        }
                    }
                }
                "setdefault" => {
                    let cur = d.borrow().get(&arg(0)).cloned();
                    match cur {
                        Some(x) => x,
                        None => {
                            d.borrow_mut().insert(arg(0), arg(1), span);
                            arg(1)
                        }
                    }
                }
                _ => return py_err(span, format!("'dict' object has no attribute '{m}'")),
            });
        }
        Value::Concept(c) | Value::Formula(c, _) => {
            let hv: Vec<_> = v.iter().map(to_host).collect();
            let c = c.clone();
            return match me.sink.method(&c, m, &hv) {
                Ok(h) => Ok(from_host(h)),
                Err(e) => Err(crate::interp::exec_diag(span, e).into()),
            };
        }
        // A method of an attribute of a concept (`resu.userName.ljust(8)`):
        // the attribute is known only when the commands run.
        Value::Method(r, _) if matches!(**r, Value::Concept(_) | Value::Formula(..)) => {
            return Ok(Value::Unknown)
        }
        Value::Float(f) if m == "is_integer" => return Ok(Value::Bool(f.fract() == 0.0)),
        Value::Complex(a, b) if m == "conjugate" => return Ok(Value::Complex(*a, -*b)),
        _ => {}
    }
    py_err(
        span,
        format!("'{}' object has no attribute '{m}'", recv.type_name()),
    )
}

/// `"...".format(...)`.
fn str_format(s: &str, args: &[CallArg], span: Span) -> R<String> {
    let pos: Vec<&Value> = args
        .iter()
        .filter(|a| a.name.is_none())
        .map(|a| &a.value)
        .collect();
    let mut out = String::new();
    let mut auto = 0usize;
    let chars: Vec<char> = s.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '{' && chars.get(i + 1) == Some(&'{') {
            out.push('{');
            i += 2;
            continue;
        }
        if c == '}' && chars.get(i + 1) == Some(&'}') {
            out.push('}');
            i += 2;
            continue;
        }
        if c != '{' {
            out.push(c);
            i += 1;
            continue;
        }
        let start = i + 1;
        while i < chars.len() && chars[i] != '}' {
            i += 1;
        }
        let field: String = chars[start..i.min(chars.len())].iter().collect();
        i += 1;
        let (name, spec) = field.split_once(':').unwrap_or((&field, ""));
        let (name, conv) = name.split_once('!').unwrap_or((name, ""));
        let v = if name.is_empty() {
            auto += 1;
            pos.get(auto - 1).copied()
        } else if let Ok(k) = name.parse::<usize>() {
            pos.get(k).copied()
        } else {
            args.iter()
                .find(|a| a.name.as_ref().is_some_and(|n| n.0 == name))
                .map(|a| &a.value)
        };
        let Some(v) = v else {
            return py_err(span, format!("format field `{{{field}}}` has no argument"));
        };
        let v = if conv == "r" {
            Value::str(&v.repr())
        } else {
            v.clone()
        };
        out.push_str(&format::format_spec(&v, spec).or_else(|m| py_err(span, m))?);
    }
    Ok(out)
}

pub fn slice(
    v: &Value,
    lo: Option<Value>,
    hi: Option<Value>,
    st: Option<Value>,
    span: Span,
) -> R<Value> {
    let int = |x: &Option<Value>| -> R<Option<i64>> {
        match x {
            None | Some(Value::None) => Ok(None),
            Some(Value::Int(i)) => Ok(Some(*i)),
            Some(Value::Bool(b)) => Ok(Some(*b as i64)),
            // A huge index clamps to the ends, as in Python.
            Some(x @ Value::Big(_)) => Ok(Some(if count(x).is_some_and(|c| c < 0) {
                i64::MIN / 2
            } else {
                i64::MAX / 2
            })),
            Some(other) => py_err(
                span,
                format!("slice indices must be integers, not {}", other.type_name()),
            ),
        }
    };
    let (lo, hi, st) = (int(&lo)?, int(&hi)?, int(&st)?.unwrap_or(1));
    if st == 0 {
        return py_err(span, "slice step cannot be zero");
    }
    let pick = |n: usize| -> Vec<usize> {
        let n = n as i64;
        let norm = |x: i64| {
            if x < 0 {
                (n + x).max(if st > 0 { 0 } else { -1 })
            } else {
                x.min(if st > 0 { n } else { n - 1 })
            }
        };
        let (a, b) = if st > 0 {
            (lo.map(norm).unwrap_or(0), hi.map(norm).unwrap_or(n))
        } else {
            (lo.map(norm).unwrap_or(n - 1), hi.map(norm).unwrap_or(-1))
        };
        let mut out = Vec::new();
        let mut i = a;
        while (st > 0 && i < b) || (st < 0 && i > b) {
            out.push(i as usize);
            i += st;
        }
        out
    };
    Ok(match v {
        Value::List(l) => {
            let l = l.borrow();
            Value::list(pick(l.len()).into_iter().map(|i| l[i].clone()).collect())
        }
        Value::Tuple(t) => Value::tuple(pick(t.len()).into_iter().map(|i| t[i].clone()).collect()),
        Value::Str(s) => {
            let c: Vec<char> = s.chars().collect();
            Value::str(&pick(c.len()).into_iter().map(|i| c[i]).collect::<String>())
        }
        Value::Unknown => Value::Unknown,
        other => {
            return py_err(
                span,
                format!("'{}' object is not subscriptable", other.type_name()),
            )
        }
    })
}

/// Python ordering of two values.
pub fn order(a: &Value, b: &Value) -> Result<Ordering, String> {
    match (a, b) {
        (Value::Str(x), Value::Str(y)) => Ok(x.cmp(y)),
        (Value::Int(x), Value::Int(y)) => Ok(x.cmp(y)),
        (
            Value::Int(_) | Value::Big(_) | Value::Bool(_),
            Value::Int(_) | Value::Big(_) | Value::Bool(_),
        ) => Ok(int::big(a).cmp(&int::big(b))),
        (Value::Int(_) | Value::Big(_), Value::Float(f)) => Ok(int::big(a)
            .and_then(|x| int::cmp_float(&x, *f))
            .unwrap_or(Ordering::Equal)),
        (Value::Float(f), Value::Int(_) | Value::Big(_)) => Ok(int::big(b)
            .and_then(|x| int::cmp_float(&x, *f))
            .map(Ordering::reverse)
            .unwrap_or(Ordering::Equal)),
        (Value::List(x), Value::List(y)) => seq_order(&x.borrow(), &y.borrow()),
        (Value::Tuple(x), Value::Tuple(y)) => seq_order(x, y),
        _ => match (a.as_f64(), b.as_f64()) {
            (Some(x), Some(y)) => Ok(x.partial_cmp(&y).unwrap_or(Ordering::Equal)),
            _ => Err(format!(
                "'<' not supported between '{}' and '{}'",
                a.type_name(),
                b.type_name()
            )),
        },
    }
}

fn seq_order(a: &[Value], b: &[Value]) -> Result<Ordering, String> {
    for (x, y) in a.iter().zip(b) {
        let o = order(x, y)?;
        if o != Ordering::Equal {
            return Ok(o);
        }
    }
    Ok(a.len().cmp(&b.len()))
}

fn py_mod(a: f64, b: f64) -> f64 {
    let r = a % b;
    if r != 0.0 && (r < 0.0) != (b < 0.0) {
        r + b
    } else {
        r
    }
}

/// Binary arithmetic with Python semantics.
pub fn binop(op: BinOp, l: Value, r: Value) -> Result<Value, String> {
    use Value::*;
    let bad = |l: &Value, r: &Value| {
        Err(format!(
            "unsupported operand types for {op:?}: '{}' and '{}'",
            l.type_name(),
            r.type_name()
        ))
    };
    let l = if let Bool(b) = l { Int(b as i64) } else { l };
    let r = if let Bool(b) = r { Int(b as i64) } else { r };
    Ok(match (op, &l, &r) {
        (_, Unknown, _) | (_, _, Unknown) => Unknown,
        (BinOp::Add, Str(a), Str(b)) => {
            check_str_len(a.len() as u128 + b.len() as u128)?;
            Value::str(&format!("{a}{b}"))
        }
        (BinOp::Add, List(a), List(b)) => {
            check_items(a.borrow().len() + b.borrow().len())?;
            let mut v = a.borrow().to_vec();
            v.extend(b.borrow().iter().cloned());
            Value::list(v)
        }
        (BinOp::Add, Tuple(a), Tuple(b)) => {
            check_items(a.len() + b.len())?;
            let mut v = a.to_vec();
            v.extend(b.iter().cloned());
            Value::tuple(v)
        }
        (BinOp::Mul, Str(s), n) | (BinOp::Mul, n, Str(s)) if int::is_int(n) => {
            let n = count(n).unwrap_or(0);
            if n <= 0 || s.is_empty() {
                Value::str("")
            } else {
                check_str_len((s.len() as u128).saturating_mul(n as u128))?;
                Value::str(&s.repeat(n as usize))
            }
        }
        (BinOp::Mul, List(a), n) | (BinOp::Mul, n, List(a)) if int::is_int(n) => {
            Value::list(repeat_items(&a.borrow(), count(n).unwrap_or(0))?)
        }
        (BinOp::Mul, Tuple(a), n) | (BinOp::Mul, n, Tuple(a)) if int::is_int(n) => {
            Value::tuple(repeat_items(a, count(n).unwrap_or(0))?)
        }
        (BinOp::Mod, Str(f), args) => Value::str(&format::percent(f, args)?),
        (_, a, b) if int::is_int(a) && int::is_int(b) => int::binop(op, a, b)?,
        (_, Complex(..), _) | (_, _, Complex(..)) => {
            let c = |v: &Value| match v {
                Complex(a, b) => Some((*a, *b)),
                x => x.as_f64().map(|f| (f, 0.0)),
            };
            let (Some((a, b)), Some((x, y))) = (c(&l), c(&r)) else {
                return bad(&l, &r);
            };
            match op {
                BinOp::Add => Complex(a + x, b + y),
                BinOp::Sub => Complex(a - x, b - y),
                BinOp::Mul => Complex(a * x - b * y, a * y + b * x),
                BinOp::Div => {
                    let d = x * x + y * y;
                    if d == 0.0 {
                        return Err("complex division by zero".into());
                    }
                    Complex((a * x + b * y) / d, (b * x - a * y) / d)
                }
                _ => return bad(&l, &r),
            }
        }
        _ => {
            let (Some(a), Some(b)) = (l.as_f64(), r.as_f64()) else {
                return bad(&l, &r);
            };
            if (matches!(l, Big(_)) && a.is_infinite()) || (matches!(r, Big(_)) && b.is_infinite())
            {
                return Err("int too large to convert to float".into());
            }
            match op {
                BinOp::Add => Float(a + b),
                BinOp::Sub => Float(a - b),
                BinOp::Mul => Float(a * b),
                BinOp::Div => {
                    if b == 0.0 {
                        return Err("float division by zero".into());
                    }
                    Float(a / b)
                }
                BinOp::FloorDiv => {
                    if b == 0.0 {
                        return Err("float floor division by zero".into());
                    }
                    Float((a / b).floor())
                }
                BinOp::Mod => {
                    if b == 0.0 {
                        return Err("float modulo by zero".into());
                    }
                    Float(py_mod(a, b))
                }
                BinOp::Pow => {
                    if a < 0.0 && b.fract() != 0.0 {
                        return Err("negative number raised to a fractional power".into());
                    }
                    Float(a.powf(b))
                }
                _ => return bad(&l, &r),
            }
        }
    })
}
