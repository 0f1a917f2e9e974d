//! Post-parse checks: rules Python enforces at compile time that a grammar
//! does not express well. Each has its own message, pointing at the
//! offending node:
//! - `return` outside a function, `break`/`continue` outside a loop;
//! - a keyword argument repeated in one call (`MAILLAGE=MA, MAILLAGE=MB`);
//! - a positional argument after a keyword argument (or after `**kw`);
//! - a parameter name repeated in a `def`/`lambda`, and a parameter without
//!   default after one with a default.

use crate::ast::*;
use crate::limits::MAX_DEPTH;
use crate::ParseError;

type R = Result<(), ParseError>;

/// The tree is deeper than [`MAX_DEPTH`] at this node.
fn too_deep(span: crate::Span) -> ParseError {
    error(span, crate::limits::too_deep_message())
}

fn error(span: crate::Span, message: String) -> ParseError {
    ParseError { span, message }
}

/// Run every check on a module; the first violation (in source order) is returned.
pub fn check(module: &Module) -> R {
    let ctx = Ctx {
        in_function: false,
        in_loop: false,
        depth: 0,
    };
    stmts(&module.body, ctx)
}

#[derive(Clone, Copy)]
struct Ctx {
    in_function: bool,
    in_loop: bool,
    /// How deep the statement is (see [`crate::limits::MAX_DEPTH`]).
    depth: usize,
}

fn stmts(body: &[Stmt], ctx: Ctx) -> R {
    body.iter().try_for_each(|s| stmt(s, ctx))
}

fn stmt(s: &Stmt, ctx: Ctx) -> R {
    if ctx.depth >= MAX_DEPTH {
        return Err(too_deep(s.span));
    }
    let ctx = Ctx {
        depth: ctx.depth + 1,
        ..ctx
    };
    let d = ctx.depth;
    match &s.kind {
        StmtKind::Expr { value } => expr(value, d),
        StmtKind::Assign { targets, value } => {
            targets.iter().try_for_each(|e| expr(e, d))?;
            expr(value, d)
        }
        StmtKind::AugAssign { target, value, .. } => {
            expr(target, d)?;
            expr(value, d)
        }
        StmtKind::AnnAssign {
            target,
            annotation,
            value,
        } => {
            expr(target, d)?;
            expr(annotation, d)?;
            opt(value.as_ref(), d)
        }
        StmtKind::If { test, body, orelse } => {
            expr(test, d)?;
            stmts(body, ctx)?;
            stmts(orelse, ctx)
        }
        StmtKind::For {
            target,
            iter,
            body,
            orelse,
        } => {
            expr(target, d)?;
            expr(iter, d)?;
            stmts(
                body,
                Ctx {
                    in_loop: true,
                    ..ctx
                },
            )?;
            stmts(orelse, ctx)
        }
        StmtKind::While { test, body, orelse } => {
            expr(test, d)?;
            stmts(
                body,
                Ctx {
                    in_loop: true,
                    ..ctx
                },
            )?;
            stmts(orelse, ctx)
        }
        StmtKind::FunctionDef {
            params,
            body,
            decorators,
            ..
        } => {
            decorators.iter().try_for_each(|e| expr(e, d))?;
            check_params(params, d)?;
            stmts(
                body,
                Ctx {
                    in_function: true,
                    in_loop: false,
                    ..ctx
                },
            )
        }
        StmtKind::ClassDef {
            bases,
            body,
            decorators,
            ..
        } => {
            decorators.iter().try_for_each(|e| expr(e, d))?;
            check_args(bases, d)?;
            stmts(
                body,
                Ctx {
                    in_function: false,
                    in_loop: false,
                    ..ctx
                },
            )
        }
        StmtKind::Return { value } => {
            if !ctx.in_function {
                return Err(error(
                    s.span,
                    "`return` outside a function: a command file's top level cannot return".into(),
                ));
            }
            opt(value.as_ref(), d)
        }
        StmtKind::Break | StmtKind::Continue => {
            if !ctx.in_loop {
                let what = if matches!(s.kind, StmtKind::Break) {
                    "break"
                } else {
                    "continue"
                };
                return Err(error(
                    s.span,
                    format!("`{what}` outside a loop: it must be inside a `for` or `while` body"),
                ));
            }
            Ok(())
        }
        StmtKind::Try {
            body,
            handlers,
            orelse,
            finalbody,
        } => {
            stmts(body, ctx)?;
            for h in handlers {
                opt(h.typ.as_ref(), d)?;
                stmts(&h.body, ctx)?;
            }
            stmts(orelse, ctx)?;
            stmts(finalbody, ctx)
        }
        StmtKind::With { items, body } => {
            for item in items {
                expr(&item.context, d)?;
                opt(item.target.as_ref(), d)?;
            }
            stmts(body, ctx)
        }
        StmtKind::Raise { exc, cause } => {
            opt(exc.as_ref(), d)?;
            opt(cause.as_ref(), d)
        }
        StmtKind::Assert { test, msg } => {
            expr(test, d)?;
            opt(msg.as_ref(), d)
        }
        StmtKind::Del { targets } => targets.iter().try_for_each(|e| expr(e, d)),
        StmtKind::Print { dest, values, .. } => {
            opt(dest.as_ref(), d)?;
            values.iter().try_for_each(|e| expr(e, d))
        }
        StmtKind::Exec {
            code,
            globals,
            locals,
        } => {
            expr(code, d)?;
            opt(globals.as_ref(), d)?;
            opt(locals.as_ref(), d)
        }
        StmtKind::Import { .. }
        | StmtKind::ImportFrom { .. }
        | StmtKind::Global { .. }
        | StmtKind::Nonlocal { .. }
        | StmtKind::Pass => Ok(()),
    }
}

fn opt(e: Option<&Expr>, d: usize) -> R {
    e.map_or(Ok(()), |e| expr(e, d))
}

fn expr(e: &Expr, d: usize) -> R {
    if d >= MAX_DEPTH {
        return Err(too_deep(e.span));
    }
    let d = d + 1;
    match &e.kind {
        ExprKind::Call { func, args } => {
            expr(func, d)?;
            check_args(args, d)
        }
        ExprKind::Name { .. }
        | ExprKind::Int { .. }
        | ExprKind::Float { .. }
        | ExprKind::Imag { .. }
        | ExprKind::Str { .. }
        | ExprKind::Bytes { .. }
        | ExprKind::Bool { .. }
        | ExprKind::None
        | ExprKind::Ellipsis => Ok(()),
        ExprKind::FString { parts } => fstring(parts, d),
        ExprKind::List { elts } | ExprKind::Tuple { elts } | ExprKind::Set { elts } => {
            elts.iter().try_for_each(|e| expr(e, d))
        }
        ExprKind::Dict { items } => items.iter().try_for_each(|i| {
            opt(i.key.as_ref(), d)?;
            expr(&i.value, d)
        }),
        ExprKind::Attribute { value, .. } => expr(value, d),
        ExprKind::Subscript { value, index } => {
            expr(value, d)?;
            expr(index, d)
        }
        ExprKind::Slice { lower, upper, step } => {
            opt(lower.as_deref(), d)?;
            opt(upper.as_deref(), d)?;
            opt(step.as_deref(), d)
        }
        ExprKind::BinOp { left, right, .. } => {
            expr(left, d)?;
            expr(right, d)
        }
        ExprKind::UnaryOp { operand, .. } => expr(operand, d),
        ExprKind::BoolOp { values, .. } => values.iter().try_for_each(|e| expr(e, d)),
        ExprKind::Compare { left, ops } => {
            expr(left, d)?;
            ops.iter().try_for_each(|(_, e)| expr(e, d))
        }
        ExprKind::IfExp { test, body, orelse } => {
            expr(test, d)?;
            expr(body, d)?;
            expr(orelse, d)
        }
        ExprKind::Lambda { params, body } => {
            check_params(params, d)?;
            expr(body, d)
        }
        ExprKind::ListComp { elt, generators }
        | ExprKind::SetComp { elt, generators }
        | ExprKind::GeneratorExp { elt, generators } => {
            expr(elt, d)?;
            comprehensions(generators, d)
        }
        ExprKind::DictComp {
            key,
            value,
            generators,
        } => {
            expr(key, d)?;
            expr(value, d)?;
            comprehensions(generators, d)
        }
        ExprKind::Starred { value }
        | ExprKind::YieldFrom { value }
        | ExprKind::Await { value }
        | ExprKind::Repr { value } => expr(value, d),
        ExprKind::Yield { value } => opt(value.as_deref(), d),
        ExprKind::NamedExpr { value, .. } => expr(value, d),
    }
}

fn fstring(parts: &[FStringPart], d: usize) -> R {
    for p in parts {
        if let FStringPart::Field {
            value, format_spec, ..
        } = p
        {
            expr(value, d)?;
            fstring(format_spec, d)?;
        }
    }
    Ok(())
}

fn comprehensions(gens: &[Comprehension], d: usize) -> R {
    for g in gens {
        expr(&g.target, d)?;
        expr(&g.iter, d)?;
        g.ifs.iter().try_for_each(|e| expr(e, d))?;
    }
    Ok(())
}

/// Keyword arguments are unique; no positional argument after a keyword one.
fn check_args(args: &[Arg], d: usize) -> R {
    let mut keyword_seen = false;
    let mut dstar_seen = false;
    for (i, arg) in args.iter().enumerate() {
        match &arg.kind {
            ArgKind::Keyword { name, value } => {
                // The earlier arguments are the set of names seen so far (no
                // allocation: this runs for every call of every file).
                let repeated = args[..i].iter().any(
                    |a| matches!(&a.kind, ArgKind::Keyword { name: k, .. } if k.name == name.name),
                );
                if repeated {
                    return Err(error(
                        name.span,
                        format!(
                            "keyword argument `{}` repeated: each keyword may appear once per call",
                            name.name
                        ),
                    ));
                }
                keyword_seen = true;
                expr(value, d)?;
            }
            ArgKind::Positional { value } => {
                if dstar_seen {
                    return Err(error(
                        arg.span,
                        "positional argument follows keyword argument unpacking (`**`)".into(),
                    ));
                }
                if keyword_seen {
                    return Err(error(
                        arg.span,
                        "positional argument follows keyword argument: put positional arguments first, or name this one (`KEYWORD=...`)".into(),
                    ));
                }
                expr(value, d)?;
            }
            ArgKind::Star { value } => {
                if dstar_seen {
                    return Err(error(
                        arg.span,
                        "iterable argument unpacking (`*`) follows keyword argument unpacking (`**`)".into(),
                    ));
                }
                expr(value, d)?;
            }
            ArgKind::DoubleStar { value } => {
                dstar_seen = true;
                expr(value, d)?;
            }
        }
    }
    Ok(())
}

/// Parameter names are unique; defaults are not followed by non-defaults
/// (before `*`).
fn check_params(params: &[Param], d: usize) -> R {
    let mut names: Vec<&str> = Vec::new();
    let mut default_seen = false;
    let mut kw_only = false;
    for p in params {
        if matches!(p.kind, ParamKind::KwOnlyMarker | ParamKind::PosOnlyMarker) {
            kw_only |= p.kind == ParamKind::KwOnlyMarker;
            continue;
        }
        if names.contains(&p.name.name.as_str()) {
            return Err(error(
                p.name.span,
                format!(
                    "duplicate parameter `{}` in function definition",
                    p.name.name
                ),
            ));
        }
        names.push(&p.name.name);
        match p.kind {
            ParamKind::VarArgs => kw_only = true,
            ParamKind::Normal if !kw_only => {
                if p.default.is_some() {
                    default_seen = true;
                } else if default_seen {
                    return Err(error(
                        p.name.span,
                        format!(
                            "parameter `{}` without a default follows a parameter with a default",
                            p.name.name
                        ),
                    ));
                }
            }
            _ => {}
        }
        opt(p.default.as_ref(), d)?;
        opt(p.annotation.as_ref(), d)?;
    }
    Ok(())
}
