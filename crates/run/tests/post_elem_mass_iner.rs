//! POST_ELEM/MASS_INER (comm/mass_iner_block.comm on
//! comm/mass_iner_block.mail and comm/mass_iner_2d.comm on
//! comm/mass_iner_2d.mail, written for the project): mass, centre of
//! gravity, inertia about it and about ORIG_INER, principal inertias and
//! the angles of a tilted block, against closed forms; 3D, a point mass,
//! a POU_D_E beam, D_PLAN and AXIS, DKT shells (comm/mass_iner_shells.comm
//! on comm/dkt_strips.mail), COQUE_3D (comm/mass_iner_coque3d.comm); and
//! the located refusals around it.

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

/// DKT shells (dxiner) on comm/dkt_strips.mail: two plates of QUAD4 and
/// TRIA3 in perpendicular planes, each m/12 (d₂² + d₃², …) about its
/// centre with the thickness along its normal, and their sum by Huygens
/// (comm/mass_iner_shells.comm).
#[test]
fn dkt_strips_match_the_closed_forms_of_plates() {
    let text = scene::read("mass_iner_shells.comm");
    let got = scene::run_on(&text, "comm/dkt_strips.mail", "mass-iner-shells");
    assert_eq!(got, (60, 0, None));
}

/// COQUE_3D (te0417) on comm/coque3d_strip.mail: the strip and one cell
/// of it, each a plate's closed form (comm/mass_iner_coque3d.comm).
#[test]
fn a_coque3d_strip_matches_the_closed_forms_of_plates() {
    let text = scene::read("mass_iner_coque3d.comm");
    let got = scene::run_on(&text, "comm/coque3d_strip.mail", "mass-iner-coque3d");
    assert_eq!(got, (40, 0, None));
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

/// A DIS_TR node with M_TR_D_N (te0045, MECA_DIS_TR_N): the mass at the
/// node, its inertia the matrix's rotation block (Huygens on the offset
/// e = (0, 0, 0.1) included, the products as given); a segment mass is
/// refused at CARA_ELEM.
#[test]
fn a_dis_tr_node_mass_carries_its_inertia() {
    let text = scene::read("mass_iner_block.comm");
    let mut t = text
        .replacen(
            "_F(GROUP_MA=\"PM\", PHENOMENE=\"MECANIQUE\", MODELISATION=\"DIS_T\")",
            "_F(GROUP_MA=\"PM\", PHENOMENE=\"MECANIQUE\", MODELISATION=\"DIS_TR\")",
            1,
        )
        .replacen(
            "_F(GROUP_MA=\"PM\", CARA=\"M_T_D_N\", VALE=MPT),\n        _F(GROUP_MA=\"PM\", CARA=\"K_T_D_N\", VALE=(0.0, 0.0, 0.0)),",
            "_F(GROUP_MA=\"PM\", CARA=\"M_TR_D_N\", VALE=(MPT, 10.0, 20.0, 30.0, 1.0, 2.0, 3.0, 0.0, 0.0, 0.1)),\n        _F(GROUP_MA=\"PM\", CARA=\"K_TR_D_N\", VALE=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)),",
            1,
        );
    let cut = t.find("check(TD, \"PM\", \"IX_G\"").expect("the PM checks");
    let end = t[cut..].find('\n').unwrap() + cut;
    t.replace_range(
        cut..end,
        "check(TD, \"PM\", \"IX_G\", 20.0)\ncheck(TD, \"PM\", \"IY_G\", 30.0)\ncheck(TD, \"PM\", \"IZ_G\", 30.0)\ncheck(TD, \"PM\", \"IXY_G\", 1.0)\ncheck(TD, \"PM\", \"IYZ_G\", 2.0)\ncheck(TD, \"PM\", \"IXZ_G\", 3.0)",
    );
    // The block's own rows are those of a point mass without inertia: drop
    // the checks of TD's TOUT row (its inertia now has the node's).
    let t = t.replace("check(TD, MA.getName(),", "ignore(TD, MA.getName(),");
    let t = t.replacen(
        "# The block and the point mass.",
        "def ignore(*args):\n    pass\n\n\n# The block and the point mass.",
        1,
    );
    let t = t.replacen("check(TD, \"PM\", \"ALPHA\", 0.0, 1.0)\n", "", 1);
    let (ok, nook, err) = run("mass_iner_block", &t, "dis-tr");
    assert_eq!((nook, err), (0, None));
    // Two OK lines per check: 10 checks of the TOUT row and 2 of PM
    // dropped, 6 added.
    assert_eq!(ok, 160 - 2 * (10 + 2) + 2 * 6);
    let t = text.replacen(
        "_F(GROUP_MA=\"PM\", CARA=\"M_T_D_N\", VALE=MPT),",
        "_F(GROUP_MA=\"PM\", CARA=\"M_T_D_N\", VALE=MPT),\n        _F(GROUP_MA=\"PM\", CARA=\"M_T_N\", VALE=(MPT, 0.0, MPT, 0.0, 0.0, MPT), REPERE=\"LOCAL\"),",
        1,
    );
    let (_, _, err) = run("mass_iner_block", &t, "local");
    let err = err.expect("a refusal");
    assert!(
        err.contains("not supported yet") && err.contains("local frame"),
        "{err}"
    );
}
