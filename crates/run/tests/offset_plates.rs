//! The project's scene of offset plates (comm/offset_strips.comm on
//! comm/dkt_strips.mail): `AFFE_CARA_ELEM/COQUE/EXCENTREMENT` on DKQ and
//! DKT strips against the closed forms of an eccentric strip (a strip in
//! tension bends, POST_CHAMP/COQU_EXCENT, the layer stresses, a held
//! strip's bending stiffness D + e²·A), then what is refused with it.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/dkt_strips.mail", &format!("offset-{tag}"))
}

fn strips() -> String {
    scene::read("offset_strips.comm")
}

fn edit(from: &str, to: &str) -> String {
    let t = strips();
    assert!(t.contains(from), "the edit applies: {from}");
    t.replacen(from, to, 1)
}

#[test]
fn offset_strips_match_the_eccentric_strip() {
    assert_eq!(run(&strips(), "strips"), (23, 0, None));
}

/// Without the offset the tension no longer bends the strip: the same
/// checks fail (the scene tests the offset, not the plain plate).
#[test]
fn without_the_offset_the_checks_fail() {
    let t = edit("EXCENTREMENT=0.05", "EXCENTREMENT=0.0");
    let (_, nook, err) = run(&t, "zero");
    assert_eq!(err, None);
    assert!(nook >= 8, "{nook} NOOK");
}

/// DST and Q4G facets have their own coupling terms, not reproduced:
/// refused at EXCENTREMENT before solving.
#[test]
fn an_offset_on_dst_is_refused_at_the_keyword() {
    let t = edit(
        "PHENOMENE=\"MECANIQUE\", MODELISATION=\"DKT\"",
        "PHENOMENE=\"MECANIQUE\", MODELISATION=\"DST\"",
    );
    let (ok, nook, err) = run(&t, "dst");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(
        err.contains("EXCENTREMENT on the DST cell") && err.contains("case.comm:36:49"),
        "{err}"
    );
}
