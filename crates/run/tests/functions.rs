//! The project's functions-and-tables scene (comm/functions.comm on
//! comm/strip.mail): RECU_FONCTION, CALC_FONCTION (COMB, INTEGRE),
//! CALC_FONC_INTERP, CREA_TABLE, CALC_TABLE, TEST_FONCTION against analytic values, and
//! IMPR_FONCTION's XMGRACE file on a unit named by DEFI_FICHIER, and
//! IMPR_TABLE's.

mod common;

use common::Report;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn functions_and_tables_pass_and_the_curves_are_written() {
    let out = std::env::temp_dir().join(format!("aster-functions-{}", std::process::id()));
    let case = aster_run::program::prepare(
        &root().join("comm/functions.comm"),
        Some(&root().join("comm/strip.mail")),
        &out,
    )
    .unwrap();
    let report = Report::default();
    let outcome = aster_run::program::run(&case, Box::new(report.clone()));
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (16, 0));
    let report = report.text();
    // PILOTE: no image drawn, the text format written and said so; an
    // interactive display writes nothing.
    assert!(
        report.contains("<A> IMPR_TABLE: PILOTE='PNG': the image is not drawn"),
        "{report}"
    );
    assert!(
        report.contains("<A> IMPR_FONCTION: PILOTE='INTERACTIF': the graph is not shown"),
        "{report}"
    );
    let png = std::fs::read_to_string(out.join("table.png")).unwrap();
    assert!(png.contains("@s0 legend \"YY\""), "{png}");
    assert!(!out.join("shown.agr").exists());
    let agr = std::fs::read_to_string(out.join("curves.agr")).unwrap();
    assert!(agr.contains("@title \"strip\""), "{agr}");
    assert!(
        agr.contains("@target G0.S1\n@type xy\n1.0 10.0\n2.0 40.0\n3.0 90.0\n&"),
        "{agr}"
    );
    assert!(agr.contains("0.5 0.0004999999999999"), "{agr}");
    // AGRAF as code_aster's TraceAgraf writes it: the bounds are the
    // curve's box widened by 2.5 % of its size on each side.
    let dogr = std::fs::read_to_string(out.join("curves.dogr")).unwrap();
    assert_eq!(
        dogr,
        "#NOM DE LA FONCTION: f_xy\n  1.00000E+00  1.00000E+01\n  2.00000E+00  4.00000E+01\n  3.00000E+00  9.00000E+01\n\n"
    );
    let digr = std::fs::read_to_string(out.join("curves.digr")).unwrap();
    assert!(digr.starts_with("\nASPECT_GRAPHIQUE:\n"), "{digr}");
    assert!(
        digr.ends_with(
            "GRAPHIQUE:\nTitre :strip\nFrequence Grille X :0\nFrequence Grille Y :0\nEchelle X :0\nEchelle Y :0\nLegende X :X\n\
             Min X : 0.95\nMax X : 3.05\nMin Y : 8.0\nMax Y : 92.0\n  COURBE:\n     Trait :0\n     Couleur :0\n     Marqueur :0\n\
             \x20    Frequence Marqueur :0\n     Legende :f_xy\n     Tri :N\n     Abscisses : [ 1, 1]\n     Ordonnees : [ 1, 2]\n"
        ),
        "{digr}"
    );
    let table = std::fs::read_to_string(out.join("table.agraf")).unwrap();
    assert!(
        table.contains("\n  X              XY          \n"),
        "{table}"
    );
    assert!(
        table.contains("\n 1.0000000E+00  1.0000000E+01\n"),
        "{table}"
    );
    // IMPR_TABLE(FORMAT='XMGRACE'): X the abscissa, YY and XY one set
    // each, in the table's order (sorted by decreasing X).
    let agr = std::fs::read_to_string(out.join("table.agr")).unwrap();
    assert!(
        agr.contains("@xaxis label \"X\"\n@world xmin 0.0\n@world xmax 4.0\n"),
        "{agr}"
    );
    assert!(
        agr.contains(
            "@s0 legend \"YY\"\n@target G0.S0\n@type xy\n3.0 30.0\n2.0 20.0\n1.0 10.0\n&\n\
             @s1 legend \"XY\"\n@target G0.S1\n@type xy\n3.0 90.0\n2.0 40.0\n1.0 10.0\n&\n"
        ),
        "{agr}"
    );
    let _ = std::fs::remove_dir_all(out);
}
