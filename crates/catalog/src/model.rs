//! The catalog's own data model: commands, keywords, blocks, rules.
//!
//! Generated once from code_aster's keyword facts by `examples/gen_catalog.rs`
//! and embedded as compact JSON (see `data/catalog-v17.json`).

use serde::{Deserialize, Serialize};

/// A literal of the catalog: a default or an allowed value.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Lit {
    Int(i64),
    Real(f64),
    Str(String),
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
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
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

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
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
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "String", into = "String")]
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
    Concept(String),
}

impl From<String> for ValueType {
    fn from(s: String) -> ValueType {
        match s.as_str() {
            "R" => ValueType::Real,
            "I" => ValueType::Int,
            "TXM" => ValueType::Text,
            "C" => ValueType::Complex,
            "grma" => ValueType::GroupMa,
            "grno" => ValueType::GroupNo,
            "ma" => ValueType::Cell,
            "no" => ValueType::Node,
            "CO" => ValueType::Co,
            "UnitDefault" | "UnitMed" => ValueType::Unit,
            "not_checked" | "DataStructure" => ValueType::Any,
            _ => ValueType::Concept(s),
        }
    }
}

impl From<ValueType> for String {
    fn from(t: ValueType) -> String {
        t.code().to_string()
    }
}

impl ValueType {
    pub fn code(&self) -> &str {
        match self {
            ValueType::Real => "R",
            ValueType::Int => "I",
            ValueType::Text => "TXM",
            ValueType::Complex => "C",
            ValueType::GroupMa => "grma",
            ValueType::GroupNo => "grno",
            ValueType::Cell => "ma",
            ValueType::Node => "no",
            ValueType::Co => "CO",
            ValueType::Unit => "UnitDefault",
            ValueType::Any => "not_checked",
            ValueType::Concept(s) => s,
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

/// A simple keyword: a list of values.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SimpleKw {
    #[serde(rename = "s")]
    pub status: Status,
    /// Accepted types (any of them).
    #[serde(rename = "t", default, skip_serializing_if = "Vec::is_empty")]
    pub types: Vec<ValueType>,
    #[serde(rename = "into", default, skip_serializing_if = "Option::is_none")]
    pub into: Option<Vec<Lit>>,
    /// The default value(s).
    #[serde(rename = "d", default, skip_serializing_if = "Option::is_none")]
    pub default: Option<Vec<Lit>>,
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub min: u32,
    #[serde(default = "max_one", skip_serializing_if = "is_max_one")]
    pub max: Max,
    #[serde(rename = "lo", default, skip_serializing_if = "Option::is_none")]
    pub val_min: Option<f64>,
    #[serde(rename = "hi", default, skip_serializing_if = "Option::is_none")]
    pub val_max: Option<f64>,
    /// `default` as block conditions see it (a scalar, or a tuple when
    /// several values), made once when the catalog loads.
    #[serde(skip)]
    pub default_cond: Option<crate::cond::CVal>,
}

impl SimpleKw {
    /// The default as block conditions see it (see `default_cond`).
    pub fn default_cval(&self) -> Option<std::borrow::Cow<'_, crate::cond::CVal>> {
        use std::borrow::Cow;
        match (&self.default_cond, &self.default) {
            (Some(c), _) => Some(Cow::Borrowed(c)),
            (None, Some(d)) => Some(Cow::Owned(lits_cval(d))),
            (None, None) => None,
        }
    }
}

/// Catalog literals as a condition value: one value is a scalar, several a
/// tuple.
pub fn lits_cval(v: &[Lit]) -> crate::cond::CVal {
    use crate::cond::CVal;
    let one = |l: &Lit| match l {
        Lit::Int(i) => CVal::Int(*i),
        Lit::Real(r) => CVal::Real(*r),
        Lit::Str(s) => CVal::Str(s.clone()),
    };
    match v {
        [x] => one(x),
        many => CVal::Tuple(many.iter().map(one).collect()),
    }
}

fn one() -> u32 {
    1
}
fn is_one(v: &u32) -> bool {
    *v == 1
}
fn max_one() -> Max {
    Max::Count(1)
}
fn is_max_one(m: &Max) -> bool {
    *m == Max::Count(1)
}

/// A factor keyword: occurrences of `_F(...)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FactorKw {
    #[serde(rename = "s")]
    pub status: Status,
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub min: u32,
    #[serde(default = "max_one", skip_serializing_if = "is_max_one")]
    pub max: Max,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rules: Vec<Rule>,
    #[serde(rename = "k")]
    pub keywords: Vec<Entry>,
}

/// A conditional block: its keywords apply when `condition` holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Block {
    /// The condition as written in the catalog (a Python expression).
    #[serde(rename = "if")]
    pub condition: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rules: Vec<Rule>,
    #[serde(rename = "k")]
    pub keywords: Vec<Entry>,
    /// `condition` parsed, once, when the catalog loads (`None` in a
    /// catalog built by hand; see [`Block::cond`]).
    #[serde(skip)]
    pub parsed: Option<Result<crate::cond::Cond, String>>,
}

impl Block {
    /// The parsed condition (parsed now if the catalog did not do it).
    pub fn cond(&self) -> std::borrow::Cow<'_, Result<crate::cond::Cond, String>> {
        match &self.parsed {
            Some(c) => std::borrow::Cow::Borrowed(c),
            None => std::borrow::Cow::Owned(crate::cond::parse(&self.condition)),
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::load::RawEntry")]
pub struct Entry {
    #[serde(rename = "n")]
    pub name: String,
    #[serde(flatten)]
    pub node: Node,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum RuleKind {
    ExactlyOne,
    AtMostOne,
    AtLeastOne,
    AllTogether,
    OnlyFirstPresent,
    IfFirstAllPresent,
    NotEmpty,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rule {
    #[serde(rename = "r")]
    pub kind: RuleKind,
    #[serde(rename = "a")]
    pub args: Vec<String>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum CommandKind {
    Operator,
    Macro,
    Procedure,
    Formule,
}

/// What a command produces.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Produces {
    /// Nothing (a procedure).
    Nothing,
    /// Always this concept type.
    Type(String),
    /// Computed from the arguments by a code_aster function (`crea_champ_prod`).
    Computed(String),
}

/// How `reuse=` is accepted.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Reentrant {
    /// `n`: never.
    No,
    /// `f:KW` / `o:KW`: optional/mandatory; the reused concept must also be
    /// given under one of the keyword paths (`RESULTAT`, `ETAT_INIT:EVOL_NOLI`).
    Yes {
        mandatory: bool,
        keywords: Vec<String>,
    },
    /// Not stated by the catalog (`""`): accepted.
    Unstated,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Command {
    pub name: String,
    pub kind: CommandKind,
    pub produces: Produces,
    pub reentrant: Reentrant,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rules: Vec<Rule>,
    #[serde(rename = "k")]
    pub keywords: Vec<Entry>,
}

impl Command {
    /// Finds a keyword by name anywhere at the top level of this command,
    /// looking inside blocks (first match wins).
    pub fn find(&self, name: &str) -> Option<&Entry> {
        find_in(&self.keywords, name)
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
        if same_name(&e.name, name) {
            return Some(e);
        }
        if let Node::Block(b) = &e.node {
            if let Some(found) = find_in(&b.keywords, name) {
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
                Node::Block(b) => walk(&b.keywords, out),
                _ => {
                    if !out.contains(&e.name.as_str()) {
                        out.push(&e.name)
                    }
                }
            }
        }
    }
    walk(entries, &mut out);
    out
}
