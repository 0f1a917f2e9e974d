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

#[test]
fn liaison_unil_matches_contact_on_hertz_and_the_rigid_base_on_zzzz237() {
    let hertz = run(r#"
name = "hertz-unil"
scene = "hertz"
reference = "analytic"
[sweep]
refine = [8]
[[methods]]
kind = "discrete-contrainte"
[[methods]]
kind = "liaison-unil"
[[methods]]
kind = "liaison-unil-penalisation"
coefficients = [1e5, 1e9]
"#);
    let by = |label: &str| {
        hertz
            .records
            .iter()
            .find(|r| r.point.method.label() == label)
            .unwrap_or_else(|| panic!("no run {label}"))
    };
    let contact = by("DISCRETE/CONTRAINTE");
    let unil = by("LIAISON_UNIL/CONTRAINTE");
    assert_eq!(unil.status, Status::Converged, "{unil:?}");
    // A flat rigid plane: node-to-segment rows with normal (0, 1) and the
    // node-wise rows −DY ≤ y are the same conditions.
    let (a, b) = (
        contact.measures.as_ref().unwrap().value,
        unil.measures.as_ref().unwrap().value,
    );
    assert!(
        (a - b).abs() < 1e-8 * a,
        "p0 contact {a} vs LIAISON_UNIL {b}"
    );
    let m = unil.measures.as_ref().unwrap();
    assert!(m.penetration.unwrap() < 1e-9);
    assert_eq!(m.phases.unwrap().pairing, 0.0, "LIAISON_UNIL does not pair");
    // Penalised: a weak COEF_PENA lets the cylinder sink (wrong, with why),
    // a strong one is within 0.1% of the exact rows.
    let weak = by("LIAISON_UNIL/PENALISATION COEF_PENA=1e5");
    assert_eq!(weak.kind, Some(FailureKind::Penetration), "{weak:?}");
    let strong = by("LIAISON_UNIL/PENALISATION COEF_PENA=1e9");
    assert_eq!(strong.status, Status::Converged, "{strong:?}");
    let c = strong.measures.as_ref().unwrap().value;
    assert!((c - b).abs() < 1e-3 * b, "{c} vs {b}");

    let blocks = run(r#"
name = "zzzz237-unil"
scene = "zzzz237"
reference = "finest"
[sweep]
refine = [1, 4]
stiffness_ratio = [1.0]
[[methods]]
kind = "discrete-contrainte"
[[methods]]
kind = "liaison-unil"
"#);
    // ZZZZ237 B: the rigid base gives 2 × 2.197802198e10 on any mesh (a
    // uniform state); LIAISON_UNIL is compared with it, not with the
    // deformable base of the contact runs.
    for r in blocks
        .records
        .iter()
        .filter(|r| r.point.method.family().is_unilateral())
    {
        assert_eq!(r.status, Status::Converged, "{r:?}");
        let f = r.measures.as_ref().unwrap().value;
        assert!((f - 4.395604396e10).abs() < 1e-6 * 4.395604396e10, "{f}");
        assert!(r.error.unwrap() < 1e-6);
    }
}

/// The stick/slip scene: sliding, ΣFX/ΣFY is μ exactly for the augmented
/// and penalised continuous friction; a soft discrete E_T leaves the block
/// stuck elastically below μ (a converged, wrong answer); frictionless
/// methods and μ = 0 are not available on it.
#[test]
fn friction_scene_slides_at_mu_and_flags_a_soft_tangential_penalty() {
    let result = run(r#"
name = "friction-test"
scene = "friction"
reference = "analytic"
tolerance = 1e-3
[scene_params]
iter_glob_maxi = 50
coef_matr_frot = 0.5
[sweep]
refine = [2, 4]
coulomb = [0.3]
[[methods]]
kind = "continuous-friction-standard"
[[methods]]
kind = "continuous-friction-penalisation"
coefficients = [1e5]
[[methods]]
kind = "discrete-friction-penalisation"
coefficients = [1e3, 1e9]
"#);
    for r in &result.records {
        let label = r.point.method.label();
        let m = r.measures.as_ref().expect("every run measures");
        // Sliding is checked by the analytic reference μ = 0.3.
        assert_eq!(m.reference, Some(0.3), "{label}");
        if label.ends_with("E_T=1000") {
            // E_T·slip stays below μ·N: the block sticks elastically.
            assert_eq!(r.status, Status::Wrong, "{label}: {r:?}");
            assert_eq!(r.kind, Some(FailureKind::Inaccurate));
            assert!(m.value < 0.1, "{label}: ratio {}", m.value);
        } else {
            assert_eq!(r.status, Status::Converged, "{label}: {r:?}");
            // Continuous: converged to round-off; discrete: Newton stops at
            // RESI_GLOB_RELA = 1e-6 on its linear convergence.
            assert!(r.error.unwrap() < 1e-6, "{label}: error {:?}", r.error);
            assert!(m.penetration.unwrap() < 1e-3, "{label}");
        }
    }
    // The spec refuses frictionless methods beside frictional ones; alone,
    // a frictionless method on the friction scene is not available.
    let frictionless = run(r#"
name = "friction-frictionless"
scene = "friction"
reference = "analytic"
[sweep]
refine = [2]
[[methods]]
kind = "discrete-contrainte"
"#);
    let r = &frictionless.records[0];
    assert_eq!(r.status, Status::Unsupported, "{r:?}");
    assert!(r.reason.as_deref().unwrap().contains("frictional methods"));
}
