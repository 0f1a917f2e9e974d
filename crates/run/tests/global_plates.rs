//! The project's scene of DKTG and Q4GG plates (comm/global_plates.comm on
//! comm/dkt_strips.mail): the facets whose behaviour is integrated on the
//! generalised strains (`te0409`), with ELAS, in STAT_NON_LINE against the
//! closed forms of an eccentric strip — their SIEF_ELGA is the generalised
//! efforts, a DKTG's without shear force — and the plates' elastic energy
//! (ENEL_ELEM, `te0412`) by the non-linear and the linear paths; then what
//! stays refused.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/dkt_strips.mail", &format!("global-{tag}"))
}

fn plates() -> String {
    scene::read("global_plates.comm")
}

fn edit(from: &str, to: &str) -> String {
    let t = plates();
    assert!(t.contains(from), "the edit applies: {from}");
    t.replacen(from, to, 1)
}

#[test]
fn global_plates_match_the_eccentric_strip() {
    assert_eq!(run(&plates(), "plates"), (30, 0, None));
}

/// Without the offset the tension no longer bends the Q4GG strip, nor does
/// the DKTG's membrane strain carry e²·N/D0: the checks fail — the scene
/// tests the offset's coupling on both facets.
#[test]
fn without_the_offset_the_checks_fail() {
    let t = plates().replace("EXCENTREMENT=0.05", "EXCENTREMENT=0.0");
    let (_, nook, err) = run(&t, "zero");
    assert_eq!(err, None);
    assert!(nook >= 10, "{nook} NOOK");
}

/// A DKT (not DKTG) has layer stresses, not generalised efforts, in its
/// SIEF_ELGA: asking NXX of it is an error, never a number.
#[test]
fn a_dkt_has_no_generalised_sief() {
    let t = edit(
        "PHENOMENE=\"MECANIQUE\", MODELISATION=\"DKTG\"",
        "PHENOMENE=\"MECANIQUE\", MODELISATION=\"DKT\"",
    );
    let (_, nook, err) = run(&t, "dkt");
    assert_eq!(nook, 0);
    let err = err.expect("an error");
    assert!(err.contains("no component NXX"), "{err}");
}

/// code_aster's Q4G (not Q4GG) has no coupling of an offset reproduced
/// (refused at EXCENTREMENT) and, without offset, no non-linear options
/// (refused at MODELE before solving).
#[test]
fn a_q4g_in_stat_non_line_is_refused() {
    let t = edit(
        "PHENOMENE=\"MECANIQUE\", MODELISATION=\"Q4GG\"",
        "PHENOMENE=\"MECANIQUE\", MODELISATION=\"Q4G\"",
    );
    let (_, nook, err) = run(&t, "q4g-offset");
    assert_eq!(nook, 0);
    let err = err.expect("refused");
    assert!(err.contains("EXCENTREMENT on the Q4G cell MQ1"), "{err}");
    let carq = "CARQ = AFFE_CARA_ELEM(MODELE=MOQ, COQUE=_F(GROUP_MA=(\"SQ\", \"ST\"), EPAIS=0.02, EXCENTREMENT=0.05";
    assert!(t.contains(carq));
    let t = t.replacen(carq, &carq.replace("0.05", "0.0"), 1);
    let (_, nook, err) = run(&t, "q4g");
    assert_eq!(nook, 0);
    let err = err.expect("refused");
    assert!(
        err.contains("code_aster's Q4G plates have no non-linear options"),
        "{err}"
    );
}

/// The plates' ENEL_ELNO (te0004's extrapolation) is refused at ENERGIE.
#[test]
fn enel_elno_on_plates_is_refused() {
    let t = edit(
        "ENERGIE=(\"ENEL_ELEM\", \"ENEL_ELGA\")",
        "ENERGIE=(\"ENEL_ELEM\", \"ENEL_ELNO\")",
    );
    let (_, nook, err) = run(&t, "elno");
    assert_eq!(nook, 0);
    let err = err.expect("refused");
    assert!(err.contains("ENEL_ELNO' on plate cells"), "{err}");
}
