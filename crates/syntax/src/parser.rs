//! From pest pairs to the spanned AST.
//!
//! The grammar (`grammar/comm.pest`) delimits the constructs; this module
//! gives them meaning: operator precedence (a Pratt parser over the flat
//! operand/operator sequence of `or_expr`), literal values, assignment
//! targets, f-string fields.

use crate::ast::*;
use crate::codemap::Span;
use crate::literals;
use crate::tree::{Children, Node, Tree};
use crate::ParseError;
use pest::Parser as _;

#[derive(pest_derive::Parser)]
#[grammar = "../../grammar/comm.pest"]
pub struct CommParser;

type P<'t> = Node<'t>;
type R<T> = Result<T, ParseError>;

/// Files are parsed in pieces of about this many bytes, each ending at the
/// end of a top-level statement: pest's token queue and the flat tree
/// (about 20–80 bytes per input byte) then exist for one piece at a time,
/// and the memory of a parse follows the size of the AST. Nearly every
/// command file is a single piece.
const CHUNK_BYTES: usize = 1 << 20;

/// Parse a whole file into its AST (no post-parse validation).
pub fn parse_module_unchecked(source: &str) -> R<Module> {
    parse_module_unchecked_at(source, 0)
}

/// [`parse_module_unchecked`] with every span shifted by `base` (a file at
/// that offset of a several-file code map).
pub fn parse_module_unchecked_at(source: &str, base: usize) -> R<Module> {
    // pest reads a copy whose logical line ends are marked (same offsets);
    // the tree and the builder read the original text.
    let marked = crate::logical::mark_line_ends(source);
    let mut body = Vec::new();
    let mut start = 0;
    loop {
        let end = chunk_end(marked.as_bytes(), start);
        if let Err(e) = parse_piece(source, &marked, (start, end), base, &mut body) {
            if end == source.len() {
                return Err(e);
            }
            // A failure in a piece: the rest of the file in one piece gives
            // the error exactly as a parse of the whole file would (it may
            // also succeed, if the cut was not a statement boundary).
            parse_piece(source, &marked, (start, source.len()), base, &mut body)?;
            break;
        }
        if end == source.len() {
            break;
        }
        start = end;
    }
    Ok(Module {
        body,
        span: Span::new(base, base + source.len()),
    })
}

/// Parses `source[start..end]` (whole top-level statements) and appends its
/// statements to `body` (nothing on failure); spans shifted by `base` (the
/// file's offset in a several-file code map).
fn parse_piece(
    source: &str,
    marked: &str,
    (start, end): (usize, usize),
    base: usize,
    body: &mut Vec<Stmt>,
) -> R<()> {
    let text = &source[start..end];
    let at = base + start;
    let pairs = CommParser::parse(Rule::module, &marked[start..end]).map_err(|e| {
        let mut pe = crate::error::from_pest(&e, text);
        pe.span = Span::new(at + pe.span.start as usize, at + pe.span.end as usize);
        pe
    })?;
    let tree = Tree::new(pairs, text);
    let builder = Builder {
        base: at,
        source: text,
    };
    if let Some(module) = tree.top().next() {
        let stmts = builder.stmts(module.into_inner())?;
        body.extend(stmts);
    }
    Ok(())
}

/// Where the piece that starts at `start` ends: the start of the first
/// top-level statement line at least [`CHUNK_BYTES`] further (a line after
/// a marked line end that starts at column 0 with a name that is not a
/// continuation clause, `def`, `class` or a decorator's target), or the end
/// of the file.
fn chunk_end(marked: &[u8], start: usize) -> usize {
    let n = marked.len();
    let mut i = start.saturating_add(CHUNK_BYTES);
    while i < n {
        let Some(k) = marked[i..]
            .iter()
            .position(|&b| b == crate::logical::LINE_END)
        else {
            return n;
        };
        let line = i + k + 1;
        if line < n && starts_statement(&marked[line..]) {
            return line;
        }
        i = line;
    }
    n
}

/// Whether a line (at column 0 after a logical line end) surely starts a
/// new top-level statement.
fn starts_statement(line: &[u8]) -> bool {
    let word_len = line
        .iter()
        .position(|b| !(b.is_ascii_alphanumeric() || *b == b'_'))
        .unwrap_or(line.len());
    let word = &line[..word_len];
    let first_ok = line
        .first()
        .is_some_and(|b| b.is_ascii_alphabetic() || *b == b'_');
    first_ok
        && !matches!(
            word,
            b"else" | b"elif" | b"except" | b"finally" | b"def" | b"class" | b"async"
        )
}

fn err(span: Span, message: impl Into<String>) -> ParseError {
    ParseError {
        span,
        message: message.into(),
    }
}

/// Builds AST nodes; `base` shifts spans of sub-parses (f-string fields).
struct Builder<'s> {
    base: usize,
    /// The text the pairs come from (the file, or an f-string field).
    source: &'s str,
}

impl Builder<'_> {
    /// A pair's span, without the trailing whitespace and comments that
    /// pest's implicit whitespace consumed after its last element (an
    /// expression consumes the whitespace after it, so that the rule that
    /// follows need not skip it again).
    fn span(&self, pair: &P) -> Span {
        let (start, end) = (pair.start(), pair.end());
        // Most pairs end on their last token: nothing to trim. A pair that
        // ends on another character can only end with a comment if a line
        // break follows it (a comment runs to the end of its line).
        // (Byte tests: no `str` slicing with its boundary checks here.)
        let bytes = self.source.as_bytes();
        let ends_blank = end > start
            && bytes
                .get(end - 1)
                .is_some_and(|b| matches!(b, b' ' | b'\t' | b'\n' | b'\r' | b'\x0C' | b'\\'));
        let at_line_end = bytes.get(end).is_none_or(|b| matches!(b, b'\n' | b'\r'));
        if !ends_blank && !at_line_end {
            return Span::new(self.base + start, self.base + end);
        }
        let text = &self.source[start..end];
        let mut text = text.trim_end_matches([' ', '\t', '\n', '\r', '\x0C', '\\']);
        loop {
            let line_start = text.rfind('\n').map_or(0, |i| i + 1);
            let Some(hash) = comment_start(&text[line_start..]) else {
                break;
            };
            let cut =
                text[..line_start + hash].trim_end_matches([' ', '\t', '\n', '\r', '\x0C', '\\']);
            if cut.is_empty() || cut.len() == text.len() {
                break;
            }
            text = cut;
        }
        Span::new(self.base + start, self.base + start + text.len())
    }

    fn ident(&self, pair: P) -> Ident {
        Ident {
            name: Text::new(pair.as_str()),
            span: self.span(&pair),
        }
    }

    /// The name of a `kwarg_name` token (`NAME=`, `NAME =`): what precedes
    /// the whitespace or the `=`.
    fn kwarg_name(&self, pair: P) -> Ident {
        let text = pair.as_str();
        // A byte scan: the delimiters are ASCII, never inside a multi-byte char.
        let len = text
            .bytes()
            .position(|b| matches!(b, b' ' | b'\t' | b'=' | b'\\' | b'#' | b'\n' | b'\r' | 0x0C))
            .unwrap_or(text.len());
        let start = self.base + pair.start();
        Ident {
            name: Text::new(&text[..len]),
            span: Span::new(start, start + len),
        }
    }

    // ------------------------------------------------------------ statements

    fn stmts<'i>(&self, pairs: impl Iterator<Item = P<'i>>) -> R<Vec<Stmt>> {
        let mut out = Vec::new();
        for pair in pairs {
            match pair.as_rule() {
                Rule::EOI => {}
                Rule::simple_stmts => {
                    for small in pair.into_inner() {
                        out.push(self.small_stmt(small)?);
                    }
                }
                _ => out.push(self.compound_stmt(pair)?),
            }
        }
        Ok(out)
    }

    /// A suite: an indented `block` or statements on the header's line.
    fn suite(&self, pair: P) -> R<Vec<Stmt>> {
        match pair.as_rule() {
            Rule::block => self.stmts(pair.into_inner()),
            _ => self.stmts(std::iter::once(pair)),
        }
    }

    fn small_stmt(&self, pair: P) -> R<Stmt> {
        let span = self.span(&pair);
        let rule = pair.as_rule();
        let mut inner = pair.into_inner();
        let kind = match rule {
            Rule::pass_stmt => StmtKind::Pass,
            Rule::break_stmt => StmtKind::Break,
            Rule::continue_stmt => StmtKind::Continue,
            Rule::return_stmt => {
                inner.next();
                StmtKind::Return {
                    value: inner.next().map(|p| self.testlist(p)).transpose()?,
                }
            }
            Rule::global_stmt | Rule::nonlocal_stmt => {
                inner.next();
                let names = inner.map(|p| self.ident(p)).collect();
                if rule == Rule::global_stmt {
                    StmtKind::Global { names }
                } else {
                    StmtKind::Nonlocal { names }
                }
            }
            Rule::del_stmt => {
                inner.next();
                let mut targets = Vec::new();
                if let Some(list) = inner.next() {
                    for p in list.into_inner() {
                        if p.as_rule() != Rule::comma {
                            let t = self.element(p)?;
                            check_target(&t, "delete")?;
                            targets.push(t);
                        }
                    }
                }
                StmtKind::Del { targets }
            }
            Rule::assert_stmt => {
                inner.next();
                let test = self.required_test(inner.next(), span)?;
                let msg = inner.next().map(|p| self.test(p)).transpose()?;
                StmtKind::Assert { test, msg }
            }
            Rule::raise_stmt => {
                inner.next();
                let mut exc = inner.next().map(|p| self.test(p)).transpose()?;
                let mut cause = None;
                if let Some(tail) = inner.next() {
                    let tail_rule = tail.as_rule();
                    let mut parts = tail.into_inner();
                    if tail_rule == Rule::raise_from {
                        parts.next();
                        cause = parts.next().map(|p| self.test(p)).transpose()?;
                    } else if let (Some(e), Some(v)) = (exc.take(), parts.next()) {
                        // Python 2 `raise E, V` means `raise E(V)`.
                        let value = self.test(v)?;
                        let call_span = e.span.merge(value.span);
                        let arg = Arg {
                            span: value.span,
                            kind: ArgKind::Positional { value },
                        };
                        exc = Some(Expr {
                            span: call_span,
                            kind: ExprKind::Call {
                                func: Box::new(e),
                                args: vec![arg],
                            },
                        });
                    }
                }
                StmtKind::Raise { exc, cause }
            }
            Rule::print_stmt => {
                inner.next();
                let mut dest = None;
                let mut values = Vec::new();
                let mut newline = true;
                for p in inner {
                    match p.as_rule() {
                        Rule::print_dest => {
                            dest = p.into_inner().next().map(|t| self.test(t)).transpose()?
                        }
                        Rule::comma => newline = false,
                        _ => values.push(self.test(p)?),
                    }
                }
                StmtKind::Print {
                    dest,
                    values,
                    newline,
                }
            }
            Rule::exec_stmt => {
                inner.next();
                let mut code = self.required_test(inner.next(), span)?;
                let locals = inner.next().map(|p| self.test(p)).transpose()?;
                // `exec code in g` was read as the comparison `code in g`.
                let (code, globals) = match std::mem::replace(&mut code.kind, ExprKind::None) {
                    ExprKind::Compare { left, mut ops }
                        if ops.len() == 1
                            && ops[0].0 == CmpOp::In
                            && code.span.end == ops[0].1.span.end =>
                    {
                        let (_, g) = ops.remove(0);
                        (*left, Some(g))
                    }
                    kind => (
                        Expr {
                            kind,
                            span: code.span,
                        },
                        None,
                    ),
                };
                StmtKind::Exec {
                    code,
                    globals,
                    locals,
                }
            }
            Rule::import_stmt => {
                inner.next();
                let mut names = Vec::new();
                for p in inner {
                    names.push(self.alias(p)?);
                }
                StmtKind::Import { names }
            }
            Rule::from_stmt => {
                let mut level = 0;
                let mut module = None;
                let mut names = Vec::new();
                let mut star = false;
                for p in inner {
                    match p.as_rule() {
                        Rule::import_level => level = p.as_str().len() as u32,
                        Rule::dotted_name => module = Some(dotted(&p)),
                        Rule::import_star => star = true,
                        Rule::import_names => {
                            for a in p.into_inner() {
                                names.push(self.alias(a)?);
                            }
                        }
                        _ => {}
                    }
                }
                StmtKind::ImportFrom {
                    module,
                    level,
                    names,
                    star,
                }
            }
            Rule::expr_stmt => self.expr_stmt(inner)?,
            Rule::yield_stmt => match inner.next() {
                Some(y) => StmtKind::Expr {
                    value: self.yield_expr(y)?,
                },
                None => return Err(err(span, "expected `yield`")),
            },
            other => {
                return Err(err(
                    span,
                    format!("internal: unexpected statement {other:?}"),
                ))
            }
        };
        Ok(Stmt { kind, span })
    }

    fn required_test(&self, pair: Option<P>, at: Span) -> R<Expr> {
        match pair {
            Some(p) => self.test(p),
            None => Err(err(at, "expected an expression")),
        }
    }

    fn alias(&self, pair: P) -> R<Alias> {
        let span = self.span(&pair);
        let mut inner = pair.into_inner();
        let name = match inner.next() {
            Some(p) if p.as_rule() == Rule::dotted_name => dotted(&p),
            Some(p) => p.as_str().to_string(),
            None => String::new(),
        };
        let asname = inner
            .find(|p| p.as_rule() == Rule::name)
            .map(|p| self.ident(p));
        Ok(Alias { name, asname, span })
    }

    fn expr_stmt(&self, mut inner: Children) -> R<StmtKind> {
        let Some(first) = inner.next() else {
            return Ok(StmtKind::Pass);
        };
        let first = self.testlist(first)?;
        let Some(next) = inner.peek() else {
            return Ok(StmtKind::Expr { value: first });
        };
        match next.as_rule() {
            Rule::augassign => {
                let mut parts = next.into_inner();
                let op = match parts.next().map(|p| p.as_str()) {
                    Some(op) => aug_op(op),
                    None => BinOp::Add,
                };
                check_aug_target(&first)?;
                let value = match parts.next() {
                    Some(p) => self.rhs(p)?,
                    None => return Err(err(first.span, "expected a value")),
                };
                Ok(StmtKind::AugAssign {
                    target: first,
                    op,
                    value,
                })
            }
            Rule::annassign => {
                let mut parts = next.into_inner();
                let annotation = self.required_test(parts.next(), first.span)?;
                let value = parts.next().map(|p| self.rhs(p)).transpose()?;
                check_target(&first, "annotate")?;
                Ok(StmtKind::AnnAssign {
                    target: first,
                    annotation,
                    value,
                })
            }
            _ => {
                let mut targets = vec![first];
                for rhs in inner {
                    if let Some(p) = rhs.into_inner().next() {
                        targets.push(self.rhs(p)?);
                    }
                }
                let Some(value) = targets.pop() else {
                    return Ok(StmtKind::Pass);
                };
                for t in &targets {
                    check_target(t, "assign to")?;
                }
                Ok(StmtKind::Assign { targets, value })
            }
        }
    }

    /// The right-hand side of an assignment: a yield or an expression list.
    fn rhs(&self, pair: P) -> R<Expr> {
        match pair.as_rule() {
            Rule::yield_expr => self.yield_expr(pair),
            _ => self.testlist(pair),
        }
    }

    fn compound_stmt(&self, pair: P) -> R<Stmt> {
        let span = self.span(&pair);
        let rule = pair.as_rule();
        let mut inner = pair.into_inner();
        let kind = match rule {
            Rule::if_stmt => {
                let head = self.head(inner.next(), span)?;
                let test = self.head_test(head, span)?;
                let body = self.next_suite(&mut inner, span)?;
                // `elif` chains become nested `If`s in `orelse`, built from the end.
                let mut clauses = Vec::new();
                let mut orelse = Vec::new();
                for clause in inner {
                    let clause_span = self.span(&clause);
                    let is_elif = clause.as_rule() == Rule::elif_clause;
                    let mut parts = clause.into_inner();
                    let head = self.head(parts.next(), clause_span)?;
                    let suite = self.next_suite(&mut parts, clause_span)?;
                    if is_elif {
                        let test = self.head_test(head, clause_span)?;
                        clauses.push((test, suite, clause_span));
                    } else {
                        orelse = suite;
                    }
                }
                while let Some((test, body, clause_span)) = clauses.pop() {
                    let end = orelse.last().map(|s: &Stmt| s.span).unwrap_or(clause_span);
                    orelse = vec![Stmt {
                        span: clause_span.merge(end),
                        kind: StmtKind::If { test, body, orelse },
                    }];
                }
                StmtKind::If { test, body, orelse }
            }
            Rule::while_stmt => {
                let head = self.head(inner.next(), span)?;
                let test = self.head_test(head, span)?;
                let body = self.next_suite(&mut inner, span)?;
                let orelse = self.else_clause(inner.next(), span)?;
                StmtKind::While { test, body, orelse }
            }
            Rule::for_stmt => {
                let head = self.head(inner.next(), span)?;
                let mut parts = head.into_inner();
                parts.next();
                let target = match parts.next() {
                    Some(p) => self.target_list(p)?,
                    None => return Err(err(span, "expected a loop target")),
                };
                parts.next();
                let iter = match parts.next() {
                    Some(p) => self.testlist(p)?,
                    None => return Err(err(span, "expected an iterable")),
                };
                let body = self.next_suite(&mut inner, span)?;
                let orelse = self.else_clause(inner.next(), span)?;
                StmtKind::For {
                    target,
                    iter,
                    body,
                    orelse,
                }
            }
            Rule::try_stmt => {
                inner.next();
                let body = self.next_suite(&mut inner, span)?;
                let mut handlers = Vec::new();
                let mut orelse = Vec::new();
                let mut finalbody = Vec::new();
                for clause in inner {
                    let clause_span = self.span(&clause);
                    let clause_rule = clause.as_rule();
                    let mut parts = clause.into_inner();
                    let head = self.head(parts.next(), clause_span)?;
                    let suite = self.next_suite(&mut parts, clause_span)?;
                    match clause_rule {
                        Rule::except_clause => {
                            let mut typ = None;
                            let mut name = None;
                            for p in head.into_inner() {
                                match p.as_rule() {
                                    Rule::test => typ = Some(self.test(p)?),
                                    Rule::name => name = Some(self.ident(p)),
                                    _ => {}
                                }
                            }
                            handlers.push(ExceptHandler {
                                typ,
                                name,
                                body: suite,
                                span: clause_span,
                            });
                        }
                        Rule::else_clause => orelse = suite,
                        _ => finalbody = suite,
                    }
                }
                StmtKind::Try {
                    body,
                    handlers,
                    orelse,
                    finalbody,
                }
            }
            Rule::with_stmt => {
                let head = self.head(inner.next(), span)?;
                let mut items = Vec::new();
                for item in head.into_inner().filter(|p| p.as_rule() == Rule::with_item) {
                    let mut parts = item.into_inner();
                    let context = self.required_test(parts.next(), span)?;
                    parts.next();
                    let target = parts.next().map(|p| self.target(p)).transpose()?;
                    items.push(WithItem { context, target });
                }
                let body = self.next_suite(&mut inner, span)?;
                StmtKind::With { items, body }
            }
            Rule::def_stmt => return self.def_stmt(span, inner, Vec::new()),
            Rule::class_stmt => return self.class_stmt(span, inner, Vec::new()),
            Rule::decorated => {
                let mut decorators = Vec::new();
                for p in inner {
                    match p.as_rule() {
                        Rule::decorator => {
                            let test = p
                                .into_inner()
                                .next()
                                .and_then(|line| line.into_inner().next());
                            decorators.push(self.required_test(test, span)?);
                        }
                        Rule::def_stmt => {
                            let mut s = self.def_stmt(span, p.into_inner(), decorators)?;
                            s.span = span;
                            return Ok(s);
                        }
                        Rule::class_stmt => {
                            let mut s = self.class_stmt(span, p.into_inner(), decorators)?;
                            s.span = span;
                            return Ok(s);
                        }
                        _ => {}
                    }
                }
                return Err(err(span, "expected `def` or `class` after decorators"));
            }
            other => {
                return Err(err(
                    span,
                    format!("internal: unexpected statement {other:?}"),
                ))
            }
        };
        Ok(Stmt { kind, span })
    }

    fn head<'i>(&self, pair: Option<P<'i>>, at: Span) -> R<P<'i>> {
        pair.ok_or_else(|| err(at, "internal: missing statement header"))
    }

    /// The test of an `if`/`elif`/`while` header (after its keyword).
    fn head_test(&self, head: P, at: Span) -> R<Expr> {
        let test = head.into_inner().find(|p| p.as_rule() == Rule::test);
        self.required_test(test, at)
    }

    fn next_suite(&self, inner: &mut Children, at: Span) -> R<Vec<Stmt>> {
        match inner.next() {
            Some(p) => self.suite(p),
            None => Err(err(at, "internal: missing block")),
        }
    }

    fn else_clause(&self, clause: Option<P>, at: Span) -> R<Vec<Stmt>> {
        match clause {
            Some(c) => {
                let mut parts = c.into_inner();
                parts.next();
                self.next_suite(&mut parts, at)
            }
            None => Ok(Vec::new()),
        }
    }

    fn def_stmt(&self, span: Span, mut inner: Children, decorators: Vec<Expr>) -> R<Stmt> {
        let head = self.head(inner.next(), span)?;
        let mut name = None;
        let mut params = Vec::new();
        for p in head.into_inner() {
            match p.as_rule() {
                Rule::name => name = Some(self.ident(p)),
                Rule::params => params = self.params(p)?,
                _ => {}
            }
        }
        let name = name.ok_or_else(|| err(span, "expected a function name"))?;
        let body = self.next_suite(&mut inner, span)?;
        Ok(Stmt {
            kind: StmtKind::FunctionDef {
                name,
                params,
                body,
                decorators,
            },
            span,
        })
    }

    fn class_stmt(&self, span: Span, mut inner: Children, decorators: Vec<Expr>) -> R<Stmt> {
        let head = self.head(inner.next(), span)?;
        let mut name = None;
        let mut bases = Vec::new();
        for p in head.into_inner() {
            match p.as_rule() {
                Rule::name => name = Some(self.ident(p)),
                Rule::arglist => bases = self.arglist(p)?,
                _ => {}
            }
        }
        let name = name.ok_or_else(|| err(span, "expected a class name"))?;
        let body = self.next_suite(&mut inner, span)?;
        Ok(Stmt {
            kind: StmtKind::ClassDef {
                name,
                bases,
                body,
                decorators,
            },
            span,
        })
    }

    fn params(&self, pair: P) -> R<Vec<Param>> {
        let mut out = Vec::new();
        for param in pair.into_inner() {
            let p = match param.as_rule() {
                Rule::param | Rule::lambda_param => match param.into_inner().next() {
                    Some(p) => p,
                    None => continue,
                },
                _ => param,
            };
            let span = self.span(&p);
            let rule = p.as_rule();
            let kind = match rule {
                Rule::varargs_param | Rule::lambda_varargs => ParamKind::VarArgs,
                Rule::kwargs_param | Rule::lambda_kwargs => ParamKind::KwArgs,
                Rule::kwonly_marker => ParamKind::KwOnlyMarker,
                Rule::posonly_marker => ParamKind::PosOnlyMarker,
                _ => ParamKind::Normal,
            };
            let marker = p.as_str().to_string();
            let mut name = None;
            let mut default = None;
            let mut annotation = None;
            for part in p.into_inner() {
                match part.as_rule() {
                    Rule::name => name = Some(self.ident(part)),
                    Rule::default => {
                        default = part.into_inner().next().map(|t| self.test(t)).transpose()?
                    }
                    Rule::annotation => {
                        annotation = part.into_inner().next().map(|t| self.test(t)).transpose()?
                    }
                    _ => {}
                }
            }
            let name = name.unwrap_or(Ident {
                name: marker.into(),
                span,
            });
            out.push(Param {
                name,
                kind,
                default,
                annotation,
            });
        }
        Ok(out)
    }

    // ------------------------------------------------------------ expressions

    /// `testlist_star` / `exprlist`: a tuple unless a single element without comma.
    fn testlist(&self, pair: P) -> R<Expr> {
        match pair.as_rule() {
            Rule::testlist_star | Rule::exprlist | Rule::target_list => {}
            _ => return self.element(pair),
        }
        let inner = pair.into_inner();
        // A lone element (nearly every statement's value) needs no vector.
        let mut rest = inner.clone();
        if let (Some(only), None) = (rest.next(), rest.next()) {
            if only.as_rule() != Rule::comma {
                return self.element(only);
            }
        }
        let mut elts = Vec::with_capacity(inner.clone().count());
        let mut comma = false;
        for p in inner {
            if p.as_rule() == Rule::comma {
                comma = true;
            } else {
                elts.push(self.element(p)?);
            }
        }
        if elts.len() == 1 && !comma {
            if let Some(e) = elts.pop() {
                return Ok(e);
            }
        }
        // Only a tuple needs the list's own span (a lone element has its own).
        Ok(Expr {
            kind: ExprKind::Tuple { elts },
            span: self.span(&pair),
        })
    }

    /// One element of a list: an expression, a starred expression or a target.
    fn element(&self, pair: P) -> R<Expr> {
        match pair.as_rule() {
            Rule::test => self.test(pair),
            Rule::or_expr => self.or_expr(pair),
            Rule::star_expr | Rule::star_target => {
                let span = self.span(&pair);
                let value = match pair.into_inner().next() {
                    Some(p) => self.element(p)?,
                    None => return Err(err(span, "expected an expression after `*`")),
                };
                Ok(Expr {
                    kind: ExprKind::Starred {
                        value: Box::new(value),
                    },
                    span,
                })
            }
            Rule::primary => self.primary(pair),
            Rule::target => self.target(pair),
            Rule::namedexpr => self.namedexpr(pair),
            Rule::yield_expr => self.yield_expr(pair),
            Rule::testlist_star | Rule::exprlist | Rule::target_list => self.testlist(pair),
            Rule::test_nocond | Rule::lambdef | Rule::lambdef_nocond => self.test(pair),
            other => Err(err(
                self.span(&pair),
                format!("internal: unexpected expression {other:?}"),
            )),
        }
    }

    fn target_list(&self, pair: P) -> R<Expr> {
        let t = self.testlist(pair)?;
        check_target(&t, "assign to")?;
        Ok(t)
    }

    fn target(&self, pair: P) -> R<Expr> {
        let t = match pair.as_rule() {
            Rule::target => match pair.into_inner().next() {
                Some(p) => self.element(p)?,
                None => return Err(err(Span::default(), "internal: empty target")),
            },
            _ => self.element(pair)?,
        };
        check_target(&t, "assign to")?;
        Ok(t)
    }

    fn test(&self, pair: P) -> R<Expr> {
        match pair.as_rule() {
            Rule::test => {}
            Rule::test_nocond => match pair.into_inner().next() {
                Some(p) => return self.test(p),
                None => return Err(err(Span::default(), "internal: empty test")),
            },
            Rule::lambdef | Rule::lambdef_nocond => return self.lambda(pair),
            _ => return self.element(pair),
        }
        let span = self.span(&pair);
        self.test_items(&mut pair.into_inner(), span)
    }

    /// The children of a `test` (an operand sequence and an optional
    /// conditional, or a lambda), read from `inner`; also the value of a
    /// keyword argument, which has no `test` pair of its own.
    fn test_items(&self, inner: &mut Children, at: Span) -> R<Expr> {
        match inner.peek() {
            Some(first) if first.as_rule() == Rule::lambdef => {
                inner.next();
                return self.lambda(first);
            }
            Some(_) => {}
            None => return Err(err(at, "expected an expression")),
        }
        let body = self.operation(inner)?;
        match inner.next() {
            Some(ternary) => {
                let span = body.span.merge(self.span(&ternary));
                let mut parts = ternary
                    .into_inner()
                    .filter(|p| !matches!(p.as_rule(), Rule::kw_if | Rule::kw_else));
                let test = self.required_test(parts.next(), span)?;
                let orelse = self.required_test(parts.next(), span)?;
                Ok(Expr {
                    kind: ExprKind::IfExp {
                        test: Box::new(test),
                        body: Box::new(body),
                        orelse: Box::new(orelse),
                    },
                    span,
                })
            }
            None => Ok(body),
        }
    }

    fn lambda(&self, pair: P) -> R<Expr> {
        let span = self.span(&pair);
        let mut params = Vec::new();
        let mut body = None;
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::lambda_params => params = self.params(p)?,
                Rule::kw_lambda => {}
                _ => body = Some(self.test(p)?),
            }
        }
        let body = body.ok_or_else(|| err(span, "expected the body of the lambda"))?;
        Ok(Expr {
            kind: ExprKind::Lambda {
                params,
                body: Box::new(body),
            },
            span,
        })
    }

    fn or_expr(&self, pair: P) -> R<Expr> {
        if pair.as_rule() != Rule::or_expr {
            return self.element(pair);
        }
        self.operation(&mut pair.into_inner())
    }

    /// The flat operand/operator sequence of the grammar's `operation`, read
    /// from `inner` up to the first pair that is neither (e.g. a `ternary`),
    /// folded by Python's precedence. A lone operand (the common case: a
    /// keyword's value) skips the folding.
    fn operation(&self, inner: &mut Children) -> R<Expr> {
        let mut items = Vec::new();
        loop {
            while let Some(op) = inner.peek().and_then(|p| prefix_op(p.as_rule())) {
                let span = inner.next().map(|p| self.span(&p)).unwrap_or_default();
                items.push(OpItem::Prefix(op, span));
            }
            let operand = self.operand(inner)?;
            match inner.peek().map(|p| p.as_rule()) {
                Some(Rule::string) => {
                    let span = inner.next().map(|p| self.span(&p)).unwrap_or_default();
                    return Err(err(
                        span,
                        "expected an operator or `,` before this string (adjacent strings concatenate only with each other)",
                    ));
                }
                Some(rule) if infix_prec(rule).is_some() => {
                    inner.next();
                    items.push(OpItem::Operand(operand));
                    items.push(OpItem::Infix(rule));
                }
                _ if items.is_empty() => return Ok(operand),
                _ => {
                    items.push(OpItem::Operand(operand));
                    break;
                }
            }
        }
        let mut items = items.into_iter().peekable();
        fold(&mut items, 0, 0)
    }

    fn primary(&self, pair: P) -> R<Expr> {
        if pair.as_rule() != Rule::primary {
            return self.atom(pair);
        }
        self.operand(&mut pair.into_inner())
    }

    /// An atom and its trailers (calls, subscripts, attributes), read from `inner`.
    fn operand(&self, inner: &mut Children) -> R<Expr> {
        let mut expr = match inner.next() {
            Some(atom) if atom.as_rule() == Rule::string => self.strings(atom, inner)?,
            Some(atom)
                if atom.as_rule() == Rule::name
                    && is_upper_string_prefix(atom.as_str())
                    && inner.peek().is_some_and(|s| {
                        s.as_rule() == Rule::string && s.start() == atom.end()
                    }) =>
            {
                match inner.next() {
                    Some(first) => self.prefixed_strings(Some(atom), first, inner)?,
                    None => self.atom(atom)?,
                }
            }
            Some(atom) => self.atom(atom)?,
            None => return Err(err(Span::default(), "internal: missing operand")),
        };
        while let Some(trailer) = inner.peek() {
            if !matches!(
                trailer.as_rule(),
                Rule::call | Rule::subscript | Rule::attribute
            ) {
                break;
            }
            inner.next();
            let tspan = self.span(&trailer);
            let span = expr.span.merge(tspan);
            let kind = match trailer.as_rule() {
                Rule::call => {
                    let args = match trailer.into_inner().next() {
                        Some(list) => self.arglist(list)?,
                        None => Vec::new(),
                    };
                    ExprKind::Call {
                        func: Box::new(expr),
                        args,
                    }
                }
                Rule::subscript => {
                    let index = match trailer.into_inner().next() {
                        Some(list) => self.subscript_list(list)?,
                        None => return Err(err(tspan, "expected an index")),
                    };
                    ExprKind::Subscript {
                        value: Box::new(expr),
                        index: Box::new(index),
                    }
                }
                _ => match trailer.into_inner().next() {
                    Some(name) => ExprKind::Attribute {
                        value: Box::new(expr),
                        attr: self.ident(name),
                    },
                    None => return Err(err(tspan, "expected an attribute name")),
                },
            };
            expr = Expr { kind, span };
        }
        Ok(expr)
    }

    fn arglist(&self, pair: P) -> R<Vec<Arg>> {
        let inner = pair.into_inner();
        let mut args = Vec::with_capacity(inner.clone().count());
        for arg in inner {
            let span = self.span(&arg);
            let rule = arg.as_rule();
            let mut inner = arg.into_inner();
            let kind = match rule {
                Rule::kwarg => {
                    let name = match inner.next() {
                        Some(n) => self.kwarg_name(n),
                        None => return Err(err(span, "expected a keyword name")),
                    };
                    let value = self.test_items(&mut inner, span)?;
                    ArgKind::Keyword { name, value }
                }
                Rule::star_arg => ArgKind::Star {
                    value: self.required_test(inner.next(), span)?,
                },
                Rule::dstar_arg => ArgKind::DoubleStar {
                    value: self.required_test(inner.next(), span)?,
                },
                _ => {
                    let first = self.required_test(inner.next(), span)?;
                    let value = match inner.next() {
                        Some(comp) => Expr {
                            span,
                            kind: ExprKind::GeneratorExp {
                                elt: Box::new(first),
                                generators: self.comp_for(comp)?,
                            },
                        },
                        None => first,
                    };
                    ArgKind::Positional { value }
                }
            };
            args.push(Arg { kind, span });
        }
        Ok(args)
    }

    fn subscript_list(&self, pair: P) -> R<Expr> {
        let span = self.span(&pair);
        let mut elts = Vec::new();
        let mut comma = false;
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::comma => comma = true,
                Rule::slice => elts.push(self.slice(p)?),
                _ => elts.push(self.element(p)?),
            }
        }
        if elts.len() == 1 && !comma {
            if let Some(e) = elts.pop() {
                return Ok(e);
            }
        }
        Ok(Expr {
            kind: ExprKind::Tuple { elts },
            span,
        })
    }

    fn slice(&self, pair: P) -> R<Expr> {
        let span = self.span(&pair);
        let mut bounds = Vec::with_capacity(3);
        for bound in pair.into_inner() {
            bounds.push(
                bound
                    .into_inner()
                    .next()
                    .map(|p| self.test(p).map(Box::new))
                    .transpose()?,
            );
        }
        let mut bounds = bounds.into_iter();
        Ok(Expr {
            kind: ExprKind::Slice {
                lower: bounds.next().flatten(),
                upper: bounds.next().flatten(),
                step: bounds.next().flatten(),
            },
            span,
        })
    }

    fn atom(&self, pair: P) -> R<Expr> {
        let span = self.span(&pair);
        let kind = match pair.as_rule() {
            Rule::name => ExprKind::Name {
                id: Text::new(pair.as_str()),
            },
            Rule::number => literals::number(pair.as_str()).map_err(|m| err(span, m))?,
            Rule::string => return self.strings(pair, &mut Children::default()),
            Rule::none => ExprKind::None,
            Rule::true_ => ExprKind::Bool { value: true },
            Rule::false_ => ExprKind::Bool { value: false },
            Rule::ellipsis => ExprKind::Ellipsis,
            Rule::backquote => {
                let value = match pair.into_inner().next() {
                    Some(p) => self.testlist(p)?,
                    None => return Err(err(span, "expected an expression in backquotes")),
                };
                ExprKind::Repr {
                    value: Box::new(value),
                }
            }
            Rule::paren => {
                let Some(body) = pair.into_inner().next() else {
                    return Ok(Expr {
                        kind: ExprKind::Tuple { elts: Vec::new() },
                        span,
                    });
                };
                if body.as_rule() == Rule::yield_expr {
                    let mut e = self.yield_expr(body)?;
                    e.span = span;
                    return Ok(e);
                }
                let (elts, generators, comma) = self.comp_body(body)?;
                let mut elts = elts;
                match generators {
                    Some(generators) => ExprKind::GeneratorExp {
                        elt: Box::new(first(&mut elts, span)?),
                        generators,
                    },
                    None if elts.len() == 1 && !comma => {
                        // A parenthesized expression keeps the parentheses in its
                        // span: that is how `(a < b) < c` stays nested.
                        let mut e = first(&mut elts, span)?;
                        e.span = span;
                        return Ok(e);
                    }
                    None => ExprKind::Tuple { elts },
                }
            }
            Rule::list => match pair.into_inner().next() {
                None => ExprKind::List { elts: Vec::new() },
                Some(body) => {
                    let (mut elts, generators, _) = self.comp_body(body)?;
                    match generators {
                        Some(generators) => ExprKind::ListComp {
                            elt: Box::new(first(&mut elts, span)?),
                            generators,
                        },
                        None => ExprKind::List { elts },
                    }
                }
            },
            Rule::brace => match pair.into_inner().next() {
                None => ExprKind::Dict { items: Vec::new() },
                Some(body) if body.as_rule() == Rule::dict_body => self.dict_body(body, span)?,
                Some(body) => {
                    let (mut elts, generators, _) = self.comp_body(body)?;
                    match generators {
                        Some(generators) => ExprKind::SetComp {
                            elt: Box::new(first(&mut elts, span)?),
                            generators,
                        },
                        None => ExprKind::Set { elts },
                    }
                }
            },
            Rule::primary => return self.primary(pair),
            other => return Err(err(span, format!("internal: unexpected atom {other:?}"))),
        };
        Ok(Expr { kind, span })
    }

    /// Elements of a display, or one element and its `for` clauses.
    #[allow(clippy::type_complexity)]
    fn comp_body(&self, pair: P) -> R<(Vec<Expr>, Option<Vec<Comprehension>>, bool)> {
        let inner = pair.into_inner();
        let mut elts = Vec::with_capacity(inner.clone().count());
        let mut generators = None;
        let mut comma = false;
        for p in inner {
            match p.as_rule() {
                Rule::comp_for => generators = Some(self.comp_for(p)?),
                Rule::comma => comma = true,
                _ => elts.push(self.element(p)?),
            }
        }
        Ok((elts, generators, comma))
    }

    fn dict_body(&self, pair: P, span: Span) -> R<ExprKind> {
        let mut items = Vec::new();
        let mut generators = None;
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::comp_for => generators = Some(self.comp_for(p)?),
                _ => {
                    let mut parts = p.into_inner();
                    let Some(first) = parts.next() else { continue };
                    if first.as_rule() == Rule::dict_unpack {
                        let value = self.required_test(first.into_inner().next(), span)?;
                        items.push(DictItem { key: None, value });
                    } else {
                        let key = self.test(first)?;
                        let value = self.required_test(parts.next(), span)?;
                        items.push(DictItem {
                            key: Some(key),
                            value,
                        });
                    }
                }
            }
        }
        match generators {
            Some(generators) => {
                let item = items.pop();
                match item {
                    Some(DictItem {
                        key: Some(key),
                        value,
                    }) => Ok(ExprKind::DictComp {
                        key: Box::new(key),
                        value: Box::new(value),
                        generators,
                    }),
                    _ => Err(err(
                        span,
                        "dict unpacking cannot be used in dict comprehension",
                    )),
                }
            }
            None => Ok(ExprKind::Dict { items }),
        }
    }

    fn comp_for(&self, pair: P) -> R<Vec<Comprehension>> {
        let mut out = Vec::new();
        let mut next = Some(pair);
        while let Some(clause) = next.take() {
            let span = self.span(&clause);
            let rule = clause.as_rule();
            let mut parts = clause.into_inner();
            parts.next();
            if rule == Rule::comp_for {
                let target = match parts.next() {
                    Some(p) => self.target_list(p)?,
                    None => return Err(err(span, "expected a target")),
                };
                parts.next();
                let iter = self.required_test(parts.next(), span)?;
                out.push(Comprehension {
                    target,
                    iter,
                    ifs: Vec::new(),
                    is_async: false,
                });
            } else {
                let cond = self.required_test(parts.next(), span)?;
                match out.last_mut() {
                    Some(c) => c.ifs.push(cond),
                    None => return Err(err(span, "`if` without `for` in comprehension")),
                }
            }
            next = parts.next();
        }
        Ok(out)
    }

    fn namedexpr(&self, pair: P) -> R<Expr> {
        let span = self.span(&pair);
        let mut parts = pair.into_inner();
        let target = match parts.next() {
            Some(p) => self.ident(p),
            None => return Err(err(span, "expected a name")),
        };
        let value = self.required_test(parts.next(), span)?;
        Ok(Expr {
            kind: ExprKind::NamedExpr {
                target,
                value: Box::new(value),
            },
            span,
        })
    }

    fn yield_expr(&self, pair: P) -> R<Expr> {
        let span = self.span(&pair);
        let mut parts = pair.into_inner();
        parts.next();
        let kind = match parts.next() {
            Some(p) if p.as_rule() == Rule::yield_from => {
                let mut inner = p.into_inner();
                inner.next();
                ExprKind::YieldFrom {
                    value: Box::new(self.required_test(inner.next(), span)?),
                }
            }
            Some(p) => ExprKind::Yield {
                value: Some(Box::new(self.testlist(p)?)),
            },
            None => ExprKind::Yield { value: None },
        };
        Ok(Expr { kind, span })
    }

    // ------------------------------------------------------------ strings

    /// Adjacent literals, concatenated. Mixing bytes and text is an error.
    /// A string literal and the literals adjacent to it (implicit
    /// concatenation), which follow it in `rest`.
    fn strings<'i>(&self, first: P<'i>, rest: &mut Children<'i>) -> R<Expr> {
        self.prefixed_strings(None, first, rest)
    }

    /// [`Builder::strings`], the first literal possibly preceded by an
    /// upper-case two-letter prefix (`RB`, `BR`, `FR`, `RF`, `UR`) that the
    /// grammar read as a name: the name rule takes any upper-case letter
    /// followed by another without checking for a quote (one test instead of
    /// a lookahead on every name).
    fn prefixed_strings<'i>(
        &self,
        mut prefix: Option<P<'i>>,
        first: P<'i>,
        rest: &mut Children<'i>,
    ) -> R<Expr> {
        let mut span = self.span(&first);
        if let Some(p) = &prefix {
            span = span.merge(self.span(p));
        }
        // Built inline (no allocation) while it fits in 24 bytes.
        let mut text = Text::default();
        let mut bytes: Vec<u8> = Vec::new();
        let mut parts: Vec<FStringPart> = Vec::new();
        let mut kinds = (false, false); // (saw bytes, saw text)
        let mut is_fstring = false;
        let mut next = Some(first);
        while let Some(tok) = next {
            next = match rest.peek() {
                Some(p) if p.as_rule() == Rule::string => rest.next(),
                _ => None,
            };
            let (tok_span, token) = match prefix.take() {
                Some(p) => (
                    self.span(&p).merge(self.span(&tok)),
                    &self.source[p.start()..tok.end()],
                ),
                None => (self.span(&tok), tok.as_str()),
            };
            span = span.merge(tok_span);
            let (flags, offset, body) = literals::split_string(token);
            if flags.bytes {
                kinds.0 = true;
                let codes = if flags.raw {
                    body.chars().map(|c| c as u32).collect()
                } else {
                    literals::unescape(body, true).map_err(|m| err(tok_span, m))?
                };
                bytes.extend(literals::to_bytes(&codes).map_err(|m| err(tok_span, m))?);
            } else {
                kinds.1 = true;
                if flags.fstring {
                    is_fstring = true;
                    if !text.is_empty() {
                        parts.push(FStringPart::Literal {
                            value: std::mem::take(&mut text).into_string(),
                        });
                    }
                    let body_start = tok_span.start as usize + offset;
                    self.fstring_parts(body, body_start, flags.raw, &mut parts)?;
                } else if flags.raw {
                    text.push_str(body);
                } else if body.contains('\\') {
                    let codes = literals::unescape(body, false).map_err(|m| err(tok_span, m))?;
                    text.push_str(&literals::to_string(&codes));
                } else {
                    text.push_str(body);
                }
            }
        }
        if kinds.0 && kinds.1 {
            return Err(err(span, "cannot mix bytes and nonbytes literals"));
        }
        let kind = if kinds.0 {
            ExprKind::Bytes { value: bytes }
        } else if is_fstring {
            if !text.is_empty() {
                parts.push(FStringPart::Literal {
                    value: text.into_string(),
                });
            }
            ExprKind::FString {
                parts: merge_literals(parts),
            }
        } else {
            ExprKind::Str { value: text }
        };
        Ok(Expr { kind, span })
    }

    /// The parts of an f-string body that starts at byte `start` of the file.
    fn fstring_parts(
        &self,
        body: &str,
        start: usize,
        raw: bool,
        out: &mut Vec<FStringPart>,
    ) -> R<()> {
        let bytes = body.as_bytes();
        let mut literal = String::new();
        let mut lit_start = 0;
        let mut i = 0;
        let flush =
            |literal: &mut String, from: usize, to: usize, out: &mut Vec<FStringPart>| -> R<()> {
                let piece = &body[from..to];
                if raw || !piece.contains('\\') {
                    literal.push_str(piece);
                } else {
                    let codes = literals::unescape(piece, false)
                        .map_err(|m| err(Span::new(start + from, start + to), m))?;
                    literal.push_str(&literals::to_string(&codes));
                }
                let _ = out;
                Ok(())
            };
        while i < bytes.len() {
            match bytes[i] {
                b'{' if bytes.get(i + 1) == Some(&b'{') => {
                    flush(&mut literal, lit_start, i + 1, out)?;
                    i += 2;
                    lit_start = i;
                }
                b'}' if bytes.get(i + 1) == Some(&b'}') => {
                    flush(&mut literal, lit_start, i + 1, out)?;
                    i += 2;
                    lit_start = i;
                }
                b'{' => {
                    flush(&mut literal, lit_start, i, out)?;
                    if !literal.is_empty() {
                        out.push(FStringPart::Literal {
                            value: std::mem::take(&mut literal),
                        });
                    }
                    let (field, end) = self.fstring_field(body, i + 1, start, raw)?;
                    out.push(field);
                    i = end;
                    lit_start = i;
                }
                b'}' => {
                    return Err(err(
                        Span::new(start + i, start + i + 1),
                        "f-string: single `}` is not allowed (write `}}`)",
                    ))
                }
                b'\\' => i += 2,
                _ => i += 1,
            }
        }
        flush(&mut literal, lit_start, bytes.len().min(body.len()), out)?;
        if !literal.is_empty() {
            out.push(FStringPart::Literal { value: literal });
        }
        Ok(())
    }

    /// One replacement field starting after its `{` at `from`; returns the
    /// field and the index just after its closing `}`.
    fn fstring_field(
        &self,
        body: &str,
        from: usize,
        start: usize,
        raw: bool,
    ) -> R<(FStringPart, usize)> {
        let bytes = body.as_bytes();
        let open = Span::new(start + from - 1, start + from);
        // Find where the expression ends: `}`, `!`, `:` or a final `=` at depth 0.
        let mut depth = 0usize;
        let mut i = from;
        let mut quote: Option<u8> = None;
        let expr_end = loop {
            let Some(&c) = bytes.get(i) else {
                return Err(err(open, "f-string: expecting `}`"));
            };
            if let Some(q) = quote {
                if c == q {
                    quote = None;
                }
                i += 1;
                continue;
            }
            match c {
                b'\'' | b'"' => quote = Some(c),
                b'(' | b'[' | b'{' => depth += 1,
                b')' | b']' => depth = depth.saturating_sub(1),
                b'}' if depth > 0 => depth -= 1,
                b'}' => break i,
                b'!' if depth == 0 && bytes.get(i + 1) != Some(&b'=') => break i,
                b':' if depth == 0 => break i,
                b'=' if depth == 0
                    && bytes.get(i + 1) != Some(&b'=')
                    && !matches!(
                        bytes.get(i.wrapping_sub(1)),
                        Some(b'=' | b'!' | b'<' | b'>')
                    ) =>
                {
                    let rest = body[i + 1..].trim_start();
                    if rest.starts_with(['}', '!', ':']) {
                        break i;
                    }
                }
                _ => {}
            }
            i += 1;
        };
        let raw_expr = &body[from..expr_end];
        let lead = raw_expr.len() - raw_expr.trim_start().len();
        let expr_text = raw_expr.trim();
        if expr_text.is_empty() {
            return Err(err(open, "f-string: empty expression not allowed"));
        }
        let expr_start = start + from + lead;
        // The field is parsed on its own: the nesting limits apply to it too.
        crate::diagnose::check_limits(expr_text).map_err(|mut e| {
            e.span = Span::new(
                expr_start + e.span.start as usize,
                expr_start + e.span.end as usize,
            );
            e
        })?;
        let pairs = CommParser::parse(Rule::fstring_expr, expr_text).map_err(|e| {
            let mut pe = crate::error::from_pest(&e, expr_text);
            pe.span = Span::new(
                expr_start + pe.span.start as usize,
                expr_start + pe.span.end as usize,
            );
            pe.message = format!("f-string: {}", pe.message);
            pe
        })?;
        let sub = Builder {
            base: expr_start,
            source: expr_text,
        };
        let tree = Tree::new(pairs, expr_text);
        let value = match tree
            .top()
            .next()
            .and_then(|p| p.into_inner().next())
            .and_then(|inner| inner.into_inner().next())
        {
            Some(p) => sub.rhs(p)?,
            None => return Err(err(open, "f-string: empty expression not allowed")),
        };
        let mut i = expr_end;
        let mut debug = false;
        if bytes.get(i) == Some(&b'=') {
            debug = true;
            i += 1;
            while bytes.get(i).is_some_and(|b| b.is_ascii_whitespace()) {
                i += 1;
            }
        }
        let mut conversion = None;
        if bytes.get(i) == Some(&b'!') {
            match bytes.get(i + 1) {
                Some(&c @ (b'r' | b's' | b'a')) => conversion = Some(c as char),
                _ => {
                    return Err(err(
                        Span::new(start + i, start + i + 1),
                        "f-string: invalid conversion character: expected `s`, `r` or `a`",
                    ))
                }
            }
            i += 2;
        }
        let mut format_spec = Vec::new();
        if bytes.get(i) == Some(&b':') {
            // The spec runs to the matching `}`; it may hold nested fields.
            let spec_start = i + 1;
            let mut depth = 0usize;
            let mut j = spec_start;
            loop {
                match bytes.get(j) {
                    None => return Err(err(open, "f-string: expecting `}`")),
                    Some(b'{') => depth += 1,
                    Some(b'}') if depth == 0 => break,
                    Some(b'}') => depth -= 1,
                    _ => {}
                }
                j += 1;
            }
            self.fstring_parts(
                &body[spec_start..j],
                start + spec_start,
                raw,
                &mut format_spec,
            )?;
            i = j;
        }
        if bytes.get(i) != Some(&b'}') {
            return Err(err(open, "f-string: expecting `}`"));
        }
        Ok((
            FStringPart::Field {
                value,
                conversion,
                format_spec,
                debug,
            },
            i + 1,
        ))
    }
}

/// Where a comment starts on a line (a `#` outside quotes), if any.
/// A two-letter upper-case string prefix, which the name rule reads as a
/// name (see [`Builder::prefixed_strings`]).
fn is_upper_string_prefix(name: &str) -> bool {
    matches!(name, "RB" | "BR" | "FR" | "RF" | "UR")
}

fn comment_start(line: &str) -> Option<usize> {
    // Most lines have no `#` at all: one byte scan instead of the quote walk.
    if !line.as_bytes().contains(&b'#') {
        return None;
    }
    let mut quote: Option<char> = None;
    let mut escaped = false;
    for (i, c) in line.char_indices() {
        if let Some(q) = quote {
            if escaped {
                escaped = false;
            } else if c == '\\' {
                escaped = true;
            } else if c == q {
                quote = None;
            }
        } else if c == '\'' || c == '"' {
            quote = Some(c);
        } else if c == '#' {
            return Some(i);
        }
    }
    None
}

/// Adjacent literal parts are merged so `f"a" "b"` and `f"ab"` read the same.
fn merge_literals(parts: Vec<FStringPart>) -> Vec<FStringPart> {
    let mut out: Vec<FStringPart> = Vec::with_capacity(parts.len());
    for part in parts {
        if let (FStringPart::Literal { value }, Some(FStringPart::Literal { value: prev })) =
            (&part, out.last_mut())
        {
            prev.push_str(value);
            continue;
        }
        if matches!(&part, FStringPart::Literal { value } if value.is_empty()) {
            continue;
        }
        out.push(part);
    }
    out
}

fn first(elts: &mut Vec<Expr>, span: Span) -> R<Expr> {
    if elts.is_empty() {
        return Err(err(span, "expected an expression"));
    }
    Ok(elts.remove(0))
}

fn dotted(pair: &P) -> String {
    pair.into_inner()
        .map(|p| p.as_str())
        .collect::<Vec<_>>()
        .join(".")
}

fn aug_op(op: &str) -> BinOp {
    match op {
        "-=" => BinOp::Sub,
        "*=" => BinOp::Mul,
        "@=" => BinOp::MatMul,
        "/=" => BinOp::Div,
        "//=" => BinOp::FloorDiv,
        "%=" => BinOp::Mod,
        "**=" => BinOp::Pow,
        "<<=" => BinOp::LShift,
        ">>=" => BinOp::RShift,
        "|=" => BinOp::BitOr,
        "^=" => BinOp::BitXor,
        "&=" => BinOp::BitAnd,
        _ => BinOp::Add,
    }
}

/// Fold one binary operator; comparisons chain and `and`/`or` flatten, unless
/// the left operand was parenthesized (its span then ends after the `)`).
/// One element of a flat operator sequence.
enum OpItem {
    Prefix(UnaryOp, Span),
    Operand(Expr),
    Infix(Rule),
}

// Binding powers, Python's precedence (lowest first); gaps of 10 leave
// room for right associativity (`**` parses its right side at power - 1).
const PREC_NOT: u32 = 30;
const PREC_UNARY: u32 = 110;

fn prefix_op(rule: Rule) -> Option<UnaryOp> {
    match rule {
        Rule::neg => Some(UnaryOp::Neg),
        Rule::pos => Some(UnaryOp::Pos),
        Rule::invert => Some(UnaryOp::Invert),
        Rule::not => Some(UnaryOp::Not),
        _ => None,
    }
}

/// Binding power of an infix operator (None: not an infix operator).
fn infix_prec(rule: Rule) -> Option<u32> {
    Some(match rule {
        Rule::or => 10,
        Rule::and => 20,
        Rule::lt
        | Rule::gt
        | Rule::eq
        | Rule::ne
        | Rule::ne_py2
        | Rule::le
        | Rule::ge
        | Rule::in_
        | Rule::not_in
        | Rule::is_
        | Rule::is_not => 40,
        Rule::bitor => 50,
        Rule::bitxor => 60,
        Rule::bitand => 70,
        Rule::lshift | Rule::rshift => 80,
        Rule::add | Rule::sub => 90,
        Rule::mul | Rule::matmul | Rule::div | Rule::floordiv | Rule::modulo => 100,
        Rule::pow => 120,
        _ => return None,
    })
}

/// Pratt folding of an operator sequence: operators binding tighter than
/// `min` are taken into the left operand.
///
/// `depth` counts the recursion (prefix operators and `**` chains nest the
/// tree as deep as they are long): it stops at [`crate::limits::MAX_DEPTH`],
/// as the tree would be refused at that depth anyway.
fn fold(
    items: &mut std::iter::Peekable<std::vec::IntoIter<OpItem>>,
    min: u32,
    depth: usize,
) -> R<Expr> {
    if depth >= crate::limits::MAX_DEPTH {
        let span = match items.peek() {
            Some(OpItem::Operand(e)) => e.span,
            Some(OpItem::Prefix(_, span)) => *span,
            _ => Span::default(),
        };
        return Err(err(span, crate::limits::too_deep_message()));
    }
    let mut lhs = match items.next() {
        Some(OpItem::Operand(e)) => e,
        Some(OpItem::Prefix(op, span)) => {
            let prec = if op == UnaryOp::Not {
                PREC_NOT
            } else {
                PREC_UNARY
            };
            let operand = fold(items, prec, depth + 1)?;
            Expr {
                span: span.merge(operand.span),
                kind: ExprKind::UnaryOp {
                    op,
                    operand: Box::new(operand),
                },
            }
        }
        _ => return Err(err(Span::default(), "internal: operator without operand")),
    };
    while let Some(OpItem::Infix(rule)) = items.peek() {
        let rule = *rule;
        let prec = infix_prec(rule).unwrap_or(0);
        if prec <= min {
            break;
        }
        items.next();
        let rhs = fold(
            items,
            if rule == Rule::pow { prec - 1 } else { prec },
            depth + 1,
        )?;
        lhs = infix(lhs, rule, rhs);
    }
    Ok(lhs)
}

fn infix(mut lhs: Expr, op: Rule, rhs: Expr) -> Expr {
    let span = lhs.span.merge(rhs.span);
    let arith = match op {
        Rule::add => Some(BinOp::Add),
        Rule::sub => Some(BinOp::Sub),
        Rule::mul => Some(BinOp::Mul),
        Rule::matmul => Some(BinOp::MatMul),
        Rule::div => Some(BinOp::Div),
        Rule::floordiv => Some(BinOp::FloorDiv),
        Rule::modulo => Some(BinOp::Mod),
        Rule::pow => Some(BinOp::Pow),
        Rule::lshift => Some(BinOp::LShift),
        Rule::rshift => Some(BinOp::RShift),
        Rule::bitor => Some(BinOp::BitOr),
        Rule::bitxor => Some(BinOp::BitXor),
        Rule::bitand => Some(BinOp::BitAnd),
        _ => None,
    };
    if let Some(op) = arith {
        return Expr {
            kind: ExprKind::BinOp {
                left: Box::new(lhs),
                op,
                right: Box::new(rhs),
            },
            span,
        };
    }
    match op {
        Rule::and | Rule::or => {
            let bop = if op == Rule::and {
                BoolOp::And
            } else {
                BoolOp::Or
            };
            match std::mem::replace(&mut lhs.kind, ExprKind::None) {
                ExprKind::BoolOp {
                    op: lop,
                    mut values,
                } if lop == bop && values.last().is_some_and(|v| v.span.end == lhs.span.end) => {
                    values.push(rhs);
                    Expr {
                        kind: ExprKind::BoolOp { op: bop, values },
                        span,
                    }
                }
                kind => Expr {
                    kind: ExprKind::BoolOp {
                        op: bop,
                        values: vec![
                            Expr {
                                kind,
                                span: lhs.span,
                            },
                            rhs,
                        ],
                    },
                    span,
                },
            }
        }
        _ => {
            let cmp = match op {
                Rule::lt => CmpOp::Lt,
                Rule::gt => CmpOp::Gt,
                Rule::eq => CmpOp::Eq,
                Rule::le => CmpOp::LtE,
                Rule::ge => CmpOp::GtE,
                Rule::in_ => CmpOp::In,
                Rule::not_in => CmpOp::NotIn,
                Rule::is_ => CmpOp::Is,
                Rule::is_not => CmpOp::IsNot,
                _ => CmpOp::NotEq,
            };
            match std::mem::replace(&mut lhs.kind, ExprKind::None) {
                ExprKind::Compare { left, mut ops }
                    if ops.last().is_some_and(|(_, e)| e.span.end == lhs.span.end) =>
                {
                    ops.push((cmp, rhs));
                    Expr {
                        kind: ExprKind::Compare { left, ops },
                        span,
                    }
                }
                kind => Expr {
                    kind: ExprKind::Compare {
                        left: Box::new(Expr {
                            kind,
                            span: lhs.span,
                        }),
                        ops: vec![(cmp, rhs)],
                    },
                    span,
                },
            }
        }
    }
}

fn describe(e: &Expr) -> &'static str {
    match &e.kind {
        ExprKind::Call { .. } => "function call",
        ExprKind::Int { .. }
        | ExprKind::Float { .. }
        | ExprKind::Imag { .. }
        | ExprKind::Str { .. }
        | ExprKind::Bytes { .. }
        | ExprKind::Bool { .. }
        | ExprKind::None
        | ExprKind::Ellipsis => "literal",
        ExprKind::FString { .. } => "f-string expression",
        ExprKind::BinOp { .. } | ExprKind::UnaryOp { .. } => "expression",
        ExprKind::BoolOp { .. } => "expression",
        ExprKind::Compare { .. } => "comparison",
        ExprKind::IfExp { .. } => "conditional expression",
        ExprKind::Lambda { .. } => "lambda",
        ExprKind::Dict { .. } | ExprKind::Set { .. } => "dict or set display",
        ExprKind::ListComp { .. }
        | ExprKind::SetComp { .. }
        | ExprKind::DictComp { .. }
        | ExprKind::GeneratorExp { .. } => "comprehension",
        ExprKind::NamedExpr { .. } => "named expression",
        _ => "expression",
    }
}

/// Is `e` something one can assign to (or delete)?
fn check_target(e: &Expr, verb: &str) -> R<()> {
    match &e.kind {
        ExprKind::Name { .. } | ExprKind::Attribute { .. } | ExprKind::Subscript { .. } => Ok(()),
        ExprKind::Starred { value } => check_target(value, verb),
        ExprKind::Tuple { elts } | ExprKind::List { elts } => {
            elts.iter().try_for_each(|t| check_target(t, verb))
        }
        _ => Err(err(
            e.span,
            format!(
                "cannot {verb} {}; expected a name, attribute, subscript or tuple of them",
                describe(e)
            ),
        )),
    }
}

fn check_aug_target(e: &Expr) -> R<()> {
    match &e.kind {
        ExprKind::Name { .. } | ExprKind::Attribute { .. } | ExprKind::Subscript { .. } => Ok(()),
        _ => Err(err(
            e.span,
            format!(
                "'{}' is an illegal target for augmented assignment",
                describe(e)
            ),
        )),
    }
}
