//! The project's results scene (comm/results.comm on comm/strip.mail):
//! ASSE_MAILLAGE SUPERPOSE, a field of functions evaluated on the geometry,
//! CREA_RESU AFFE (new and reuse=), RECU_TABLE and POST_ELEM ENER_POT
//! against the exact energy of a uniform strain.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn results_built_by_hand_and_superposed_meshes() {
    let out = std::env::temp_dir().join(format!("aster-results-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/results.comm"),
        Some(&root().join("comm/strip.mail")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (10, 0));
    // The superposed mesh written on unit 30: 16 nodes, 12 cells, each
    // group of the second copy renamed.
    let m = aster_mesh::read_mail(&out.join("fort.30")).unwrap();
    assert_eq!((m.node_count(), m.cells.len()), (16, 12));
    assert_eq!(m.cell_names[6], "M7");
    let left: Vec<&str> = m
        .groups_ma
        .iter()
        .map(|g| g.name.as_str())
        .filter(|n| n.starts_with("LEFT"))
        .collect();
    assert_eq!(left, ["LEFT", "LEFT___0"]);
    assert_eq!(m.group_ma("LEFT___0").unwrap().members[0].0, 9);
    let _ = std::fs::remove_dir_all(out);
}
