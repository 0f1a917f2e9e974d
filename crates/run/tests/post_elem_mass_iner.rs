//! POST_ELEM/MASS_INER (comm/mass_iner_block.comm on
//! comm/mass_iner_block.mail and comm/mass_iner_2d.comm on
//! comm/mass_iner_2d.mail, written for the project): mass, centre of
//! gravity, inertia about it and about ORIG_INER, principal inertias and
//! the angles of a tilted block, against closed forms; 3D, a point mass,
//! a POU_D_E beam, D_PLAN and AXIS; and the located refusals around it.

mod scene;

fn run(comm: &str, text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        &format!("comm/{comm}.mail"),
        &format!("mass-iner-{tag}"),
    )
}

#[test]
fn a_block_a_point_mass_a_tilted_block_and_a_beam_match_the_closed_forms() {
    let text = scene::read("mass_iner_block.comm");
    assert_eq!(run("mass_iner_block", &text, "block"), (160, 0, None));
}

#[test]
fn plane_and_axisymmetric_rectangles_match_the_closed_forms() {
    let text = scene::read("mass_iner_2d.comm");
    assert_eq!(run("mass_iner_2d", &text, "2d"), (64, 0, None));
}

/// The deformed geometry is refused at GEOMETRIE; a material without RHO
/// is an error naming the cell.
#[test]
fn the_deformed_geometry_and_a_missing_density_are_located() {
    let text = scene::read("mass_iner_2d.comm");
    let t = text.replacen(
        "TA = POST_ELEM(MODELE=MOA,",
        "TA = POST_ELEM(GEOMETRIE=\"DEFORMEE\", MODELE=MOA,",
        1,
    );
    let (ok, _, err) = run("mass_iner_2d", &t, "deformee");
    let err = err.expect("a refusal");
    assert_eq!(ok, 0);
    assert!(
        err.contains("not supported yet") && err.contains("GEOMETRIE"),
        "{err}"
    );
    let t = text.replacen("NU=0.3, RHO=RHO)", "NU=0.3)", 1);
    let (_, nook, err) = run("mass_iner_2d", &t, "rho");
    let err = err.expect("an error");
    assert_eq!(nook, 0);
    assert!(err.contains("no density") && err.contains("Q1"), "{err}");
}
