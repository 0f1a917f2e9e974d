//! The project's 3D LAC patch test (comm/lac3d_patch.comm on
//! comm/lac3d_patch.mail, both written for aster): a HEXA8 block on a
//! TETRA4 block with non-matching QUAD4/TRIA3 faces, slave on either side,
//! both DECOUPE_HEXA cuts, TYPE_JACOBIEN='ACTUALISE'; every TEST_RESU and
//! TEST_TABLE against the analytic solution (pressure 25 transmitted
//! exactly). Also the cut meshes' counts (code_aster's `cppagn`) and the
//! refusals of what LAC and OBSERVATION do not take.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &str, name: &str) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-lac3d-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.comm"));
    std::fs::write(&file, comm).unwrap();
    let case =
        aster_run::program::prepare(&file, Some(&root().join("comm/lac3d_patch.mail")), &dir)
            .unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

fn scene() -> String {
    std::fs::read_to_string(root().join("comm/lac3d_patch.comm")).unwrap()
}

#[test]
fn patch_test_passes_every_check_four_ways() {
    let outcome = run(&scene(), "patch");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    // 4 analyses × (15 TEST_RESU × 2 + 1 + 2 TEST_TABLE × 2): the
    // non-regression and the analytic check of each value.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (136, 0));
}

fn cut(group: &str, hexa: aster_mesh::DecoupeHexa) -> (aster_mesh::Mesh, aster_mesh::LacPatches) {
    let mesh = aster_mesh::read_mail(&root().join("comm/lac3d_patch.mail")).unwrap();
    let options = aster_mesh::LacOptions {
        hexa,
        reference: &aster_fem::shape::ReferenceCells,
    };
    aster_mesh::decoupe_lac_with(&mesh, &[group], options).unwrap()
}

#[test]
fn decoupe_lac_counts_in_3d() {
    use aster_mesh::{CellType, DecoupeHexa};
    let (nodes, cells) = (75, 128);
    let count = |m: &aster_mesh::Mesh, ty| m.cells.iter().filter(|c| c.ty == ty).count();
    // QUAD4 of HEXA8, PYRA: per face +1 node, +3 triangles (the face is one
    // of four), the hexahedron becomes 5 pyramids.
    let (m, p) = cut("ESCH", DecoupeHexa::Pyra);
    assert_eq!(m.coords.len(), nodes + 9);
    assert_eq!(m.cells.len(), cells + 9 * 3 + 9 * 4);
    assert_eq!(
        (count(&m, CellType::PYRAM5), count(&m, CellType::HEXA8)),
        (45, 9)
    );
    assert_eq!(m.group_ma("ESCH").unwrap().members.len(), 36);
    assert_eq!(m.group_ma("HAUT").unwrap().members.len(), 9 + 45);
    let patches = &p.zone("ESCH").unwrap().patches;
    assert_eq!(patches.len(), 9);
    assert!(patches
        .iter()
        .all(|p| p.cells.len() == 4 && p.pressure_nodes.len() == 1));
    // HEXA: per face +8 nodes, +4 quadrangles, +5 hexahedra; four pressure
    // nodes (code_aster ties them).
    let (m, p) = cut("ESCH", DecoupeHexa::Hexa);
    assert_eq!(m.coords.len(), nodes + 72);
    assert_eq!(m.cells.len(), cells + 9 * 4 + 9 * 5);
    assert_eq!(count(&m, CellType::HEXA8), 18 + 45);
    assert!(p.zones[0]
        .patches
        .iter()
        .all(|p| p.cells.len() == 5 && p.pressure_nodes.len() == 4));
    // TRIA3 of TETRA4: +1 node (the centroid), +2 triangles, +2 tetrahedra.
    let (m, p) = cut("ESCB", DecoupeHexa::Pyra);
    assert_eq!(m.coords.len(), nodes + 8);
    assert_eq!(m.cells.len(), cells + 8 * 2 + 8 * 2);
    assert_eq!(m.group_ma("BAS").unwrap().members.len(), 48 + 16);
    assert!(p.zones[0].patches.iter().all(|p| p.cells.len() == 3));
}

/// The scene's first analysis with `edit` applied to its text.
fn variant(edit: impl Fn(String) -> String) -> String {
    edit(scene().replace("for i in range(4):", "for i in range(1):"))
}

#[test]
fn an_unobservable_field_is_refused_before_running() {
    let comm = variant(|c| c.replace("NOM_CHAM=\"CONT_ELEM\",\n", "NOM_CHAM=\"FORC_NODA\",\n"));
    let outcome = run(&comm, "obs");
    let e = outcome.error.expect("must fail").to_string();
    assert!(
        e.contains("OBSERVATION/NOM_CHAM='FORC_NODA'") && e.contains("obs.comm:"),
        "{e}"
    );
    assert_eq!(outcome.tally.ok + outcome.tally.nook, 0, "nothing ran");
}

#[test]
fn a_table_the_result_has_not_is_named() {
    let comm = variant(|c| {
        c.replace(
            "        OBSERVATION=_F(",
            "        OBSERVATIOX=_F(",
        )
        .replace("OBSERVATIOX=_F(\n            NOM_CHAM=\"CONT_ELEM\",\n            NOM_CMP=(\"PRES\", \"COEFSURF\"),\n            EVAL_CHAM=\"MIN\",\n            GROUP_MA=slaves[i],\n            OBSE_ETAT_INIT=\"NON\",\n        ),\n", "")
    });
    let e = run(&comm, "notable").error.expect("must fail").to_string();
    assert!(
        e.contains("has no table 'OBSERVATION'") && e.contains("OBSERVATION=_F(...)"),
        "{e}"
    );
}
