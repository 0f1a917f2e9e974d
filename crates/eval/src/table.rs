//! code_aster's `Table` object, the result of `TAB.EXTR_TABLE()`.
//!
//! As code_aster's `Objects/table_py.py`: the table's rows as dicts, its parameters, its
//! columns (`t['DX']`, `t.DX`, with `.values()`), `t.values()` (a dict of
//! columns), `len(t)`, iteration over the rows, and `print(t)` (the table's
//! `IMPR_TABLE` text). Anything else of code_aster's class (`sort`,
//! filters `t.DX > 0`, `Array`…) is refused, before solving.
//!
//! While checking (the static pass) the table's contents are not known:
//! the object is then an *unknown* table, whose supported attributes are
//! run-time values and whose other uses are refused all the same.

use crate::command::HostTable;
use crate::interp::{needs_run_time, py_err, unsupported, R};
use crate::value::{Dict, Value};
use aster_syntax::Span;
use std::cell::RefCell;
use std::rc::Rc;

/// A table extracted from a table concept.
#[derive(Debug)]
pub struct TableObj {
    /// The parameters (column names) and rows (`None`: an empty cell), or
    /// `None` while checking.
    pub data: Option<TableData>,
    /// What `print(t)` shows.
    pub text: String,
}

#[derive(Debug)]
pub struct TableData {
    pub para: Vec<String>,
    pub rows: Vec<Vec<Value>>,
}

impl TableObj {
    pub fn from_host(t: Option<HostTable>) -> TableObj {
        match t {
            None => TableObj {
                data: None,
                text: String::new(),
            },
            Some(t) => TableObj {
                data: Some(TableData {
                    para: t.para,
                    rows: t
                        .rows
                        .into_iter()
                        .map(|r| r.into_iter().map(crate::interp::from_host).collect())
                        .collect(),
                }),
                text: t.text,
            },
        }
    }

    /// Number of rows (`len(t)`); `None` while checking.
    pub fn len(&self) -> Option<usize> {
        self.data.as_ref().map(|d| d.rows.len())
    }

    /// The rows as Python dicts, every parameter present (`None` in an
    /// empty cell), as code_aster's `EXTR_TABLE` builds them.
    pub fn rows(&self) -> Option<Vec<Value>> {
        let d = self.data.as_ref()?;
        Some(
            d.rows
                .iter()
                .map(|r| {
                    let mut dict = Dict::default();
                    for (p, v) in d.para.iter().zip(r) {
                        dict.insert(Value::str(p), v.clone(), Span::default());
                    }
                    Value::Dict(Rc::new(RefCell::new(dict)))
                })
                .collect(),
        )
    }

    fn column_index(&self, name: &str) -> Option<Option<usize>> {
        self.data
            .as_ref()
            .map(|d| d.para.iter().position(|p| p == name))
    }

    /// The values of one column (`None` while checking).
    fn column(&self, k: usize) -> Option<Vec<Value>> {
        self.data
            .as_ref()
            .map(|d| d.rows.iter().map(|r| r[k].clone()).collect())
    }
}

/// A column of a table (code_aster's `Colonne`): `t['DX']`, `t.DX`.
#[derive(Debug)]
pub struct ColumnObj {
    pub table: Rc<TableObj>,
    pub name: Rc<str>,
    /// Its index among the parameters (`None` while checking).
    pub index: Option<usize>,
}

impl ColumnObj {
    fn values(&self) -> Value {
        match self.index.and_then(|k| self.table.column(k)) {
            Some(v) => Value::list(v),
            None => Value::Unknown,
        }
    }
}

/// What code_aster's table object has and aster does not reproduce.
fn refused<T>(span: Span, what: &str) -> R<T> {
    unsupported(
        span,
        format!("{what} of code_aster's Table object (the result of EXTR_TABLE()): aster gives its rows, para, columns (t['P'], t.P, .values()), values(), len() and print()"),
    )
}

/// `t.name`: `rows`, `para`, the methods aster has, or a column.
pub fn attribute(t: &Rc<TableObj>, name: &str, span: Span) -> R<Value> {
    match name {
        "rows" => Ok(t.rows().map_or(Value::Unknown, Value::list)),
        "para" => Ok(t.data.as_ref().map_or(Value::Unknown, |d| {
            Value::list(d.para.iter().map(|p| Value::str(p)).collect())
        })),
        "values" => Ok(Value::Method(
            Box::new(Value::Table(t.clone())),
            Rc::from(name),
        )),
        _ => column(t, name, span),
    }
}

/// `t['DX']` (or `t.DX`): the column, a `KeyError` when the table has no
/// such parameter.
pub fn column(t: &Rc<TableObj>, name: &str, span: Span) -> R<Value> {
    match t.column_index(name) {
        Some(None) => {
            // code_aster's `__getattr__` raises AttributeError for a name
            // that is neither an attribute nor a parameter; its many
            // methods aster does not have look the same from here.
            if name.chars().any(|c| c.is_ascii_lowercase()) {
                return refused(span, &format!("`.{name}`"));
            }
            py_err(
                span,
                format!("KeyError: the table has no parameter '{name}'"),
            )
        }
        Some(index) => Ok(Value::Column(Rc::new(ColumnObj {
            table: t.clone(),
            name: Rc::from(name),
            index,
        }))),
        // While checking: a lower-case name is one of code_aster's
        // methods (refused), an upper-case one a parameter.
        None if name.chars().any(|c| c.is_ascii_lowercase()) => {
            refused(span, &format!("`.{name}`"))
        }
        None => Ok(Value::Column(Rc::new(ColumnObj {
            table: t.clone(),
            name: Rc::from(name),
            index: None,
        }))),
    }
}

/// `t[key]`: a column by its name.
pub fn subscript(t: &Rc<TableObj>, key: &Value, span: Span) -> R<Value> {
    match key {
        Value::Str(s) => {
            let t2 = t.clone();
            match t.column_index(s) {
                Some(None) => py_err(span, format!("KeyError: the table has no parameter '{s}'")),
                index => Ok(Value::Column(Rc::new(ColumnObj {
                    table: t2,
                    name: s.clone(),
                    index: index.flatten(),
                }))),
            }
        }
        _ => refused(span, "a subscript other than a parameter name"),
    }
}

/// `col[i]`: the i-th value of a column.
pub fn column_item(c: &ColumnObj, i: usize) -> Option<Value> {
    let k = c.index?;
    c.table.data.as_ref()?.rows.get(i).map(|r| r[k].clone())
}

/// Methods of a table: `values()`, a dict of the columns in parameter
/// order.
pub fn method(t: &Rc<TableObj>, m: &str, args: &[Value], span: Span) -> R<Value> {
    match (m, args) {
        ("values", []) => {
            let Some(d) = t.data.as_ref() else {
                return Ok(Value::Unknown);
            };
            let mut dict = Dict::default();
            for (k, p) in d.para.iter().enumerate() {
                let col: Vec<Value> = d.rows.iter().map(|r| r[k].clone()).collect();
                dict.insert(Value::str(p), Value::list(col), Span::default());
            }
            Ok(Value::Dict(Rc::new(RefCell::new(dict))))
        }
        _ => refused(span, &format!("`.{m}()`")),
    }
}

/// Methods of a column: `values()`, the list of its cells.
pub fn column_method(c: &ColumnObj, m: &str, args: &[Value], span: Span) -> R<Value> {
    match (m, args) {
        ("values", []) => Ok(c.values()),
        _ => refused(span, &format!("`.{}.{m}()`", c.name)),
    }
}

/// Iterating a table gives its rows; a column, its values.
pub fn iterate(v: &Value, span: Span) -> R<Vec<Value>> {
    let items = match v {
        Value::Table(t) => t.rows(),
        Value::Column(c) => match c.values() {
            Value::List(l) => Some(l.borrow().to_vec()),
            _ => None,
        },
        _ => None,
    };
    match items {
        Some(items) => Ok(items),
        None => needs_run_time(
            span,
            "iterating over a table known only when the commands run",
        ),
    }
}

/// `len(t)`, `len(col)`: the number of rows.
pub fn len(v: &Value) -> Option<Value> {
    match v {
        Value::Table(t) => Some(t.len().map_or(Value::Unknown, |n| Value::Int(n as i64))),
        Value::Column(c) => Some(
            c.table
                .len()
                .map_or(Value::Unknown, |n| Value::Int(n as i64)),
        ),
        _ => None,
    }
}

/// Comparisons of a column (`t.DX > 0`: code_aster's filters) are not
/// reproduced.
pub fn refuse_comparison<T>(span: Span) -> R<T> {
    refused(span, "a comparison of a column (a filter)")
}
