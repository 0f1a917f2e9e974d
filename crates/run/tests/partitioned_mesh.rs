//! `LIRE_MAILLAGE(FORMAT='MED', PARTITIONNEUR=...)`: code_aster 17
//! partitions the mesh over its MPI processes; on one process it reads the
//! whole mesh (alarm MED_18), and aster runs as that one process. The
//! project's strip (comm/strip.mail) written as MED is read with a
//! partitioner and pulled: the exact tension answer, and the alarm.

mod common;

use common::Report;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

const COMM: &str = r#"
DEBUT(CODE="OUI")
mesh0 = LIRE_MAILLAGE(FORMAT="MED", UNITE=20, PARTITIONNEUR="PTSCOTCH")
mesh = CREA_MAILLAGE(MAILLAGE=mesh0, RESTREINT=_F(GROUP_MA=("PLATE", "LEFT", "RIGHT"), TOUT_GROUP_NO="OUI"))
steel = DEFI_MATERIAU(ELAS=_F(E=200000.0, NU=0.3))
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="C_PLAN"))
mater = AFFE_MATERIAU(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", MATER=steel))
load = AFFE_CHAR_MECA(
    MODELE=model,
    DDL_IMPO=(_F(GROUP_MA="LEFT", DX=0.0), _F(GROUP_NO="A", DY=0.0)),
    FORCE_CONTOUR=_F(GROUP_MA="RIGHT", FX=100.0),
)
resu = MECA_STATIQUE(MODELE=model, CHAM_MATER=mater, EXCIT=_F(CHARGE=load))
TEST_RESU(RESU=_F(RESULTAT=resu, NUME_ORDRE=1, NOM_CHAM="DEPL", NOM_CMP="DX", GROUP_NO="B",
                  VALE_CALC=1.0e-3, VALE_REFE=1.0e-3, REFERENCE="ANALYTIQUE"))
FIN()
"#;

#[test]
fn a_partitioned_mesh_is_read_whole_on_one_process() {
    let dir = std::env::temp_dir().join(format!("aster-partitioned-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = aster_mesh::read_mesh(&root().join("comm/strip.mail")).unwrap();
    let med = dir.join("strip.mmed");
    aster_mesh::write_med(&med, &mesh, "strip", &[]).unwrap();
    let comm = dir.join("partitioned.comm");
    std::fs::write(&comm, COMM).unwrap();
    let out = dir.join("out");
    let case = aster_run::program::prepare(&comm, Some(&med), &out).unwrap();
    let report = Report::default();
    let outcome = aster_run::program::run(&case, Box::new(report.clone()));
    let text = report.text();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (2, 0), "{text}");
    assert!(
        text.contains(
            "<A> LIRE_MAILLAGE: PARTITIONNEUR='PTSCOTCH': one process, the mesh is read whole"
        ),
        "{text}"
    );
}
