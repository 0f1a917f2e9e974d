//! `aster explain`: the keyword tree of a command, or the facts of one
//! keyword, as text for the terminal.

use crate::model::*;
use crate::{catalog, Catalog};
use std::fmt::Write;

fn types_of(s: &SimpleKw) -> String {
    if s.types.is_empty() {
        "any".into()
    } else {
        s.types
            .iter()
            .map(|t| t.code().to_string())
            .collect::<Vec<_>>()
            .join("|")
    }
}

fn count(min: u32, max: Max) -> Option<String> {
    match (min, max) {
        (1, Max::Count(1)) => None,
        (a, Max::Count(b)) if a == b => Some(format!("exactly {a} values")),
        (a, m) => Some(format!(
            "{a}..{} values",
            match m {
                Max::Count(b) => b.to_string(),
                Max::Unbounded(_) => "n".into(),
            }
        )),
    }
}

fn short_list(into: &[Lit], max: usize) -> String {
    let shown: Vec<String> = into.iter().take(max).map(|l| l.to_string()).collect();
    if into.len() > max {
        format!("{}, … ({} values)", shown.join(", "), into.len())
    } else {
        shown.join(", ")
    }
}

fn simple_line(name: &str, s: &SimpleKw, list_max: usize) -> String {
    let mut line = format!("{name:<16} {:<9} {}", status_word(s.status), types_of(s));
    if let Some(c) = count(s.min, s.max) {
        let _ = write!(line, ", {c}");
    }
    if let Some(d) = &s.default {
        let _ = write!(
            line,
            ", default {}",
            d.iter()
                .map(|l| l.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    if let Some(into) = &s.into {
        let _ = write!(line, ", one of {}", short_list(into, list_max.min(6)));
    }
    match (s.val_min, s.val_max) {
        (Some(a), Some(b)) => {
            let _ = write!(line, ", in [{}, {}]", bound(s, a), bound(s, b));
        }
        (Some(a), None) => {
            let _ = write!(line, ", >= {}", bound(s, a));
        }
        (None, Some(b)) => {
            let _ = write!(line, ", <= {}", bound(s, b));
        }
        _ => {}
    }
    line
}

/// A bound as the keyword's type reads it (`0` for an integer, `0.0` for a real).
fn bound(s: &SimpleKw, x: f64) -> String {
    if s.types.contains(&ValueType::Int) && !s.types.contains(&ValueType::Real) && x.fract() == 0.0
    {
        format!("{}", x as i64)
    } else {
        fmt_real(x)
    }
}

fn status_word(s: Status) -> &'static str {
    match s {
        Status::Mandatory => "mandatory",
        Status::Optional => "optional",
        Status::Defaulted => "default",
        Status::Hidden => "hidden",
    }
}

fn rule_line(r: &Rule) -> String {
    let what = match r.kind {
        RuleKind::ExactlyOne => "exactly one of",
        RuleKind::AtMostOne => "at most one of",
        RuleKind::AtLeastOne => "at least one of",
        RuleKind::AllTogether => "all or none of",
        RuleKind::OnlyFirstPresent => "if the first is given, none of the others:",
        RuleKind::IfFirstAllPresent => "if the first is given, all of the others:",
        RuleKind::NotEmpty => "at least one of",
    };
    format!("rule: {what} {}", r.args.join(", "))
}

/// How much `explain` prints.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// Every allowed value, however long the list (`--all`).
    pub all: bool,
}

impl Options {
    fn list_max(self, short: usize) -> usize {
        if self.all {
            usize::MAX
        } else {
            short
        }
    }
}

fn tree(
    out: &mut String,
    entries: &[Entry],
    rules: &[Rule],
    indent: usize,
    depth: usize,
    list_max: usize,
) {
    let pad = " ".repeat(indent);
    for r in rules {
        let _ = writeln!(out, "{pad}{}", rule_line(r));
    }
    for e in entries {
        match &e.node {
            Node::Simple(s) if s.status == Status::Hidden => {}
            Node::Simple(s) => {
                let _ = writeln!(out, "{pad}{}", simple_line(e.name, s, list_max));
            }
            Node::Factor(f) => {
                let occ = match (f.min, f.max) {
                    (_, Max::Count(1)) => "one _F(...)".to_string(),
                    (_, Max::Unbounded(_)) => "one or more _F(...)".to_string(),
                    (_, Max::Count(n)) => format!("up to {n} _F(...)"),
                };
                let _ = writeln!(
                    out,
                    "{pad}{:<16} {:<9} factor, {occ}",
                    e.name,
                    status_word(f.status)
                );
                if depth > 0 {
                    tree(out, f.keywords, f.rules, indent + 4, depth - 1, list_max);
                } else {
                    let _ = writeln!(out, "{pad}    … (aster explain …/{})", e.name);
                }
            }
            Node::Block(b) => {
                let _ = writeln!(out, "{pad}when {}:", plain_condition(b.condition));
                tree(out, b.keywords, b.rules, indent + 4, depth, list_max);
            }
        }
    }
}

fn header(c: &Command) -> String {
    let produces = match &c.produces {
        Produces::Nothing => "nothing (a procedure)".to_string(),
        Produces::Type(t) => t.to_string(),
        Produces::Computed(f) => format!("a type computed from the keywords ({f})"),
    };
    let reuse = match &c.reentrant {
        Reentrant::No => "not accepted".to_string(),
        Reentrant::Unstated => "accepted".to_string(),
        Reentrant::Yes {
            mandatory,
            keywords,
        } => format!(
            "{} ({})",
            if *mandatory { "mandatory" } else { "optional" },
            if keywords.is_empty() {
                "-".into()
            } else {
                keywords.join(", ")
            }
        ),
    };
    format!(
        "{} ({:?})\n  produces: {produces}\n  reuse=: {reuse}\n",
        c.name, c.kind
    )
}

/// A block condition of code_aster's catalog in plain words:
/// `equal_to("FORMULATION", 'CONTINUE')` reads `FORMULATION='CONTINUE'`,
/// `not exists("X")` reads `X is not given`, `is_in("K", ('A','B'))` reads
/// `K one of 'A', 'B'`. What is not one of these calls stays as written.
pub fn plain_condition(cond: &str) -> String {
    let mut out = String::with_capacity(cond.len());
    let spaced = cond.replace(")or(", ") or (").replace(")and(", ") and (");
    let mut rest = spaced.trim();
    while !rest.is_empty() {
        let boundary = !out.ends_with(|c: char| c.is_alphanumeric() || c == '_');
        let (negated, after_not) = match rest.strip_prefix("not ") {
            Some(r) if boundary => (true, r.trim_start()),
            _ => (false, rest),
        };
        if boundary {
            if let Some((text, len)) = plain_call(after_not, negated) {
                out.push_str(&text);
                rest = &after_not[len..];
                continue;
            }
        }
        let mut chars = rest.chars();
        if let Some(c) = chars.next() {
            out.push(c);
        }
        rest = chars.as_str();
    }
    // Doubled spaces and padded parentheses as the catalog writes them.
    out.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace("( ", "(")
        .replace(" )", ")")
}

/// `equal_to(...)`, `exists(...)`, `is_in(...)` at the start of `s`: the
/// plain text and the length of the call.
fn plain_call(s: &str, negated: bool) -> Option<(String, usize)> {
    let name_end = s.find('(')?;
    let name = s[..name_end].trim_end();
    if !["equal_to", "exists", "is_in"].contains(&name) {
        return None;
    }
    let (args, len) = call_args(&s[name_end..])?;
    let key = unquote(args.first()?);
    let text = match (name, args.len()) {
        ("exists", 1) => format!(
            "{key} {}",
            if negated { "is not given" } else { "is given" }
        ),
        ("equal_to", 2) if !args[1].trim().starts_with('(') => {
            format!(
                "{key}{}{}",
                if negated { "≠" } else { "=" },
                value(&args[1])
            )
        }
        ("is_in" | "equal_to", 2) => {
            let inner = args[1].trim().trim_start_matches('(').trim_end_matches(')');
            let values: Vec<String> = inner
                .split(',')
                .map(str::trim)
                .filter(|v| !v.is_empty())
                .map(value)
                .collect();
            format!(
                "{key} {}one of {}",
                if negated { "not " } else { "" },
                values.join(", ")
            )
        }
        _ => return None,
    };
    Some((text, name_end + len))
}

/// The comma-separated arguments of the call whose `(` starts `s`, and the
/// length up to its `)`.
fn call_args(s: &str) -> Option<(Vec<String>, usize)> {
    let mut depth = 0i32;
    let mut quote: Option<char> = None;
    let mut args = Vec::new();
    let mut cur = String::new();
    for (i, c) in s.char_indices() {
        match quote {
            Some(q) => {
                cur.push(c);
                if c == q {
                    quote = None;
                }
            }
            None => match c {
                '\'' | '"' => {
                    quote = Some(c);
                    cur.push(c);
                }
                '(' => {
                    depth += 1;
                    if depth > 1 {
                        cur.push(c);
                    }
                }
                ')' => {
                    depth -= 1;
                    if depth == 0 {
                        args.push(cur.trim().to_string());
                        return Some((args, i + 1));
                    }
                    cur.push(c);
                }
                ',' if depth == 1 => args.push(std::mem::take(&mut cur).trim().to_string()),
                _ => cur.push(c),
            },
        }
    }
    None
}

fn unquote(s: &str) -> &str {
    s.trim().trim_matches(|c| c == '"' || c == '\'')
}

/// A value as a user writes it: strings in single quotes.
fn value(s: &str) -> String {
    let t = s.trim();
    if t.starts_with(['"', '\'']) {
        format!("'{}'", unquote(t))
    } else {
        t.to_string()
    }
}

/// The conditions of nested blocks, all required: one with an `or` is
/// parenthesised so that the reading stays unambiguous.
fn join_conditions(conds: &[String]) -> String {
    if conds.len() == 1 {
        return conds[0].clone();
    }
    conds
        .iter()
        .map(|c| {
            if c.contains(" or ") && !(c.starts_with('(') && c.ends_with(')')) {
                format!("({c})")
            } else {
                c.clone()
            }
        })
        .collect::<Vec<_>>()
        .join(", and ")
}

/// All the places a keyword path (`ZONE/GROUP_MA_ESCL`) reaches, with the
/// block conditions on the way.
fn lookup<'a>(
    entries: &'a [Entry],
    path: &[&str],
    conds: Vec<String>,
    out: &mut Vec<(Vec<String>, &'a Entry)>,
) {
    let Some((first, rest)) = path.split_first() else {
        return;
    };
    for e in entries {
        match &e.node {
            Node::Block(b) => {
                let mut c = conds.clone();
                c.push(plain_condition(b.condition));
                lookup(b.keywords, path, c, out);
            }
            _ if e.name == *first => {
                if rest.is_empty() {
                    out.push((conds.clone(), e));
                } else if let Node::Factor(f) = &e.node {
                    lookup(f.keywords, rest, conds.clone(), out);
                }
            }
            _ => {}
        }
    }
}

/// Explains `CMD` or `CMD/KEYWORD[/KEYWORD...]`; `Err` says what is unknown,
/// with suggestions.
pub fn explain(path: &str) -> Result<String, String> {
    explain_in(catalog(), path, Options::default())
}

/// Whether `aster explain PATH` explains something (a command, or keywords
/// under it), without writing the explanation: cheap enough for every
/// diagnostic to ask.
pub fn resolves(path: &str) -> bool {
    let parts = path_parts(path);
    let Some((cname, kws)) = parts.split_first() else {
        return false;
    };
    let Some(cmd) = catalog().command(cname) else {
        return false;
    };
    if kws.is_empty() {
        return true;
    }
    let kref: Vec<&str> = kws.iter().map(String::as_str).collect();
    let mut found = Vec::new();
    lookup(cmd.keywords, &kref, Vec::new(), &mut found);
    !found.is_empty()
}

/// [`explain`] with [`Options`].
pub fn explain_with(path: &str, options: Options) -> Result<String, String> {
    explain_in(catalog(), path, options)
}

/// A path as a diagnostic prints it (`` `DEFI_CONTACT/ZONE[1]/COEF_CONT` ``)
/// or as a user types it: quotes and occurrence indices dropped.
fn path_parts(path: &str) -> Vec<String> {
    path.trim()
        .trim_matches('`')
        .split('/')
        .map(|p| match p.find('[') {
            Some(i) if p.ends_with(']') => p[..i].trim().to_uppercase(),
            _ => p.trim().to_uppercase(),
        })
        .filter(|p| !p.is_empty())
        .collect()
}

/// Every place a keyword name appears in a command, at any depth: its path
/// and the conditions of the blocks on the way.
fn find_anywhere(
    entries: &[Entry],
    name: &str,
    prefix: &str,
    conds: &[String],
    out: &mut Vec<(String, Vec<String>)>,
) {
    for e in entries {
        match &e.node {
            Node::Block(b) => {
                let mut c = conds.to_vec();
                c.push(plain_condition(b.condition));
                find_anywhere(b.keywords, name, prefix, &c, out);
            }
            node => {
                let path = format!("{prefix}/{}", e.name);
                if e.name == name {
                    out.push((path.clone(), conds.to_vec()));
                }
                if let Node::Factor(f) = node {
                    find_anywhere(f.keywords, name, &path, conds, out);
                }
            }
        }
    }
}

fn suggest(word: &str, names: &[&str]) -> String {
    let mut best: Vec<(usize, &str)> = names
        .iter()
        .map(|n| (levenshtein(word, n), *n))
        .filter(|(d, _)| *d <= (word.len() / 3).max(2))
        .collect();
    best.sort();
    best.dedup();
    if best.is_empty() {
        String::new()
    } else {
        format!(
            "; did you mean {}?",
            best.iter()
                .take(3)
                .map(|(_, n)| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

fn levenshtein(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1];
        for (j, cb) in b.iter().enumerate() {
            cur.push(
                (prev[j] + usize::from(ca != *cb))
                    .min(prev[j + 1] + 1)
                    .min(cur[j] + 1),
            );
        }
        prev = cur;
    }
    prev[b.len()]
}

pub fn explain_in(cat: &Catalog, path: &str, options: Options) -> Result<String, String> {
    let parts = path_parts(path);
    let Some((cname, kws)) = parts.split_first() else {
        return Err("give a command, e.g. `aster explain DEFI_CONTACT`".into());
    };
    let upper = cname.to_uppercase();
    let Some(cmd) = cat.command(&upper) else {
        let names: Vec<&str> = cat.names().collect();
        return Err(format!(
            "unknown command `{cname}`{}",
            suggest(&upper, &names)
        ));
    };
    let mut out = header(cmd);
    if kws.is_empty() {
        out.push('\n');
        tree(&mut out, cmd.keywords, cmd.rules, 2, 1, options.list_max(6));
        return Ok(out);
    }
    let kws: Vec<String> = kws.iter().map(|k| k.to_uppercase()).collect();
    let kref: Vec<&str> = kws.iter().map(|s| s.as_str()).collect();
    let mut found = Vec::new();
    lookup(cmd.keywords, &kref, Vec::new(), &mut found);
    if found.is_empty() {
        // Suggest among the keywords of the deepest level that exists.
        let mut names: Vec<&str> = Vec::new();
        if kref.len() == 1 {
            names = names_in(cmd.keywords);
        } else {
            let mut parents = Vec::new();
            lookup(
                cmd.keywords,
                &kref[..kref.len() - 1],
                Vec::new(),
                &mut parents,
            );
            for (_, p) in parents {
                if let Node::Factor(f) = &p.node {
                    for n in names_in(f.keywords) {
                        if !names.contains(&n) {
                            names.push(n);
                        }
                    }
                }
            }
        }
        let last = kref.last().copied().unwrap_or("");
        let mut elsewhere = Vec::new();
        find_anywhere(cmd.keywords, last, cmd.name, &[], &mut elsewhere);
        if !elsewhere.is_empty() {
            let mut paths: Vec<&str> = elsewhere.iter().map(|(p, _)| p.as_str()).collect();
            paths.dedup();
            let places: Vec<String> = paths
                .iter()
                .map(|p| {
                    let conds: Vec<&Vec<String>> = elsewhere
                        .iter()
                        .filter(|(q, _)| q == p)
                        .map(|(_, c)| c)
                        .collect();
                    match conds.as_slice() {
                        [c] if c.is_empty() => format!("`{p}`"),
                        [c] => format!("`{p}` (when {})", join_conditions(c)),
                        _ => format!(
                            "`{p}` (under {} conditions: aster explain {p})",
                            conds.len()
                        ),
                    }
                })
                .collect();
            return Err(format!(
                "{} has no keyword `{}` there; {last} exists as {}",
                cmd.name,
                kws.join("/"),
                places.join(" and as ")
            ));
        }
        return Err(format!(
            "{} has no keyword `{}`{}",
            cmd.name,
            kws.join("/"),
            suggest(last, &names)
        ));
    }
    for (conds, e) in found {
        let _ = writeln!(out, "\n{}/{}", cmd.name, kws.join("/"));
        if conds.is_empty() {
            let _ = writeln!(out, "  applies: always");
        } else {
            let _ = writeln!(out, "  applies when: {}", join_conditions(&conds));
        }
        match &e.node {
            Node::Simple(s) => {
                let _ = writeln!(out, "  status: {}", s.status.describe());
                let _ = writeln!(
                    out,
                    "  type: {}",
                    s.types
                        .iter()
                        .map(|t| t.describe())
                        .collect::<Vec<_>>()
                        .join(" or ")
                );
                let _ = writeln!(out, "  values: {} to {}", s.min, s.max.describe());
                if let Some(d) = &s.default {
                    let _ = writeln!(
                        out,
                        "  default: {}",
                        d.iter()
                            .map(|l| l.to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    );
                }
                if let Some(into) = &s.into {
                    let _ = writeln!(out, "  allowed: {}", short_list(into, options.list_max(40)));
                }
                if let Some(a) = s.val_min {
                    let _ = writeln!(out, "  minimum: {}", bound(s, a));
                }
                if let Some(b) = s.val_max {
                    let _ = writeln!(out, "  maximum: {}", bound(s, b));
                }
            }
            Node::Factor(f) => {
                let _ = writeln!(out, "  status: {}", f.status.describe());
                let _ = writeln!(out, "  occurrences: {} to {}", f.min, f.max.describe());
                tree(&mut out, f.keywords, f.rules, 2, 2, options.list_max(6));
            }
            Node::Block(_) => {}
        }
    }
    Ok(out)
}
