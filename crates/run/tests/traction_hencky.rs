//! Traction curves per temperature and Hencky elasticity
//! (comm/traction_nappe_bar.comm, comm/hencky_bar.comm): a bar pulled at
//! fixed temperatures with `VMIS_ISOT_TRAC` and a `DEFI_NAPPE` of TEMP
//! (each curve, and code_aster's interpolation in the plastic strain
//! between them), heated with its strain held (p kept, the yield read on
//! the new curve); a bar loaded past its elastic limit and released under
//! `ELAS_VMIS_LINE` / `ELAS_VMIS_TRAC` (back along the same curve); then
//! what is refused, located.

mod scene;

const MESH: &str = "comm/thermoplast_bar.mail";

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, MESH, &format!("traction-{tag}"))
}

fn edited(name: &str, from: &str, to: &str) -> String {
    let t = scene::read(name);
    assert!(t.contains(from), "the scene changed: {from}");
    t.replacen(from, to, 1)
}

#[test]
fn bars_on_a_nappe_of_traction_curves_follow_the_closed_forms() {
    let t = scene::read("traction_nappe_bar.comm");
    assert_eq!(run(&t, "nappe"), (44, 0, None));
}

/// Interpolating σ at a common strain instead of R at a common plastic
/// strain gives another hardening slope at 120 (the closed form with
/// H = 5500 instead of 6000 must fail).
#[test]
fn the_curve_between_two_temperatures_is_interpolated_in_p() {
    let t = edited(
        "traction_nappe_bar.comm",
        "120.0: (150000.0, 150.0, 6000.0)",
        "120.0: (150000.0, 150.0, 5500.0)",
    );
    let (ok, nook, err) = run(&t, "slope");
    assert_eq!(err, None);
    assert!(nook >= 4, "{ok} OK, {nook} NOOK");
}

#[test]
fn hencky_bars_return_along_their_curve() {
    let t = scene::read("hencky_bar.comm");
    assert_eq!(run(&t, "hencky"), (48, 0, None));
}

/// VMIS_ISOT_LINE keeps its plastic strain on unloading: the released
/// bar's references (no residual strain) must fail with it.
#[test]
fn a_plastic_law_would_keep_a_residual_strain() {
    let t = edited(
        "hencky_bar.comm",
        "for relation in (\"ELAS_VMIS_LINE\", \"ELAS_VMIS_TRAC\"):",
        "for relation in (\"ELAS_VMIS_LINE\",):",
    )
    .replacen(
        "COMPORTEMENT=_F(RELATION=relation)",
        "COMPORTEMENT=_F(RELATION=relation.replace(\"ELAS_VMIS\", \"VMIS_ISOT\"))",
        1,
    );
    let (ok, nook, err) = run(&t, "plastic");
    assert_eq!(err, None);
    assert!(nook >= 4, "{ok} OK, {nook} NOOK");
}

#[test]
fn hencky_in_finite_strains_is_refused_at_the_keyword() {
    let t = edited(
        "hencky_bar.comm",
        "COMPORTEMENT=_F(RELATION=relation)",
        "COMPORTEMENT=_F(RELATION=relation, DEFORMATION=\"GREEN_LAGRANGE\")",
    );
    let (ok, nook, err) = run(&t, "gl");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("DEFORMATION='GREEN_LAGRANGE'"), "{err}");
    assert!(err.contains("ELAS_VMIS_LINE"), "{err}");
    assert!(err.contains("case.comm:"), "{err}");
}

#[test]
fn a_nappe_without_temperature_is_refused() {
    let t = edited(
        "traction_nappe_bar.comm",
        "        AFFE_VARC=_F(NOM_VARC=\"TEMP\", TOUT=\"OUI\", EVOL=evol, VALE_REF=20.0),\n",
        "",
    );
    let (ok, nook, err) = run(&t, "notemp");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("nappe of TEMP"), "{err}");
    assert!(err.contains("AFFE_VARC"), "{err}");
}

#[test]
fn a_nappe_of_another_parameter_is_refused_at_the_keyword() {
    let t = edited(
        "traction_nappe_bar.comm",
        "    NOM_PARA=\"TEMP\", PARA=(20.0, 220.0)",
        "    NOM_PARA=\"INST\", PARA=(20.0, 220.0)",
    );
    let (ok, nook, err) = run(&t, "inst");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("DEFI_MATERIAU/TRACTION/SIGM"), "{err}");
    assert!(err.contains("a nappe of INST"), "{err}");
}
