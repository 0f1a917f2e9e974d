//! Errors a program catches by code_aster's message id (comm/raised_errors
//! .comm on comm/two_plates.mail): `except CA.AsterError as err` sees
//! `err.id_message` — CONTACT_93 when a checked contact zone with
//! STOP_INTERP='OUI' interpenetrates, MECANONLINE9_7 when Newton runs out
//! of iterations with no step cutting left — and an error whose id aster
//! does not know is not caught: it stops the run, saying so. CONTACT1_3
//! when a Nitsche slave skin has no volume cell under it.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &Path, mesh: &Path, tag: &str) -> aster_run::program::Outcome {
    let out = std::env::temp_dir().join(format!("aster-raised-{tag}-{}", std::process::id()));
    let case = aster_run::program::prepare(comm, Some(mesh), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    outcome
}

#[test]
fn the_handlers_see_code_aster_message_ids() {
    let outcome = run(
        &root().join("comm/raised_errors.comm"),
        &root().join("comm/two_plates.mail"),
        "scene",
    );
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (4, 0));
}

/// comm/nitsche_no_volume.comm: DEFI_CONT stops with CONTACT1_3 on a
/// Nitsche slave skin with no volume cell under it (cells of its own, or
/// inside the volume), and accepts the skin of a volume.
#[test]
fn a_nitsche_skin_without_volume_raises_contact1_3() {
    let outcome = run(
        &root().join("comm/nitsche_no_volume.comm"),
        &root().join("comm/nitsche_no_volume.mail"),
        "nitsche",
    );
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (5, 0));
}

#[test]
fn an_error_without_a_known_id_is_not_caught() {
    let dir = std::env::temp_dir().join(format!("aster-raised-unknown-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join("unknown.comm");
    std::fs::write(
        &comm,
        "DEBUT()\nseen = 0\ntry:\n    m = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=99)\nexcept CA.AsterError as err:\n    seen = 1\nFIN()\n",
    )
    .unwrap();
    let outcome = run(&comm, &root().join("comm/two_plates.mail"), "unknown");
    let _ = std::fs::remove_dir_all(&dir);
    let e = outcome.error.expect("the error stops the run");
    assert!(
        e.message.contains("LIRE_MAILLAGE: no file for unit 99"),
        "{e}"
    );
    assert!(
        e.message
            .contains("aster does not know the id code_aster gives this error"),
        "{e}"
    );
}
