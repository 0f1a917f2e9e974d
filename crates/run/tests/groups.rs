//! The project's geometric-groups scene (comm/groups.comm on
//! comm/strip.mail): PLAN, ENV_SPHERE, SEGM_DROI_ORDO and NOEUD_ORDO node
//! groups carry the conditions of an exact tension test; ORIE_LIGNE,
//! CREA_CHAMP AFFE + MODI_MAILLAGE DEFORME and ECHELLE change the written mesh.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn geometric_groups_carry_the_tension_test() {
    let out = std::env::temp_dir().join(format!("aster-groups-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/groups.comm"),
        Some(&root().join("comm/strip.mail")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (12, 0));
    // ORIE_LIGNE: the left edge now starts at A = (0, 0) and goes up.
    let mesh = aster_mesh::read_mail(&out.join("fort.71")).unwrap();
    let left = mesh.group_ma("LEFT").unwrap().members[0];
    let ends: Vec<[f64; 3]> = mesh
        .cell(left)
        .nodes
        .iter()
        .map(|n| mesh.coord(*n))
        .collect();
    assert_eq!(ends, vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    // Moved by DX = 0.5, then scaled by 2.
    let moved = aster_mesh::read_mail(&out.join("fort.72")).unwrap();
    let left = moved.group_ma("LEFT").unwrap().members[0];
    let ends: Vec<[f64; 3]> = moved
        .cell(left)
        .nodes
        .iter()
        .map(|n| moved.coord(*n))
        .collect();
    assert_eq!(ends, vec![[1.0, 0.0, 0.0], [1.0, 2.0, 0.0]]);
    let _ = std::fs::remove_dir_all(out);
}
