//! `RECH_LINEAIRE` in MECA_NON_LINE with a DEFI_CONT contact on the
//! project's scene `comm/line_search_defi_cont.comm`: two plastic blocks
//! (VMIS_ISOT_TRAC with five knees) pressed together through a Lagrangian
//! or a penalised mortar contact, with and without the line search (CORDE,
//! MIXTE), against the uniaxial closed form to 1e-9; and the Newton path:
//! the line search scales the first correction of the step that crosses
//! four knees, which then converges in fewer iterations.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs the scene with its progress written to a `.mess` file; gives the
/// outcome and that file's text.
fn run_scene() -> (aster_run::program::Outcome, String) {
    let dir = std::env::temp_dir().join(format!("aster-lsdefi-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut case = aster_run::program::prepare(
        &root().join("comm/line_search_defi_cont.comm"),
        Some(&root().join("comm/dc3d_blocks.mail")),
        &dir,
    )
    .unwrap();
    let mess = dir.join("lsdefi.mess");
    case.report_files.push(mess.clone());
    case.mess = Some(mess.clone());
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let text = std::fs::read_to_string(&mess).unwrap_or_default();
    let _ = std::fs::remove_dir_all(dir);
    (outcome, text)
}

/// The Newton iterations of each instant, per MECA_NON_LINE, from the
/// progress ("instant … converged in N Newton iteration(s)" lines, the
/// command's line after them).
fn iterations(mess: &str) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut current = Vec::new();
    for line in mess.lines() {
        if let Some(rest) = line.split("converged in ").nth(1) {
            let n = rest.split_whitespace().next().unwrap().parse().unwrap();
            current.push(n);
        } else if line.contains("MECA_NON_LINE") && !current.is_empty() {
            out.push(std::mem::take(&mut current));
        }
    }
    out
}

#[test]
fn line_search_with_defi_cont_matches_the_closed_form_on_a_shorter_path() {
    let (outcome, mess) = run_scene();
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    // Six analyses × three instants × (DZ ×3, DX, SIZZ ×2, and LAGS_C
    // with the Lagrangian contact): each value and its analytic reference.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (234, 0));
    let its = iterations(&mess);
    assert_eq!(its.len(), 6, "{mess}");
    // Per contact: no search, CORDE, MIXTE.
    for runs in its.chunks(3) {
        let (plain, corde, mixte) = (&runs[0], &runs[1], &runs[2]);
        assert_eq!(plain.len(), 3);
        // t = 2 crosses four knees: the scaled correction saves iterations.
        assert!(corde[1] < plain[1], "{its:?}");
        assert!(mixte[1] < plain[1], "{its:?}");
    }
}
