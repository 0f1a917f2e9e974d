//! The one JSON contract of `aster parse --json` and `aster check --emit
//! commands` (schema: docs/json.md).
//!
//! Both print one object per file, in the order the files were given:
//! `{"schema_version": 1, "kind": "ast" | "commands", "path": <as given>,
//! …}`, pretty-printed, or one object per line (JSON Lines) with
//! `--compact`. Every command and every keyword the user wrote carries its
//! 1-based `line` and `column` (columns in characters, as diagnostics
//! count them); AST nodes carry them beside their byte `span`.

use std::io::Write;

use aster_eval::{CommandCall, Keyword, Keywords, KwValue};
use aster_syntax::ast::Module;
use aster_syntax::codemap::{CodeMap, Span};
use serde_json::{json, Map, Value};

/// Bumped when a field changes meaning or goes away (adding one does not).
pub const SCHEMA_VERSION: u64 = 1;

/// How the objects are written.
#[derive(Clone, Copy, Debug, Default)]
pub struct JsonOptions {
    /// One object per line (JSON Lines) instead of indented objects.
    pub compact: bool,
    /// Leave out the keywords the catalog filled in (`"defaulted": true`).
    pub no_defaults: bool,
}

/// The envelope every object starts with.
fn envelope(kind: &str, path: &str) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("schema_version".into(), json!(SCHEMA_VERSION));
    m.insert("kind".into(), json!(kind));
    m.insert("path".into(), json!(path));
    m
}

/// `line`/`column` (and `end_line`/`end_column`, exclusive) of a span.
fn locate_span(map: &CodeMap, span: Span, obj: &mut Map<String, Value>, with_end: bool) {
    let start = map.line_col(span.start as usize);
    obj.insert("line".into(), json!(start.line));
    obj.insert("column".into(), json!(start.column));
    if with_end {
        let end = map.line_col(span.end as usize);
        obj.insert("end_line".into(), json!(end.line));
        obj.insert("end_column".into(), json!(end.column));
    }
}

/// Adds `line` and `column` beside every `span: [start, end]` of a
/// serialised AST.
fn locate_ast(value: &mut Value, map: &CodeMap) {
    match value {
        Value::Object(obj) => {
            let start = obj
                .get("span")
                .and_then(|s| s.as_array())
                .and_then(|a| a.first())
                .and_then(|s| s.as_u64());
            if let Some(start) = start {
                let lc = map.line_col(start as usize);
                obj.insert("line".into(), json!(lc.line));
                obj.insert("column".into(), json!(lc.column));
            }
            for v in obj.values_mut() {
                if v.is_object() || v.is_array() {
                    locate_ast(v, map);
                }
            }
        }
        Value::Array(items) => items.iter_mut().for_each(|v| locate_ast(v, map)),
        _ => {}
    }
}

/// The AST of one file.
pub fn ast_object(path: &str, map: &CodeMap, module: &Module) -> serde_json::Result<Value> {
    let mut body = serde_json::to_value(&module.body)?;
    locate_ast(&mut body, map);
    let mut obj = envelope("ast", path);
    obj.insert("body".into(), body);
    Ok(Value::Object(obj))
}

fn keyword_value(
    kw: &Keyword,
    map: &CodeMap,
    opts: JsonOptions,
) -> serde_json::Result<Option<Value>> {
    if kw.defaulted && opts.no_defaults {
        return Ok(None);
    }
    let value = match &kw.value {
        KwValue::Simple(scalars) => {
            json!({"kind": "Simple", "value": serde_json::to_value(scalars)?})
        }
        KwValue::Factor(occurrences) => {
            let occs = occurrences
                .iter()
                .map(|o| keywords_value(o, map, opts))
                .collect::<serde_json::Result<Vec<_>>>()?;
            json!({"kind": "Factor", "value": occs})
        }
    };
    let mut obj = Map::new();
    obj.insert("name".into(), json!(kw.name));
    obj.insert("value".into(), value);
    obj.insert("defaulted".into(), json!(kw.defaulted));
    // A default has no place of its own in the file.
    if !kw.defaulted {
        locate_span(map, kw.span, &mut obj, false);
    }
    Ok(Some(Value::Object(obj)))
}

fn keywords_value(kws: &Keywords, map: &CodeMap, opts: JsonOptions) -> serde_json::Result<Value> {
    let mut out = Vec::with_capacity(kws.entries.len());
    for kw in &kws.entries {
        if let Some(v) = keyword_value(kw, map, opts)? {
            out.push(v);
        }
    }
    Ok(Value::Array(out))
}

/// The evaluated commands of one file.
pub fn commands_object(
    path: &str,
    map: &CodeMap,
    calls: &[CommandCall],
    opts: JsonOptions,
) -> serde_json::Result<Value> {
    let mut commands = Vec::with_capacity(calls.len());
    for call in calls {
        let mut obj = Map::new();
        obj.insert("command".into(), json!(call.command));
        locate_span(map, call.span, &mut obj, true);
        obj.insert("result".into(), serde_json::to_value(&call.result)?);
        obj.insert("reuse".into(), serde_json::to_value(&call.reuse)?);
        obj.insert(
            "keywords".into(),
            keywords_value(&call.keywords, map, opts)?,
        );
        commands.push(Value::Object(obj));
    }
    let mut obj = envelope("commands", path);
    obj.insert("commands".into(), Value::Array(commands));
    Ok(Value::Object(obj))
}

/// Writes one object: indented, or on one line with `compact`.
pub fn write_object(out: &mut impl Write, value: &Value, compact: bool) -> std::io::Result<()> {
    let text = if compact {
        serde_json::to_string(value)
    } else {
        serde_json::to_string_pretty(value)
    }
    .map_err(std::io::Error::other)?;
    writeln!(out, "{text}")
}
