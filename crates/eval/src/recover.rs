//! Checking goes on after a Python-level error, as compilers do: `aster
//! check` reports every independent error of a file, not only the first.
//!
//! Only the checker recovers (`RunOptions::keep_going`); the runner stops at
//! the first error. Recovery is per top-level statement. When one fails, its
//! diagnostic is recorded and the next statement runs; what the failed one
//! would have bound (assignment targets, loop variables, `def`/`class`
//! names, imports — in nested blocks too) becomes a run-time value
//! ([`Value::Unknown`](crate::value::Value)).
//!
//! No consequence is reported as an error of its own: the corpus of real
//! files, all valid, is the measure (no file may gain an error). A later
//! statement whose text mentions a name a failure left unknown — bound by
//! it, or only used by it (a list it appended to) — is a consequence: its
//! errors are dropped and what it binds or mentions becomes unknown in turn.
//! An undefined name that appears in a failed statement's text (a concept
//! `CO('M')` a macro would have made), or that was given to `CO()`, is a
//! run-time value; after a failed `from m import *`, `exec` or `INCLUDE`
//! every undefined name is (they bind names the text does not show).
//!
//! A spent step budget is not recovered from (every later statement would
//! spend it again).

use crate::diag::{DiagKind, Diagnostic};
use aster_syntax::ast::{self, ExprKind, StmtKind};
use std::collections::HashSet;

/// Whether checking may go on after this error.
pub(crate) fn recoverable(d: &Diagnostic) -> bool {
    matches!(
        d.kind,
        DiagKind::Python
            | DiagKind::UnknownCommand
            | DiagKind::NotSupported
            | DiagKind::RunTimeValue
            | DiagKind::Exec
    )
}

/// The names a statement binds in its scope, nested blocks included (not
/// the bodies of the functions and classes it defines).
pub(crate) fn bound_names(s: &ast::Stmt, out: &mut Vec<String>) {
    match &s.kind {
        StmtKind::Assign { targets, .. } => targets.iter().for_each(|t| target_names(t, out)),
        StmtKind::AugAssign { target, .. } | StmtKind::AnnAssign { target, .. } => {
            target_names(target, out)
        }
        StmtKind::For {
            target,
            body,
            orelse,
            ..
        } => {
            target_names(target, out);
            block(body, out);
            block(orelse, out);
        }
        StmtKind::If { body, orelse, .. } | StmtKind::While { body, orelse, .. } => {
            block(body, out);
            block(orelse, out);
        }
        StmtKind::FunctionDef { name, .. } | StmtKind::ClassDef { name, .. } => {
            out.push(name.name.to_string())
        }
        StmtKind::Import { names } => {
            for a in names {
                out.push(match &a.asname {
                    Some(n) => n.name.to_string(),
                    None => a.name.split('.').next().unwrap_or(&a.name).to_string(),
                });
            }
        }
        StmtKind::ImportFrom { names, .. } => {
            for a in names {
                out.push(match &a.asname {
                    Some(n) => n.name.to_string(),
                    None => a.name.clone(),
                });
            }
        }
        StmtKind::Try {
            body,
            handlers,
            orelse,
            finalbody,
        } => {
            block(body, out);
            for h in handlers {
                if let Some(n) = &h.name {
                    out.push(n.name.to_string());
                }
                block(&h.body, out);
            }
            block(orelse, out);
            block(finalbody, out);
        }
        StmtKind::With { items, body } => {
            for i in items {
                if let Some(t) = &i.target {
                    target_names(t, out);
                }
            }
            block(body, out);
        }
        _ => {}
    }
}

fn block(body: &[ast::Stmt], out: &mut Vec<String>) {
    body.iter().for_each(|s| bound_names(s, out));
}

fn target_names(t: &ast::Expr, out: &mut Vec<String>) {
    match &t.kind {
        ExprKind::Name { id } => out.push(id.to_string()),
        ExprKind::Tuple { elts } | ExprKind::List { elts } => {
            elts.iter().for_each(|e| target_names(e, out))
        }
        ExprKind::Starred { value } => target_names(value, out),
        _ => {}
    }
}

/// What the statements that failed while checking left unknown.
#[derive(Debug, Default)]
pub(crate) struct Recovery {
    /// Names a failed statement bound, or used (a list it appended to, a
    /// concept it modified in place).
    names: HashSet<String>,
    /// Every word of the failed statements' text: a name defined behind a
    /// string (`CO('M')` given to a macro) is among them.
    words: HashSet<String>,
    /// Names may have been bound in ways the text does not show (`exec`, a
    /// failed `from m import *`): an undefined name is a run-time value.
    pub(crate) names_unknown: bool,
    /// Undefined names read as run-time values (with `names_unknown`): a
    /// statement that reads one is a consequence.
    pub(crate) unknown_names_read: std::cell::Cell<u64>,
    /// Names given to `CO()`: a concept a command will create, or that a
    /// macro defined in the file (not run while checking) would have.
    pub(crate) made_by_co: HashSet<String>,
}

impl Recovery {
    /// A statement failed: `bound` are the names it binds; `defined` tells
    /// the names defined when it ran.
    pub(crate) fn failed(
        &mut self,
        s: &ast::Stmt,
        text: &str,
        bound: Vec<String>,
        defined: impl Fn(&str) -> bool,
    ) {
        self.derived(text, bound, defined);
        for w in words(text) {
            if w == "exec" {
                self.names_unknown = true;
            }
            self.words.insert(w.to_string());
        }
        if matches!(&s.kind, StmtKind::ImportFrom { star: true, .. }) {
            self.names_unknown = true;
        }
    }

    /// Whether an undefined name is a run-time value rather than an error:
    /// after a failure, a name bound in ways the text does not show, or
    /// one given to `CO()`.
    pub(crate) fn undefined_is_unknown(&self, name: &str) -> bool {
        self.names_unknown || (!self.words.is_empty() && self.made_by_co.contains(name))
    }

    /// A statement that used what a failure left unknown ran: the names it
    /// bound, and the defined names it mentions (a list it appended to),
    /// are derived from unknowns.
    pub(crate) fn derived(
        &mut self,
        text: &str,
        bound: Vec<String>,
        defined: impl Fn(&str) -> bool,
    ) {
        for w in words(text) {
            if defined(w) {
                self.names.insert(w.to_string());
            }
        }
        self.names.extend(bound);
    }

    /// Whether a statement's errors would be consequences of an earlier
    /// failure: its text mentions a name that failure left unknown.
    /// Textual on purpose: a mention inside a string or a comment also
    /// counts, which can only hide a consequence, never report a false
    /// error.
    pub(crate) fn is_consequence(&self, text: &str) -> bool {
        !self.names.is_empty() && words(text).any(|w| self.names.contains(w))
    }

    /// An undefined-name error whose name a failed statement may have
    /// defined (it appears in its text).
    pub(crate) fn undefined_name_explained(&self, d: &Diagnostic) -> bool {
        d.kind == DiagKind::Python
            && d.message
                .strip_prefix("name `")
                .and_then(|m| m.strip_suffix("` is not defined"))
                .is_some_and(|n| self.words.contains(n))
    }
}

fn words(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(src: &str) -> Vec<String> {
        let m = aster_syntax::parse_module(src).unwrap();
        let mut out = Vec::new();
        m.body.iter().for_each(|s| bound_names(s, &mut out));
        out
    }

    #[test]
    fn bound_names_cover_targets_loops_defs_imports_and_nested_blocks() {
        assert_eq!(names("a, (b, *c) = f()\nd += 1"), ["a", "b", "c", "d"]);
        assert_eq!(
            names(
                "for i in x:\n    if i:\n        m = 1\n    else:\n        n = 2\nelse:\n    o = 3"
            ),
            ["i", "m", "n", "o"]
        );
        assert_eq!(
            names(
                "def f(x):\n    y = x\nimport os.path\nimport numpy as np\nfrom m import p, q as r"
            ),
            ["f", "os", "np", "p", "r"]
        );
        assert_eq!(
            names("try:\n    t = 1\nexcept ImportError as e:\n    u = 2\nwith open(f) as g:\n    h = 1"),
            ["t", "e", "u", "g", "h"]
        );
        assert!(names("x[0] = 1\nobj.a = 2\nprint(x)").is_empty());
    }

    #[test]
    fn a_consequence_mentions_a_name_a_failed_statement_left_unknown() {
        let m = aster_syntax::parse_module("l = []\nfor x in f():\n    l.append(g(CO('M')))\n")
            .unwrap();
        let mut r = Recovery::default();
        let text = "for x in f():\n    l.append(g(CO('M')))";
        let mut bound = Vec::new();
        bound_names(&m.body[1], &mut bound);
        r.failed(&m.body[1], text, bound, |w| w == "l" || w == "f");
        assert!(r.is_consequence("y = l[0]"), "a list the loop appended to");
        assert!(r.is_consequence("z = x + 1"), "the loop variable");
        assert!(!r.is_consequence("MAT = DEFI_MATERIAU(ELAS=_F(E=1.0))"));
        let undefined = |n: &str| {
            Diagnostic::error(
                DiagKind::Python,
                Default::default(),
                format!("name `{n}` is not defined"),
            )
        };
        assert!(
            r.undefined_name_explained(&undefined("M")),
            "made by CO('M')"
        );
        assert!(!r.undefined_name_explained(&undefined("N")));
        assert!(!r.names_unknown);
        r.failed(&m.body[0], "exec(code)", Vec::new(), |_| false);
        assert!(r.names_unknown);
    }
}
