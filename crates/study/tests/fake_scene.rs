//! The engine, the CSV and the charts on the synthetic `fake` scene.

use aster_study::{
    builtin_scene, csv_out, run_and_write, run_study, FailureKind, Progress, Status, StudySpec,
};

const SPEC: &str = r#"
name = "fake-study"
scene = "fake"
reference = "analytic"
tolerance = 0.05
accuracy_target = 0.01

[scene_params]
work = 10.0

[sweep]
refine = [2, 4, 8, 16, 32]
stiffness_ratio = [1.0, 1e5]

[[methods]]
kind = "discrete-contrainte"

[[methods]]
kind = "discrete-penalisation"
coefficients = [1e1, 1e3, 1e5, 1e7, 1e9]

[[methods]]
kind = "discrete-gcp"

[[methods]]
kind = "liaison-unil"
"#;

fn spec() -> StudySpec {
    StudySpec::from_toml(SPEC).expect("the test spec is valid")
}

#[test]
fn every_point_is_recorded_and_failures_carry_reasons() {
    let spec = spec();
    let scene = builtin_scene(&spec.scene, &spec.scene_params).unwrap();
    let result = run_study(&spec, scene.as_ref(), Progress::Hidden);
    // 8 methods × 5 refinements × 2 ratios.
    assert_eq!(result.records.len(), 8 * 5 * 2);
    for r in &result.records {
        match r.status {
            Status::Converged => assert!(r.reason.is_none() && r.kind.is_none()),
            _ => {
                let reason = r.reason.as_deref().unwrap_or("");
                assert!(
                    !reason.is_empty() && r.kind.is_some(),
                    "run {} has no reason",
                    r.point.index
                );
            }
        }
    }
    let kinds = |k: FailureKind| result.records.iter().filter(|r| r.kind == Some(k)).count();
    // E_N × ratio > 1e12 only for E_N = 1e9 at ratio 1e5 (5 refinements).
    assert_eq!(kinds(FailureKind::SingularMatrix), 5);
    // GCP fails at ratio 1e5 on every mesh.
    assert_eq!(kinds(FailureKind::NoConvergence), 5);
    assert_eq!(kinds(FailureKind::Unsupported), 10);
    // Penetration ratio/E_N > 1e-2 for ratio 1e5 with E_N = 1e1, 1e3, 1e5
    // and for ratio 1 with E_N = 1e1: 4 cells × 5 meshes.
    assert_eq!(kinds(FailureKind::Penetration), 20);
    // The remaining converged runs are inaccurate only where the h² term
    // (0.3 h²) exceeds the 5% tolerance: refine 2.
    let inaccurate: Vec<_> = result
        .records
        .iter()
        .filter(|r| r.kind == Some(FailureKind::Inaccurate))
        .collect();
    assert!(!inaccurate.is_empty());
    assert!(inaccurate
        .iter()
        .all(|r| r.error.unwrap() > 0.05 && r.point.refine <= 2));
    // The exact method converges at h², its error computed against 1.
    let exact = result
        .records
        .iter()
        .find(|r| r.point.method.label() == "DISCRETE/CONTRAINTE" && r.point.refine == 8)
        .unwrap();
    assert_eq!(exact.status, Status::Converged);
    assert!((exact.error.unwrap() - 0.3 / 64.0).abs() < 1e-12);
    assert!(exact.wall_seconds > 0.0);
}

#[test]
fn finest_reference_uses_the_first_method_on_the_finest_mesh() {
    let text = SPEC.replace("reference = \"analytic\"", "reference = \"finest\"");
    let spec = StudySpec::from_toml(&text).unwrap();
    let scene = builtin_scene(&spec.scene, &spec.scene_params).unwrap();
    let result = run_study(&spec, scene.as_ref(), Progress::Hidden);
    let finest = 1.0 + 0.3 / (32.0f64 * 32.0);
    for r in result.records.iter().filter(|r| r.measures.is_some()) {
        assert!((r.reference.unwrap() - finest).abs() < 1e-12);
    }
    let r = result
        .records
        .iter()
        .find(|r| r.point.method.label() == "DISCRETE/CONTRAINTE" && r.point.refine == 32)
        .unwrap();
    assert_eq!(r.error, Some(0.0));
}

#[test]
fn writes_csv_charts_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let (result, out) = run_and_write(&spec(), dir.path(), Progress::Hidden).unwrap();

    let mut reader = csv::Reader::from_path(&out.csv).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header, csv_out::COLUMNS);
    let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), result.records.len());
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    for row in &rows {
        let status = &row[col("status")];
        assert!(["converged", "wrong", "failed", "unsupported"].contains(&status));
        if status != "converged" {
            assert!(!row[col("reason")].is_empty(), "{row:?}");
            assert!(!row[col("failure")].is_empty(), "{row:?}");
        }
        assert!(row[col("wall_s")].parse::<f64>().unwrap() >= 0.0);
    }
    // A singular run's reason survives the CSV quoting (it holds commas? no:
    // it holds `×`, non-ASCII) intact.
    assert!(rows
        .iter()
        .any(|r| r[col("reason")].contains("coefficient × stiffness ratio")));

    assert_eq!(out.charts.len(), 6);
    for kind in ["pareto", "convergence", "stability"] {
        let svg = dir.path().join(format!("fake-study-{kind}.svg"));
        let png = dir.path().join(format!("fake-study-{kind}.png"));
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(
            text.contains("<svg") && text.contains("fake-study"),
            "{kind}"
        );
        let bytes = std::fs::read(&png).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{kind}");
        assert!(bytes.len() > 5000, "{kind} PNG is nearly empty");
    }
    let svg = std::fs::read_to_string(dir.path().join("fake-study-stability.svg")).unwrap();
    for label in [
        "DISCRETE/GCP",
        "singular-matrix",
        "no-convergence",
        "(columns: E_N)",
        "1e9",
        "ratio 1e5",
    ] {
        assert!(svg.contains(label), "stability map lacks {label}");
    }
    let svg = std::fs::read_to_string(dir.path().join("fake-study-convergence.svg")).unwrap();
    assert!(
        svg.contains("DISCRETE/CONTRAINTE, ratio 1: slope 2.00"),
        "fitted slope missing"
    );

    let summary = std::fs::read_to_string(&out.summary).unwrap();
    assert!(summary.contains("## Fastest at equal accuracy"));
    assert!(summary.contains("singular-matrix"));
}

#[test]
fn bad_specs_and_scenes_are_errors_with_hints() {
    let e = builtin_scene("hetz", &Default::default())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("did you mean `hertz`"), "{e}");
    let spec = StudySpec::from_toml(&SPEC.replace("work = 10.0", "wrok = 10.0")).unwrap();
    let e = builtin_scene(&spec.scene, &spec.scene_params)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("did you mean `work`"), "{e}");
}
