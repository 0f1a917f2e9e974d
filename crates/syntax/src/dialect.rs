//! code_aster 11 (Python 2) versus code_aster 17 (Python 3).
//!
//! The grammar accepts both dialects; this module tells which Python 2
//! constructs a parsed module uses (the ones the AST keeps: `print x`,
//! `exec code`, backquotes), so that tools can report legacy syntax.
//! Forms that the parser normalizes are documented here for reference:
//! `<>` becomes `NotEq`, `0777` an `Int` (octal), `10L` an `Int`,
//! `ur''` a `Str`, `except E, e:` a handler with a name, `raise E, V` a
//! `raise E(V)`.

use crate::ast::*;
use crate::codemap::Span;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    /// Nothing Python-2-only in the AST.
    Python3,
    /// At least one Python 2 statement or expression.
    Python2,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Legacy {
    PrintStatement,
    ExecStatement,
    Backquotes,
}

/// The Python 2 constructs of a module, in source order.
pub fn legacy_features(module: &Module) -> Vec<(Span, Legacy)> {
    let mut out = Vec::new();
    stmts(&module.body, &mut out);
    out.sort_by_key(|(s, _)| s.start);
    out
}

pub fn dialect(module: &Module) -> Dialect {
    if legacy_features(module).is_empty() {
        Dialect::Python3
    } else {
        Dialect::Python2
    }
}

fn stmts(body: &[Stmt], out: &mut Vec<(Span, Legacy)>) {
    for s in body {
        match &s.kind {
            StmtKind::Print { dest, values, .. } => {
                out.push((s.span, Legacy::PrintStatement));
                dest.iter().chain(values).for_each(|e| expr(e, out));
            }
            StmtKind::Exec { code, .. } => {
                out.push((s.span, Legacy::ExecStatement));
                expr(code, out);
            }
            StmtKind::Expr { value } => expr(value, out),
            StmtKind::Assign { targets, value } => {
                targets.iter().for_each(|e| expr(e, out));
                expr(value, out);
            }
            StmtKind::AugAssign { value, .. } => expr(value, out),
            StmtKind::Return { value: Some(v) } => expr(v, out),
            StmtKind::If { test, body, orelse } | StmtKind::While { test, body, orelse } => {
                expr(test, out);
                stmts(body, out);
                stmts(orelse, out);
            }
            StmtKind::For {
                iter, body, orelse, ..
            } => {
                expr(iter, out);
                stmts(body, out);
                stmts(orelse, out);
            }
            StmtKind::FunctionDef { body, .. }
            | StmtKind::ClassDef { body, .. }
            | StmtKind::With { body, .. } => stmts(body, out),
            StmtKind::Try {
                body,
                handlers,
                orelse,
                finalbody,
            } => {
                stmts(body, out);
                handlers.iter().for_each(|h| stmts(&h.body, out));
                stmts(orelse, out);
                stmts(finalbody, out);
            }
            _ => {}
        }
    }
}

fn expr(e: &Expr, out: &mut Vec<(Span, Legacy)>) {
    match &e.kind {
        ExprKind::Repr { value } => {
            out.push((e.span, Legacy::Backquotes));
            expr(value, out);
        }
        ExprKind::Call { func, args } => {
            expr(func, out);
            for a in args {
                match &a.kind {
                    ArgKind::Positional { value }
                    | ArgKind::Keyword { value, .. }
                    | ArgKind::Star { value }
                    | ArgKind::DoubleStar { value } => expr(value, out),
                }
            }
        }
        ExprKind::BinOp { left, right, .. } => {
            expr(left, out);
            expr(right, out);
        }
        ExprKind::UnaryOp { operand, .. } => expr(operand, out),
        ExprKind::List { elts } | ExprKind::Tuple { elts } | ExprKind::Set { elts } => {
            elts.iter().for_each(|x| expr(x, out))
        }
        ExprKind::Compare { left, ops } => {
            expr(left, out);
            ops.iter().for_each(|(_, x)| expr(x, out));
        }
        ExprKind::BoolOp { values, .. } => values.iter().for_each(|x| expr(x, out)),
        ExprKind::IfExp { test, body, orelse } => {
            expr(test, out);
            expr(body, out);
            expr(orelse, out);
        }
        ExprKind::Subscript { value, index } => {
            expr(value, out);
            expr(index, out);
        }
        ExprKind::Attribute { value, .. } => expr(value, out),
        ExprKind::Dict { items } => items.iter().for_each(|i| expr(&i.value, out)),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_python2_constructs() {
        let m = crate::parse_module("x = `a`\nprint x\nexec 'y=1'\nz = repr(a)\n");
        let m = match m {
            Ok(m) => m,
            Err(e) => panic!("{}", e.message),
        };
        let kinds: Vec<Legacy> = legacy_features(&m).into_iter().map(|(_, k)| k).collect();
        assert_eq!(
            kinds,
            [
                Legacy::Backquotes,
                Legacy::PrintStatement,
                Legacy::ExecStatement
            ]
        );
        assert_eq!(dialect(&m), Dialect::Python2);
        let m3 = crate::parse_module("print(x)\n").map_err(|e| e.message);
        assert_eq!(m3.map(|m| dialect(&m)), Ok(Dialect::Python3));
    }
}
