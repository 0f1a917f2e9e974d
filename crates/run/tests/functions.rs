//! The project's functions-and-tables scene (comm/functions.comm on
//! comm/strip.mail): RECU_FONCTION, CALC_FONCTION (COMB, INTEGRE),
//! CALC_FONC_INTERP, CREA_TABLE, CALC_TABLE, TEST_FONCTION against analytic values, and
//! IMPR_FONCTION's XMGRACE file on a unit named by DEFI_FICHIER.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn functions_and_tables_pass_and_the_curves_are_written() {
    let out = std::env::temp_dir().join(format!("aster-functions-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/functions.comm"),
        Some(&root().join("comm/strip.mail")),
        &out,
    )
    .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (16, 0));
    let agr = std::fs::read_to_string(out.join("curves.agr")).unwrap();
    assert!(agr.contains("@title \"strip\""), "{agr}");
    assert!(
        agr.contains("@target G0.S1\n@type xy\n1.0 10.0\n2.0 40.0\n3.0 90.0\n&"),
        "{agr}"
    );
    assert!(agr.contains("0.5 0.0004999999999999"), "{agr}");
    let _ = std::fs::remove_dir_all(out);
}
