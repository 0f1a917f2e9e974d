//! Machine-readable forms of `aster check`'s diagnostics, all built from the
//! one [`Diagnostic`] type: JSON Lines (one object per file), SARIF 2.1.0
//! (one log for every file), and GitHub Actions workflow commands.
//!
//! Every diagnostic carries its stable code (`E-unknown-keyword`,
//! `U-unsupported`, `W-legacy`: level letter and kind), its level (`error`,
//! `unsupported`, `warning`), the file as given on the command line, the
//! 1-based line and column of its start and end, the message, its notes and
//! the suggestion (`help:` note) when there is one. docs/check.md documents
//! the schema.

use aster_eval::{DiagKind, Diagnostic, Level};
use aster_syntax::CodeMap;
use serde::Serialize;
use serde_json::{json, Value};

/// The version of the JSON object `--format json` prints per file.
pub const SCHEMA_VERSION: u32 = 1;

/// One diagnostic with its position resolved.
#[derive(Clone, Debug, Serialize)]
pub struct Located {
    pub code: String,
    pub level: Level,
    pub kind: &'static str,
    pub file: String,
    pub line: usize,
    pub column: usize,
    pub end_line: usize,
    pub end_column: usize,
    pub message: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub suggestion: Option<String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

impl Located {
    pub fn new(d: &Diagnostic, map: &CodeMap, file: &str) -> Located {
        let start = map.line_col(d.span.start as usize);
        let end = map.line_col(d.span.end.max(d.span.start) as usize);
        let (end_line, end_column) = if (end.line, end.column) > (start.line, start.column) {
            (end.line, end.column)
        } else {
            (start.line, start.column + 1)
        };
        let suggestion = d
            .notes
            .iter()
            .find_map(|n| n.strip_prefix("help: "))
            .map(str::to_string);
        Located {
            code: d.code(),
            level: d.level(),
            kind: d.kind.slug(),
            file: file.to_string(),
            line: start.line,
            column: start.column,
            end_line,
            end_column,
            message: d.message.clone(),
            suggestion,
            notes: d.notes_with_explain(),
        }
    }
}

/// What one file amounts to: `clean` (warnings allowed), `unsupported`
/// (nothing wrong was found, but aster cannot follow the whole file) or
/// `error`.
pub fn status(diags: &[Located]) -> &'static str {
    if diags.iter().any(|d| d.level == Level::Error) {
        "error"
    } else if diags.iter().any(|d| d.level == Level::Unsupported) {
        "unsupported"
    } else {
        "clean"
    }
}

/// The JSON Lines object of one file.
pub fn json_line(path: &str, diags: &[Located]) -> String {
    let v = json!({
        "schema_version": SCHEMA_VERSION,
        "path": path,
        "status": status(diags),
        "diagnostics": diags,
    });
    v.to_string()
}

/// Escapes the message of a workflow command (`%`, CR, LF).
fn gh_data(s: &str) -> String {
    s.replace('%', "%25")
        .replace('\r', "%0D")
        .replace('\n', "%0A")
}

/// Escapes a property of a workflow command (also `:` and `,`).
fn gh_property(s: &str) -> String {
    gh_data(s).replace(':', "%3A").replace(',', "%2C")
}

/// One GitHub Actions workflow command (`::error file=…::message`):
/// errors as `error`, warnings as `warning`, unsupported as `notice`.
pub fn github_line(d: &Located) -> String {
    let cmd = match d.level {
        Level::Error => "error",
        Level::Warning => "warning",
        Level::Unsupported => "notice",
    };
    let mut message = d.message.clone();
    for n in &d.notes {
        message.push('\n');
        message.push_str(n);
    }
    format!(
        "::{cmd} file={},line={},col={},endLine={},endColumn={},title={}::{}",
        gh_property(&d.file),
        d.line,
        d.column,
        d.end_line,
        d.end_column,
        gh_property(&d.code),
        gh_data(&message)
    )
}

/// The SARIF level of a diagnostic: unsupported constructs are `note`s (the
/// file is not wrong).
fn sarif_level(l: Level) -> &'static str {
    match l {
        Level::Error => "error",
        Level::Warning => "warning",
        Level::Unsupported => "note",
    }
}

/// The rule of each code a log may use: every kind at each level it
/// occurs with.
fn sarif_rules() -> Vec<(String, Value)> {
    let mut rules = Vec::new();
    for kind in DiagKind::ALL {
        let levels: &[Level] = if kind.is_not_supported() {
            &[Level::Unsupported]
        } else if kind == DiagKind::Legacy {
            &[Level::Warning, Level::Error]
        } else {
            &[Level::Error, Level::Warning]
        };
        for &level in levels {
            let id = format!("{}-{}", level.letter(), kind.slug());
            rules.push((
                id.clone(),
                json!({
                    "id": id,
                    "name": kind.slug(),
                    "shortDescription": { "text": kind.label() },
                    "defaultConfiguration": { "level": sarif_level(level) },
                }),
            ));
        }
    }
    rules
}

/// A SARIF 2.1.0 log of every file's diagnostics.
pub fn sarif(files: &[(String, Vec<Located>)]) -> Value {
    let rules = sarif_rules();
    let rule_index = |code: &str| rules.iter().position(|(id, _)| id == code);
    let mut results = Vec::new();
    for (_, diags) in files {
        for d in diags {
            let mut r = json!({
                "ruleId": d.code,
                "level": sarif_level(d.level),
                "message": { "text": d.message },
                "locations": [{
                    "physicalLocation": {
                        "artifactLocation": { "uri": uri(&d.file) },
                        "region": {
                            "startLine": d.line,
                            "startColumn": d.column,
                            "endLine": d.end_line,
                            "endColumn": d.end_column,
                        }
                    }
                }],
                "properties": { "aster_level": d.level.name() },
            });
            if let Some(i) = rule_index(&d.code) {
                r["ruleIndex"] = json!(i);
            }
            if let Some(s) = &d.suggestion {
                r["properties"]["suggestion"] = json!(s);
            }
            if !d.notes.is_empty() {
                r["properties"]["notes"] = json!(d.notes);
            }
            results.push(r);
        }
    }
    let artifacts: Vec<Value> = files
        .iter()
        .map(|(p, _)| json!({ "location": { "uri": uri(p) } }))
        .collect();
    json!({
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [{
            "tool": {
                "driver": {
                    "name": "aster",
                    "semanticVersion": env!("CARGO_PKG_VERSION"),
                    "rules": rules.into_iter().map(|(_, r)| r).collect::<Vec<_>>(),
                }
            },
            "artifacts": artifacts,
            "results": results,
            "columnKind": "unicodeCodePoints",
        }]
    })
}

/// A file path as a relative URI reference: `/` separators, characters
/// outside RFC 3986's unreserved set and `/` percent-encoded.
fn uri(path: &str) -> String {
    let mut out = String::new();
    for b in path.replace('\\', "/").bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn github_escapes_properties_and_data() {
        let d = Located {
            code: "E-rule".into(),
            level: Level::Error,
            kind: "rule",
            file: "a,b:c.comm".into(),
            line: 3,
            column: 5,
            end_line: 3,
            end_column: 9,
            message: "100% wrong\nreally".into(),
            suggestion: None,
            notes: vec![],
        };
        assert_eq!(
            github_line(&d),
            "::error file=a%2Cb%3Ac.comm,line=3,col=5,endLine=3,endColumn=9,title=E-rule::100%25 wrong%0Areally"
        );
    }

    #[test]
    fn uris_are_percent_encoded() {
        assert_eq!(uri("dir/my case.comm"), "dir/my%20case.comm");
        assert_eq!(uri("a\\b.comm"), "a/b.comm");
    }
}
