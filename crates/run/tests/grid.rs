//! Reinforcement grids (`GRILLE_MEMBRANE`, `GRILLE_EXCENTRE`,
//! `AFFE_CARA_ELEM/GRILLE`): the project's scene comm/grid_slab.comm (a
//! concrete strip with a steel grid in tension along and across the bars,
//! an offset grid in bending, against the closed forms) and the refusals,
//! located.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/grid_slab.mail", tag)
}

#[test]
fn grids_in_tension_and_an_offset_grid_in_bending_match_the_closed_forms() {
    // 8 values x 2 (NON_REGRESSION, ANALYTIQUE).
    let got = run(&scene::read("grid_slab.comm"), "slab");
    assert_eq!(got, (16, 0, None));
}

/// Without its offset the grid does not move the neutral axis: the
/// bending values checked against the offset's must fail.
#[test]
fn the_offset_changes_the_bending() {
    let text = scene::read("grid_slab.comm").replace("EXCENTREMENT=0.07", "EXCENTREMENT=0.0");
    let (ok, nook, err) = run(&text, "slab-centred");
    assert!(err.is_none(), "{err:?}");
    assert_eq!((ok, nook), (10, 6));
}

/// The bars turned along Y by ANGL_REP_1 as by VECT_2: the same values.
#[test]
fn angl_rep_1_and_vect_2_give_the_same_bars() {
    let text =
        scene::read("grid_slab.comm").replace("VECT_2=(-1.0, 0.0, 0.0)", "ANGL_REP_1=(90.0, 0.0)");
    assert_eq!(run(&text, "slab-angl"), (16, 0, None));
}

fn refused(from: &str, to: &str, tag: &str) -> String {
    let text = scene::read("grid_slab.comm");
    assert!(text.contains(from), "{from}");
    let (_, nook, err) = run(&text.replacen(from, to, 1), tag);
    assert_eq!(nook, 0);
    err.expect("an error")
}

#[test]
fn what_is_not_reproduced_is_refused_at_its_keyword() {
    let err = refused(
        "ANGL_REP_1=(0.0, 0.0)),",
        r#"VECT_1=(1.0, 0.0, 0.0), REPERE="CYLINDRIQUE", ORIGINE=(0.0, 0.0, 0.0), AXE_Z=(0.0, 0.0, 1.0)),"#,
        "cyl",
    );
    assert!(
        err.contains("REPERE") && err.contains("case.comm:"),
        "{err}"
    );
    let err = refused(
        r#"MOME = AFFE_CHAR_MECA(MODELE=MOE, FORCE_NODALE=_F(GROUP_NO="BOUT", MY=5.0e3))"#,
        r#"MOME = AFFE_CHAR_MECA(MODELE=MOE, PESANTEUR=_F(GRAVITE=9.81, DIRECTION=(0.0, 0.0, -1.0)))"#,
        "pesa",
    );
    assert!(err.contains("grid") && err.contains("case.comm:"), "{err}");
    let err = refused(
        r#"COMPORTEMENT=_F(RELATION="ELAS")"#,
        r#"COMPORTEMENT=_F(RELATION="GRILLE_ISOT_LINE")"#,
        "plastic",
    );
    assert!(
        err.contains("RELATION") && err.contains("case.comm:"),
        "{err}"
    );
}

/// comm/grid_plastic.comm: a grid alone stretched along its bars beyond
/// yield, unloaded and reloaded in compression, GRILLE_ISOT_LINE and
/// GRILLE_CINE_LINE against the closed forms (13 values × 2).
#[test]
fn plastic_grids_follow_the_uniaxial_closed_forms() {
    let got = scene::run_on(
        &scene::read("grid_plastic.comm"),
        "comm/grid_slab.mail",
        "plastic",
    );
    assert_eq!(got, (26, 0, None));
}

/// The kinematic checks read with the isotropic law (its reverse yield
/// comes later, its V1 is p, not X) must fail: the two laws differ.
#[test]
fn the_isotropic_law_does_not_pass_the_kinematic_checks() {
    let text = scene::read("grid_plastic.comm").replace(
        r#"COMPORTEMENT=_F(RELATION="GRILLE_CINE_LINE")"#,
        r#"COMPORTEMENT=_F(RELATION="GRILLE_ISOT_LINE")"#,
    );
    let (ok, nook, err) = scene::run_on(&text, "comm/grid_slab.mail", "plastic-swap");
    assert!(err.is_none(), "{err:?}");
    // RCIN's V1 at t = 1 and its SIXX and V1 at t = 3 (× 2) fail.
    assert_eq!((ok, nook), (20, 6));
}

/// A grid law on a cell that is not a grid, or ECRO_LINE missing, is
/// refused before solving, as is a hardening slope not below E.
#[test]
fn grid_laws_where_they_do_not_apply_are_refused() {
    let text = scene::read("grid_plastic.comm");
    let ecro = ", ECRO_LINE=_F(D_SIGM_EPSI=2e10, SY=2e8)";
    assert!(text.contains(ecro), "the edit applies");
    let no_ecro = text.replacen(ecro, "", 1);
    let (_, nook, err) = scene::run_on(&no_ecro, "comm/grid_slab.mail", "plastic-noecro");
    assert_eq!(nook, 0);
    let err = err.expect("an error");
    assert!(err.contains("ECRO_LINE"), "{err}");
    let steep = text.replacen("D_SIGM_EPSI=2e10", "D_SIGM_EPSI=2e11", 1);
    let (_, nook, err) = scene::run_on(&steep, "comm/grid_slab.mail", "plastic-steep");
    assert_eq!(nook, 0);
    assert!(err.expect("an error").contains("D_SIGM_EPSI"));
    // On the slab's DKT cells.
    let err = refused(
        r#"COMPORTEMENT=_F(RELATION="ELAS")"#,
        r#"COMPORTEMENT=_F(RELATION="GRILLE_CINE_LINE")"#,
        "plastic-dkt",
    );
    assert!(err.contains("grids") && err.contains("case.comm:"), "{err}");
}
