//! `FORMULE`: a Python expression of named parameters, kept with the values
//! it refers to and evaluated later (by the runner) with the same evaluator.

use crate::interp::Interp;
use crate::value::Value;
use crate::{CommandCall, CommandOutput, CommandSink, ConceptRef, ExecError};
use aster_syntax::{ast, CodeMap};
use std::collections::HashMap;
use std::rc::Rc;

/// A compiled formula.
#[derive(Debug)]
pub struct Formula {
    /// The parameter names (`NOM_PARA`), in order.
    pub params: Vec<String>,
    /// The expression as written in `VALE`.
    pub source: String,
    pub(crate) expr: ast::Expr,
    /// The names the expression can see: the program's globals when the
    /// formula was defined, plus the extra keyword arguments of `FORMULE`.
    pub(crate) context: HashMap<String, Value>,
    pub(crate) map: Rc<CodeMap>,
}

/// A formula evaluation never executes commands.
struct NoCommands;

impl CommandSink for NoCommands {
    fn execute(&mut self, call: &CommandCall) -> Result<CommandOutput, ExecError> {
        Err(ExecError::new(format!(
            "a formula cannot run the command {}",
            call.command
        )))
    }
}

impl Formula {
    /// Evaluates the formula for real parameter values given in the order of
    /// [`Formula::params`].
    pub fn eval(&self, args: &[f64]) -> Result<f64, String> {
        self.eval_in(args, &mut NoCommands)
    }

    /// The concepts the expression can see (the function concepts it may
    /// call, `F(INST)`).
    pub fn concepts(&self) -> Vec<ConceptRef> {
        self.context
            .values()
            .filter_map(|v| match v {
                Value::Concept(c) => Some(c.clone()),
                _ => None,
            })
            .collect()
    }

    /// [`Formula::eval`] with a sink that answers the calls of concepts
    /// (`F(INST)` of a function concept is `sink.method(F, "__call__", …)`);
    /// no command can run.
    pub fn eval_in(&self, args: &[f64], sink: &mut dyn CommandSink) -> Result<f64, String> {
        let vals: Vec<Value> = args.iter().map(|a| Value::Float(*a)).collect();
        match self.call_in(&vals, sink)? {
            Value::Int(i) => Ok(i as f64),
            big @ Value::Big(_) => match big.as_f64() {
                Some(f) if f.is_finite() => Ok(f),
                _ => Err(format!(
                    "formula `{}` gave an integer too large for a real",
                    self.source
                )),
            },
            Value::Float(f) => Ok(f),
            Value::Bool(b) => Ok(b as i64 as f64),
            other => Err(format!(
                "formula `{}` gave {} instead of a real",
                self.source,
                other.type_name()
            )),
        }
    }

    /// Evaluates the formula with named parameters (any order).
    pub fn eval_named(&self, args: &[(&str, f64)]) -> Result<f64, String> {
        self.eval_named_in(args, &mut NoCommands)
    }

    /// [`Formula::eval_named`] with a sink for the calls of concepts.
    pub fn eval_named_in(
        &self,
        args: &[(&str, f64)],
        sink: &mut dyn CommandSink,
    ) -> Result<f64, String> {
        let mut ordered = Vec::with_capacity(self.params.len());
        for p in &self.params {
            let v = args
                .iter()
                .find(|(n, _)| n == p)
                .map(|(_, v)| *v)
                .ok_or_else(|| format!("formula `{}`: parameter {p} not given", self.source))?;
            ordered.push(v);
        }
        self.eval_in(&ordered, sink)
    }

    pub(crate) fn call_in(
        &self,
        args: &[Value],
        sink: &mut dyn CommandSink,
    ) -> Result<Value, String> {
        if args.len() != self.params.len() {
            return Err(format!(
                "formula `{}` takes {} parameter(s) ({}), {} given",
                self.source,
                self.params.len(),
                self.params.join(", "),
                args.len()
            ));
        }
        let mut interp = Interp::for_formula(&self.map, sink, self.context.clone());
        let mut locals = HashMap::new();
        for (p, a) in self.params.iter().zip(args) {
            locals.insert(p.clone(), a.clone());
        }
        interp
            .eval_with_locals(&self.expr, locals)
            .map_err(|d| format!("formula `{}`: {}", self.source, d.message))
    }
}
