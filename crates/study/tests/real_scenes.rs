//! Small real sweeps on the built-in scenes, through fem and contact.

use aster_study::{builtin_scene, run_study, FailureKind, Progress, Status, StudySpec};

fn run(spec: &str) -> aster_study::StudyResult {
    let spec = StudySpec::from_toml(spec).expect("valid spec");
    let scene = builtin_scene(&spec.scene, &spec.scene_params).expect("known scene");
    run_study(&spec, scene.as_ref(), Progress::Hidden)
}

#[test]
fn hertz_peak_pressure_converges_and_weak_penalty_is_flagged() {
    let result = run(r#"
name = "hertz-test"
scene = "hertz"
reference = "analytic"
tolerance = 0.05
[sweep]
refine = [4, 8]
[[methods]]
kind = "discrete-contrainte"
[[methods]]
kind = "discrete-penalisation"
coefficients = [1e5]
"#);
    let exact: Vec<_> = result
        .records
        .iter()
        .filter(|r| r.point.method.label() == "DISCRETE/CONTRAINTE")
        .collect();
    assert!(
        exact.iter().all(|r| r.status == Status::Converged),
        "{exact:?}"
    );
    let (coarse, fine) = (exact[0].error.unwrap(), exact[1].error.unwrap());
    // Measured: 3.8% at 4 cells across the sector, 0.74% at 8.
    assert!(fine < coarse && fine < 0.01, "p0 errors {coarse} -> {fine}");
    let m = exact[1].measures.as_ref().unwrap();
    assert!(m.penetration.unwrap() < 1e-9);
    // The phases cover the run: the solver is part of it, and the phases
    // add up to the run's CPU time (up to the clock's overhead).
    let phases = m.phases.unwrap();
    let solver = m.solver_seconds.unwrap();
    assert!(solver > 0.0 && solver == phases.solver());
    let cpu = exact[1].cpu_seconds;
    assert!(solver <= cpu, "solver {solver} s > run {cpu} s");
    assert!(
        (phases.total() - cpu).abs() <= 0.2 * cpu + 1e-4,
        "phases {phases:?} do not add up to {cpu} s"
    );
    assert!(phases.assembly > 0.0 && phases.pairing > 0.0 && phases.mesh > 0.0);
    // E_N = 1e5 lets the cylinder sink by ~0.03 mm: a wrong answer, with why.
    let weak = result
        .records
        .iter()
        .find(|r| r.point.method.coefficient() == Some(1e5) && r.point.refine == 8)
        .unwrap();
    assert_eq!(weak.status, Status::Wrong);
    assert_eq!(weak.kind, Some(FailureKind::Penetration));
    assert!(weak.reason.as_deref().unwrap().contains("penetration"));
}

#[test]
fn zzzz237_force_matches_the_rigid_limit_for_a_stiff_base() {
    let result = run(r#"
name = "zzzz237-test"
scene = "zzzz237"
reference = "finest"
[sweep]
refine = [1, 2]
stiffness_ratio = [1e7]
[[methods]]
kind = "discrete-contrainte"
[[methods]]
kind = "discrete-gcp"
"#);
    // code_aster's ZZZZ237 A: FORC_NODA DY(A) = DY(B) = 2.197802198e10 with
    // one cell per block, i.e. a total of 4.395604396e10.
    for r in result.records.iter().filter(|r| r.point.refine == 1) {
        assert_eq!(r.status, Status::Converged, "{r:?}");
        let f = r.measures.as_ref().unwrap().value;
        assert!((f - 4.395604396e10).abs() < 1e-4 * 4.395604396e10, "{f}");
    }
    // The finest CONTRAINTE run is the reference: its error is zero.
    let finest = result
        .records
        .iter()
        .find(|r| r.point.refine == 2 && r.point.method.label() == "DISCRETE/CONTRAINTE")
        .unwrap();
    assert_eq!(finest.error, Some(0.0));
}
