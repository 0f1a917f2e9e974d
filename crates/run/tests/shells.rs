//! The project's DKT scene (comm/dkt_strips.comm on comm/dkt_strips.mail):
//! two cantilever strips of thin shells — 10 DKQ quadrangles in the plane
//! z = 0 under a tip force and a tension, 20 DKT triangles in the plane
//! y = 1 under a tip moment and a tension — against beam theory (ν = 0):
//! tip deflections and rotations, membrane stretch, and EFGE_ELGA moments
//! and membrane forces in the default frame, all within 1e-9. What the
//! shells cannot run yet is refused at its keyword.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/dkt_strips.mail", &format!("shells-{tag}"))
}

fn strips() -> String {
    scene::read("dkt_strips.comm")
}

#[test]
fn cantilever_strips_of_dkt_and_dkq_match_beam_theory() {
    assert_eq!(run(&strips(), "strips"), (20, 0, None));
}

/// MECA_STATIQUE solves the same linear system.
#[test]
fn meca_statique_gives_the_same_strips() {
    let text = strips()
        .replace("RESU = STAT_NON_LINE(", "RESU = MECA_STATIQUE(")
        .replace(
            "    COMPORTEMENT=_F(RELATION=\"ELAS\", TOUT=\"OUI\"),\n",
            "",
        )
        .replace("INCREMENT=_F(LIST_INST=LINST),", "LIST_INST=LINST,");
    assert!(text.contains("MECA_STATIQUE") && !text.contains("INCREMENT"));
    assert_eq!(run(&text, "meca"), (20, 0, None));
}

/// `BLOCAGE=('DEPLACEMENT', 'ROTATION')` blocks the six components of the
/// shells' nodes, as the explicit DDL_IMPO does.
#[test]
fn blocage_rotation_blocks_the_shells_rotations() {
    let text = strips().replace(
        "DX=0.0, DY=0.0, DZ=0.0, DRX=0.0, DRY=0.0, DRZ=0.0",
        "BLOCAGE=(\"DEPLACEMENT\", \"ROTATION\")",
    );
    assert!(text.contains("BLOCAGE"));
    assert_eq!(run(&text, "blocage"), (20, 0, None));
}

/// Without the clamp's rotations the strips are mechanisms: the singular
/// system names free rotations.
#[test]
fn unheld_rotations_are_named() {
    let text = strips().replace(", DRX=0.0, DRY=0.0, DRZ=0.0", "");
    let (ok, nook, err) = run(&text, "unheld");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("a singular system");
    assert!(err.contains("DRY") || err.contains("DRZ"), "{err}");
}

fn refused(text: &str, tag: &str, what: &[&str]) {
    let (ok, nook, err) = run(text, tag);
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("not supported yet"), "{err}");
    for w in what {
        assert!(err.contains(w), "{w} in {err}");
    }
}

#[test]
fn contact_on_shells_is_refused_at_the_zone() {
    let text = strips().replace(
        "LINST = ",
        "CONT = DEFI_CONTACT(MODELE=MO, FORMULATION=\"CONTINUE\", \
         ZONE=_F(GROUP_MA_MAIT=\"SQ\", GROUP_MA_ESCL=\"ST\"))\n\nLINST = ",
    );
    refused(
        &text,
        "contact",
        &[
            "DEFI_CONTACT/ZONE/GROUP_MA_MAIT on shell cells",
            "DIST_COQUE",
        ],
    );
}

#[test]
fn plasticity_and_pressure_on_shells_are_refused() {
    let plastic = strips()
        .replace(
            "ELAS=_F(E=2.0e11, NU=0.0)",
            "ELAS=_F(E=2.0e11, NU=0.0), ECRO_LINE=_F(D_SIGM_EPSI=1e9, SY=2e8)",
        )
        .replace("RELATION=\"ELAS\"", "RELATION=\"VMIS_ISOT_LINE\"");
    refused(
        &plastic,
        "plastic",
        &["COMPORTEMENT/RELATION other than ELAS on shell or beam cells"],
    );
    let pressure = strips().replace(
        "FORCE_NODALE=(",
        "PRES_REP=_F(GROUP_MA=\"SQ\", PRES=1.0),\n    FORCE_NODALE=(",
    );
    refused(
        &pressure,
        "pressure",
        &["AFFE_CHAR_MECA/PRES_REP on shell cells"],
    );
}

#[test]
fn a_shell_without_section_is_an_error_naming_its_cell() {
    let text = strips().replace(
        "COQUE=_F(GROUP_MA=(\"SQ\", \"ST\"), EPAIS=0.01)",
        "COQUE=_F(GROUP_MA=\"SQ\", EPAIS=0.01)",
    );
    let (_, _, err) = run(&text, "nosection");
    let err = err.expect("an error");
    assert!(err.contains("cell MT1") && err.contains("COQUE"), "{err}");
}
