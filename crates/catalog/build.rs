//! Turns the catalog JSON (`data/catalog-v17.json`) into static Rust tables
//! of the model's types (`src/model.rs`), so that the program parses nothing
//! and allocates nothing to use the catalog: `catalog().command(name)` is a
//! binary search in a sorted static array.
//!
//! The output is data, not code: one `static` array per distinct keyword
//! list (identical lists, such as the `COMPORTEMENT` of every non-linear
//! command, are written once and shared) and per distinct list of literals
//! used more than once. About 1 MB of Rust that rustc compiles in a few
//! seconds (docs/performance.md).

use serde_json::Value;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::PathBuf;

/// The value types' codes, shared with `src/model.rs` (`TYPE_CODES`); this
/// mirror of `ValueType` only lets the build script name the variants.
#[allow(dead_code)]
#[derive(Clone, Copy, Debug)]
enum ValueType {
    Real,
    Int,
    Text,
    Complex,
    GroupMa,
    GroupNo,
    Cell,
    Node,
    Co,
    Unit,
    Any,
    Concept(&'static str),
}
include!("src/type_codes.rs");

#[derive(Default)]
struct Gen {
    /// The statics, in the order they were made.
    out: String,
    /// Keyword lists already written: their JSON → their static's name.
    lists: HashMap<String, String>,
    /// Literal lists seen: their JSON → (uses, static's name once written).
    lits: HashMap<String, (usize, Option<String>)>,
    /// Literal statics written so far.
    nlits: usize,
}

fn str_field<'a>(v: &'a Value, k: &str, at: &str) -> &'a str {
    v.get(k)
        .and_then(Value::as_str)
        .unwrap_or_else(|| panic!("{at}: `{k}` is not a string"))
}

fn strs(v: &Value, at: &str) -> String {
    let items: Vec<String> = v
        .as_array()
        .unwrap_or_else(|| panic!("{at}: not an array"))
        .iter()
        .map(|s| {
            format!(
                "{:?}",
                s.as_str().unwrap_or_else(|| panic!("{at}: not a string"))
            )
        })
        .collect();
    format!("&[{}]", items.join(","))
}

fn lit(v: &Value, at: &str) -> String {
    match v {
        Value::Number(n) if n.is_i64() || n.is_u64() => format!(
            "Lit::Int({})",
            n.as_i64()
                .unwrap_or_else(|| panic!("{at}: integer out of range"))
        ),
        Value::Number(n) => {
            let r = n.as_f64().unwrap_or_else(|| panic!("{at}: not a number"));
            assert!(r.is_finite(), "{at}: {r} is not finite");
            format!("Lit::Real({r:?})")
        }
        Value::String(s) => format!("Lit::Str({s:?})"),
        other => panic!("{at}: {other} is not a literal"),
    }
}

fn real(v: Option<&Value>, at: &str) -> String {
    match v {
        None => "None".into(),
        Some(x) => {
            let r = x
                .as_f64()
                .unwrap_or_else(|| panic!("{at}: bound is not a number"));
            assert!(r.is_finite(), "{at}: {r} is not finite");
            format!("Some({r:?})")
        }
    }
}

fn count(v: Option<&Value>, at: &str) -> String {
    match v {
        None => "1".into(),
        Some(x) => x
            .as_u64()
            .filter(|&n| n <= u32::MAX as u64)
            .unwrap_or_else(|| panic!("{at}: bad minimum {x}"))
            .to_string(),
    }
}

fn max(v: Option<&Value>, at: &str) -> String {
    match v {
        None => "Max::Count(1)".into(),
        Some(Value::String(s)) if s == "**" => "Max::Unbounded(Unbounded::Stars)".into(),
        Some(x) => format!(
            "Max::Count({})",
            x.as_u64()
                .filter(|&n| n <= u32::MAX as u64)
                .unwrap_or_else(|| panic!("{at}: bad maximum {x}"))
        ),
    }
}

fn rules(v: Option<&Value>, at: &str) -> String {
    let Some(v) = v else { return "&[]".into() };
    let items: Vec<String> = v
        .as_array()
        .unwrap_or_else(|| panic!("{at}: rules are not an array"))
        .iter()
        .map(|r| {
            format!(
                "Rule{{kind:RuleKind::{},args:{}}}",
                str_field(r, "r", at),
                strs(&r["a"], at)
            )
        })
        .collect();
    format!("&[{}]", items.join(","))
}

fn status(v: &Value, at: &str) -> &'static str {
    match str_field(v, "s", at) {
        "o" => "Status::Mandatory",
        "f" => "Status::Optional",
        "d" => "Status::Defaulted",
        "c" => "Status::Hidden",
        other => panic!("{at}: unknown status `{other}`"),
    }
}

fn value_type(code: &str) -> String {
    match TYPE_CODES.iter().find(|(c, _)| *c == code) {
        Some((_, t)) => format!("ValueType::{t:?}"),
        None => format!("ValueType::Concept({code:?})"),
    }
}

impl Gen {
    /// Counts the uses of every literal list, so that only shared ones get
    /// a static of their own.
    fn count_lits(&mut self, entries: &Value) {
        for e in entries.as_array().into_iter().flatten() {
            for k in ["into", "d"] {
                if let Some(l) = e.get(k) {
                    self.lits.entry(l.to_string()).or_default().0 += 1;
                }
            }
            if let Some(k) = e.get("k") {
                self.count_lits(k);
            }
        }
    }

    fn lits(&mut self, v: Option<&Value>, at: &str) -> String {
        let Some(v) = v else { return "None".into() };
        let items: Vec<String> = v
            .as_array()
            .unwrap_or_else(|| panic!("{at}: not a list of literals"))
            .iter()
            .map(|l| lit(l, at))
            .collect();
        let Some(slot) = self.lits.get_mut(&v.to_string()) else {
            return format!("Some(&[{}])", items.join(","));
        };
        if let Some(name) = &slot.1 {
            return format!("Some(&{name})");
        }
        let name = format!("L{}", self.nlits);
        self.nlits += 1;
        slot.1 = Some(name.clone());
        let _ = writeln!(
            self.out,
            "static {name}: [Lit; {}] = [{}];",
            items.len(),
            items.join(",")
        );
        format!("Some(&{name})")
    }

    /// Writes a keyword list (once per distinct list) and returns the
    /// expression that refers to it.
    fn list(&mut self, entries: &Value, at: &str) -> String {
        let arr = entries
            .as_array()
            .unwrap_or_else(|| panic!("{at}: keywords are not an array"));
        if arr.is_empty() {
            return "&[]".into();
        }
        let key = entries.to_string();
        if let Some(name) = self.lists.get(&key) {
            return format!("&{name}");
        }
        let items: Vec<String> = arr.iter().map(|e| self.entry(e, at)).collect();
        let name = format!("K{}", self.lists.len());
        self.lists.insert(key, name.clone());
        let _ = writeln!(
            self.out,
            "static {name}: [Entry; {}] = [\n{}];",
            items.len(),
            items.join(",\n")
        );
        format!("&{name}")
    }

    fn entry(&mut self, e: &Value, at: &str) -> String {
        let name = str_field(e, "n", at);
        let at = format!("{at}/{name}");
        let at = at.as_str();
        let node = match str_field(e, "kind", at) {
            "S" => {
                let types: Vec<String> = match e.get("t") {
                    None => Vec::new(),
                    Some(t) => t
                        .as_array()
                        .unwrap_or_else(|| panic!("{at}: types are not an array"))
                        .iter()
                        .map(|c| value_type(c.as_str().unwrap_or_else(|| panic!("{at}: type"))))
                        .collect(),
                };
                format!(
                    "Node::Simple(SimpleKw{{status:{},types:&[{}],into:{},default:{},min:{},max:{},val_min:{},val_max:{},default_cond:Cache::new()}})",
                    status(e, at),
                    types.join(","),
                    self.lits(e.get("into"), at),
                    self.lits(e.get("d"), at),
                    count(e.get("min"), at),
                    max(e.get("max"), at),
                    real(e.get("lo"), at),
                    real(e.get("hi"), at),
                )
            }
            "F" => format!(
                "Node::Factor(FactorKw{{status:{},min:{},max:{},rules:{},keywords:{}}})",
                status(e, at),
                count(e.get("min"), at),
                max(e.get("max"), at),
                rules(e.get("rules"), at),
                self.list(&e["k"], at),
            ),
            "B" => format!(
                "Node::Block(Block{{condition:{:?},rules:{},keywords:{},parsed:Cache::new()}})",
                str_field(e, "if", at),
                rules(e.get("rules"), at),
                self.list(&e["k"], at),
            ),
            other => panic!("{at}: unknown kind `{other}`"),
        };
        format!("Entry{{name:{name:?},node:{node}}}")
    }

    fn command(&mut self, c: &Value) -> String {
        let name = str_field(c, "name", "catalog");
        let produces = match &c["produces"] {
            Value::String(s) if s == "Nothing" => "Produces::Nothing".to_string(),
            Value::Object(m) => match (m.get("Type"), m.get("Computed")) {
                (Some(Value::String(t)), None) => format!("Produces::Type({t:?})"),
                (None, Some(Value::String(f))) => format!("Produces::Computed({f:?})"),
                _ => panic!("{name}: bad `produces`"),
            },
            _ => panic!("{name}: bad `produces`"),
        };
        let reentrant = match &c["reentrant"] {
            Value::String(s) if s == "No" => "Reentrant::No".to_string(),
            Value::String(s) if s == "Unstated" => "Reentrant::Unstated".to_string(),
            Value::Object(m) if m.contains_key("Yes") => {
                let y = &m["Yes"];
                format!(
                    "Reentrant::Yes{{mandatory:{},keywords:{}}}",
                    y["mandatory"]
                        .as_bool()
                        .unwrap_or_else(|| panic!("{name}: bad `mandatory`")),
                    strs(&y["keywords"], name)
                )
            }
            _ => panic!("{name}: bad `reentrant`"),
        };
        format!(
            "Command{{name:{name:?},kind:CommandKind::{},produces:{produces},reentrant:{reentrant},rules:{},keywords:{}}}",
            str_field(c, "kind", name),
            rules(c.get("rules"), name),
            self.list(&c["k"], name),
        )
    }
}

fn main() {
    let src = "data/catalog-v17.json";
    println!("cargo::rerun-if-changed={src}");
    println!("cargo::rerun-if-changed=src/type_codes.rs");
    let text = std::fs::read_to_string(src).expect("data/catalog-v17.json is readable");
    let commands: Vec<Value> =
        serde_json::from_str(&text).expect("data/catalog-v17.json is a JSON array");
    let mut g = Gen::default();
    for c in &commands {
        g.count_lits(&c["k"]);
    }
    // Literal lists are numbered from here on as they are written.
    let counts: HashMap<String, (usize, Option<String>)> = std::mem::take(&mut g.lits)
        .into_iter()
        .filter(|(_, (n, _))| *n >= 2)
        .collect();
    g.lits = counts;
    let cmds: Vec<String> = commands.iter().map(|c| g.command(c)).collect();
    let names: Vec<&str> = commands
        .iter()
        .map(|c| str_field(c, "name", "catalog"))
        .collect();
    let mut sorted: Vec<usize> = (0..names.len()).collect();
    sorted.sort_by(|&a, &b| names[a].cmp(names[b]));
    let mut out = std::mem::take(&mut g.out);
    let _ = writeln!(
        out,
        "/// Every command, in catalog order.\npub static COMMANDS: [Command; {}] = [\n{}];",
        cmds.len(),
        cmds.join(",\n")
    );
    let _ = writeln!(
        out,
        "/// Positions in `COMMANDS`, sorted by name.\npub static BY_NAME: [u16; {}] = {sorted:?};",
        sorted.len()
    );
    let dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(dir.join("catalog-tables.rs"), out).expect("OUT_DIR is writable");
}
