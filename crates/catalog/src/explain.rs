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

fn simple_line(name: &str, s: &SimpleKw) -> String {
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
        let _ = write!(line, ", one of {}", short_list(into, 6));
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

fn tree(out: &mut String, entries: &[Entry], rules: &[Rule], indent: usize, depth: usize) {
    let pad = " ".repeat(indent);
    for r in rules {
        let _ = writeln!(out, "{pad}{}", rule_line(r));
    }
    for e in entries {
        match &e.node {
            Node::Simple(s) if s.status == Status::Hidden => {}
            Node::Simple(s) => {
                let _ = writeln!(out, "{pad}{}", simple_line(e.name, s));
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
                    tree(out, f.keywords, f.rules, indent + 4, depth - 1);
                } else {
                    let _ = writeln!(out, "{pad}    … (aster explain …/{})", e.name);
                }
            }
            Node::Block(b) => {
                let _ = writeln!(out, "{pad}when {}:", b.condition);
                tree(out, b.keywords, b.rules, indent + 4, depth);
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
                c.push(b.condition.to_string());
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
    explain_in(catalog(), path)
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

pub fn explain_in(cat: &Catalog, path: &str) -> Result<String, String> {
    let parts: Vec<&str> = path.split('/').filter(|p| !p.is_empty()).collect();
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
        tree(&mut out, cmd.keywords, cmd.rules, 2, 1);
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
        return Err(format!(
            "{} has no keyword `{}`{}",
            cmd.name,
            kws.join("/"),
            suggest(kref.last().copied().unwrap_or(""), &names)
        ));
    }
    for (conds, e) in found {
        let _ = writeln!(out, "\n{}/{}", cmd.name, kws.join("/"));
        if conds.is_empty() {
            let _ = writeln!(out, "  applies: always");
        } else {
            let _ = writeln!(out, "  applies when: {}", conds.join("  and then  "));
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
                    let _ = writeln!(out, "  allowed: {}", short_list(into, 40));
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
                tree(&mut out, f.keywords, f.rules, 2, 2);
            }
            Node::Block(_) => {}
        }
    }
    Ok(out)
}
