//! Discrete contact on QUAD8 faces (comm/quad8_punch.comm on
//! comm/quad8_punch.mail, written for aster): two HEXA20 blocks pressed on
//! their QUAD8 faces. code_aster ties the faces' middle nodes to their
//! edges (`aster_contact::quad8`); the punch is then exact: DZ = -0.1 on
//! the interface and the consistent QUAD8 reactions (-F/12 at corners,
//! +F/3 at middles). Before the ties, the middle nodes were contact nodes
//! of their own and the interface moved by 0.072 instead of 0.1.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &str, name: &str) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-quad8-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.comm"));
    std::fs::write(&file, comm).unwrap();
    let case =
        aster_run::program::prepare(&file, Some(&root().join("comm/quad8_punch.mail")), &dir)
            .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

#[test]
fn quad8_punch_is_exact_with_code_asters_middle_node_ties() {
    let comm = std::fs::read_to_string(root().join("comm/quad8_punch.comm")).unwrap();
    let outcome = run(&comm, "punch");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (32, 0));
}

#[test]
fn penalised_contact_keeps_the_middle_nodes_free() {
    // code_aster's `quadco`: no ties under PENALISATION; the middle nodes
    // are contact nodes and the QUAD8 punch is no longer exact.
    let comm = std::fs::read_to_string(root().join("comm/quad8_punch.comm"))
        .unwrap()
        .replace(
            "ZONE=_F(GROUP_MA_MAIT=\"SLOW\", GROUP_MA_ESCL=\"SUP\")",
            "ZONE=_F(GROUP_MA_MAIT=\"SLOW\", GROUP_MA_ESCL=\"SUP\", ALGO_CONT=\"PENALISATION\", E_N=1e12)",
        );
    let outcome = run(&comm, "pena");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    // Corners carry no force at all (tension would be needed), middles
    // too much: every reaction and most displacements are off by > 1 %.
    assert!(outcome.tally.nook >= 24, "{:?}", outcome.tally);
}
