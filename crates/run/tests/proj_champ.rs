//! PROJ_CHAMP by collocation between non-matching meshes and IMPR_RESU
//! FORMAT='MED' restricted to groups (comm/proj_champ_2d.export,
//! comm/proj_champ_3d.export, written for the project): the analytic values
//! of linear, quadratic and cubic fields projected from QUAD8/HEXA20 meshes,
//! a node outside the source mesh (nearest point, DISTANCE_MAX, PROL_ZERO),
//! results projected at several instants, the MED profiles read back, and
//! the located refusals.

mod scene;

use scene::{root, run_case as run, temp};

/// The scene with its command file edited (`from` → `to`, each present),
/// run in a directory of its own: the error message.
fn refused(name: &str, edits: &[(&str, &str)]) -> String {
    scene::refused_export(
        "proj_champ_2d.comm",
        &["proj_quad8.mail", "proj_quad4.mail"],
        edits,
        &format!("proj-{name}"),
    )
}

/// A dataset of a MED file as integers.
fn ints(file: &aster_mesh::hdf5::H5File, path: &str) -> Vec<i64> {
    let obj = file
        .get(path)
        .unwrap()
        .unwrap_or_else(|| panic!("no {path}"));
    file.read(&obj).unwrap().to_i64().unwrap()
}

#[test]
fn projections_in_2d_and_med_profiles() {
    let out = temp("2d");
    let (outcome, report) = run(&root().join("comm/proj_champ_2d.export"), &out);
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    // 17 TEST_RESU values, each against VALE_CALC (1e-12) and the analytic
    // VALE_REFE.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (34, 0), "{report}");

    // The MED file: P on LEFT's nodes only (profile 1), resB on PB only
    // (profile 2); the whole mesh B is written.
    let med = out.join("fort.81");
    let mesh_b = aster_mesh::read_mail(&root().join("comm/proj_quad4.mail")).unwrap();
    let mut left: Vec<i64> = mesh_b
        .group_ma("LEFT")
        .unwrap()
        .members
        .iter()
        .flat_map(|&c| mesh_b.cell(c).nodes.iter().map(|n| n.0 as i64 + 1))
        .collect();
    left.sort();
    left.dedup();
    let pb = mesh_b.group_no("PB").unwrap().members[0].0 as i64 + 1;
    let file = aster_mesh::hdf5::H5File::open(&med).unwrap().unwrap();
    assert_eq!(ints(&file, "PROFILS/PROFIL__00000001/PFL"), left);
    assert_eq!(ints(&file, "PROFILS/PROFIL__00000002/PFL"), vec![pb]);
    assert!(file.get("PROFILS/PROFIL__00000003").unwrap().is_none());

    // Read back: the values where written, 0 elsewhere (the reader's rule
    // for nodes a profile leaves out).
    let read = aster_mesh::read_med(&med).unwrap();
    assert_eq!(read.node_count(), mesh_b.node_count());
    let steps = aster_mesh::read_med_steps(&med, &read, "P").unwrap();
    let p = steps
        .iter()
        .flat_map(|s| &s.fields)
        .find(|f| f.name == "P")
        .expect("field P");
    assert_eq!(p.components, vec!["X1".to_string()]);
    for (i, x) in mesh_b.coords.iter().enumerate() {
        let expected = if left.contains(&(i as i64 + 1)) {
            1.0 + 2.0 * x[0] - 3.0 * x[1]
        } else {
            0.0
        };
        assert!(
            (p.values[i] - expected).abs() < 1e-12,
            "node {i}: {}",
            p.values[i]
        );
    }
    let depl: Vec<_> = steps
        .iter()
        .flat_map(|s| s.fields.iter().map(move |f| (s.nume_ordre, f)))
        .filter(|(_, f)| f.name == "resBDEPL")
        .collect();
    assert_eq!(depl.len(), 2);
    let [x, y, _] = mesh_b.coords[pb as usize - 1];
    for (nume, f) in depl {
        let t = nume as f64;
        let k = (pb - 1) as usize * 2;
        assert!((f.values[k] - t * (1.0 + 2.0 * x - 3.0 * y)).abs() < 1e-12);
        assert!((f.values[k + 1] - t * (x * x + x * y - y * y)).abs() < 1e-12);
        let others: f64 = f.values.iter().map(|v| v.abs()).sum::<f64>()
            - f.values[k].abs()
            - f.values[k + 1].abs();
        assert_eq!(others, 0.0);
    }
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn projections_in_3d_and_on_faces() {
    let out = temp("3d");
    let (outcome, report) = run(&root().join("comm/proj_champ_3d.export"), &out);
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    // 18 TEST_RESU values, each against VALE_CALC (1e-12) and VALE_REFE.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (36, 0), "{report}");
    let _ = std::fs::remove_dir_all(out);
}

/// The 2D scene with its command file edited, run: the outcome and report.
fn edited(name: &str, edits: &[(&str, &str)]) -> (aster_run::program::Outcome, String) {
    let dir = temp(name);
    let mut text = std::fs::read_to_string(root().join("comm/proj_champ_2d.comm")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    std::fs::write(dir.join("case.comm"), text).unwrap();
    for mesh in ["proj_quad8.mail", "proj_quad4.mail"] {
        std::fs::copy(root().join("comm").join(mesh), dir.join(mesh)).unwrap();
    }
    std::fs::write(
        dir.join("case.export"),
        "F comm case.comm D 1\nF mail proj_quad8.mail D 20\nF mail proj_quad4.mail D 21\n",
    )
    .unwrap();
    let out = run(&dir.join("case.export"), &dir.join("out"));
    let _ = std::fs::remove_dir_all(&dir);
    out
}

#[test]
fn models_select_cells_and_nodes() {
    // MODELE_1 on every cell of A: the same values.
    let (outcome, report) = edited(
        "modele1",
        &[(
            "P = PROJ_CHAMP(METHODE=\"AUTO\", CHAM_GD=F, MAILLAGE_1=A, MAILLAGE_2=B)",
            "MA = AFFE_MODELE(MAILLAGE=A, AFFE=_F(TOUT=\"OUI\", PHENOMENE=\"MECANIQUE\", MODELISATION=\"D_PLAN\"))\n\
             P = PROJ_CHAMP(METHODE=\"AUTO\", CHAM_GD=F, MODELE_1=MA, MAILLAGE_2=B)",
        )],
    );
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (34, 0), "{report}");
    // MODELE_2 on B's cells: NOUT, in no cell of the model, gets no value.
    let (outcome, _) = edited(
        "modele2",
        &[(
            "P = PROJ_CHAMP(METHODE=\"AUTO\", CHAM_GD=F, MAILLAGE_1=A, MAILLAGE_2=B)",
            "MB = AFFE_MODELE(MAILLAGE=B, AFFE=_F(TOUT=\"OUI\", PHENOMENE=\"MECANIQUE\", MODELISATION=\"D_PLAN\"))\n\
             P = PROJ_CHAMP(METHODE=\"AUTO\", CHAM_GD=F, MAILLAGE_1=A, MODELE_2=MB)",
        )],
    );
    let error = outcome.error.expect("NOUT has no value").message;
    assert!(
        error.contains("the field has no component X1 at node N17"),
        "{error}"
    );
}

#[test]
fn a_node_left_without_value_is_not_tested() {
    // DISTANCE_MAX without PROL_ZERO: NOUT has no value, which TEST_RESU
    // says instead of printing a number.
    let error = refused(
        "dmax",
        &[(
            ", DISTANCE_MAX=0.1, PROL_ZERO=\"OUI\")",
            ", DISTANCE_MAX=0.1)",
        )],
    );
    assert!(
        error.contains("the field has no component X1 at node N17"),
        "{error}"
    );
}

#[test]
fn unsupported_methods_and_unknown_groups_are_refused_where_written() {
    let error = refused(
        "ecla",
        &[(
            "PROJ_CHAMP(METHODE=\"AUTO\"",
            "PROJ_CHAMP(METHODE=\"ECLA_PG\"",
        )],
    );
    assert!(
        error.contains("not supported yet: PROJ_CHAMP/METHODE='ECLA_PG'")
            && error.contains("case.comm:35:16"),
        "{error}"
    );
    let error = refused(
        "group",
        &[("GROUP_MA_1=\"SURF\"", "GROUP_MA_1=\"SURFACE\"")],
    );
    assert!(error.contains("SURFACE"), "{error}");
    let error = refused(
        "segments",
        &[(
            "VIS_A_VIS=_F(GROUP_MA_1=\"SURF\"",
            "VIS_A_VIS=_F(CAS_FIGURE=\"1.5D\", GROUP_MA_1=\"SURF\"",
        )],
    );
    assert!(
        error.contains("not supported yet: PROJ_CHAMP/VIS_A_VIS/CAS_FIGURE='1.5D'"),
        "{error}"
    );
    // One MED file, one mesh: a field of A beside fields of B is refused.
    let error = refused(
        "two-meshes",
        &[(
            "_F(RESULTAT=resB, GROUP_NO=\"PB\"),",
            "_F(RESULTAT=resB, GROUP_NO=\"PB\"), _F(CHAM_GD=F),",
        )],
    );
    assert!(
        error.contains(
            "not supported yet: IMPR_RESU/FORMAT='MED' with fields of several meshes in one file"
        ),
        "{error}"
    );
}
