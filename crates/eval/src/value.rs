//! Python values of the evaluated subset.

use crate::command::ConceptRef;
use crate::formula::Formula;
use aster_syntax::ast;
use aster_syntax::Span;
use std::cell::RefCell;
use std::fmt;
use std::rc::Rc;

/// A user function (`def` or `lambda`).
#[derive(Debug)]
pub struct UserFunc {
    pub name: String,
    pub params: Vec<ast::Param>,
    /// Defaults evaluated at definition time, by parameter index.
    pub defaults: Vec<Option<Value>>,
    pub body: FuncBody,
    /// The enclosing function's variables when defined inside a function.
    pub closure: std::collections::HashMap<String, Value>,
    /// The study module the function was defined in (`None`: the command
    /// file): its globals are the module's.
    pub module: Option<Rc<str>>,
}

#[derive(Debug)]
pub enum FuncBody {
    Block(Vec<ast::Stmt>),
    Lambda(ast::Expr),
}

/// One entry of a dict; `_F(...)` keeps where each keyword was written.
#[derive(Clone, Debug)]
pub struct DictEntry {
    pub key: Value,
    pub value: Value,
    pub span: Span,
}

#[derive(Clone, Debug, Default)]
pub struct Dict {
    pub entries: Vec<DictEntry>,
}

impl Dict {
    pub fn get(&self, key: &Value) -> Option<&Value> {
        self.entries
            .iter()
            .find(|e| e.key.py_eq(key))
            .map(|e| &e.value)
    }
    pub fn insert(&mut self, key: Value, value: Value, span: Span) {
        if let Some(e) = self.entries.iter_mut().find(|e| e.key.py_eq(&key)) {
            e.value = value;
            e.span = span;
        } else {
            self.entries.push(DictEntry { key, value, span });
        }
    }
    pub fn remove(&mut self, key: &Value) -> Option<Value> {
        let i = self.entries.iter().position(|e| e.key.py_eq(key))?;
        Some(self.entries.remove(i).value)
    }
}

/// Built-in functions and modules.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Builtin {
    Fn(&'static str),
    /// `_F`
    Factor,
    /// `CO`
    Co,
    /// `code_aster.CA.TestCase`, the class.
    TestCase,
    /// A `CA.TestCase()` object (see `testcase`).
    TestCaseObject,
}

#[derive(Clone, Debug)]
pub enum Value {
    None,
    Bool(bool),
    Int(i64),
    Float(f64),
    Complex(f64, f64),
    Str(Rc<str>),
    List(Rc<RefCell<Vec<Value>>>),
    Tuple(Rc<Vec<Value>>),
    Dict(Rc<RefCell<Dict>>),
    Func(Rc<UserFunc>),
    Builtin(Builtin),
    /// A method bound to its receiver (`l.append`).
    Method(Box<Value>, Rc<str>),
    /// A catalog command.
    Command(Rc<str>),
    /// A concept produced by a command.
    Concept(ConceptRef),
    /// A `FORMULE` concept: callable.
    Formula(ConceptRef, Rc<Formula>),
    /// `CO('name')`: a concept a macro will create.
    Co(Rc<str>),
    /// An imported module (`math`, or an accepted no-op such as `code_aster`).
    Module(Rc<str>),
    /// A value only known when commands run (a table cell read while checking).
    Unknown,
}

impl Value {
    pub fn str(s: &str) -> Value {
        Value::Str(Rc::from(s))
    }
    pub fn list(v: Vec<Value>) -> Value {
        Value::List(Rc::new(RefCell::new(v)))
    }
    pub fn tuple(v: Vec<Value>) -> Value {
        Value::Tuple(Rc::new(v))
    }

    pub fn type_name(&self) -> &'static str {
        match self {
            Value::None => "NoneType",
            Value::Bool(_) => "bool",
            Value::Int(_) => "int",
            Value::Float(_) => "float",
            Value::Complex(..) => "complex",
            Value::Str(_) => "str",
            Value::List(_) => "list",
            Value::Tuple(_) => "tuple",
            Value::Dict(_) => "dict",
            Value::Func(_) | Value::Builtin(_) | Value::Method(..) => "function",
            Value::Command(_) => "command",
            Value::Concept(_) | Value::Formula(..) => "concept",
            Value::Co(_) => "CO",
            Value::Module(_) => "module",
            Value::Unknown => "run-time value",
        }
    }

    pub fn truthy(&self) -> Option<bool> {
        Some(match self {
            Value::None => false,
            Value::Bool(b) => *b,
            Value::Int(i) => *i != 0,
            Value::Float(f) => *f != 0.0,
            Value::Complex(a, b) => *a != 0.0 || *b != 0.0,
            Value::Str(s) => !s.is_empty(),
            Value::List(l) => !l.borrow().is_empty(),
            Value::Tuple(t) => !t.is_empty(),
            Value::Dict(d) => !d.borrow().entries.is_empty(),
            Value::Unknown => return None,
            _ => true,
        })
    }

    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Bool(b) => Some(*b as i64 as f64),
            Value::Int(i) => Some(*i as f64),
            Value::Float(f) => Some(*f),
            _ => None,
        }
    }

    pub fn py_eq(&self, other: &Value) -> bool {
        match (self, other) {
            (Value::Str(a), Value::Str(b)) => a == b,
            (Value::Int(a), Value::Int(b)) => a == b,
            (Value::None, Value::None) => true,
            (Value::List(a), Value::List(b)) => {
                let (a, b) = (a.borrow(), b.borrow());
                a.len() == b.len() && a.iter().zip(b.iter()).all(|(x, y)| x.py_eq(y))
            }
            (Value::Tuple(a), Value::Tuple(b)) => {
                a.len() == b.len() && a.iter().zip(b.iter()).all(|(x, y)| x.py_eq(y))
            }
            (Value::Concept(a), Value::Concept(b)) => a.id == b.id,
            (Value::Formula(a, _), Value::Formula(b, _)) => a.id == b.id,
            (Value::Complex(a, b), Value::Complex(c, d)) => a == c && b == d,
            (Value::Command(a), Value::Command(b)) => a == b,
            (Value::Module(a), Value::Module(b)) => a == b,
            (Value::Dict(a), Value::Dict(b)) => {
                let (a, b) = (a.borrow(), b.borrow());
                a.entries.len() == b.entries.len()
                    && a.entries
                        .iter()
                        .all(|e| b.get(&e.key).is_some_and(|v| v.py_eq(&e.value)))
            }
            _ => match (self.as_f64(), other.as_f64()) {
                (Some(a), Some(b)) => a == b,
                _ => false,
            },
        }
    }

    /// Python's `repr`.
    pub fn repr(&self) -> String {
        match self {
            Value::Str(s) => {
                if s.contains('\'') && !s.contains('"') {
                    format!("\"{s}\"")
                } else {
                    format!("'{}'", s.replace('\\', "\\\\").replace('\'', "\\'"))
                }
            }
            other => other.to_string(),
        }
    }
}

/// Python's `str` of a float.
pub fn float_str(f: f64) -> String {
    if f.is_nan() {
        "nan".into()
    } else if f.is_infinite() {
        if f > 0.0 { "inf" } else { "-inf" }.into()
    } else if f == f.trunc() && f.abs() < 1e16 {
        format!("{f:.1}")
    } else {
        let s = format!("{f}");
        // Python switches to exponent notation below 1e-4 and from 1e16.
        if f.abs() < 1e-4 || f.abs() >= 1e16 {
            let e = format!("{f:e}");
            match e.split_once('e') {
                Some((m, x)) => {
                    let x: i32 = x.parse().unwrap_or(0);
                    format!("{m}e{}{:02}", if x < 0 { '-' } else { '+' }, x.abs())
                }
                None => e,
            }
        } else {
            s
        }
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::None => write!(f, "None"),
            Value::Bool(b) => write!(f, "{}", if *b { "True" } else { "False" }),
            Value::Int(i) => write!(f, "{i}"),
            Value::Float(x) => write!(f, "{}", float_str(*x)),
            Value::Complex(a, b) => write!(f, "({}{:+}j)", float_str(*a), b),
            Value::Str(s) => write!(f, "{s}"),
            Value::List(l) => {
                write!(f, "[")?;
                for (i, v) in l.borrow().iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{}", v.repr())?;
                }
                write!(f, "]")
            }
            Value::Tuple(t) => {
                write!(f, "(")?;
                for (i, v) in t.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{}", v.repr())?;
                }
                if t.len() == 1 {
                    write!(f, ",")?;
                }
                write!(f, ")")
            }
            Value::Dict(d) => {
                write!(f, "{{")?;
                for (i, e) in d.borrow().entries.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{}: {}", e.key.repr(), e.value.repr())?;
                }
                write!(f, "}}")
            }
            Value::Func(u) => write!(f, "<function {}>", u.name),
            Value::Builtin(Builtin::Fn(n)) => write!(f, "<built-in function {n}>"),
            Value::Builtin(Builtin::Factor) => write!(f, "<built-in function _F>"),
            Value::Builtin(Builtin::Co) => write!(f, "<class CO>"),
            Value::Builtin(Builtin::TestCase) => write!(f, "<class TestCase>"),
            Value::Builtin(Builtin::TestCaseObject) => write!(f, "<TestCase object>"),
            Value::Method(_, m) => write!(f, "<method {m}>"),
            Value::Command(c) => write!(f, "<command {c}>"),
            Value::Concept(c) | Value::Formula(c, _) => write!(f, "{}", c.name),
            Value::Co(n) => write!(f, "CO('{n}')"),
            Value::Module(m) => write!(f, "<module '{m}'>"),
            Value::Unknown => write!(f, "<run-time value>"),
        }
    }
}
