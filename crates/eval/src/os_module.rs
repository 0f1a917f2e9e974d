//! Python's `os` and `os.path`, as far as command files use them for
//! pure computation: `os.environ` (the process environment, read when
//! the study first asks; assignments stay inside the study),
//! `os.getenv`, `os.sep`/`os.pathsep`, and the path arithmetic of
//! `os.path` (`join`, `basename`, `dirname`, `split`, `splitext`).
//!
//! Refused where used, located: what acts on the machine (`os.system`,
//! `os.rename`, `os.makedirs`, `os.remove`…) — a study's commands never
//! run other programs or move files behind the user's back — and what
//! asks the file system (`os.path.exists`, `isfile`, `isdir`, `abspath`,
//! `os.getcwd`): code_aster answers them in its own work directory, where
//! the `.export`'s files are copied under their names, so the answer here
//! (checked anywhere, run from any directory) would not be code_aster's.

use std::cell::RefCell;
use std::rc::Rc;

use aster_syntax::Span;

use crate::interp::{py_err, unsupported, R};
use crate::value::{Builtin, Dict, Value};

/// The modules this file serves.
pub(crate) fn is_os(module: &str) -> bool {
    module == "os" || module == "os.path"
}

/// `os.NAME` or `os.path.NAME`; `environ` is the interpreter's copy.
pub(crate) fn attr(module: &str, name: &str, environ: &mut Option<Value>) -> Option<Value> {
    let f = |n: &'static str| Some(Value::Builtin(Builtin::Fn(n)));
    match (module, name) {
        ("os", "path") => Some(Value::Module(Rc::from("os.path"))),
        ("os", "environ") => Some(
            environ
                .get_or_insert_with(|| {
                    let mut d = Dict::default();
                    for (k, v) in std::env::vars() {
                        d.insert(Value::str(&k), Value::str(&v), Span::default());
                    }
                    Value::Dict(Rc::new(RefCell::new(d)))
                })
                .clone(),
        ),
        ("os", "sep") | ("os.path", "sep") => Some(Value::str("/")),
        ("os", "pathsep") => Some(Value::str(":")),
        ("os", "curdir") | ("os.path", "curdir") => Some(Value::str(".")),
        ("os", "getenv") => f("os.getenv"),
        ("os.path", "join") => f("os.path.join"),
        ("os.path", "basename") => f("os.path.basename"),
        ("os.path", "dirname") => f("os.path.dirname"),
        ("os.path", "split") => f("os.path.split"),
        ("os.path", "splitext") => f("os.path.splitext"),
        _ => None,
    }
}

/// The refusal for a name of `os` this module does not serve.
pub(crate) fn refuse<T>(module: &str, name: &str, span: Span) -> R<T> {
    unsupported(
        span,
        format!(
            "`{module}.{name}` (of `{module}`, a command file may use environ, getenv and the path arithmetic of os.path: join, basename, dirname, split, splitext; the file system is code_aster's work directory, not reproduced)"
        ),
    )
}

fn text<'v>(v: &'v Value, name: &str, span: Span) -> R<&'v str> {
    match v {
        Value::Str(s) => Ok(s),
        other => py_err(
            span,
            format!("{name}() takes strings, not {}", other.type_name()),
        ),
    }
}

/// `os.path.split`: (head, tail) as Python's posixpath computes them.
fn split(p: &str) -> (String, String) {
    let i = p.rfind('/').map(|i| i + 1).unwrap_or(0);
    let (head, tail) = p.split_at(i);
    let trimmed = head.trim_end_matches('/');
    let head = if trimmed.is_empty() { head } else { trimmed };
    (head.to_string(), tail.to_string())
}

/// `os.path.splitext` (posixpath: a leading dot of the name is not an
/// extension).
fn splitext(p: &str) -> (String, String) {
    let name_at = p.rfind('/').map(|i| i + 1).unwrap_or(0);
    let name = &p[name_at..];
    let body = name.trim_start_matches('.');
    let lead = name.len() - body.len();
    match body.rfind('.') {
        Some(dot) => {
            let at = name_at + lead + dot;
            (p[..at].to_string(), p[at..].to_string())
        }
        None => (p.to_string(), String::new()),
    }
}

/// Calls `os.getenv`, `os.path.*` with positional `args`.
pub(crate) fn call(name: &str, args: &[Value], span: Span) -> R<Value> {
    let one = || -> R<&str> {
        match args {
            [a] => text(a, name, span),
            _ => py_err(span, format!("{name}() takes exactly one argument")),
        }
    };
    let pair = |(a, b): (String, String)| Value::tuple(vec![Value::str(&a), Value::str(&b)]);
    Ok(match name {
        "os.getenv" => {
            let (key, default) = match args {
                [k] => (text(k, name, span)?, Value::None),
                [k, d] => (text(k, name, span)?, d.clone()),
                _ => return py_err(span, "os.getenv() takes one or two arguments"),
            };
            match std::env::var(key) {
                Ok(v) => Value::str(&v),
                Err(_) => default,
            }
        }
        "os.path.join" => {
            if args.is_empty() {
                return py_err(span, "os.path.join() takes at least one argument");
            }
            let mut out = String::new();
            for a in args {
                let part = text(a, name, span)?;
                if part.starts_with('/') {
                    out = part.to_string();
                } else if out.is_empty() || out.ends_with('/') {
                    out.push_str(part);
                } else {
                    out.push('/');
                    out.push_str(part);
                }
            }
            Value::str(&out)
        }
        "os.path.basename" => Value::str(&split(one()?).1),
        "os.path.dirname" => Value::str(&split(one()?).0),
        "os.path.split" => pair(split(one()?)),
        "os.path.splitext" => pair(splitext(one()?)),
        other => return unsupported(span, format!("`{other}`")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn posix_path_arithmetic() {
        assert_eq!(split("/a/b/c.txt"), ("/a/b".into(), "c.txt".into()));
        assert_eq!(split("c.txt"), ("".into(), "c.txt".into()));
        assert_eq!(split("/c"), ("/".into(), "c".into()));
        assert_eq!(split("a//b"), ("a".into(), "b".into()));
        assert_eq!(
            splitext("dir.d/file.tar.gz"),
            ("dir.d/file.tar".into(), ".gz".into())
        );
        assert_eq!(
            splitext("dir.d/.bashrc"),
            ("dir.d/.bashrc".into(), "".into())
        );
        assert_eq!(splitext("x"), ("x".into(), "".into()));
        let j = |v: &[&str]| {
            let args: Vec<Value> = v.iter().map(|s| Value::str(s)).collect();
            match call("os.path.join", &args, Span::default()) {
                Ok(Value::Str(s)) => s.to_string(),
                _ => String::from("?"),
            }
        };
        assert_eq!(j(&["a", "b", "c.json"]), "a/b/c.json");
        assert_eq!(j(&["a/", "b"]), "a/b");
        assert_eq!(j(&["a", "/abs", "b"]), "/abs/b");
        assert_eq!(j(&["", "b"]), "b");
    }
}
