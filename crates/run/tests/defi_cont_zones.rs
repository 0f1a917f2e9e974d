//! Zones of different methods in one DEFI_CONT (code_aster 17 gives every
//! zone its own `ContactParameter`): comm/two_zones_methods.comm, three
//! plates stacked on non-matching meshes, one interface Lagrangian and the
//! other penalised, then swapped — every TEST_RESU against the analytic
//! state (LAGS_C = −p on the Lagrangian zone, the penalised one
//! interpenetrating by p h_F / COEF_CONT) at 1e-6; and zones sharing slave
//! nodes stopped at the zone as code_aster's CONTACT1_1.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &str, name: &str) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-zones-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.comm"));
    std::fs::write(&file, comm).unwrap();
    let case = aster_run::program::prepare(
        &file,
        Some(&root().join("comm/two_zones_methods.mail")),
        &dir,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

fn scene() -> String {
    std::fs::read_to_string(root().join("comm/two_zones_methods.comm")).unwrap()
}

#[test]
fn a_lagrangian_and_a_penalised_zone_in_one_definition() {
    let outcome = run(&scene(), "methods");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    // 2 definitions: 8 and 7 values, each checked twice (non-regression
    // and analytic).
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (30, 0));
}

/// code_aster stops a definition whose zones share slave nodes, whatever
/// their methods (`ContactNew::build`, CONTACT1_1).
#[test]
fn zones_sharing_slave_nodes_stop_as_code_aster() {
    let comm = scene().replacen(
        r#"_F(GROUP_MA_ESCL="C_BOT", GROUP_MA_MAIT="B_TOP", ALGO_CONT="PENALISATION""#,
        r#"_F(GROUP_MA_ESCL="B_BOT", GROUP_MA_MAIT="A_TOP", ALGO_CONT="PENALISATION""#,
        1,
    );
    assert_ne!(comm, scene(), "the scene's zone 2 moved");
    let outcome = run(&comm, "shared");
    let e = outcome.error.expect("must be refused").to_string();
    assert!(
        e.contains("shares nodes with B_BOT of zone 1") && e.contains("shared.comm:46:"),
        "{e}"
    );
    assert_eq!(outcome.tally.ok + outcome.tally.nook, 0, "nothing ran: {e}");
    // The same with one method for both zones.
    let same = comm.replacen(r#", ALGO_CONT="PENALISATION", COEF_CONT=1.0e3"#, "", 1);
    assert_ne!(same, comm);
    let e = run(&same, "same").error.expect("must stop").to_string();
    assert!(e.contains("shares nodes with B_BOT of zone 1"), "{e}");
}
