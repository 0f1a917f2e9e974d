//! The canonical printer (`aster fmt`): code_aster 17 style, i.e. the
//! `black` layout of current code_aster test files: 4-space indentation,
//! double quotes, a call that does not fit on one line gets one argument per
//! line (so one keyword per line in long commands) and a trailing comma.
//!
//! Guarantee (tested): `parse(format(x)) == parse(x)` up to spans.
//! Comments are kept: each is printed on its own line before the statement
//! that follows it (a comment inside a statement moves above it). One blank
//! line is kept where the source had blank lines between statements.

use crate::ast::*;
use crate::ParseError;

/// Preferred maximum line width.
pub const WIDTH: usize = 100;
const INDENT: &str = "    ";

/// Parse `source` and print it in canonical form, keeping its comments.
pub fn format_source(source: &str) -> Result<String, ParseError> {
    let module = crate::parse_module(source)?;
    let mut p = Printer {
        out: String::new(),
        comments: comments(source),
        next_comment: 0,
        source: Some(source),
        no_break: false,
        line_indent: 0,
    };
    p.body(&module.body, 0, 0);
    p.flush_comments(usize::MAX, 0);
    Ok(p.out)
}

/// Print a module in canonical form (no comments: the AST has none).
pub fn format_module(module: &Module) -> String {
    let mut p = Printer {
        out: String::new(),
        comments: Vec::new(),
        next_comment: 0,
        source: None,
        no_break: false,
        line_indent: 0,
    };
    p.body(&module.body, 0, 0);
    p.out
}

/// Comments (`#` outside strings) with their byte offsets.
fn comments(source: &str) -> Vec<(usize, String)> {
    let bytes = source.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                let end = source[i..]
                    .find(['\n', '\r'])
                    .map_or(source.len(), |e| i + e);
                out.push((i, source[i..end].trim_end().to_string()));
                i = end;
            }
            b'\'' | b'"' => {
                let q = bytes[i];
                let triple = bytes.get(i + 1) == Some(&q) && bytes.get(i + 2) == Some(&q);
                let mut j = if triple { i + 3 } else { i + 1 };
                while j < bytes.len() {
                    if bytes[j] == b'\\' {
                        j += 2;
                        continue;
                    }
                    if bytes[j] == q
                        && (!triple
                            || (bytes.get(j + 1) == Some(&q) && bytes.get(j + 2) == Some(&q)))
                    {
                        j += if triple { 3 } else { 1 };
                        break;
                    }
                    j += 1;
                }
                i = j;
            }
            _ => i += 1,
        }
    }
    out
}

// Precedence levels for printing (higher binds tighter).
const P_LAMBDA: u8 = 1;
const P_IFEXP: u8 = 2;
const P_OR: u8 = 3;
const P_AND: u8 = 4;
const P_NOT: u8 = 5;
const P_CMP: u8 = 6;
const P_BITOR: u8 = 7;
const P_BITXOR: u8 = 8;
const P_BITAND: u8 = 9;
const P_SHIFT: u8 = 10;
const P_ARITH: u8 = 11;
const P_TERM: u8 = 12;
const P_UNARY: u8 = 13;
const P_POW: u8 = 14;
const P_ATOM: u8 = 16;

fn binop_prec(op: BinOp) -> u8 {
    match op {
        BinOp::BitOr => P_BITOR,
        BinOp::BitXor => P_BITXOR,
        BinOp::BitAnd => P_BITAND,
        BinOp::LShift | BinOp::RShift => P_SHIFT,
        BinOp::Add | BinOp::Sub => P_ARITH,
        BinOp::Mul | BinOp::MatMul | BinOp::Div | BinOp::FloorDiv | BinOp::Mod => P_TERM,
        BinOp::Pow => P_POW,
    }
}

fn binop_str(op: BinOp) -> &'static str {
    match op {
        BinOp::Add => "+",
        BinOp::Sub => "-",
        BinOp::Mul => "*",
        BinOp::MatMul => "@",
        BinOp::Div => "/",
        BinOp::FloorDiv => "//",
        BinOp::Mod => "%",
        BinOp::Pow => "**",
        BinOp::LShift => "<<",
        BinOp::RShift => ">>",
        BinOp::BitOr => "|",
        BinOp::BitXor => "^",
        BinOp::BitAnd => "&",
    }
}

fn cmp_str(op: CmpOp) -> &'static str {
    match op {
        CmpOp::Eq => "==",
        CmpOp::NotEq => "!=",
        CmpOp::Lt => "<",
        CmpOp::LtE => "<=",
        CmpOp::Gt => ">",
        CmpOp::GtE => ">=",
        CmpOp::Is => "is",
        CmpOp::IsNot => "is not",
        CmpOp::In => "in",
        CmpOp::NotIn => "not in",
    }
}

fn prec(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::Lambda { .. } => P_LAMBDA,
        ExprKind::IfExp { .. } => P_IFEXP,
        ExprKind::BoolOp { op: BoolOp::Or, .. } => P_OR,
        ExprKind::BoolOp {
            op: BoolOp::And, ..
        } => P_AND,
        ExprKind::UnaryOp {
            op: UnaryOp::Not, ..
        } => P_NOT,
        ExprKind::Compare { .. } => P_CMP,
        ExprKind::BinOp { op, .. } => binop_prec(*op),
        ExprKind::UnaryOp { .. } => P_UNARY,
        // Always printed in their own parentheses or brackets.
        _ => P_ATOM,
    }
}

/// A Python string literal for `s`, quoted with `quote`.
fn quote_str(s: &str, quote: char) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push(quote);
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c == quote => {
                out.push('\\');
                out.push(c);
            }
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                out.push_str(&format!("\\x{:02x}", c as u32))
            }
            c => out.push(c),
        }
    }
    out.push(quote);
    out
}

fn float_str(v: f64) -> String {
    if v.is_infinite() {
        return "1e999".into();
    }
    if v.is_nan() {
        return "(1e999 - 1e999)".into();
    }
    // Rust prints the shortest round-trip form (`0.001`, `1e16`, `1e-7`),
    // all valid Python float literals; the exponent form is used when it
    // is clearly shorter (`2.1e11` rather than `210000000000.0`).
    let plain = format!("{v:?}");
    let exp = format!("{v:e}");
    if exp.len() + 2 < plain.len() {
        exp
    } else {
        plain
    }
}

struct Printer<'s> {
    out: String,
    comments: Vec<(usize, String)>,
    next_comment: usize,
    source: Option<&'s str>,
    /// Rendering on one line (no width checks, no line breaks).
    no_break: bool,
    /// Indentation (columns) of the output line being built.
    line_indent: usize,
}

impl Printer<'_> {
    fn line(&mut self, indent: usize, text: &str) {
        for _ in 0..indent {
            self.out.push_str(INDENT);
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn flush_comments(&mut self, before: usize, indent: usize) {
        while let Some((pos, text)) = self.comments.get(self.next_comment) {
            if *pos >= before {
                break;
            }
            let text = text.clone();
            self.line(indent, &text);
            self.next_comment += 1;
        }
    }

    /// A comment on the same source line as the end of a simple statement
    /// stays at the end of its (last) output line.
    fn trailing_comment(&mut self, s: &Stmt) {
        let compound = matches!(
            s.kind,
            StmtKind::If { .. }
                | StmtKind::For { .. }
                | StmtKind::While { .. }
                | StmtKind::FunctionDef { .. }
                | StmtKind::ClassDef { .. }
                | StmtKind::Try { .. }
                | StmtKind::With { .. }
        );
        let (Some(src), Some((pos, text))) = (self.source, self.comments.get(self.next_comment))
        else {
            return;
        };
        let end = s.span.end as usize;
        if compound || *pos < end || src.get(end..*pos).is_none_or(|gap| gap.contains('\n')) {
            return;
        }
        let text = text.clone();
        if self.out.ends_with('\n') {
            self.out.pop();
        }
        self.out.push_str("  ");
        self.out.push_str(&text);
        self.out.push('\n');
        self.next_comment += 1;
    }

    /// Was there a blank line in the source between `from` and `to`?
    fn blank_between(&self, from: usize, to: usize) -> bool {
        let Some(src) = self.source else { return false };
        // Start from the end of the previous statement's last token.
        let from = src.get(..from).map_or(from, |s| s.trim_end().len());
        let Some(gap) = src.get(from..to) else {
            return false;
        };
        let mut lines = gap.split('\n');
        lines.next();
        let mut inner: Vec<&str> = lines.collect();
        inner.pop();
        inner.iter().any(|l| l.trim().is_empty())
    }

    fn body(&mut self, stmts: &[Stmt], indent: usize, mut prev_end: usize) {
        for (i, s) in stmts.iter().enumerate() {
            let start = s.span.start as usize;
            if i > 0 && self.blank_between(prev_end, start) {
                self.out.push('\n');
            }
            self.flush_comments(start, indent);
            self.stmt(s, indent);
            self.trailing_comment(s);
            // Comments inside the statement's span move above the next statement.
            prev_end = s.span.end as usize;
        }
    }

    fn suite(&mut self, header: String, body: &[Stmt], indent: usize, header_end: usize) {
        self.line(indent, &header);
        self.body(body, indent + 1, header_end);
    }

    fn stmt(&mut self, s: &Stmt, ind: usize) {
        let col = ind * INDENT.len();
        self.line_indent = col;
        let start = s.span.start as usize;
        match &s.kind {
            StmtKind::Expr { value } => {
                let t = self.top(value, col);
                self.line(ind, &t);
            }
            StmtKind::Assign { targets, value } => {
                let mut t = String::new();
                for target in targets {
                    t.push_str(&self.target(target));
                    t.push_str(" = ");
                }
                let v = self.top(value, col + t.len());
                t.push_str(&v);
                self.line(ind, &t);
            }
            StmtKind::AugAssign { target, op, value } => {
                let mut t = format!("{} {}= ", self.expr(target, col, P_LAMBDA), binop_str(*op));
                let v = self.top(value, col + t.len());
                t.push_str(&v);
                self.line(ind, &t);
            }
            StmtKind::AnnAssign {
                target,
                annotation,
                value,
            } => {
                let mut t = format!(
                    "{}: {}",
                    self.expr(target, col, P_LAMBDA),
                    self.expr(annotation, col, P_LAMBDA)
                );
                if let Some(v) = value {
                    t.push_str(" = ");
                    let v = self.top(v, col + t.len());
                    t.push_str(&v);
                }
                self.line(ind, &t);
            }
            StmtKind::If { test, body, orelse } => {
                self.if_chain("if", test, body, orelse, ind, start)
            }
            StmtKind::For {
                target,
                iter,
                body,
                orelse,
            } => {
                let h = format!(
                    "for {} in {}:",
                    self.target(target),
                    self.expr(iter, col, P_LAMBDA)
                );
                self.suite(h, body, ind, start);
                self.else_block(orelse, ind, body);
            }
            StmtKind::While { test, body, orelse } => {
                let h = format!("while {}:", self.expr(test, col, P_LAMBDA));
                self.suite(h, body, ind, start);
                self.else_block(orelse, ind, body);
            }
            StmtKind::FunctionDef {
                name,
                params,
                body,
                decorators,
            } => {
                for d in decorators {
                    let t = format!("@{}", self.expr(d, col, P_LAMBDA));
                    self.line(ind, &t);
                }
                let h = format!("def {}({}):", name.name, self.params(params, true));
                self.suite(h, body, ind, start);
            }
            StmtKind::ClassDef {
                name,
                bases,
                body,
                decorators,
            } => {
                for d in decorators {
                    let t = format!("@{}", self.expr(d, col, P_LAMBDA));
                    self.line(ind, &t);
                }
                let h = if bases.is_empty() {
                    format!("class {}:", name.name)
                } else {
                    let args: Vec<String> = bases.iter().map(|a| self.arg(a, col)).collect();
                    format!("class {}({}):", name.name, args.join(", "))
                };
                self.suite(h, body, ind, start);
            }
            StmtKind::Return { value } => {
                let t = match value {
                    Some(v) => format!("return {}", self.top(v, col + 7)),
                    None => "return".into(),
                };
                self.line(ind, &t);
            }
            StmtKind::Import { names } => {
                let t = format!("import {}", aliases(names));
                self.line(ind, &t);
            }
            StmtKind::ImportFrom {
                module,
                level,
                names,
                star,
            } => {
                let m = format!(
                    "{}{}",
                    ".".repeat(*level as usize),
                    module.as_deref().unwrap_or("")
                );
                let what = if *star {
                    "*".to_string()
                } else {
                    aliases(names)
                };
                self.line(ind, &format!("from {m} import {what}"));
            }
            StmtKind::Try {
                body,
                handlers,
                orelse,
                finalbody,
            } => {
                self.suite("try:".into(), body, ind, start);
                for h in handlers {
                    let mut head = "except".to_string();
                    if let Some(t) = &h.typ {
                        head.push(' ');
                        head.push_str(&self.expr(t, col, P_LAMBDA));
                    }
                    if let Some(n) = &h.name {
                        head.push_str(" as ");
                        head.push_str(&n.name);
                    }
                    head.push(':');
                    self.suite(head, &h.body, ind, h.span.start as usize);
                }
                self.else_block(orelse, ind, body);
                if !finalbody.is_empty() {
                    self.suite("finally:".into(), finalbody, ind, start);
                }
            }
            StmtKind::With { items, body } => {
                let items: Vec<String> = items
                    .iter()
                    .map(|i| match &i.target {
                        Some(t) => format!(
                            "{} as {}",
                            self.expr(&i.context, col, P_LAMBDA),
                            self.expr(t, col, P_BITOR)
                        ),
                        None => self.expr(&i.context, col, P_LAMBDA),
                    })
                    .collect();
                self.suite(format!("with {}:", items.join(", ")), body, ind, start);
            }
            StmtKind::Raise { exc, cause } => {
                let mut t = "raise".to_string();
                if let Some(e) = exc {
                    t.push(' ');
                    t.push_str(&self.expr(e, col, P_LAMBDA));
                }
                if let Some(c) = cause {
                    t.push_str(" from ");
                    t.push_str(&self.expr(c, col, P_LAMBDA));
                }
                self.line(ind, &t);
            }
            StmtKind::Assert { test, msg } => {
                let mut t = format!("assert {}", self.expr(test, col, P_LAMBDA));
                if let Some(m) = msg {
                    t.push_str(", ");
                    t.push_str(&self.expr(m, col, P_LAMBDA));
                }
                self.line(ind, &t);
            }
            StmtKind::Del { targets } => {
                let t: Vec<String> = targets.iter().map(|e| self.expr(e, col, P_BITOR)).collect();
                self.line(ind, &format!("del {}", t.join(", ")));
            }
            StmtKind::Global { names } | StmtKind::Nonlocal { names } => {
                let kw = if matches!(s.kind, StmtKind::Global { .. }) {
                    "global"
                } else {
                    "nonlocal"
                };
                let n: Vec<&str> = names.iter().map(|n| n.name.as_str()).collect();
                self.line(ind, &format!("{kw} {}", n.join(", ")));
            }
            StmtKind::Pass => self.line(ind, "pass"),
            StmtKind::Break => self.line(ind, "break"),
            StmtKind::Continue => self.line(ind, "continue"),
            StmtKind::Print {
                dest,
                values,
                newline,
            } => {
                // Python 2 form, kept so that the AST round-trips.
                let mut parts = Vec::new();
                if let Some(d) = dest {
                    parts.push(format!(">>{}", self.expr(d, col, P_LAMBDA)));
                }
                for v in values {
                    parts.push(self.expr(v, col, P_LAMBDA));
                }
                let mut t = format!("print {}", parts.join(", "));
                if !newline {
                    t.push(',');
                }
                self.line(ind, &t);
            }
            StmtKind::Exec {
                code,
                globals,
                locals,
            } => {
                let mut t = format!("exec {}", self.expr(code, col, P_BITOR));
                if let Some(g) = globals {
                    t.push_str(" in ");
                    t.push_str(&self.expr(g, col, P_LAMBDA));
                    if let Some(l) = locals {
                        t.push_str(", ");
                        t.push_str(&self.expr(l, col, P_LAMBDA));
                    }
                }
                self.line(ind, &t);
            }
        }
    }

    fn if_chain(
        &mut self,
        kw: &str,
        test: &Expr,
        body: &[Stmt],
        orelse: &[Stmt],
        ind: usize,
        start: usize,
    ) {
        let h = format!("{kw} {}:", self.expr(test, ind * 4, P_LAMBDA));
        self.suite(h, body, ind, start);
        match orelse {
            [] => {}
            [Stmt {
                kind:
                    StmtKind::If {
                        test,
                        body: b,
                        orelse: o,
                    },
                span,
            }] => self.if_chain("elif", test, b, o, ind, span.start as usize),
            _ => {
                let end = body.last().map_or(start, |s| s.span.end as usize);
                self.suite("else:".into(), orelse, ind, end);
            }
        }
    }

    fn else_block(&mut self, orelse: &[Stmt], ind: usize, body: &[Stmt]) {
        if !orelse.is_empty() {
            let end = body.last().map_or(0, |s| s.span.end as usize);
            self.suite("else:".into(), orelse, ind, end);
        }
    }

    fn params(&mut self, params: &[Param], annotations: bool) -> String {
        let mut out = Vec::new();
        for p in params {
            let mut t = match p.kind {
                ParamKind::Normal => p.name.name.to_string(),
                ParamKind::VarArgs => format!("*{}", p.name.name),
                ParamKind::KwArgs => format!("**{}", p.name.name),
                ParamKind::KwOnlyMarker => "*".into(),
                ParamKind::PosOnlyMarker => "/".into(),
            };
            if annotations {
                if let Some(a) = &p.annotation {
                    t.push_str(": ");
                    t.push_str(&self.expr(a, 0, P_LAMBDA));
                }
            }
            if let Some(d) = &p.default {
                if annotations && p.annotation.is_some() {
                    t.push_str(" = ");
                } else {
                    t.push('=');
                }
                t.push_str(&self.expr(d, 0, P_LAMBDA));
            }
            out.push(t);
        }
        out.join(", ")
    }

    /// A statement-level expression: a bare tuple or yield needs no parentheses.
    fn top(&mut self, e: &Expr, col: usize) -> String {
        match &e.kind {
            ExprKind::Yield { .. } | ExprKind::YieldFrom { .. } => self.yield_expr(e, col),
            _ => self.expr(e, col, P_LAMBDA),
        }
    }

    fn yield_expr(&mut self, e: &Expr, col: usize) -> String {
        match &e.kind {
            ExprKind::Yield { value: Some(v) } => format!("yield {}", self.top(v, col + 6)),
            ExprKind::Yield { value: None } => "yield".into(),
            ExprKind::YieldFrom { value } => {
                format!("yield from {}", self.expr(value, col + 11, P_LAMBDA))
            }
            _ => self.expr(e, col, P_LAMBDA),
        }
    }

    /// An expression at column `col`, parenthesized if it binds looser than `min`.
    fn expr(&mut self, e: &Expr, col: usize, min: u8) -> String {
        if prec(e) < min {
            return format!("({})", self.expr(e, col + 1, P_LAMBDA));
        }
        let flat = self.flat(e);
        if self.no_break || col + flat.len() <= WIDTH || flat.contains('\n') {
            return flat;
        }
        self.broken(e, col).unwrap_or(flat)
    }

    /// One-line rendering.
    fn flat(&mut self, e: &Expr) -> String {
        let saved = self.no_break;
        // Width checks are disabled while rendering flat.
        self.no_break = true;
        let s = self.render(e);
        self.no_break = saved;
        s
    }

    /// A multi-line rendering of a long call or display, one element per line.
    fn broken(&mut self, e: &Expr, col: usize) -> Option<String> {
        let outer = self.line_indent;
        let ind = outer + INDENT.len();
        self.line_indent = ind;
        let result = self.broken_items(e, col, ind);
        self.line_indent = outer;
        let (open, items, close) = result?;
        if items.is_empty() {
            return None;
        }
        let pad = " ".repeat(ind);
        let mut s = open;
        s.push('\n');
        for item in items {
            s.push_str(&pad);
            s.push_str(&item);
            s.push_str(",\n");
        }
        s.push_str(&" ".repeat(outer));
        s.push_str(close);
        Some(s)
    }

    #[allow(clippy::type_complexity)]
    fn broken_items(
        &mut self,
        e: &Expr,
        col: usize,
        ind: usize,
    ) -> Option<(String, Vec<String>, &'static str)> {
        let (open, items, close) = match &e.kind {
            ExprKind::Call { func, args } => {
                let f = self.expr(func, col, P_ATOM);
                let items: Vec<String> = args.iter().map(|a| self.arg(a, ind)).collect();
                (format!("{f}("), items, ")")
            }
            ExprKind::List { elts } => ("[".to_string(), self.items(elts, ind), "]"),
            ExprKind::Tuple { elts } if !elts.is_empty() => {
                ("(".to_string(), self.items(elts, ind), ")")
            }
            ExprKind::Set { elts } => ("{".to_string(), self.items(elts, ind), "}"),
            ExprKind::Dict { items } => {
                let items = items
                    .iter()
                    .map(|i| match &i.key {
                        Some(k) => {
                            let k = self.expr(k, ind, P_LAMBDA);
                            let v = self.expr(&i.value, ind + k.len() + 2, P_LAMBDA);
                            format!("{k}: {v}")
                        }
                        None => format!("**{}", self.expr(&i.value, ind + 2, P_BITOR)),
                    })
                    .collect();
                ("{".to_string(), items, "}")
            }
            _ => return None,
        };
        Some((open, items, close))
    }

    fn items(&mut self, elts: &[Expr], col: usize) -> Vec<String> {
        elts.iter().map(|e| self.expr(e, col, P_LAMBDA)).collect()
    }

    fn arg(&mut self, a: &Arg, col: usize) -> String {
        match &a.kind {
            ArgKind::Positional { value } => self.expr(value, col, P_LAMBDA),
            ArgKind::Keyword { name, value } => {
                let v = self.expr(value, col + name.name.len() + 1, P_LAMBDA);
                format!("{}={v}", name.name)
            }
            ArgKind::Star { value } => format!("*{}", self.expr(value, col + 1, P_LAMBDA)),
            ArgKind::DoubleStar { value } => format!("**{}", self.expr(value, col + 2, P_LAMBDA)),
        }
    }

    fn comps(&mut self, gens: &[Comprehension]) -> String {
        let mut s = String::new();
        for g in gens {
            s.push_str(&format!(
                " for {} in {}",
                self.target(&g.target),
                self.render_min(&g.iter, P_OR)
            ));
            for c in &g.ifs {
                s.push_str(&format!(" if {}", self.render_min(c, P_OR)));
            }
        }
        s
    }

    /// An assignment or loop target: a tuple needs no parentheses.
    fn target(&mut self, e: &Expr) -> String {
        match &e.kind {
            ExprKind::Tuple { elts } if elts.len() > 1 => self.join(elts),
            _ => self.render_min(e, P_BITOR),
        }
    }

    fn render_min(&mut self, e: &Expr, min: u8) -> String {
        if prec(e) < min {
            format!("({})", self.render(e))
        } else {
            self.render(e)
        }
    }

    fn join(&mut self, elts: &[Expr]) -> String {
        elts.iter()
            .map(|e| self.render_min(e, P_LAMBDA))
            .collect::<Vec<_>>()
            .join(", ")
    }

    fn string(&self, s: &str) -> String {
        if s.contains('"') && !s.contains('\'') {
            quote_str(s, '\'')
        } else {
            quote_str(s, '"')
        }
    }

    /// Render without line breaks.
    fn render(&mut self, e: &Expr) -> String {
        match &e.kind {
            ExprKind::Name { id } => id.to_string(),
            ExprKind::Int { value } => value.to_string(),
            ExprKind::Float { value } => float_str(*value),
            ExprKind::Imag { value } => format!("{}j", float_str(*value)),
            ExprKind::Str { value } => self.string(value),
            ExprKind::Bytes { value } => {
                let mut s = String::from("b\"");
                for &b in value {
                    match b {
                        b'\\' => s.push_str("\\\\"),
                        b'"' => s.push_str("\\\""),
                        b'\n' => s.push_str("\\n"),
                        b'\r' => s.push_str("\\r"),
                        b'\t' => s.push_str("\\t"),
                        0x20..=0x7e => s.push(b as char),
                        _ => s.push_str(&format!("\\x{b:02x}")),
                    }
                }
                s.push('"');
                s
            }
            ExprKind::FString { parts } => format!("f\"{}\"", self.fparts(parts)),
            ExprKind::Bool { value } => if *value { "True" } else { "False" }.into(),
            ExprKind::None => "None".into(),
            ExprKind::Ellipsis => "...".into(),
            ExprKind::List { elts } => format!("[{}]", self.join(elts)),
            ExprKind::Tuple { elts } => match elts.len() {
                1 => format!("({},)", self.render_min(&elts[0], P_LAMBDA)),
                _ => format!("({})", self.join(elts)),
            },
            ExprKind::Set { elts } => format!("{{{}}}", self.join(elts)),
            ExprKind::Dict { items } => {
                let items: Vec<String> = items
                    .iter()
                    .map(|i| match &i.key {
                        Some(k) => format!(
                            "{}: {}",
                            self.render_min(k, P_LAMBDA),
                            self.render_min(&i.value, P_LAMBDA)
                        ),
                        None => format!("**{}", self.render_min(&i.value, P_BITOR)),
                    })
                    .collect();
                format!("{{{}}}", items.join(", "))
            }
            ExprKind::Attribute { value, attr } => {
                let v = match value.kind {
                    // `1 .real`: an int literal followed by `.` would read as a float.
                    ExprKind::Int { .. } => format!("({})", self.render(value)),
                    _ => self.render_min(value, P_ATOM),
                };
                format!("{v}.{}", attr.name)
            }
            ExprKind::Subscript { value, index } => {
                let idx = match &index.kind {
                    ExprKind::Tuple { elts } if !elts.is_empty() => {
                        let mut s = elts
                            .iter()
                            .map(|e| self.render_min(e, P_LAMBDA))
                            .collect::<Vec<_>>()
                            .join(", ");
                        if elts.len() == 1 {
                            s.push(',');
                        }
                        s
                    }
                    _ => self.render_min(index, P_LAMBDA),
                };
                format!("{}[{idx}]", self.render_min(value, P_ATOM))
            }
            ExprKind::Slice { lower, upper, step } => {
                let mut s = String::new();
                if let Some(l) = lower {
                    s.push_str(&self.render_min(l, P_LAMBDA));
                }
                s.push(':');
                if let Some(u) = upper {
                    s.push_str(&self.render_min(u, P_LAMBDA));
                }
                if let Some(st) = step {
                    s.push(':');
                    s.push_str(&self.render_min(st, P_LAMBDA));
                }
                s
            }
            ExprKind::Call { func, args } => {
                if let [Arg {
                    kind: ArgKind::Positional { value },
                    ..
                }] = args.as_slice()
                {
                    if let ExprKind::GeneratorExp { elt, generators } = &value.kind {
                        let g = format!(
                            "{}{}",
                            self.render_min(elt, P_LAMBDA),
                            self.comps(generators)
                        );
                        return format!("{}({g})", self.render_min(func, P_ATOM));
                    }
                }
                let args: Vec<String> = args.iter().map(|a| self.arg(a, 0)).collect();
                format!("{}({})", self.render_min(func, P_ATOM), args.join(", "))
            }
            ExprKind::BinOp { left, op, right } => {
                let p = binop_prec(*op);
                let (lp, rp) = if *op == BinOp::Pow {
                    (P_POW + 1, P_UNARY)
                } else {
                    (p, p + 1)
                };
                format!(
                    "{} {} {}",
                    self.render_min(left, lp),
                    binop_str(*op),
                    self.render_min(right, rp)
                )
            }
            ExprKind::UnaryOp { op, operand } => match op {
                UnaryOp::Not => format!("not {}", self.render_min(operand, P_NOT)),
                UnaryOp::Neg => format!("-{}", self.render_min(operand, P_UNARY)),
                UnaryOp::Pos => format!("+{}", self.render_min(operand, P_UNARY)),
                UnaryOp::Invert => format!("~{}", self.render_min(operand, P_UNARY)),
            },
            ExprKind::BoolOp { op, values } => {
                let (p, word) = match op {
                    BoolOp::And => (P_AND, " and "),
                    BoolOp::Or => (P_OR, " or "),
                };
                values
                    .iter()
                    .map(|v| self.render_min(v, p + 1))
                    .collect::<Vec<_>>()
                    .join(word)
            }
            ExprKind::Compare { left, ops } => {
                let mut s = self.render_min(left, P_BITOR);
                for (op, e) in ops {
                    s.push(' ');
                    s.push_str(cmp_str(*op));
                    s.push(' ');
                    s.push_str(&self.render_min(e, P_BITOR));
                }
                s
            }
            ExprKind::IfExp { test, body, orelse } => format!(
                "{} if {} else {}",
                self.render_min(body, P_OR),
                self.render_min(test, P_OR),
                self.render_min(orelse, P_IFEXP)
            ),
            ExprKind::Lambda { params, body } => {
                let p = self.params(params, false);
                let b = self.render_min(body, P_LAMBDA);
                if p.is_empty() {
                    format!("lambda: {b}")
                } else {
                    format!("lambda {p}: {b}")
                }
            }
            ExprKind::ListComp { elt, generators } => {
                format!(
                    "[{}{}]",
                    self.render_min(elt, P_LAMBDA),
                    self.comps(generators)
                )
            }
            ExprKind::SetComp { elt, generators } => {
                format!(
                    "{{{}{}}}",
                    self.render_min(elt, P_LAMBDA),
                    self.comps(generators)
                )
            }
            ExprKind::GeneratorExp { elt, generators } => {
                format!(
                    "({}{})",
                    self.render_min(elt, P_LAMBDA),
                    self.comps(generators)
                )
            }
            ExprKind::DictComp {
                key,
                value,
                generators,
            } => format!(
                "{{{}: {}{}}}",
                self.render_min(key, P_LAMBDA),
                self.render_min(value, P_LAMBDA),
                self.comps(generators)
            ),
            ExprKind::Starred { value } => format!("*{}", self.render_min(value, P_BITOR)),
            ExprKind::Yield { .. } | ExprKind::YieldFrom { .. } => {
                format!("({})", self.yield_expr(e, 0))
            }
            ExprKind::Await { value } => format!("await {}", self.render_min(value, P_ATOM)),
            ExprKind::NamedExpr { target, value } => {
                format!("({} := {})", target.name, self.render_min(value, P_LAMBDA))
            }
            ExprKind::Repr { value } => format!("`{}`", self.render_min(value, P_LAMBDA)),
        }
    }

    fn fparts(&mut self, parts: &[FStringPart]) -> String {
        let mut s = String::new();
        for p in parts {
            match p {
                FStringPart::Literal { value } => {
                    let q = quote_str(value, '"');
                    let inner = &q[1..q.len() - 1];
                    s.push_str(&inner.replace('{', "{{").replace('}', "}}"));
                }
                FStringPart::Field {
                    value,
                    conversion,
                    format_spec,
                    debug,
                } => {
                    let v = self.render_field(value);
                    s.push('{');
                    // A leading `{` would read as an escaped brace.
                    if v.starts_with('{') {
                        s.push(' ');
                    }
                    s.push_str(&v);
                    if *debug {
                        s.push('=');
                    }
                    if let Some(c) = conversion {
                        s.push('!');
                        s.push(*c);
                    }
                    if !format_spec.is_empty() {
                        s.push(':');
                        s.push_str(&self.fparts(format_spec));
                    }
                    s.push('}');
                }
            }
        }
        s
    }

    /// An f-string field's expression: nested strings use single quotes.
    fn render_field(&mut self, e: &Expr) -> String {
        let s = self.render_min(e, P_LAMBDA);
        // Strings inside the field were rendered with double quotes; swap them
        // for single quotes so they do not end the f-string (pre-3.12 rule).
        swap_string_quotes(&s)
    }
}

/// Re-quote double-quoted string literals of a rendered expression with single quotes.
fn swap_string_quotes(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '"' {
            if c == '\'' {
                // A single-quoted literal: copy verbatim.
                out.push(c);
                while let Some(d) = chars.next() {
                    out.push(d);
                    if d == '\\' {
                        if let Some(e) = chars.next() {
                            out.push(e);
                        }
                    } else if d == '\'' {
                        break;
                    }
                }
                continue;
            }
            out.push(c);
            continue;
        }
        let mut body = String::new();
        while let Some(d) = chars.next() {
            if d == '\\' {
                if let Some(e) = chars.next() {
                    if e == '"' {
                        body.push('"');
                    } else {
                        body.push('\\');
                        body.push(e);
                    }
                }
            } else if d == '"' {
                break;
            } else {
                body.push(d);
            }
        }
        out.push('\'');
        out.push_str(&body.replace('\'', "\\'"));
        out.push('\'');
    }
    out
}

fn aliases(names: &[Alias]) -> String {
    names
        .iter()
        .map(|a| match &a.asname {
            Some(n) => format!("{} as {}", a.name, n.name),
            None => a.name.clone(),
        })
        .collect::<Vec<_>>()
        .join(", ")
}
