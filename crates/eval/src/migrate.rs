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
//! | `` `PROJ_CHAMP/PROL_ZERO='OUI'` is compatibility syntax `` | `PROL_VALE=0.0` (`'NON'`: removed) |
//! | `` `P/KW`: legacy value 'OLD' is now 'NEW' `` | the string replaced |
//! | `DEBUT/CODE=_F(...)` | `CODE='OUI'` |
//! | `DETRUIRE/CONCEPT=_F(NOM=X)` | `NOM=X` |
//! | `ORIE_PEAU_2D/3D=_F(GROUP_MA=...)` | `ORIE_PEAU=_F(GROUP_MA_PEAU=...)` |
//! | `PARM_THETA=x` | `SCHEMA_TEMPS=_F(SCHEMA='THETA', THETA=x)` |
//! | `LIAISON='ENCASTRE'` | `BLOCAGE=('DEPLACEMENT', 'ROTATION')` |
//! | `THER_NON_LINE/NEWTON/ITER_LINE_MAXI`, `RESI_LINE_RELA` | `RECH_LINEAIRE=_F(ITER_LINE_MAXI=..., RESI_LINE_RELA=...)` |
//!
//! and the structures code_aster 17 rebuilt, from the same legacy mapping
//! (docs/legacy.md has the table): a command replaced by another with its
//! keywords moved (`MODE_ITER_SIMULT`/`MODE_ITER_INV` → `CALC_MODES`,
//! `MACRO_MATR_ASSE` → `ASSEMBLAGE`), a keyword moved to another level
//! (`CREA_RESU/NOM_CHAM` into each `AFFE`, `DEFI_LIST/METHODE` up), one
//! occurrence split per modelisation, a real wrapped in `DEFI_CONSTANTE`, a
//! keyword code_aster 11 implied written, an ignored one removed;
//! and the Python 2 statements the AST keeps become Python 3: `print x` →
//! `print(x)`, `exec c` → `exec(c)`, `` `x` `` → `repr(x)`, `xrange` →
//! `range`. A legacy
//! diagnostic with no source rewrite (a structure the program builds in a
//! dictionary, `**kw`) is left as it is and reported: the file keeps the
//! old spelling there.

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

/// A call of the AST: `NAME(args)` (a command, or `_F` of a factor keyword).
struct Call<'a> {
    span: (usize, usize),
    /// The called name when it is a plain name.
    name: Option<&'a str>,
    name_span: (usize, usize),
    args: &'a [Json],
}

impl<'a> Call<'a> {
    fn of(v: &'a Json) -> Option<Call<'a>> {
        if v.get("expr").and_then(Json::as_str) != Some("Call") {
            return None;
        }
        let func = v.get("func")?;
        Some(Call {
            span: span_of(v)?,
            name: (func.get("expr").and_then(Json::as_str) == Some("Name"))
                .then(|| func.get("id").and_then(Json::as_str))
                .flatten(),
            name_span: span_of(func)?,
            args: v.get("args")?.as_array()?,
        })
    }

    /// The keyword argument `name` written in this call.
    fn keyword(&self, name: &str) -> Option<KwArg<'a>> {
        self.keywords().into_iter().find(|k| k.name == name)
    }

    /// Every keyword argument written in this call, in order.
    fn keywords(&self) -> Vec<KwArg<'a>> {
        self.args
            .iter()
            .filter_map(|a| {
                if a.get("arg").and_then(Json::as_str) != Some("Keyword") {
                    return None;
                }
                Some(KwArg {
                    span: span_of(a)?,
                    name: a.get("name")?.get("name")?.as_str()?,
                    value: a.get("value")?,
                })
            })
            .collect()
    }

    /// The offset just after the opening parenthesis.
    fn inside(&self, source: &str) -> Option<usize> {
        let from = self.name_span.1;
        Some(from + source.get(from..self.span.1)?.find('(')? + 1)
    }
}

/// What a rewrite may look at: the source, every keyword argument and call.
struct Context<'a> {
    source: &'a str,
    calls: Vec<Call<'a>>,
}

impl<'a> Context<'a> {
    /// The innermost command call (not `_F`) around `span`.
    fn command_around(&self, span: (usize, usize)) -> Option<&Call<'a>> {
        self.calls
            .iter()
            .filter(|c| c.span.0 <= span.0 && span.1 <= c.span.1 && c.span != span)
            .filter(|c| c.name.is_some_and(|n| n != "_F"))
            .min_by_key(|c| c.span.1 - c.span.0)
    }

    fn text(&self, span: (usize, usize)) -> &'a str {
        self.source.get(span.0..span.1).unwrap_or("")
    }

    /// The source text of each element a value writes ([`elements`]).
    fn element_texts(&self, value: &Json) -> Option<Vec<&'a str>> {
        elements(value)?
            .into_iter()
            .map(|e| span_of(e).map(|s| self.text(s)))
            .collect()
    }

    /// The `_F(...)` occurrences a factor keyword's value writes (one call,
    /// or a tuple/list of calls); `None` when it is built otherwise (a
    /// variable, a comprehension).
    fn occurrences(&self, value: &'a Json) -> Option<Vec<Call<'a>>> {
        elements(value)?
            .into_iter()
            .map(|v| Call::of(v).filter(|c| c.name == Some("_F")))
            .collect()
    }
}

/// The elements a value writes: those of a tuple or list, else the value.
fn elements(value: &Json) -> Option<Vec<&Json>> {
    Some(match value.get("expr").and_then(Json::as_str) {
        Some("Tuple" | "List") => value.get("elts")?.as_array()?.iter().collect(),
        _ => vec![value],
    })
}

fn span_of(v: &Json) -> Option<(usize, usize)> {
    let s = v.get("span")?.as_array()?;
    Some((s.first()?.as_u64()? as usize, s.get(1)?.as_u64()? as usize))
}

/// Every keyword argument, Python 2 statement and backquote of the module.
fn walk<'a>(v: &'a Json, kws: &mut Vec<KwArg<'a>>, py2: &mut Vec<&'a Json>) {
    walk_all(v, kws, py2, &mut Vec::new());
}

/// [`walk`], and every call.
fn walk_all<'a>(
    v: &'a Json,
    kws: &mut Vec<KwArg<'a>>,
    py2: &mut Vec<&'a Json>,
    calls: &mut Vec<Call<'a>>,
) {
    match v {
        Json::Object(o) => {
            if let Some(c) = Call::of(v) {
                calls.push(c);
            }
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
                walk_all(x, kws, py2, calls);
            }
        }
        Json::Array(a) => {
            for x in a {
                walk_all(x, kws, py2, calls);
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
    let mut calls = Vec::new();
    walk_all(&ast, &mut kws, &mut py2, &mut calls);
    let ctx = Context { source, calls };
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
        let edit = match arg {
            Some(a) => legacy_edit(&d.message, a, &ctx),
            // A diagnostic about a whole call (a command replaced by
            // another, a keyword it lacks) spans the call.
            None => ctx
                .calls
                .iter()
                .find(|c| c.span.0 == span.0 && c.name.is_some())
                .and_then(|c| call_edit(&d.message, c, &ctx))
                .or_else(|| double_star_edit(&d.message, span, &ctx)),
        };
        match edit {
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
    // At one place: an insertion before what replaces or removes the text
    // there (`CALC_MODES(` + `OPTION=…, ` then `OPTION='SANS',` removed).
    edits.sort_by_key(|e| (e.start, e.end != e.start, std::cmp::Reverse(e.end)));
    // A call in a loop gives its diagnostics once per pass through it.
    edits.dedup_by(|a, b| a.start == b.start && a.end == b.end && a.text == b.text);
    let mut out = String::with_capacity(source.len());
    let mut at = 0;
    let mut applied = 0;
    let mut last_removal = false;
    for e in edits {
        if e.start < at {
            // Two removals that touch (an argument and the comma of the
            // next one) remove their union.
            if last_removal && e.text.is_empty() && e.end > at {
                at = e.end;
            }
            continue;
        }
        last_removal = e.text.is_empty() && e.end > e.start;
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
fn legacy_edit(message: &str, arg: &KwArg, ctx: &Context) -> Option<Vec<Edit>> {
    let source = ctx.source;
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
    if let Some(e) = moved_or_rewritten(message, subj, arg, value_src, ctx) {
        return Some(e);
    }
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
    // PROJ_CHAMP/PROL_ZERO (code_aster 17's compat_syntax): 'OUI' is
    // PROL_VALE=0.0, 'NON' the default.
    if arg.name == "PROL_ZERO" && message.contains("is compatibility syntax: now PROL_VALE=0.0") {
        return replace("PROL_VALE=0.0".into());
    }
    if arg.name == "PROL_ZERO" && message.contains("is compatibility syntax: 'NON' is the default")
    {
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
            let occurrences = elements(arg.value)?;
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

/// A quoted Python string of `text` (single quotes unless it has one).
fn quoted(text: &str) -> String {
    if text.contains('\'') && !text.contains('"') {
        format!("\"{text}\"")
    } else {
        format!("'{}'", text.replace('\\', "\\\\").replace('\'', "\\'"))
    }
}

/// The rewrites that move a value to another place or rebuild it (the
/// structures of docs/legacy.md, "Rewritten structures").
fn moved_or_rewritten(
    message: &str,
    subj: &str,
    arg: &KwArg,
    value_src: &str,
    ctx: &Context,
) -> Option<Vec<Edit>> {
    let source = ctx.source;
    let (start, end) = arg.span;
    let value = value_src.trim();
    let insert = |at: usize, text: String| Edit {
        start: at,
        end: at,
        text,
    };
    // ALPHA=1.0e-5 where a function is expected now.
    if message.contains(": a real is code_aster 11 syntax here: now a function, DEFI_CONSTANTE(") {
        return Some(vec![Edit {
            start,
            end,
            text: format!("{}=DEFI_CONSTANTE(VALE={value})", arg.name),
        }]);
    }
    // Ignored keywords (no use, or no such choice in code_aster 17).
    if subj == arg.name
        && (message.contains(" has no use: ignored")
            || message.contains(" in code_aster 17: ignored"))
    {
        return Some(vec![removal(source, start, end)]);
    }
    // CREA_RESU(NOM_CHAM=X, AFFE=_F(...)) → AFFE=_F(NOM_CHAM=X, ...).
    if subj == "NOM_CHAM" && message.contains("now AFFE=_F(NOM_CHAM=...) in each occurrence") {
        let cmd = ctx.command_around(arg.span)?;
        let affe = cmd.keyword("AFFE")?;
        let mut edits = vec![removal(source, start, end)];
        // AFFE=l_affe, a list of dictionaries built by the program: each
        // element gets the field name as the program runs.
        if affe.value.get("expr").and_then(Json::as_str) == Some("Name") {
            let list = affe.value.get("id")?.as_str()?;
            edits.push(Edit {
                start: affe.span.0,
                end: affe.span.1,
                text: format!("AFFE=[_F(NOM_CHAM={value}, **occ) for occ in {list}]"),
            });
            return Some(edits);
        }
        for occ in ctx.occurrences(affe.value)? {
            if occ.keyword("NOM_CHAM").is_none() {
                edits.push(insert(occ.inside(source)?, format!("NOM_CHAM={value}, ")));
            }
        }
        return Some(edits);
    }
    // DEFI_LIST_INST(DEFI_LIST=_F(METHODE=M, ...)) → DEFI_LIST_INST(METHODE=M, ...).
    if subj == "METHODE" && message.contains("/DEFI_LIST/METHODE` is code_aster 11 syntax: now ") {
        let cmd = ctx.command_around(arg.span)?;
        let mut edits = vec![removal(source, start, end)];
        if !message.contains("whose default is") {
            edits.push(insert(cmd.inside(source)?, format!("METHODE={value}, ")));
        }
        return Some(edits);
    }
    // PARTITION=_F(PARALLELISME=P) → DISTRIBUTION=_F(METHODE=P).
    if subj.starts_with("PARTITION=_F(") && message.contains("now DISTRIBUTION=_F(METHODE=...)") {
        let mut edits = vec![Edit {
            start,
            end: start + arg.name.len(),
            text: "DISTRIBUTION".into(),
        }];
        for occ in ctx.occurrences(arg.value)? {
            for kw in occ.keywords() {
                match kw.name {
                    "PARALLELISME" => edits.push(Edit {
                        start: kw.span.0,
                        end: kw.span.0 + kw.name.len(),
                        text: "METHODE".into(),
                    }),
                    // The FETI sub-domains went with FETI.
                    "PARTITION" => edits.push(removal(source, kw.span.0, kw.span.1)),
                    _ => {}
                }
            }
        }
        return Some(edits);
    }
    // THER_NON_LINE(NEWTON=_F(ITER_LINE_MAXI=n, RESI_LINE_RELA=r, ...)) →
    // RECH_LINEAIRE=_F(ITER_LINE_MAXI=n, RESI_LINE_RELA=r), NEWTON=_F(...)
    // (code_aster's compat_syntax of THER_NON_LINE).
    if arg.name == "NEWTON"
        && subj == "ITER_LINE_MAXI"
        && message.contains("now RECH_LINEAIRE=_F(ITER_LINE_MAXI=...)")
    {
        let mut moved = Vec::new();
        let mut edits = Vec::new();
        for occ in ctx.occurrences(arg.value)? {
            for kw in occ.keywords() {
                if matches!(kw.name, "ITER_LINE_MAXI" | "RESI_LINE_RELA") {
                    moved.push(ctx.text(kw.span).to_string());
                    edits.push(removal(source, kw.span.0, kw.span.1));
                }
            }
        }
        if moved.is_empty() {
            return None;
        }
        edits.push(insert(
            start,
            format!("RECH_LINEAIRE=_F({}), ", moved.join(", ")),
        ));
        return Some(edits);
    }
    // TITRE=('a', 'b') → TITRE='a b'.
    if message
        .contains(" with several strings is code_aster 11 syntax: now one text (joined by spaces)")
    {
        let elts = arg.value.get("elts")?.as_array()?;
        let parts: Vec<&str> = elts
            .iter()
            .map(|e| {
                (e.get("expr").and_then(Json::as_str) == Some("Str"))
                    .then(|| e.get("value").and_then(Json::as_str))
                    .flatten()
            })
            .collect::<Option<_>>()?;
        return Some(vec![Edit {
            start,
            end,
            text: format!("{}={}", arg.name, quoted(&parts.join(" "))),
        }]);
    }
    // A keyword code_aster 11 implied, written now beside `arg` (the
    // warning spans an argument of the call that lacks it).
    for (marker, text) in [
        (
            "` without TYPE_VECT: code_aster 11's default TYPE_VECT='FORC' is now written",
            "TYPE_VECT='FORC', ",
        ),
        (
            "` without FORMAT printed text in code_aster 11 (MED in code_aster 17): FORMAT='RESULTAT' written",
            "FORMAT='RESULTAT', ",
        ),
    ] {
        if message.contains(marker) {
            return Some(vec![insert(start, text.to_string())]);
        }
    }
    // DEFI_CONTACT/ZONE/TYPE_APPA='FIXE' → TYPE_PROJECTION='FIXE'.
    if subj.starts_with("TYPE_APPA=") {
        let now = message.split_once(" is code_aster 11 syntax: now ")?.1;
        if now.starts_with("TYPE_PROJECTION='") {
            return Some(vec![Edit {
                start,
                end,
                text: now.to_string(),
            }]);
        }
    }
    // AFFE=_F(..., MODELISATION=('A', 'B')) → AFFE=(_F(..., MODELISATION='A'),
    // _F(..., MODELISATION='B')), in the same order.
    if arg.name == "AFFE"
        && message.contains("/AFFE/MODELISATION` with several values is code_aster 11 syntax")
    {
        let mut occs_text = Vec::new();
        for occ in ctx.occurrences(arg.value)? {
            let whole = ctx.text(occ.span);
            let Some(m) = occ.keyword("MODELISATION") else {
                occs_text.push(whole.to_string());
                continue;
            };
            let models = ctx.element_texts(m.value)?;
            let (a, b) = (m.span.0 - occ.span.0, m.span.1 - occ.span.0);
            for model in models {
                occs_text.push(format!(
                    "{}MODELISATION={model}{}",
                    &whole[..a],
                    &whole[b..]
                ));
            }
        }
        return Some(vec![Edit {
            start,
            end,
            text: format!("AFFE=({},)", occs_text.join(", ")),
        }]);
    }
    // COMP_ELAS beside COMP_INCR: one COMPORTEMENT with the occurrences of
    // both (COMP_INCR's first); alone, a rename.
    if subj == "COMP_ELAS"
        && message.contains("now COMPORTEMENT, together with the occurrences of COMP_INCR")
    {
        let cmd = ctx.command_around(arg.span)?;
        let Some(incr) = cmd.keyword("COMP_INCR") else {
            if cmd.keyword("COMPORTEMENT").is_some() {
                return None;
            }
            return Some(vec![Edit {
                start,
                end: start + arg.name.len(),
                text: "COMPORTEMENT".into(),
            }]);
        };
        let mut all = ctx.element_texts(incr.value)?;
        all.extend(ctx.element_texts(arg.value)?);
        return Some(vec![
            Edit {
                start: incr.span.0,
                end: incr.span.1,
                text: format!("COMPORTEMENT=({},)", all.join(", ")),
            },
            removal(source, start, end),
        ]);
    }
    None
}

/// `DETRUIRE(**kw)` whose dictionary holds code_aster 11's
/// `CONCEPT=[_F(NOM=X), …]`, built by the program: the names are taken out
/// of it as the call runs (`NOM=[occ['NOM'] for occ in kw.pop('CONCEPT')]`).
/// The program builds that list by appending occurrences; were it one
/// `_F`, the migrated file would fail its check rather than run wrong.
fn double_star_edit(message: &str, span: (usize, usize), ctx: &Context) -> Option<Vec<Edit>> {
    if !message.starts_with("`DETRUIRE/CONCEPT=_F(NOM=...)` is code_aster 11 syntax") {
        return None;
    }
    let arg = ctx.calls.iter().flat_map(|c| c.args.iter()).find(|a| {
        a.get("arg").and_then(Json::as_str) == Some("DoubleStar") && span_of(a) == Some(span)
    })?;
    let value = arg.get("value")?;
    if value.get("expr").and_then(Json::as_str) != Some("Name") {
        return None;
    }
    let dict = value.get("id")?.as_str()?;
    Some(vec![Edit {
        start: span.0,
        end: span.1,
        text: format!("NOM=[occ['NOM'] for occ in {dict}.pop('CONCEPT')], **{dict}"),
    }])
}

/// Keywords of the modal solver that code_aster 11 wrote at the top level
/// of `MODE_ITER_SIMULT` (or in `CALC_FREQ`): `SOLVEUR_MODAL` now (the
/// list of [`crate::legacy_commands`]).
fn solveur_modal_key(name: &str) -> bool {
    crate::legacy_commands::SOLVEUR_MODAL_KEYS.contains(&name)
}

/// The edits for a legacy diagnostic about a whole call `call`.
fn call_edit(message: &str, call: &Call, ctx: &Context) -> Option<Vec<Edit>> {
    let source = ctx.source;
    let name = call.name?;
    let rename = |to: &str| Edit {
        start: call.name_span.0,
        end: call.name_span.1,
        text: to.to_string(),
    };
    if let Some(now) = message.strip_prefix(&format!(
        "`{name}` without INCREMENT is code_aster 11's stationary computation: now "
    )) {
        return Some(vec![Edit {
            start: call.inside(source)?,
            end: call.inside(source)?,
            text: format!("{now}, "),
        }]);
    }
    match message.strip_prefix(&format!("`{name}` is code_aster 11 syntax: now "))? {
        "ASSEMBLAGE" if name == "MACRO_MATR_ASSE" => Some(vec![rename("ASSEMBLAGE")]),
        "CALC_MODES" if matches!(name, "MODE_ITER_SIMULT" | "MODE_ITER_INV") => {
            modal_edits(name, call, ctx).map(|mut e| {
                e.push(rename("CALC_MODES"));
                e
            })
        }
        _ => None,
    }
}

/// `MODE_ITER_SIMULT` / `MODE_ITER_INV` → `CALC_MODES`, as the checker maps
/// them (`legacy_commands::modal`): the matrices renamed after the problem,
/// `CALC_FREQ/OPTION` up to `OPTION`, the method keywords into
/// `SOLVEUR_MODAL`, code_aster 11's top-level `OPTION='MODE_RIGIDE'` into
/// `SOLVEUR_MODAL/MODE_RIGIDE='OUI'`, `STOP_FREQ_VIDE` dropped.
fn modal_edits(old: &str, call: &Call, ctx: &Context) -> Option<Vec<Edit>> {
    let source = ctx.source;
    let mut edits = Vec::new();
    let mut solveur: Vec<String> = Vec::new();
    let mut option: Option<String> = None;
    fn literal(v: &Json) -> Option<&str> {
        (v.get("expr").and_then(Json::as_str) == Some("Str"))
            .then(|| v.get("value").and_then(Json::as_str))
            .flatten()
    }
    let type_resu = match call.keyword("TYPE_RESU") {
        Some(t) => Some(literal(t.value)?),
        None => None,
    };
    let names = crate::legacy_commands::modal_matrix_names(type_resu);
    for kw in call.keywords() {
        let value = ctx.text(span_of(kw.value)?);
        if let Some((_, to)) = names.iter().find(|(f, _)| *f == kw.name) {
            edits.push(Edit {
                start: kw.span.0,
                end: kw.span.0 + kw.name.len(),
                text: to.to_string(),
            });
            continue;
        }
        match kw.name {
            "OPTION" => {
                if literal(kw.value)? == "MODE_RIGIDE" {
                    solveur.push("MODE_RIGIDE='OUI'".into());
                }
                edits.push(removal(source, kw.span.0, kw.span.1));
            }
            "STOP_FREQ_VIDE" => edits.push(removal(source, kw.span.0, kw.span.1)),
            n if solveur_modal_key(n) => {
                solveur.push(format!("{n}={value}"));
                edits.push(removal(source, kw.span.0, kw.span.1));
            }
            "CALC_FREQ" | "CALC_CHAR_CRIT" => {
                let occs = ctx.occurrences(kw.value)?;
                let first = occs.first()?;
                for inner in first.keywords() {
                    let v = ctx.text(span_of(inner.value)?);
                    if inner.name == "OPTION" {
                        option = Some(v.to_string());
                    } else if solveur_modal_key(inner.name) {
                        solveur.push(format!("{}={v}", inner.name));
                    } else {
                        continue;
                    }
                    edits.push(removal(source, inner.span.0, inner.span.1));
                }
            }
            "CALC_MODE" => {
                let occs = ctx.occurrences(kw.value)?;
                for inner in occs.first()?.keywords() {
                    let v = ctx.text(span_of(inner.value)?);
                    let to = match inner.name {
                        "OPTION" => "OPTION_INV",
                        "PREC" => "PREC_INV",
                        "NMAX_ITER" => "NMAX_ITER_INV",
                        _ => continue,
                    };
                    solveur.push(format!("{to}={v}"));
                }
                edits.push(removal(source, kw.span.0, kw.span.1));
            }
            // An explicit SOLVEUR_MODAL (not code_aster 11) is not merged.
            "SOLVEUR_MODAL" if !solveur.is_empty() => return None,
            _ => {}
        }
    }
    if option.is_none() && old == "MODE_ITER_INV" {
        option = Some("'AJUSTE'".into());
    }
    let mut head = String::new();
    if let Some(o) = option {
        head.push_str(&format!("OPTION={o}, "));
    }
    if !solveur.is_empty() {
        head.push_str(&format!("SOLVEUR_MODAL=_F({}), ", solveur.join(", ")));
    }
    if !head.is_empty() {
        let at = call.inside(source)?;
        edits.push(Edit {
            start: at,
            end: at,
            text: head,
        });
    }
    Some(edits)
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
        // Nothing after it on its line: no trailing blank left either.
        let mut s = start;
        if e >= b.len() || b[e] == b'\n' {
            while s > line_start && (b[s - 1] == b' ' || b[s - 1] == b'\t') {
                s -= 1;
            }
        }
        return Edit {
            start: s,
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
