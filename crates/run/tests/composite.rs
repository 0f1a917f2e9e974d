//! The project's scene of layered plates (comm/composite_strips.comm on
//! comm/thick_strips.mail): DEFI_COMPOSITE stacks on DKT and DST strips
//! against laminate theory (a sandwich's Kirchhoff and Timoshenko
//! deflections, its ply stresses and shear stress S(z)·Q/D, crossed plies
//! under ANGL_REP), then what is refused with them.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/thick_strips.mail", &format!("composite-{tag}"))
}

fn strips() -> String {
    scene::read("composite_strips.comm")
}

fn edit(from: &str, to: &str) -> String {
    let t = strips();
    assert!(t.contains(from), "the edit applies: {from}");
    t.replacen(from, to, 1)
}

#[test]
fn composite_strips_match_laminate_theory() {
    assert_eq!(run(&strips(), "strips"), (27, 0, None));
}

/// A stack not symmetric about its mid-surface couples membrane and
/// bending (code_aster's coupmf terms): refused before solving, naming the
/// cell.
#[test]
fn a_coupled_stack_is_refused() {
    let t = edit(
        "        _F(EPAIS=0.16, MATER=CORE),\n        _F(EPAIS=0.02, MATER=SKIN),",
        "        _F(EPAIS=0.16, MATER=CORE),\n        _F(EPAIS=0.02, MATER=CORE),",
    );
    let (ok, nook, err) = run(&t, "coupled");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("couples membrane and bending"), "{err}");
}

/// The stresses are by ply: COQUE_NCOU must be the number of plies.
#[test]
fn coque_ncou_must_be_the_number_of_plies() {
    let t = edit(
        "_F(GROUP_MA=(\"S1\", \"S5\"), EPAIS=0.2, COQUE_NCOU=3)",
        "_F(GROUP_MA=(\"S1\", \"S5\"), EPAIS=0.2, COQUE_NCOU=2)",
    );
    let (_, nook, err) = run(&t, "ncou");
    assert_eq!(nook, 0);
    let err = err.expect("refused");
    assert!(
        err.contains("COQUE_NCOU = 2") && err.contains("3 layers"),
        "{err}"
    );
}

/// A ply must be an ELAS_ORTH material (code_aster's MODELISA8_71),
/// located at its MATER.
#[test]
fn a_ply_needs_elas_orth() {
    let t = edit(
        "CORE = DEFI_MATERIAU(\n    ELAS_ORTH=_F(E_L=2e10, E_T=2e10, NU_LT=0.0, G_LT=1e10, G_LN=1e10, G_TN=1e10, RHO=100.0)\n)",
        "CORE = DEFI_MATERIAU(ELAS=_F(E=2e10, NU=0.0))",
    );
    let (_, nook, err) = run(&t, "elas");
    assert_eq!(nook, 0);
    let err = err.expect("refused");
    assert!(
        err.contains("ELAS_ORTH") && err.contains("COUCHE/MATER") && err.contains(":59:24"),
        "{err}"
    );
}

/// The layered DKQ facets (DKT on QUAD4) have no transverse shear stresses
/// here (`dkqlxy` is not reproduced): a TEST_RESU on SIXZ of a DKQ strip is
/// refused, naming the component, not given a number.
#[test]
fn layered_dkt_has_no_sixz() {
    let t = edit(
        "            GROUP_NO=\"O1\",\n            GROUP_MA=\"M1\",\n            NOM_CMP=\"SIXZ\",",
        "            GROUP_NO=\"O5\",\n            GROUP_MA=\"M5\",\n            NOM_CMP=\"SIXZ\",",
    );
    let (_, nook, err) = run(&t, "dkt-sixz");
    assert_eq!(nook, 0);
    let err = err.expect("refused");
    assert!(err.contains("no component SIXZ"), "{err}");
}
