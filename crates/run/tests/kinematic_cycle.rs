//! `RELATION='VMIS_CINE_LINE'` (linear kinematic hardening, code_aster's
//! `nmcine`) on the project's scene `comm/kinematic_cycle.comm`: a
//! tension-compression cycle of a cube against the uniaxial closed form
//! (the Bauschinger effect: reversed yield after a range of 2 SY), the
//! back stress in VARI, the isotropic law's different answer, and a
//! continued result (`reuse=`) whose earlier instants CALC_CHAMP still
//! computes.

mod scene;

fn run(comm: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(comm, "comm/finite_strain.mail", tag)
}

#[test]
fn kinematic_cycle_matches_the_closed_form() {
    let outcome = run(&scene::read("kinematic_cycle.comm"), "kine");
    assert!(outcome.2.is_none(), "{:?}", outcome.2);
    assert_eq!((outcome.0, outcome.1), (31, 0));
}

/// The isotropic law's reversed branch checked against the kinematic
/// law's answer (−206 where it gives −217.88): both comparisons of that
/// check fail — the two laws are not confused.
#[test]
fn isotropic_hardening_gives_another_reversed_branch() {
    let comm = scene::read("kinematic_cycle.comm").replace(
        "check(isot, 3.0, \"SIEF_ELGA\", \"SIXX\", -206.0 - ET * (2 * EPS - 412.0 / E), point=2)",
        "check(isot, 3.0, \"SIEF_ELGA\", \"SIXX\", -206.0, point=2)",
    );
    assert_eq!(run(&comm, "isot"), (29, 2, None));
}

/// code_aster's VMIS_CINE_LINE takes PETIT, PETIT_REAC, GROT_GDEP and
/// GDEF_LOG; SIMO_MIEHE is refused before solving.
#[test]
fn vmis_cine_line_refuses_simo_miehe() {
    let comm = scene::read("kinematic_cycle.comm").replace(
        "kine = STAT_NON_LINE(\n    COMPORTEMENT=_F(RELATION=\"VMIS_CINE_LINE\")",
        "kine = STAT_NON_LINE(\n    COMPORTEMENT=_F(RELATION=\"VMIS_CINE_LINE\", DEFORMATION=\"SIMO_MIEHE\")",
    );
    let err = format!("{:?}", run(&comm, "simo").2.expect("refused"));
    assert!(err.contains("RELATION='VMIS_CINE_LINE'"), "{err}");
}
