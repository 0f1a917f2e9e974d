//! Modal analysis (CALC_MATR_ELEM, NUME_DDL, ASSE_MATRICE, ASSEMBLAGE,
//! CALC_MODES, NORM_MODE): the project's scene comm/modal_bar.comm against
//! the closed forms of a clamped-free bar and an Euler–Bernoulli
//! cantilever, and the refusals, located at their keyword.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &Path, tag: &str) -> aster_run::program::Outcome {
    let out = std::env::temp_dir().join(format!("aster-modal-{tag}-{}", std::process::id()));
    let mesh = root().join("comm").join("modal_bar.mail");
    let case = aster_run::program::prepare(comm, Some(&mesh), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(out);
    outcome
}

/// The scene's program with `edit` applied, run; its error message.
fn edited(tag: &str, edit: impl Fn(&str) -> String) -> aster_run::program::Outcome {
    let text = std::fs::read_to_string(root().join("comm/modal_bar.comm")).unwrap();
    let dir = std::env::temp_dir().join(format!("aster-modal-src-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join(format!("{tag}.comm"));
    std::fs::write(&comm, edit(&text)).unwrap();
    let outcome = run(&comm, tag);
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

#[test]
fn bar_and_cantilever_frequencies_shapes_and_norms() {
    // Axial: 3 frequencies, DX at B (+1, vpnorx) and at M (sin π/4);
    // bending: 3 frequencies (NUME_MODE), MASS_GENE = 1 after NORM_MODE;
    // each check NON_REGRESSION and ANALYTIQUE.
    let outcome = run(&root().join("comm/modal_bar.comm"), "scene");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (18, 0));
}

#[test]
fn a_wrong_frequency_is_a_nook() {
    // The check can fail: the second axial frequency is not the first's.
    let outcome = edited("nook", |t| {
        t.replacen(
            "VALE_CALC=1946.9048892873318",
            "VALE_CALC=648.6348283881513",
            1,
        )
    });
    assert!(outcome.tally.nook >= 1);
}

#[test]
fn a_buckling_problem_is_refused_at_its_keyword() {
    let outcome = edited("flamb", |t| {
        t.replacen(
            "CALC_MODES(MATR_RIGI=K, MATR_MASS=M,",
            "CALC_MODES(TYPE_RESU='MODE_FLAMB', MATR_RIGI=K, MATR_RIGI_GEOM=M, CALC_CHAR_CRIT=_F(NMAX_CHAR_CRIT=3),",
            1,
        )
        .replacen(", CALC_FREQ=_F(NMAX_FREQ=3))", ")", 1)
    });
    let err = outcome.error.expect("refused").message;
    assert!(err.contains("TYPE_RESU"), "{err}");
    assert!(err.contains("flamb.comm:"), "{err}");
}

#[test]
fn a_mode_of_a_repeated_eigenvalue_has_no_components_to_test() {
    // Blocking nothing but the clamped end makes the bending in XY and XZ
    // the same eigenvalue: its modes' components are the solver's choice.
    let outcome = edited("repeated", |t| {
        t.replacen(
            "_F(GROUP_MA=\"BAR\", DX=0.0, DZ=0.0, DRX=0.0, DRY=0.0),\n        _F(GROUP_NO=\"A\", DY=0.0, DRZ=0.0),",
            "_F(GROUP_NO=\"A\", DX=0.0, DY=0.0, DZ=0.0, DRX=0.0, DRY=0.0, DRZ=0.0),",
            1,
        )
        .replacen(
            "            NUME_ORDRE=1,\n            PARA=\"MASS_GENE\",",
            "            NUME_ORDRE=1,\n            NOM_CHAM=\"DEPL\",\n            GROUP_NO=\"B\",\n            NOM_CMP=\"DY\",",
            1,
        )
    });
    let err = outcome.error.expect("refused").message;
    assert!(err.contains("repeated"), "{err}");
}

/// comm/modal_ajuste.comm (with its mesh) after `edit`.
fn ajuste(tag: &str, edit: impl Fn(&str) -> String) -> aster_run::program::Outcome {
    let text = std::fs::read_to_string(root().join("comm/modal_ajuste.comm")).unwrap();
    let dir = std::env::temp_dir().join(format!("aster-ajuste-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join(format!("{tag}.comm"));
    std::fs::write(&comm, edit(&text)).unwrap();
    let out = dir.join("out");
    let mesh = root().join("comm/modal_ajuste.mail");
    let case = aster_run::program::prepare(&comm, Some(&mesh), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

#[test]
fn ajuste_filtre_mode_and_modal_energies_match_the_closed_forms() {
    // AJUSTE (2 frequencies, 4 energies per cell against the clamped-free
    // bar's mode), BANDE over 3 frequencies with FILTRE_MODE (4
    // frequencies, 2 effective masses): each check NON_REGRESSION and
    // ANALYTIQUE.
    let outcome = ajuste("scene", |t| t.to_string());
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (24, 0));
}

#[test]
fn nmax_freq_caps_the_modes_of_the_band() {
    // NMAX_FREQ=2 of three modes in the band: there is no third.
    let outcome = ajuste("nmax", |t| {
        t.replacen(
            "            NUME_MODE=2,\n            PARA=\"FREQ\",\n            VALE_CALC=1946.9048892873318,",
            "            NUME_MODE=3,\n            PARA=\"FREQ\",\n            VALE_CALC=1946.9048892873318,",
            1,
        )
    });
    assert!(
        outcome.error.is_some() || outcome.tally.nook >= 1,
        "a third mode was found"
    );
}

#[test]
fn filtre_mode_drops_the_modes_below_its_threshold() {
    // Without the filter the third mode is the third bending one, not the
    // axial one: a NOOK.
    let outcome = ajuste("nofilter", |t| {
        t.replacen(
            "    FILTRE_MODE=_F(CRIT_EXTR=\"MASS_EFFE_UN\", SEUIL=0.1),\n",
            "",
            1,
        )
    });
    assert!(outcome.tally.nook >= 1, "{:?}", outcome.error);
}

#[test]
fn another_option_on_modes_is_refused_at_its_keyword() {
    let outcome = ajuste("sief", |t| {
        t.replacen(
            "ENERGIE=(\"ECIN_ELEM\", \"EPOT_ELEM\"))",
            "ENERGIE=(\"ECIN_ELEM\", \"EPOT_ELEM\"), CONTRAINTE=\"SIEF_ELGA\")",
            1,
        )
    });
    let err = outcome.error.expect("refused").message;
    assert!(
        err.contains("SIEF_ELGA") && err.contains("sief.comm:"),
        "{err}"
    );
}
