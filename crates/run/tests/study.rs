//! Studies as code_aster runs them (comm/study.export, written for the
//! project): two command files in one process, POURSUITE continuing with
//! the concepts and plain values of the first (not its functions), a Python
//! module beside them, a GMSH mesh, POST_ELEM energies against the exact
//! plane-strain value; and the located errors around them.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-study-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs a case; returns the outcome and the report text.
fn run(case: &Path, out: &Path) -> (aster_run::program::Outcome, String) {
    let prepared = aster_run::program::prepare(case, None, out).unwrap();
    let buf = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    struct W(std::rc::Rc<std::cell::RefCell<Vec<u8>>>);
    impl std::io::Write for W {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0.borrow_mut().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let outcome = aster_run::program::run(&prepared, Box::new(W(buf.clone())));
    let text = String::from_utf8(buf.borrow().clone()).unwrap();
    (outcome, text)
}

#[test]
fn two_files_a_module_and_a_gmsh_mesh() {
    let out = temp("scene");
    let (outcome, report) = run(&root().join("comm/study.export"), &out);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (12, 0), "{report}");
    // The energy table as IMPR_TABLE prints it: the whole mesh (by its
    // internal name, a concept counter's), then each half.
    assert!(
        report.contains(
            "           1  0.00000E+00 00000002                 TOUT      2.19780E-01  1.00000E+02"
        ),
        "{report}"
    );
    assert!(
        report.contains("half2                    GROUP_MA  1.09890E-01  5.00000E+01"),
        "{report}"
    );
    // `F resu study.resu R 8`: the report is also written there, with the summary.
    let resu = std::fs::read_to_string(out.join("study.resu")).unwrap();
    assert!(resu.starts_with(&report), "the .resu file is the report");
    assert!(resu.ends_with("TEST_RESU: 12 OK, 0 NOOK\n"), "{resu}");
    let _ = std::fs::remove_dir_all(out);
}

/// A study written into a fresh folder: the files, then the outcome's
/// error (rendered) and report.
fn study(name: &str, files: &[(&str, &str)]) -> (Option<String>, String, PathBuf) {
    let dir = temp(name);
    for (f, text) in files {
        std::fs::write(dir.join(f), text).unwrap();
    }
    let (outcome, report) = run(&dir.join("s.export"), &dir.join("out"));
    (outcome.error.map(|e| e.message), report, dir)
}

#[test]
fn poursuite_keeps_values_and_concepts_but_not_functions() {
    let first = "DEBUT()\nx = 2.5\nnames = ['a', 'b']\ndef twice(v):\n    return 2 * v\nt = CREA_TABLE(LISTE=_F(PARA='V', LISTE_R=(twice(x),)))\nFIN()\n";
    let second = "POURSUITE()\nTEST_TABLE(TABLE=t, NOM_PARA='V', VALE_CALC=5.0)\nassert names == ['a', 'b'] and x == 2.5\nFIN()\n";
    let (error, report, dir) = study(
        "values",
        &[
            ("s.export", "F comm s.comm D 1\nF comm s.com1 D 1\n"),
            ("s.comm", first),
            ("s.com1", second),
        ],
    );
    assert!(error.is_none(), "{error:?}");
    assert!(report.contains(" OK "), "{report}");
    let _ = std::fs::remove_dir_all(dir);
    // A function defined before POURSUITE is not restored (code_aster
    // pickles values and concepts only): the static pass over the whole
    // study finds the name error before anything runs.
    let second = second.replace("FIN()", "y = twice(x)\nFIN()");
    let (error, _, dir) = study(
        "functions",
        &[
            ("s.export", "F comm s.comm D 1\nF comm s.com1 D 1\n"),
            ("s.comm", first),
            ("s.com1", &second),
        ],
    );
    let error = error.expect("twice is not restored");
    let error = error.replace(&dir.display().to_string(), "DIR");
    insta::assert_snapshot!(error, @r"
    DIR/s.com1:4:5: error: name `twice` is not defined
      |
    4 | y = twice(x)
      |     ^^^^^
    aster run: 1 reason to refuse this case, found before running anything
    ");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_module_the_export_does_not_give_is_located() {
    let (error, _, dir) = study(
        "nomodule",
        &[
            ("s.export", "F comm s.comm D 1\nF nom helpers.py D 0\n"),
            ("helpers.py", "A = 1\n"),
            ("s.comm", "DEBUT()\nfrom helper import *\nFIN()\n"),
        ],
    );
    let error = error.unwrap().replace(&dir.display().to_string(), "DIR");
    insta::assert_snapshot!(error, @r"
    DIR/s.comm:2:1: error: not supported: import from module `helper`
      |
    2 | from helper import *
      | ^^^^^^^^^^^^^^^^^^^^
      = the study's own modules are the `.export`'s `F nom <module>.py D 0` files (helpers)
    aster run: 1 reason to refuse this case, found before running anything
    ");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_error_inside_a_module_names_the_module_file() {
    let (error, _, dir) = study(
        "modulerr",
        &[
            ("s.export", "F comm s.comm D 1\nF nom helpers.py D 0\n"),
            ("helpers.py", "A = 1\nB = A + undefined_name\n"),
            (
                "s.comm",
                "DEBUT()\nimport helpers\nprint(helpers.A)\nFIN()\n",
            ),
        ],
    );
    let error = error.unwrap().replace(&dir.display().to_string(), "DIR");
    insta::assert_snapshot!(error, @r"
    DIR/helpers.py:2:9: error: name `undefined_name` is not defined
      |
    2 | B = A + undefined_name
      |         ^^^^^^^^^^^^^^
    aster run: 1 reason to refuse this case, found before running anything
    ");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_bad_gmsh_line_is_located_in_the_mesh_file() {
    let (error, _, dir) = study(
        "badmsh",
        &[
            ("s.export", "F comm s.comm D 1\nF msh m.msh D 19\n"),
            ("m.msh", "$NOD\n2\n1 0 0 0\n2 1 0\n$ENDNOD\n"),
            (
                "s.comm",
                "DEBUT()\nm = LIRE_MAILLAGE(FORMAT='GMSH', UNITE=19)\nFIN()\n",
            ),
        ],
    );
    let error = error.unwrap().replace(&dir.display().to_string(), "DIR");
    insta::assert_snapshot!(error, @r"
    DIR/s.comm:2:5: error: LIRE_MAILLAGE: DIR/m.msh:4:6: a node (number x y z): expected 4 values, found 3
      |
    2 | m = LIRE_MAILLAGE(FORMAT='GMSH', UNITE=19)
      |     ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^
    ");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn mesh_adaptation_is_refused_with_its_reason() {
    let (error, _, dir) = study(
        "homard",
        &[
            ("s.export", "F comm s.comm D 1\nF mail m.mail D 20\n"),
            ("m.mail", "COOR_2D\nN1 0 0\nN2 1 0\nFINSF\nSEG2\nM1 N1 N2\nFINSF\nFIN\n"),
            (
                "s.comm",
                "DEBUT()\nm = LIRE_MAILLAGE(FORMAT='ASTER')\nMACR_ADAP_MAIL(ADAPTATION='RAFFINEMENT_UNIFORME', MAILLAGE_N=m, MAILLAGE_NP1=CO('m2'))\nFIN()\n",
            ),
        ],
    );
    let error = error.unwrap().replace(&dir.display().to_string(), "DIR");
    assert!(
        error.contains("DIR/s.comm:3:16: error: not supported yet: MACR_ADAP_MAIL/ADAPTATION='RAFFINEMENT_UNIFORME' (mesh adaptation runs the external HOMARD tool, which aster does not have)"),
        "{error}"
    );
    let _ = std::fs::remove_dir_all(dir);
}
