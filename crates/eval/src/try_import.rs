//! `try: import X ... except ImportError: ...` — the one form of `try`
//! that real command files use to stay runnable without an optional module
//! (`from code_aster.Utilities import sympy` then a fallback). The checker
//! runs the program in an environment that does not provide such modules:
//! their import (or first use, for code_aster's lazily imported ones)
//! raises ImportError there, exactly as on a code_aster without them, and
//! the `except ImportError` branch is what runs.

use crate::diag::Diagnostic;
use aster_syntax::ast::{ExceptHandler, Expr, ExprKind, Stmt, StmtKind};

const IMPORT_ERRORS: [&str; 2] = ["ImportError", "ModuleNotFoundError"];

/// Whether a handler catches ImportError and nothing else (a broader
/// `except:` would also swallow errors the checker must report).
pub(crate) fn catches_only_import_error(h: &ExceptHandler) -> bool {
    fn is_import_error(e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Name { id } => IMPORT_ERRORS.contains(&id.as_str()),
            ExprKind::Tuple { elts } => !elts.is_empty() && elts.iter().all(is_import_error),
            _ => false,
        }
    }
    h.typ.as_ref().is_some_and(is_import_error)
}

/// A bare `except:` (or `except Exception:`): catches any Python
/// exception the body raises.
pub(crate) fn catches_any_exception(h: &ExceptHandler) -> bool {
    match &h.typ {
        None => true,
        Some(e) => matches!(&e.kind, ExprKind::Name { id } if id == "Exception"),
    }
}

/// The handler catches code_aster's errors (`except CA.AsterError`,
/// `except AsterError`): the program checks which error a command raises.
pub(crate) fn catches_aster_error(h: &ExceptHandler) -> bool {
    fn is_aster_error(e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Name { id } => id.ends_with("Error") && id.starts_with("Aster"),
            ExprKind::Attribute { attr, .. } => attr.name.starts_with("Aster"),
            ExprKind::Tuple { elts } => elts.iter().any(is_aster_error),
            _ => false,
        }
    }
    h.typ.as_ref().is_some_and(is_aster_error)
}

/// The modules and module members a `try` body imports at its top level
/// (`code_aster.Utilities.sympy` for `from code_aster.Utilities import sympy`).
pub(crate) fn imported_paths(body: &[Stmt]) -> Vec<String> {
    let mut out = Vec::new();
    for s in body {
        match &s.kind {
            StmtKind::Import { names } => out.extend(names.iter().map(|a| a.name.clone())),
            StmtKind::ImportFrom {
                module: Some(m),
                names,
                ..
            } => {
                out.push(m.clone());
                out.extend(names.iter().map(|a| format!("{m}.{}", a.name)));
            }
            _ => {}
        }
    }
    out
}

/// Whether a "not supported" stop is a module the checker does not
/// provide, imported by this `try` body: an ImportError at run time.
pub(crate) fn is_missing_module(d: &Diagnostic, imported: &[String]) -> bool {
    if !d.kind.is_not_supported() {
        return false;
    }
    let Some(what) = d.message.strip_prefix("not supported: ") else {
        return false;
    };
    if what.starts_with("import of module `") || what.starts_with("import from module `") {
        return true;
    }
    // A member of a lazily imported module used for the first time.
    imported
        .iter()
        .any(|p| what.starts_with(&format!("`{p}.")) || what == format!("`{p}`"))
}
