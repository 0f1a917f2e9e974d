//! The project's CALC_PRESSION scene (comm/pressure.comm on
//! comm/strip.mail): the normal stress on both vertical edges of a strip in
//! uniform tension, and no shear.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn pressure_on_the_edges_of_a_strip_in_tension() {
    let out = std::env::temp_dir().join(format!("aster-pressure-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/pressure.comm"),
        Some(&root().join("comm/strip.mail")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (16, 0));
    let listing = std::fs::read_to_string(out.join("fort.73")).unwrap();
    assert!(
        listing.contains("CHAMP AUX NOEUDS DE NOM SYMBOLIQUE  PRES_NOEU"),
        "{listing}"
    );
    assert!(
        listing.contains(&format!("NOEUD     {:>21}\n", "PRES")),
        "{listing}"
    );
    let row = listing
        .lines()
        .find(|l| l.starts_with("N7 "))
        .expect("a line for B = N7");
    let value: f64 = row[9..].trim().parse().unwrap();
    assert!((value - 100.0).abs() < 1e-9, "{row}");
    assert_eq!(
        listing
            .lines()
            .filter(|l| l.starts_with('N') && !l.starts_with("NO") && !l.starts_with("NU"))
            .count(),
        1
    );
    assert!(!listing.contains("CISA"), "{listing}");
    let msh = std::fs::read_to_string(out.join("fort.74")).unwrap();
    assert!(
        msh.starts_with("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n"),
        "{msh}"
    );
    // 2 QUAD4 and 2 SEG2 cells; one view, DX at the 6 nodes; B = N7 is
    // node 6 of the restricted mesh, DX(B) = 1e-3.
    assert!(msh.contains("$Elements\n4\n1 3 2 0 0 1 2 5 4\n"), "{msh}");
    assert!(
        msh.contains("\"resu_DEPL_DX\"\n1\n1.0\n3\n1\n1\n6\n"),
        "{msh}"
    );
    let b = msh
        .lines()
        .find(|l| l.starts_with("6 0.00"))
        .expect("DX of node 6");
    let dx: f64 = b[2..].parse().unwrap();
    assert!((dx - 1e-3).abs() < 1e-12, "{b}");
    // A second run into the same directory starts the listing afresh (as
    // code_aster does), rather than appending to the first run's.
    let again = aster_run::program::run(&case, Box::new(std::io::sink()));
    assert!(again.error.is_none(), "{:?}", again.error);
    assert_eq!(
        std::fs::read_to_string(out.join("fort.73")).unwrap(),
        listing
    );
    let _ = std::fs::remove_dir_all(out);
}
