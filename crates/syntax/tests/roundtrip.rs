//! The canonical printer's contract: `parse(fmt(x)) == parse(x)` up to spans,
//! and `fmt` is idempotent. Checked on the project's inputs and, when
//! `../shared` exists, on a sample of the real corpora.

use aster_syntax::{decode, fmt::format_source, parse_module};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The AST as JSON without any `span` (positions legitimately change).
pub fn shape(source: &str) -> Result<Value, String> {
    let m = parse_module(source).map_err(|e| format!("{:?}: {}", e.span, e.message))?;
    let mut v = serde_json::to_value(&m).map_err(|e| e.to_string())?;
    strip(&mut v);
    Ok(v)
}

fn strip(v: &mut Value) {
    match v {
        Value::Object(map) => {
            map.remove("span");
            map.values_mut().for_each(strip);
        }
        Value::Array(items) => items.iter_mut().for_each(strip),
        _ => {}
    }
}

fn check(name: &str, source: &str) -> Result<(), String> {
    let before = shape(source).map_err(|e| format!("{name}: original does not parse: {e}"))?;
    let once = format_source(source).map_err(|e| format!("{name}: fmt failed: {}", e.message))?;
    let after =
        shape(&once).map_err(|e| format!("{name}: formatted text does not parse: {e}\n{once}"))?;
    if before != after {
        return Err(format!("{name}: AST changed by fmt:\n{once}"));
    }
    let twice =
        format_source(&once).map_err(|e| format!("{name}: second fmt failed: {}", e.message))?;
    if once != twice {
        return Err(format!(
            "{name}: fmt is not idempotent:\n--- once\n{once}\n--- twice\n{twice}"
        ));
    }
    Ok(())
}

fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "comm"))
                .collect()
        })
        .unwrap_or_default();
    out.sort();
    out
}

#[test]
fn own_inputs_round_trip() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inputs");
    let inputs = files(&dir);
    assert!(inputs.len() >= 4);
    for path in inputs {
        let source = decode(&std::fs::read(&path).unwrap_or_default());
        if let Err(e) = check(&path.display().to_string(), &source) {
            panic!("{e}");
        }
    }
}

#[test]
fn long_commands_get_one_keyword_per_line() {
    let src = "RESU = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=CH1), _F(CHARGE=CH2, FONC_MULT=RAMPE)), INCREMENT=_F(LIST_INST=L_INST))\n";
    let out = format_source(src).unwrap_or_default();
    assert_eq!(
        out,
        "RESU = STAT_NON_LINE(\n    MODELE=MO,\n    CHAM_MATER=CHMAT,\n    EXCIT=(_F(CHARGE=CH1), _F(CHARGE=CH2, FONC_MULT=RAMPE)),\n    INCREMENT=_F(LIST_INST=L_INST),\n)\n"
    );
}

#[test]
fn corpus_sample_round_trips() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    if !root.exists() {
        eprintln!("skipped: {} not found", root.display());
        return;
    }
    let mut failures = Vec::new();
    let mut checked = 0;
    for version in ["v17", "v11"] {
        // Every 25th file keeps the debug-mode test fast; the full corpora
        // are checked by `cargo run --release --example corpus -- --fmt`.
        for path in files(&root.join(version)).into_iter().step_by(25) {
            let source = decode(&std::fs::read(&path).unwrap_or_default());
            checked += 1;
            if let Err(e) = check(&path.display().to_string(), &source) {
                failures.push(e.lines().next().unwrap_or("").to_string());
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {checked} failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
