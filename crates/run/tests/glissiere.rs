//! The project's GLISSIERE scene (comm/glissiere.comm on
//! comm/glissiere.mail): two plates linked by bilateral sliding contact,
//! discrete and continuous, against the analytic solution (the plates stay
//! together under a pull, slide without shear, part without GLISSIERE);
//! then the refusals around it.

mod scene;

/// Runs a scene text on a mesh and returns (OK, NOOK, error).
fn run_on(text: &str, mesh: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, mesh, &format!("glissiere-{tag}"))
}

fn scene() -> String {
    scene::read("glissiere.comm")
}

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    run_on(text, "comm/glissiere.mail", tag)
}

#[test]
fn glissiere_plates_pass_every_check() {
    assert_eq!(run(&scene(), "scene"), (70, 0, None));
}

#[test]
fn without_glissiere_the_pulled_plates_part_and_the_checks_fail() {
    // Case 1 with GLISSIERE='NON': the plates part under the pull, so the
    // checks of a linked interface (DY = 0.05, sigma = 1e5) fail.
    let text = scene().replace(
        "linked = solve(pull, contact(\"DISCRETE\", \"OUI\"), one)",
        "linked = solve(pull, contact(\"DISCRETE\", \"NON\"), one, RESI_GLOB_MAXI=1.0e-6)",
    );
    let (ok, nook, err) = run(&text, "non");
    assert!(nook >= 8, "{ok} OK, {nook} NOOK, {err:?}");
}

#[test]
fn discrete_zones_must_agree_on_glissiere() {
    let text = r#"
DEBUT(CODE="OUI")
mesh = LIRE_MAILLAGE(FORMAT="ASTER", UNITE=20)
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
contact = DEFI_CONTACT(
    MODELE=model,
    FORMULATION="DISCRETE",
    ZONE=(
        _F(GROUP_MA_ESCL="AB", GROUP_MA_MAIT="EF", GLISSIERE="OUI"),
        _F(GROUP_MA_ESCL="CD", GROUP_MA_MAIT="GH"),
    ),
)
FIN()
"#;
    let (_, _, err) = run(text, "zones");
    let err = err.expect("an error");
    assert!(
        err.contains("every zone must give the same GLISSIERE") && err.contains("case.comm:10:"),
        "{err}"
    );
}

#[test]
fn a_fixed_projection_needs_its_direction() {
    let text = r#"
DEBUT(CODE="OUI")
mesh = LIRE_MAILLAGE(FORMAT="ASTER", UNITE=20)
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
contact = DEFI_CONTACT(
    MODELE=model,
    FORMULATION="DISCRETE",
    ZONE=_F(GROUP_MA_ESCL="AB", GROUP_MA_MAIT="EF", TYPE_PROJECTION="FIXE"),
)
FIN()
"#;
    let (_, _, err) = run(text, "dire");
    let err = err.expect("an error");
    assert!(err.contains("needs the direction DIRE_APPA"), "{err}");
}
