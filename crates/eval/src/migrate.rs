//! `aster migrate`: rewrite a code_aster 11–15 command file into code_aster
//! 17 spelling, as source edits that keep every comment and the layout.
//!
//! The rewrites are the legacy mapping itself ([`crate::legacy`]): the file
//! is checked, and each `W-legacy` diagnostic the checker emits (it spans
//! the keyword argument `NAME=value` it is about) becomes an edit of that
//! argument when its rewrite is a local one:
//!
//! | diagnostic | edit |
//! | --- | --- |
//! | `` `P/OLD` is legacy syntax: now NEW `` | the keyword renamed |
//! | `` `P/NAME` no longer exists and is ignored `` | the argument removed |
//! | `` `P/KW`: legacy value 'OLD' is now 'NEW' `` | the string replaced |
//! | `DEBUT/CODE=_F(...)` | `CODE='OUI'` |
//! | `DETRUIRE/CONCEPT=_F(NOM=X)` | `NOM=X` |
//! | `ORIE_PEAU_2D/3D=_F(GROUP_MA=...)` | `ORIE_PEAU=_F(GROUP_MA_PEAU=...)` |
//! | `PARM_THETA=x` | `SCHEMA_TEMPS=_F(SCHEMA='THETA', THETA=x)` |
//! | `LIAISON='ENCASTRE'` | `BLOCAGE=('DEPLACEMENT', 'ROTATION')` |
//!
//! and the Python 2 statements the AST keeps become Python 3: `print x` →
//! `print(x)`, `exec c` → `exec(c)`, `` `x` `` → `repr(x)`, `xrange` →
//! `range`. A legacy
//! diagnostic with no local rewrite (a command replaced by another, values
//! moved between keywords) is left as it is and reported: the file keeps
//! the old spelling there.

use crate::diag::{DiagKind, Diagnostic};
use aster_syntax::CodeMap;
use serde_json::Value as Json;

/// The migrated text and what could not be rewritten.
#[derive(Debug, Clone)]
pub struct Migration {
    pub text: String,
    /// Edits made.
    pub edits: usize,
    /// Legacy diagnostics left as they are (no local rewrite).
    pub left: Vec<Diagnostic>,
}

/// A replacement of `source[start..end]`.
#[derive(Debug, Clone)]
struct Edit {
    start: usize,
    end: usize,
    text: String,
}

/// A keyword argument of the AST: its whole span, its name and its value.
struct KwArg<'a> {
    span: (usize, usize),
    name: &'a str,
    value: &'a Json,
}

fn span_of(v: &Json) -> Option<(usize, usize)> {
    let s = v.get("span")?.as_array()?;
    Some((s.first()?.as_u64()? as usize, s.get(1)?.as_u64()? as usize))
}

/// Every keyword argument, Python 2 statement and backquote of the module.
fn walk<'a>(v: &'a Json, kws: &mut Vec<KwArg<'a>>, py2: &mut Vec<&'a Json>) {
    match v {
        Json::Object(o) => {
            if o.get("arg").and_then(Json::as_str) == Some("Keyword") {
                if let (Some(span), Some(name), Some(value)) = (
                    span_of(v),
                    o.get("name")
                        .and_then(|n| n.get("name"))
                        .and_then(Json::as_str),
                    o.get("value"),
                ) {
                    kws.push(KwArg { span, name, value });
                }
            }
            let stmt = o.get("stmt").and_then(Json::as_str);
            let expr = o.get("expr").and_then(Json::as_str);
            let xrange =
                expr == Some("Name") && o.get("id").and_then(Json::as_str) == Some("xrange");
            if matches!(stmt, Some("Print" | "Exec")) || expr == Some("Repr") || xrange {
                py2.push(v);
            }
            for x in o.values() {
                walk(x, kws, py2);
            }
        }
        Json::Array(a) => {
            for x in a {
                walk(x, kws, py2);
            }
        }
        _ => {}
    }
}

/// The path's last segment in a message: `` `DEBUT/CODE=...` `` → `CODE=...`.
fn subject(message: &str) -> Option<&str> {
    let inner = message.strip_prefix('`')?;
    let inner = &inner[..inner.find('`')?];
    Some(inner.rsplit('/').next().unwrap_or(inner))
}

fn is_ident(s: &str) -> bool {
    !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
}

/// Migrates one command file (`name` is for the code map only). A rewrite
/// can reveal another (a keyword checked only once its command's spelling
/// is current): passes are repeated while they change the text (at most 4).
pub fn migrate(name: &str, source: &str) -> Result<Migration, String> {
    let mut m = migrate_once(name, source)?;
    for _ in 0..3 {
        if m.edits == 0 {
            break;
        }
        let next = migrate_once(name, &m.text)?;
        if next.edits == 0 {
            break;
        }
        m = Migration {
            edits: m.edits + next.edits,
            ..next
        };
    }
    Ok(m)
}

fn migrate_once(name: &str, source: &str) -> Result<Migration, String> {
    let module = aster_syntax::parse_module(source).map_err(|e| {
        let map = CodeMap::new(name, source);
        let lc = map.line_col(e.span.start as usize);
        format!("{name}:{}:{}: {}", lc.line, lc.column, e.message)
    })?;
    let ast = serde_json::to_value(&module).map_err(|e| e.to_string())?;
    let mut kws = Vec::new();
    let mut py2 = Vec::new();
    walk(&ast, &mut kws, &mut py2);
    let map = CodeMap::new(name, source);
    let report = crate::check_source(&map, false);
    let text = |s: (usize, usize)| source.get(s.0..s.1).unwrap_or("");
    let mut edits = Vec::new();
    let mut left = Vec::new();
    for d in report
        .diagnostics
        .0
        .iter()
        .filter(|d| d.kind == DiagKind::Legacy)
    {
        let span = (d.span.start as usize, d.span.end as usize);
        let arg = kws.iter().find(|k| k.span == span);
        match arg.and_then(|a| legacy_edit(&d.message, a, source)) {
            Some(e) => edits.extend(e),
            None => left.push(d.clone()),
        }
    }
    for node in py2 {
        if let Some(e) = python3_edit(node, &text) {
            edits.push(e);
        }
    }
    // Apply in order; an edit inside one already made is dropped (the
    // outer one rewrote that text).
    edits.sort_by_key(|e| (e.start, std::cmp::Reverse(e.end)));
    let mut out = String::with_capacity(source.len());
    let mut at = 0;
    let mut applied = 0;
    for e in edits {
        if e.start < at {
            continue;
        }
        out.push_str(&source[at..e.start]);
        out.push_str(&e.text);
        at = e.end;
        applied += 1;
    }
    out.push_str(&source[at..]);
    Ok(Migration {
        text: out,
        edits: applied,
        left,
    })
}

/// The edits for a legacy diagnostic about the keyword argument `arg`:
/// as small as can be (a name, a string), so that the rewrites of keywords
/// inside it (`COMP_INCR=_F(RESI_INTE_RELA=...)`) apply too.
fn legacy_edit(message: &str, arg: &KwArg, source: &str) -> Option<Vec<Edit>> {
    let (start, end) = arg.span;
    let whole = source.get(start..end)?;
    // The argument must be written as `NAME = value` here (not built by
    // Python code elsewhere).
    let after_name = whole.strip_prefix(arg.name)?;
    let value_src = after_name.trim_start().strip_prefix('=')?;
    let replace = |text: String| Some(vec![Edit { start, end, text }]);
    let at = |start: usize, len: usize, text: &str| Edit {
        start,
        end: start + len,
        text: text.to_string(),
    };
    let subj = subject(message)?;
    if let Some(rest) = message.split_once(" is legacy syntax: now ").map(|p| p.1) {
        if subj == arg.name && is_ident(rest) {
            return Some(vec![at(start, arg.name.len(), rest)]);
        }
        if subj == "PARM_THETA" && rest.starts_with("SCHEMA_TEMPS=") {
            return replace(format!(
                "SCHEMA_TEMPS=_F(SCHEMA='THETA', THETA={})",
                value_src.trim()
            ));
        }
        if subj == "LIAISON='ENCASTRE'" {
            return replace("BLOCAGE=('DEPLACEMENT', 'ROTATION')".into());
        }
        return None;
    }
    if subj == arg.name && message.contains(" no longer exists and is ignored") {
        return Some(vec![removal(source, start, end)]);
    }
    if let Some((_, values)) = message.split_once(": legacy value '") {
        let (old, new) = values.split_once("' is now '")?;
        let new = new.strip_suffix('\'')?;
        for q in ['\'', '"'] {
            let quoted = format!("{q}{old}{q}");
            if let Some(i) = whole.find(&quoted) {
                return Some(vec![at(start + i, quoted.len(), &format!("{q}{new}{q}"))]);
            }
        }
        return None;
    }
    match subj {
        "CODE=_F(NOM=...)" => replace("CODE='OUI'".into()),
        "CONCEPT=_F(NOM=...)" => {
            // NOM of each occurrence, in order.
            let occurrences: Vec<&Json> = match arg.value.get("expr").and_then(Json::as_str) {
                Some("Tuple" | "List") => arg.value.get("elts")?.as_array()?.iter().collect(),
                _ => vec![arg.value],
            };
            let mut names = Vec::new();
            for occ in occurrences {
                let args = occ.get("args")?.as_array()?;
                for a in args {
                    if a.get("arg").and_then(Json::as_str) == Some("Keyword")
                        && a.get("name")
                            .and_then(|n| n.get("name"))
                            .and_then(Json::as_str)
                            == Some("NOM")
                    {
                        names.push(source.get(span_of(a.get("value")?).map(|s| s.0..s.1)?)?);
                    }
                }
            }
            match names.as_slice() {
                [] => None,
                [one] => replace(format!("NOM={one}")),
                many => replace(format!("NOM=({},)", many.join(", "))),
            }
        }
        "ORIE_PEAU_2D" | "ORIE_PEAU_3D" => {
            // The keyword renamed, and GROUP_MA inside it GROUP_MA_PEAU.
            let mut inner = Vec::new();
            let mut py2 = Vec::new();
            walk(arg.value, &mut inner, &mut py2);
            let mut edits = vec![at(start, arg.name.len(), "ORIE_PEAU")];
            edits.extend(
                inner
                    .iter()
                    .filter(|k| k.name == "GROUP_MA")
                    .map(|k| at(k.span.0, k.name.len(), "GROUP_MA_PEAU")),
            );
            Some(edits)
        }
        _ => None,
    }
}

/// Removing `source[start..end]`, an argument: with the comma after it (or
/// before it when it is the last), and its whole line when it is alone there.
fn removal(source: &str, start: usize, end: usize) -> Edit {
    let b = source.as_bytes();
    let mut e = end;
    while e < b.len() && (b[e] == b' ' || b[e] == b'\t') {
        e += 1;
    }
    if e < b.len() && b[e] == b',' {
        e += 1;
        while e < b.len() && (b[e] == b' ' || b[e] == b'\t') {
            e += 1;
        }
        let line_start = source[..start].rfind('\n').map_or(0, |i| i + 1);
        let alone = source[line_start..start].trim().is_empty();
        if alone && (e >= b.len() || b[e] == b'\n') {
            return Edit {
                start: line_start,
                end: (e + 1).min(b.len()),
                text: String::new(),
            };
        }
        return Edit {
            start,
            end: e,
            text: String::new(),
        };
    }
    // The last argument: take the comma before it.
    let mut s = start;
    while s > 0 && b[s - 1].is_ascii_whitespace() {
        s -= 1;
    }
    if s > 0 && b[s - 1] == b',' {
        s -= 1;
    } else {
        s = start;
    }
    Edit {
        start: s,
        end,
        text: String::new(),
    }
}

/// `print x, y` → `print(x, y)`, `exec c in g` → `exec(c, g)`, `` `x` `` →
/// `repr(x)`, `xrange` → `range`.
fn python3_edit<'s>(node: &Json, text: &dyn Fn((usize, usize)) -> &'s str) -> Option<Edit> {
    let (start, end) = span_of(node)?;
    let src = |key: &str| node.get(key).and_then(span_of).map(text);
    let new = match (node.get("stmt").and_then(Json::as_str), node.get("expr")) {
        (Some("Print"), _) => {
            let mut parts: Vec<String> = node
                .get("values")?
                .as_array()?
                .iter()
                .map(|v| span_of(v).map(|s| text(s).to_string()))
                .collect::<Option<_>>()?;
            if node.get("newline").and_then(Json::as_bool) == Some(false) {
                parts.push("end=' '".into());
            }
            if let Some(dest) = src("dest") {
                parts.push(format!("file={dest}"));
            }
            format!("print({})", parts.join(", "))
        }
        (Some("Exec"), _) => {
            let mut parts = vec![src("code")?.to_string()];
            parts.extend(src("globals").map(str::to_string));
            parts.extend(src("locals").map(str::to_string));
            format!("exec({})", parts.join(", "))
        }
        (_, Some(e)) if e.as_str() == Some("Name") => "range".to_string(),
        _ => format!("repr({})", src("value")?),
    };
    Some(Edit {
        start,
        end,
        text: new,
    })
}
