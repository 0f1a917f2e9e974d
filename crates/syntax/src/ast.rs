//! The abstract syntax tree of a command file.
//!
//! `.comm` files are Python programs, so the tree is general Python (enough of
//! Python 3 and of the Python 2 still found in code_aster 11 files). Every
//! node carries a [`Span`]. Commands are not special here: `MA =
//! LIRE_MAILLAGE(...)` is an assignment of a call; the evaluator decides that
//! `LIRE_MAILLAGE` is a command.

use crate::codemap::Span;
use serde::Serialize;

/// The text of a name or of a string literal. Up to 24 bytes it is stored
/// inline, without a heap allocation: nearly every code_aster keyword, concept
/// name and string value fits, and these were 60 % of the allocations (and
/// of the frees) of parsing the v17 corpus. It derefs to `str`.
pub type Text = compact_str::CompactString;

/// A whole file.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Module {
    pub body: Vec<Stmt>,
    pub span: Span,
}

/// A name as written in the source (variable, keyword argument, attribute).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Ident {
    pub name: Text,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stmt {
    #[serde(flatten)]
    pub kind: StmtKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "stmt")]
pub enum StmtKind {
    /// An expression evaluated for its effect, e.g. `DEBUT()`.
    Expr {
        value: Expr,
    },
    /// `a = b = value`; targets may be names, tuples/lists, attributes, subscripts.
    Assign {
        targets: Vec<Expr>,
        value: Expr,
    },
    /// `target op= value`.
    AugAssign {
        target: Expr,
        op: BinOp,
        value: Expr,
    },
    /// `target: annotation [= value]`.
    AnnAssign {
        target: Expr,
        annotation: Expr,
        value: Option<Expr>,
    },
    If {
        test: Expr,
        body: Vec<Stmt>,
        orelse: Vec<Stmt>,
    },
    For {
        target: Expr,
        iter: Expr,
        body: Vec<Stmt>,
        orelse: Vec<Stmt>,
    },
    While {
        test: Expr,
        body: Vec<Stmt>,
        orelse: Vec<Stmt>,
    },
    FunctionDef {
        name: Ident,
        params: Vec<Param>,
        body: Vec<Stmt>,
        decorators: Vec<Expr>,
    },
    ClassDef {
        name: Ident,
        bases: Vec<Arg>,
        body: Vec<Stmt>,
        decorators: Vec<Expr>,
    },
    Return {
        value: Option<Expr>,
    },
    /// `import a.b as c, d`.
    Import {
        names: Vec<Alias>,
    },
    /// `from ..a.b import c as d` (`level` counts the leading dots);
    /// `names` is empty for `import *`.
    ImportFrom {
        module: Option<String>,
        level: u32,
        names: Vec<Alias>,
        star: bool,
    },
    Try {
        body: Vec<Stmt>,
        handlers: Vec<ExceptHandler>,
        orelse: Vec<Stmt>,
        finalbody: Vec<Stmt>,
    },
    With {
        items: Vec<WithItem>,
        body: Vec<Stmt>,
    },
    Raise {
        exc: Option<Expr>,
        cause: Option<Expr>,
    },
    Assert {
        test: Expr,
        msg: Option<Expr>,
    },
    Del {
        targets: Vec<Expr>,
    },
    Global {
        names: Vec<Ident>,
    },
    Nonlocal {
        names: Vec<Ident>,
    },
    Pass,
    Break,
    Continue,
    /// Python 2 `print x, y` / `print >>f, x` (legacy files).
    Print {
        dest: Option<Expr>,
        values: Vec<Expr>,
        /// False when the statement ends with a comma (no newline printed).
        newline: bool,
    },
    /// Python 2 `exec code [in globals[, locals]]`.
    Exec {
        code: Expr,
        globals: Option<Expr>,
        locals: Option<Expr>,
    },
}

/// `name` or `module.path` imported, with an optional `as` name.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Alias {
    pub name: String,
    pub asname: Option<Ident>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExceptHandler {
    /// The exception type(s); `None` for a bare `except:`.
    pub typ: Option<Expr>,
    /// `except E as e:` (or Python 2 `except E, e:`).
    pub name: Option<Ident>,
    pub body: Vec<Stmt>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WithItem {
    pub context: Expr,
    pub target: Option<Expr>,
}

/// A formal parameter of `def` or `lambda`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Param {
    pub name: Ident,
    pub kind: ParamKind,
    pub default: Option<Expr>,
    pub annotation: Option<Expr>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum ParamKind {
    /// An ordinary (positional-or-keyword, or keyword-only after `*`) parameter.
    Normal,
    /// `*args`
    VarArgs,
    /// `**kwargs`
    KwArgs,
    /// A bare `*` separating keyword-only parameters (its `name` is `*`).
    KwOnlyMarker,
    /// A bare `/` ending positional-only parameters (its `name` is `/`).
    PosOnlyMarker,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Expr {
    #[serde(flatten)]
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "expr")]
pub enum ExprKind {
    Name {
        id: Text,
    },
    /// Integer literal (decimal, hex, octal, binary; Python 2 `L` suffix accepted).
    /// Integers that do not fit an `i64` become [`ExprKind::Float`].
    Int {
        value: i64,
    },
    Float {
        value: f64,
    },
    /// Imaginary literal `2j`.
    Imag {
        value: f64,
    },
    /// A string literal, after escape processing and implicit concatenation.
    Str {
        value: Text,
    },
    Bytes {
        value: Vec<u8>,
    },
    /// An f-string (or a concatenation containing one).
    FString {
        parts: Vec<FStringPart>,
    },
    Bool {
        value: bool,
    },
    None,
    Ellipsis,
    List {
        elts: Vec<Expr>,
    },
    Tuple {
        elts: Vec<Expr>,
    },
    Set {
        elts: Vec<Expr>,
    },
    /// `{k: v, **m}`: a `None` key is a `**` unpacking.
    Dict {
        items: Vec<DictItem>,
    },
    Attribute {
        value: Box<Expr>,
        attr: Ident,
    },
    Subscript {
        value: Box<Expr>,
        index: Box<Expr>,
    },
    /// `lower:upper:step` inside a subscript.
    Slice {
        lower: Option<Box<Expr>>,
        upper: Option<Box<Expr>>,
        step: Option<Box<Expr>>,
    },
    Call {
        func: Box<Expr>,
        args: Vec<Arg>,
    },
    BinOp {
        left: Box<Expr>,
        op: BinOp,
        right: Box<Expr>,
    },
    UnaryOp {
        op: UnaryOp,
        operand: Box<Expr>,
    },
    /// `a and b and c` / `a or b`.
    BoolOp {
        op: BoolOp,
        values: Vec<Expr>,
    },
    /// `a < b <= c`.
    Compare {
        left: Box<Expr>,
        ops: Vec<(CmpOp, Expr)>,
    },
    /// `body if test else orelse`.
    IfExp {
        test: Box<Expr>,
        body: Box<Expr>,
        orelse: Box<Expr>,
    },
    Lambda {
        params: Vec<Param>,
        body: Box<Expr>,
    },
    ListComp {
        elt: Box<Expr>,
        generators: Vec<Comprehension>,
    },
    SetComp {
        elt: Box<Expr>,
        generators: Vec<Comprehension>,
    },
    GeneratorExp {
        elt: Box<Expr>,
        generators: Vec<Comprehension>,
    },
    DictComp {
        key: Box<Expr>,
        value: Box<Expr>,
        generators: Vec<Comprehension>,
    },
    /// `*x` in a call, list, tuple or assignment target.
    Starred {
        value: Box<Expr>,
    },
    Yield {
        value: Option<Box<Expr>>,
    },
    YieldFrom {
        value: Box<Expr>,
    },
    Await {
        value: Box<Expr>,
    },
    /// `name := value`.
    NamedExpr {
        target: Ident,
        value: Box<Expr>,
    },
    /// Python 2 backquotes `` `x` `` (= `repr(x)`).
    Repr {
        value: Box<Expr>,
    },
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DictItem {
    pub key: Option<Expr>,
    pub value: Expr,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "part")]
pub enum FStringPart {
    Literal {
        value: String,
    },
    Field {
        value: Expr,
        /// `!r`, `!s`, `!a`
        conversion: Option<char>,
        /// The format spec after `:`, itself possibly containing fields.
        format_spec: Vec<FStringPart>,
        /// `f"{x=}"`
        debug: bool,
    },
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comprehension {
    pub target: Expr,
    pub iter: Expr,
    pub ifs: Vec<Expr>,
    pub is_async: bool,
}

/// An argument in a call.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Arg {
    #[serde(flatten)]
    pub kind: ArgKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "arg")]
pub enum ArgKind {
    Positional {
        value: Expr,
    },
    /// `NAME=value`: for commands, a keyword (`MAILLAGE=MA`).
    Keyword {
        name: Ident,
        value: Expr,
    },
    /// `*args`
    Star {
        value: Expr,
    },
    /// `**kwargs`
    DoubleStar {
        value: Expr,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    MatMul,
    Div,
    FloorDiv,
    Mod,
    Pow,
    LShift,
    RShift,
    BitOr,
    BitXor,
    BitAnd,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum UnaryOp {
    /// `-x`
    Neg,
    /// `+x`
    Pos,
    /// `not x`
    Not,
    /// `~x`
    Invert,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum BoolOp {
    And,
    Or,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum CmpOp {
    Eq,
    /// `!=` (and Python 2 `<>`)
    NotEq,
    Lt,
    LtE,
    Gt,
    GtE,
    Is,
    IsNot,
    In,
    NotIn,
}

// ---------------------------------------------------------------- dropping

/// A node whose children are being dropped (see [`drop_bounded`]); only
/// its own drop matters.
#[allow(dead_code)]
enum Detached {
    Expr(ExprKind),
    Stmt(StmtKind),
}

/// How many nested drops run on the native stack before deeper nodes are
/// deferred to the loop of the outermost drop.
const DROP_NESTING: u32 = 200;

thread_local! {
    static DROP_DEPTH: std::cell::Cell<u32> = const { std::cell::Cell::new(0) };
    static DEFERRED: std::cell::RefCell<Vec<Detached>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Drops a node's children with bounded recursion: the usual nested drop up
/// to [`DROP_NESTING`] levels, deeper nodes are queued and dropped by the
/// outermost call's loop. A tree of any depth (a rejected `1 + 1 + …` of a
/// million terms) is freed without exhausting the stack.
fn drop_bounded(node: Detached) {
    let depth = DROP_DEPTH.with(|d| d.get());
    if depth >= DROP_NESTING {
        DEFERRED.with(|q| q.borrow_mut().push(node));
        return;
    }
    DROP_DEPTH.with(|d| d.set(depth + 1));
    drop(node);
    if depth == 0 {
        while let Some(next) = DEFERRED.with(|q| q.borrow_mut().pop()) {
            drop(next);
        }
    }
    DROP_DEPTH.with(|d| d.set(depth));
}

impl Expr {
    /// The node's kind, moved out (a node with `Drop` cannot be destructured).
    pub fn into_kind(mut self) -> ExprKind {
        std::mem::replace(&mut self.kind, ExprKind::None)
    }
}

impl Stmt {
    /// The statement's kind, moved out (a node with `Drop` cannot be destructured).
    pub fn into_kind(mut self) -> StmtKind {
        std::mem::replace(&mut self.kind, StmtKind::Pass)
    }
}

impl Drop for Expr {
    fn drop(&mut self) {
        match self.kind {
            // Leaves: nothing nested to drop (their text frees itself).
            ExprKind::Name { .. }
            | ExprKind::Int { .. }
            | ExprKind::Float { .. }
            | ExprKind::Imag { .. }
            | ExprKind::Str { .. }
            | ExprKind::Bytes { .. }
            | ExprKind::Bool { .. }
            | ExprKind::None
            | ExprKind::Ellipsis => {}
            _ => drop_bounded(Detached::Expr(std::mem::replace(
                &mut self.kind,
                ExprKind::None,
            ))),
        }
    }
}

impl Drop for Stmt {
    fn drop(&mut self) {
        match self.kind {
            StmtKind::Pass | StmtKind::Break | StmtKind::Continue => {}
            _ => drop_bounded(Detached::Stmt(std::mem::replace(
                &mut self.kind,
                StmtKind::Pass,
            ))),
        }
    }
}
