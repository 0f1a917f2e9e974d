//! Studies: several command files run in order, and the Python modules
//! they import.
//!
//! code_aster runs the command files of an `.export` (`F comm X.comm D 1`,
//! `F comm X.com1 D 1`…) one after the other. At the end of a file, `FIN`
//! saves the Python context (code_aster's `Serializer`): every object it can
//! pickle, except modules, functions, classes and names starting with `__`;
//! `POURSUITE` in the next file restores them. So concepts, numbers,
//! strings, lists and dicts carry over; `def` functions and imports do not
//! (the next file imports again).
//!
//! A study's own Python modules (`F nom module.py D 0`) are imported by the
//! command files (`from module import *`, `import module`). A module runs
//! once per command file, in its own namespace, with the same interpreter
//! and the same "not supported" rule as command files; a function defined
//! in a module sees the module's globals when called.

use crate::diag::{DiagKind, Diagnostic};
use crate::interp::{py_err, unsupported, Halt, Interp, R};
use crate::value::Value;
use aster_syntax::{ast, Span};
use std::collections::{HashMap, HashSet};
use std::rc::Rc;

/// The name of the command files' namespace.
const MAIN: &str = "__main__";

/// What the interpreter knows of the study it runs.
#[derive(Default)]
pub struct StudyState<'a> {
    /// The study's Python modules, parsed, by module name.
    pub(crate) sources: HashMap<String, &'a ast::Module>,
    /// The file runs after another of the same study: `POURSUITE` restores
    /// the saved context (instead of assuming unknown concepts).
    pub(crate) several_files: bool,
    /// The module whose globals are the interpreter's globals (`None`: the
    /// command file).
    pub(crate) current: Option<Rc<str>>,
    /// The globals of the namespaces that are not current.
    namespaces: HashMap<String, HashMap<String, Value>>,
    /// Modules imported during the current command file.
    loaded: HashSet<String>,
    /// Modules being imported (a cycle is an error).
    loading: Vec<String>,
    /// The context the last `FIN` saved, for the next `POURSUITE`.
    saved: HashMap<String, Value>,
    /// The run was given the study's module list (an `.export`): a module
    /// it lacks is said so.
    pub(crate) declared: bool,
}

impl StudyState<'_> {
    pub(crate) fn has_module(&self, name: &str) -> bool {
        self.sources.contains_key(name)
    }

    pub(crate) fn is_loaded(&self, name: &str) -> bool {
        self.loaded.contains(name)
    }
}

/// Whether code_aster's `FIN` saves a value (`Serializer._filteringContext`
/// and pickling): modules, functions and commands are left out, and so is a
/// container holding one (it cannot be pickled).
fn saved_by_fin(v: &Value) -> bool {
    match v {
        Value::Func(_)
        | Value::Builtin(_)
        | Value::Method(..)
        | Value::Command(_)
        | Value::Module(_)
        | Value::Co(_) => false,
        Value::List(l) => l.borrow().iter().all(saved_by_fin),
        Value::Tuple(t) => t.iter().all(saved_by_fin),
        Value::Dict(d) => d
            .borrow()
            .entries
            .iter()
            .all(|e| saved_by_fin(&e.key) && saved_by_fin(&e.value)),
        _ => true,
    }
}

impl<'a> Interp<'a> {
    /// The end of a command file of a study: the context `FIN` saves, then
    /// a fresh interpreter state for the next file.
    pub(crate) fn end_command_file(&mut self) {
        let globals = std::mem::take(&mut self.globals);
        self.study.saved = globals
            .into_iter()
            .filter(|(name, v)| !name.starts_with("__") && name != "CO" && saved_by_fin(v))
            .collect();
        self.study.namespaces.clear();
        self.study.loaded.clear();
        self.study.current = None;
        self.finished = false;
    }

    /// `POURSUITE` in a later file of a study: the saved context comes back.
    pub(crate) fn restore_context(&mut self) {
        for (name, v) in std::mem::take(&mut self.study.saved) {
            self.globals.insert(name, v);
        }
    }

    /// Makes `target`'s namespace the current globals; returns the namespace
    /// to come back to (`None` when nothing changed).
    pub(crate) fn enter_namespace(
        &mut self,
        target: Option<Rc<str>>,
        span: Span,
    ) -> R<Option<Option<Rc<str>>>> {
        if target == self.study.current {
            return Ok(None);
        }
        let key = |m: &Option<Rc<str>>| m.as_deref().unwrap_or(MAIN).to_string();
        let Some(globals) = self.study.namespaces.remove(&key(&target)) else {
            return unsupported(
                span,
                format!(
                    "calling a function of `{}` from a module it imports",
                    key(&target)
                ),
            );
        };
        let previous = std::mem::replace(&mut self.globals, globals);
        self.study
            .namespaces
            .insert(key(&self.study.current), previous);
        let home = std::mem::replace(&mut self.study.current, target);
        Ok(Some(home))
    }

    /// Undoes [`Interp::enter_namespace`].
    pub(crate) fn leave_namespace(&mut self, home: Option<Option<Rc<str>>>) {
        let Some(home) = home else { return };
        let key = |m: &Option<Rc<str>>| m.as_deref().unwrap_or(MAIN).to_string();
        let globals = self
            .study
            .namespaces
            .remove(&key(&home))
            .unwrap_or_default();
        let left = std::mem::replace(&mut self.globals, globals);
        self.study.namespaces.insert(key(&self.study.current), left);
        self.study.current = home;
    }

    /// Runs a study module once (per command file), in its own namespace.
    pub(crate) fn load_module(&mut self, name: &str, span: Span) -> R<()> {
        if self.study.loaded.contains(name) {
            return Ok(());
        }
        if self.study.loading.iter().any(|m| m == name) {
            return py_err(
                span,
                format!(
                    "module `{name}` imports itself (through {})",
                    self.study.loading.join(" → ")
                ),
            );
        }
        let Some(&module) = self.study.sources.get(name) else {
            return Err(self.missing_module(span, format!("import of module `{name}`")));
        };
        self.study
            .namespaces
            .insert(name.to_string(), HashMap::new());
        self.study.loading.push(name.to_string());
        let home = self.enter_namespace(Some(Rc::from(name)), span)?;
        let legacy = std::mem::replace(
            &mut self.legacy,
            aster_syntax::dialect::generation(module).is_legacy(),
        );
        let r = self.run_module(module);
        self.legacy = legacy;
        self.leave_namespace(home);
        self.study.loading.pop();
        r?;
        self.study.loaded.insert(name.to_string());
        Ok(())
    }

    /// The globals of a loaded module (its namespace, or the interpreter's
    /// globals while it is current).
    fn module_globals(&self, name: &str) -> Option<&HashMap<String, Value>> {
        if self.study.current.as_deref() == Some(name) {
            Some(&self.globals)
        } else {
            self.study.namespaces.get(name)
        }
    }

    /// `module.name` for a study module.
    pub(crate) fn module_attr(&mut self, module: &str, name: &str, span: Span) -> R<Value> {
        match self.module_globals(module).and_then(|g| g.get(name)) {
            Some(v) => Ok(v.clone()),
            None => py_err(span, format!("module '{module}' has no attribute '{name}'")),
        }
    }

    /// `from module import a, b as c` / `from module import *`.
    pub(crate) fn import_from_user_module(
        &mut self,
        module: &str,
        names: &[ast::Alias],
        star: bool,
        span: Span,
    ) -> R<()> {
        self.load_module(module, span)?;
        let Some(globals) = self.module_globals(module) else {
            return py_err(span, format!("module `{module}` did not load"));
        };
        let mut bound: Vec<(String, Value)> = Vec::new();
        if star {
            // Python: `__all__` when the module defines it, else every name
            // not starting with `_`.
            match globals.get("__all__") {
                Some(all) => {
                    let all = self.iterate(&all.clone(), span)?;
                    let globals = self.module_globals(module).cloned().unwrap_or_default();
                    for n in all {
                        let Value::Str(n) = n else {
                            return py_err(span, format!("`{module}.__all__` holds a non-string"));
                        };
                        let Some(v) = globals.get(&*n) else {
                            return py_err(
                                span,
                                format!("module '{module}' has no attribute '{n}'"),
                            );
                        };
                        bound.push((n.to_string(), v.clone()));
                    }
                }
                None => {
                    let mut names: Vec<(&String, &Value)> = globals
                        .iter()
                        .filter(|(n, _)| !n.starts_with('_'))
                        .collect();
                    names.sort_by(|a, b| a.0.cmp(b.0));
                    bound.extend(names.into_iter().map(|(n, v)| (n.clone(), v.clone())));
                }
            }
        }
        for a in names {
            let Some(v) = globals.get(&a.name) else {
                return py_err(
                    a.span,
                    format!("cannot import name '{}' from '{module}'", a.name),
                );
            };
            let bind = a
                .asname
                .as_ref()
                .map(|i| i.name.to_string())
                .unwrap_or(a.name.clone());
            bound.push((bind, v.clone()));
        }
        for (n, v) in bound {
            self.set_var(&n, v);
        }
        Ok(())
    }

    /// "not supported: import of module `x`", with where a study's own
    /// modules come from.
    pub(crate) fn missing_module(&self, span: Span, what: String) -> Halt {
        let mut d = Diagnostic::error(
            DiagKind::NotSupported,
            span,
            format!("not supported: {what}"),
        );
        if self.study.declared {
            let mut known: Vec<&str> = self.study.sources.keys().map(String::as_str).collect();
            known.sort_unstable();
            d = d.note(format!(
                "the study's own modules are the `.export`'s `F nom <module>.py D 0` files ({})",
                if known.is_empty() {
                    "none here".to_string()
                } else {
                    known.join(", ")
                }
            ));
        }
        d.into()
    }
}
