//! LIRE_FONCTION (comm/lire_fonction.export, written for the project):
//! functions and a nappe read from a text file of blocks of columns,
//! against the values the file's lines give; the located errors of a file
//! that does not have the columns asked, and the refusal of what is not
//! read (NumPy files, complex functions).

mod scene;

use scene::{root, run_case as run, temp};

/// The scene with its command file edited, the data file on unit 21: the
/// error message.
fn refused(name: &str, edits: &[(&str, &str)]) -> String {
    scene::refused_export(
        "lire_fonction.comm",
        &["strip.mail", "lire_fonction.dat"],
        edits,
        &format!("lire-fonction-{name}"),
    )
}

#[test]
fn functions_and_a_nappe_read_from_blocks_of_columns() {
    let out = temp("lire-fonction");
    let (outcome, report) = run(&root().join("comm/lire_fonction.export"), &out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    // 6 TEST_FONCTION values, each against VALE_CALC and VALE_REFE.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (12, 0), "{report}");
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn a_column_the_file_does_not_have_is_located() {
    let err = refused("column", &[("INDIC_RESU=(2, 3))", "INDIC_RESU=(2, 4))")]);
    assert!(
        err.contains("block 2 has 3 column(s), but INDIC_RESU = (2, 4)"),
        "{err}"
    );
    assert!(err.contains("case.comm:15:"), "{err}");
    let err = refused("block", &[("INDIC_PARA=(3, 1)", "INDIC_PARA=(4, 1)")]);
    assert!(
        err.contains("the file has 3 block(s), but INDIC_PARA = (4, 1)"),
        "{err}"
    );
}

#[test]
fn columns_of_different_lengths_are_an_error() {
    // Block 1 (3 lines) against block 2 (3 lines) is fine; against block
    // 3 (2 lines) it is code_aster's FONCT0_42.
    let err = refused("lengths", &[("INDIC_RESU=(2, 3))", "INDIC_RESU=(3, 1))")]);
    assert!(
        err.contains("the two columns differ in length: 3 lines for INDIC_PARA, 2 for INDIC_RESU"),
        "{err}"
    );
}

#[test]
fn numpy_files_and_complex_functions_are_refused_before_running() {
    let err = refused(
        "numpy",
        &[(
            "LIRE_FONCTION(UNITE=21, NOM_PARA=\"EPSI\", PROL",
            "LIRE_FONCTION(UNITE=21, FORMAT=\"NUMPY\", NOM_PARA=\"EPSI\", PROL",
        )],
    );
    assert!(
        err.contains("not supported yet: LIRE_FONCTION/FORMAT='NUMPY'"),
        "{err}"
    );
    let err = refused(
        "complex",
        &[(
            "INDIC_PARA=(2, 1), INDIC_RESU=(2, 3))",
            "TYPE=\"FONCTION_C\")",
        )],
    );
    assert!(
        err.contains("not supported yet: LIRE_FONCTION/TYPE='FONCTION_C'"),
        "{err}"
    );
}
