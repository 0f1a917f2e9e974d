//! Fields at Gauss points and L2 error norms (comm/elga_error_norm.export,
//! written for the project): CREA_CHAMP DISC, AFFE of ELGA_NEUT_F, EVAL,
//! ASSE of ELGA_DEPL_R with PROL_ZERO='OUI', POST_ELEM/NORME, against the
//! interpolation error of X**2 on QUAD4 and HEXA8 cells as code_aster's
//! Gauss points integrate it; and the located refusals around them.

mod scene;

use scene::{root, run_case as run, temp};

/// The scene with its command file edited (`from` → `to`, each present),
/// run in a directory of its own: the error message.
fn refused(name: &str, edits: &[(&str, &str)]) -> String {
    scene::refused_export(
        "elga_error_norm.comm",
        &["elga_square.mail", "elga_block.mail"],
        edits,
        &format!("elga-{name}"),
    )
}

#[test]
fn interpolation_errors_at_gauss_points() {
    let out = temp("scene");
    let (outcome, report) = run(&root().join("comm/elga_error_norm.export"), &out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    // 13 TEST_TABLE/TEST_RESU values, each against VALE_CALC and the
    // analytic VALE_REFE.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (26, 0), "{report}");
    // IMPR_TABLE of the norms: code_aster's columns, the 2D errors
    // sqrt(2)/24 and sqrt(2)/8.
    assert!(
        report.contains("CHAM_GD  GROUP_MA                 TYPE_MAIL TYPE_NORM VALE_NORM"),
        "{report}"
    );
    assert!(
        report.contains("diff_u   VOLUME                    -         L2        5.89256E-02"),
        "{report}"
    );
    assert!(
        report.contains("diff_p   TOP                       -         L2        1.76777E-01"),
        "{report}"
    );
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn functions_at_gauss_points_need_prol_zero() {
    let error = refused(
        "affe-f",
        &[(
            "        TYPE_CHAM=\"ELGA_NEUT_F\",\n        MODELE=model,\n        PROL_ZERO=\"OUI\",\n        AFFE=[",
            "        TYPE_CHAM=\"ELGA_NEUT_F\",\n        MODELE=model,\n        AFFE=[",
        )],
    );
    assert!(
        error.contains(
            "not supported yet: CREA_CHAMP/TYPE_CHAM='ELGA_NEUT_F' without PROL_ZERO='OUI'"
        ) && error.contains("case.comm:63:9"),
        "{error}"
    );
}

#[test]
fn values_left_to_nan_are_refused() {
    // The pressure is given on TOP's nodes only: the faces below lack it,
    // which code_aster fills with NaN without PROL_ZERO.
    let error = refused(
        "nan",
        &[(
            "TYPE_CHAM=\"ELGA_NEUT_R\", MODELE=model, PROL_ZERO=\"OUI\", CHAM_GD=np_",
            "TYPE_CHAM=\"ELGA_NEUT_R\", MODELE=model, CHAM_GD=np_",
        )],
    );
    assert!(
        error.contains("not supported yet: CREA_CHAMP: component X1 of cell Q1 has no value, which code_aster fills with NaN without PROL_ZERO='OUI'")
            && error.contains("case.comm:92:27"),
        "{error}"
    );
}

#[test]
fn other_discretisations_and_norms_are_refused_where_written() {
    let error = refused(
        "elno",
        &[(
            "OPERATION=\"DISC\", TYPE_CHAM=\"ELGA_GEOM_R\"",
            "OPERATION=\"DISC\", TYPE_CHAM=\"ELNO_GEOM_R\"",
        )],
    );
    assert!(
        error.contains(
            "not supported yet: CREA_CHAMP/OPERATION='DISC' with TYPE_CHAM='ELNO_GEOM_R'"
        ) && error.contains("case.comm:59:27"),
        "{error}"
    );
    let error = refused(
        "frobenius",
        &[(
            "NORME=_F(TYPE_NORM=\"L2\", GROUP_MA=\"VOLUME\"",
            "NORME=_F(TYPE_NORM=\"FROBENIUS\", GROUP_MA=\"VOLUME\"",
        )],
    );
    assert!(
        error.contains("not supported yet: POST_ELEM/NORME/TYPE_NORM='FROBENIUS'"),
        "{error}"
    );
}

/// A TYPE_TEST over a Gauss-point field made by CREA_CHAMP on a mesh with
/// volumes and segments (comm/crack_front_3d.mail: HEXA8 and the SEG2
/// front) is refused at TYPE_TEST: code_aster's edge elements give the
/// segments Gauss points aster's models leave out.
#[test]
fn a_type_test_over_a_3d_field_with_edges_is_refused() {
    let dir = temp("edges");
    std::fs::write(
        dir.join("case.comm"),
        r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER", UNITE=20)
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="3D"))
xn = CREA_CHAMP(OPERATION="EXTR", TYPE_CHAM="NOEU_GEOM_R", NOM_CHAM="GEOMETRIE", MAILLAGE=mesh)
xg = CREA_CHAMP(OPERATION="DISC", TYPE_CHAM="ELGA_GEOM_R", PROL_ZERO="OUI", CHAM_GD=xn, MODELE=model)
TEST_RESU(CHAM_ELEM=_F(CHAM_GD=xg, NOM_CMP="X", TYPE_TEST="MAX", VALE_CALC=10.0))
FIN()
"#,
    )
    .unwrap();
    std::fs::copy(
        root().join("comm/crack_front_3d.mail"),
        dir.join("crack_front_3d.mail"),
    )
    .unwrap();
    std::fs::write(
        dir.join("case.export"),
        "F comm case.comm D 1\nF mail crack_front_3d.mail D 20\n",
    )
    .unwrap();
    let (outcome, report) = run(&dir.join("case.export"), &dir.join("out"));
    let _ = std::fs::remove_dir_all(&dir);
    let error = outcome
        .error
        .unwrap_or_else(|| panic!("not refused\n{report}"))
        .message;
    assert!(
        error.contains("not supported yet: TEST_RESU/CHAM_ELEM/TYPE_TEST over a Gauss-point field made by CREA_CHAMP on a mesh with volumes and segments")
            && error.contains("case.comm:6:49"),
        "{error}"
    );
}
