//! MACR_LIGN_COUPE (comm/macr_lign_coupe.export, written for the project):
//! a result's values along cut lines — segments leaving the mesh, a
//! segment's own frame (REPERE='LOCAL'), a group of nodes, the mean along a
//! line, a field with its model, an arc — against their closed forms, the
//! table's columns as code_aster's macro leaves them, and the located
//! refusals.

mod scene;

use scene::{root, run_case as run, temp};

fn refused(name: &str, edits: &[(&str, &str)]) -> String {
    scene::refused_export(
        "macr_lign_coupe.comm",
        &["proj_quad8.mail"],
        edits,
        &format!("mlc-{name}"),
    )
}

#[test]
fn cut_lines_give_the_closed_forms() {
    let out = temp("mlc");
    let (outcome, report) = run(&root().join("comm/macr_lign_coupe.export"), &out);
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    // 21 TEST_TABLE, each against VALE_CALC and the analytic VALE_REFE.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (42, 0), "{report}");
    // The table printed by IMPR_TABLE: POST_RELEVE_T's columns without RESU
    // and NOEUD, and only the five points inside the mesh.
    let header = report
        .lines()
        .find(|l| l.starts_with("INTITULE"))
        .expect("the table's header");
    let columns: Vec<&str> = header.split_whitespace().collect();
    assert_eq!(
        columns,
        [
            "INTITULE",
            "NOM_CHAM",
            "NUME_ORDRE",
            "INST",
            "ABSC_CURV",
            "COOR_X",
            "COOR_Y",
            "DX",
            "DY"
        ]
    );
    let rows = report.lines().filter(|l| l.starts_with("l.coupe1")).count();
    assert_eq!(rows, 5, "{report}");
}

#[test]
fn what_is_not_computed_is_refused_at_its_keyword() {
    let m = refused(
        "elno",
        &[(
            "RESULTAT=resu, NOM_CHAM=\"DEPL\", INST=1.0,\n    LIGN_COUPE=_F(NB_POINTS=7",
            "RESULTAT=resu, NOM_CHAM=\"SIGM_ELNO\", INST=1.0,\n    LIGN_COUPE=_F(NB_POINTS=7",
        )],
    );
    assert!(
        m.contains("NOM_CHAM='SIGM_ELNO'") && m.contains("case.comm:"),
        "{m}"
    );
    let m = refused(
        "cyl",
        &[(
            "REPERE=\"LOCAL\", VECT_Y=(0.0, 1.0),\n    ),\n)\nlast",
            "REPERE=\"CYLINDRIQUE\",\n    ),\n)\nlast",
        )],
    );
    assert!(
        m.contains("REPERE='CYLINDRIQUE'") && m.contains("case.comm:"),
        "{m}"
    );
    let m = refused(
        "grma",
        &[(
            "TYPE=\"GROUP_NO\", GROUP_NO=\"BOTTOM\"",
            "TYPE=\"GROUP_MA\", GROUP_MA=\"SURF\", MAILLAGE=A",
        )],
    );
    assert!(m.contains("TYPE='GROUP_MA'"), "{m}");
}

#[test]
fn a_line_outside_the_model_is_an_error_not_an_empty_table() {
    let m = refused(
        "outside",
        &[(
            "COOR_ORIG=(0.25, 0.25), COOR_EXTR=(1.75, 0.75)",
            "COOR_ORIG=(3.0, 3.0), COOR_EXTR=(4.0, 3.0)",
        )],
    );
    // code_aster's PROJ_CHAMP stops when no node is projected; located.
    assert!(
        m.contains("MACR_LIGN_COUPE") && m.contains("case.comm:") && m.contains("projected"),
        "{m}"
    );
}
