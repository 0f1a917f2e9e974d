//! Results you can see: `aster run --vtu DIR` (every result, every step,
//! for ParaView) and `aster mesh RESULT.med` (fields and steps listed,
//! `--to vtu` keeping them). The two paths share no code above the VTU
//! writer: `run --vtu` converts the results in memory, `mesh` reads them
//! back from the MED file `IMPR_RESU` wrote, so equal arrays check both.

mod cli;

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-vtu-cli-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

use cli::aster;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The rows of the DataArray `name` of a VTU file.
fn array(vtu: &Path, name: &str) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(vtu).unwrap();
    let head = format!("Name=\"{name}\"");
    let at = text
        .find(&head)
        .unwrap_or_else(|| panic!("no {name} in {}", vtu.display()));
    let body = &text[at..];
    let body = &body[body.find('\n').unwrap() + 1..body.find("</DataArray>").unwrap()];
    body.lines()
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// two_plates.comm (contact between two plates, 8 TEST_RESU) with its
/// result also printed to MED unit 80.
fn two_plates_with_med(d: &Path) -> PathBuf {
    let text = std::fs::read_to_string(root().join("comm/two_plates.comm")).unwrap();
    assert!(text.contains("\nFIN()"));
    let text = text.replace(
        "\nFIN()",
        "\nIMPR_RESU(FORMAT='MED', UNITE=80, RESU=_F(RESULTAT=resu))\nFIN()",
    );
    let comm = d.join("two_plates.comm");
    std::fs::write(&comm, text).unwrap();
    comm
}

#[test]
fn run_vtu_writes_every_step_and_the_med_path_agrees() {
    let d = dir("run");
    let comm = two_plates_with_med(&d);
    let mail = root().join("comm/two_plates.mail");
    let (vtu, out) = (d.join("vtu"), d.join("out"));
    let (code, stdout, stderr) = aster(&[
        "run",
        s(&comm),
        "--mesh",
        s(&mail),
        "--out",
        s(&out),
        "--vtu",
        s(&vtu),
        "-q",
    ]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert!(stdout.ends_with("TEST_RESU: 8 OK, 0 NOOK\n"), "{stdout}");
    let pvd = std::fs::read_to_string(vtu.join("resu.pvd")).unwrap();
    insta::assert_snapshot!("two_plates_pvd", pvd);
    // Step 1: displacements, stresses and contact status.
    let step = vtu.join("resu_000001.vtu");
    let depl = array(&step, "DEPL");
    let cont = array(&step, "CONT_NOEU");
    assert_eq!((depl.len(), cont.len()), (85, 85));
    assert_eq!(array(&step, "SIEF_ELGA").len(), 83);
    // The scene integrates by SIMPSON: code_aster's CONT_NOEU (`mmmres`)
    // is written only at contact points that are nodes (`mmnumn`: AUTO or
    // NOEUD integration), so its status is 0 at every node here, while
    // the plates are pressed together (DY < 0 at every upper-plate node).
    let status: Vec<f64> = cont.iter().map(|r| r[0]).collect();
    assert!(status.iter().all(|&c| c == 0.0), "{status:?}");
    assert!(depl.iter().any(|r| r[1] < -0.04), "{depl:?}");
    // The MED file IMPR_RESU wrote, read back: the same steps and fields.
    let med = out.join("fort.80");
    let (code, listing, err) = aster(&["mesh", s(&med)]);
    assert_eq!(code, 0, "{err}");
    let fields = &listing[listing.find("fields:").unwrap()..];
    insta::assert_snapshot!("two_plates_med_fields", fields);
    let back = d.join("back/tp.vtu");
    let (code, _, err) = aster(&["mesh", s(&med), "--to", "vtu", "--out", s(&back)]);
    assert_eq!(code, 0, "{err}");
    let again = d.join("back/tp_000001.vtu");
    assert_eq!(array(&again, "resuDEPL"), depl);
    assert_eq!(array(&again, "resuCONT_NOEU"), cont);
    assert!(d.join("back/tp.pvd").exists() && d.join("back/tp_000000.vtu").exists());
    // --json lists them too, after the mesh summary.
    let (code, json, _) = aster(&["mesh", s(&med), "--json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["nodes"], 85);
    let names: Vec<&str> = v["fields"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    // CONT_NOEU of the contact elements (SIMPSON) from step 1 on.
    assert_eq!(names, ["resuDEPL", "resuSIEF_ELGA", "resuCONT_NOEU"]);
    assert_eq!(v["fields"][0]["steps"][1]["inst"], 1.0);
}

#[test]
fn med_to_med_keeps_the_fields() {
    let d = dir("med");
    let comm = two_plates_with_med(&d);
    let mail = root().join("comm/two_plates.mail");
    let out = d.join("out");
    let (code, _, err) = aster(&["run", s(&comm), "--mesh", s(&mail), "--out", s(&out), "-q"]);
    assert_eq!(code, 0, "{err}");
    let copy = d.join("copy.med");
    let (code, _, err) = aster(&[
        "mesh",
        s(&out.join("fort.80")),
        "--to",
        "med",
        "--out",
        s(&copy),
    ]);
    assert_eq!(code, 0, "{err}");
    let (_, a, _) = aster(&["mesh", s(&out.join("fort.80")), "--json"]);
    let (_, b, _) = aster(&["mesh", s(&copy), "--json"]);
    let (a, b): (serde_json::Value, serde_json::Value) = (
        serde_json::from_str(&a).unwrap(),
        serde_json::from_str(&b).unwrap(),
    );
    assert_eq!(a["fields"], b["fields"]);
}

#[test]
fn vtu_dir_that_cannot_be_made_is_an_error() {
    let d = dir("bad");
    let blocker = d.join("file");
    std::fs::write(&blocker, "").unwrap();
    let (code, _, err) = aster(&[
        "run",
        s(&root().join("comm/two_plates.comm")),
        "--mesh",
        s(&root().join("comm/two_plates.mail")),
        "--out",
        s(&d.join("out")),
        "--vtu",
        s(&blocker.join("sub")),
        "-q",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--vtu"), "{err}");
}
