//! Runs a command file as a program. Python-level statements are evaluated;
//! every command call is validated against the catalog (defaults filled,
//! legacy keywords mapped) and handed, as a [`CommandCall`], to a
//! [`CommandSink`]: the checker's sink ([`CheckSink`]) only types the
//! result, the runner's sink executes it.
//!
//! Entry points: [`run_program`] (a parsed module), [`check_source`] (parse +
//! run with the [`CheckSink`]), and [`Formula::eval`] for `FORMULE`s.

mod builtins;
pub mod command;
mod commands;
pub mod diag;
mod format;
pub mod formula;
mod int;
mod interp;
pub mod legacy;
pub mod legacy_commands;
pub mod limits;
mod memo;
pub mod migrate;
mod os_module;
mod recover;
mod study;
mod table;
mod testcase;
mod try_import;
mod validate;
mod value;

pub use command::*;
pub use diag::{DiagKind, Diagnostic, Diagnostics, Level, Severity};
pub use formula::Formula;
pub use memo::ValidationMemo;

use aster_syntax::{ast, CodeMap};

/// How to run a program.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOptions {
    /// Keep evaluating after a command with validation errors (the checker
    /// wants every error; the runner stops at the first invalid command).
    pub keep_going: bool,
}

/// What a successful run did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunSummary {
    /// Commands handed to the sink.
    pub commands: usize,
    /// True when the program reached `FIN()`.
    pub reached_fin: bool,
    /// Warnings (legacy syntax mapped...).
    pub warnings: Diagnostics,
}

/// Runs a parsed program, handing each validated command to `sink`.
///
/// `Ok` when no error occurred (warnings are in the summary); `Err` with
/// every diagnostic (errors and warnings) otherwise.
pub fn run_program(
    map: &CodeMap,
    module: &ast::Module,
    sink: &mut dyn CommandSink,
    options: RunOptions,
) -> Result<RunSummary, Diagnostics> {
    let study = Study {
        files: vec![module],
        modules: Vec::new(),
        declared: false,
    };
    run_study(map, &study, sink, options)
}

/// A study as an `.export` describes it: command files run in order, and
/// the Python modules they may import. Every file is parsed at its own
/// offset of one [`CodeMap`] (`CodeMap::add_file`, `parse_module_at`).
pub struct Study<'m> {
    /// The command files, in order (`F comm X.comm D 1`, `X.com1`…).
    pub files: Vec<&'m ast::Module>,
    /// The modules (`F nom name.py D 0`), by module name.
    pub modules: Vec<(String, &'m ast::Module)>,
    /// The module list is the study's whole list (an `.export` gave it): a
    /// missing module is said so.
    pub declared: bool,
}

/// Runs a study: each command file in turn in one interpreter; at the end
/// of a file the context `FIN` saves (concepts and plain values, not
/// functions or modules) is what `POURSUITE` in the next file restores.
pub fn run_study(
    map: &CodeMap,
    study: &Study,
    sink: &mut dyn CommandSink,
    options: RunOptions,
) -> Result<RunSummary, Diagnostics> {
    run_study_memo(map, study, sink, options, None)
}

/// [`run_study`] sharing validations with another pass over the same study
/// ([`ValidationMemo`]: `aster run`'s static pass records, its run reuses).
pub fn run_study_memo(
    map: &CodeMap,
    study: &Study,
    sink: &mut dyn CommandSink,
    options: RunOptions,
    memo: Option<&mut ValidationMemo>,
) -> Result<RunSummary, Diagnostics> {
    let mut interp = interp::Interp::new(map, sink, options.keep_going);
    interp.memo = memo;
    interp.study.sources = study.modules.iter().map(|(n, m)| (n.clone(), *m)).collect();
    interp.study.declared = study.declared;
    let mut diags = Vec::new();
    let mut reached_fin = false;
    for (i, module) in study.files.iter().enumerate() {
        if i > 0 {
            interp.end_command_file();
            interp.study.several_files = true;
        }
        interp.legacy = aster_syntax::dialect::generation(module).is_legacy();
        let r = interp.run_module(module);
        diags.append(&mut interp.diags);
        reached_fin = interp.finished;
        if let Err(interp::Halt::Diag(d)) = r {
            diags.push(*d);
        }
        if diags.iter().any(Diagnostic::is_error) {
            break;
        }
    }
    let diags = Diagnostics(diags);
    if diags.has_errors() {
        return Err(diags);
    }
    Ok(RunSummary {
        commands: interp.commands,
        reached_fin,
        warnings: diags,
    })
}

/// A sink that executes nothing: each command just yields its typed result
/// concept; values read from concepts are "known at run time".
#[derive(Debug, Default)]
pub struct CheckSink {
    /// Every call, in order (for `aster check --emit commands`).
    pub calls: Vec<CommandCall>,
    /// Keep the calls (off when only diagnostics matter).
    pub record: bool,
}

impl CommandSink for CheckSink {
    fn execute(&mut self, call: &CommandCall) -> Result<CommandOutput, ExecError> {
        if self.record {
            self.calls.push(call.clone());
        }
        Ok(if call.result.is_some() {
            CommandOutput::Concept
        } else {
            CommandOutput::Nothing
        })
    }
    fn method(&mut self, _: &ConceptRef, _: &str, _: &[HostValue]) -> Result<HostValue, ExecError> {
        Ok(HostValue::Unknown)
    }
    fn make(
        &mut self,
        _: &ConceptRef,
        _: &str,
        _: &[(&'static str, HostValue)],
        _: &ConceptRef,
    ) -> Result<(), ExecError> {
        Ok(())
    }
    fn index(&mut self, _: &ConceptRef, _: &[HostValue]) -> Result<HostValue, ExecError> {
        Ok(HostValue::Unknown)
    }
    fn print(&mut self, _: &str) {}
}

/// The outcome of checking one source text.
#[derive(Debug)]
pub struct CheckReport {
    pub diagnostics: Diagnostics,
    /// The evaluated command calls (when recorded).
    pub calls: Vec<CommandCall>,
}

impl CheckReport {
    pub fn ok(&self) -> bool {
        !self.diagnostics.has_errors()
    }
}

/// Parses and checks a command file: every command validated, none executed.
pub fn check_source(map: &CodeMap, record: bool) -> CheckReport {
    let module = match aster_syntax::parse_module(map.source()) {
        Ok(m) => m,
        Err(e) => {
            return CheckReport {
                diagnostics: Diagnostics(vec![Diagnostic::error(
                    DiagKind::Syntax,
                    e.span,
                    e.message,
                )]),
                calls: Vec::new(),
            }
        }
    };
    check_module(map, &module, record)
}

/// Checks an already parsed command file (what [`check_source`] does after
/// parsing): every command validated, none executed.
pub fn check_module(map: &CodeMap, module: &ast::Module, record: bool) -> CheckReport {
    let mut sink = CheckSink {
        calls: Vec::new(),
        record,
    };
    let diagnostics = match run_program(map, module, &mut sink, RunOptions { keep_going: true }) {
        Ok(s) => s.warnings,
        Err(d) => d,
    };
    CheckReport {
        diagnostics,
        calls: sink.calls,
    }
}
