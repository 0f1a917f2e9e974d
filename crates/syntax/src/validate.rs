//! Post-parse checks: rules Python enforces at compile time that a grammar
//! does not express well. Each has its own message, pointing at the
//! offending node:
//! - `return` outside a function, `break`/`continue` outside a loop;
//! - a keyword argument repeated in one call (`MAILLAGE=MA, MAILLAGE=MB`);
//! - a positional argument after a keyword argument (or after `**kw`);
//! - a parameter name repeated in a `def`/`lambda`, and a parameter without
//!   default after one with a default.

use crate::ast::*;
use crate::ParseError;

type R = Result<(), ParseError>;

fn error(span: crate::Span, message: String) -> ParseError {
    ParseError { span, message }
}

/// Run every check on a module; the first violation (in source order) is returned.
pub fn check(module: &Module) -> R {
    let ctx = Ctx {
        in_function: false,
        in_loop: false,
    };
    stmts(&module.body, ctx)
}

#[derive(Clone, Copy)]
struct Ctx {
    in_function: bool,
    in_loop: bool,
}

fn stmts(body: &[Stmt], ctx: Ctx) -> R {
    body.iter().try_for_each(|s| stmt(s, ctx))
}

fn stmt(s: &Stmt, ctx: Ctx) -> R {
    match &s.kind {
        StmtKind::Expr { value } => expr(value),
        StmtKind::Assign { targets, value } => {
            targets.iter().try_for_each(expr)?;
            expr(value)
        }
        StmtKind::AugAssign { target, value, .. } => {
            expr(target)?;
            expr(value)
        }
        StmtKind::AnnAssign {
            target,
            annotation,
            value,
        } => {
            expr(target)?;
            expr(annotation)?;
            opt(value.as_ref())
        }
        StmtKind::If { test, body, orelse } => {
            expr(test)?;
            stmts(body, ctx)?;
            stmts(orelse, ctx)
        }
        StmtKind::For {
            target,
            iter,
            body,
            orelse,
        } => {
            expr(target)?;
            expr(iter)?;
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
            expr(test)?;
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
            decorators.iter().try_for_each(expr)?;
            check_params(params)?;
            stmts(
                body,
                Ctx {
                    in_function: true,
                    in_loop: false,
                },
            )
        }
        StmtKind::ClassDef {
            bases,
            body,
            decorators,
            ..
        } => {
            decorators.iter().try_for_each(expr)?;
            check_args(bases)?;
            stmts(
                body,
                Ctx {
                    in_function: false,
                    in_loop: false,
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
            opt(value.as_ref())
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
                opt(h.typ.as_ref())?;
                stmts(&h.body, ctx)?;
            }
            stmts(orelse, ctx)?;
            stmts(finalbody, ctx)
        }
        StmtKind::With { items, body } => {
            for item in items {
                expr(&item.context)?;
                opt(item.target.as_ref())?;
            }
            stmts(body, ctx)
        }
        StmtKind::Raise { exc, cause } => {
            opt(exc.as_ref())?;
            opt(cause.as_ref())
        }
        StmtKind::Assert { test, msg } => {
            expr(test)?;
            opt(msg.as_ref())
        }
        StmtKind::Del { targets } => targets.iter().try_for_each(expr),
        StmtKind::Print { dest, values, .. } => {
            opt(dest.as_ref())?;
            values.iter().try_for_each(expr)
        }
        StmtKind::Exec {
            code,
            globals,
            locals,
        } => {
            expr(code)?;
            opt(globals.as_ref())?;
            opt(locals.as_ref())
        }
        StmtKind::Import { .. }
        | StmtKind::ImportFrom { .. }
        | StmtKind::Global { .. }
        | StmtKind::Nonlocal { .. }
        | StmtKind::Pass => Ok(()),
    }
}

fn opt(e: Option<&Expr>) -> R {
    e.map_or(Ok(()), expr)
}

fn expr(e: &Expr) -> R {
    match &e.kind {
        ExprKind::Call { func, args } => {
            expr(func)?;
            check_args(args)
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
        ExprKind::FString { parts } => fstring(parts),
        ExprKind::List { elts } | ExprKind::Tuple { elts } | ExprKind::Set { elts } => {
            elts.iter().try_for_each(expr)
        }
        ExprKind::Dict { items } => items.iter().try_for_each(|i| {
            opt(i.key.as_ref())?;
            expr(&i.value)
        }),
        ExprKind::Attribute { value, .. } => expr(value),
        ExprKind::Subscript { value, index } => {
            expr(value)?;
            expr(index)
        }
        ExprKind::Slice { lower, upper, step } => {
            opt(lower.as_deref())?;
            opt(upper.as_deref())?;
            opt(step.as_deref())
        }
        ExprKind::BinOp { left, right, .. } => {
            expr(left)?;
            expr(right)
        }
        ExprKind::UnaryOp { operand, .. } => expr(operand),
        ExprKind::BoolOp { values, .. } => values.iter().try_for_each(expr),
        ExprKind::Compare { left, ops } => {
            expr(left)?;
            ops.iter().try_for_each(|(_, e)| expr(e))
        }
        ExprKind::IfExp { test, body, orelse } => {
            expr(test)?;
            expr(body)?;
            expr(orelse)
        }
        ExprKind::Lambda { params, body } => {
            check_params(params)?;
            expr(body)
        }
        ExprKind::ListComp { elt, generators }
        | ExprKind::SetComp { elt, generators }
        | ExprKind::GeneratorExp { elt, generators } => {
            expr(elt)?;
            comprehensions(generators)
        }
        ExprKind::DictComp {
            key,
            value,
            generators,
        } => {
            expr(key)?;
            expr(value)?;
            comprehensions(generators)
        }
        ExprKind::Starred { value }
        | ExprKind::YieldFrom { value }
        | ExprKind::Await { value }
        | ExprKind::Repr { value } => expr(value),
        ExprKind::Yield { value } => opt(value.as_deref()),
        ExprKind::NamedExpr { value, .. } => expr(value),
    }
}

fn fstring(parts: &[FStringPart]) -> R {
    for p in parts {
        if let FStringPart::Field {
            value, format_spec, ..
        } = p
        {
            expr(value)?;
            fstring(format_spec)?;
        }
    }
    Ok(())
}

fn comprehensions(gens: &[Comprehension]) -> R {
    for g in gens {
        expr(&g.target)?;
        expr(&g.iter)?;
        g.ifs.iter().try_for_each(expr)?;
    }
    Ok(())
}

/// Keyword arguments are unique; no positional argument after a keyword one.
fn check_args(args: &[Arg]) -> R {
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
                expr(value)?;
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
                expr(value)?;
            }
            ArgKind::Star { value } => {
                if dstar_seen {
                    return Err(error(
                        arg.span,
                        "iterable argument unpacking (`*`) follows keyword argument unpacking (`**`)".into(),
                    ));
                }
                expr(value)?;
            }
            ArgKind::DoubleStar { value } => {
                dstar_seen = true;
                expr(value)?;
            }
        }
    }
    Ok(())
}

/// Parameter names are unique; defaults are not followed by non-defaults
/// (before `*`).
fn check_params(params: &[Param]) -> R {
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
        opt(p.default.as_ref())?;
        opt(p.annotation.as_ref())?;
    }
    Ok(())
}
