//! Reading the embedded catalog fast.
//!
//! The catalog is 1.8 MB of JSON for 268 commands (code_aster 17's 267 and
//! the `DEFI_CONT` macro), and a command file uses a
//! dozen of them. Two things keep its first use cheap:
//!
//! - **One command at a time.** The build script (`build.rs`) writes each
//!   command's JSON apart and an index by name; [`crate::Catalog::command`]
//!   deserialises a command the first time it is asked for, never the others.
//! - **No buffering deserialisers.** serde's untagged and internally tagged
//!   enums (and `flatten`) buffer every value into an intermediate tree before
//!   choosing a variant; on this catalog that was nine tenths of the load
//!   time. [`Lit`] and [`Max`] are read by visitors that see the JSON token
//!   directly, and an [`Entry`] is read into [`RawEntry`], a plain struct of
//!   every field any kind of entry has, then checked into its kind.
//!
//! The JSON itself is unchanged: serialising still writes the tagged form.

use crate::model::{Block, Entry, FactorKw, Lit, Max, Node, Rule, SimpleKw, Status, ValueType};
use serde::de::{self, Deserializer, Visitor};
use serde::Deserialize;
use std::fmt;

impl<'de> Deserialize<'de> for Lit {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Lit, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Lit;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an integer, a real or a string")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Lit, E> {
                Ok(Lit::Int(v))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Lit, E> {
                i64::try_from(v)
                    .map(Lit::Int)
                    .map_err(|_| E::custom(format!("integer {v} out of range")))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Lit, E> {
                Ok(Lit::Real(v))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Lit, E> {
                Ok(Lit::Str(v.to_string()))
            }
            fn visit_string<E: de::Error>(self, v: String) -> Result<Lit, E> {
                Ok(Lit::Str(v))
            }
        }
        d.deserialize_any(V)
    }
}

impl<'de> Deserialize<'de> for Max {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Max, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Max;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a count or \"**\"")
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Max, E> {
                u32::try_from(v)
                    .map(Max::Count)
                    .map_err(|_| E::custom(format!("count {v} out of range")))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Max, E> {
                u32::try_from(v)
                    .map(Max::Count)
                    .map_err(|_| E::custom(format!("count {v} out of range")))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Max, E> {
                match v {
                    "**" => Ok(Max::Unbounded(crate::model::Unbounded::Stars)),
                    other => Err(E::custom(format!("unknown maximum `{other}`"))),
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// Every field an entry of any kind has, as the JSON spells it.
#[derive(Deserialize)]
pub struct RawEntry {
    n: String,
    kind: String,
    s: Option<Status>,
    #[serde(default)]
    t: Vec<ValueType>,
    into: Option<Vec<Lit>>,
    d: Option<Vec<Lit>>,
    min: Option<u32>,
    max: Option<Max>,
    lo: Option<f64>,
    hi: Option<f64>,
    #[serde(default)]
    rules: Vec<Rule>,
    k: Option<Vec<Entry>>,
    #[serde(rename = "if")]
    condition: Option<String>,
}

impl TryFrom<RawEntry> for Entry {
    type Error = String;
    fn try_from(r: RawEntry) -> Result<Entry, String> {
        let name = r.n;
        let missing = |field: &str| format!("entry `{name}`: `{field}` missing");
        let node = match r.kind.as_str() {
            "S" => Node::Simple(SimpleKw {
                status: r.s.ok_or_else(|| missing("s"))?,
                types: r.t,
                into: r.into,
                default: r.d,
                min: r.min.unwrap_or(1),
                max: r.max.unwrap_or(Max::Count(1)),
                val_min: r.lo,
                val_max: r.hi,
                default_cond: None,
            }),
            "F" => Node::Factor(FactorKw {
                status: r.s.ok_or_else(|| missing("s"))?,
                min: r.min.unwrap_or(1),
                max: r.max.unwrap_or(Max::Count(1)),
                rules: r.rules,
                keywords: r.k.ok_or_else(|| missing("k"))?,
            }),
            "B" => Node::Block(Block {
                condition: r.condition.ok_or_else(|| missing("if"))?,
                rules: r.rules,
                keywords: r.k.ok_or_else(|| missing("k"))?,
                parsed: None,
            }),
            other => return Err(format!("entry `{name}`: unknown kind `{other}`")),
        };
        Ok(Entry { name, node })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_read_back_what_serialising_wrote() {
        let json = r#"[{"n":"A","kind":"S","s":"o","t":["R"],"d":[1.5],"max":"**","lo":0.0},
            {"n":"B","kind":"F","s":"f","max":3,"k":[{"n":"C","kind":"S","s":"f","into":["X",2]}]},
            {"n":"b_c","kind":"B","if":"A == 1","k":[]}]"#;
        let entries: Vec<Entry> = serde_json::from_str(json).unwrap();
        let again: Vec<Entry> =
            serde_json::from_str(&serde_json::to_string(&entries).unwrap()).unwrap();
        assert_eq!(entries, again);
        let Node::Simple(a) = &entries[0].node else {
            panic!("A is simple")
        };
        assert_eq!(a.default, Some(vec![Lit::Real(1.5)]));
        assert_eq!(a.max, Max::Unbounded(crate::model::Unbounded::Stars));
        assert_eq!(a.min, 1);
        let Node::Factor(b) = &entries[1].node else {
            panic!("B is a factor")
        };
        assert_eq!(b.max, Max::Count(3));
        let Node::Simple(c) = &b.keywords[0].node else {
            panic!("C is simple")
        };
        assert_eq!(c.into, Some(vec![Lit::Str("X".into()), Lit::Int(2)]));
    }

    #[test]
    fn a_malformed_entry_names_itself() {
        let err = serde_json::from_str::<Entry>(r#"{"n":"Z","kind":"F","s":"f"}"#)
            .unwrap_err()
            .to_string();
        assert!(err.contains("entry `Z`: `k` missing"), "{err}");
        let err = serde_json::from_str::<Entry>(r#"{"n":"Z","kind":"Q"}"#)
            .unwrap_err()
            .to_string();
        assert!(err.contains("unknown kind `Q`"), "{err}");
    }
}
