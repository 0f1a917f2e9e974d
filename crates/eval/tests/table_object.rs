//! code_aster's Table object (`TAB.EXTR_TABLE()`): rows, parameters,
//! columns, `values()`, `len()`, iteration and printing, with a table the
//! sink hands over; the uses aster does not reproduce are refused; while
//! checking (contents unknown) the supported uses are run-time values.

use aster_eval::*;
use aster_syntax::CodeMap;

/// A sink whose every table concept is the same small table:
/// INST (reals), NOEUD (text), DX (reals, one empty cell).
#[derive(Default)]
struct Tables {
    printed: Vec<String>,
    /// Give the contents (the run) or not (the static pass).
    unknown: bool,
}

fn r(v: f64) -> HostValue {
    HostValue::Scalar(Scalar::Real(v))
}

fn s(v: &str) -> HostValue {
    HostValue::Scalar(Scalar::Str(v.to_string()))
}

impl CommandSink for Tables {
    fn execute(&mut self, _: &CommandCall) -> Result<CommandOutput, ExecError> {
        Ok(CommandOutput::Concept)
    }
    fn method(
        &mut self,
        _: &ConceptRef,
        name: &str,
        _: &[HostValue],
    ) -> Result<HostValue, ExecError> {
        assert_eq!(name, "EXTR_TABLE");
        if self.unknown {
            return Ok(HostValue::Table(None));
        }
        Ok(HostValue::Table(Some(HostTable {
            para: vec!["INST".into(), "NOEUD".into(), "DX".into()],
            rows: vec![
                vec![r(10.0), s("N1"), r(0.5)],
                vec![r(20.0), s("N2"), HostValue::None],
                vec![r(30.0), s("N3"), r(-1.5)],
            ],
            text: "INST NOEUD DX\n(the table's text)".into(),
        })))
    }
    fn print(&mut self, line: &str) {
        self.printed.push(line.to_string());
    }
}

fn run_with(src: &str, unknown: bool) -> Result<Vec<String>, String> {
    let map = CodeMap::new("t.comm", src);
    let module = aster_syntax::parse_module(src).map_err(|e| e.message)?;
    let mut sink = Tables {
        unknown,
        ..Tables::default()
    };
    let options = RunOptions {
        keep_going: unknown,
    };
    run_program(&map, &module, &mut sink, options).map_err(|d| d.render(&map))?;
    Ok(sink.printed)
}

const PROLOGUE: &str =
    "T = CREA_TABLE(LISTE=_F(PARA='INST', LISTE_R=(1.0,)))\nt = T.EXTR_TABLE()\n";

fn run(body: &str) -> Result<Vec<String>, String> {
    run_with(&format!("{PROLOGUE}{body}"), false)
}

#[test]
fn rows_are_dicts_with_every_parameter() {
    let out = run(r#"
for row in t.rows:
    print(row["INST"], row["NOEUD"], row["DX"])
print(len(t.rows), t.rows[0])
"#)
    .unwrap();
    assert_eq!(
        out,
        [
            "10.0 N1 0.5",
            "20.0 N2 None",
            "30.0 N3 -1.5",
            "3 {'INST': 10.0, 'NOEUD': 'N1', 'DX': 0.5}"
        ]
    );
}

#[test]
fn sdnl133d_style_loop_over_rows() {
    let out = run(r#"
from math import radians, cos
l_angle = []
for row in t.rows:
    l_angle.append(radians(row["INST"]))
print(round(sum(cos(a) for a in l_angle), 12))
"#)
    .unwrap();
    let expected: f64 = [10.0f64, 20.0, 30.0]
        .iter()
        .map(|d| d.to_radians().cos())
        .sum();
    let got: f64 = out[0].parse().unwrap();
    assert!((got - expected).abs() < 1e-12, "{got} vs {expected}");
}

#[test]
fn para_values_columns_and_len() {
    let out = run(r#"
print(t.para)
print(t.values()["INST"], sorted(t.values().keys()))
print(t["DX"].values(), t.NOEUD.values())
print(len(t), len(t["INST"]), t["INST"][2], t.INST[-1])
print([x * 2 for x in t.INST])
if t:
    print("not empty")
"#)
    .unwrap();
    assert_eq!(
        out,
        [
            "['INST', 'NOEUD', 'DX']",
            "[10.0, 20.0, 30.0] ['DX', 'INST', 'NOEUD']",
            "[0.5, None, -1.5] ['N1', 'N2', 'N3']",
            "3 3 30.0 30.0",
            "[20.0, 40.0, 60.0]",
            "not empty"
        ]
    );
}

#[test]
fn iterating_the_table_gives_its_rows_and_print_its_text() {
    let out = run(r#"
print([r["NOEUD"] for r in t])
print(t)
"#)
    .unwrap();
    assert_eq!(out[0], "['N1', 'N2', 'N3']");
    assert_eq!(out[1], "INST NOEUD DX\n(the table's text)");
}

#[test]
fn a_missing_parameter_is_a_key_error() {
    let err = run("x = t['DY']\n").unwrap_err();
    assert!(err.contains("KeyError") && err.contains("DY"), "{err}");
    assert!(err.contains("t.comm:3:"), "{err}");
}

#[test]
fn what_aster_does_not_reproduce_is_refused() {
    for (src, what) in [
        ("u = t.sort('INST')\n", "`.sort`"),
        ("u = t.DX > 0.0\n", "comparison of a column"),
        ("u = t.INST == 10.0\n", "comparison of a column"),
        ("u = t.INST.MAXI()\n", "MAXI"),
        ("u = t[0]\n", "subscript"),
    ] {
        let err = run(src).unwrap_err();
        assert!(err.contains("not supported"), "{src}: {err}");
        assert!(err.contains(what), "{src}: {err}");
        assert!(err.contains("t.comm:3:"), "{src}: {err}");
    }
}

#[test]
fn while_checking_the_contents_are_run_time_values_and_refusals_stay() {
    // Supported uses check clean (their values come with the run)...
    let ok = run_with(
        &format!("{PROLOGUE}n = len(t)\nc = t.values()\nv = t.DX.values()\np = t.para\n"),
        true,
    );
    assert!(ok.is_ok(), "{ok:?}");
    // ... and the others are refused before anything runs.
    let err = run_with(&format!("{PROLOGUE}u = t.sort('INST')\n"), true).unwrap_err();
    assert!(
        err.contains("not supported") && err.contains("`.sort`"),
        "{err}"
    );
    let err = run_with(&format!("{PROLOGUE}u = t.DX >= 1.0\n"), true).unwrap_err();
    assert!(err.contains("comparison of a column"), "{err}");
}

#[test]
fn bare_except_catches_python_errors_only() {
    let out = run(r#"
k = []
for l in ([1.0, 3.0], []):
    try:
        k.append(max(l))
    except:
        k.append(0.0)
print(k)
try:
    x = 1 / 0
except Exception:
    x = -1
print(x)
"#)
    .unwrap();
    assert_eq!(out, ["[3.0, 0.0]", "-1"]);
    // What aster cannot evaluate is not swallowed by the handler.
    let err = run("try:\n    u = t.sort('INST')\nexcept:\n    u = None\n").unwrap_err();
    assert!(err.contains("not supported"), "{err}");
}
