//! The project's post-processing tail scene (comm/post_tail.comm on
//! comm/strip.mail): STAT_NON_LINE from a stress-free rigid ETAT_INIT/DEPL,
//! POST_RELEVE_T OPERATION='MOYENNE_ARITH' (code_aster's divisor: every
//! selected node) and POST_ERREUR OPTION='LAGR_RELA' against exact L2 norms;
//! and the refusal of an initial displacement that strains the structure.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &Path, out: &Path) -> (aster_run::program::Outcome, String) {
    let case =
        aster_run::program::prepare(comm, Some(&root().join("comm/strip.mail")), out).unwrap();
    let report = out.join("report.txt");
    std::fs::create_dir_all(out).unwrap();
    let file = std::fs::File::create(&report).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(file));
    let text = std::fs::read_to_string(&report).unwrap_or_default();
    (outcome, text)
}

/// The real number of a table's row (IMPR_TABLE text) starting with `first`,
/// in the column `col` (0-based, blank-separated).
fn cell(report: &str, first: &str, col: usize) -> f64 {
    let line = report
        .lines()
        .find(|l| l.starts_with(first))
        .unwrap_or_else(|| panic!("no row {first} in {report}"));
    line.split_whitespace().nth(col).unwrap().parse().unwrap()
}

#[test]
fn initial_rigid_displacement_arithmetic_mean_and_pressure_error() {
    let out = std::env::temp_dir().join(format!("aster-post-tail-{}", std::process::id()));
    let (outcome, report) = run(&root().join("comm/post_tail.comm"), &out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (16, 0), "{report}");
    // MOYENNE_ARITH of DX over the 6 nodes at INST 1: 0.501; of LAGS_C over
    // LEFT, given on one node of two: 3 / 2.
    assert!(
        (cell(&report, "mean DX", 7) - 0.501).abs() < 1e-5,
        "{report}"
    );
    assert!(
        (cell(&report, "mean LAGS_C", 4) - 1.5).abs() < 1e-5,
        "{report}"
    );
    // POST_ERREUR: DIFFERENCE 1, REFERENCE sqrt(7), relative 1/sqrt(7).
    assert!((cell(&report, "TOTAL", 1) - 1.0).abs() < 1e-5);
    assert!((cell(&report, "TOTAL", 2) - 7f64.sqrt()).abs() < 1e-5);
    assert!((cell(&report, "TOTAL", 3) - 7f64.powf(-0.5)).abs() < 1e-5);
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn an_initial_displacement_that_strains_is_refused_at_its_keyword() {
    let dir = std::env::temp_dir().join(format!("aster-post-tail-strain-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // u0 = (1e-3 x, 0): a uniform strain, which code_aster would count from
    // (stress-free) and aster's total elastic stresses would not.
    let text = std::fs::read_to_string(root().join("comm/post_tail.comm"))
        .unwrap()
        .replace(
            "AFFE=_F(TOUT=\"OUI\", NOM_CMP=(\"DX\", \"DY\"), VALE=(0.5, 0.0)),",
            "AFFE=(_F(TOUT=\"OUI\", NOM_CMP=(\"DX\", \"DY\"), VALE=(0.0, 0.0)), _F(GROUP_NO=\"D\", NOM_CMP=\"DX\", VALE=1.0e-3)),",
        );
    let comm = dir.join("strained.comm");
    std::fs::write(&comm, text).unwrap();
    let (outcome, _) = run(&comm, &dir.join("out"));
    let error = outcome.error.expect("refused").message;
    assert!(
        error.contains(
            "not supported yet: ETAT_INIT/DEPL with a displacement that strains the structure"
        ) && error.contains("strained.comm:44:18)"),
        "{error}"
    );
    let _ = std::fs::remove_dir_all(dir);
}
