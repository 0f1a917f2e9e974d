//! What a run did, for reports (`aster run --report json|junit FILE`): each
//! command with its position and wall time, each TEST_RESU/TEST_TABLE
//! comparison with its position, reference kind, reference and computed
//! values, tolerance and verdict. The executor fills it as commands run; the
//! report is written from it after the run (also when the run stopped).

use crate::test_resu::{Comparison, Judged, Verdict};
use serde::Serialize;
use std::fmt::Write as _;

/// The version of the JSON report's layout.
pub const SCHEMA_VERSION: u32 = 1;

/// A position in a command file.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Position {
    pub file: String,
    pub line: usize,
    pub column: usize,
}

/// One command as it ran.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CommandRecord {
    pub command: String,
    /// The concept it produced (`RESU = STAT_NON_LINE(…)` → `RESU`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub result: Option<String>,
    #[serde(flatten)]
    pub at: Position,
    pub seconds: f64,
    /// The error that stopped the run at this command.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// One comparison of a TEST_* command.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CheckRecord {
    /// The test command (`TEST_RESU`, `TEST_TABLE`…).
    pub command: String,
    /// Position of the keyword holding the reference value (`VALE_CALC`,
    /// `VALE_REFE`), else of the occurrence.
    #[serde(flatten)]
    pub at: Position,
    /// What is tested, as the `.resu` header names it
    /// (`RESULTAT=RESU NUME_ORDRE=20 NOM_CHAM=DEPL …`).
    pub test: String,
    /// `NON_REGRESSION`, `ANALYTIQUE`, `AUTRE_ASTER`…
    pub kind: String,
    pub reference: f64,
    pub computed: f64,
    /// The tolerance, in percent when `relative`.
    pub tolerance: f64,
    pub relative: bool,
    /// |reference − computed| (in percent of |reference| when relative).
    pub error: f64,
    pub verdict: VerdictName,
}

/// A verdict as reports spell it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum VerdictName {
    #[serde(rename = "OK")]
    Ok,
    #[serde(rename = "NOOK")]
    Nook,
    #[serde(rename = "SKIP")]
    Skip,
}

impl From<Verdict> for VerdictName {
    fn from(v: Verdict) -> Self {
        match v {
            Verdict::Ok => VerdictName::Ok,
            Verdict::Nook => VerdictName::Nook,
            Verdict::Skip => VerdictName::Skip,
        }
    }
}

/// The record of a run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Journal {
    pub commands: Vec<CommandRecord>,
    pub checks: Vec<CheckRecord>,
}

impl Journal {
    /// Records the comparisons of one test occurrence.
    pub fn checks_of(
        &mut self,
        command: &str,
        at: Position,
        fields: &[(&str, String)],
        judged: &[(&Comparison, Judged)],
    ) {
        let test = fields
            .iter()
            .map(|(k, v)| format!("{k}={v}"))
            .collect::<Vec<_>>()
            .join(" ");
        for (c, j) in judged {
            self.checks.push(CheckRecord {
                command: command.to_string(),
                at: at.clone(),
                test: test.clone(),
                kind: c.kind.clone(),
                reference: j.expected,
                computed: j.computed,
                tolerance: j.tolerance,
                relative: c.relative,
                error: j.error,
                verdict: j.verdict.into(),
            });
        }
    }

    fn count(&self, v: VerdictName) -> usize {
        self.checks.iter().filter(|c| c.verdict == v).count()
    }

    /// The JSON report: `{"schema_version", "case", "summary", "commands",
    /// "checks"}` (docs/run.md). Non-finite numbers are `null`.
    pub fn to_json(&self, case: &str, error: Option<&str>) -> serde_json::Value {
        serde_json::json!({
            "schema_version": SCHEMA_VERSION,
            "case": case,
            "summary": {
                "ok": self.count(VerdictName::Ok),
                "nook": self.count(VerdictName::Nook),
                "skipped": self.count(VerdictName::Skip),
                "commands": self.commands.len(),
                "seconds": self.commands.iter().map(|c| c.seconds).sum::<f64>(),
                "error": error,
            },
            "commands": self.commands,
            "checks": self.checks,
        })
    }

    /// The JUnit XML report: a suite of the case's checks (one test case
    /// per comparison: a NOOK is a failure, a skipped comparison is
    /// skipped) and a suite of its commands (one test case per command with
    /// its time; the command that stopped the run has an error).
    pub fn to_junit(&self, case: &str, error: Option<&str>) -> String {
        let total: f64 = self.commands.iter().map(|c| c.seconds).sum();
        let nook = self.count(VerdictName::Nook);
        let skipped = self.count(VerdictName::Skip);
        let failed_commands = self.commands.iter().filter(|c| c.error.is_some()).count();
        // A run stopped outside any command (a refusal before running).
        let stray = error.filter(|_| failed_commands == 0);
        let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        let _ = writeln!(
            x,
            "<testsuites name=\"aster run\" tests=\"{}\" failures=\"{nook}\" errors=\"{}\" skipped=\"{skipped}\" time=\"{total:.3}\">",
            self.checks.len() + self.commands.len() + usize::from(stray.is_some()),
            failed_commands + usize::from(stray.is_some()),
        );
        let _ = writeln!(
            x,
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{nook}\" errors=\"0\" skipped=\"{skipped}\">",
            xml(&format!("{case} checks")),
            self.checks.len()
        );
        for c in &self.checks {
            let name = format!(
                "{}:{} {} {} {}",
                c.at.file, c.at.line, c.command, c.kind, c.test
            );
            let _ = write!(
                x,
                "    <testcase classname=\"{}\" name=\"{}\" file=\"{}\" line=\"{}\"",
                xml(&format!("{case}.{}", c.command)),
                xml(&name),
                xml(&c.at.file),
                c.at.line
            );
            let unit = if c.relative { " %" } else { "" };
            match c.verdict {
                VerdictName::Ok => x.push_str("/>\n"),
                VerdictName::Skip => {
                    x.push_str(
                        ">\n      <skipped message=\"reference value zero without ORDRE_GRANDEUR\"/>\n    </testcase>\n",
                    );
                }
                VerdictName::Nook => {
                    let _ = write!(
                        x,
                        ">\n      <failure type=\"NOOK\" message=\"{}\"/>\n    </testcase>\n",
                        xml(&format!(
                            "computed {:e}, reference {:e}: error {:e}{unit} > tolerance {:e}{unit}",
                            c.computed, c.reference, c.error, c.tolerance
                        ))
                    );
                }
            }
        }
        x.push_str("  </testsuite>\n");
        let _ = writeln!(
            x,
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"0\" errors=\"{}\" time=\"{total:.3}\">",
            xml(&format!("{case} commands")),
            self.commands.len() + usize::from(stray.is_some()),
            failed_commands + usize::from(stray.is_some()),
        );
        for c in &self.commands {
            let name = match &c.result {
                Some(r) => format!("{}:{} {r} = {}", c.at.file, c.at.line, c.command),
                None => format!("{}:{} {}", c.at.file, c.at.line, c.command),
            };
            let _ = write!(
                x,
                "    <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\"",
                xml(&format!("{case}.commands")),
                xml(&name),
                c.seconds
            );
            match &c.error {
                None => x.push_str("/>\n"),
                Some(e) => {
                    let _ = write!(
                        x,
                        ">\n      <error message=\"{}\"/>\n    </testcase>\n",
                        xml(e)
                    );
                }
            }
        }
        if let Some(e) = stray {
            let _ = write!(
                x,
                "    <testcase classname=\"{}\" name=\"run\">\n      <error message=\"{}\"/>\n    </testcase>\n",
                xml(&format!("{case}.commands")),
                xml(e)
            );
        }
        x.push_str("  </testsuite>\n</testsuites>\n");
        x
    }
}

/// Escapes text for an XML attribute.
fn xml(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\n' => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            '\t' => out.push_str("&#9;"),
            // Characters XML 1.0 does not allow.
            c if (c as u32) < 0x20 => out.push('?'),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn journal() -> Journal {
        let at = |line| Position {
            file: "case.comm".into(),
            line,
            column: 5,
        };
        Journal {
            commands: vec![
                CommandRecord {
                    command: "STAT_NON_LINE".into(),
                    result: Some("RESU".into()),
                    at: at(10),
                    seconds: 1.25,
                    error: None,
                },
                CommandRecord {
                    command: "TEST_RESU".into(),
                    result: None,
                    at: at(20),
                    seconds: 0.5,
                    error: Some("TEST_RESU/RESU: no field \"SIEF\" <here>".into()),
                },
            ],
            checks: vec![
                CheckRecord {
                    command: "TEST_RESU".into(),
                    at: at(21),
                    test: "RESULTAT=RESU NUME_ORDRE=1 NOM_CHAM=DEPL NOM_CMP=DX GROUP_NO=A".into(),
                    kind: "NON_REGRESSION".into(),
                    reference: 1.0,
                    computed: 1.0000001,
                    tolerance: 1e-4,
                    relative: true,
                    error: 1e-5,
                    verdict: VerdictName::Ok,
                },
                CheckRecord {
                    command: "TEST_RESU".into(),
                    at: at(22),
                    test: "RESULTAT=RESU NUME_ORDRE=1 NOM_CHAM=DEPL NOM_CMP=DY GROUP_NO=A".into(),
                    kind: "ANALYTIQUE".into(),
                    reference: 2.0,
                    computed: 2.5,
                    tolerance: 0.1,
                    relative: true,
                    error: 25.0,
                    verdict: VerdictName::Nook,
                },
                CheckRecord {
                    command: "TEST_TABLE".into(),
                    at: at(23),
                    test: "TABLE=T NOM_PARA=F".into(),
                    kind: "NON_REGRESSION".into(),
                    reference: 0.0,
                    computed: 0.0,
                    tolerance: f64::NAN,
                    relative: true,
                    error: f64::NAN,
                    verdict: VerdictName::Skip,
                },
            ],
        }
    }

    #[test]
    fn json_report() {
        let v = journal().to_json("case", Some("stopped"));
        assert_eq!(v["summary"]["nook"], 1);
        assert_eq!(v["checks"][1]["line"], 22);
        insta::assert_snapshot!(serde_json::to_string_pretty(&v).unwrap());
    }

    #[test]
    fn junit_report() {
        let x = journal().to_junit("case", Some("stopped"));
        assert!(x.contains("failures=\"1\""), "{x}");
        insta::assert_snapshot!(x);
    }

    #[test]
    fn junit_report_of_a_refused_run() {
        let x = Journal::default().to_junit("case", Some("a.comm:3:1: not supported"));
        assert!(
            x.contains("<error message=\"a.comm:3:1: not supported\"/>"),
            "{x}"
        );
        assert!(x.contains("errors=\"1\""), "{x}");
    }
}
