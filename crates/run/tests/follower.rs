//! Follower pressures (`EXCIT/TYPE_CHARGE='SUIV'`) and differential
//! Dirichlet conditions (`TYPE_CHARGE='DIDI'`) in STAT_NON_LINE, on the
//! project's thick ring (comm/follower_ring.comm: Lamé's solution with the
//! pressure on the current inner radius, REAC_NODA balancing the pressure
//! on the current circle, a radial displacement imposed relative to the
//! initial state), and the refusals, located, of what is not executed.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-follower-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(case: &Path, mesh: &Path, name: &str) -> (aster_run::program::Outcome, String) {
    let out = temp(name);
    let prepared = aster_run::program::prepare(case, Some(mesh), &out).unwrap();
    let report = out.join("report.txt");
    let file = std::fs::File::create(&report).unwrap();
    let outcome = aster_run::program::run(&prepared, Box::new(file));
    let text = std::fs::read_to_string(&report).unwrap_or_default();
    let _ = std::fs::remove_dir_all(&out);
    (outcome, text)
}

/// The ring scene with `edits` applied.
fn ring(edits: &[(&str, &str)], name: &str) -> (aster_run::program::Outcome, String) {
    let dir = temp(&format!("{name}-src"));
    let mut text = std::fs::read_to_string(root().join("comm/follower_ring.comm")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    let comm = dir.join("case.comm");
    std::fs::write(&comm, text).unwrap();
    let r = run(&comm, &root().join("comm/follower_ring.mail"), name);
    let _ = std::fs::remove_dir_all(dir);
    r
}

fn error(outcome: &aster_run::program::Outcome) -> String {
    format!("{:?}", outcome.error)
}

#[test]
fn the_ring_follows_lame_with_the_pressure_on_the_current_radius() {
    let (outcome, report) = ring(&[], "ring");
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (18, 0), "{report}");
}

#[test]
fn a_dead_pressure_misses_the_follower_solution() {
    // Without SUIV the first run is the dead load's: u_A = p K, 19 % below
    // the follower answer; the four DEPL checks and the reaction fail
    // (analytic and non-regression), the rest holds.
    let (outcome, report) = ring(
        &[(
            "_F(CHARGE=PRES, FONC_MULT=RAMP, TYPE_CHARGE=\"SUIV\")",
            "_F(CHARGE=PRES, FONC_MULT=RAMP)",
        )],
        "dead",
    );
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (8, 10), "{report}");
}

#[test]
fn a_fixed_imposed_displacement_is_not_relative_to_the_initial_state() {
    // FIXE_CSTE instead of DIDI: the outer circle moves by d, not by
    // u_B + d; the three checks of the continued run fail.
    let (outcome, report) = ring(
        &[(
            "_F(CHARGE=OUT, FONC_MULT=RAMP2, TYPE_CHARGE=\"DIDI\")",
            "_F(CHARGE=OUT, FONC_MULT=RAMP2)",
        )],
        "fixe",
    );
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (12, 6), "{report}");
}

#[test]
fn what_a_follower_load_does_not_cover_is_refused_at_its_keyword() {
    // A follower load with a nodal force in it.
    let (outcome, _) = ring(
        &[(
            "PRES_REP=_F(GROUP_MA=\"INNER\", PRES=P))",
            "PRES_REP=_F(GROUP_MA=\"INNER\", PRES=P), FORCE_NODALE=_F(GROUP_NO=\"PB\", FX=1.0))",
        )],
        "mixed",
    );
    let e = error(&outcome);
    assert!(
        e.contains("TYPE_CHARGE='SUIV' on a load with other things than PRES_REP")
            && e.contains("case.comm:49:"),
        "{e}"
    );
    assert_eq!(outcome.tally.ok + outcome.tally.nook, 0);
    // A pressure of the current coordinates in a dead load.
    let (outcome, _) = ring(
        &[
            (
                "PRES = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA=\"INNER\", PRES=P))",
                "FP = DEFI_FONCTION(NOM_PARA=\"XF\", VALE=(0.0, 100.0, 3.0, 100.0))\nPRES = AFFE_CHAR_MECA_F(MODELE=MO, PRES_REP=_F(GROUP_MA=\"INNER\", PRES=FP))",
            ),
            (
                "_F(CHARGE=PRES, FONC_MULT=RAMP, TYPE_CHARGE=\"SUIV\")",
                "_F(CHARGE=PRES, FONC_MULT=RAMP)",
            ),
        ],
        "xf-dead",
    );
    let e = error(&outcome);
    assert!(
        e.contains("a PRES_REP function of the current coordinates XF, YF, ZF")
            && e.contains("case.comm:"),
        "{e}"
    );
}

#[test]
fn a_pressure_of_the_current_coordinates_follows_the_body() {
    // The pressure given as a function of XF, constant over the ring's
    // current extent: the same answers as the constant pressure.
    let (outcome, report) = ring(
        &[(
            "PRES = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA=\"INNER\", PRES=P))",
            "FP = DEFI_FONCTION(NOM_PARA=\"XF\", VALE=(-1.0, 100.0, 3.0, 100.0))\nPRES = AFFE_CHAR_MECA_F(MODELE=MO, PRES_REP=_F(GROUP_MA=\"INNER\", PRES=FP))",
        )],
        "xf",
    );
    // The dead run (2) and its continuation (3) cannot take a function of
    // XF: the first run's checks are made before the refusal.
    let e = error(&outcome);
    assert!(e.contains("XF, YF, ZF"), "{e}\n{report}");
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (10, 0), "{report}");
}
