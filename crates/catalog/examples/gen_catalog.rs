//! Generates the project's catalog (`data/catalog-v17.json`) from code_aster's
//! keyword facts.
//!
//! ```text
//! cargo run -p aster-catalog --example gen_catalog [-- INPUT [OUTPUT]]
//! ```
//! INPUT defaults to `../shared/reference/catalog-v17.json` (beside the
//! repository), OUTPUT to `crates/catalog/data/catalog-v17.json`. The output is
//! committed: building the project never needs the facts file.

use aster_catalog::model::*;
use serde::de::{Deserializer, MapAccess, Visitor};
use serde::Deserialize;
use std::fmt;
use std::marker::PhantomData;
use std::path::PathBuf;

// The model holds `&'static` data (the program's catalog is static tables
// made by the build script); this one-shot generator leaks what it builds.
fn text(s: String) -> &'static str {
    s.leak()
}
fn list<T>(v: Vec<T>) -> &'static [T] {
    v.leak()
}

/// A JSON object read in file order (the catalog's keyword order matters:
/// it is the order `explain` shows and `--emit` writes).
struct Ordered<T>(Vec<(String, T)>);

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Ordered<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<T>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>> Visitor<'de> for V<T> {
            type Value = Ordered<T>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an object")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<Self::Value, A::Error> {
                let mut out = Vec::new();
                while let Some((k, v)) = m.next_entry::<String, T>()? {
                    out.push((k, v));
                }
                Ok(Ordered(out))
            }
        }
        d.deserialize_map(V(PhantomData))
    }
}

#[derive(Deserialize)]
struct RawRule {
    rule: RuleKind,
    args: Vec<String>,
}

#[derive(Deserialize)]
struct RawCmd {
    #[serde(default)]
    rules: Vec<RawRule>,
    keywords: Ordered<RawKw>,
    kind: CommandKind,
    reentrant: String,
    sd_prod: Option<String>,
}

#[derive(Deserialize)]
struct RawKw {
    kind: String,
    statut: Option<Status>,
    typ: Option<serde_json::Value>,
    into: Option<Vec<serde_json::Value>>,
    defaut: Option<serde_json::Value>,
    min: Option<u32>,
    max: Option<serde_json::Value>,
    val_min: Option<f64>,
    val_max: Option<f64>,
    condition: Option<String>,
    #[serde(default)]
    rules: Vec<RawRule>,
    keywords: Option<Ordered<RawKw>>,
}

fn lit(v: &serde_json::Value) -> Result<Lit, String> {
    match v {
        serde_json::Value::Number(n) => match n.as_i64() {
            Some(i) if !n.is_f64() => Ok(Lit::Int(i)),
            _ => n
                .as_f64()
                .map(Lit::Real)
                .ok_or_else(|| format!("bad number {n}")),
        },
        serde_json::Value::String(s) => Ok(Lit::Str(text(s.clone()))),
        other => Err(format!("unexpected literal {other}")),
    }
}

fn rules(raw: Vec<RawRule>) -> &'static [Rule] {
    list(
        raw.into_iter()
            .map(|r| Rule {
                kind: r.rule,
                args: list(r.args.into_iter().map(text).collect()),
            })
            .collect(),
    )
}

fn max(v: Option<serde_json::Value>) -> Result<Max, String> {
    match v {
        None => Ok(Max::Count(1)),
        Some(serde_json::Value::String(s)) if s == "**" => Ok(Max::Unbounded(Unbounded::Stars)),
        Some(serde_json::Value::Number(n)) => n
            .as_u64()
            .map(|m| Max::Count(m as u32))
            .ok_or_else(|| format!("bad max {n}")),
        Some(other) => Err(format!("bad max {other}")),
    }
}

fn entries(raw: Ordered<RawKw>, at: &str) -> Result<&'static [Entry], String> {
    raw.0
        .into_iter()
        .map(|(name, kw)| {
            let path = format!("{at}/{name}");
            let node = convert(kw, &path)?;
            Ok(Entry {
                name: text(name),
                node,
            })
        })
        .collect::<Result<Vec<_>, String>>()
        .map(list)
}

fn convert(kw: RawKw, path: &str) -> Result<Node, String> {
    let err = |m: String| format!("{path}: {m}");
    match kw.kind.as_str() {
        "simple" => {
            let types = match kw.typ {
                None | Some(serde_json::Value::Null) => Vec::new(),
                Some(serde_json::Value::String(s)) => vec![ValueType::from(text(s))],
                Some(serde_json::Value::Array(a)) => a
                    .into_iter()
                    .map(|t| match t {
                        serde_json::Value::String(s) => Ok(ValueType::from(text(s))),
                        other => Err(err(format!("bad type {other}"))),
                    })
                    .collect::<Result<_, _>>()?,
                Some(other) => return Err(err(format!("bad type {other}"))),
            };
            let into = kw
                .into
                .map(|v| v.iter().map(lit).collect::<Result<Vec<_>, _>>())
                .transpose()
                .map_err(err)?;
            let default = match kw.defaut {
                None | Some(serde_json::Value::Null) => None,
                Some(serde_json::Value::Array(a)) => Some(
                    a.iter()
                        .map(lit)
                        .collect::<Result<Vec<_>, _>>()
                        .map_err(err)?,
                ),
                Some(v) => Some(vec![lit(&v).map_err(err)?]),
            };
            Ok(Node::Simple(SimpleKw {
                status: kw.statut.ok_or_else(|| err("no status".into()))?,
                types: list(types),
                into: into.map(list),
                default: default.map(list),
                min: kw.min.unwrap_or(1),
                max: max(kw.max).map_err(err)?,
                val_min: kw.val_min,
                val_max: kw.val_max,
                default_cond: Cache::new(),
            }))
        }
        "factor" => Ok(Node::Factor(FactorKw {
            status: kw.statut.ok_or_else(|| err("no status".into()))?,
            min: kw.min.unwrap_or(1),
            max: max(kw.max).map_err(err)?,
            rules: rules(kw.rules),
            keywords: entries(kw.keywords.unwrap_or(Ordered(Vec::new())), path)?,
        })),
        "bloc" => Ok(Node::Block(Block {
            condition: text(
                kw.condition
                    .ok_or_else(|| err("block without condition".into()))?
                    .split_whitespace()
                    .collect::<Vec<_>>()
                    .join(" "),
            ),
            rules: rules(kw.rules),
            keywords: entries(kw.keywords.unwrap_or(Ordered(Vec::new())), path)?,
            parsed: Cache::new(),
        })),
        other => Err(err(format!("unknown kind {other}"))),
    }
}

fn reentrant(s: &str) -> Reentrant {
    match s {
        "n" => Reentrant::No,
        "" => Reentrant::Unstated,
        _ => {
            let (flag, rest) = s.split_once(':').unwrap_or((s, ""));
            Reentrant::Yes {
                mandatory: flag == "o",
                keywords: list(
                    rest.split('|')
                        .filter(|k| !k.is_empty())
                        .map(|k| text(k.replace(':', "/")))
                        .collect(),
                ),
            }
        }
    }
}

fn produces(sd: Option<String>) -> Produces {
    match sd {
        None => Produces::Nothing,
        Some(s) if s.ends_with("_prod") || s.ends_with("_sdprod") => Produces::Computed(text(s)),
        Some(s) => Produces::Type(text(s)),
    }
}

fn main() -> Result<(), String> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut args = std::env::args().skip(1);
    let input = args
        .next()
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("../shared/reference/catalog-v17.json"));
    let output = args
        .next()
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("crates/catalog/data/catalog-v17.json"));
    let source = std::fs::read_to_string(&input)
        .map_err(|e| format!("cannot read {}: {e}", input.display()))?;
    let raw: Ordered<RawCmd> =
        serde_json::from_str(&source).map_err(|e| format!("{}: {e}", input.display()))?;
    let mut commands = Vec::new();
    for (name, c) in raw.0 {
        commands.push(Command {
            keywords: entries(c.keywords, &name)?,
            name: text(name),
            kind: c.kind,
            produces: produces(c.sd_prod),
            reentrant: reentrant(&c.reentrant),
            rules: rules(c.rules),
        });
    }
    // One command per line: small diffs when the facts change.
    let mut out = String::from("[\n");
    for (i, c) in commands.iter().enumerate() {
        out.push_str(&serde_json::to_string(c).map_err(|e| e.to_string())?);
        out.push_str(if i + 1 < commands.len() { ",\n" } else { "\n" });
    }
    out.push_str("]\n");
    std::fs::write(&output, out).map_err(|e| format!("cannot write {}: {e}", output.display()))?;
    eprintln!(
        "{} commands written to {}",
        commands.len(),
        output.display()
    );
    Ok(())
}
