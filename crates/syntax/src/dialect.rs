//! code_aster 11 (Python 2) versus code_aster 17 (Python 3).
//!
//! The grammar accepts both dialects; this module tells which Python 2
//! constructs a parsed module uses (the ones the AST keeps: `print x`,
//! `exec code`, backquotes), so that tools can report legacy syntax.
//! Forms that the parser normalizes are documented here for reference:
//! `<>` becomes `NotEq`, `0777` an `Int` (octal), `10L` an `Int`,
//! `ur''` a `Str`, `except E, e:` a handler with a name, `raise E, V` a
//! `raise E(V)`.
//!
//! [`generation`] answers a different question: was the file written for
//! code_aster 17, or for an older code_aster (11–15)? Python 2 constructs
//! say so, and so do keywords that only older catalogs had and that every
//! code_aster 11 test file writes (`DEBUT(CODE=_F(NIV_PUB_WEB=...))`).
//! The evaluator translates the older spellings only in older files, so a
//! code_aster 17 file is checked against the code_aster 17 catalog alone.

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

/// Keyword names that no code_aster 17 command accepts anywhere and that
/// older command files write: `DEBUT(CODE=_F(NOM=..., NIV_PUB_WEB=...))`
/// opens every code_aster 11 test file, `VISU_EFICAS` sits beside it,
/// `COMP_INCR`/`COMP_ELAS` became `COMPORTEMENT` in code_aster 12.
/// (`PAR_LOT` is not one: code_aster 17 still accepts and ignores it.)
pub const LEGACY_KEYWORDS: &[&str] = &["NIV_PUB_WEB", "VISU_EFICAS", "COMP_INCR", "COMP_ELAS"];

/// Which code_aster generation a command file was written for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Generation {
    /// Nothing in the file is older than code_aster 17's syntax.
    Current,
    /// The first construct (in source order) that only older code_aster
    /// versions accept.
    Legacy { span: Span, marker: LegacyMarker },
}

/// What marks a file as written for an older code_aster.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LegacyMarker {
    /// A Python 2 statement or expression (code_aster ≤ 14 ran Python 2).
    Python2(Legacy),
    /// A keyword argument named in [`LEGACY_KEYWORDS`].
    Keyword(&'static str),
}

impl Generation {
    pub fn is_legacy(self) -> bool {
        matches!(self, Generation::Legacy { .. })
    }
}

/// Tells whether `module` was written for code_aster 17 or an older one.
pub fn generation(module: &Module) -> Generation {
    let mut w = Walker::default();
    w.stmts(&module.body);
    let first_py2 = w.py2.iter().min_by_key(|(s, _)| s.start);
    let first_kw = w.keywords.iter().min_by_key(|(s, _)| s.start);
    let found = match (first_py2, first_kw) {
        (Some(&(s, l)), Some(&(k, _))) if s.start <= k.start => Some((s, LegacyMarker::Python2(l))),
        (Some(&(s, l)), None) => Some((s, LegacyMarker::Python2(l))),
        (_, Some(&(k, name))) => Some((k, LegacyMarker::Keyword(name))),
        (None, None) => None,
    };
    match found {
        Some((span, marker)) => Generation::Legacy { span, marker },
        None => Generation::Current,
    }
}

/// The Python 2 constructs of a module, in source order.
pub fn legacy_features(module: &Module) -> Vec<(Span, Legacy)> {
    let mut w = Walker::default();
    w.stmts(&module.body);
    let mut out = w.py2;
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

/// Collects the legacy markers of a module.
#[derive(Default)]
struct Walker {
    py2: Vec<(Span, Legacy)>,
    keywords: Vec<(Span, &'static str)>,
}

impl Walker {
    fn stmts(&mut self, body: &[Stmt]) {
        for s in body {
            match &s.kind {
                StmtKind::Print { dest, values, .. } => {
                    self.py2.push((s.span, Legacy::PrintStatement));
                    dest.iter().chain(values).for_each(|e| self.expr(e));
                }
                StmtKind::Exec { code, .. } => {
                    self.py2.push((s.span, Legacy::ExecStatement));
                    self.expr(code);
                }
                StmtKind::Expr { value } => self.expr(value),
                StmtKind::Assign { targets, value } => {
                    targets.iter().for_each(|e| self.expr(e));
                    self.expr(value);
                }
                StmtKind::AugAssign { value, .. } => self.expr(value),
                StmtKind::Return { value: Some(v) } => self.expr(v),
                StmtKind::If { test, body, orelse } | StmtKind::While { test, body, orelse } => {
                    self.expr(test);
                    self.stmts(body);
                    self.stmts(orelse);
                }
                StmtKind::For {
                    iter, body, orelse, ..
                } => {
                    self.expr(iter);
                    self.stmts(body);
                    self.stmts(orelse);
                }
                StmtKind::FunctionDef { body, .. }
                | StmtKind::ClassDef { body, .. }
                | StmtKind::With { body, .. } => self.stmts(body),
                StmtKind::Try {
                    body,
                    handlers,
                    orelse,
                    finalbody,
                } => {
                    self.stmts(body);
                    handlers.iter().for_each(|h| self.stmts(&h.body));
                    self.stmts(orelse);
                    self.stmts(finalbody);
                }
                _ => {}
            }
        }
    }

    fn expr(&mut self, e: &Expr) {
        match &e.kind {
            ExprKind::Repr { value } => {
                self.py2.push((e.span, Legacy::Backquotes));
                self.expr(value);
            }
            ExprKind::Call { func, args } => {
                self.expr(func);
                for a in args {
                    match &a.kind {
                        ArgKind::Keyword { name, value } => {
                            if let Some(k) = LEGACY_KEYWORDS.iter().find(|k| **k == name.name) {
                                self.keywords.push((name.span, k));
                            }
                            self.expr(value)
                        }
                        ArgKind::Positional { value }
                        | ArgKind::Star { value }
                        | ArgKind::DoubleStar { value } => self.expr(value),
                    }
                }
            }
            ExprKind::BinOp { left, right, .. } => {
                self.expr(left);
                self.expr(right);
            }
            ExprKind::UnaryOp { operand, .. } => self.expr(operand),
            ExprKind::List { elts } | ExprKind::Tuple { elts } | ExprKind::Set { elts } => {
                elts.iter().for_each(|x| self.expr(x))
            }
            ExprKind::Compare { left, ops } => {
                self.expr(left);
                ops.iter().for_each(|(_, x)| self.expr(x));
            }
            ExprKind::BoolOp { values, .. } => values.iter().for_each(|x| self.expr(x)),
            ExprKind::IfExp { test, body, orelse } => {
                self.expr(test);
                self.expr(body);
                self.expr(orelse);
            }
            ExprKind::Subscript { value, index } => {
                self.expr(value);
                self.expr(index);
            }
            ExprKind::Attribute { value, .. } => self.expr(value),
            ExprKind::Dict { items } => items.iter().for_each(|i| self.expr(&i.value)),
            _ => {}
        }
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

    #[test]
    fn tells_code_aster_11_files_from_current_ones() {
        let parse = |src: &str| crate::parse_module(src).map_err(|e| e.message);
        let v11 = parse("DEBUT(CODE=_F(NOM='T', NIV_PUB_WEB='INTERNET'))\nFIN()\n");
        let g = v11.map(|m| generation(&m));
        assert!(
            matches!(
                g,
                Ok(Generation::Legacy {
                    marker: LegacyMarker::Keyword("NIV_PUB_WEB"),
                    ..
                })
            ),
            "{g:?}"
        );
        // Inside a nested expression too (a list of _F, a function body).
        let nested = parse("def f():\n    return [_F(COMP_INCR=_F(RELATION='ELAS'))]\n");
        assert_eq!(nested.map(|m| generation(&m).is_legacy()), Ok(true));
        let py2 = parse("print 'x'\nDEBUT()\n");
        assert!(matches!(
            py2.map(|m| generation(&m)),
            Ok(Generation::Legacy {
                marker: LegacyMarker::Python2(Legacy::PrintStatement),
                ..
            })
        ));
        // A name in a comment or a string is no marker; PAR_LOT is still
        // accepted by code_aster 17.
        let v17 = parse("# COMP_INCR\nDEBUT(PAR_LOT='NON', CODE='OUI')\nx = 'NIV_PUB_WEB'\n");
        assert_eq!(v17.map(|m| generation(&m)), Ok(Generation::Current));
    }
}
