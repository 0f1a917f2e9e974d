//! The project's fracture scene (comm/crack_plate.comm on
//! comm/crack_plate.mail): G and K1 of a centre-cracked plate in plane
//! strain and plane stress against Feddersen's formula, G independent of the theta crown,
//! a uniform temperature that gives no K; and CALC_G refused where its
//! load terms would be needed.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &std::path::Path, tag: &str) -> aster_run::program::Outcome {
    let out = std::env::temp_dir().join(format!("aster-fracture-{tag}-{}", std::process::id()));
    let case = aster_run::program::prepare(comm, Some(&root().join("comm/crack_plate.mail")), &out)
        .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    outcome
}

#[test]
fn centre_cracked_plate_g_and_k1() {
    let outcome = run(&root().join("comm/crack_plate.comm"), "scene");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (47, 0));
}

#[test]
fn a_load_inside_the_crown_is_refused() {
    let text = std::fs::read_to_string(root().join("comm/crack_plate.comm")).unwrap();
    // A pressure on the lip, where theta is not zero.
    let text = text.replace(
        "PRES_REP=_F(GROUP_MA=\"TOP\", PRES=-SIGMA)",
        "PRES_REP=(_F(GROUP_MA=\"TOP\", PRES=-SIGMA), _F(GROUP_MA=\"LIP\", PRES=1.0))",
    );
    let dir = std::env::temp_dir().join(format!("aster-fracture-lip-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("lip.comm");
    std::fs::write(&comm, text).unwrap();
    let outcome = run(&comm, "lip");
    let err = outcome.error.expect("refused");
    assert!(
        err.to_string().contains("load inside the theta crown"),
        "{err}"
    );
    assert_eq!(outcome.tally.nook, 0);
    let _ = std::fs::remove_dir_all(dir);
}

/// comm/crack_front_3d.comm: DEFI_FOND_FISS on a straight 3D front (both
/// lips, the ends on free faces) and POST_K1_K2_K3's K1 against Feddersen's
/// formula (linear cells: 6.4 % low), K2 = K3 = 0, G from method 1's K.
#[test]
fn extruded_centre_crack_post_k1_k2_k3() {
    let comm = root().join("comm/crack_front_3d.comm");
    let out = std::env::temp_dir().join(format!("aster-fracture-3d-{}", std::process::id()));
    let case =
        aster_run::program::prepare(&comm, Some(&root().join("comm/crack_front_3d.mail")), &out)
            .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (20, 0));
}

/// comm/crack_front_calcg.comm: CALC_G OPTION='K' along a straight 3D
/// front (5 nodes, DISCRETISATION='LINEAIRE'): K1 within 0.05 % of
/// Feddersen's formula at the ends and the middle, K2 = K3 = 0, G_IRWIN;
/// the Legendre fields (DEGRE=2) give the same K1 at the middle.
#[test]
fn extruded_centre_crack_calc_g_k() {
    assert_eq!(calcg_scene("crack_front_calcg", "calcg-k"), (22, 0));
}

/// comm/crack_front_calcg_g.comm: CALC_G OPTION='G' along a straight 3D
/// front on HEXA8 cells: G 0.9 % below Irwin's value of Feddersen's K1,
/// the interaction integral's G_IRWIN within 1 % of it at the same
/// points; Legendre fields and NB_POINT_FOND on the front's nodes agree;
/// a pressure on the lips instead of the remote tension gives the same G
/// (superposition) through te0147's face term.
#[test]
fn extruded_centre_crack_calc_g_g_linear() {
    assert_eq!(calcg_scene("crack_front_calcg_g", "calcg-g"), (50, 0));
}

/// comm/crack_front_calcg_quad.comm: the same plate in HEXA20 (a SEG3
/// front of 9 nodes): G and K at every node with the middle nodes' theta
/// fields and the SEG3 smoothing, the Irwin relation within 0.4 %.
#[test]
fn extruded_centre_crack_calc_g_quadratic() {
    assert_eq!(calcg_scene("crack_front_calcg_quad", "calcg-quad"), (62, 0));
}

/// NB_POINT_FOND with Legendre fields (the catalog's condition; code_aster's
/// RUPTURE1_73), a linear front of 3 points (the end correction reads
/// before the first) and K with a pressure on the lips are refused, with
/// no NOOK.
#[test]
fn calc_g_3d_refusals() {
    let text = std::fs::read_to_string(root().join("comm/crack_front_calcg_g.comm")).unwrap();
    for (from, to, expected) in [
        (
            "DISCRETISATION=\"LEGENDRE\", DEGRE=0",
            "DISCRETISATION=\"LEGENDRE\", DEGRE=0, NB_POINT_FOND=3",
            "it applies only when (DISCRETISATION='LINEAIRE')",
        ),
        ("NB_POINT_FOND=5", "NB_POINT_FOND=3", "a front of 3 points"),
        // K with the lips loaded: te0147's K terms are not computed.
        (
            "RESULTAT=resu_lip,\n    OPTION=\"G\",",
            "RESULTAT=resu_lip,\n    OPTION=(\"G\", \"K\"),",
            "te0147's terms of K are not reproduced",
        ),
    ] {
        assert!(text.contains(from));
        let outcome = run_text(
            &text.replace(from, to),
            "comm/crack_front_calcg.mail",
            "calcg-refused",
        );
        let err = outcome.error.expect("refused");
        assert!(err.to_string().contains(expected), "{err}");
        assert_eq!(outcome.tally.nook, 0);
    }
}

/// A front whose segments do not chain from the origin is refused before
/// any K is computed, located at DEFI_FOND_FISS.
#[test]
fn a_front_not_from_its_origin_is_refused() {
    let text = std::fs::read_to_string(root().join("comm/crack_front_3d.comm")).unwrap();
    let text = text.replace("GROUP_NO_EXTR=\"EXTR\"", "GROUP_NO_EXTR=\"ORIG\"");
    let dir = std::env::temp_dir().join(format!("aster-fracture-3dx-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("front.comm");
    std::fs::write(&comm, text).unwrap();
    let case =
        aster_run::program::prepare(&comm, Some(&root().join("comm/crack_front_3d.mail")), &dir)
            .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let err = outcome.error.expect("refused");
    assert!(
        err.to_string().contains("does not end at GROUP_NO_EXTR"),
        "{err}"
    );
    assert_eq!(outcome.tally.nook, 0);
    let _ = std::fs::remove_dir_all(dir);
}

/// Runs comm/NAME.comm on comm/crack_front_calcg.mail: its (OK, NOOK)
/// tally, the run without error.
fn calcg_scene(name: &str, tag: &str) -> (usize, usize) {
    let text = std::fs::read_to_string(root().join(format!("comm/{name}.comm"))).unwrap();
    let outcome = run_text(&text, "comm/crack_front_calcg.mail", tag);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    (outcome.tally.ok, outcome.tally.nook)
}

/// Runs a command text on a mesh of comm/ in a directory of its own.
fn run_text(text: &str, mesh: &str, tag: &str) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("case.comm");
    std::fs::write(&comm, text).unwrap();
    let case = aster_run::program::prepare(&comm, Some(&root().join(mesh)), &dir).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

fn quarter(text: &str, tag: &str) -> aster_run::program::Outcome {
    run_text(text, "comm/quarter_points.mail", &format!("quarter-{tag}"))
}

fn quarter_scene() -> String {
    std::fs::read_to_string(root().join("comm/quarter_points.comm")).unwrap()
}

/// comm/quarter_points.comm: MODI_MAILLE/NOEUD_QUART moves the mid-edge
/// nodes leaving the tip to the quarter points (code_aster's momaba), and
/// the moved cells still pass the patch test within 1e-9.
#[test]
fn noeud_quart_moves_the_mid_nodes_next_to_the_tip() {
    let outcome = quarter(&quarter_scene(), "scene");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (22, 0));
    // Without the modification the quarter-point checks fail.
    let scene = quarter_scene();
    let start = scene.find("mesh = MODI_MAILLAGE(").unwrap();
    let end = start + scene[start..].find("\n)\n").unwrap() + 3;
    let text = format!("{}{}", &scene[..start], &scene[end..]);
    assert!(!text.contains("MODI_MAILLAGE("));
    let outcome = quarter(&text, "unmoved");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert!(outcome.tally.nook >= 6, "{:?}", outcome.tally);
}

/// A plane mesh's crack tip is a node: GROUP_MA_FOND is code_aster's
/// ALGORITH6_16 error, named at the command.
#[test]
fn noeud_quart_by_cells_on_a_plane_mesh_is_an_error() {
    let text = quarter_scene().replace("GROUP_NO_FOND=\"TIP\"", "GROUP_MA_FOND=\"BOTTOM\"");
    let outcome = quarter(&text, "cells2d");
    let err = outcome.error.expect("an error").to_string();
    assert!(
        err.contains("ALGORITH6_16") && err.contains("GROUP_NO_FOND"),
        "{err}"
    );
    assert_eq!(outcome.tally.ok + outcome.tally.nook, 0);
}

/// comm/crack_front_quad.comm: the plate of comm/crack_front_3d.comm made
/// quadratic (LINE_QUAD) with quarter-point cells at its SEG3 front: the
/// rows are the cells' ends in order with their abscissa, K1 1.3 % above
/// Feddersen's value, K2 = K3 = 0.
#[test]
fn quadratic_front_post_k1_k2_k3() {
    let comm = root().join("comm/crack_front_quad.comm");
    let out = std::env::temp_dir().join(format!("aster-crackquad-{}", std::process::id()));
    let case =
        aster_run::program::prepare(&comm, Some(&root().join("comm/crack_front_3d.mail")), &out)
            .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(&out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (29, 0));
    // Without the quarter points the jump is not singular: K1 falls out
    // of the analytic tolerance.
    let text = std::fs::read_to_string(&comm).unwrap();
    let start = text.find("mesh = MODI_MAILLAGE(").unwrap();
    let end = start + text[start..].find("\n)\n").unwrap() + 3;
    let plain = format!("{}{}", &text[..start], &text[end..]);
    let dir = std::env::temp_dir().join(format!("aster-crackquad-plain-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("plain.comm");
    std::fs::write(&file, plain).unwrap();
    let case =
        aster_run::program::prepare(&file, Some(&root().join("comm/crack_front_3d.mail")), &dir)
            .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(&dir);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert!(outcome.tally.nook >= 3, "{:?}", outcome.tally);
}
