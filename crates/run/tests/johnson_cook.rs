//! `RELATION='VMIS_JOHN_COOK'` with `DEFI_MATERIAU/ECRO_COOK` on the
//! project's scene `comm/johnson_cook_bar.comm`: a bar pulled at two strain
//! rates then unloaded, in PETIT and GDEF_LOG, against the uniaxial
//! recurrence of code_aster's `nmtevp` (solved by bisection in the command
//! file), and the settings code_aster's law does not take refused.

mod scene;

/// (TEST_RESU OK, NOOK, the error that stopped the run) on the bar mesh.
fn run(comm: &str, name: &str) -> (usize, usize, Option<String>) {
    scene::run_on(comm, "comm/hexs8_beam.mail", name)
}

fn scene() -> String {
    scene::read("johnson_cook_bar.comm")
}

/// σ (SIXX, and T in GDEF_LOG), p, Δp, Δt, the dissipated power and the
/// elastic unloading's indicator against the closed form to 1e-8.
#[test]
fn johnson_cook_bar_matches_the_uniaxial_recurrence() {
    let outcome = run(&scene(), "bar");
    assert!(outcome.2.is_none(), "{:?}", outcome.2);
    assert_eq!((outcome.0, outcome.1), (68, 0));
}

/// SIMO_MIEHE is not in the law's catalogue; DEKKER and SECANTE (zerofr's
/// other methods) are not reproduced.
#[test]
fn johnson_cook_refuses_what_is_not_reproduced() {
    let comm = scene().replace(
        "RELATION=\"VMIS_JOHN_COOK\", ALGO_INTE=\"BRENT\"",
        "RELATION=\"VMIS_JOHN_COOK\", DEFORMATION=\"SIMO_MIEHE\"",
    );
    let err = format!("{:?}", run(&comm, "sm").2.expect("SIMO_MIEHE refused"));
    assert!(
        err.contains("DEFORMATION='SIMO_MIEHE' with RELATION='VMIS_JOHN_COOK'"),
        "{err}"
    );
    let comm = scene().replace("ALGO_INTE=\"BRENT\"", "ALGO_INTE=\"SECANTE\"");
    let err = format!("{:?}", run(&comm, "sec").2.expect("SECANTE refused"));
    assert!(err.contains("ALGO_INTE='SECANTE'"), "{err}");
    // Without ECRO_COOK in the material: named.
    let comm = scene().replace(
        ", ECRO_COOK=_F(A=A, B=B, N_PUIS=N, C=C, EPSP0=EPSP0)",
        ", ECRO_LINE=_F(SY=A, D_SIGM_EPSI=1000.0)",
    );
    let err = format!("{:?}", run(&comm, "mat").2.expect("ECRO_COOK missing"));
    assert!(err.contains("needs ECRO_COOK"), "{err}");
}
