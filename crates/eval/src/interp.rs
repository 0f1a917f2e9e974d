//! The evaluator of the Python subset: statements, expressions, user
//! functions, and command calls (validated, then handed to the sink).

use crate::builtins;
use crate::command::*;
use crate::diag::{did_you_mean, DiagKind, Diagnostic};
use crate::format;
use crate::formula::Formula;
use crate::limits::{MAX_CALL_DEPTH, MAX_EVAL_DEPTH, STEP_BUDGET, STR_BYTES_PER_STEP};
use crate::value::*;
use aster_catalog::catalog;
use aster_syntax::ast::{self, ArgKind, BinOp, CmpOp, ExprKind, StmtKind, UnaryOp};
use aster_syntax::{CodeMap, Span};
use std::collections::{HashMap, HashSet};
use std::rc::Rc;

/// Why evaluation stopped early.
#[derive(Debug)]
pub(crate) enum Halt {
    /// An error not yet recorded.
    Diag(Box<Diagnostic>),
    /// Errors already recorded in the diagnostics.
    Reported,
}

impl From<Diagnostic> for Halt {
    fn from(d: Diagnostic) -> Halt {
        Halt::Diag(Box::new(d))
    }
}

pub(crate) type R<T> = Result<T, Halt>;

pub(crate) fn err<T>(kind: DiagKind, span: Span, msg: impl Into<String>) -> R<T> {
    Err(Diagnostic::error(kind, span, msg).into())
}

pub(crate) fn unsupported<T>(span: Span, what: impl std::fmt::Display) -> R<T> {
    err(
        DiagKind::NotSupported,
        span,
        format!("not supported: {what}"),
    )
}

/// Why a code_aster callable imported from a module is not executed, when
/// it is known. (code_aster 17's `DEFI_CONT`, imported from
/// `code_aster.MacroCommands.defi_cont`, is a catalog command: the import
/// binds it.)
fn module_call_why(_path: &str) -> &'static str {
    ""
}

/// A step checking cannot take: it needs a value known only at run time.
pub(crate) fn needs_run_time<T>(span: Span, what: impl std::fmt::Display) -> R<T> {
    err(
        DiagKind::RunTimeValue,
        span,
        format!("not supported: {what}"),
    )
}

pub(crate) fn py_err<T>(span: Span, msg: impl Into<String>) -> R<T> {
    err(DiagKind::Python, span, msg)
}

enum Flow {
    Normal,
    Break,
    Continue,
    Return(Value),
}

#[derive(Default)]
struct Frame {
    vars: HashMap<String, Value>,
    globals: HashSet<String>,
}

/// An evaluated call argument.
pub(crate) struct CallArg {
    pub name: Option<(String, Span)>,
    pub value: Value,
    pub span: Span,
}

pub(crate) struct Interp<'a> {
    pub map: &'a CodeMap,
    pub sink: &'a mut dyn CommandSink,
    pub globals: HashMap<String, Value>,
    frames: Vec<Frame>,
    pub diags: Vec<Diagnostic>,
    pub next_id: u32,
    pub keep_going: bool,
    pub finished: bool,
    /// After `POURSUITE`, names not defined here are concepts of the
    /// previous run (of a type the checker cannot know).
    pub continued: bool,
    pub commands: usize,
    /// The program was written for an older code_aster (11–15): legacy
    /// spellings that code_aster 17 dropped are translated.
    pub legacy: bool,
    /// User function calls in progress (see [`MAX_CALL_DEPTH`]).
    depth: usize,
    /// Several command files and their Python modules (see `study`).
    pub study: crate::study::StudyState<'a>,
    /// Nested evaluation levels in progress (see [`MAX_EVAL_DEPTH`]).
    nesting: usize,
    /// Steps spent from the program's [`STEP_BUDGET`].
    steps: std::cell::Cell<u64>,
    /// The loops in progress (where, and what), innermost last: the one a
    /// spent budget is blamed on.
    loops: Vec<(Span, &'static str)>,
    /// What failed statements left unknown while checking (`recover`).
    pub(crate) recovery: crate::recover::Recovery,
    /// Validations shared between the two passes of `aster run` (`memo`).
    pub(crate) memo: Option<&'a mut crate::memo::ValidationMemo>,
    /// `os.environ` once read (`os_module`): assignments stay in it.
    pub(crate) environ: Option<Value>,
}

impl<'a> Interp<'a> {
    pub fn new(map: &'a CodeMap, sink: &'a mut dyn CommandSink, keep_going: bool) -> Interp<'a> {
        Interp {
            map,
            sink,
            globals: HashMap::new(),
            frames: Vec::new(),
            diags: Vec::new(),
            next_id: 1,
            keep_going,
            finished: false,
            continued: false,
            commands: 0,
            legacy: false,
            depth: 0,
            study: crate::study::StudyState::default(),
            nesting: 0,
            steps: std::cell::Cell::new(0),
            loops: Vec::new(),
            recovery: Default::default(),
            memo: None,
            environ: None,
        }
    }

    /// Spends `n` steps of the program's budget on `what` (at `span`):
    /// an error naming it when the budget runs out.
    /// Inside a loop, the innermost loop is named instead.
    pub(crate) fn charge(&self, n: u64, span: Span, what: &str) -> R<()> {
        let used = self.steps.get().saturating_add(n);
        self.steps.set(used);
        if used > STEP_BUDGET {
            let (span, what) = match self.loops.last() {
                Some((loop_span, kind)) => (*loop_span, format!("this {kind}")),
                None => (span, what.to_string()),
            };
            return py_err(
                span,
                format!(
                    "{what} runs too long: the program used up its budget of {STEP_BUDGET} evaluation steps (loop turns, calls, items built)"
                ),
            );
        }
        Ok(())
    }

    /// Spends the cost of building `v` (its items, or its text by
    /// [`STR_BYTES_PER_STEP`]) on `what`.
    pub(crate) fn charge_value(&self, v: &Value, span: Span, what: &str) -> R<()> {
        let n = match v {
            Value::List(l) => l.borrow().len() as u64,
            Value::Tuple(t) => t.len() as u64,
            Value::Dict(d) => d.borrow().entries.len() as u64,
            Value::Str(s) => (s.len() / STR_BYTES_PER_STEP) as u64,
            _ => return Ok(()),
        };
        if n > 0 {
            self.charge(n, span, what)?;
        }
        Ok(())
    }

    pub fn for_formula(
        map: &'a CodeMap,
        sink: &'a mut dyn CommandSink,
        globals: HashMap<String, Value>,
    ) -> Interp<'a> {
        let mut i = Interp::new(map, sink, false);
        i.globals = globals;
        i
    }

    pub fn eval_with_locals(
        &mut self,
        e: &ast::Expr,
        locals: HashMap<String, Value>,
    ) -> Result<Value, Diagnostic> {
        self.frames.push(Frame {
            vars: locals,
            globals: HashSet::new(),
        });
        let r = self.eval(e);
        self.frames.pop();
        r.map_err(|h| match h {
            Halt::Diag(d) => *d,
            Halt::Reported => self.diags.last().cloned().unwrap_or_else(|| {
                Diagnostic::error(DiagKind::Python, e.span, "evaluation failed")
            }),
        })
    }

    // ---------- statements ----------

    /// Runs a command file's statements. The checker (`keep_going`) goes on
    /// after a recoverable error in a statement (see `recover`).
    pub fn run_module(&mut self, m: &ast::Module) -> R<()> {
        if !self.keep_going {
            self.exec_block(&m.body)?;
            return Ok(());
        }
        for s in &m.body {
            if self.finished {
                break;
            }
            let before = self.diags.len();
            let text = self.map.snippet(s.span);
            let hits = self.recovery.unknown_names_read.get();
            let mentions = self.recovery.is_consequence(text);
            let r = self.exec(s);
            let consequence = mentions || self.recovery.unknown_names_read.get() > hits;
            match r {
                Ok(Flow::Normal) => {}
                Ok(Flow::Return(_) | Flow::Break | Flow::Continue) => break,
                Err(Halt::Diag(d))
                    if crate::recover::recoverable(&d) && self.steps.get() <= STEP_BUDGET =>
                {
                    if !consequence && !self.recovery.undefined_name_explained(&d) {
                        self.diags.push(*d);
                    }
                    self.recover_from(s, text);
                    continue;
                }
                Err(e) => return Err(e),
            }
            // A statement that uses what a failed one left unknown: its
            // errors recorded without stopping (a command's keywords) are
            // consequences, and what it binds or touches is derived from
            // unknowns in turn.
            if consequence {
                if self.diags[before..].iter().any(Diagnostic::is_error) {
                    self.diags.truncate(before);
                }
                let mut bound = Vec::new();
                crate::recover::bound_names(s, &mut bound);
                let defined = |w: &str| self.globals.contains_key(w);
                self.recovery.derived(text, bound, defined);
            }
        }
        Ok(())
    }

    /// After `s` failed while checking: what it would have bound becomes
    /// unknown (`recover`).
    fn recover_from(&mut self, s: &ast::Stmt, text: &str) {
        let mut bound = Vec::new();
        crate::recover::bound_names(s, &mut bound);
        for n in &bound {
            self.set_var(n, Value::Unknown);
        }
        let defined = |w: &str| self.globals.contains_key(w);
        self.recovery.failed(s, text, bound, defined);
    }

    /// `try` whose handlers all catch ImportError (see `try_import`);
    /// any other `try` is outside the subset.
    fn exec_try(
        &mut self,
        span: Span,
        body: &[ast::Stmt],
        handlers: &[ast::ExceptHandler],
        orelse: &[ast::Stmt],
        finalbody: &[ast::Stmt],
    ) -> R<Flow> {
        use crate::try_import::*;
        if handlers.iter().any(catches_aster_error) {
            return self.exec_try_aster_error(span, body, handlers, orelse, finalbody);
        }
        if let [h] = handlers {
            if catches_any_exception(h) && h.name.is_none() {
                return self.exec_try_any(body, h, orelse, finalbody);
            }
        }
        if handlers.is_empty() || !handlers.iter().all(catches_only_import_error) {
            return unsupported(
                span,
                "try/except (only `except ImportError` around imports is supported)",
            );
        }
        let imported = imported_paths(body);
        let flow = match self.exec_block(body) {
            Ok(Flow::Normal) => self.exec_block(orelse),
            Ok(other) => Ok(other),
            Err(Halt::Diag(d)) if is_missing_module(&d, &imported) => {
                self.diags.push(Diagnostic::warning(
                    DiagKind::NotSupported,
                    d.span,
                    format!(
                        "{} raises ImportError here: checking the `except ImportError` branch",
                        d.message.trim_start_matches("not supported: ")
                    ),
                ));
                let h = &handlers[0];
                if let Some(n) = &h.name {
                    self.set_var(&n.name, Value::None);
                }
                self.exec_block(&h.body)
            }
            Err(e) => Err(e),
        };
        self.then_finally(flow, finalbody)
    }

    /// `try: … except CA.AsterError as err: …` (every handler catching
    /// code_aster's errors): an error a command of the body raises is
    /// caught when aster knows the message id code_aster raises for it
    /// ([`ExecError::id_message`]); the handler then sees `err.id_message`
    /// and `str(err)`. Any other error stops the program as it would
    /// without the `try`, saying that its id is not known, since the
    /// handler's decision (which tests the id) cannot be reproduced.
    fn exec_try_aster_error(
        &mut self,
        span: Span,
        body: &[ast::Stmt],
        handlers: &[ast::ExceptHandler],
        orelse: &[ast::Stmt],
        finalbody: &[ast::Stmt],
    ) -> R<Flow> {
        use crate::try_import::catches_aster_error;
        if !handlers.iter().all(catches_aster_error) {
            return unsupported(
                span,
                "try/except mixing code_aster's errors with other exceptions (only `except CA.AsterError as err` handlers, or only `except ImportError` around imports, are supported)",
            );
        }
        // Checking executes no command: whether one raises, and with which
        // id, is known only when the program runs. The body is checked; an
        // error found there may be the one the program expects (it is not
        // reported as the file's), and what the handlers assign is a
        // run-time value.
        if self.keep_going {
            let diags_before = self.diags.len();
            let body_flow = self.exec_block(body);
            let found = self.diags[diags_before..].iter().any(Diagnostic::is_error);
            if found || matches!(body_flow, Err(Halt::Diag(_) | Halt::Reported)) {
                let kept: Vec<Diagnostic> = self
                    .diags
                    .drain(diags_before..)
                    .filter(|d| !d.is_error())
                    .collect();
                self.diags.extend(kept);
                return needs_run_time(
                    span,
                    "checking `try: … except CA.AsterError` around a command with an error: the program may expect it (which error a command raises is known only when the commands run)",
                );
            }
            let mut names = Vec::new();
            for h in handlers {
                assigned_names(&h.body, &mut names);
            }
            for n in names {
                self.set_var(&n, Value::Unknown);
            }
            body_flow?;
            return self
                .exec_block(orelse)
                .and_then(|flow| match self.exec_block(finalbody)? {
                    Flow::Normal => Ok(flow),
                    other => Ok(other),
                });
        }
        let flow = match self.exec_block(body) {
            Ok(Flow::Normal) => self.exec_block(orelse),
            Ok(other) => Ok(other),
            Err(Halt::Diag(d)) if d.kind == DiagKind::Exec && d.id_message.is_some() => {
                let id = d.id_message.unwrap_or_default();
                let h = &handlers[0];
                if let Some(n) = &h.name {
                    let raised = crate::value::RaisedError {
                        id_message: id.to_string(),
                        message: d.message.clone(),
                    };
                    self.set_var(&n.name, Value::Raised(Rc::new(raised)));
                }
                self.exec_block(&h.body)
            }
            Err(Halt::Diag(d)) if d.kind == DiagKind::Exec => Err(Halt::Diag(Box::new((*d).note(
                "note: raised inside `try: … except AsterError`, which tests code_aster's message id: aster does not know the id code_aster gives this error, so the handler is not run",
            )))),
            Err(e) => Err(e),
        };
        self.then_finally(flow, finalbody)
    }

    /// A `try` statement's `finally:` block, run after the body's flow
    /// (a `return` or `break` in it replaces that flow, as in Python).
    fn then_finally(&mut self, flow: R<Flow>, finalbody: &[ast::Stmt]) -> R<Flow> {
        if finalbody.is_empty() {
            return flow;
        }
        match self.exec_block(finalbody)? {
            Flow::Normal => flow,
            other => Ok(other),
        }
    }

    /// `try: … except: …` (or `except Exception:`): a Python exception of
    /// the body (`max([])`'s ValueError, a KeyError, a division by zero)
    /// runs the handler, as Python does. What aster cannot evaluate (a
    /// construct outside the subset, a value known only at run time) and
    /// the errors of commands are not caught: the handler would hide that
    /// the program was not reproduced.
    fn exec_try_any(
        &mut self,
        body: &[ast::Stmt],
        handler: &ast::ExceptHandler,
        orelse: &[ast::Stmt],
        finalbody: &[ast::Stmt],
    ) -> R<Flow> {
        let flow = match self.exec_block(body) {
            Ok(Flow::Normal) => self.exec_block(orelse),
            Ok(other) => Ok(other),
            Err(Halt::Diag(d)) if d.kind == DiagKind::Python => self.exec_block(&handler.body),
            Err(e) => Err(e),
        };
        self.then_finally(flow, finalbody)
    }

    fn exec_block(&mut self, body: &[ast::Stmt]) -> R<Flow> {
        for s in body {
            if self.finished {
                return Ok(Flow::Normal);
            }
            match self.exec(s)? {
                Flow::Normal => {}
                other => return Ok(other),
            }
        }
        Ok(Flow::Normal)
    }

    /// Executes a statement: one level of [`MAX_EVAL_DEPTH`].
    fn exec(&mut self, s: &ast::Stmt) -> R<Flow> {
        if self.nesting >= MAX_EVAL_DEPTH {
            return self.too_deep(s.span);
        }
        self.nesting += 1;
        let r = self.exec_stmt(s);
        self.nesting -= 1;
        r
    }

    /// A `for` or `while` loop (each turn is a step of the budget).
    fn exec_loop(&mut self, s: &ast::Stmt) -> R<Flow> {
        match &s.kind {
            StmtKind::For {
                target,
                iter,
                body,
                orelse,
            } => {
                let it = self.eval(iter)?;
                let items = self.iterate(&it, iter.span)?;
                for item in items {
                    self.charge(1, s.span, "this `for` loop")?;
                    self.assign(target, item)?;
                    match self.exec_block(body)? {
                        Flow::Break => return Ok(Flow::Normal),
                        Flow::Return(v) => return Ok(Flow::Return(v)),
                        Flow::Normal | Flow::Continue => {}
                    }
                    if self.finished {
                        return Ok(Flow::Normal);
                    }
                }
                self.exec_block(orelse)
            }
            StmtKind::While { test, body, orelse } => {
                loop {
                    let t = self.eval(test)?;
                    if !self.truth(&t, test.span)? {
                        break;
                    }
                    self.charge(1, s.span, "this `while` loop")?;
                    match self.exec_block(body)? {
                        Flow::Break => return Ok(Flow::Normal),
                        Flow::Return(v) => return Ok(Flow::Return(v)),
                        Flow::Normal | Flow::Continue => {}
                    }
                    if self.finished {
                        return Ok(Flow::Normal);
                    }
                }
                self.exec_block(orelse)
            }
            _ => Ok(Flow::Normal),
        }
    }

    fn exec_stmt(&mut self, s: &ast::Stmt) -> R<Flow> {
        match &s.kind {
            StmtKind::Expr { value } => {
                self.eval(value)?;
            }
            StmtKind::Assign { targets, value } => {
                let v = match (&value.kind, targets.as_slice()) {
                    (ExprKind::Call { func, args }, [t]) => {
                        let name = match &t.kind {
                            ExprKind::Name { id } => Some(id.to_string()),
                            _ => Some(self.map.snippet(t.span).to_string()),
                        };
                        self.eval_call(func, args, value.span, name.as_deref())?
                    }
                    _ => self.eval(value)?,
                };
                for t in targets {
                    self.assign(t, v.clone())?;
                }
            }
            StmtKind::AugAssign { target, op, value } => {
                let cur = self.eval(target)?;
                let rhs = self.eval(value)?;
                let v = self.binop(*op, cur, rhs, s.span)?;
                self.assign(target, v)?;
            }
            StmtKind::AnnAssign { target, value, .. } => {
                if let Some(v) = value {
                    let v = self.eval(v)?;
                    self.assign(target, v)?;
                }
            }
            StmtKind::If { test, body, orelse } => {
                let t = self.eval(test)?;
                let b = self.truth(&t, test.span)?;
                return self.exec_block(if b { body } else { orelse });
            }
            StmtKind::For { .. } => {
                self.loops.push((s.span, "`for` loop"));
                let r = self.exec_loop(s);
                self.loops.pop();
                return r;
            }
            StmtKind::While { .. } => {
                self.loops.push((s.span, "`while` loop"));
                let r = self.exec_loop(s);
                self.loops.pop();
                return r;
            }
            StmtKind::FunctionDef {
                name,
                params,
                body,
                decorators,
            } => {
                if let Some(d) = decorators.first() {
                    return unsupported(d.span, "decorators");
                }
                let f = self.make_func(&name.name, params, FuncBody::Block(body.clone()))?;
                self.set_var(&name.name, f);
            }
            StmtKind::Return { value } => {
                let v = match value {
                    Some(v) => self.eval(v)?,
                    None => Value::None,
                };
                return Ok(Flow::Return(v));
            }
            StmtKind::Import { names } => {
                for a in names {
                    let bind = |n: &str| n.split('.').next().unwrap_or(n).to_string();
                    if self.study.has_module(&a.name) {
                        self.load_module(&a.name, a.span)?;
                    } else if module_kind(&a.name).is_none() {
                        return Err(
                            self.missing_module(a.span, format!("import of module `{}`", a.name))
                        );
                    }
                    match &a.asname {
                        Some(as_) => {
                            self.set_var(&as_.name, Value::Module(Rc::from(a.name.as_str())))
                        }
                        None => {
                            let top = bind(&a.name);
                            self.set_var(&top, Value::Module(Rc::from(top.as_str())))
                        }
                    }
                }
            }
            StmtKind::ImportFrom {
                module,
                level,
                names,
                star,
            } => {
                let m = module.clone().unwrap_or_default();
                if *level > 0 {
                    return unsupported(s.span, "relative imports");
                }
                if self.study.has_module(&m) {
                    self.import_from_user_module(&m, names, *star, s.span)?;
                    return Ok(Flow::Normal);
                }
                match module_kind(&m) {
                    None => {
                        return Err(self.missing_module(s.span, format!("import from module `{m}`")))
                    }
                    Some(ModuleKind::Os) => {
                        if *star {
                            return unsupported(s.span, format!("`from {m} import *`"));
                        }
                        for a in names {
                            let v = match crate::os_module::attr(&m, &a.name, &mut self.environ) {
                                Some(v) => v,
                                None => return crate::os_module::refuse(&m, &a.name, a.span),
                            };
                            let bind = bound_name(a);
                            self.set_var(&bind, v);
                        }
                    }
                    Some(ModuleKind::Re) => {
                        if *star || !names.is_empty() {
                            return unsupported(s.span, format!("import from module `{m}`"));
                        }
                    }
                    Some(ModuleKind::Math) => {
                        if *star {
                            for n in builtins::MATH_NAMES {
                                self.set_var(n, builtins::math_attr(n).unwrap_or(Value::None));
                            }
                        }
                        for a in names {
                            let v = builtins::math_attr(&a.name).ok_or(()).or_else(|_| {
                                py_err(a.span, format!("cannot import name `{}` from math", a.name))
                            })?;
                            let bind = bound_name(a);
                            self.set_var(&bind, v);
                        }
                    }
                    Some(ModuleKind::NoOp) => {
                        // code_aster.Commands / Accas: the commands and `_F`
                        // are already known; other names become opaque
                        // modules that say "not supported" when used.
                        for a in names {
                            let bind = bound_name(a);
                            let v = self.lookup_builtin(&a.name).unwrap_or_else(|| {
                                Value::Module(Rc::from(format!("{m}.{}", a.name).as_str()))
                            });
                            self.set_var(&bind, v);
                        }
                    }
                }
            }
            StmtKind::Pass => {}
            StmtKind::Break => return Ok(Flow::Break),
            StmtKind::Continue => return Ok(Flow::Continue),
            StmtKind::Global { names } => {
                if let Some(f) = self.frames.last_mut() {
                    for n in names {
                        f.globals.insert(n.name.to_string());
                    }
                }
            }
            StmtKind::Print {
                dest,
                values,
                newline: _,
            } => {
                if dest.is_some() {
                    return unsupported(s.span, "print >> file");
                }
                let mut parts = Vec::new();
                for v in values {
                    let text = self.eval(v)?.try_str().or_else(|m| py_err(v.span, m))?;
                    parts.push(text);
                }
                self.sink.print(&parts.join(" "));
            }
            StmtKind::Del { targets } => {
                for t in targets {
                    match &t.kind {
                        ExprKind::Name { id } => {
                            let removed = match self.frames.last_mut() {
                                Some(f) if !f.globals.contains(id.as_str()) => {
                                    f.vars.remove(id.as_str()).is_some()
                                }
                                _ => self.globals.remove(id.as_str()).is_some(),
                            };
                            if !removed {
                                return py_err(t.span, format!("name '{id}' is not defined"));
                            }
                        }
                        ExprKind::Subscript { value, index } => {
                            let c = self.eval(value)?;
                            let k = self.eval(index)?;
                            match c {
                                Value::Dict(d) => {
                                    d.borrow_mut().remove(&k);
                                }
                                Value::List(l) => {
                                    let n = l.borrow().len();
                                    let i = self.index_of(&k, n, t.span)?;
                                    l.borrow_mut().remove(i);
                                }
                                _ => return unsupported(t.span, "del on this value"),
                            }
                        }
                        _ => return unsupported(t.span, "del of this target"),
                    }
                }
            }
            StmtKind::Assert { test, msg } => {
                let t = self.eval(test)?;
                if !self.truth(&t, test.span)? {
                    let m = match msg {
                        Some(m) => self.eval(m)?.to_string(),
                        None => String::new(),
                    };
                    return py_err(s.span, format!("AssertionError {m}").trim_end().to_string());
                }
            }
            StmtKind::Raise { .. } => {
                return py_err(s.span, "the program raises an exception");
            }
            StmtKind::Try {
                body,
                handlers,
                orelse,
                finalbody,
            } => return self.exec_try(s.span, body, handlers, orelse, finalbody),
            StmtKind::With { .. } => return unsupported(s.span, "with statements (file access)"),
            StmtKind::ClassDef { .. } => return unsupported(s.span, "class definitions"),
            StmtKind::Nonlocal { .. } => return unsupported(s.span, "nonlocal"),
            StmtKind::Exec { .. } => return unsupported(s.span, "exec"),
        }
        Ok(Flow::Normal)
    }

    /// After a macro created `CO('name')`, variables still holding that
    /// `CO` object now refer to the concept.
    pub fn resolve_co(&mut self, c: &ConceptRef) {
        let fix = |v: &mut Value| {
            if matches!(v, Value::Co(n) if **n == *c.name) {
                *v = Value::Concept(c.clone());
            }
        };
        let fix_deep = |v: &mut Value| match v {
            Value::List(l) => l.borrow_mut().iter_mut().for_each(fix),
            Value::Dict(d) => d
                .borrow_mut()
                .entries
                .iter_mut()
                .for_each(|e| fix(&mut e.value)),
            other => fix(other),
        };
        self.globals.values_mut().for_each(fix_deep);
        for f in self.frames.iter_mut() {
            f.vars.values_mut().for_each(fix_deep);
        }
    }

    fn make_func(&mut self, name: &str, params: &[ast::Param], body: FuncBody) -> R<Value> {
        let mut defaults = Vec::new();
        for p in params {
            defaults.push(match &p.default {
                Some(d) => Some(self.eval(d)?),
                None => None,
            });
        }
        let closure = self
            .frames
            .last()
            .map(|f| f.vars.clone())
            .unwrap_or_default();
        Ok(Value::Func(Rc::new(UserFunc {
            name: name.to_string(),
            params: params.to_vec(),
            defaults,
            body,
            closure,
            module: self.study.current.clone(),
        })))
    }

    pub fn set_var(&mut self, name: &str, v: Value) {
        match self.frames.last_mut() {
            Some(f) if !f.globals.contains(name) => {
                f.vars.insert(name.to_string(), v);
            }
            _ => {
                self.globals.insert(name.to_string(), v);
            }
        }
    }

    fn assign(&mut self, t: &ast::Expr, v: Value) -> R<()> {
        match &t.kind {
            ExprKind::Name { id } => {
                self.set_var(id, v);
                Ok(())
            }
            ExprKind::Tuple { elts } | ExprKind::List { elts } => {
                let items = self.iterate(&v, t.span)?;
                let star = elts
                    .iter()
                    .position(|e| matches!(e.kind, ExprKind::Starred { .. }));
                match star {
                    None => {
                        if items.len() != elts.len() {
                            return py_err(
                                t.span,
                                format!(
                                    "cannot unpack {} values into {} targets",
                                    items.len(),
                                    elts.len()
                                ),
                            );
                        }
                        for (e, i) in elts.iter().zip(items) {
                            self.assign(e, i)?;
                        }
                    }
                    Some(k) => {
                        let after = elts.len() - k - 1;
                        if items.len() < elts.len() - 1 {
                            return py_err(t.span, "not enough values to unpack");
                        }
                        for (e, i) in elts[..k].iter().zip(items.iter()) {
                            self.assign(e, i.clone())?;
                        }
                        let mid = items[k..items.len() - after].to_vec();
                        if let ExprKind::Starred { value } = &elts[k].kind {
                            self.assign(value, Value::list(mid))?;
                        }
                        for (e, i) in elts[k + 1..]
                            .iter()
                            .zip(items[items.len() - after..].iter())
                        {
                            self.assign(e, i.clone())?;
                        }
                    }
                }
                Ok(())
            }
            ExprKind::Subscript { value, index } => {
                let c = self.eval(value)?;
                let k = self.eval(index)?;
                match c {
                    Value::List(l) => {
                        let n = l.borrow().len();
                        let i = self.index_of(&k, n, index.span)?;
                        l.borrow_mut()[i] = v;
                        Ok(())
                    }
                    Value::Dict(d) => {
                        if matches!(k, Value::List(_) | Value::Dict(_)) {
                            return py_err(index.span, "unhashable key");
                        }
                        d.borrow_mut().insert(k, v, t.span);
                        Ok(())
                    }
                    other => py_err(
                        t.span,
                        format!("'{}' does not support item assignment", other.type_name()),
                    ),
                }
            }
            ExprKind::Attribute { .. } => unsupported(t.span, "assignment to an attribute"),
            _ => py_err(t.span, "cannot assign to this expression"),
        }
    }

    // ---------- expressions ----------

    fn lookup_builtin(&self, name: &str) -> Option<Value> {
        match name {
            "_F" => Some(Value::Builtin(Builtin::Factor)),
            "CO" => Some(Value::Builtin(Builtin::Co)),
            // code_aster runs command files with `math` names and `CA` in scope.
            "CA" => Some(Value::Module(Rc::from("code_aster.CA"))),
            _ => {
                if let Some(b) = builtins::builtin(name) {
                    return Some(b);
                }
                if let Some(c) = catalog().command(name) {
                    return Some(Value::Command(Rc::from(c.name)));
                }
                // code_aster 17 keeps `POURSUITE` as `DEBUT(MODE='POURSUITE')`.
                if name == "POURSUITE" {
                    return Some(Value::Command(Rc::from("POURSUITE")));
                }
                if self.legacy && crate::legacy_commands::replacement(name).is_some() {
                    return Some(Value::Command(Rc::from(name)));
                }
                // Python 2's lazy range: the same values for a loop.
                if self.legacy && name == "xrange" {
                    return builtins::builtin("range");
                }
                builtins::math_attr(name)
            }
        }
    }

    fn lookup(&self, name: &str, span: Span) -> R<Value> {
        if let Some(f) = self.frames.last() {
            if let Some(v) = f.vars.get(name) {
                return Ok(v.clone());
            }
        }
        if let Some(v) = self.globals.get(name) {
            return Ok(v.clone());
        }
        if let Some(v) = self.lookup_builtin(name) {
            return Ok(v);
        }
        if name == "__name__" {
            return Ok(Value::str(
                self.study.current.as_deref().unwrap_or("__main__"),
            ));
        }
        if name == "VARIABLE" {
            // code_aster 17 puts it in scope beside the catalog's commands.
            return unsupported(
                span,
                "VARIABLE (a parameter of a parametric study, read from the inputs.pick file code_aster's study tools write)",
            );
        }
        if self.recovery.undefined_is_unknown(name) {
            self.recovery
                .unknown_names_read
                .set(self.recovery.unknown_names_read.get() + 1);
            return Ok(Value::Unknown);
        }
        if self.continued {
            return Ok(Value::Concept(ConceptRef {
                name: name.to_string(),
                id: 0,
                typ: aster_catalog::types::UNKNOWN.to_string(),
            }));
        }
        let looks_like_command = name.len() > 2
            && name
                .chars()
                .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_');
        let mut names: Vec<&str> = self.globals.keys().map(|s| s.as_str()).collect();
        if let Some(f) = self.frames.last() {
            names.extend(f.vars.keys().map(|s| s.as_str()));
        }
        if looks_like_command {
            names.extend(catalog().names());
        }
        let mut d = Diagnostic::error(
            DiagKind::Python,
            span,
            format!("name `{name}` is not defined"),
        );
        if let Some(h) = did_you_mean(name, names) {
            d = d.note(h);
        }
        Err(d.into())
    }

    pub fn truth(&self, v: &Value, span: Span) -> R<bool> {
        match v.truthy() {
            Some(b) => Ok(b),
            None => needs_run_time(
                span,
                "a condition on a value known only when the commands run (checking does not execute them)",
            ),
        }
    }

    /// Evaluates an expression: one level of [`MAX_EVAL_DEPTH`].
    pub fn eval(&mut self, e: &ast::Expr) -> R<Value> {
        if self.nesting >= MAX_EVAL_DEPTH {
            return self.too_deep(e.span);
        }
        self.nesting += 1;
        let r = self.eval_expr(e);
        self.nesting -= 1;
        r
    }

    fn too_deep<T>(&self, span: Span) -> R<T> {
        py_err(
            span,
            format!(
                "maximum recursion depth exceeded: evaluation nested more than {MAX_EVAL_DEPTH} levels (expressions, blocks and calls)"
            ),
        )
    }

    fn eval_expr(&mut self, e: &ast::Expr) -> R<Value> {
        Ok(match &e.kind {
            ExprKind::Name { id } => self.lookup(id, e.span)?,
            ExprKind::Int { value } => Value::Int(*value),
            ExprKind::Float { value } => Value::Float(*value),
            ExprKind::Imag { value } => Value::Complex(0.0, *value),
            ExprKind::Str { value } => Value::str(value),
            ExprKind::Bool { value } => Value::Bool(*value),
            ExprKind::None => Value::None,
            ExprKind::FString { parts } => {
                let v = Value::str(&self.fstring(parts)?);
                self.charge_value(&v, e.span, "this f-string")?;
                v
            }
            ExprKind::List { elts } => Value::list(self.eval_elts(elts)?),
            ExprKind::Tuple { elts } => Value::tuple(self.eval_elts(elts)?),
            ExprKind::Set { elts } => {
                let mut out: Vec<Value> = Vec::new();
                for v in self.eval_elts(elts)? {
                    if !out.iter().any(|x| x.py_eq(&v)) {
                        out.push(v);
                    }
                }
                Value::list(out)
            }
            ExprKind::Dict { items } => {
                let mut d = Dict::default();
                for it in items {
                    let v = self.eval(&it.value)?;
                    match &it.key {
                        Some(k) => {
                            let kv = self.eval(k)?;
                            d.insert(kv, v, k.span);
                        }
                        None => match v {
                            Value::Dict(src) => {
                                for en in src.borrow().entries.iter() {
                                    d.insert(en.key.clone(), en.value.clone(), en.span);
                                }
                            }
                            other => {
                                return py_err(
                                    it.value.span,
                                    format!("cannot unpack {} with **", other.type_name()),
                                )
                            }
                        },
                    }
                }
                Value::Dict(Rc::new(std::cell::RefCell::new(d)))
            }
            ExprKind::Attribute { value, attr } => {
                let v = self.eval(value)?;
                self.attribute(v, &attr.name, attr.span)?
            }
            ExprKind::Subscript { value, index } => {
                let v = self.eval(value)?;
                if let ExprKind::Slice { lower, upper, step } = &index.kind {
                    let lo = lower.as_ref().map(|x| self.eval(x)).transpose()?;
                    let hi = upper.as_ref().map(|x| self.eval(x)).transpose()?;
                    let st = step.as_ref().map(|x| self.eval(x)).transpose()?;
                    return builtins::slice(&v, lo, hi, st, e.span);
                }
                if matches!(v, Value::Unknown) {
                    // `m[0:n, 0:n]` of a run-time matrix.
                    return Ok(Value::Unknown);
                }
                let k = self.eval(index)?;
                self.subscript(v, k, e.span)?
            }
            ExprKind::Slice { .. } => return py_err(e.span, "slice outside a subscript"),
            ExprKind::Call { func, args } => self.eval_call(func, args, e.span, None)?,
            ExprKind::BinOp { left, op, right } => {
                let l = self.eval(left)?;
                let r = self.eval(right)?;
                self.binop(*op, l, r, e.span)?
            }
            ExprKind::UnaryOp { op, operand } => {
                let v = self.eval(operand)?;
                match (op, v) {
                    (UnaryOp::Not, v) => match v.truthy() {
                        Some(b) => Value::Bool(!b),
                        None => Value::Unknown,
                    },
                    (_, Value::Unknown) => Value::Unknown,
                    (UnaryOp::Neg, v @ (Value::Int(_) | Value::Bool(_) | Value::Big(_))) => {
                        crate::int::neg(&v)
                    }
                    (UnaryOp::Neg, Value::Float(f)) => Value::Float(-f),
                    (UnaryOp::Neg, Value::Complex(a, b)) => Value::Complex(-a, -b),
                    (UnaryOp::Pos, Value::Bool(b)) => Value::Int(b as i64),
                    (
                        UnaryOp::Pos,
                        v @ (Value::Int(_) | Value::Big(_) | Value::Float(_) | Value::Complex(..)),
                    ) => v,
                    (UnaryOp::Invert, v @ (Value::Int(_) | Value::Bool(_) | Value::Big(_))) => {
                        crate::int::invert(&v)
                    }
                    (_, v) => {
                        return py_err(
                            e.span,
                            format!("bad operand type for unary operator: '{}'", v.type_name()),
                        )
                    }
                }
            }
            ExprKind::BoolOp { op, values } => {
                let mut last = Value::None;
                for (i, x) in values.iter().enumerate() {
                    last = self.eval(x)?;
                    if i + 1 == values.len() {
                        break;
                    }
                    let Some(t) = last.truthy() else {
                        return Ok(Value::Unknown);
                    };
                    match op {
                        ast::BoolOp::And if !t => return Ok(last),
                        ast::BoolOp::Or if t => return Ok(last),
                        _ => {}
                    }
                }
                last
            }
            ExprKind::Compare { left, ops } => {
                let mut l = self.eval(left)?;
                for (op, r) in ops {
                    let rv = self.eval(r)?;
                    match self.compare(*op, &l, &rv, e.span)? {
                        Some(true) => {}
                        Some(false) => return Ok(Value::Bool(false)),
                        None => return Ok(Value::Unknown),
                    }
                    l = rv;
                }
                Value::Bool(true)
            }
            ExprKind::IfExp { test, body, orelse } => {
                let t = self.eval(test)?;
                if self.truth(&t, test.span)? {
                    self.eval(body)?
                } else {
                    self.eval(orelse)?
                }
            }
            ExprKind::Lambda { params, body } => {
                self.make_func("<lambda>", params, FuncBody::Lambda((**body).clone()))?
            }
            ExprKind::ListComp { elt, generators }
            | ExprKind::SetComp { elt, generators }
            | ExprKind::GeneratorExp { elt, generators } => {
                let mut out = Vec::new();
                self.comprehension(e.span, generators, &mut |me| {
                    out.push(me.eval(elt)?);
                    Ok(())
                })?;
                if matches!(e.kind, ExprKind::SetComp { .. }) {
                    let mut uniq: Vec<Value> = Vec::new();
                    for v in out {
                        if !uniq.iter().any(|x| x.py_eq(&v)) {
                            uniq.push(v);
                        }
                    }
                    out = uniq;
                }
                Value::list(out)
            }
            ExprKind::DictComp {
                key,
                value,
                generators,
            } => {
                let mut d = Dict::default();
                self.comprehension(e.span, generators, &mut |me| {
                    let k = me.eval(key)?;
                    let v = me.eval(value)?;
                    d.insert(k, v, key.span);
                    Ok(())
                })?;
                Value::Dict(Rc::new(std::cell::RefCell::new(d)))
            }
            ExprKind::Starred { .. } => return py_err(e.span, "starred expression here"),
            ExprKind::NamedExpr { target, value } => {
                let v = self.eval(value)?;
                self.set_var(&target.name, v.clone());
                v
            }
            ExprKind::Repr { value } => Value::str(
                &self
                    .eval(value)?
                    .try_repr()
                    .or_else(|m| py_err(e.span, m))?,
            ),
            ExprKind::Bytes { .. } => return unsupported(e.span, "bytes literals"),
            ExprKind::Ellipsis => return unsupported(e.span, "`...`"),
            ExprKind::Yield { .. } | ExprKind::YieldFrom { .. } => {
                return unsupported(e.span, "generators (yield)")
            }
            ExprKind::Await { .. } => return unsupported(e.span, "await"),
        })
    }

    fn eval_elts(&mut self, elts: &[ast::Expr]) -> R<Vec<Value>> {
        let mut out = Vec::with_capacity(elts.len());
        for x in elts {
            if let ExprKind::Starred { value } = &x.kind {
                let v = self.eval(value)?;
                out.extend(self.iterate(&v, value.span)?);
            } else {
                out.push(self.eval(x)?);
            }
        }
        Ok(out)
    }

    fn comprehension(
        &mut self,
        span: Span,
        gens: &[ast::Comprehension],
        body: &mut dyn FnMut(&mut Interp<'a>) -> R<()>,
    ) -> R<()> {
        // A comprehension has its own scope that sees the enclosing one.
        let vars = self
            .frames
            .last()
            .map(|f| f.vars.clone())
            .unwrap_or_default();
        let globals = self
            .frames
            .last()
            .map(|f| f.globals.clone())
            .unwrap_or_default();
        self.frames.push(Frame { vars, globals });
        self.loops.push((span, "comprehension"));
        let r = self.comp_level(gens, body);
        self.loops.pop();
        self.frames.pop();
        r
    }

    fn comp_level(
        &mut self,
        gens: &[ast::Comprehension],
        body: &mut dyn FnMut(&mut Interp<'a>) -> R<()>,
    ) -> R<()> {
        let Some((g, rest)) = gens.split_first() else {
            return body(self);
        };
        let it = self.eval(&g.iter)?;
        for item in self.iterate(&it, g.iter.span)? {
            self.charge(1, g.iter.span, "this comprehension")?;
            self.assign(&g.target, item)?;
            let mut keep = true;
            for cond in &g.ifs {
                let c = self.eval(cond)?;
                if !self.truth(&c, cond.span)? {
                    keep = false;
                    break;
                }
            }
            if keep {
                self.comp_level(rest, body)?;
            }
        }
        Ok(())
    }

    fn fstring(&mut self, parts: &[ast::FStringPart]) -> R<String> {
        let mut out = String::new();
        for p in parts {
            match p {
                ast::FStringPart::Literal { value } => out.push_str(value),
                ast::FStringPart::Field {
                    value,
                    conversion,
                    format_spec,
                    debug,
                } => {
                    let v = self.eval(value)?;
                    if *debug {
                        out.push_str(self.map.snippet(value.span));
                        out.push('=');
                    }
                    let v = match conversion {
                        Some('r') | Some('a') => {
                            Value::str(&v.try_repr().or_else(|m| py_err(value.span, m))?)
                        }
                        Some('s') => Value::str(&v.try_str().or_else(|m| py_err(value.span, m))?),
                        _ => v,
                    };
                    let spec = self.fstring(format_spec)?;
                    out.push_str(
                        &format::format_spec(&v, &spec).or_else(|m| py_err(value.span, m))?,
                    );
                    if out.len() > crate::limits::MAX_STR_BYTES {
                        return py_err(
                            value.span,
                            crate::limits::too_large(
                                out.len() as u128,
                                crate::limits::MAX_STR_BYTES,
                                "characters",
                            ),
                        );
                    }
                }
            }
        }
        Ok(out)
    }

    /// The items of an iterable, materialized: their number is charged to
    /// the step budget before they are copied.
    pub fn iterate(&self, v: &Value, span: Span) -> R<Vec<Value>> {
        let n = match v {
            Value::List(l) => l.borrow().len(),
            Value::Tuple(t) => t.len(),
            Value::Str(s) => s.len(),
            Value::Dict(d) => d.borrow().entries.len(),
            _ => 0,
        };
        if n > 0 {
            self.charge(n as u64, span, "this iteration")?;
        }
        Ok(match v {
            Value::List(l) => l.borrow().to_vec(),
            Value::Tuple(t) => t.to_vec(),
            Value::Str(s) => s.chars().map(|c| Value::str(&c.to_string())).collect(),
            Value::Dict(d) => d.borrow().entries.iter().map(|e| e.key.clone()).collect(),
            Value::Table(_) | Value::Column(_) => crate::table::iterate(v, span)?,
            Value::Unknown => {
                return needs_run_time(
                    span,
                    "iterating over a value known only when the commands run",
                )
            }
            other => {
                return py_err(
                    span,
                    format!("'{}' object is not iterable", other.type_name()),
                )
            }
        })
    }

    pub fn index_of(&self, k: &Value, n: usize, span: Span) -> R<usize> {
        let i = match k {
            Value::Int(i) => *i,
            Value::Bool(b) => *b as i64,
            Value::Big(_) => {
                return py_err(span, format!("index {k} out of range (length {n})"));
            }
            other => {
                return py_err(
                    span,
                    format!("indices must be integers, not {}", other.type_name()),
                )
            }
        };
        let j = if i < 0 { n as i64 + i } else { i };
        if j < 0 || j >= n as i64 {
            return py_err(span, format!("index {i} out of range (length {n})"));
        }
        Ok(j as usize)
    }

    fn subscript(&mut self, v: Value, k: Value, span: Span) -> R<Value> {
        Ok(match (&v, &k) {
            (Value::Unknown, _) | (_, Value::Unknown) => Value::Unknown,
            (Value::List(l), _) => {
                let l = l.borrow();
                l[self.index_of(&k, l.len(), span)?].clone()
            }
            (Value::Tuple(t), _) => t[self.index_of(&k, t.len(), span)?].clone(),
            (Value::Str(s), _) => {
                let chars: Vec<char> = s.chars().collect();
                Value::str(&chars[self.index_of(&k, chars.len(), span)?].to_string())
            }
            (Value::Dict(d), _) => match d.borrow().get(&k) {
                Some(v) => v.clone(),
                None => return py_err(span, format!("KeyError: {}", k.repr())),
            },
            (Value::Table(t), _) => crate::table::subscript(t, &k, span)?,
            (Value::Column(c), _) => match c.table.len() {
                None => Value::Unknown,
                Some(n) => {
                    let i = self.index_of(&k, n, span)?;
                    crate::table::column_item(c, i).unwrap_or(Value::Unknown)
                }
            },
            (Value::Concept(c), _) => {
                let key = match &k {
                    Value::Tuple(t) => t.iter().map(to_host).collect(),
                    other => vec![to_host(other)],
                };
                match self.sink.index(c, &key) {
                    Ok(h) => from_host(h),
                    Err(e) => return Err(exec_diag(span, e).into()),
                }
            }
            _ => {
                return py_err(
                    span,
                    format!("'{}' object is not subscriptable", v.type_name()),
                )
            }
        })
    }

    pub(crate) fn attribute(&mut self, v: Value, name: &str, span: Span) -> R<Value> {
        match &v {
            Value::Module(m) if &**m == "math" => builtins::math_attr(name)
                .ok_or(())
                .or_else(|_| py_err(span, format!("module 'math' has no attribute '{name}'"))),
            Value::Module(m) if &**m == "code_aster.CA" && name == "TestCase" => {
                Ok(Value::Builtin(Builtin::TestCase))
            }
            Value::Module(m) if m.starts_with("code_aster") || m.starts_with("Accas") => {
                match self.lookup_builtin(name) {
                    Some(b) => Ok(b),
                    None => unsupported(span, format!("`{m}.{name}`")),
                }
            }
            Value::Module(m) if self.study.is_loaded(m) => self.module_attr(m, name, span),
            Value::Module(m) if crate::os_module::is_os(m) => {
                match crate::os_module::attr(m, name, &mut self.environ) {
                    Some(v) => Ok(v),
                    None => crate::os_module::refuse(m, name, span),
                }
            }
            Value::Module(m) => unsupported(span, format!("`{m}.{name}`")),
            Value::Complex(a, b) => match name {
                "real" => Ok(Value::Float(*a)),
                "imag" => Ok(Value::Float(*b)),
                _ => Ok(Value::Method(Box::new(v.clone()), Rc::from(name))),
            },
            Value::Unknown => Ok(Value::Unknown),
            Value::Table(t) => crate::table::attribute(t, name, span),
            Value::Column(_) if name == "values" => {
                Ok(Value::Method(Box::new(v.clone()), Rc::from(name)))
            }
            Value::Column(c) => unsupported(
                span,
                format!("`.{}.{name}` of code_aster's Table object (a column gives its values())", c.name),
            ),
            Value::Raised(e) => match name {
                "id_message" => Ok(Value::str(&e.id_message)),
                "message" => Ok(Value::str(&e.message)),
                _ => unsupported(
                    span,
                    format!("`{name}` of a caught code_aster error (`id_message` and `message` are known)"),
                ),
            },
            _ => Ok(Value::Method(Box::new(v), Rc::from(name))),
        }
    }

    pub fn eval_call(
        &mut self,
        func: &ast::Expr,
        args: &[ast::Arg],
        span: Span,
        target: Option<&str>,
    ) -> R<Value> {
        let f = match &func.kind {
            ExprKind::Name { id } => match self.lookup(id, func.span) {
                Ok(v) => v,
                Err(Halt::Diag(d))
                    if d.kind == DiagKind::Python
                        && id.len() > 2
                        && id
                            .chars()
                            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_') =>
                {
                    if let Some(why) = self
                        .legacy
                        .then(|| crate::legacy_commands::removed_after_v11(id))
                        .flatten()
                    {
                        return Err(Diagnostic::error(
                            DiagKind::NotSupported,
                            func.span,
                            format!("not supported: `{id}` (code_aster 11): {why}"),
                        )
                        .into());
                    }
                    let mut nd = Diagnostic::error(
                        DiagKind::UnknownCommand,
                        func.span,
                        format!("`{id}` is not a code_aster 17 command"),
                    );
                    nd.notes = d.notes;
                    if let Some(n) = crate::legacy::removed_command(id) {
                        nd = nd.note(n);
                    }
                    return Err(nd.into());
                }
                Err(e) => return Err(e),
            },
            _ => self.eval(func)?,
        };
        let mut cargs = Vec::with_capacity(args.len());
        for a in args {
            match &a.kind {
                ArgKind::Positional { value } => cargs.push(CallArg {
                    name: None,
                    value: self.eval(value)?,
                    span: a.span,
                }),
                ArgKind::Keyword { name, value } => cargs.push(CallArg {
                    name: Some((name.name.to_string(), name.span)),
                    value: self.eval(value)?,
                    span: a.span,
                }),
                ArgKind::Star { value } => {
                    let v = self.eval(value)?;
                    for item in self.iterate(&v, value.span)? {
                        cargs.push(CallArg {
                            name: None,
                            value: item,
                            span: a.span,
                        });
                    }
                }
                ArgKind::DoubleStar { value } => match self.eval(value)? {
                    Value::Dict(d) => {
                        for en in d.borrow().entries.iter() {
                            let Value::Str(k) = &en.key else {
                                return py_err(a.span, "keywords must be strings");
                            };
                            cargs.push(CallArg {
                                name: Some((k.to_string(), a.span)),
                                value: en.value.clone(),
                                span: a.span,
                            });
                        }
                    }
                    Value::Unknown => return needs_run_time(a.span, "`**` of a run-time value"),
                    other => {
                        return py_err(
                            a.span,
                            format!(
                                "argument after ** must be a mapping, not {}",
                                other.type_name()
                            ),
                        )
                    }
                },
            }
        }
        self.call_value(f, cargs, span, target)
    }

    pub fn call_value(
        &mut self,
        f: Value,
        args: Vec<CallArg>,
        span: Span,
        target: Option<&str>,
    ) -> R<Value> {
        match f {
            Value::Command(name) => crate::commands::call_command(self, &name, args, span, target),
            Value::Builtin(Builtin::Factor) => {
                let mut d = Dict::default();
                for a in args {
                    match a.name {
                        Some((n, _)) => d.insert(Value::str(&n), a.value, a.span),
                        None => match a.value {
                            Value::Dict(src) => {
                                for en in src.borrow().entries.iter() {
                                    d.insert(en.key.clone(), en.value.clone(), en.span);
                                }
                            }
                            _ => return py_err(a.span, "_F() takes keyword arguments"),
                        },
                    }
                }
                Ok(Value::Dict(Rc::new(std::cell::RefCell::new(d))))
            }
            Value::Builtin(Builtin::Co) => match args.as_slice() {
                [CallArg {
                    name: None,
                    value: Value::Str(s),
                    ..
                }] => {
                    self.recovery.made_by_co.insert(s.to_string());
                    Ok(Value::Co(s.clone()))
                }
                _ => py_err(span, "CO() takes one name, e.g. CO('RESU')"),
            },
            Value::Builtin(Builtin::Fn(name)) => {
                let v = builtins::call(self, name, args, span)?;
                self.charge_value(&v, span, "this call")?;
                Ok(v)
            }
            Value::Builtin(Builtin::TestCase) => Ok(Value::Builtin(Builtin::TestCaseObject)),
            Value::Method(recv, m) if matches!(*recv, Value::Builtin(Builtin::TestCaseObject)) => {
                crate::testcase::call(self, &m, args, span)
            }
            Value::Func(uf) => self.call_user(&uf, args, span),
            Value::Method(recv, m) if making_of(&recv, &m).is_some() => match *recv {
                Value::Concept(c) => self.call_making(&c, &m, args, span, target),
                recv => builtins::method(self, recv, &m, args, span),
            },
            Value::Method(recv, m) => {
                let v = builtins::method(self, *recv, &m, args, span)?;
                self.charge_value(&v, span, "this call")?;
                Ok(v)
            }
            Value::Formula(c, formula) => {
                let mut vals = Vec::new();
                for a in args {
                    if a.value.as_f64().is_none() && !matches!(a.value, Value::Complex(..)) {
                        if matches!(a.value, Value::Unknown) {
                            return Ok(Value::Unknown);
                        }
                        return py_err(a.span, format!("formula {} takes numbers", c.name));
                    }
                    vals.push(a.value);
                }
                // The function concepts it calls (`F(INST)`, a nappe
                // `N(AMOR, FREQ)`) are answered by this program's sink.
                formula
                    .call_in(&vals, &mut *self.sink)
                    .or_else(|m| py_err(span, m))
            }
            Value::Unknown => Ok(Value::Unknown),
            // A function concept is callable: `F(0.5)` evaluates it.
            Value::Concept(c) => {
                let hv: Vec<HostValue> = args.iter().map(|a| to_host(&a.value)).collect();
                match self.sink.method(&c, "__call__", &hv) {
                    Ok(h) => Ok(from_host(h)),
                    Err(e) => Err(exec_diag(span, e).into()),
                }
            }
            Value::Module(m) => unsupported(span, format!("calling `{m}`{}", module_call_why(&m))),
            other => py_err(
                span,
                format!("'{}' object is not callable", other.type_name()),
            ),
        }
    }

    /// A concept-making method (`mesh.refine(2)`, [`MAKING_METHODS`]): the
    /// arguments bound to its parameters as Python binds them, a new concept
    /// (named after the assignment's target), made by the sink.
    fn call_making(
        &mut self,
        c: &ConceptRef,
        m: &str,
        args: Vec<CallArg>,
        span: Span,
        target: Option<&str>,
    ) -> R<Value> {
        let Some(how) = making_method(&c.typ, m) else {
            return py_err(span, format!("'{}' object has no attribute '{m}'", c.typ));
        };
        let mut bound: Vec<(&'static str, Option<HostValue>)> =
            how.params.iter().map(|(n, _)| (*n, None)).collect();
        let mut positional = 0;
        for a in &args {
            let slot = match &a.name {
                None => {
                    positional += 1;
                    match bound.get_mut(positional - 1) {
                        Some(slot) => slot,
                        None => {
                            return py_err(
                                a.span,
                                format!(
                                    "{m}() takes at most {} positional argument(s)",
                                    how.params.len()
                                ),
                            )
                        }
                    }
                }
                Some((n, at)) => match bound.iter_mut().find(|(p, _)| p == n) {
                    Some(slot) => slot,
                    None => {
                        return py_err(
                            *at,
                            format!("{m}() got an unexpected keyword argument '{n}'"),
                        )
                    }
                },
            };
            if slot.1.is_some() {
                return py_err(
                    a.span,
                    format!("{m}() got multiple values for argument '{}'", slot.0),
                );
            }
            slot.1 = Some(to_host(&a.value));
        }
        let bound: Vec<(&'static str, HostValue)> = bound
            .into_iter()
            .zip(how.params)
            .map(|((n, v), (_, d))| (n, v.unwrap_or(HostValue::Scalar(Scalar::Int(*d)))))
            .collect();
        let id = self.next_id;
        self.next_id += 1;
        let result = ConceptRef {
            name: target
                .map(str::to_string)
                .unwrap_or_else(|| format!("_{m}_{id}")),
            id,
            typ: how.result.to_string(),
        };
        match self.sink.make(c, how.name, &bound, &result) {
            Ok(()) => Ok(Value::Concept(result)),
            Err(e) => Err(exec_diag(span, e).into()),
        }
    }

    fn call_user(&mut self, f: &Rc<UserFunc>, args: Vec<CallArg>, span: Span) -> R<Value> {
        if self.depth >= MAX_CALL_DEPTH {
            return py_err(
                span,
                format!("maximum recursion depth exceeded: more than {MAX_CALL_DEPTH} calls inside one another"),
            );
        }
        self.charge(1, span, "this call")?;
        let mut frame = Frame {
            vars: f.closure.clone(),
            globals: HashSet::new(),
        };
        let mut positional: Vec<Value> = Vec::new();
        let mut keywords: Vec<(String, Value, Span)> = Vec::new();
        for a in args {
            match a.name {
                Some((n, _)) => keywords.push((n, a.value, a.span)),
                None => positional.push(a.value),
            }
        }
        let mut pos = positional.into_iter();
        let mut varargs_name = None;
        let mut kwargs_name = None;
        let mut after_star = false;
        for (p, dflt) in f.params.iter().zip(&f.defaults) {
            match p.kind {
                ast::ParamKind::VarArgs => {
                    varargs_name = Some(p.name.name.clone());
                    after_star = true;
                }
                ast::ParamKind::KwArgs => kwargs_name = Some(p.name.name.clone()),
                ast::ParamKind::KwOnlyMarker => after_star = true,
                ast::ParamKind::PosOnlyMarker => {}
                ast::ParamKind::Normal => {
                    let name = &p.name.name;
                    let v = if let Some(i) = keywords.iter().position(|(k, _, _)| k == name) {
                        keywords.remove(i).1
                    } else if let (false, Some(v)) = (after_star, pos.next()) {
                        v
                    } else if let Some(d) = dflt {
                        d.clone()
                    } else {
                        return py_err(span, format!("{}() missing argument '{name}'", f.name));
                    };
                    frame.vars.insert(name.to_string(), v);
                }
            }
        }
        let rest: Vec<Value> = pos.collect();
        match varargs_name {
            Some(n) => {
                frame.vars.insert(n.to_string(), Value::tuple(rest));
            }
            None if !rest.is_empty() => {
                return py_err(
                    span,
                    format!("{}() takes fewer positional arguments", f.name),
                )
            }
            None => {}
        }
        match kwargs_name {
            Some(n) => {
                let mut d = Dict::default();
                for (k, v, s) in keywords {
                    d.insert(Value::str(&k), v, s);
                }
                frame.vars.insert(
                    n.to_string(),
                    Value::Dict(Rc::new(std::cell::RefCell::new(d))),
                );
            }
            None => {
                if let Some((k, _, s)) = keywords.first() {
                    return py_err(
                        *s,
                        format!("{}() got an unexpected keyword argument '{k}'", f.name),
                    );
                }
            }
        }
        // A function of a module sees that module's globals.
        let home = self.enter_namespace(f.module.clone(), span)?;
        self.frames.push(frame);
        self.depth += 1;
        let r = match &f.body {
            FuncBody::Block(body) => self.exec_block(body).map(|fl| match fl {
                Flow::Return(v) => v,
                _ => Value::None,
            }),
            FuncBody::Lambda(e) => self.eval(e),
        };
        self.depth -= 1;
        self.frames.pop();
        self.leave_namespace(home);
        r
    }

    pub fn binop(&mut self, op: BinOp, l: Value, r: Value, span: Span) -> R<Value> {
        // Fields and functions support arithmetic in code_aster: the sink
        // decides (the checker answers "known at run time").
        if let Value::Concept(c) = &l {
            let m = format!("__{}__", format!("{op:?}").to_lowercase());
            return match self.sink.method(c, &m, &[to_host(&r)]) {
                Ok(h) => Ok(from_host(h)),
                Err(e) => Err(exec_diag(span, e).into()),
            };
        }
        if let Value::Concept(c) = &r {
            let m = format!("__r{}__", format!("{op:?}").to_lowercase());
            return match self.sink.method(c, &m, &[to_host(&l)]) {
                Ok(h) => Ok(from_host(h)),
                Err(e) => Err(exec_diag(span, e).into()),
            };
        }
        let v = builtins::binop(op, l, r).or_else(|m| py_err(span, m))?;
        if matches!(op, BinOp::Add | BinOp::Mul | BinOp::Mod) {
            self.charge_value(&v, span, "this operation")?;
        }
        Ok(v)
    }

    /// `None` when the answer depends on a run-time value.
    fn compare(&mut self, op: CmpOp, l: &Value, r: &Value, span: Span) -> R<Option<bool>> {
        if matches!(l, Value::Column(_))
            || (matches!(r, Value::Column(_)) && !matches!(op, CmpOp::In | CmpOp::NotIn))
        {
            return crate::table::refuse_comparison(span);
        }
        if matches!(l, Value::Unknown) || matches!(r, Value::Unknown) {
            return Ok(None);
        }
        let eq = |a: &Value, b: &Value| -> R<bool> {
            let e = a.py_eq(b);
            crate::value::guard::check().or_else(|m| py_err(span, m))?;
            Ok(e)
        };
        Ok(Some(match op {
            CmpOp::Eq => eq(l, r)?,
            CmpOp::NotEq => !eq(l, r)?,
            CmpOp::Is => l.py_eq(r) && l.type_name() == r.type_name(),
            CmpOp::IsNot => !(l.py_eq(r) && l.type_name() == r.type_name()),
            CmpOp::In | CmpOp::NotIn => {
                let found = match r {
                    Value::Str(s) => match l {
                        Value::Str(x) => s.contains(&**x),
                        _ => return py_err(span, "'in <string>' requires a string"),
                    },
                    Value::Dict(d) => d.borrow().get(l).is_some(),
                    other => self.iterate(other, span)?.iter().any(|x| x.py_eq(l)),
                };
                found == (op == CmpOp::In)
            }
            _ => {
                let o = builtins::order(l, r).or_else(|m| py_err(span, m))?;
                match op {
                    CmpOp::Lt => o.is_lt(),
                    CmpOp::LtE => o.is_le(),
                    CmpOp::Gt => o.is_gt(),
                    _ => o.is_ge(),
                }
            }
        }))
    }
}

/// The name `from m import a [as b]` binds.
fn bound_name(a: &ast::Alias) -> String {
    a.asname
        .as_ref()
        .map(|i| i.name.to_string())
        .unwrap_or_else(|| a.name.clone())
}

#[derive(Clone, Copy)]
enum ModuleKind {
    Math,
    NoOp,
    /// `re`, `numpy`: the import is accepted; their functions are refused
    /// where used (a study that imports numpy without using it runs).
    Re,
    /// `os`, `os.path`: environment and path arithmetic (`os_module`).
    Os,
}

fn module_kind(m: &str) -> Option<ModuleKind> {
    if m == "math" {
        return Some(ModuleKind::Math);
    }
    if m == "re" || m == "numpy" {
        return Some(ModuleKind::Re);
    }
    if crate::os_module::is_os(m) {
        return Some(ModuleKind::Os);
    }
    let top = m.split('.').next().unwrap_or(m);
    match top {
        "code_aster" | "Accas" | "Cata" => Some(ModuleKind::NoOp),
        _ => None,
    }
}

/// The concept-making method `m` of a receiver ([`MAKING_METHODS`]).
fn making_of(recv: &Value, m: &str) -> Option<&'static MakingMethod> {
    match recv {
        Value::Concept(c) => making_method(&c.typ, m),
        _ => None,
    }
}

pub(crate) fn to_host(v: &Value) -> HostValue {
    match v {
        Value::None => HostValue::None,
        Value::Bool(b) => HostValue::Scalar(Scalar::Int(*b as i64)),
        Value::Int(i) => HostValue::Scalar(Scalar::Int(*i)),
        // code_aster converts an integer given for a real with `float()`.
        Value::Big(_) => match v.as_f64() {
            Some(f) if f.is_finite() => HostValue::Scalar(Scalar::Real(f)),
            _ => HostValue::Scalar(Scalar::Opaque(v.to_string())),
        },
        Value::Float(f) => HostValue::Scalar(Scalar::Real(*f)),
        Value::Complex(a, b) => HostValue::Scalar(Scalar::Complex(*a, *b)),
        Value::Str(s) => HostValue::Scalar(Scalar::Str(s.to_string())),
        Value::Concept(c) | Value::Formula(c, _) => HostValue::Scalar(Scalar::Concept(c.clone())),
        Value::List(l) => HostValue::List(l.borrow().iter().map(to_host).collect()),
        Value::Tuple(t) => HostValue::List(t.iter().map(to_host).collect()),
        Value::Dict(d) => HostValue::Dict(
            d.borrow()
                .entries
                .iter()
                .map(|e| (e.key.to_string(), to_host(&e.value)))
                .collect(),
        ),
        Value::Unknown => HostValue::Unknown,
        other => HostValue::Scalar(Scalar::Opaque(other.to_string())),
    }
}

pub(crate) fn from_scalar(s: Scalar) -> Value {
    match s {
        Scalar::Int(i) => Value::Int(i),
        Scalar::Real(r) => Value::Float(r),
        Scalar::Complex(a, b) => Value::Complex(a, b),
        Scalar::Str(s) => Value::str(&s),
        Scalar::Concept(c) => Value::Concept(c),
        Scalar::Opaque(_) => Value::Unknown,
    }
}

pub(crate) fn from_host(h: HostValue) -> Value {
    match h {
        HostValue::None => Value::None,
        HostValue::Scalar(s) => from_scalar(s),
        HostValue::List(l) => Value::list(l.into_iter().map(from_host).collect()),
        HostValue::Dict(d) => {
            let mut out = Dict::default();
            for (k, v) in d {
                out.insert(Value::str(&k), from_host(v), Span::default());
            }
            Value::Dict(Rc::new(std::cell::RefCell::new(out)))
        }
        HostValue::Unknown => Value::Unknown,
        HostValue::Table(t) => Value::Table(Rc::new(crate::table::TableObj::from_host(t))),
    }
}

pub(crate) fn exec_diag(span: Span, e: ExecError) -> Diagnostic {
    let kind = if e.message.starts_with("not supported") {
        DiagKind::NotSupported
    } else {
        DiagKind::Exec
    };
    let mut d = Diagnostic::error(kind, span, e.message);
    d.id_message = e.id_message;
    d
}

pub(crate) fn new_formula(
    interp: &Interp,
    params: Vec<String>,
    source: &str,
    extra: Vec<(String, Value)>,
    span: Span,
) -> R<Formula> {
    // code_aster evaluates VALE as one expression: line breaks inside it
    // are continuation, not statements.
    let flat = source
        .split(['\n', '\r'])
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(" ");
    let source = flat.as_str();
    let map = Rc::new(CodeMap::new("FORMULE", source.trim().to_string()));
    let module = aster_syntax::parse_module(map.source()).map_err(|e| {
        Diagnostic::error(
            DiagKind::Python,
            span,
            format!(
                "FORMULE: VALE `{}` does not parse: {}",
                source.trim(),
                e.message
            ),
        )
    })?;
    let expr = match module.body.as_slice() {
        [ast::Stmt {
            kind: StmtKind::Expr { value },
            ..
        }] => value.clone(),
        _ => {
            return py_err(
                span,
                format!("FORMULE: VALE `{}` is not one expression", source.trim()),
            )
        }
    };
    let mut context = interp.globals.clone();
    for (k, v) in extra {
        context.insert(k, v);
    }
    Ok(Formula {
        params,
        source: source.trim().to_string(),
        expr,
        context,
        map,
    })
}

/// The plain names a block assigns (`x = …`, `x += …`, in nested `if`/`for`
/// blocks too): what a handler that may or may not run changes.
fn assigned_names(body: &[ast::Stmt], out: &mut Vec<String>) {
    use ast::{ExprKind, StmtKind};
    let target = |e: &ast::Expr, out: &mut Vec<String>| {
        if let ExprKind::Name { id } = &e.kind {
            out.push(id.to_string());
        }
    };
    for s in body {
        match &s.kind {
            StmtKind::Assign { targets, .. } => targets.iter().for_each(|t| target(t, out)),
            StmtKind::AugAssign { target: t, .. } | StmtKind::AnnAssign { target: t, .. } => {
                target(t, out)
            }
            StmtKind::If { body, orelse, .. } | StmtKind::For { body, orelse, .. } => {
                assigned_names(body, out);
                assigned_names(orelse, out);
            }
            _ => {}
        }
    }
}
