//! PESANTEUR, FORCE_ARETE and LIAISON_OBLIQUE: the project's scenes
//! (comm/gravity_column.comm, gravity_strip.comm, edge_strip.comm,
//! coque3d_edge.comm, oblique_block.comm) against their analytic values, and the refusals,
//! located at the keyword.

mod scene;

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &Path, mesh: &str, tag: &str) -> aster_run::program::Outcome {
    let out = std::env::temp_dir().join(format!("aster-loads-more-{tag}-{}", std::process::id()));
    let case =
        aster_run::program::prepare(comm, Some(&root().join("comm").join(mesh)), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    outcome
}

fn scene(name: &str, mesh: &str) -> (usize, usize) {
    let outcome = run(&root().join("comm").join(name), mesh, name);
    assert!(outcome.error.is_none(), "{name}: {:?}", outcome.error);
    (outcome.tally.ok, outcome.tally.nook)
}

#[test]
fn a_column_under_its_own_weight_and_edge_loads_in_3d() {
    // Weight: 4 values x 2 (NON_REGRESSION, ANALYTIQUE); the dynamics
    // continued from it: 1; FORCE_ARETE: 2; the plastic bar continued by
    // DYNA_NON_LINE: 2.
    assert_eq!(scene("gravity_column.comm", "gravity_column.mail"), (18, 0));
}

#[test]
fn gravity_in_d_plan_c_plan_and_axis() {
    assert_eq!(scene("gravity_strip.comm", "gravity_strip.mail"), (24, 0));
}

#[test]
fn forces_and_moments_on_the_edge_of_a_dkt_strip_and_its_weight() {
    assert_eq!(scene("edge_strip.comm", "edge_strip.mail"), (12, 0));
}

#[test]
fn force_coque_on_a_dkt_strip_global_normal_plane_and_functions() {
    // 11 values x 2 (NON_REGRESSION, ANALYTIQUE).
    assert_eq!(scene("shell_force_strip.comm", "edge_strip.mail"), (22, 0));
}

#[test]
fn force_coque_off_shells_or_in_the_local_frame_is_refused() {
    let err = refused(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
load = AFFE_CHAR_MECA(MODELE=model, FORCE_COQUE=_F(TOUT="OUI", PRES=1.0))
FIN()
"#,
        "gravity_strip.mail",
        "noshell",
    );
    assert!(err.contains("the selection has no shell cell"), "{err}");
    assert!(err.contains("noshell.comm:4:"), "{err}");
    let err = refused(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA="STRIP", PHENOMENE="MECANIQUE", MODELISATION="DKT"))
load = AFFE_CHAR_MECA(MODELE=model, FORCE_COQUE=_F(TOUT="OUI", F1=1.0))
FIN()
"#,
        "edge_strip.mail",
        "local",
    );
    assert!(
        err.contains("not supported yet: AFFE_CHAR_MECA/FORCE_COQUE/F1"),
        "{err}"
    );
    assert!(err.contains("local.comm:4:"), "{err}");
}

#[test]
fn a_block_sliding_on_an_inclined_support() {
    assert_eq!(scene("oblique_block.comm", "oblique_block.mail"), (16, 0));
}

/// Runs a small program on a scene mesh and returns its error message.
fn refused(source: &str, mesh: &str, tag: &str) -> String {
    let dir =
        std::env::temp_dir().join(format!("aster-loads-more-src-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join(format!("{tag}.comm"));
    std::fs::write(&comm, source).unwrap();
    let outcome = run(&comm, mesh, tag);
    let _ = std::fs::remove_dir_all(dir);
    outcome.error.expect("refused").message
}

#[test]
fn gravity_without_rho_is_refused_at_pesanteur() {
    let err = refused(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
steel = DEFI_MATERIAU(ELAS=_F(E=1.0e7, NU=0.0))
mater = AFFE_MATERIAU(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", MATER=steel))
held = AFFE_CHAR_MECA(MODELE=model, DDL_IMPO=(_F(GROUP_MA="BASE", DY=0.0), _F(GROUP_NO="A", DX=0.0)))
weight = AFFE_CHAR_MECA(MODELE=model, PESANTEUR=_F(GRAVITE=10.0, DIRECTION=(0.0, 1.0, 0.0)))
res = MECA_STATIQUE(MODELE=model, CHAM_MATER=mater, EXCIT=(_F(CHARGE=held), _F(CHARGE=weight)))
FIN()
"#,
        "gravity_strip.mail",
        "norho",
    );
    assert!(err.contains("has no ELAS/RHO"), "{err}");
    assert!(err.contains("norho.comm:7:"), "{err}");
}

#[test]
fn gravity_on_beams_and_a_zero_direction_are_refused() {
    let err = refused(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA="END", PHENOMENE="MECANIQUE", MODELISATION="POU_D_E"))
weight = AFFE_CHAR_MECA(MODELE=model, PESANTEUR=_F(GRAVITE=10.0, DIRECTION=(0.0, 0.0, -1.0)))
FIN()
"#,
        "edge_strip.mail",
        "beam",
    );
    assert!(
        err.contains("not supported yet: AFFE_CHAR_MECA/PESANTEUR on cell S1, a POU_D_E beam"),
        "{err}"
    );
    assert!(err.contains("beam.comm:4:"), "{err}");
    let err = refused(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
weight = AFFE_CHAR_MECA(MODELE=model, PESANTEUR=_F(GRAVITE=10.0, DIRECTION=(0.0, 0.0, 0.0)))
FIN()
"#,
        "gravity_strip.mail",
        "zero",
    );
    assert!(err.contains("CHARGES2_53"), "{err}");
    assert!(err.contains("zero.comm:4:"), "{err}");
}

#[test]
fn edge_loads_off_segments_or_moments_on_solids_are_refused() {
    let err = refused(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA="COL", PHENOMENE="MECANIQUE", MODELISATION="3D"))
load = AFFE_CHAR_MECA(MODELE=model, FORCE_ARETE=_F(GROUP_MA="TOP", FZ=1.0))
FIN()
"#,
        "gravity_column.mail",
        "face",
    );
    assert!(
        err.contains("cell TOP1 is a QUAD4; FORCE_ARETE needs segments"),
        "{err}"
    );
    assert!(err.contains("face.comm:4:"), "{err}");
    let err = refused(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA="COL", PHENOMENE="MECANIQUE", MODELISATION="3D"))
load = AFFE_CHAR_MECA(MODELE=model, FORCE_ARETE=_F(GROUP_MA="TOPEDGES", MX=1.0))
FIN()
"#,
        "gravity_column.mail",
        "moment",
    );
    assert!(err.contains("AFFE_CHAR_MECA/FORCE_ARETE"), "{err}");
    assert!(err.contains("DRX"), "{err}");
}

#[test]
fn an_oblique_relation_of_the_coordinates_is_refused_with_its_location() {
    let err = refused(
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
f = FORMULE(NOM_PARA="X", VALE="1.0e-3 * X")
load = AFFE_CHAR_MECA_F(MODELE=model, LIAISON_OBLIQUE=_F(GROUP_MA="BASE", ANGL_NAUT=30.0, DY=f))
FIN()
"#,
        "oblique_block.mail",
        "oblx",
    );
    assert!(
        err.contains(
            "not supported yet: AFFE_CHAR_MECA_F/LIAISON_OBLIQUE/DY as a function of X (only functions of INST)"
        ),
        "{err}"
    );
    assert!(err.contains("oblx.comm:5:"), "{err}");
}

#[test]
fn a_relation_given_by_two_occurrences_is_kept_once() {
    // Two LIAISON_GROUP occurrences tying the same pair (as two sections
    // sharing a line do): code_aster's ordlrl keeps the relation once;
    // twice, the system was singular.
    let dir = std::env::temp_dir().join(format!("aster-loads-more-dup-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("dup.comm");
    std::fs::write(
        &comm,
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
steel = DEFI_MATERIAU(ELAS=_F(E=1.0e7, NU=0.0, RHO=8000.0))
mater = AFFE_MATERIAU(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", MATER=steel))
tie = _F(GROUP_NO_1="MID", GROUP_NO_2="A", DDL_1="DX", DDL_2="DX", COEF_MULT_1=1.0, COEF_MULT_2=-1.0, COEF_IMPO=0.0)
held = AFFE_CHAR_MECA(MODELE=model, DDL_IMPO=(_F(GROUP_MA="BASE", DY=0.0), _F(GROUP_NO="A", DX=0.0)),
                      LIAISON_GROUP=(tie, tie))
weight = AFFE_CHAR_MECA(MODELE=model, PESANTEUR=_F(GRAVITE=10.0, DIRECTION=(0.0, 1.0, 0.0)))
res = MECA_STATIQUE(MODELE=model, CHAM_MATER=mater, EXCIT=(_F(CHARGE=held), _F(CHARGE=weight)))
TEST_RESU(RESU=_F(NUME_ORDRE=1, RESULTAT=res, NOM_CHAM="DEPL", GROUP_NO="TIP", NOM_CMP="DY",
                  VALE_CALC=0.4, VALE_REFE=0.4, REFERENCE="ANALYTIQUE", PRECISION=1.0e-3))
FIN()
"#,
    )
    .unwrap();
    // QUAD4 with nu = 0: the nodal values of a bar under its own weight
    // are exact (1D linear elements with the consistent load).
    let outcome = run(&comm, "gravity_strip.mail", "dup");
    let _ = std::fs::remove_dir_all(dir);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (2, 0));
}

/// FORCE_ARETE on the SEG3 edge of COQUE_3D cells (te0418, FPG4): forces
/// and moments per unit length, AFFE_CHAR_MECA_F of INST, against beam
/// theory and statics (comm/coque3d_edge.comm: 12 values x 2).
#[test]
fn forces_and_moments_on_the_edge_of_a_coque3d_strip() {
    assert_eq!(scene("coque3d_edge.comm", "coque3d_edge.mail"), (24, 0));
}

/// A SEG2 on the nodes of COQUE_3D cells gets no element in code_aster
/// (MEBOCQ3 is the SEG3 edge only): refused at its GROUP_MA, before
/// solving.
#[test]
fn an_edge_force_on_a_seg2_of_coque3d_cells_is_refused_at_its_group() {
    let text = scene::read("coque3d_edge.comm");
    let cut = text
        .find("RESE = MECA_STATIQUE")
        .expect("the scene's first solve");
    let mut variant = text[..cut].to_string();
    variant.push_str(
        "bad = AFFE_CHAR_MECA(MODELE=MO, FORCE_ARETE=_F(GROUP_MA=\"EDGE\", FZ=1.0))\nFIN()\n",
    );
    // The free end as a SEG2 cell.
    let mesh = scene::read("coque3d_edge.mail").replacen(
        "SEG3\n  E1 N16_0 N16_2 N16_1",
        "SEG2\n  E1 N16_0 N16_2",
        1,
    );
    assert!(mesh.contains("SEG2\n  E1"));
    let dir = scene::temp("coque3d-edge-seg2");
    let path = dir.join("strip_edge.mail");
    std::fs::write(&path, mesh).unwrap();
    let (ok, nook, err) = scene::run_on(&variant, path.to_str().unwrap(), "coque3d-edge-seg2");
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("an error");
    assert!(
        err.contains("SEG2 on the nodes of COQUE_3D cells")
            && err.contains("MEBOCQ3")
            && err.contains("case.comm:"),
        "{err}"
    );
}
