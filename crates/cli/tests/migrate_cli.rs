//! `aster migrate`: code_aster 11 spelling rewritten as code_aster 17,
//! comments and layout kept; a unified diff by default, `--write` in place.
//! The scene is written for this test (the legacy forms of docs/legacy.md).

mod cli;

use std::path::PathBuf;

const V11: &str = "\
# A code_aster 11 study (comments stay).
DEBUT(CODE=_F(NOM='TEST', NIV_PUB_WEB='INTERNET'), PAR_LOT='NON')

MA = LIRE_MAILLAGE(FORMAT='MED')
MO = AFFE_MODELE(MAILLAGE=MA,
                 VERIF='MAILLE',   # gone in v17
                 AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))
MAT = DEFI_MATERIAU(ELAS=_F(E=1.0, NU=0.3))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))
CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(NOEUD='N1', DX=0.0, DY=0.0))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))
R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH),
                  COMP_INCR=_F(RELATION='ELAS', RESI_INTE_RELA=1.0e-6),
                  INCREMENT=_F(LIST_INST=L),
                  SOLVEUR=_F(METHODE='MUMPS', SYME='OUI'))
for i in xrange(2):
    print 'step', i
DETRUIRE(CONCEPT=_F(NOM=L))
FIN()
";

use cli::aster;

fn file(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-migrate-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = d.join("study.comm");
    std::fs::write(&p, V11).unwrap();
    p
}

#[test]
fn migrate_prints_a_unified_diff() {
    let p = file("diff");
    let (code, diff, err) = aster(&["migrate", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let diff = diff.replace(p.to_str().unwrap(), "study.comm");
    insta::assert_snapshot!("migrate_v11_diff", diff);
    // The file itself is untouched without --write.
    assert_eq!(std::fs::read_to_string(&p).unwrap(), V11);
}

#[test]
fn migrated_file_checks_clean_without_legacy_warnings() {
    let p = file("write");
    let path = p.to_str().unwrap();
    // The v11 form checks with legacy warnings.
    let (code, out, _) = aster(&["check", "--format", "json", path]);
    assert_eq!(code, 0);
    assert!(out.contains("W-legacy"), "{out}");
    let (code, _, err) = aster(&["migrate", "--write", path]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.contains("# gone in v17") && text.contains("# A code_aster 11 study"));
    let (code, out, err) = aster(&["check", "--format", "json", path]);
    assert_eq!(code, 0, "{out}{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["status"], "clean", "{out}");
    assert_eq!(v["diagnostics"], serde_json::json!([]), "{out}");
    // A second migration has nothing left to do.
    let (code, diff, _) = aster(&["migrate", path]);
    assert_eq!((code, diff.as_str()), (0, ""));
}

#[test]
fn unreadable_file_exits_2() {
    let (code, _, err) = aster(&["migrate", "/no/such.comm"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error: /no/such.comm"), "{err}");
}
