//! MED writing and reading on meshes built here: round trips, node-order
//! conventions, fields, and the errors of bad files.

use aster_mesh::hdf5::H5File;
use aster_mesh::med::read_med_bytes;
use aster_mesh::{
    med_bytes, parse_mail, read_mesh, CellType, Field, Mesh, MeshError, NodeId, ResultStep,
};
use std::path::{Path, PathBuf};

/// A 3D mesh with one cell of every type whose node order MED changes,
/// plus faces, edges and a point, and groups over all of them.
fn all_types_mesh() -> Mesh {
    let mut text = String::from("COOR_3D\n");
    for i in 1..=40 {
        let x = i as f64;
        text += &format!("N{i} {} {} {}\n", x * 0.5, (x * 1.3).sin(), (x * 0.7).cos());
    }
    text += "FINSF\n";
    let mut next = 1;
    let mut cell = |ty: CellType, text: &mut String| {
        let nodes: Vec<String> = (0..ty.node_count())
            .map(|k| format!("N{}", (k * 7 + next) % 40 + 1))
            .collect();
        *text += &format!("{}\nC{next} {}\nFINSF\n", ty.name(), nodes.join(" "));
        next += 1;
    };
    // In MED type order, so a round trip keeps cell numbering.
    for ty in [
        CellType::POI1,
        CellType::SEG2,
        CellType::SEG3,
        CellType::TRIA3,
        CellType::QUAD4,
        CellType::TRIA6,
        CellType::TRIA7,
        CellType::QUAD8,
        CellType::QUAD9,
        CellType::TETRA4,
        CellType::PYRAM5,
        CellType::PENTA6,
        CellType::HEXA8,
        CellType::TETRA10,
        CellType::PYRAM13,
        CellType::PENTA15,
        CellType::PENTA18,
        CellType::HEXA20,
        CellType::HEXA27,
    ] {
        cell(ty, &mut text);
    }
    text += "GROUP_MA\nVOLUMES C10 C11 C12 C13 C14 C15 C16 C17 C18 C19\nFINSF\n";
    text += "GROUP_MA NOM=FACES\nC4 C5 C6 C7 C8 C9\nFINSF\n";
    text += "GROUP_MA\nQUADRATIC C3 C6 C7 C8 C9 C14 C15 C16 C17 C18 C19\nFINSF\n";
    text += "GROUP_NO\nFIRST N1 N2 N3\nFINSF\nGROUP_NO\nODD N1 N3 N5 N7\nFINSF\nFIN\n";
    parse_mail(&text, Path::new("all.mail")).unwrap()
}

fn roundtrip(mesh: &Mesh) -> Mesh {
    let bytes = med_bytes(mesh, "ALL", &[]).unwrap();
    read_med_bytes(bytes, Path::new("mem.med"), None).unwrap().0
}

#[test]
fn every_cell_type_round_trips_exactly() {
    let mesh = all_types_mesh();
    let back = roundtrip(&mesh);
    assert_eq!(back.dim, 3);
    assert_eq!(
        back.coords, mesh.coords,
        "coordinates are stored bit for bit"
    );
    assert_eq!(
        back.cells, mesh.cells,
        "cell types and code_aster node order survive"
    );
    assert_eq!(back.node_names, mesh.node_names);
    assert_eq!(back.cell_names, mesh.cell_names);
    assert_eq!(back.groups_ma, mesh.groups_ma, "groups, members and order");
    assert_eq!(back.groups_no, mesh.groups_no);
}

#[test]
fn hexa8_is_stored_in_med_order() {
    // code_aster's HEXA8 1..8 is MED's 1,4,3,2,5,8,7,6 (the faces turn the other way).
    let text = "COOR_3D\nN1 0 0 0\nN2 1 0 0\nN3 1 1 0\nN4 0 1 0\nN5 0 0 1\nN6 1 0 1\nN7 1 1 1\nN8 0 1 1\nFINSF\n\
        HEXA8\nH1 N1 N2 N3 N4 N5 N6 N7 N8\nFINSF\nFIN\n";
    let mesh = parse_mail(text, Path::new("h.mail")).unwrap();
    let file = H5File::from_bytes(med_bytes(&mesh, "H", &[]).unwrap()).unwrap();
    let nod = file
        .get("ENS_MAA/H/-0000000000000000001-0000000000000000001/MAI/HE8/NOD")
        .unwrap()
        .unwrap();
    assert_eq!(
        file.read(&nod).unwrap().to_i64().unwrap(),
        [1, 4, 3, 2, 5, 8, 7, 6]
    );
}

#[test]
fn cells_come_back_grouped_by_med_type() {
    let text = "COOR_2D\nN1 0 0\nN2 1 0\nN3 1 1\nN4 0 1\nFINSF\nQUAD4\nQ N1 N2 N3 N4\nFINSF\nSEG2\nS N1 N2\nFINSF\n\
        GROUP_MA\nALL Q S\nFINSF\nFIN\n";
    let mesh = parse_mail(text, Path::new("q.mail")).unwrap();
    let back = roundtrip(&mesh);
    assert_eq!(
        back.cell_names,
        ["S", "Q"],
        "MED stores segments before quadrangles"
    );
    assert_eq!(back.cells[1], mesh.cells[0]);
    let names: Vec<&str> = back
        .group_ma("ALL")
        .unwrap()
        .members
        .iter()
        .map(|c| back.cell_names[c.0 as usize].as_str())
        .collect();
    assert_eq!(names, ["S", "Q"]);
}

#[test]
fn default_names_are_not_stored_and_come_back() {
    let text = "COOR_2D\nN1 0 0\nN2 1 0\nFINSF\nSEG2\nM1 N1 N2\nFINSF\nFIN\n";
    let mesh = parse_mail(text, Path::new("d.mail")).unwrap();
    let bytes = med_bytes(&mesh, "D", &[]).unwrap();
    let file = H5File::from_bytes(bytes.clone()).unwrap();
    assert!(file
        .get("ENS_MAA/D/-0000000000000000001-0000000000000000001/NOE/NOM")
        .unwrap()
        .is_none());
    let back = read_med_bytes(bytes, Path::new("d.med"), None).unwrap().0;
    assert_eq!(back.node_names, ["N1", "N2"]);
    assert_eq!(back.cell_names, ["M1"]);
}

#[test]
fn fields_are_written_component_after_component() {
    let text = "COOR_2D\nN1 0 0\nN2 1 0\nN3 1 1\nN4 0 1\nFINSF\nSEG2\nS N1 N2\nFINSF\nQUAD4\nQ N1 N2 N3 N4\nFINSF\nFIN\n";
    let mesh = parse_mail(text, Path::new("f.mail")).unwrap();
    let depl = Field::nodal(
        "RESU____DEPL",
        &["DX", "DY"],
        vec![0.0, 0.1, 1.0, 1.1, 2.0, 2.1, 3.0, 3.1],
    );
    let sief = Field::gauss(
        "RESU____SIEF_ELGA",
        &["SIXX"],
        vec![0, 4],
        vec![1.0, 2.0, 3.0, 6.0],
    );
    let steps = [
        ResultStep {
            nume_ordre: 1,
            inst: 0.5,
            fields: vec![depl.clone(), sief],
        },
        ResultStep {
            nume_ordre: 2,
            inst: 1.0,
            fields: vec![depl],
        },
    ];
    let file = H5File::from_bytes(med_bytes(&mesh, "F", &steps).unwrap()).unwrap();
    let co = |path: &str| {
        let o = file
            .get(path)
            .unwrap()
            .unwrap_or_else(|| panic!("{path} missing"));
        file.read(&o).unwrap().to_f64().unwrap()
    };
    assert_eq!(
        co("CHA/RESU____DEPL/00000000000000000001-0000000000000000001/NOE/MED_NO_PROFILE_INTERNAL/CO"),
        [0.0, 1.0, 2.0, 3.0, 0.1, 1.1, 2.1, 3.1]
    );
    let sief = co("CHA/RESU____SIEF_ELGA/00000000000000000001-0000000000000000001/MAI.QU4/MED_NO_PROFILE_INTERNAL/CO");
    assert_eq!(sief, [3.0], "Gauss values are averaged per cell");
    let cha = file.get("CHA/RESU____DEPL").unwrap().unwrap();
    assert_eq!(
        file.attribute(&cha, "NCO").unwrap().unwrap().as_i64(),
        Some(2)
    );
    assert_eq!(
        file.attribute(&cha, "NOM")
            .unwrap()
            .unwrap()
            .as_string()
            .unwrap(),
        "DX              DY"
    );
    let step2 = file
        .get("CHA/RESU____DEPL/00000000000000000002-0000000000000000001")
        .unwrap()
        .unwrap();
    assert_eq!(
        file.attribute(&step2, "PDT").unwrap().unwrap().as_f64(),
        Some(1.0)
    );
}

#[test]
fn a_field_of_the_wrong_size_is_refused() {
    let mesh = all_types_mesh();
    let bad = ResultStep {
        nume_ordre: 1,
        inst: 0.0,
        fields: vec![Field::nodal("D", &["DX"], vec![1.0; 3])],
    };
    let e = med_bytes(&mesh, "M", &[bad]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "field `D` has 3 values where the mesh needs 40"
    );
}

#[test]
fn groups_of_many_families_and_big_groups_survive() {
    // 300 nodes in 100 overlapping groups: many families, B-trees with several levels.
    let mut text = String::from("COOR_1D\n");
    for i in 1..=300 {
        text += &format!("N{i} {i}\n");
    }
    text += "FINSF\n";
    for g in 0..100 {
        text += &format!("GROUP_NO\nG{g:03}");
        for i in (g + 1..=300).step_by(g + 1) {
            text += &format!(" N{i}");
        }
        text += "\nFINSF\n";
    }
    let mesh = parse_mail(&text, Path::new("many.mail")).unwrap();
    let back = roundtrip(&mesh);
    assert_eq!(back.dim, 1);
    assert_eq!(back.groups_no, mesh.groups_no);
}

fn temp(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("aster-mesh-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

#[test]
fn missing_file_is_a_clear_error() {
    let e = read_mesh(Path::new("/nonexistent/dir/mesh.med")).unwrap_err();
    assert!(matches!(e, MeshError::Io { .. }));
    assert!(
        e.to_string()
            .starts_with("/nonexistent/dir/mesh.med: cannot read the mesh file: "),
        "{e}"
    );
}

#[test]
fn non_hdf5_and_truncated_files_are_clear_errors() {
    let p = temp("text.med", b"this is not HDF5 at all\n");
    let e = read_mesh(&p).unwrap_err();
    assert!(
        e.to_string().ends_with(
            "text.med: cannot read as a MED file: not an HDF5 file (no HDF5 signature found)"
        ),
        "{e}"
    );

    let bytes = med_bytes(&all_types_mesh(), "ALL", &[]).unwrap();
    let p = temp("cut.med", &bytes[..bytes.len() / 2]);
    let e = read_mesh(&p).unwrap_err();
    assert!(e.to_string().contains("truncated HDF5 file"), "{e}");
}

#[test]
fn an_hdf5_file_that_is_not_med_says_so() {
    use aster_mesh::hdf5::write::{to_bytes, Node};
    let bytes = to_bytes(&Node::group(
        "",
        vec![],
        vec![Node::f64s("DATA", vec![], &[1.0])],
    ));
    let p = temp("plain.h5.med", &bytes);
    let e = read_mesh(&p).unwrap_err();
    assert!(
        e.to_string()
            .ends_with("not a MED mesh file: no `ENS_MAA` group (is it a MED result-only file?)"),
        "{e}"
    );
}

#[test]
fn unknown_extension_without_mesh_content() {
    let p = temp("notes.xyz", b"hello");
    let e = read_mesh(&p).unwrap_err();
    assert!(e.to_string().contains("unknown mesh format"), "{e}");
}

#[test]
fn first_node_of_every_cell_is_valid_after_roundtrip() {
    let back = roundtrip(&all_types_mesh());
    assert!(back
        .cells
        .iter()
        .flat_map(|c| &c.nodes)
        .all(|n| (n.0 as usize) < back.node_count()));
    assert_eq!(back.cells[0].nodes, [NodeId(1)]);
}

/// A family header whose `NUM` attribute is damaged: the file still reads,
/// and the reader says which entities lost their groups instead of
/// dropping the groups silently.
#[test]
fn a_damaged_family_header_is_reported() {
    let text = "COOR_2D\nN1 0 0\nN2 1 0\nN3 1 1\nFINSF\nSEG2\nM1 N1 N2\nM2 N2 N3\nFINSF\nGROUP_MA\nLOW M1\nFINSF\nGROUP_MA\nSIDE M2\nFINSF\nGROUP_NO\nTOP N3\nFINSF\nFIN\n";
    let mesh = parse_mail(text, Path::new("fam.mail")).unwrap();
    let bytes = med_bytes(&mesh, "M", &[]).unwrap();
    let (intact, info) = read_med_bytes(bytes.clone(), Path::new("fam.med"), None).unwrap();
    assert_eq!(intact.groups_ma.len(), 2);
    assert!(info.warnings.is_empty(), "{:?}", info.warnings);
    // Rename every `NUM` attribute: no family is defined any more.
    let mut damaged = bytes;
    let mut hits = 0;
    for i in 0..damaged.len().saturating_sub(4) {
        if &damaged[i..i + 4] == b"NUM\0" {
            damaged[i + 2] = b'X';
            hits += 1;
        }
    }
    assert!(
        hits > 0,
        "the writer stores family numbers as NUM attributes"
    );
    let (broken, info) = read_med_bytes(damaged, Path::new("fam.med"), None).unwrap();
    assert!(broken.groups_ma.is_empty() && broken.groups_no.is_empty());
    let text = info.warnings.join("\n");
    assert!(
        text.contains("1 node(s) belong to family")
            && text.contains("cell(s) belong to family")
            && text.contains("which the file does not define"),
        "{text}"
    );
}
