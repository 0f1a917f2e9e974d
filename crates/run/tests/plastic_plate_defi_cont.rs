//! `RELATION='VMIS_ISOT_NL'` with code_aster 17's mortar contact
//! (DEFI_CONT + MECA_NON_LINE) on the project's scene
//! `comm/plastic_plate_defi_cont.comm`: a plate pressed onto a rigid
//! support with non-matching nodes, elastic then plastic (p from
//! R(p) = P by bisection in the command file): LAGS_C = −P at every slave
//! node and the top displacement −P/E − p, 30 checks against the closed
//! form (measured ≤ 2e-12 relative).

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn a_plastic_plate_pressed_by_a_defi_cont_contact_matches_the_closed_form() {
    let out = std::env::temp_dir().join(format!("aster-plastic-defi-cont-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/plastic_plate_defi_cont.comm"),
        Some(&root().join("comm/plastic_plate.mail")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (30, 0));
}
