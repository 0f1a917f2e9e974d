//! The project's LAC patch test (comm/lac_patch.comm on
//! comm/lac_patch.mail, both written for aster): CREA_MAILLAGE/DECOUPE_LAC
//! then DEFI_CONTACT(ALGO_CONT='LAC') with a QUAD4 slave (edges cut in
//! three) and with a TRIA3 slave (edges halved), non-matching interface,
//! plane strain, then AXIS (contact integrals × r);
//! every TEST_RESU against the analytic solution (pressure 25 transmitted
//! exactly). Also the cut mesh's counts and LAC's refusals.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &str, name: &str) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-lac-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.comm"));
    std::fs::write(&file, comm).unwrap();
    let case = aster_run::program::prepare(&file, Some(&root().join("comm/lac_patch.mail")), &dir)
        .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

#[test]
fn patch_test_passes_every_check_both_ways_and_axisymmetric() {
    let comm = std::fs::read_to_string(root().join("comm/lac_patch.comm")).unwrap();
    let outcome = run(&comm, "patch");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (84, 0));
}

#[test]
fn decoupe_lac_counts_on_the_scene_mesh() {
    let mesh = aster_mesh::read_mail(&root().join("comm/lac_patch.mail")).unwrap();
    assert_eq!((mesh.coords.len(), mesh.cells.len()), (41, 62));
    // Upper block slave: 3 QUAD4 edges, each +4 nodes, +2 edges, +3 quads.
    let (up, p) = aster_mesh::decoupe_lac(&mesh, &["SUP"]).unwrap();
    assert_eq!((up.coords.len(), up.cells.len()), (41 + 12, 62 + 15));
    assert_eq!(p.zones[0].patches.len(), 3);
    assert!(p.zones[0]
        .patches
        .iter()
        .all(|p| p.pressure_nodes.len() == 2));
    // Lower block slave: 4 TRIA3 edges, each +1 node, +1 edge, +1 triangle.
    let (low, p) = aster_mesh::decoupe_lac(&mesh, &["SLOW"]).unwrap();
    assert_eq!((low.coords.len(), low.cells.len()), (41 + 4, 62 + 8));
    assert_eq!(low.group_ma("LOW").unwrap().members.len(), 32 + 4);
    assert_eq!(low.group_ma("SLOW").unwrap().members.len(), 8);
    assert!(p.zones[0].patches.iter().all(|p| p.cells.len() == 2));
}

/// The scene's first analysis with `edit` applied to its text.
fn variant(edit: impl Fn(String) -> String) -> String {
    let comm = std::fs::read_to_string(root().join("comm/lac_patch.comm")).unwrap();
    edit(comm.replace("for i in range(3):", "for i in range(1):"))
}

#[test]
fn lac_without_decoupe_lac_is_refused_with_a_located_message() {
    let comm = variant(|c| c.replace("MAILLAGE=cut[i], AFFE=", "MAILLAGE=mesh, AFFE="));
    let comm = comm.replace(
        "AFFE_MATERIAU(MAILLAGE=cut[i]",
        "AFFE_MATERIAU(MAILLAGE=mesh",
    );
    let e = run(&comm, "nocut").error.expect("must fail").to_string();
    assert!(
        e.contains("ALGO_CONT='LAC' needs a mesh cut by CREA_MAILLAGE/DECOUPE_LAC"),
        "{e}"
    );
    assert!(
        e.contains("patch.comm:") || e.contains("nocut.comm:"),
        "{e}"
    );
}

#[test]
fn a_slave_group_not_cut_is_named() {
    let comm = variant(|c| {
        c.replace(
            "slaves = [\"SUP\", \"SLOW\", \"SUP\"]",
            "slaves = [\"SUP\", \"SLOW\", \"SUP\"]\nother = [\"SLOW\"]",
        )
        .replace(
            "GROUP_MA_ESCL=slaves[i],\n            GROUP_MA_MAIT=masters[i]",
            "GROUP_MA_ESCL=other[i],\n            GROUP_MA_MAIT=slaves[i]",
        )
    });
    let e = run(&comm, "other").error.expect("must fail").to_string();
    assert!(
        e.contains("'SLOW' was not cut by CREA_MAILLAGE/DECOUPE_LAC (cut: 'SUP')"),
        "{e}"
    );
}

#[test]
fn test_resu_maillage_counts_the_cut_meshes() {
    let comm = r#"
DEBUT(CODE="OUI")
mesh = LIRE_MAILLAGE(FORMAT="ASTER", UNITE=20)
up = CREA_MAILLAGE(MAILLAGE=mesh, DECOUPE_LAC=_F(GROUP_MA_ESCL="SUP"))
both = CREA_MAILLAGE(MAILLAGE=mesh, DECOUPE_LAC=_F(GROUP_MA_ESCL=("SUP", "SLOW")))
TEST_RESU(
    MAILLAGE=(
        _F(MAILLAGE=up, CARA="NB_MAILLE", VALE_CALC_I=77),
        _F(MAILLAGE=up, CARA="NB_NOEUD", VALE_CALC_I=53),
        _F(MAILLAGE=up, CARA="NB_MA_GROUP_MA", NOM_GROUP_MA="SUP", VALE_CALC_I=9),
        _F(MAILLAGE=up, CARA="NB_MA_GROUP_MA", NOM_GROUP_MA="UP", VALE_CALC_I=18),
        _F(MAILLAGE=up, CARA="NB_GROUP_MA", VALE_CALC_I=7),
        _F(MAILLAGE=up, CARA="NB_NO_GROUP_NO", NOM_GROUP_NO="PTOP", VALE_CALC_I=1),
        _F(MAILLAGE=both, CARA="NB_MAILLE", VALE_CALC_I=85),
        _F(MAILLAGE=both, CARA="NB_NOEUD", VALE_CALC_I=57),
    )
)
FIN()
"#;
    let outcome = run(comm, "counts");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (8, 0));
}

/// A LAC solve stopped at a loose Newton tolerance is refused before the
/// solve, at the keyword: code_aster's answer is then where its LAC Newton
/// stops (ssnp165e, RESI_GLOB_MAXI = 0.5), aster's the converged state.
/// The same scene at RESI_GLOB_MAXI = 1e-6 runs and passes its checks.
#[test]
fn lac_with_a_loose_newton_tolerance_is_refused_before_the_solve() {
    let with = |conv: &str| {
        variant(|c| {
            c.replace(
                "        INCREMENT=_F(LIST_INST=times),\n    )",
                &format!("        INCREMENT=_F(LIST_INST=times),\n        CONVERGENCE=_F({conv}),\n    )"),
            )
        })
    };
    for (conv, name) in [
        ("RESI_GLOB_MAXI=0.5", "RESI_GLOB_MAXI"),
        ("RESI_GLOB_RELA=1e-3", "RESI_GLOB_RELA"),
    ] {
        let comm = with(conv);
        assert!(comm.contains(conv));
        let outcome = run(&comm, "loose");
        let e = outcome.error.expect("must be refused").to_string();
        assert!(
            e.contains(&format!("STAT_NON_LINE/CONVERGENCE/{name}=")),
            "{e}"
        );
        assert!(e.contains("with a LAC contact"), "{e}");
        assert!(e.contains("loose.comm:"), "{e}");
        assert_eq!((outcome.tally.ok, outcome.tally.nook), (0, 0));
    }
    let outcome = run(&with("RESI_GLOB_MAXI=1e-6"), "tight");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert!(outcome.tally.ok > 0 && outcome.tally.nook == 0);
}
