//! What `aster run` can execute, as data: for each command, the keywords its
//! implementation reads and the values it handles.
//!
//! This table is the one place that says what is supported. It is read twice:
//! by the static pass ([`crate::preflight`]) that validates a whole program
//! before anything runs — so that a case is refused before any solve, with
//! every unsupported keyword located at once — and by the executor before it
//! runs each command (the same check, so both always agree).
//!
//! Each command module declares its entry next to its implementation
//! (`pub(crate) const SUPPORT: Support`); `commands::COMMANDS` lists them
//! with the implementations. What the table cannot say — a combination of
//! keywords, a property of a concept or of the mesh — stays a run-time check
//! in the implementation, located the same way.

use aster_eval::{CommandCall, Keywords, KwValue};
use aster_syntax::Span;

/// The keywords and values one command's implementation handles.
#[derive(Clone, Copy, Debug)]
pub struct Support {
    /// Keyword paths the implementation reads: `"DDL_IMPO"`,
    /// `"DDL_IMPO/DX"`; `"X/*"` accepts every keyword under factor `X`,
    /// `"*"` every keyword of the command.
    /// Catalog defaults are never refused (the user did not write them).
    pub keywords: &'static [&'static str],
    /// Keywords whose values are restricted.
    pub values: &'static [Values],
    /// Keywords refused with an explanation (`"ZONE/SANS_NOEUD"`, "use
    /// SANS_GROUP_NO") rather than the plain "not supported yet".
    pub hints: &'static [(&'static str, &'static str)],
    /// `reuse=` is handled (the result continues or enriches a concept).
    pub reuse: bool,
    /// Static rules the lists cannot say (a keyword allowed only with some
    /// value of another): pushes its refusals.
    pub rules: Option<fn(&CommandCall, &mut Vec<Refusal>)>,
}

impl Support {
    /// An entry with keywords only.
    pub const fn keywords(keywords: &'static [&'static str]) -> Support {
        Support {
            keywords,
            values: &[],
            hints: &[],
            reuse: true,
            rules: None,
        }
    }
}

/// `a` followed by `b`, at compile time: a command that reads another's
/// keywords and values plus its own declares them as
/// `joined::<_, { A.len() + B.len() }>(A, B)`. `N` must be the total length
/// (checked when the constant is evaluated).
pub const fn joined<T: Copy, const N: usize>(a: &[T], b: &[T]) -> [T; N] {
    assert!(N > 0 && a.len() + b.len() == N);
    let mut out = [if a.is_empty() { b[0] } else { a[0] }; N];
    let mut i = 0;
    while i < a.len() {
        out[i] = a[i];
        i += 1;
    }
    while i < N {
        out[i] = b[i - a.len()];
        i += 1;
    }
    out
}

/// The values handled for one keyword path.
#[derive(Clone, Copy, Debug)]
pub struct Values {
    /// `"FORMAT"`, `"AFFE/MODELISATION"`.
    pub path: &'static str,
    pub allowed: &'static [&'static str],
    /// Said after the refused value, e.g. "(large strains or rotations):
    /// only small strains". Empty: the plain message.
    pub why: &'static str,
    /// List the allowed values in the message.
    pub list: bool,
}

impl Values {
    pub const fn new(path: &'static str, allowed: &'static [&'static str]) -> Values {
        Values {
            path,
            allowed,
            why: "",
            list: false,
        }
    }
    /// The message lists the supported values.
    pub const fn listed(path: &'static str, allowed: &'static [&'static str]) -> Values {
        Values {
            path,
            allowed,
            why: "",
            list: true,
        }
    }
    pub const fn why(mut self, why: &'static str) -> Values {
        self.why = why;
        self
    }
}

impl Refusal {
    /// A refusal of keyword `name` of `kw` (at the keyword when written,
    /// else at `fallback`).
    pub fn at(what: String, kw: &Keywords, name: &str, fallback: Span) -> Refusal {
        let span = kw.keyword(name).map(|k| k.span).unwrap_or(fallback);
        Refusal { what, span }
    }
}

/// One thing a command uses that `aster run` does not execute.
#[derive(Clone, Debug, PartialEq)]
pub struct Refusal {
    /// `COMMAND/KEYWORD='VALUE' (why)`: what follows "not supported yet: ".
    pub what: String,
    /// Where the keyword (or the command) is written.
    pub span: Span,
}

/// A command not executed whose refusal says why (what a user cannot get
/// from aster at all, rather than "not yet").
#[derive(Clone, Copy, Debug)]
pub struct CommandHint {
    pub command: &'static str,
    /// The keyword the refusal is located at, its value quoted (the
    /// command's own position when the call does not write it).
    pub keyword: Option<&'static str>,
    pub why: &'static str,
    /// The command runs a program outside code_aster (HOMARD, ECREVISSE):
    /// nothing else in the case matters until it is available, so the
    /// static pass reports it first, whatever its position.
    pub external: bool,
}

/// Commands not executed whose refusal says why.
pub const COMMAND_HINTS: &[CommandHint] = &[
    CommandHint {
        command: "MACR_ADAP_MAIL",
        keyword: Some("ADAPTATION"),
        why: "mesh adaptation runs the external HOMARD tool, which aster does not have",
        external: true,
    },
    CommandHint {
        command: "MACR_ECREVISSE",
        keyword: None,
        why: "couples code_aster's thermal and mechanical solves with the external ECREVISSE code (flow through the crack), which aster does not have",
        external: true,
    },
];

/// The hint of a command not executed, if it has one.
pub fn command_hint(cmd: &str) -> Option<&'static CommandHint> {
    COMMAND_HINTS.iter().find(|h| h.command == cmd)
}

/// Checks one call against its command's entry; `None` when the command
/// itself is not executed. Every refusal is returned, in keyword order.
pub fn check_call(support: Option<&Support>, call: &CommandCall) -> Vec<Refusal> {
    let cmd = call.command.as_str();
    let Some(support) = support else {
        let Some(hint) = command_hint(cmd) else {
            return vec![Refusal {
                what: cmd.to_string(),
                span: call.span,
            }];
        };
        let at = hint.keyword.and_then(|k| call.keywords.keyword(k));
        let what = match at.map(|k| (k, &k.value)) {
            Some((k, KwValue::Simple(v))) => {
                let values: Vec<String> = v
                    .iter()
                    .map(|s| match s.as_str() {
                        Some(t) => format!("'{t}'"),
                        None => format!("{s:?}"),
                    })
                    .collect();
                format!("{cmd}/{}={} ({})", k.name, values.join(","), hint.why)
            }
            _ => format!("{cmd} ({})", hint.why),
        };
        return vec![Refusal {
            what,
            span: at.map(|k| k.span).unwrap_or(call.span),
        }];
    };
    let mut out = Vec::new();
    if call.reuse.is_some() && !support.reuse {
        out.push(Refusal {
            what: format!("{cmd} with reuse= (continuing a result)"),
            span: call.span,
        });
    }
    check_level(cmd, support, &call.keywords, "", &mut out);
    check_iterative_solver(cmd, &call.keywords, &mut out);
    if let Some(rules) = support.rules {
        rules(call, &mut out);
    }
    out
}

/// Fewer iterations than this for code_aster's iterative solvers
/// (`SOLVEUR/METHODE='GCPC'` or `'PETSC'`, `NMAX_ITER`) are refused.
pub const SOLVEUR_NMAX_ITER_MIN: i64 = 10;

/// `SOLVEUR/NMAX_ITER` of an iterative method (GCPC, PETSC), whatever the
/// command: aster solves every system directly, so it reproduces code_aster
/// only when code_aster's iterations converge. With the limits real studies
/// give (20 to 1000, or 0: code_aster's own choice) they do; with a handful
/// code_aster may stop with its solver's error (erreu11a: `NMAX_ITER=1`,
/// DYNA_NON_LINE must fail with MECANONLINE9_12), which a direct solve
/// would not raise: refused at the keyword.
///
/// Likewise a Krylov solve without preconditioner or with a diagonal one
/// (`PRE_COND` `'SANS'`, `'JACOBI'`, `'SOR'`): stopped at `RESI_RELA`, its
/// iterate is off the exact solution by up to the condition number times
/// RESI_RELA (petsc01g: `PRE_COND='JACOBI'`, RESI_RELA 1e-9, a small
/// displacement 2.8e-6 off code_aster's where the direct solve is exact),
/// so it is refused at `PRE_COND`. Only petsc01g of the v17 corpus uses one.
fn check_iterative_solver(cmd: &str, kws: &Keywords, out: &mut Vec<Refusal>) {
    for occ in kws.factor("SOLVEUR") {
        let Some(method @ ("GCPC" | "PETSC")) = occ.str("METHODE") else {
            continue;
        };
        if let Some(kw) = occ.keyword("PRE_COND").filter(|k| !k.defaulted) {
            if let Some(pre @ ("SANS" | "JACOBI" | "SOR")) = occ.str("PRE_COND") {
                out.push(Refusal {
                    what: format!(
                        "{cmd}/SOLVEUR/PRE_COND='{pre}' with METHODE='{method}' (code_aster's Krylov iterate, stopped at RESI_RELA with so weak a preconditioner, is off the exact solution aster's direct solve gives by up to the condition number times RESI_RELA)"
                    ),
                    span: kw.span,
                });
            }
        }
        let Some(kw) = occ.keyword("NMAX_ITER").filter(|k| !k.defaulted) else {
            continue;
        };
        let Some(n) = occ.f64("NMAX_ITER") else {
            continue;
        };
        if n >= 1.0 && n < SOLVEUR_NMAX_ITER_MIN as f64 {
            out.push(Refusal {
                what: format!(
                    "{cmd}/SOLVEUR/NMAX_ITER={n} with METHODE='{method}' (code_aster's iterative solver stops after {n} iteration(s) and may fail where aster's direct solve does not: a limit of {SOLVEUR_NMAX_ITER_MIN} or more, or 0, is accepted)"
                ),
                span: kw.span,
            });
        }
    }
}

fn check_level(cmd: &str, s: &Support, kws: &Keywords, prefix: &str, out: &mut Vec<Refusal>) {
    if s.keywords.contains(&format!("{prefix}*").as_str()) {
        return;
    }
    for k in &kws.entries {
        let path = format!("{prefix}{}", k.name);
        if !s.keywords.contains(&path.as_str()) {
            if k.defaulted {
                continue;
            }
            let what = match s.hints.iter().find(|(p, _)| *p == path) {
                Some((_, hint)) => format!("{cmd}/{path} ({hint})"),
                None => format!("{cmd}/{path}"),
            };
            out.push(Refusal { what, span: k.span });
            continue;
        }
        match &k.value {
            KwValue::Factor(occurrences) => {
                for occ in occurrences {
                    check_level(cmd, s, occ, &format!("{path}/"), out);
                }
            }
            KwValue::Simple(scalars) => {
                let Some(rule) = s.values.iter().find(|v| v.path == path) else {
                    continue;
                };
                for v in scalars.iter().filter_map(|s| s.as_str()) {
                    if rule.allowed.contains(&v) {
                        continue;
                    }
                    let mut what = format!("{cmd}/{path}='{v}'");
                    if !rule.why.is_empty() {
                        what.push(' ');
                        what.push_str(rule.why);
                    }
                    if rule.list {
                        what.push_str(&format!(" (supported: {})", rule.allowed.join(", ")));
                    }
                    out.push(Refusal { what, span: k.span });
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_eval::{Keyword, Scalar};

    fn simple(name: &str, v: &str, at: usize) -> Keyword {
        Keyword {
            name: name.into(),
            value: KwValue::Simple(vec![Scalar::Str(v.into())]),
            span: Span::new(at, at + 1),
            defaulted: false,
        }
    }

    fn call(entries: Vec<Keyword>) -> CommandCall {
        CommandCall {
            command: "CMD".into(),
            result: None,
            reuse: None,
            keywords: Keywords { entries },
            span: Span::new(0, 1),
        }
    }

    const S: Support = Support {
        keywords: &["A", "F", "F/B", "G", "G/*"],
        values: &[
            Values::new("A", &["X"]).why("(only X)"),
            Values::listed("F/B", &["Y", "Z"]),
        ],
        hints: &[("F/C", "use F/B")],
        reuse: false,
        rules: None,
    };

    #[test]
    fn every_refusal_is_reported_at_its_keyword() {
        let factor = |entries| Keyword {
            name: "F".into(),
            value: KwValue::Factor(vec![Keywords { entries }]),
            span: Span::new(10, 11),
            defaulted: false,
        };
        let c = call(vec![
            simple("A", "W", 2),
            factor(vec![simple("B", "Q", 12), simple("C", "1", 14)]),
            simple("H", "1", 20),
        ]);
        let r = check_call(Some(&S), &c);
        let got: Vec<(String, usize)> = r
            .iter()
            .map(|r| (r.what.clone(), r.span.start as usize))
            .collect();
        assert_eq!(
            got,
            vec![
                ("CMD/A='W' (only X)".to_string(), 2),
                ("CMD/F/B='Q' (supported: Y, Z)".to_string(), 12),
                ("CMD/F/C (use F/B)".to_string(), 14),
                ("CMD/H".to_string(), 20),
            ]
        );
    }

    #[test]
    fn defaults_star_factors_and_reuse() {
        let mut d = simple("UNREAD", "1", 3);
        d.defaulted = true;
        let g = Keyword {
            name: "G".into(),
            value: KwValue::Factor(vec![Keywords {
                entries: vec![simple("ANY", "1", 5)],
            }]),
            span: Span::new(4, 5),
            defaulted: false,
        };
        let mut c = call(vec![d, g, simple("A", "X", 6)]);
        assert!(check_call(Some(&S), &c).is_empty());
        c.reuse = Some(aster_eval::ConceptRef {
            id: 1,
            name: "R".into(),
            typ: "evol_noli".into(),
        });
        assert_eq!(
            check_call(Some(&S), &c)[0].what,
            "CMD with reuse= (continuing a result)"
        );
        assert_eq!(check_call(None, &c)[0].what, "CMD");
    }

    #[test]
    fn joined_keeps_both_lists_in_order() {
        const A: &[&str] = &["A", "B"];
        const B: &[&str] = &["C"];
        const J: [&str; 3] = joined::<_, { A.len() + B.len() }>(A, B);
        assert_eq!(J, ["A", "B", "C"]);
        const E: [&str; 1] = joined::<_, 1>(&[], B);
        assert_eq!(E, ["C"]);
    }
}

/// What `aster run` does with a command, or with one of its keyword paths
/// (`"ZONE/ALGO_CONT"`, occurrence indices dropped), in a sentence for
/// `aster explain`. Read from the same table as the refusals.
pub fn describe(command: &str, path: &str) -> String {
    let Some(c) = crate::commands::find(command) else {
        return match command_hint(command) {
            Some(h) => format!("{command} is refused before the run ({})", h.why),
            None => format!("{command} is not executed yet: a case using it is refused before the run (aster check validates it)"),
        };
    };
    let s = &c.support;
    if path.is_empty() {
        return format!(
            "{command} is executed{}",
            if s.reuse { "" } else { " (not with reuse=)" }
        );
    }
    let covered = s.keywords.iter().any(|k| {
        *k == path
            || *k == "*"
            || k.strip_suffix('*')
                .is_some_and(|p| path.starts_with(p) && p.ends_with('/'))
    });
    if !covered {
        return match s.hints.iter().find(|(p, _)| *p == path) {
            Some((_, hint)) => format!("{command}/{path} is not supported yet ({hint})"),
            None => format!(
                "{command}/{path} is not supported yet: a case that writes it is refused before the run (its catalog default is accepted)"
            ),
        };
    }
    match s.values.iter().find(|v| v.path == path) {
        Some(v) => {
            let why = if v.why.is_empty() {
                String::new()
            } else {
                format!(" {}", v.why)
            };
            let values: Vec<String> = v.allowed.iter().map(|a| format!("'{a}'")).collect();
            format!(
                "{command}/{path} is supported with the values {}; others are refused before the run{why}",
                values.join(", ")
            )
        }
        None => {
            let ruled = if s.rules.is_some() {
                " (some combinations with other keywords are refused before the run)"
            } else {
                ""
            };
            format!("{command}/{path} is supported{ruled}")
        }
    }
}

#[cfg(test)]
mod describe_tests {
    use super::describe;

    #[test]
    fn describe_reads_the_support_table() {
        assert_eq!(describe("FIN", ""), "FIN is executed");
        assert!(
            describe("DEFI_CONTACT", "ZONE/GROUP_MA_ESCL").ends_with("is supported")
                || describe("DEFI_CONTACT", "ZONE/GROUP_MA_ESCL").contains("is supported (")
        );
        let m = describe("AFFE_MODELE", "AFFE/MODELISATION");
        assert!(
            m.contains("supported with the values") && m.contains("'D_PLAN'"),
            "{m}"
        );
        let n = describe("NOT_A_COMMAND_X", "");
        assert!(n.contains("not executed yet"), "{n}");
        let h = describe("MACR_ADAP_MAIL", "");
        assert!(
            h.contains("refused before the run (") && h.contains("HOMARD"),
            "{h}"
        );
    }
}
