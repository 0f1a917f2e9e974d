//! `aster mesh FILE --json` and `--to FORMAT --out PATH`.

mod cli;

use std::path::{Path, PathBuf};

const SQUARE: &str = "COOR_2D\nA 0 0\nB 1 0\nC 1 1\nD 0 1\nFINSF\nSEG2\nAB A B\nCD C D\nFINSF\nQUAD4\nQ A B C D\nFINSF\n\
    GROUP_MA\nSURF Q\nFINSF\nGROUP_MA\nBOTTOM AB\nFINSF\nGROUP_NO\nORIGIN A\nFINSF\nFIN\n";

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-mesh-cli-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

use cli::aster;

const EXPECTED: &str = r#"{"nodes":4,"cells":{"SEG2":2,"QUAD4":1},"groups_ma":["SURF","BOTTOM"],"groups_no":["ORIGIN"]}"#;

#[test]
fn json_summary_of_a_mail_file() {
    let p = dir().join("square.mail");
    std::fs::write(&p, SQUARE).unwrap();
    let (code, out, err) = aster(&["mesh", p.to_str().unwrap(), "--json"]);
    assert_eq!((code, err.as_str()), (0, ""));
    assert_eq!(out.trim_end(), EXPECTED);
}

#[test]
fn conversions_keep_the_summary() {
    let d = dir();
    let src = d.join("conv.mail");
    std::fs::write(&src, SQUARE).unwrap();
    for (format, name) in [("med", "conv.med"), ("mail", "conv2.mail")] {
        let out = d.join(name);
        let (code, _, err) = aster(&[
            "mesh",
            src.to_str().unwrap(),
            "--to",
            format,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{err}");
        let (code, json, err) = aster(&["mesh", out.to_str().unwrap(), "--json"]);
        assert_eq!(code, 0, "{err}");
        assert_eq!(json.trim_end(), EXPECTED, "through {format}");
    }
    let vtu = d.join("conv.vtu");
    let (code, _, err) = aster(&[
        "mesh",
        src.to_str().unwrap(),
        "--to",
        "vtu",
        "--out",
        vtu.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&vtu).unwrap();
    assert!(
        text.contains("<Piece NumberOfPoints=\"4\" NumberOfCells=\"3\">"),
        "{text}"
    );
}

#[test]
fn errors_exit_2_with_a_message() {
    let (code, out, err) = aster(&["mesh", "/no/such/mesh.med", "--json"]);
    assert_eq!((code, out.as_str()), (2, ""));
    assert!(
        err.starts_with("error: /no/such/mesh.med: cannot read the mesh file"),
        "{err}"
    );

    let p = dir().join("bad.mail");
    std::fs::write(&p, "COOR_2D\nN1 0 0\nFINSF\nQUAD5\nM1 N1 N1 N1 N1\nFINSF\n").unwrap();
    let (code, _, err) = aster(&["mesh", p.to_str().unwrap(), "--json"]);
    assert_eq!(code, 2);
    assert!(err.contains("bad.mail:4:1: unknown block `QUAD5`"), "{err}");

    let (code, _, err) = aster(&["mesh", p.to_str().unwrap(), "--to", "stl", "--out", "x"]);
    assert_eq!(code, 2);
    assert!(err.contains("error:"), "{err}");
}

#[test]
fn seed_mesh_summary() {
    let seed =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/cases/zzzz237/zzzz237a.mmed");
    if !seed.exists() {
        eprintln!("skipped: {} absent", seed.display());
        return;
    }
    let (code, out, _) = aster(&["mesh", seed.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0);
    assert_eq!(
        out.trim_end(),
        r#"{"nodes":10,"cells":{"SEG2":10,"QUAD4":2},"groups_ma":["AB","BC","CD","DA","ABCD","K1","K2","EF","FG","GH","HE","EFGH"],"groups_no":["A","B","C","D","R1","R2","E","F","G","H"]}"#
    );
}

/// An I-DEAS universal file (comm/ideas_bar.unv) as code_aster's PRE_IDEAS
/// converts it: the summary and the INFO_MAILLAGE-like report.
#[test]
fn ideas_universal_file_summary() {
    let unv = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../comm/ideas_bar.unv");
    let (code, out, err) = aster(&["mesh", unv.to_str().unwrap(), "--json"]);
    assert_eq!((code, err.as_str()), (0, ""));
    insta::assert_snapshot!("ideas_bar_json", out);
    let (code, out, _) = aster(&["mesh", unv.to_str().unwrap()]);
    assert_eq!(code, 0);
    insta::assert_snapshot!("ideas_bar_report", out);
}

/// A malformed universal file: a located error, exit 2.
#[test]
fn ideas_errors_are_located() {
    let p = dir().join("bad.unv");
    std::fs::write(
        &p,
        "    -1\n  2411\n         1         1         1        11\n   1.0D+00   oops\n    -1\n",
    )
    .unwrap();
    let (code, _, err) = aster(&["mesh", p.to_str().unwrap(), "--json"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("bad.unv:4:1: expected a coordinate in columns 1–25, found `1.0D+00oops`"),
        "{err}"
    );
}
