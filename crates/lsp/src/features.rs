//! The language features, each a pure function of a document's text, its
//! [`Analysis`] and a position: diagnostics and their quick fixes, hover,
//! completion, signature help, definition, references, symbols. The
//! server ([`crate::server`]) only converts positions and routes messages.

use crate::analysis::{Analysis, Finding, Level};
use crate::context::{self, Context, Env, Slot};
use crate::lex::{self, Kind};
use crate::text::Document;
use aster_catalog::{catalog, Entry, Lit, Node, Produces, SimpleKw, Status, ValueType};
use lsp_types::*;
use std::collections::HashMap;

// ------------------------------------------------------------ diagnostics

/// The LSP diagnostics of an analysis.
pub fn diagnostics(doc: &Document, uri: &Uri, a: &Analysis) -> Vec<Diagnostic> {
    a.findings
        .iter()
        .map(|f| diagnostic(doc, uri, a, f))
        .collect()
}

fn diagnostic(doc: &Document, uri: &Uri, a: &Analysis, f: &Finding) -> Diagnostic {
    let mut message = f.message.clone();
    for n in &f.notes {
        message.push('\n');
        message.push_str(n);
    }
    let related: Vec<DiagnosticRelatedInformation> = related(doc, a, f)
        .into_iter()
        .map(|(s, e, m)| DiagnosticRelatedInformation {
            location: Location::new(uri.clone(), doc.range(s, e)),
            message: m,
        })
        .collect();
    Diagnostic {
        range: doc.range(f.start, f.end),
        severity: Some(match f.level {
            Level::Error => DiagnosticSeverity::ERROR,
            Level::Warning => DiagnosticSeverity::WARNING,
            Level::Information => DiagnosticSeverity::INFORMATION,
        }),
        code: Some(NumberOrString::String(f.code.clone())),
        source: Some("aster".into()),
        message,
        related_information: (!related.is_empty()).then_some(related),
        ..Diagnostic::default()
    }
}

/// The places a finding refers to: the definition of a concept it names
/// (`found concept BLOC of type …`), the keywords written in the call that
/// a block condition it quotes reads.
fn related(doc: &Document, a: &Analysis, f: &Finding) -> Vec<(usize, usize, String)> {
    let mut out = Vec::new();
    let words: Vec<&str> = f
        .message
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .collect();
    for w in words.windows(2) {
        if w[0] == "concept" {
            if let Some(d) = a.definition(w[1], f.start) {
                out.push((d.start, d.end, format!("`{}` is defined here", w[1])));
            }
        }
    }
    if f.code == "keyword_not_applicable" {
        let ctx = context::at(&doc.text, f.start);
        if let Some(path) = &ctx.path {
            for &fi in &path.frames {
                for w in &ctx.frames[fi].written {
                    if f.message.contains(&format!("\"{}\"", w.name))
                        || f.message.contains(&format!("'{}'", w.name))
                    {
                        out.push((
                            w.start,
                            w.end,
                            format!("the condition reads {} here", w.name),
                        ));
                    }
                }
            }
        }
    }
    out
}

/// The edits that fix a finding: each did-you-mean suggestion, and the
/// current form of a legacy spelling. `(title, start, end, new text)`.
pub fn fixes(doc: &Document, f: &Finding) -> Vec<(String, usize, usize, String)> {
    let src = &doc.text;
    let toks: Vec<lex::Token> = lex::tokens(&src[..f.end.min(src.len())])
        .into_iter()
        .filter(|t| t.start >= f.start)
        .collect();
    let first_name = toks.iter().find(|t| t.kind == Kind::Name);
    // A value quoted in the message (`value 'MECANIQE'`): its literal.
    let quoted_value = |v: &str| {
        toks.iter()
            .find(|t| matches!(t.kind, Kind::Str { .. }) && lex::str_content(src, t) == v)
            .map(|t| lex::str_content_range(src, t))
    };
    let mut out = Vec::new();
    let legacy_value = f
        .message
        .split_once("legacy value ")
        .and_then(|(_, r)| r.split_once(" is now "));
    if let Some((old, new)) = legacy_value {
        let (old, new) = (unquote(old), unquote(new));
        if let Some((s, e)) = quoted_value(old) {
            out.push((format!("Migrate to '{new}'"), s, e, new.to_string()));
        }
        return out;
    }
    if let Some((_, new)) = f.message.split_once("is legacy syntax: now ") {
        let new = new.trim();
        if let Some(t) = first_name {
            if new.chars().all(|c| c.is_alphanumeric() || c == '_') {
                out.push((format!("Migrate to {new}"), t.start, t.end, new.to_string()));
            }
        }
        return out;
    }
    let target = if f.code == "value_not_allowed" {
        f.message
            .split_once("value ")
            .map(|(_, r)| r.split(' ').next().unwrap_or(""))
            .and_then(|v| quoted_value(unquote(v)))
    } else {
        first_name.map(|t| (t.start, t.end))
    };
    let Some((s, e)) = target else { return out };
    for n in &f.notes {
        let Some(list) = n.strip_prefix("help: did you mean ") else {
            continue;
        };
        for cand in list.split('`').skip(1).step_by(2) {
            out.push((
                format!("Replace with {cand}"),
                s,
                e,
                unquote(cand).to_string(),
            ));
        }
    }
    out
}

fn unquote(s: &str) -> &str {
    let s = s.trim().trim_end_matches(['.', ',', ':']);
    s.trim_matches(|c| c == '\'' || c == '"')
}

/// The quick fixes of the findings a range touches.
// `WorkspaceEdit::changes` is lsp-types' `HashMap<Uri, _>`; `Uri` caches its
// parse lazily (interior mutability) but never changes its hash.
#[allow(clippy::mutable_key_type)]
pub fn code_actions(doc: &Document, uri: &Uri, a: &Analysis, range: Range) -> Vec<CodeAction> {
    let (rs, re) = (doc.offset(range.start), doc.offset(range.end));
    let mut out = Vec::new();
    for f in &a.findings {
        if f.end < rs || f.start > re {
            continue;
        }
        let fx = fixes(doc, f);
        let single = fx.len() == 1;
        for (title, s, e, new) in fx {
            let mut changes = HashMap::new();
            changes.insert(
                uri.clone(),
                vec![TextEdit {
                    range: doc.range(s, e),
                    new_text: new,
                }],
            );
            out.push(CodeAction {
                title,
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![diagnostic(doc, uri, a, f)]),
                edit: Some(WorkspaceEdit {
                    changes: Some(changes),
                    ..WorkspaceEdit::default()
                }),
                is_preferred: Some(single),
                ..CodeAction::default()
            });
        }
    }
    out
}

// ------------------------------------------------------------------ hover

/// The token under a position (a position at a token's end counts).
fn token_at(src: &str, offset: usize) -> Option<lex::Token> {
    lex::tokens(src)
        .into_iter()
        .find(|t| t.start <= offset && offset <= t.end && t.kind == Kind::Name)
}

/// Legacy names a keyword of the current catalog replaces.
fn replaced_names(command: &str, keyword: &str) -> Vec<&'static str> {
    let renames = aster_eval::legacy::RENAMES
        .iter()
        .map(|(c, o, n, _)| (*c, *o, *n))
        .chain(aster_eval::legacy::LEGACY_RENAMES.iter().copied());
    let mut out: Vec<&str> = renames
        .filter(|(c, _, n)| (*c == "*" || *c == command) && *n == keyword)
        .map(|(_, o, _)| o)
        .collect();
    out.dedup();
    out
}

/// The current name of a legacy keyword.
fn renamed_to(command: &str, keyword: &str) -> Option<&'static str> {
    aster_eval::legacy::RENAMES
        .iter()
        .map(|(c, o, n, _)| (*c, *o, *n))
        .chain(aster_eval::legacy::LEGACY_RENAMES.iter().copied())
        .find(|(c, o, _)| (*c == "*" || *c == command) && *o == keyword)
        .map(|(_, _, n)| n)
}

fn markdown(text: String) -> Hover {
    Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: text,
        }),
        range: None,
    }
}

/// Hover: on a command, its keyword tree; on a keyword, what `aster
/// explain CMD/…/KW` prints (with the legacy names it replaces); on a
/// name, its concept type and where it is defined.
pub fn hover(doc: &Document, a: &Analysis, pos: Position) -> Option<Hover> {
    let src = &doc.text;
    let offset = doc.offset(pos);
    let tok = token_at(src, offset)?;
    let word = tok.text(src);
    let rest = src[tok.end..].trim_start_matches([' ', '\t']);
    let range = Some(doc.range(tok.start, tok.end));
    if rest.starts_with('=') && !rest.starts_with("==") {
        let ctx = context::at(src, tok.start);
        if ctx.slot == Slot::Keyword {
            let path = ctx.path.as_ref()?;
            let mut parts = vec![path.command.clone()];
            parts.extend(path.factors.iter().cloned());
            parts.push(word.to_string());
            let mut text = match aster_catalog::explain::explain(&parts.join("/")) {
                Ok(t) => format!("```text\n{t}```"),
                Err(e) => match renamed_to(&path.command, word) {
                    Some(new) => format!(
                        "`{word}` is a legacy keyword: code_aster 17 writes `{new}` (`aster check` rewrites it)"
                    ),
                    None => e,
                },
            };
            let old = replaced_names(&path.command, word);
            if !old.is_empty() {
                text.push_str(&format!(
                    "\n\nReplaces the legacy {}.",
                    old.iter()
                        .map(|o| format!("`{o}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
            return Some(Hover {
                range,
                ..markdown(text)
            });
        }
    }
    if rest.starts_with('(') && catalog().command(word).is_some() {
        let text = aster_catalog::explain::explain(word).ok()?;
        return Some(Hover {
            range,
            ..markdown(format!("```text\n{text}```"))
        });
    }
    let def = a.definition(word, offset);
    let concept = a.concept_before(word, offset);
    if def.is_none() && concept.is_none() {
        return None;
    }
    let mut text = format!("`{word}`");
    if let Some(c) = concept {
        let p = doc.position(c.call.start as usize);
        text.push_str(&format!(
            ": concept of type `{}`, made by {} (line {})",
            c.typ,
            c.command,
            p.line + 1
        ));
    }
    if let Some(d) = def {
        let p = doc.position(d.start);
        text.push_str(&format!(
            "\n\ndefined at line {}, column {}",
            p.line + 1,
            p.character + 1
        ));
    }
    Some(Hover {
        range,
        ..markdown(text)
    })
}

// ------------------------------------------------------------- completion

fn kw_detail(e: &Entry) -> String {
    match &e.node {
        Node::Simple(s) => {
            let types: Vec<&str> = s.types.iter().map(|t| t.code()).collect();
            let mut d = format!("{} {}", status(s.status), types.join("|"));
            if let Some(def) = &s.default {
                d.push_str(&format!(
                    ", default {}",
                    def.iter()
                        .map(Lit::to_string)
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
            d
        }
        Node::Factor(f) => format!("{} factor keyword", status(f.status)),
        Node::Block(_) => String::new(),
    }
}

fn status(s: Status) -> &'static str {
    match s {
        Status::Mandatory => "mandatory",
        Status::Optional => "optional",
        Status::Defaulted => "default",
        Status::Hidden => "hidden",
    }
}

/// The keywords valid at the innermost catalog level of `ctx` (with the
/// rules that apply there), and the names already written there.
pub fn valid_keywords<'c>(
    ctx: &Context,
    a: &Analysis,
    offset: usize,
) -> Option<(context::Level<'c>, Vec<String>)> {
    let path = ctx.path.as_ref()?;
    let cmd = catalog().command(&path.command)?;
    let types = |n: &str| a.concept_before(n, offset).map(|c| c.typ.clone());
    let mut env = Env::new(ctx, &types);
    let active = context::level_active(cmd, &path.factors, &mut env)?;
    let level = &ctx.frames[*path.frames.last()?];
    let written = level.written.iter().map(|w| w.name.clone()).collect();
    Some((active, written))
}

fn item(label: String, kind: CompletionItemKind, detail: String) -> CompletionItem {
    CompletionItem {
        label,
        kind: Some(kind),
        detail: (!detail.is_empty()).then_some(detail),
        ..CompletionItem::default()
    }
}

/// Completion at a position. `groups` gives the group names of the
/// meshes the program reads (cell groups, node groups), when they resolve.
pub fn completion(
    doc: &Document,
    a: &Analysis,
    pos: Position,
    groups: &dyn Fn() -> (Vec<String>, Vec<String>),
) -> Vec<CompletionItem> {
    let offset = doc.offset(pos);
    let ctx = context::at(&doc.text, offset);
    let prefix = ctx.prefix.to_uppercase();
    let edit_range = doc.range(ctx.prefix_start, offset);
    let mut items: Vec<CompletionItem> = Vec::new();
    match &ctx.slot {
        Slot::Keyword => {
            if let Some((level, written)) = valid_keywords(&ctx, a, offset) {
                for &e in &level.entries {
                    if e.name.starts_with(&prefix)
                        && !written.iter().any(|w| w == e.name)
                        && !level.excluded(e.name, &written)
                    {
                        if matches!(&e.node, Node::Simple(s) if s.status == Status::Hidden) {
                            continue;
                        }
                        let (kind, insert) = match &e.node {
                            Node::Factor(_) => {
                                (CompletionItemKind::STRUCT, format!("{}=_F(", e.name))
                            }
                            _ => (CompletionItemKind::FIELD, format!("{}=", e.name)),
                        };
                        let mandatory = matches!(
                            &e.node,
                            Node::Simple(SimpleKw {
                                status: Status::Mandatory,
                                ..
                            })
                        ) || matches!(&e.node, Node::Factor(f) if f.status == Status::Mandatory);
                        let mut it = item(e.name.to_string(), kind, kw_detail(e));
                        it.sort_text = Some(format!("{}{}", u8::from(!mandatory), e.name));
                        it.text_edit = Some(CompletionTextEdit::Edit(TextEdit {
                            range: edit_range,
                            new_text: insert,
                        }));
                        items.push(it);
                    }
                }
            }
        }
        Slot::Value { keyword } => {
            let entry = valid_keywords(&ctx, a, offset)
                .and_then(|(level, _)| level.entries.into_iter().find(|e| e.name == keyword));
            if let Some(Entry {
                node: Node::Simple(s),
                ..
            }) = entry
            {
                value_items(&ctx, a, s, offset, groups, &mut items);
            }
            for it in &mut items {
                it.text_edit = Some(CompletionTextEdit::Edit(TextEdit {
                    range: edit_range,
                    new_text: it.insert_text.take().unwrap_or_else(|| it.label.clone()),
                }));
            }
            items.retain(|i| {
                i.label
                    .trim_matches(['\'', '"'])
                    .to_uppercase()
                    .starts_with(&prefix)
            });
        }
        Slot::Other => {}
    }
    if ctx.slot == Slot::Other && !ctx.in_string {
        for c in catalog().commands() {
            if c.name.starts_with(&prefix) && !prefix.is_empty() {
                let produces = match &c.produces {
                    Produces::Nothing => "procedure".to_string(),
                    Produces::Type(t) => t.to_string(),
                    Produces::Computed(_) => "type from its keywords".to_string(),
                };
                let mut it = item(c.name.to_string(), CompletionItemKind::FUNCTION, produces);
                it.text_edit = Some(CompletionTextEdit::Edit(TextEdit {
                    range: edit_range,
                    new_text: c.name.to_string(),
                }));
                items.push(it);
            }
        }
        names(a, offset, &prefix, None, edit_range, &mut items);
    }
    items
}

/// Names defined before `offset` (concepts with their type), of a type
/// accepted by `accept` when given.
fn names(
    a: &Analysis,
    offset: usize,
    prefix: &str,
    accept: Option<&dyn Fn(&str) -> bool>,
    range: Range,
    items: &mut Vec<CompletionItem>,
) {
    let mut seen: Vec<&str> = Vec::new();
    for o in a
        .occurrences
        .iter()
        .filter(|o| o.definition && o.start < offset)
    {
        if seen.contains(&o.name.as_str()) || !o.name.to_uppercase().starts_with(prefix) {
            continue;
        }
        let typ = a.concept_before(&o.name, offset).map(|c| c.typ.as_str());
        if let Some(acc) = accept {
            if !typ.is_some_and(acc) {
                continue;
            }
        }
        seen.push(&o.name);
        let mut it = item(
            o.name.clone(),
            CompletionItemKind::VARIABLE,
            typ.unwrap_or("").to_string(),
        );
        it.text_edit = Some(CompletionTextEdit::Edit(TextEdit {
            range,
            new_text: o.name.clone(),
        }));
        items.push(it);
    }
}

fn value_items(
    ctx: &Context,
    a: &Analysis,
    s: &SimpleKw,
    offset: usize,
    groups: &dyn Fn() -> (Vec<String>, Vec<String>),
    items: &mut Vec<CompletionItem>,
) {
    let quote = |v: &str| {
        if ctx.in_string {
            v.to_string()
        } else {
            format!("'{v}'")
        }
    };
    if let Some(into) = s.into {
        for l in into {
            let label = match l {
                Lit::Str(v) => quote(v),
                other => other.to_string(),
            };
            let default = s.default.as_ref().is_some_and(|d| d.contains(l));
            items.push(item(
                label,
                CompletionItemKind::ENUM_MEMBER,
                if default {
                    "default".into()
                } else {
                    String::new()
                },
            ));
        }
        return;
    }
    let (ma, no) = if s
        .types
        .iter()
        .any(|t| matches!(t, ValueType::GroupMa | ValueType::GroupNo))
    {
        groups()
    } else {
        (Vec::new(), Vec::new())
    };
    let mut seen: Vec<String> = Vec::new();
    for t in s.types {
        let (list, what) = match t {
            ValueType::GroupMa => (&ma, "cell group"),
            ValueType::GroupNo => (&no, "node group"),
            _ => continue,
        };
        for g in list {
            if !seen.contains(g) {
                seen.push(g.clone());
                items.push(item(quote(g), CompletionItemKind::VALUE, what.into()));
            }
        }
    }
    if ctx.in_string {
        return;
    }
    let expected: Vec<&str> = s
        .types
        .iter()
        .filter_map(|t| match t {
            ValueType::Concept(c) => Some(*c),
            _ => None,
        })
        .collect();
    if !expected.is_empty() {
        let accept = |typ: &str| expected.iter().any(|e| aster_catalog::types::is_a(typ, e));
        let range = Range::default();
        names(a, offset, "", Some(&accept), range, items);
        for it in items.iter_mut() {
            it.text_edit = None;
        }
    }
}

// --------------------------------------------------------- signature help

/// Signature help inside a call or `_F(`: the keywords valid there
/// (mandatory first, at most 40), the one being written active.
pub fn signature_help(doc: &Document, a: &Analysis, pos: Position) -> Option<SignatureHelp> {
    let offset = doc.offset(pos);
    let ctx = context::at(&doc.text, offset);
    let path = ctx.path.as_ref()?;
    let (level, _) = valid_keywords(&ctx, a, offset)?;
    let active = level.entries;
    let level = &ctx.frames[*path.frames.last()?];
    let current: Option<String> = match &ctx.slot {
        Slot::Value { keyword } => Some(keyword.clone()),
        Slot::Keyword if !ctx.prefix.is_empty() => Some(ctx.prefix.to_uppercase()),
        _ => level.pending.map(|w| level.written[w].name.clone()),
    };
    let mut shown: Vec<&Entry> = active
        .iter()
        .copied()
        .filter(|e| !matches!(&e.node, Node::Simple(s) if s.status == Status::Hidden))
        .collect();
    let rank = |e: &Entry| {
        let written = level.written.iter().any(|w| w.name == e.name);
        let mandatory = match &e.node {
            Node::Simple(s) => s.status == Status::Mandatory,
            Node::Factor(f) => f.status == Status::Mandatory,
            Node::Block(_) => false,
        };
        let is_current = current.as_deref() == Some(e.name);
        (!is_current, !mandatory, !written)
    };
    shown.sort_by_key(|e| rank(e));
    shown.truncate(40);
    let head = match path.factors.last() {
        Some(f) => format!("{f}=_F("),
        None => format!("{}(", path.command),
    };
    let mut label = head.clone();
    let mut params = Vec::new();
    let mut active_param = None;
    for (i, e) in shown.iter().enumerate() {
        if i > 0 {
            label.push_str(", ");
        }
        let start = label.encode_utf16().count() as u32;
        label.push_str(e.name);
        let end = label.encode_utf16().count() as u32;
        if current.as_deref() == Some(e.name) {
            active_param = Some(i as u32);
        }
        params.push(ParameterInformation {
            label: ParameterLabel::LabelOffsets([start, end]),
            documentation: Some(Documentation::String(kw_detail(e))),
        });
    }
    if active.len() > shown.len() {
        label.push_str(", …");
    }
    label.push(')');
    Some(SignatureHelp {
        signatures: vec![SignatureInformation {
            label,
            documentation: None,
            parameters: Some(params),
            active_parameter: active_param,
        }],
        active_signature: Some(0),
        active_parameter: active_param,
    })
}

// ------------------------------------------------------------- navigation

/// The definition of the name under a position.
pub fn definition(doc: &Document, a: &Analysis, uri: &Uri, pos: Position) -> Option<Location> {
    let offset = doc.offset(pos);
    let o = a.occurrence_at(offset)?;
    let d = a.definition(&o.name, offset)?;
    Some(Location::new(uri.clone(), doc.range(d.start, d.end)))
}

/// Every place the name under a position is bound or used.
pub fn references(
    doc: &Document,
    a: &Analysis,
    uri: &Uri,
    pos: Position,
    include_declaration: bool,
) -> Vec<Location> {
    let offset = doc.offset(pos);
    let Some(o) = a.occurrence_at(offset) else {
        return Vec::new();
    };
    a.occurrences
        .iter()
        .filter(|x| x.name == o.name && (include_declaration || !x.definition))
        .map(|x| Location::new(uri.clone(), doc.range(x.start, x.end)))
        .collect()
}

/// The command sequence as an outline, factor keywords as children.
pub fn symbols(doc: &Document, a: &Analysis) -> Vec<DocumentSymbol> {
    fn conv(doc: &Document, o: &crate::analysis::OutlineItem, top: bool) -> DocumentSymbol {
        #[allow(deprecated)]
        DocumentSymbol {
            name: o.name.clone(),
            detail: Some(o.detail.clone()),
            kind: if top {
                SymbolKind::FUNCTION
            } else {
                SymbolKind::FIELD
            },
            tags: None,
            deprecated: None,
            range: doc.range(o.start, o.end),
            selection_range: doc.range(o.sel_start, o.sel_end),
            children: (!o.children.is_empty())
                .then(|| o.children.iter().map(|c| conv(doc, c, false)).collect()),
        }
    }
    a.outline.iter().map(|o| conv(doc, o, true)).collect()
}
