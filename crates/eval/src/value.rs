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

/// The items of a list or tuple (a `Vec<Value>`; dropping a structure
/// nested deeper than the stack allows is bounded: see [`deep_drop`]).
#[derive(Clone, Debug, Default)]
pub struct Items(pub Vec<Value>);

impl std::ops::Deref for Items {
    type Target = Vec<Value>;
    fn deref(&self) -> &Vec<Value> {
        &self.0
    }
}

impl std::ops::DerefMut for Items {
    fn deref_mut(&mut self) -> &mut Vec<Value> {
        &mut self.0
    }
}

impl Drop for Items {
    fn drop(&mut self) {
        if !self.0.is_empty() {
            deep_drop::values(std::mem::take(&mut self.0));
        }
    }
}

impl Drop for Dict {
    fn drop(&mut self) {
        if !self.entries.is_empty() {
            let entries = std::mem::take(&mut self.entries);
            deep_drop::values(entries.into_iter().flat_map(|e| [e.key, e.value]).collect());
        }
    }
}

impl Drop for UserFunc {
    fn drop(&mut self) {
        // Defaults and closures can chain functions (`g = lambda g=g: g`
        // in a loop).
        let mut held: Vec<Value> = std::mem::take(&mut self.defaults)
            .into_iter()
            .flatten()
            .collect();
        held.extend(std::mem::take(&mut self.closure).into_values());
        if !held.is_empty() {
            deep_drop::values(held);
        }
    }
}

/// Dropping nested values with bounded recursion: the usual nested drop
/// up to a fixed depth, deeper containers queued and dropped by the loop of
/// the outermost drop (a list nested a million deep frees without
/// exhausting the stack; Python's "trashcan" does the same).
pub mod deep_drop {
    use super::Value;
    use std::cell::{Cell, RefCell};

    const NESTING: u32 = 200;

    thread_local! {
        static DEPTH: Cell<u32> = const { Cell::new(0) };
        static DEFERRED: RefCell<Vec<Vec<Value>>> = const { RefCell::new(Vec::new()) };
    }

    pub fn values(v: Vec<Value>) {
        let depth = DEPTH.with(|d| d.get());
        if depth >= NESTING {
            DEFERRED.with(|q| q.borrow_mut().push(v));
            return;
        }
        DEPTH.with(|d| d.set(depth + 1));
        drop(v);
        if depth == 0 {
            while let Some(next) = DEFERRED.with(|q| q.borrow_mut().pop()) {
                drop(next);
            }
        }
        DEPTH.with(|d| d.set(depth));
    }
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

/// An error a command raised, as `except CA.AsterError as err` binds it:
/// `err.id_message` is code_aster's message id, `str(err)` the message.
#[derive(Debug, PartialEq)]
pub struct RaisedError {
    pub id_message: String,
    pub message: String,
}

#[derive(Clone, Debug)]
pub enum Value {
    None,
    Bool(bool),
    Int(i64),
    /// An integer beyond `i64` (see `int`): never one that fits an `Int`.
    Big(Rc<num_bigint::BigInt>),
    Float(f64),
    Complex(f64, f64),
    Str(Rc<str>),
    List(Rc<RefCell<Items>>),
    Tuple(Rc<Items>),
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
    /// A caught error of a command (`except CA.AsterError as err`).
    Raised(Rc<RaisedError>),
    /// code_aster's Table object (`TAB.EXTR_TABLE()`, see `table`).
    Table(Rc<crate::table::TableObj>),
    /// A column of a table (`t['DX']`, `t.DX`).
    Column(Rc<crate::table::ColumnObj>),
}

impl Value {
    pub fn str(s: &str) -> Value {
        Value::Str(Rc::from(s))
    }
    pub fn list(v: Vec<Value>) -> Value {
        Value::List(Rc::new(RefCell::new(Items(v))))
    }
    pub fn tuple(v: Vec<Value>) -> Value {
        Value::Tuple(Rc::new(Items(v)))
    }

    pub fn type_name(&self) -> &'static str {
        match self {
            Value::None => "NoneType",
            Value::Bool(_) => "bool",
            Value::Int(_) | Value::Big(_) => "int",
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
            Value::Raised(_) => "AsterError",
            Value::Table(_) => "Table",
            Value::Column(_) => "Colonne",
        }
    }

    pub fn truthy(&self) -> Option<bool> {
        Some(match self {
            Value::None => false,
            Value::Bool(b) => *b,
            Value::Int(i) => *i != 0,
            Value::Big(_) => true,
            Value::Float(f) => *f != 0.0,
            Value::Complex(a, b) => *a != 0.0 || *b != 0.0,
            Value::Str(s) => !s.is_empty(),
            Value::List(l) => !l.borrow().is_empty(),
            Value::Tuple(t) => !t.is_empty(),
            Value::Dict(d) => !d.borrow().entries.is_empty(),
            Value::Unknown => return None,
            Value::Table(t) => return t.len().map(|n| n > 0),
            // An attribute of a concept (`contact.hasFriction`, a property
            // in code_aster): known only when the commands run.
            Value::Method(r, _) if matches!(**r, Value::Concept(_) | Value::Formula(..)) => {
                return None
            }
            _ => true,
        })
    }

    /// The value as a float; a big integer beyond the float range is
    /// infinite here (arithmetic refuses it: see `builtins::binop`).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Bool(b) => Some(*b as i64 as f64),
            Value::Int(i) => Some(*i as f64),
            Value::Big(b) => Some(num_traits::ToPrimitive::to_f64(&**b).unwrap_or(
                if num_traits::Signed::is_negative(&**b) {
                    f64::NEG_INFINITY
                } else {
                    f64::INFINITY
                },
            )),
            Value::Float(f) => Some(*f),
            _ => None,
        }
    }

    /// Python's `==`. Containers compare their items with Python's
    /// identity shortcut (`a == a` is true for a list that contains
    /// itself); comparing two different structures nested deeper than the
    /// evaluator's depth limit stops there and marks the comparison as
    /// failed ([`guard::take_overflow`]), as Python raises `RecursionError`.
    pub fn py_eq(&self, other: &Value) -> bool {
        match (self, other) {
            (Value::List(a), Value::List(b)) if Rc::ptr_eq(a, b) => return true,
            (Value::Tuple(a), Value::Tuple(b)) if Rc::ptr_eq(a, b) => return true,
            (Value::Dict(a), Value::Dict(b)) if Rc::ptr_eq(a, b) => return true,
            (Value::List(_) | Value::Tuple(_) | Value::Dict(_), _) => {
                let Some(_level) = guard::enter() else {
                    return false;
                };
                return self.py_eq_items(other);
            }
            _ => {}
        }
        self.py_eq_items(other)
    }

    fn py_eq_items(&self, other: &Value) -> bool {
        match (self, other) {
            (Value::Str(a), Value::Str(b)) => a == b,
            (Value::Int(a), Value::Int(b)) => a == b,
            (Value::Big(a), Value::Big(b)) => a == b,
            (Value::Big(_), Value::Int(_) | Value::Bool(_))
            | (Value::Int(_) | Value::Bool(_), Value::Big(_)) => false,
            (Value::Int(_) | Value::Big(_), Value::Float(f)) => crate::int::big(self)
                .and_then(|a| crate::int::cmp_float(&a, *f))
                .is_some_and(|o| o.is_eq()),
            (Value::Float(f), Value::Int(_) | Value::Big(_)) => crate::int::big(other)
                .and_then(|a| crate::int::cmp_float(&a, *f))
                .is_some_and(|o| o.is_eq()),
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

    /// Python's `repr`, or an error when the value is nested deeper than
    /// the evaluator's depth limit (Python's `RecursionError`); a container
    /// that contains itself prints as `[...]`, as in Python.
    pub fn try_repr(&self) -> Result<String, String> {
        let s = self.repr();
        guard::check()?;
        Ok(s)
    }

    /// Python's `str`, with the errors of [`Value::try_repr`].
    pub fn try_str(&self) -> Result<String, String> {
        let s = self.to_string();
        guard::check()?;
        Ok(s)
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
            Value::Big(b) => write!(f, "{b}"),
            Value::Float(x) => write!(f, "{}", float_str(*x)),
            Value::Complex(a, b) => write!(f, "({}{:+}j)", float_str(*a), b),
            Value::Str(s) => write!(f, "{s}"),
            Value::List(l) => {
                let Some(_level) = guard::enter_repr(Rc::as_ptr(l) as *const ()) else {
                    return write!(f, "[...]");
                };
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
                let Some(_level) = guard::enter_repr(Rc::as_ptr(t) as *const ()) else {
                    return write!(f, "(...)");
                };
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
                let Some(_level) = guard::enter_repr(Rc::as_ptr(d) as *const ()) else {
                    return write!(f, "{{...}}");
                };
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
            Value::Raised(e) => write!(f, "{}", e.message),
            Value::Table(t) => write!(f, "{}", t.text),
            Value::Column(c) => write!(f, "<column {} of a table>", c.name),
        }
    }
}

/// Recursion over values (printing, comparing): nested containers are
/// bounded by the evaluator's depth limit, and a container met again while
/// it is being printed prints as `[...]` (Python's `Py_ReprEnter`).
pub mod guard {
    use crate::limits::MAX_EVAL_DEPTH;
    use std::cell::{Cell, RefCell};

    thread_local! {
        static DEPTH: Cell<usize> = const { Cell::new(0) };
        static OVERFLOW: Cell<bool> = const { Cell::new(false) };
        static PRINTING: RefCell<Vec<*const ()>> = const { RefCell::new(Vec::new()) };
    }

    /// One level of recursion; leaves it when dropped.
    pub struct Level {
        printing: bool,
    }

    impl Drop for Level {
        fn drop(&mut self) {
            DEPTH.with(|d| d.set(d.get().saturating_sub(1)));
            if self.printing {
                PRINTING.with(|p| p.borrow_mut().pop());
            }
        }
    }

    /// Enters one level; `None` (and the overflow mark) past the limit.
    pub fn enter() -> Option<Level> {
        let depth = DEPTH.with(|d| d.get());
        if depth >= MAX_EVAL_DEPTH {
            OVERFLOW.with(|o| o.set(true));
            return None;
        }
        DEPTH.with(|d| d.set(depth + 1));
        Some(Level { printing: false })
    }

    /// Enters the printing of container `ptr`; `None` when it is already
    /// being printed (a cycle) or past the depth limit.
    pub fn enter_repr(ptr: *const ()) -> Option<Level> {
        if PRINTING.with(|p| p.borrow().contains(&ptr)) {
            return None;
        }
        let mut level = enter()?;
        PRINTING.with(|p| p.borrow_mut().push(ptr));
        level.printing = true;
        Some(level)
    }

    /// Whether a recursion went past the limit since the last call (and
    /// clears the mark).
    pub fn take_overflow() -> bool {
        OVERFLOW.with(|o| o.replace(false))
    }

    /// `Err` with Python's message when a recursion went past the limit.
    pub fn check() -> Result<(), String> {
        if take_overflow() {
            return Err(format!(
                "maximum recursion depth exceeded (values nested more than {MAX_EVAL_DEPTH} deep)"
            ));
        }
        Ok(())
    }
}
