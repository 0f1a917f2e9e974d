//! Block conditions: the small Python expressions of the catalog
//! (`equal_to("FORMULATION", 'CONTINUE') and not exists("FROTTEMENT")`,
//! `is_type("RESULTAT") in (evol_elas, evol_noli)`, `value("RELATION").startswith('META_')`).
//!
//! They are parsed once into a [`Cond`] tree and evaluated against the
//! keyword values of the current level through a [`CondEnv`].

use std::fmt;

/// A value seen by a condition.
#[derive(Clone, Debug, PartialEq)]
pub enum CVal {
    None,
    Bool(bool),
    Int(i64),
    Real(f64),
    Str(String),
    Tuple(Vec<CVal>),
    /// A type name (`evol_noli`, `list`).
    Type(String),
}

impl CVal {
    fn truthy(&self) -> bool {
        match self {
            CVal::None => false,
            CVal::Bool(b) => *b,
            CVal::Int(i) => *i != 0,
            CVal::Real(r) => *r != 0.0,
            CVal::Str(s) => !s.is_empty(),
            CVal::Tuple(t) => !t.is_empty(),
            CVal::Type(_) => true,
        }
    }

    fn num(&self) -> Option<f64> {
        match self {
            CVal::Int(i) => Some(*i as f64),
            CVal::Real(r) => Some(*r),
            CVal::Bool(b) => Some(*b as i64 as f64),
            _ => None,
        }
    }

    fn py_eq(&self, other: &CVal) -> bool {
        match (self.num(), other.num()) {
            (Some(a), Some(b)) => a == b,
            _ => self == other,
        }
    }

    /// The values as a list (a scalar is a list of one).
    fn items(&self) -> Vec<CVal> {
        self.as_slice().to_vec()
    }

    /// The values as a slice, without copying them.
    fn as_slice(&self) -> &[CVal] {
        match self {
            CVal::Tuple(t) => t,
            CVal::None => &[],
            v => std::slice::from_ref(v),
        }
    }
}

/// What a condition can ask about the keywords of its level.
pub trait CondEnv {
    /// The value of a keyword (a scalar, or a tuple when several values),
    /// `None` if absent. Borrowed: conditions are evaluated for every block
    /// of every call, and copying values would dominate their cost.
    fn value(&self, keyword: &str) -> Option<&CVal>;
    /// The concept type of a keyword's (first) value, if it is a concept.
    fn type_of(&self, keyword: &str) -> Option<&str>;
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CmpOp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    In,
    NotIn,
    Is,
    IsNot,
}

/// A parsed condition.
#[derive(Clone, Debug, PartialEq)]
pub enum Cond {
    Lit(CVal),
    Name(String),
    Tuple(Vec<Cond>),
    Call(String, Vec<Cond>),
    Method(Box<Cond>, String, Vec<Cond>),
    Index(Box<Cond>, Box<Cond>),
    Slice(Box<Cond>, Option<Box<Cond>>, Option<Box<Cond>>),
    Neg(Box<Cond>),
    Not(Box<Cond>),
    And(Box<Cond>, Box<Cond>),
    Or(Box<Cond>, Box<Cond>),
    Compare(Box<Cond>, Vec<(CmpOp, Cond)>),
    IfElse(Box<Cond>, Box<Cond>, Box<Cond>),
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Name(String),
    Int(i64),
    Real(f64),
    Str(String),
    Op(&'static str),
}

fn tokenize(src: &str) -> Result<Vec<Tok>, String> {
    let b = src.as_bytes();
    let mut i = 0;
    let mut out = Vec::new();
    while i < b.len() {
        let c = b[i] as char;
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_alphabetic() || c == '_' {
            let s = i;
            while i < b.len() && ((b[i] as char).is_ascii_alphanumeric() || b[i] == b'_') {
                i += 1;
            }
            out.push(Tok::Name(src[s..i].to_string()));
        } else if c.is_ascii_digit() || (c == '.' && i + 1 < b.len() && b[i + 1].is_ascii_digit()) {
            let s = i;
            let mut real = false;
            while i < b.len() {
                let d = b[i] as char;
                if d.is_ascii_digit() {
                    i += 1;
                } else if d == '.' {
                    real = true;
                    i += 1;
                } else if d == 'e' || d == 'E' {
                    real = true;
                    i += 1;
                    if i < b.len() && (b[i] == b'-' || b[i] == b'+') {
                        i += 1;
                    }
                } else {
                    break;
                }
            }
            let t = &src[s..i];
            out.push(if real {
                Tok::Real(t.parse().map_err(|_| format!("bad number `{t}`"))?)
            } else {
                Tok::Int(t.parse().map_err(|_| format!("bad number `{t}`"))?)
            });
        } else if c == '\'' || c == '"' {
            let s = i + 1;
            i += 1;
            while i < b.len() && b[i] as char != c {
                i += 1;
            }
            if i >= b.len() {
                return Err("unterminated string".into());
            }
            out.push(Tok::Str(src[s..i].to_string()));
            i += 1;
        } else {
            const OPS: [&str; 16] = [
                "==", "!=", "<=", ">=", "<", ">", "(", ")", "[", "]", ",", ":", ".", "-", "+", "*",
            ];
            let rest = &src[i..];
            let Some(op) = OPS.iter().find(|o| rest.starts_with(**o)) else {
                return Err(format!("unexpected character `{c}`"));
            };
            out.push(Tok::Op(op));
            i += op.len();
        }
    }
    Ok(out)
}

struct Parser {
    toks: Vec<Tok>,
    pos: usize,
}

impl Parser {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.pos)
    }
    fn is_op(&self, op: &str) -> bool {
        matches!(self.peek(), Some(Tok::Op(o)) if *o == op)
    }
    fn is_kw(&self, kw: &str) -> bool {
        matches!(self.peek(), Some(Tok::Name(n)) if n == kw)
    }
    fn expect_op(&mut self, op: &str) -> Result<(), String> {
        if self.is_op(op) {
            self.pos += 1;
            Ok(())
        } else {
            Err(format!("expected `{op}`, found {:?}", self.peek()))
        }
    }

    fn expr(&mut self) -> Result<Cond, String> {
        let body = self.or()?;
        if self.is_kw("if") {
            self.pos += 1;
            let test = self.or()?;
            if !self.is_kw("else") {
                return Err("expected `else`".into());
            }
            self.pos += 1;
            let orelse = self.expr()?;
            return Ok(Cond::IfElse(
                Box::new(test),
                Box::new(body),
                Box::new(orelse),
            ));
        }
        Ok(body)
    }
    fn or(&mut self) -> Result<Cond, String> {
        let mut l = self.and()?;
        while self.is_kw("or") {
            self.pos += 1;
            l = Cond::Or(Box::new(l), Box::new(self.and()?));
        }
        Ok(l)
    }
    fn and(&mut self) -> Result<Cond, String> {
        let mut l = self.not()?;
        while self.is_kw("and") {
            self.pos += 1;
            l = Cond::And(Box::new(l), Box::new(self.not()?));
        }
        Ok(l)
    }
    fn not(&mut self) -> Result<Cond, String> {
        if self.is_kw("not") {
            self.pos += 1;
            return Ok(Cond::Not(Box::new(self.not()?)));
        }
        self.compare()
    }
    fn cmp_op(&mut self) -> Option<CmpOp> {
        let op = match self.peek()? {
            Tok::Op("==") => CmpOp::Eq,
            Tok::Op("!=") => CmpOp::Ne,
            Tok::Op("<") => CmpOp::Lt,
            Tok::Op("<=") => CmpOp::Le,
            Tok::Op(">") => CmpOp::Gt,
            Tok::Op(">=") => CmpOp::Ge,
            Tok::Name(n) if n == "in" => CmpOp::In,
            Tok::Name(n) if n == "not" => {
                if matches!(self.toks.get(self.pos + 1), Some(Tok::Name(m)) if m == "in") {
                    self.pos += 1;
                    CmpOp::NotIn
                } else {
                    return None;
                }
            }
            Tok::Name(n) if n == "is" => {
                if matches!(self.toks.get(self.pos + 1), Some(Tok::Name(m)) if m == "not") {
                    self.pos += 1;
                    CmpOp::IsNot
                } else {
                    CmpOp::Is
                }
            }
            _ => return None,
        };
        self.pos += 1;
        Some(op)
    }
    fn compare(&mut self) -> Result<Cond, String> {
        let l = self.unary()?;
        let mut ops = Vec::new();
        while let Some(op) = self.cmp_op() {
            ops.push((op, self.unary()?));
        }
        Ok(if ops.is_empty() {
            l
        } else {
            Cond::Compare(Box::new(l), ops)
        })
    }
    fn unary(&mut self) -> Result<Cond, String> {
        if self.is_op("-") {
            self.pos += 1;
            return Ok(Cond::Neg(Box::new(self.unary()?)));
        }
        if self.is_op("+") {
            self.pos += 1;
            return self.unary();
        }
        self.postfix()
    }
    fn args(&mut self, close: &str) -> Result<Vec<Cond>, String> {
        let mut args = Vec::new();
        while !self.is_op(close) {
            args.push(self.expr()?);
            if self.is_op(",") {
                self.pos += 1;
            } else {
                break;
            }
        }
        self.expect_op(close)?;
        Ok(args)
    }
    fn postfix(&mut self) -> Result<Cond, String> {
        let mut e = self.atom()?;
        loop {
            if self.is_op("(") {
                self.pos += 1;
                let args = self.args(")")?;
                e = match e {
                    Cond::Name(f) => Cond::Call(f, args),
                    _ => return Err("only named functions can be called".into()),
                };
            } else if self.is_op(".") {
                self.pos += 1;
                let Some(Tok::Name(m)) = self.peek().cloned() else {
                    return Err("expected a method name".into());
                };
                self.pos += 1;
                self.expect_op("(")?;
                let args = self.args(")")?;
                e = Cond::Method(Box::new(e), m, args);
            } else if self.is_op("[") {
                self.pos += 1;
                let lo = if self.is_op(":") {
                    None
                } else {
                    Some(Box::new(self.expr()?))
                };
                if self.is_op(":") {
                    self.pos += 1;
                    let hi = if self.is_op("]") {
                        None
                    } else {
                        Some(Box::new(self.expr()?))
                    };
                    self.expect_op("]")?;
                    e = Cond::Slice(Box::new(e), lo, hi);
                } else {
                    self.expect_op("]")?;
                    let idx = lo.ok_or("empty subscript")?;
                    e = Cond::Index(Box::new(e), idx);
                }
            } else {
                return Ok(e);
            }
        }
    }
    fn atom(&mut self) -> Result<Cond, String> {
        let t = self.peek().cloned().ok_or("unexpected end of condition")?;
        self.pos += 1;
        Ok(match t {
            Tok::Int(i) => Cond::Lit(CVal::Int(i)),
            Tok::Real(r) => Cond::Lit(CVal::Real(r)),
            Tok::Str(s) => Cond::Lit(CVal::Str(s)),
            Tok::Name(n) => match n.as_str() {
                "True" => Cond::Lit(CVal::Bool(true)),
                "False" => Cond::Lit(CVal::Bool(false)),
                "None" => Cond::Lit(CVal::None),
                _ => Cond::Name(n),
            },
            Tok::Op("(") | Tok::Op("[") => {
                let close = if t == Tok::Op("(") { ")" } else { "]" };
                if self.is_op(close) {
                    self.pos += 1;
                    return Ok(Cond::Tuple(Vec::new()));
                }
                let first = self.expr()?;
                if self.is_op(close) && close == ")" {
                    self.pos += 1;
                    return Ok(first);
                }
                let mut items = vec![first];
                while self.is_op(",") {
                    self.pos += 1;
                    if self.is_op(close) {
                        break;
                    }
                    items.push(self.expr()?);
                }
                self.expect_op(close)?;
                Cond::Tuple(items)
            }
            other => return Err(format!("unexpected {other:?}")),
        })
    }
}

/// Parses a catalog condition.
pub fn parse(src: &str) -> Result<Cond, String> {
    let mut p = Parser {
        toks: tokenize(src)?,
        pos: 0,
    };
    let c = p.expr()?;
    if p.pos != p.toks.len() {
        return Err(format!("unexpected {:?} in condition `{src}`", p.peek()));
    }
    Ok(c)
}

/// The keyword named by a call's first argument (a literal in the catalog:
/// borrowed, not evaluated).
fn kw_name<'a>(
    args: &'a [Cond],
    env: &dyn CondEnv,
    f: &str,
) -> Result<std::borrow::Cow<'a, str>, String> {
    match args.first() {
        Some(Cond::Lit(CVal::Str(s))) => Ok(std::borrow::Cow::Borrowed(s)),
        Some(a) => match eval(a, env)? {
            CVal::Str(s) => Ok(std::borrow::Cow::Owned(s)),
            _ => Err(format!("{f}() expects a keyword name")),
        },
        None => Err(format!("{f}() expects a keyword name")),
    }
}

/// A sub-expression's value, borrowed when it is a literal.
fn eval_lit<'a>(c: &'a Cond, env: &dyn CondEnv) -> Result<std::borrow::Cow<'a, CVal>, String> {
    match c {
        Cond::Lit(v) => Ok(std::borrow::Cow::Borrowed(v)),
        other => eval(other, env).map(std::borrow::Cow::Owned),
    }
}

fn compare(op: CmpOp, a: &CVal, b: &CVal) -> Result<bool, String> {
    let ord = |a: &CVal, b: &CVal| -> Result<std::cmp::Ordering, String> {
        match (a.num(), b.num(), a, b) {
            (Some(x), Some(y), _, _) => x.partial_cmp(&y).ok_or_else(|| "NaN".to_string()),
            (_, _, CVal::Str(x), CVal::Str(y)) => Ok(x.cmp(y)),
            _ => Err(format!("cannot order {a:?} and {b:?}")),
        }
    };
    Ok(match op {
        CmpOp::Eq | CmpOp::Is => a.py_eq(b),
        CmpOp::Ne | CmpOp::IsNot => !a.py_eq(b),
        CmpOp::Lt => ord(a, b)?.is_lt(),
        CmpOp::Le => ord(a, b)?.is_le(),
        CmpOp::Gt => ord(a, b)?.is_gt(),
        CmpOp::Ge => ord(a, b)?.is_ge(),
        CmpOp::In | CmpOp::NotIn => {
            let found = match b {
                CVal::Str(s) => match a {
                    CVal::Str(x) => s.contains(x.as_str()),
                    _ => false,
                },
                CVal::None => false,
                other => other.items().iter().any(|x| x.py_eq(a)),
            };
            found == (op == CmpOp::In)
        }
    })
}

/// Evaluates a condition to a value.
pub fn eval(c: &Cond, env: &dyn CondEnv) -> Result<CVal, String> {
    Ok(match c {
        Cond::Lit(v) => v.clone(),
        Cond::Name(n) => match env.value(n) {
            Some(v) => v.clone(),
            None if n.chars().any(|c| c.is_ascii_lowercase()) => CVal::Type(n.clone()),
            None => CVal::None,
        },
        Cond::Tuple(items) => CVal::Tuple(
            items
                .iter()
                .map(|i| eval(i, env))
                .collect::<Result<_, _>>()?,
        ),
        Cond::Neg(e) => match eval(e, env)? {
            CVal::Int(i) => CVal::Int(-i),
            CVal::Real(r) => CVal::Real(-r),
            other => return Err(format!("cannot negate {other:?}")),
        },
        Cond::Not(e) => CVal::Bool(!eval(e, env)?.truthy()),
        Cond::And(a, b) => {
            let l = eval(a, env)?;
            if !l.truthy() {
                l
            } else {
                eval(b, env)?
            }
        }
        Cond::Or(a, b) => {
            let l = eval(a, env)?;
            if l.truthy() {
                l
            } else {
                eval(b, env)?
            }
        }
        Cond::IfElse(t, a, b) => {
            if eval(t, env)?.truthy() {
                eval(a, env)?
            } else {
                eval(b, env)?
            }
        }
        Cond::Compare(l, ops) => {
            let mut left = eval(l, env)?;
            for (op, r) in ops {
                let right = eval(r, env)?;
                if !compare(*op, &left, &right)? {
                    return Ok(CVal::Bool(false));
                }
                left = right;
            }
            CVal::Bool(true)
        }
        Cond::Index(v, i) => {
            let v = eval(v, env)?;
            let i = eval(i, env)?;
            let CVal::Int(i) = i else {
                return Err("index must be an integer".into());
            };
            match v {
                CVal::Str(s) => {
                    let chars: Vec<char> = s.chars().collect();
                    let i = if i < 0 { chars.len() as i64 + i } else { i };
                    CVal::Str(
                        chars
                            .get(i as usize)
                            .map(|c| c.to_string())
                            .ok_or("index out of range")?,
                    )
                }
                other => {
                    let items = other.items();
                    let i = if i < 0 { items.len() as i64 + i } else { i };
                    items.get(i as usize).cloned().ok_or("index out of range")?
                }
            }
        }
        Cond::Slice(v, lo, hi) => {
            let v = eval(v, env)?;
            let bound = |b: &Option<Box<Cond>>, n: usize, dflt: usize| -> Result<usize, String> {
                match b {
                    None => Ok(dflt),
                    Some(e) => match eval(e, env)? {
                        CVal::Int(i) if i < 0 => Ok((n as i64 + i).max(0) as usize),
                        CVal::Int(i) => Ok((i as usize).min(n)),
                        _ => Err("slice bound must be an integer".into()),
                    },
                }
            };
            match v {
                CVal::Str(s) => {
                    let chars: Vec<char> = s.chars().collect();
                    let (a, b) = (
                        bound(lo, chars.len(), 0)?,
                        bound(hi, chars.len(), chars.len())?,
                    );
                    CVal::Str(chars[a.min(b)..b].iter().collect())
                }
                other => {
                    let items = other.items();
                    let (a, b) = (
                        bound(lo, items.len(), 0)?,
                        bound(hi, items.len(), items.len())?,
                    );
                    CVal::Tuple(items[a.min(b)..b].to_vec())
                }
            }
        }
        Cond::Method(recv, m, args) => {
            let recv = eval(recv, env)?;
            let arg = args.first().map(|a| eval(a, env)).transpose()?;
            match (m.as_str(), recv, arg) {
                ("startswith", CVal::Str(s), Some(CVal::Str(p))) => CVal::Bool(s.starts_with(&p)),
                ("endswith", CVal::Str(s), Some(CVal::Str(p))) => CVal::Bool(s.ends_with(&p)),
                // An absent keyword: code_aster guards these with exists().
                (_, CVal::None, _) => CVal::Bool(false),
                (m, r, _) => return Err(format!("unsupported method {m} on {r:?}")),
            }
        }
        Cond::Call(f, args) => match f.as_str() {
            "exists" => CVal::Bool(env.value(&kw_name(args, env, f)?).is_some()),
            "value" => env
                .value(&kw_name(args, env, f)?)
                .cloned()
                .unwrap_or(CVal::None),
            "size" => CVal::Int(
                env.value(&kw_name(args, env, f)?)
                    .map(|v| v.as_slice().len() as i64)
                    .unwrap_or(0),
            ),
            "is_type" => env
                .type_of(&kw_name(args, env, f)?)
                .map(|t| CVal::Type(t.to_string()))
                .unwrap_or(CVal::None),
            "equal_to" | "is_in" | "greater_than" | "less_than" => {
                let k = kw_name(args, env, f)?;
                let Some(v) = env.value(&k) else {
                    return Ok(CVal::Bool(false));
                };
                let expected = match args.get(1) {
                    Some(a) => eval_lit(a, env)?,
                    None => return Err(format!("{f}() expects two arguments")),
                };
                let expected: &CVal = &expected;
                let items = v.as_slice();
                let hit = |x: &CVal| -> Result<bool, String> {
                    Ok(match f.as_str() {
                        // `equal_to('MODELISATION', ('3D_HHO', 'D_PLAN_HHO'))`
                        // is used in the catalog to mean "one of".
                        "equal_to" if matches!(expected, CVal::Tuple(_)) => {
                            compare(CmpOp::In, x, expected)?
                        }
                        "equal_to" => x.py_eq(expected),
                        "is_in" => compare(CmpOp::In, x, expected)?,
                        "greater_than" => compare(CmpOp::Gt, x, expected)?,
                        _ => compare(CmpOp::Lt, x, expected)?,
                    })
                };
                let mut any = false;
                for x in items {
                    any |= hit(x)?;
                }
                CVal::Bool(any)
            }
            "len" => match args.first().map(|a| eval(a, env)).transpose()? {
                Some(CVal::Str(s)) => CVal::Int(s.chars().count() as i64),
                Some(v) => CVal::Int(v.items().len() as i64),
                None => return Err("len() expects an argument".into()),
            },
            "abs" => match args.first().map(|a| eval(a, env)).transpose()? {
                Some(CVal::Int(i)) => CVal::Int(i.abs()),
                Some(CVal::Real(r)) => CVal::Real(r.abs()),
                other => return Err(format!("abs() of {other:?}")),
            },
            "type" => match args.first().map(|a| eval(a, env)).transpose()? {
                Some(CVal::Tuple(_)) => CVal::Type("tuple".into()),
                Some(CVal::Int(_)) => CVal::Type("int".into()),
                Some(CVal::Real(_)) => CVal::Type("float".into()),
                Some(CVal::Str(_)) => CVal::Type("str".into()),
                _ => CVal::Type("object".into()),
            },
            "AsType" => match args.first() {
                Some(Cond::Name(n)) => env
                    .type_of(n)
                    .map(|t| CVal::Type(t.to_string()))
                    .unwrap_or(CVal::None),
                _ => CVal::None,
            },
            other => return Err(format!("unknown function {other}() in condition")),
        },
    })
}

/// Evaluates a condition to a truth value.
pub fn holds(c: &Cond, env: &dyn CondEnv) -> Result<bool, String> {
    eval(c, env).map(|v| v.truthy())
}

impl fmt::Display for CVal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CVal::None => write!(f, "None"),
            CVal::Bool(b) => write!(f, "{}", if *b { "True" } else { "False" }),
            CVal::Int(i) => write!(f, "{i}"),
            CVal::Real(r) => write!(f, "{}", crate::model::fmt_real(*r)),
            CVal::Str(s) => write!(f, "'{s}'"),
            CVal::Type(t) => write!(f, "{t}"),
            CVal::Tuple(t) => {
                write!(f, "(")?;
                for (i, x) in t.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{x}")?;
                }
                write!(f, ")")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    struct Env(
        HashMap<&'static str, CVal>,
        HashMap<&'static str, &'static str>,
    );
    impl CondEnv for Env {
        fn value(&self, k: &str) -> Option<&CVal> {
            self.0.get(k)
        }
        fn type_of(&self, k: &str) -> Option<&str> {
            self.1.get(k).copied()
        }
    }

    fn env() -> Env {
        Env(
            HashMap::from([
                ("FORMULATION", CVal::Str("CONTINUE".into())),
                ("TYPE_CHAM", CVal::Str("ELGA_SIEF_R".into())),
                ("RELATION", CVal::Str("META_P_IL".into())),
                (
                    "FREQ",
                    CVal::Tuple(vec![CVal::Real(1.0), CVal::Real(2.0), CVal::Real(3.0)]),
                ),
                ("VALE_CALC", CVal::Real(1e-20)),
                ("NB", CVal::Int(-2)),
            ]),
            HashMap::from([("RESULTAT", "evol_noli")]),
        )
    }

    fn check(src: &str) -> bool {
        let c = parse(src).unwrap_or_else(|e| panic!("{src}: {e}"));
        holds(&c, &env()).unwrap_or_else(|e| panic!("{src}: {e}"))
    }

    #[test]
    fn catalog_forms() {
        assert!(check(
            r#"equal_to("FORMULATION", 'CONTINUE') and not equal_to("FROTTEMENT", 'COULOMB')"#
        ));
        assert!(!check(r#"equal_to("FORMULATION", 'DISCRETE')"#));
        assert!(check(r#"exists("TYPE_CHAM") and (TYPE_CHAM[0:2] == 'EL')"#));
        assert!(check(
            r#"is_type("RESULTAT") in (evol_elas,evol_noli,dyna_trans,)"#
        ));
        assert!(!check(r#"is_type("RESULTAT") == evol_ther"#));
        assert!(check(
            r#"value("RELATION").startswith('META_') and not value("RELATION").startswith('META_LEMA_ANI')"#
        ));
        assert!(check("size('FREQ') > 2"));
        assert!(check(r#"is_in("FREQ", (2.0, 7.0))"#));
        assert!(check("less_than('NB', 0)"));
        assert!(!check("greater_than('NB', 0)"));
        assert!(check(
            r#"exists("VALE_CALC") and abs(VALE_CALC if type(VALE_CALC) not in (list, tuple) else VALE_CALC[0]) < 1.e-16"#
        ));
        assert!(!check(r#"exists("CARA") and (len(CARA)==1)"#));
        assert!(check(r#"'MFRONT' not in value("RELATION_KIT")"#));
    }

    #[test]
    fn errors_are_reported() {
        assert!(parse("equal_to(").is_err());
        assert!(parse("a $ b").is_err());
        let c = parse("frobnicate('A')").unwrap();
        assert!(holds(&c, &env()).is_err());
    }
}
