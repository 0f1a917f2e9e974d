//! Building command calls by hand, to drive the executor without the
//! parser and evaluator.
#![allow(dead_code)]

use aster_eval::{CommandCall, ConceptRef, Keyword, Keywords, KwValue, Scalar};
use aster_syntax::Span;

pub enum V {
    R(f64),
    I(i64),
    S(&'static str),
    C(ConceptRef),
    L(Vec<V>),
    F(Vec<Vec<(&'static str, V)>>),
}

fn scalar(v: V) -> Vec<Scalar> {
    match v {
        V::R(r) => vec![Scalar::Real(r)],
        V::I(i) => vec![Scalar::Int(i)],
        V::S(s) => vec![Scalar::Str(s.to_string())],
        V::C(c) => vec![Scalar::Concept(c)],
        V::L(l) => l.into_iter().flat_map(scalar).collect(),
        V::F(_) => panic!("factor inside a simple keyword"),
    }
}

pub fn kws(entries: Vec<(&'static str, V)>) -> Keywords {
    Keywords {
        entries: entries
            .into_iter()
            .map(|(name, v)| Keyword {
                name: name.to_string(),
                value: match v {
                    V::F(occs) => KwValue::Factor(occs.into_iter().map(kws).collect()),
                    other => KwValue::Simple(scalar(other)),
                },
                span: Span::default(),
                defaulted: false,
            })
            .collect(),
    }
}

/// Creates concepts with unique ids.
#[derive(Default)]
pub struct Program {
    next: u32,
}

impl Program {
    pub fn concept(&mut self, name: &str, typ: &str) -> ConceptRef {
        self.next += 1;
        ConceptRef {
            name: name.to_string(),
            id: self.next,
            typ: typ.to_string(),
        }
    }
}

pub fn call(
    command: &str,
    result: Option<&ConceptRef>,
    entries: Vec<(&'static str, V)>,
) -> CommandCall {
    CommandCall {
        command: command.to_string(),
        result: result.cloned(),
        reuse: None,
        keywords: kws(entries),
        span: Span::default(),
    }
}

pub fn reuse(command: &str, target: &ConceptRef, entries: Vec<(&'static str, V)>) -> CommandCall {
    CommandCall {
        command: command.to_string(),
        result: Some(target.clone()),
        reuse: Some(target.clone()),
        keywords: kws(entries),
        span: Span::default(),
    }
}

/// A writer shared with the test, to read the report back.
#[derive(Clone, Default)]
pub struct Shared(pub std::rc::Rc<std::cell::RefCell<Vec<u8>>>);

impl std::io::Write for Shared {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Shared {
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.0.borrow()).into_owned()
    }
}

/// The run's report, kept to be read after the run.
#[derive(Clone, Default)]
pub struct Report(pub std::rc::Rc<std::cell::RefCell<Vec<u8>>>);

impl std::io::Write for Report {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Report {
    /// What the run wrote.
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.0.borrow()).into_owned()
    }
}
