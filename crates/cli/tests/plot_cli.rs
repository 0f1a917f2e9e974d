//! `aster plot` end to end: the project's functions scene writes tables and
//! curves (AGRAF, XMGRACE; its ./REPE_OUT/ files land in --out), `aster plot` draws them; errors name the file
//! and the column.

mod cli;

use cli::aster;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs comm/functions.comm once into a fresh folder; returns it.
fn scene_outputs() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("tempdir");
    let comm = root().join("comm/functions.comm");
    let mesh = root().join("comm/strip.mail");
    let out = dir.path().to_str().expect("utf-8 path");
    let (code, stdout, stderr) = aster(&[
        "run",
        "-q",
        comm.to_str().expect("path"),
        "--mesh",
        mesh.to_str().expect("path"),
        "--out",
        out,
    ]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    dir
}

/// The points of each curve of an SVG chart (the polylines drawn 2 px
/// wide; axes and ticks are 1 px), in pixels.
fn polylines(svg: &str) -> Vec<Vec<(f64, f64)>> {
    svg.split("<polyline")
        .skip(1)
        .filter(|p| {
            p.split('>')
                .next()
                .is_some_and(|tag| tag.contains("stroke-width=\"2\""))
        })
        .filter_map(|p| {
            let points = p.split("points=\"").nth(1)?.split('"').next()?;
            Some(
                points
                    .split_whitespace()
                    .filter_map(|xy| {
                        let (x, y) = xy.split_once(',')?;
                        Some((x.parse().ok()?, y.parse().ok()?))
                    })
                    .collect(),
            )
        })
        .collect()
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

#[test]
fn draws_an_impr_table_in_its_row_order() {
    let dir = scene_outputs();
    let table = dir.path().join("table.agraf");
    let svg = dir.path().join("xy.svg");
    let (code, stdout, stderr) = aster(&["plot", path(&table), "--out", path(&svg)]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("(1 curve)"), "{stdout}");
    let text = std::fs::read_to_string(&svg).expect("svg written");
    assert!(text.lines().any(|l| l.trim() == "XY"), "legend");
    // The curve (the first polyline; the second is its legend sample) has
    // the table's three rows in its order: X = 3, 2, 1 and XY = 90, 40, 10,
    // so leftwards and downwards (pixel y grows downwards) — and XY is not
    // linear in X: the first segment is steeper than the second.
    let curve = &polylines(&text)[0];
    assert_eq!(curve.len(), 3, "{curve:?}");
    assert!(
        curve[0].0 > curve[1].0 && curve[1].0 > curve[2].0,
        "{curve:?}"
    );
    assert!(
        curve[0].1 < curve[1].1 && curve[1].1 < curve[2].1,
        "{curve:?}"
    );
    let slope = |a: (f64, f64), b: (f64, f64)| (b.1 - a.1) / (a.0 - b.0);
    let (s1, s2) = (slope(curve[0], curve[1]), slope(curve[1], curve[2]));
    assert!((s1 / s2 - 50.0 / 30.0).abs() < 0.05, "slopes {s1} {s2}");
}

#[test]
fn draws_every_set_of_an_xmgrace_file_as_png() {
    let dir = scene_outputs();
    let curves = dir.path().join("curves.agr");
    let png = dir.path().join("curves.png");
    let (code, stdout, stderr) = aster(&["plot", path(&curves), "--out", path(&png), "--log-y"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("(2 curves)"), "{stdout}");
    let bytes = std::fs::read(&png).expect("png written");
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn filters_rows_and_names_columns() {
    let dir = tempfile::tempdir().expect("tempdir");
    let table = dir.path().join("releve.txt");
    std::fs::write(
        &table,
        "#\n#ASTER CONCEPT T\nNOEUD    NUME_ORDRE   INST         DX\n\
         N1                  1  1.00000E+00  1.00000E-03\n\
         N2                  1  1.00000E+00  5.00000E-03\n\
         N1                  2  2.00000E+00  2.00000E-03\n\
         N2                  2  2.00000E+00  6.00000E-03\n",
    )
    .expect("written");
    let svg = dir.path().join("n1.svg");
    let (code, stdout, stderr) = aster(&[
        "plot",
        path(&table),
        "--where",
        "NOEUD=n1",
        "--out",
        path(&svg),
    ]);
    assert_eq!(code, 0, "{stderr}");
    // INST is the default abscissa, NUME_ORDRE a counter: one curve, DX.
    assert!(stdout.contains("(1 curve)"), "{stdout}");
    let text = std::fs::read_to_string(&svg).expect("svg");
    assert_eq!(polylines(&text)[0].len(), 2, "N1's two rows");

    let (code, _, stderr) = aster(&["plot", path(&table), "--y", "DZ"]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("no column `DZ` (columns: NOEUD, NUME_ORDRE, INST, DX)"),
        "{stderr}"
    );
    let (code, _, stderr) = aster(&["plot", path(&table), "--where", "NOEUD"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("expected COLUMN=VALUE"), "{stderr}");
    let (code, _, stderr) = aster(&["plot", path(&table), "--where", "NOEUD=N9"]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("no row passes the --where filters"),
        "{stderr}"
    );
    let (code, _, stderr) = aster(&["plot", &format!("{}/missing.txt", path(dir.path()))]);
    assert_eq!(code, 2);
    assert!(stderr.contains("missing.txt"), "{stderr}");
}
