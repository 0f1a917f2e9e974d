//! The catalog's own data model: commands, keywords, blocks, rules.
//!
//! Generated once from code_aster's keyword facts by `examples/gen_catalog.rs`
//! into `data/catalog-v17.json`; the build script turns that JSON into static
//! tables of these types (`build.rs`), so every string and list here is
//! `&'static` and nothing is read or allocated when the catalog is used.

use serde::Serialize;
use std::sync::OnceLock;

/// A literal of the catalog: a default or an allowed value.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Lit {
    Int(i64),
    Real(f64),
    Str(&'static str),
}

impl std::fmt::Display for Lit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Lit::Int(i) => write!(f, "{i}"),
            Lit::Real(r) => write!(f, "{}", fmt_real(*r)),
            Lit::Str(s) => write!(f, "'{s}'"),
        }
    }
}

/// A real as Python prints it (`1.0`, `1e-06`, `2e+16`).
pub fn fmt_real(r: f64) -> String {
    if !r.is_finite() {
        return format!("{r}");
    }
    if r != 0.0 && (r.abs() < 1e-4 || r.abs() >= 1e16) {
        let e = format!("{r:e}");
        return match e.split_once('e') {
            Some((m, x)) => {
                let x: i32 = x.parse().unwrap_or(0);
                format!("{m}e{}{:02}", if x < 0 { '-' } else { '+' }, x.abs())
            }
            None => e,
        };
    }
    if r == r.trunc() {
        format!("{r:.1}")
    } else {
        format!("{r}")
    }
}

/// Whether a keyword must be given.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
pub enum Status {
    /// `o`: obligatory.
    #[serde(rename = "o")]
    Mandatory,
    /// `f`: optional.
    #[serde(rename = "f")]
    Optional,
    /// `d`: a factor keyword always present (created with its defaults).
    #[serde(rename = "d")]
    Defaulted,
    /// `c`: hidden (set by the system, e.g. `reuse`).
    #[serde(rename = "c")]
    Hidden,
}

impl Status {
    pub fn describe(self) -> &'static str {
        match self {
            Status::Mandatory => "mandatory",
            Status::Optional => "optional",
            Status::Defaulted => "always present (defaults filled)",
            Status::Hidden => "hidden",
        }
    }
}

/// The maximum number of values/occurrences.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(untagged)]
pub enum Max {
    Count(u32),
    /// `**`: unbounded.
    Unbounded(Unbounded),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Unbounded {
    #[serde(rename = "**")]
    Stars,
}

impl Max {
    pub fn allows(self, n: usize) -> bool {
        match self {
            Max::Count(m) => n <= m as usize,
            Max::Unbounded(_) => true,
        }
    }
    pub fn describe(self) -> String {
        match self {
            Max::Count(m) => m.to_string(),
            Max::Unbounded(_) => "unbounded".into(),
        }
    }
}

/// One of the accepted types of a simple keyword.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(into = "&str")]
pub enum ValueType {
    /// `R`
    Real,
    /// `I`
    Int,
    /// `TXM`
    Text,
    /// `C`
    Complex,
    /// `grma`: a cell group name.
    GroupMa,
    /// `grno`: a node group name.
    GroupNo,
    /// `ma`: a cell name.
    Cell,
    /// `no`: a node name.
    Node,
    /// `CO`: a concept created by a macro (`CO('name')`).
    Co,
    /// A logical unit number (`UnitDefault`, `UnitMed`).
    Unit,
    /// Anything (`not_checked`, `DataStructure`).
    Any,
    /// A concept type such as `maillage_sdaster`.
    Concept(&'static str),
}

include!("type_codes.rs");

impl From<&'static str> for ValueType {
    fn from(s: &'static str) -> ValueType {
        TYPE_CODES
            .iter()
            .find(|(code, _)| *code == s)
            .map_or(ValueType::Concept(s), |&(_, t)| t)
    }
}

impl From<ValueType> for &'static str {
    fn from(t: ValueType) -> &'static str {
        t.code()
    }
}

impl ValueType {
    pub fn code(&self) -> &'static str {
        match self {
            ValueType::Concept(s) => s,
            t => TYPE_CODES
                .iter()
                .find(|(_, u)| u == t)
                .map_or("", |&(code, _)| code),
        }
    }

    /// How an error message names it.
    pub fn describe(&self) -> String {
        match self {
            ValueType::Real => "a real (R)".into(),
            ValueType::Int => "an integer (I)".into(),
            ValueType::Text => "a text (TXM)".into(),
            ValueType::Complex => "a complex (C)".into(),
            ValueType::GroupMa => "a cell group name (grma)".into(),
            ValueType::GroupNo => "a node group name (grno)".into(),
            ValueType::Cell => "a cell name (ma)".into(),
            ValueType::Node => "a node name (no)".into(),
            ValueType::Co => "a concept to create, CO('name')".into(),
            ValueType::Unit => "a logical unit (I)".into(),
            ValueType::Any => "any value".into(),
            ValueType::Concept(s) => format!("a concept of type {s}"),
        }
    }
}

/// A value computed on first use and kept: the parsed condition of a block,
/// the default of a keyword as conditions see it. It lives inside the static
/// catalog, so it is made at most once per process. It takes no part in
/// equality (two keywords are equal whether or not their caches are filled)
/// nor in serialisation.
pub struct Cache<T>(OnceLock<T>);

impl<T> Cache<T> {
    pub const fn new() -> Cache<T> {
        Cache(OnceLock::new())
    }
    pub fn get_or_init(&self, f: impl FnOnce() -> T) -> &T {
        self.0.get_or_init(f)
    }
}

impl<T> Default for Cache<T> {
    fn default() -> Self {
        Cache::new()
    }
}

impl<T: Clone> Clone for Cache<T> {
    fn clone(&self) -> Self {
        Cache(self.0.clone())
    }
}

impl<T> PartialEq for Cache<T> {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl<T> std::fmt::Debug for Cache<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Cache")
    }
}

/// A simple keyword: a list of values.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SimpleKw {
    #[serde(rename = "s")]
    pub status: Status,
    /// Accepted types (any of them).
    #[serde(rename = "t", skip_serializing_if = "<[_]>::is_empty")]
    pub types: &'static [ValueType],
    #[serde(rename = "into", skip_serializing_if = "Option::is_none")]
    pub into: Option<&'static [Lit]>,
    /// The default value(s).
    #[serde(rename = "d", skip_serializing_if = "Option::is_none")]
    pub default: Option<&'static [Lit]>,
    #[serde(skip_serializing_if = "is_one")]
    pub min: u32,
    #[serde(skip_serializing_if = "is_max_one")]
    pub max: Max,
    #[serde(rename = "lo", skip_serializing_if = "Option::is_none")]
    pub val_min: Option<f64>,
    #[serde(rename = "hi", skip_serializing_if = "Option::is_none")]
    pub val_max: Option<f64>,
    /// `default` as block conditions see it, made on first use (see
    /// [`SimpleKw::default_cval`]).
    #[serde(skip)]
    pub default_cond: Cache<Option<crate::cond::CVal>>,
}

impl SimpleKw {
    /// The default as block conditions see it: a scalar, or a tuple when
    /// several values (made once, on first use).
    pub fn default_cval(&self) -> Option<&crate::cond::CVal> {
        self.default_cond
            .get_or_init(|| self.default.map(lits_cval))
            .as_ref()
    }
}

/// Catalog literals as a condition value: one value is a scalar, several a
/// tuple.
pub fn lits_cval(v: &[Lit]) -> crate::cond::CVal {
    use crate::cond::CVal;
    let one = |l: &Lit| match l {
        Lit::Int(i) => CVal::Int(*i),
        Lit::Real(r) => CVal::Real(*r),
        Lit::Str(s) => CVal::Str(s.to_string()),
    };
    match v {
        [x] => one(x),
        many => CVal::Tuple(many.iter().map(one).collect()),
    }
}

fn is_one(v: &u32) -> bool {
    *v == 1
}
fn is_max_one(m: &Max) -> bool {
    *m == Max::Count(1)
}

/// A factor keyword: occurrences of `_F(...)`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FactorKw {
    #[serde(rename = "s")]
    pub status: Status,
    #[serde(skip_serializing_if = "is_one")]
    pub min: u32,
    #[serde(skip_serializing_if = "is_max_one")]
    pub max: Max,
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    pub rules: &'static [Rule],
    #[serde(rename = "k")]
    pub keywords: &'static [Entry],
}

/// A conditional block: its keywords apply when `condition` holds.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Block {
    /// The condition as written in the catalog (a Python expression).
    #[serde(rename = "if")]
    pub condition: &'static str,
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    pub rules: &'static [Rule],
    #[serde(rename = "k")]
    pub keywords: &'static [Entry],
    /// `condition` parsed, on first use (see [`Block::cond`]).
    #[serde(skip)]
    pub parsed: Cache<Result<crate::cond::Cond, String>>,
}

impl Block {
    /// The parsed condition (parsed once, on first use).
    pub fn cond(&self) -> &Result<crate::cond::Cond, String> {
        self.parsed
            .get_or_init(|| crate::cond::parse(self.condition))
    }
}

#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind")]
pub enum Node {
    #[serde(rename = "S")]
    Simple(SimpleKw),
    #[serde(rename = "F")]
    Factor(FactorKw),
    #[serde(rename = "B")]
    Block(Block),
}

/// A named entry of a keyword level (blocks are named too: `b_xxx`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Entry {
    #[serde(rename = "n")]
    pub name: &'static str,
    #[serde(flatten)]
    pub node: Node,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
pub enum RuleKind {
    ExactlyOne,
    AtMostOne,
    AtLeastOne,
    AllTogether,
    OnlyFirstPresent,
    IfFirstAllPresent,
    NotEmpty,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Rule {
    #[serde(rename = "r")]
    pub kind: RuleKind,
    #[serde(rename = "a")]
    pub args: &'static [&'static str],
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
pub enum CommandKind {
    Operator,
    Macro,
    Procedure,
    Formule,
}

/// What a command produces.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Produces {
    /// Nothing (a procedure).
    Nothing,
    /// Always this concept type.
    Type(&'static str),
    /// Computed from the arguments by a code_aster function (`crea_champ_prod`).
    Computed(&'static str),
}

/// How `reuse=` is accepted.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Reentrant {
    /// `n`: never.
    No,
    /// `f:KW` / `o:KW`: optional/mandatory; the reused concept must also be
    /// given under one of the keyword paths (`RESULTAT`, `ETAT_INIT:EVOL_NOLI`).
    Yes {
        mandatory: bool,
        keywords: &'static [&'static str],
    },
    /// Not stated by the catalog (`""`): accepted.
    Unstated,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Command {
    pub name: &'static str,
    pub kind: CommandKind,
    pub produces: Produces,
    pub reentrant: Reentrant,
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    pub rules: &'static [Rule],
    #[serde(rename = "k")]
    pub keywords: &'static [Entry],
}

impl Command {
    /// Finds a keyword by name anywhere at the top level of this command,
    /// looking inside blocks (first match wins).
    pub fn find(&self, name: &str) -> Option<&'static Entry> {
        find_in(self.keywords, name)
    }
}

/// Whether two keyword names are equal. Names of one level often share
/// their length and prefix (`GROUP_MA`, `GROUP_NO`): comparing the last
/// byte first settles most pairs without a call to `memcmp`.
#[inline]
pub fn same_name(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.as_bytes().last() == b.as_bytes().last() && a == b
}

/// Finds a keyword at one level, looking through blocks.
pub fn find_in<'a>(entries: &'a [Entry], name: &str) -> Option<&'a Entry> {
    for e in entries {
        if same_name(e.name, name) {
            return Some(e);
        }
        if let Node::Block(b) = &e.node {
            if let Some(found) = find_in(b.keywords, name) {
                return Some(found);
            }
        }
    }
    None
}

/// All keyword names of one level (through blocks), deduplicated, in order.
pub fn names_in(entries: &[Entry]) -> Vec<&str> {
    let mut out: Vec<&str> = Vec::new();
    fn walk<'a>(entries: &'a [Entry], out: &mut Vec<&'a str>) {
        for e in entries {
            match &e.node {
                Node::Block(b) => walk(b.keywords, out),
                _ => {
                    if !out.contains(&e.name) {
                        out.push(e.name)
                    }
                }
            }
        }
    }
    walk(entries, &mut out);
    out
}
