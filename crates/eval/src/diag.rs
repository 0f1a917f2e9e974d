//! Diagnostics: errors and warnings with a source position, rendered as
//! `file:line:col: error: message` followed by the source line and a caret.

use aster_syntax::{CodeMap, Span};
use serde::Serialize;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Error,
    Warning,
}

/// What kind of problem (used to count corpus results by reason and to let
/// tools filter).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DiagKind {
    /// The file does not parse.
    Syntax,
    /// A Python construct, module or builtin outside the supported subset.
    NotSupported,
    /// A step that needs a value known only when the commands run (a
    /// condition on a table value…): checking cannot go past it, running
    /// can. Reported as "not supported" by `check`.
    RunTimeValue,
    /// A Python-level error (unknown name, wrong operand types...).
    Python,
    UnknownCommand,
    UnknownKeyword,
    /// A keyword of a block whose condition does not hold.
    KeywordNotApplicable,
    MissingKeyword,
    WrongType,
    NotInto,
    /// Too many / too few values or occurrences.
    Count,
    OutOfRange,
    Rule,
    /// `reuse=` misuse.
    Reuse,
    /// A legacy keyword mapped to its current form.
    Legacy,
    /// An error reported by the command sink while executing.
    Exec,
}

impl DiagKind {
    /// "not supported" (by the checker or the runner).
    pub fn is_not_supported(self) -> bool {
        matches!(self, DiagKind::NotSupported | DiagKind::RunTimeValue)
    }

    pub fn label(self) -> &'static str {
        match self {
            DiagKind::Syntax => "syntax error",
            DiagKind::NotSupported | DiagKind::RunTimeValue => "not supported",
            DiagKind::Python => "Python error",
            DiagKind::UnknownCommand => "unknown command",
            DiagKind::UnknownKeyword => "unknown keyword",
            DiagKind::KeywordNotApplicable => "keyword not applicable",
            DiagKind::MissingKeyword => "missing mandatory keyword",
            DiagKind::WrongType => "wrong type",
            DiagKind::NotInto => "value not allowed",
            DiagKind::Count => "wrong number of values",
            DiagKind::OutOfRange => "value out of range",
            DiagKind::Rule => "rule violated",
            DiagKind::Reuse => "reuse",
            DiagKind::Legacy => "legacy syntax",
            DiagKind::Exec => "execution error",
        }
    }

    /// The stable name of the kind, used in diagnostic codes
    /// (`E-unknown-keyword`): tools may filter on it, so a name never
    /// changes once published (docs/check.md lists them).
    pub fn slug(self) -> &'static str {
        match self {
            DiagKind::Syntax => "syntax",
            DiagKind::NotSupported => "unsupported",
            DiagKind::RunTimeValue => "run-time-value",
            DiagKind::Python => "python",
            DiagKind::UnknownCommand => "unknown-command",
            DiagKind::UnknownKeyword => "unknown-keyword",
            DiagKind::KeywordNotApplicable => "not-applicable",
            DiagKind::MissingKeyword => "missing-keyword",
            DiagKind::WrongType => "wrong-type",
            DiagKind::NotInto => "not-into",
            DiagKind::Count => "count",
            DiagKind::OutOfRange => "out-of-range",
            DiagKind::Rule => "rule",
            DiagKind::Reuse => "reuse",
            DiagKind::Legacy => "legacy",
            DiagKind::Exec => "exec",
        }
    }

    /// Every kind, in declaration order (the rules of a SARIF log).
    pub const ALL: [DiagKind; 16] = [
        DiagKind::Syntax,
        DiagKind::NotSupported,
        DiagKind::RunTimeValue,
        DiagKind::Python,
        DiagKind::UnknownCommand,
        DiagKind::UnknownKeyword,
        DiagKind::KeywordNotApplicable,
        DiagKind::MissingKeyword,
        DiagKind::WrongType,
        DiagKind::NotInto,
        DiagKind::Count,
        DiagKind::OutOfRange,
        DiagKind::Rule,
        DiagKind::Reuse,
        DiagKind::Legacy,
        DiagKind::Exec,
    ];
}

/// How a diagnostic counts for a user or a CI system: an error in the file,
/// a construct `aster` does not support (the file may well be valid
/// code_aster: numpy, a table value only known at run time…), or a warning.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    Error,
    Unsupported,
    Warning,
}

impl Level {
    /// The letter that starts a diagnostic code.
    pub fn letter(self) -> char {
        match self {
            Level::Error => 'E',
            Level::Unsupported => 'U',
            Level::Warning => 'W',
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Level::Error => "error",
            Level::Unsupported => "unsupported",
            Level::Warning => "warning",
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Diagnostic {
    pub severity: Severity,
    pub kind: DiagKind,
    #[serde(skip)]
    pub span: Span,
    pub message: String,
    /// Extra lines: `help: did you mean ...`, `note: ...`.
    pub notes: Vec<String>,
    /// An error a command raised that code_aster raises as this message id
    /// ([`crate::ExecError::id_message`]): what `except CA.AsterError`
    /// catches.
    #[serde(skip)]
    pub id_message: Option<&'static str>,
}

impl Diagnostic {
    pub fn error(kind: DiagKind, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            kind,
            span,
            message: message.into(),
            notes: Vec::new(),
            id_message: None,
        }
    }
    pub fn warning(kind: DiagKind, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(kind, span, message)
        }
    }
    pub fn note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// Error, unsupported or warning: an error of a "not supported" kind
    /// is [`Level::Unsupported`].
    pub fn level(&self) -> Level {
        match self.severity {
            Severity::Warning => Level::Warning,
            Severity::Error if self.kind.is_not_supported() => Level::Unsupported,
            Severity::Error => Level::Error,
        }
    }

    /// The stable code: the level's letter and the kind's slug
    /// (`E-unknown-keyword`, `U-unsupported`, `W-legacy`).
    pub fn code(&self) -> String {
        format!("{}-{}", self.level().letter(), self.kind.slug())
    }

    /// The `aster explain` path of what the diagnostic is about: the
    /// catalog path its message starts with (`` `DEFI_CONTACT/ZONE[1]/COEF_CONT` ``),
    /// a value written after it dropped (`` `DEBUT/CODE=_F(...)` ``); `None`
    /// when it names nothing `aster explain` knows (a Python name, a command
    /// code_aster 17 no longer has).
    pub fn explain_path(&self) -> Option<String> {
        let inner = self.message.strip_prefix('`')?;
        let quoted = &inner[..inner.find('`')?];
        let path = quoted.split('=').next()?.trim();
        let catalog_like =
            |c: char| c.is_ascii_uppercase() || c.is_ascii_digit() || "_/[]".contains(c);
        if path.is_empty() || !path.chars().all(catalog_like) {
            return None;
        }
        aster_catalog::explain::resolves(path).then(|| path.to_string())
    }

    /// The notes, ending with `see: aster explain PATH` where there is one.
    pub fn notes_with_explain(&self) -> Vec<String> {
        let mut notes = self.notes.clone();
        if let Some(path) = self.explain_path() {
            notes.push(format!("see: aster explain {path}"));
        }
        notes
    }

    /// The one-line form: `file:line:col: error: message`.
    pub fn headline(&self, map: &CodeMap) -> String {
        let sev = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        format!("{}: {sev}: {}", map.location(self.span), self.message)
    }

    /// The full form, with the source line, a caret under the span and notes.
    pub fn render(&self, map: &CodeMap) -> String {
        let mut out = self.headline(map);
        out.push('\n');
        let lc = map.line_col(self.span.start as usize);
        let end = map.line_col((self.span.end.max(self.span.start)) as usize);
        let text = map.line_text_at(lc);
        let num = lc.line.to_string();
        let pad = " ".repeat(num.len());
        let width = if end.line == lc.line && end.column > lc.column {
            end.column - lc.column
        } else {
            1
        };
        out.push_str(&format!("{pad} |\n{num} | {text}\n{pad} | "));
        out.push_str(&" ".repeat(lc.column - 1));
        out.push_str(
            &"^".repeat(
                width
                    .min(text.chars().count().saturating_sub(lc.column - 1))
                    .max(1),
            ),
        );
        out.push('\n');
        for n in self.notes_with_explain() {
            out.push_str(&format!("{pad} = {n}\n"));
        }
        out
    }
}

/// The diagnostics of one run, in source order of discovery.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Diagnostics(pub Vec<Diagnostic>);

impl Diagnostics {
    pub fn has_errors(&self) -> bool {
        self.0.iter().any(Diagnostic::is_error)
    }
    pub fn errors(&self) -> impl Iterator<Item = &Diagnostic> {
        self.0.iter().filter(|d| d.is_error())
    }
    pub fn render(&self, map: &CodeMap) -> String {
        self.0.iter().map(|d| d.render(map)).collect()
    }
}

/// The closest candidates to `word` by edit distance (did-you-mean).
pub fn suggest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Vec<&'a str> {
    let mut scored: Vec<(f64, &str)> = candidates
        .into_iter()
        .map(|c| (strsim::jaro_winkler(word, c), c))
        .filter(|(s, c)| *s >= 0.85 || strsim::levenshtein(word, c) <= (word.len() / 4).max(1))
        .collect();
    scored.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(b.1)));
    scored.dedup_by(|a, b| a.1 == b.1);
    scored.into_iter().take(3).map(|(_, c)| c).collect()
}

/// `did you mean `A`?` / `did you mean one of `A`, `B`?`, if any.
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<String> {
    let s = suggest(word, candidates);
    match s.as_slice() {
        [] => None,
        [one] => Some(format!("help: did you mean `{one}`?")),
        many => Some(format!(
            "help: did you mean one of {}?",
            many.iter()
                .map(|m| format!("`{m}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// A list of allowed names for a note, shortened when long.
pub fn allowed_list<T: std::fmt::Display>(items: &[T]) -> String {
    const MAX: usize = 12;
    let shown: Vec<String> = items.iter().take(MAX).map(|i| i.to_string()).collect();
    if items.len() > MAX {
        format!("{}, … ({} in all)", shown.join(", "), items.len())
    } else {
        shown.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn about(message: &str) -> Option<String> {
        Diagnostic::error(DiagKind::Rule, Span::new(0, 1), message).explain_path()
    }

    #[test]
    fn the_explain_path_is_the_catalog_path_the_message_names() {
        assert_eq!(
            about("`DEFI_CONTACT/ZONE[1]/COEF_CONT`: value 0 is not allowed").as_deref(),
            Some("DEFI_CONTACT/ZONE[1]/COEF_CONT")
        );
        assert_eq!(
            about("`AFFE_MODELE`: missing").as_deref(),
            Some("AFFE_MODELE")
        );
        // A value written after the keyword is dropped.
        assert_eq!(
            about("`DEBUT/CODE=_F(NOM=...)` is code_aster 11 syntax").as_deref(),
            Some("DEBUT/CODE")
        );
        // Nothing aster explain knows: a Python name, an unknown keyword,
        // a command code_aster 17 no longer has, no path at all.
        assert_eq!(about("name `YOUNG` is not defined"), None);
        assert_eq!(about("`YOUNG` is not defined"), None);
        assert_eq!(about("`AFFE_MODELE/NO_SUCH`: unknown"), None);
        assert_eq!(
            about("`MODE_ITER_SIMULT` is not a code_aster 17 command"),
            None
        );
        assert_eq!(about("unknown keyword"), None);
    }

    #[test]
    fn rendered_diagnostics_end_with_their_explain_path() {
        let map = CodeMap::new("a.comm", "X = AFFE_MODELE()\n");
        let d = Diagnostic::error(
            DiagKind::Rule,
            Span::new(4, 17),
            "`AFFE_MODELE`: missing MAILLAGE",
        )
        .note("help: give MAILLAGE");
        let text = d.render(&map);
        assert!(
            text.ends_with("  = help: give MAILLAGE\n  = see: aster explain AFFE_MODELE\n"),
            "{text}"
        );
        assert_eq!(
            d.notes_with_explain().last().map(String::as_str),
            Some("see: aster explain AFFE_MODELE")
        );
    }
}
