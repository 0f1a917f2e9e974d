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

/// code_aster 11 structures that a rename cannot migrate: a command
/// replaced by another with keywords moved, values moved between levels.
const V11_STRUCTURES: &str = "\
# code_aster 11 structures that migrate rebuilds.
DEBUT(CODE=_F(NOM='TEST2', NIV_PUB_WEB='INTERNET'))
MA = LIRE_MAILLAGE(FORMAT='MED')
MO = AFFE_MODELE(MAILLAGE=MA,
                 AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE',
                         MODELISATION=('D_PLAN', 'D_PLAN_SI')))
E = DEFI_CONSTANTE(VALE=2.0e11)
NU = DEFI_CONSTANTE(VALE=0.3)
MAT = DEFI_MATERIAU(ELAS_FO=_F(E=E, NU=NU, RHO=7800.0))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))
MACRO_MATR_ASSE(MODELE=MO, CHAM_MATER=CM, NUME_DDL=CO('NUM'),
                SOLVEUR=_F(METHODE='LDLT'),
                MATR_ASSE=(_F(MATRICE=CO('K'), OPTION='RIGI_MECA'),
                           _F(MATRICE=CO('M'), OPTION='MASS_MECA')))
MODES = MODE_ITER_SIMULT(MATR_A=K, MATR_B=M,
                         METHODE='SORENSEN',  # the modal solver
                         OPTION='SANS',
                         CALC_FREQ=_F(OPTION='BANDE', FREQ=(1.0, 100.0)))
MODE2 = MODE_ITER_INV(MATR_A=K, MATR_B=M, CALC_FREQ=_F(FREQ=(10.0,)),
                      CALC_MODE=_F(NMAX_ITER=40))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=2))
LI = DEFI_LIST_INST(DEFI_LIST=_F(METHODE='AUTO', LIST_INST=L))
CH = CREA_CHAMP(TYPE_CHAM='NOEU_TEMP_R', OPERATION='AFFE', MAILLAGE=MA,
                AFFE=_F(TOUT='OUI', NOM_CMP='TEMP', VALE=0.0))
T = CREA_RESU(OPERATION='AFFE', TYPE_RESU='EVOL_THER', NOM_CHAM='TEMP',
              AFFE=(_F(CHAM_GD=CH, INST=0.0), _F(CHAM_GD=CH, INST=1.0)))
KW = {}
KW['CONCEPT'] = []
for name in (L,):
    KW['CONCEPT'].append(_F(NOM=name))
DETRUIRE(INFO=1, **KW)
L_AFFE = [_F(CHAM_GD=CH, INST=2.0)]
T = CREA_RESU(reuse=T, RESULTAT=T, OPERATION='AFFE', TYPE_RESU='EVOL_THER',
              NOM_CHAM='TEMP', AFFE=L_AFFE)
FIN()
";

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

/// Whole-command rewrites: MODE_ITER_SIMULT/INV → CALC_MODES (keywords
/// moved into SOLVEUR_MODAL, OPTION up), MACRO_MATR_ASSE → ASSEMBLAGE,
/// NOM_CHAM into each CREA_RESU occurrence (also of a list the program
/// builds), DETRUIRE's CONCEPT built in a dictionary passed as `**kw`,
/// METHODE up from DEFI_LIST, one AFFE per modelisation, a real
/// where a function is wanted: the migrated file checks clean, with its
/// comments, and a second migration changes nothing.
#[test]
fn whole_commands_and_moved_keywords_are_rebuilt() {
    let d = std::env::temp_dir().join(format!("aster-migrate-{}-struct", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = d.join("study.comm");
    std::fs::write(&p, V11_STRUCTURES).unwrap();
    let path = p.to_str().unwrap();
    let (code, out, err) = aster(&["check", "--format", "json", path]);
    assert_eq!(code, 0, "{out}{err}");
    let (code, diff, err) = aster(&["migrate", path]);
    assert_eq!(code, 0, "{err}");
    insta::assert_snapshot!("migrate_v11_structures", diff.replace(path, "study.comm"));
    let (code, _, err) = aster(&["migrate", "--write", path]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.contains("# the modal solver"), "{text}");
    let (code, out, err) = aster(&["check", "--format", "json", path]);
    assert_eq!(code, 0, "{out}{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["diagnostics"], serde_json::json!([]), "{text}\n{out}");
    let (code, diff, _) = aster(&["migrate", path]);
    assert_eq!((code, diff.as_str()), (0, ""));
    let _ = std::fs::remove_dir_all(&d);
}

/// PROJ_CHAMP/PROL_ZERO, translated by code_aster 17's compat_syntax:
/// 'OUI' becomes PROL_VALE=0.0, 'NON' (the default) goes; the migrated
/// file checks clean.
#[test]
fn proj_champ_prol_zero_becomes_prol_vale() {
    let d = std::env::temp_dir().join(format!("aster-migrate-{}-prolzero", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = d.join("study.comm");
    std::fs::write(
        &p,
        "DEBUT(CODE='OUI')\n\
         MA = LIRE_MAILLAGE(FORMAT='MED')\n\
         MB = LIRE_MAILLAGE(FORMAT='MED', UNITE=21)\n\
         CH = CREA_CHAMP(TYPE_CHAM='NOEU_TEMP_R', OPERATION='AFFE', MAILLAGE=MA,\n\
                         AFFE=_F(TOUT='OUI', NOM_CMP='TEMP', VALE=1.0))\n\
         P1 = PROJ_CHAMP(CHAM_GD=CH, MAILLAGE_1=MA, MAILLAGE_2=MB, PROL_ZERO='OUI')\n\
         P2 = PROJ_CHAMP(CHAM_GD=CH, MAILLAGE_1=MA, MAILLAGE_2=MB, PROL_ZERO='NON')\n\
         FIN()\n",
    )
    .unwrap();
    let path = p.to_str().unwrap();
    let (code, _, err) = aster(&["migrate", "--write", path]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.contains("MAILLAGE_2=MB, PROL_VALE=0.0)"), "{text}");
    assert!(!text.contains("PROL_ZERO"), "{text}");
    let (code, out, err) = aster(&["check", "--format", "json", path]);
    assert_eq!(code, 0, "{out}{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["diagnostics"], serde_json::json!([]), "{text}\n{out}");
    let _ = std::fs::remove_dir_all(&d);
}

/// THER_NON_LINE's line search of code_aster 15 (`NEWTON/ITER_LINE_MAXI`,
/// `RESI_LINE_RELA`), moved by code_aster 17's compat_syntax into
/// RECH_LINEAIRE: the migrated file has it there and checks clean.
#[test]
fn ther_non_line_line_search_moves_to_rech_lineaire() {
    let d = std::env::temp_dir().join(format!("aster-migrate-{}-rechlin", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = d.join("study.comm");
    std::fs::write(
        &p,
        "DEBUT(CODE='OUI')\n\
         MA = LIRE_MAILLAGE(FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='THERMIQUE', MODELISATION='PLAN'))\n\
         MAT = DEFI_MATERIAU(THER_NL=_F(LAMBDA=DEFI_CONSTANTE(VALE=1.0), BETA=DEFI_CONSTANTE(VALE=1.0)))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         CH = AFFE_CHAR_THER(MODELE=MO, TEMP_IMPO=_F(TOUT='OUI', TEMP=1.0))\n\
         L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=2))\n\
         T = THER_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH),\n\
                           ETAT_INIT=_F(VALE=0.0), INCREMENT=_F(LIST_INST=L),\n\
                           NEWTON=_F(ITER_LINE_MAXI=2, RESI_LINE_RELA=0.01, REAC_ITER=1))\n\
         FIN()\n",
    )
    .unwrap();
    let path = p.to_str().unwrap();
    let (code, _, err) = aster(&["migrate", "--write", path]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(
        text.contains("RECH_LINEAIRE=_F(ITER_LINE_MAXI=2, RESI_LINE_RELA=0.01), NEWTON=_F("),
        "{text}"
    );
    assert!(text.contains("REAC_ITER=1"), "{text}");
    let (code, out, err) = aster(&["check", "--format", "json", path]);
    assert_eq!(code, 0, "{out}{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["diagnostics"], serde_json::json!([]), "{text}\n{out}");
    let _ = std::fs::remove_dir_all(&d);
}
