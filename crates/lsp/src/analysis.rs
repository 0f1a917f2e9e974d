//! What the server knows of one document after checking it: the
//! diagnostics of `aster check` (the same parser, evaluator and catalog
//! validation) and, as information, what `aster run` would refuse (the
//! support table of `aster-run`, the check its static pass makes); the
//! concepts the evaluated program made, with their types; and an index of
//! names (definitions, uses) and of the command sequence (the outline),
//! read from the tolerant token stream so that navigation keeps working
//! while the file does not parse.

use crate::lex::{self, Kind, Token};
use aster_eval::{
    CheckSink, CommandCall, CommandOutput, CommandSink, ConceptRef, DiagKind, Diagnostic,
    ExecError, HostValue, Severity,
};
use aster_syntax::{CodeMap, Span};

/// How serious a finding is, in LSP terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    Error,
    Warning,
    /// `aster run` does not execute this (the file is valid code_aster).
    Information,
}

/// One finding, located in the document.
#[derive(Clone, Debug)]
pub struct Finding {
    pub level: Level,
    /// `unknown_keyword`, `not_supported_by_run`…
    pub code: String,
    pub start: usize,
    pub end: usize,
    pub message: String,
    /// `help: …`, `note: …` lines of the checker.
    pub notes: Vec<String>,
}

/// A concept made by a command of the evaluated program.
#[derive(Clone, Debug, PartialEq)]
pub struct Concept {
    pub name: String,
    pub typ: String,
    pub command: String,
    /// The call that made it.
    pub call: Span,
}

/// A name in the text: where it is bound or used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Occurrence {
    pub name: String,
    pub start: usize,
    pub end: usize,
    pub definition: bool,
}

/// A command call of the outline, with its factor keywords as children.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OutlineItem {
    /// `mesh = LIRE_MAILLAGE`, `IMPR_TABLE`, or a factor keyword `ZONE`.
    pub name: String,
    /// The command or keyword.
    pub detail: String,
    pub start: usize,
    pub end: usize,
    /// The name to select (the result's name, else the command's).
    pub sel_start: usize,
    pub sel_end: usize,
    pub children: Vec<OutlineItem>,
}

/// A `LIRE_MAILLAGE` of the program: the unit and format it reads.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshRead {
    pub result: Option<String>,
    pub unit: i64,
    pub format: String,
}

#[derive(Clone, Debug, Default)]
pub struct Analysis {
    pub findings: Vec<Finding>,
    pub concepts: Vec<Concept>,
    pub occurrences: Vec<Occurrence>,
    pub outline: Vec<OutlineItem>,
    pub meshes: Vec<MeshRead>,
}

impl Analysis {
    /// The type of the concept `name` as last made before `offset` (or
    /// anywhere, when none is made before).
    pub fn concept_before(&self, name: &str, offset: usize) -> Option<&Concept> {
        let mut found = None;
        for c in self.concepts.iter().filter(|c| c.name == name) {
            if (c.call.start as usize) <= offset || found.is_none() {
                found = Some(c);
            }
        }
        found
    }

    /// The definition of `name` that a use at `offset` refers to: the last
    /// one before it, else the first.
    pub fn definition(&self, name: &str, offset: usize) -> Option<&Occurrence> {
        let defs = self
            .occurrences
            .iter()
            .filter(|o| o.definition && o.name == name);
        let mut first = None;
        let mut before = None;
        for d in defs {
            first.get_or_insert(d);
            if d.start <= offset {
                before = Some(d);
            }
        }
        before.or(first)
    }

    /// The occurrence under `offset`.
    pub fn occurrence_at(&self, offset: usize) -> Option<&Occurrence> {
        self.occurrences
            .iter()
            .find(|o| o.start <= offset && offset <= o.end)
    }
}

/// The sink of the analysis: types each result as `aster check` does and
/// asks `aster run`'s static pass whether the call would run.
struct Sink {
    check: CheckSink,
    run: aster_run::preflight::CallRefusals,
    refusals: Vec<(String, Span)>,
}

impl CommandSink for Sink {
    fn execute(&mut self, call: &CommandCall) -> Result<CommandOutput, ExecError> {
        self.refusals.extend(self.run.call(call));
        self.check.execute(call)
    }
    fn method(
        &mut self,
        c: &ConceptRef,
        name: &str,
        args: &[HostValue],
    ) -> Result<HostValue, ExecError> {
        self.check.method(c, name, args)
    }
    fn make(
        &mut self,
        c: &ConceptRef,
        name: &str,
        args: &[(&'static str, HostValue)],
        result: &ConceptRef,
    ) -> Result<(), ExecError> {
        self.check.make(c, name, args, result)
    }
    fn index(&mut self, c: &ConceptRef, key: &[HostValue]) -> Result<HostValue, ExecError> {
        self.check.index(c, key)
    }
    fn print(&mut self, line: &str) {
        self.check.print(line)
    }
}

fn code_of(kind: DiagKind) -> &'static str {
    match kind {
        DiagKind::Syntax => "syntax",
        DiagKind::NotSupported | DiagKind::RunTimeValue => "not_supported",
        DiagKind::Python => "python",
        DiagKind::UnknownCommand => "unknown_command",
        DiagKind::UnknownKeyword => "unknown_keyword",
        DiagKind::KeywordNotApplicable => "keyword_not_applicable",
        DiagKind::MissingKeyword => "missing_keyword",
        DiagKind::WrongType => "wrong_type",
        DiagKind::NotInto => "value_not_allowed",
        DiagKind::Count => "count",
        DiagKind::OutOfRange => "out_of_range",
        DiagKind::Rule => "rule",
        DiagKind::Reuse => "reuse",
        DiagKind::Legacy => "legacy",
        DiagKind::Exec => "exec",
    }
}

fn finding(d: Diagnostic) -> Finding {
    Finding {
        level: match d.severity {
            Severity::Error => Level::Error,
            Severity::Warning => Level::Warning,
        },
        code: code_of(d.kind).to_string(),
        start: d.span.start as usize,
        end: d.span.end.max(d.span.start) as usize,
        message: d.message,
        notes: d.notes,
    }
}

/// Checks a document's text: parse, evaluate (no command executed),
/// validate, and ask `aster run`'s support table about each call.
pub fn analyse(name: &str, text: &str) -> Analysis {
    let map = CodeMap::new(name, text);
    let tokens = lex::tokens(text);
    let (occurrences, outline) = index(text, &tokens);
    let mut out = Analysis {
        occurrences,
        outline,
        ..Analysis::default()
    };
    let module = match aster_syntax::parse_module(map.source()) {
        Ok(m) => m,
        Err(e) => {
            out.findings.push(finding(Diagnostic::error(
                DiagKind::Syntax,
                e.span,
                e.message,
            )));
            return out;
        }
    };
    let mut sink = Sink {
        check: CheckSink {
            calls: Vec::new(),
            record: true,
        },
        run: Default::default(),
        refusals: Vec::new(),
    };
    let diags = match aster_eval::run_program(
        &map,
        &module,
        &mut sink,
        aster_eval::RunOptions { keep_going: true },
    ) {
        Ok(s) => s.warnings.0,
        Err(d) => d.0,
    };
    out.findings.extend(diags.into_iter().map(finding));
    for (what, span) in sink.refusals {
        out.findings.push(Finding {
            level: Level::Information,
            code: "not_supported_by_run".into(),
            start: span.start as usize,
            end: span.end as usize,
            message: format!("not supported by aster run: {what}"),
            notes: Vec::new(),
        });
    }
    for call in &sink.check.calls {
        if let Some(r) = &call.result {
            out.concepts.push(Concept {
                name: r.name.clone(),
                typ: r.typ.clone(),
                command: call.command.clone(),
                call: call.span,
            });
        }
        if call.command == "LIRE_MAILLAGE" {
            out.meshes.push(MeshRead {
                result: call.result.as_ref().map(|r| r.name.clone()),
                unit: call
                    .keywords
                    .first("UNITE")
                    .and_then(|s| s.as_i64())
                    .unwrap_or(20),
                format: call.keywords.str("FORMAT").unwrap_or("MED").to_string(),
            });
        }
    }
    out
}

const PY_KEYWORDS: &[&str] = &[
    "False", "None", "True", "and", "as", "assert", "break", "class", "continue", "def", "del",
    "elif", "else", "except", "finally", "for", "from", "global", "if", "import", "in", "is",
    "lambda", "nonlocal", "not", "or", "pass", "print", "raise", "return", "try", "while", "with",
    "yield", "_F", "reuse",
];

/// Names bound and used, and the outline, from the token stream.
pub fn index(src: &str, tokens: &[Token]) -> (Vec<Occurrence>, Vec<OutlineItem>) {
    let mut occ: Vec<Occurrence> = Vec::new();
    let mut outline: Vec<OutlineItem> = Vec::new();
    // Per open bracket: is it a call (keyword arguments are not names).
    let mut stack: Vec<bool> = Vec::new();
    let mut line_start = 0usize;
    // The outline entry being read: its index in `outline` and the depth
    // of its call; a factor child and its depth.
    let mut open_cmd: Option<(usize, usize)> = None;
    let mut open_child: Option<(usize, usize)> = None;
    let cat = aster_catalog::catalog();
    let text = |t: &Token| t.text(src);
    for (i, t) in tokens.iter().enumerate() {
        let prev = i.checked_sub(1).map(|p| tokens[p]);
        let next = tokens.get(i + 1);
        match t.kind {
            Kind::Newline => line_start = i + 1,
            Kind::Open => {
                let call =
                    prev.is_some_and(|p| p.kind == Kind::Name) && src.as_bytes()[t.start] == b'(';
                stack.push(call);
                // A command call of the outline: the first call of a
                // statement at depth 0.
                if stack.len() == 1 && call && open_cmd.is_none() {
                    if let Some(p) = prev.filter(|p| cat.command(text(p)).is_some()) {
                        let head = &tokens[line_start..i - 1];
                        let result = match head {
                            [n, a] if n.kind == Kind::Name && a.kind == Kind::Assign => Some(*n),
                            _ => None,
                        };
                        let (name, sel) = match result {
                            Some(r) => (format!("{} = {}", text(&r), text(&p)), r),
                            None => (text(&p).to_string(), p),
                        };
                        if head.is_empty() || result.is_some() {
                            outline.push(OutlineItem {
                                name,
                                detail: text(&p).to_string(),
                                start: tokens[line_start].start,
                                end: src.len(),
                                sel_start: sel.start,
                                sel_end: sel.end,
                                children: Vec::new(),
                            });
                            open_cmd = Some((outline.len() - 1, 1));
                        }
                    }
                }
                // A factor keyword of the command being read: `KW=_F(` or `KW=(`.
                if let (Some((o, d)), None) = (open_cmd, open_child) {
                    let kw = match (i.checked_sub(3).map(|k| tokens[k]), prev) {
                        (Some(k), Some(f)) if stack.len() == d + 1 && text(&f) == "_F" => {
                            (tokens[i - 2].kind == Kind::Assign).then_some(k)
                        }
                        (_, Some(a))
                            if stack.len() == d + 1
                                && a.kind == Kind::Assign
                                && tokens.get(i + 1).is_some_and(|n| text(n) == "_F") =>
                        {
                            Some(tokens[i - 2])
                        }
                        _ => None,
                    };
                    if let Some(k) = kw.filter(|k| k.kind == Kind::Name) {
                        outline[o].children.push(OutlineItem {
                            name: text(&k).to_string(),
                            detail: "factor keyword".into(),
                            start: k.start,
                            end: src.len(),
                            sel_start: k.start,
                            sel_end: k.end,
                            children: Vec::new(),
                        });
                        open_child = Some((outline[o].children.len() - 1, stack.len()));
                    }
                }
            }
            Kind::Close => {
                if let (Some((o, _)), Some((c, d))) = (open_cmd, open_child) {
                    if stack.len() == d {
                        // `KW=(_F(…), _F(…))` ends at its last bracket.
                        outline[o].children[c].end = t.end;
                        open_child = None;
                    }
                }
                if let Some((o, d)) = open_cmd {
                    if stack.len() == d {
                        outline[o].end = t.end;
                        open_cmd = None;
                    }
                }
                stack.pop();
            }
            Kind::Name => {
                let name = text(t);
                if PY_KEYWORDS.contains(&name) || prev.is_some_and(|p| p.kind == Kind::Dot) {
                    continue;
                }
                let keyword_arg = stack.last() == Some(&true)
                    && next.is_some_and(|n| n.kind == Kind::Assign)
                    && prev.is_some_and(|p| matches!(p.kind, Kind::Open | Kind::Comma));
                if keyword_arg {
                    continue;
                }
                let definition = stack.is_empty()
                    && (prev.is_some_and(|p| matches!(text(&p), "for" | "def" | "class"))
                        || assigned(src, &tokens[line_start..], i - line_start));
                occ.push(Occurrence {
                    name: name.to_string(),
                    start: t.start,
                    end: t.end,
                    definition,
                });
            }
            Kind::Str { .. } => {
                // `CO('name')` makes concept `name`.
                let co = prev.is_some_and(|p| p.kind == Kind::Open)
                    && i >= 2
                    && text(&tokens[i - 2]) == "CO";
                if co {
                    let (s, e) = lex::str_content_range(src, t);
                    occ.push(Occurrence {
                        name: src[s..e].to_string(),
                        start: s,
                        end: e,
                        definition: true,
                    });
                }
            }
            _ => {}
        }
    }
    (occ, outline)
}

/// Whether the name at `line[k]` is a target of an assignment `a, b = …`
/// of its logical line: only names and commas before the first `=`.
fn assigned(src: &str, line: &[Token], k: usize) -> bool {
    let Some(eq) = line.iter().position(|t| t.kind == Kind::Assign) else {
        return false;
    };
    k < eq
        && line[..eq].iter().all(|t| {
            matches!(t.kind, Kind::Name | Kind::Comma) || (t.kind == Kind::Op && t.text(src) == "*")
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn definitions_uses_and_outline() {
        let src = "DEBUT()\nMA = LIRE_MAILLAGE(UNITE=20)\nMO = AFFE_MODELE(MAILLAGE=MA,\n  AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\nfor i in range(2):\n    x = i\nMACR(RESU=CO('R2'))\n";
        let toks = lex::tokens(src);
        let (occ, outline) = index(src, &toks);
        let defs: Vec<&str> = occ
            .iter()
            .filter(|o| o.definition)
            .map(|o| o.name.as_str())
            .collect();
        assert_eq!(defs, vec!["MA", "MO", "i", "x", "R2"]);
        let uses: Vec<&str> = occ
            .iter()
            .filter(|o| !o.definition)
            .map(|o| o.name.as_str())
            .collect();
        assert!(
            uses.contains(&"MA") && !uses.contains(&"MAILLAGE"),
            "{uses:?}"
        );
        let names: Vec<&str> = outline.iter().map(|o| o.name.as_str()).collect();
        assert_eq!(
            names,
            vec!["DEBUT", "MA = LIRE_MAILLAGE", "MO = AFFE_MODELE"]
        );
        assert_eq!(outline[2].children[0].name, "AFFE");
        assert_eq!(
            &src[outline[2].start..outline[2].end].chars().last(),
            &Some(')')
        );
    }
}
