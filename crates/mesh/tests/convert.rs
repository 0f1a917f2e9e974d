//! GMSH and GIBI files the project wrote (comm/study.msh, study41.msh,
//! square3.mgib), read as code_aster's PRE_GMSH / PRE_GIBI convert them:
//! node and cell names, cell order (type by type), groups, coordinates.

use aster_mesh::{read_mesh, CellType, Mesh};
use std::path::PathBuf;

fn comm(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../comm")
        .join(name)
}

fn names_of_group(m: &Mesh, g: &str) -> Vec<String> {
    m.group_ma(g)
        .unwrap()
        .members
        .iter()
        .map(|c| m.cell_names[c.0 as usize].clone())
        .collect()
}

#[test]
fn gmsh_22_as_pre_gmsh_converts_it() {
    let m = read_mesh(&comm("study.msh")).unwrap();
    // PRE_GMSH always writes COOR_3D.
    assert_eq!(m.dim, 3);
    assert_eq!(m.node_names, ["N1", "N2", "N3", "N4", "N5", "N6"]);
    // Cells type by type (GMSH types 1 SEG2, 3 QUAD4, 15 POI1), file order within.
    assert_eq!(m.cell_names, ["M2", "M3", "M4", "M5", "M1"]);
    let types: Vec<CellType> = m.cells.iter().map(|c| c.ty).collect();
    assert_eq!(
        types,
        [
            CellType::SEG2,
            CellType::SEG2,
            CellType::QUAD4,
            CellType::QUAD4,
            CellType::POI1
        ]
    );
    // Groups named by $PhysicalNames, in their order (code_aster 17's
    // pregms/gmlelt for 2.x files).
    let groups: Vec<&str> = m.groups_ma.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(groups, ["corner", "left", "right", "half1", "half2"]);
    assert_eq!(names_of_group(&m, "half1"), ["M4"]);
    // A physical group of one point cell is also a node group.
    assert_eq!(m.groups_no.len(), 1);
    assert_eq!(
        m.node_names[m.group_no("corner").unwrap().members[0].0 as usize],
        "N1"
    );
}

#[test]
fn gmsh_41_reads_as_the_same_mesh() {
    let a = read_mesh(&comm("study.msh")).unwrap();
    let b = read_mesh(&comm("study41.msh")).unwrap();
    assert_eq!(a, b);
}

#[test]
fn gibi_level_3_with_an_indirection() {
    let m = read_mesh(&comm("square3.mgib")).unwrap();
    assert_eq!(m.dim, 2);
    // The coordinate indices the indirection reaches (point 7 is not), sorted.
    assert_eq!(m.node_names, ["N1", "N2", "N3", "N4", "N5", "N6"]);
    assert_eq!(m.coords[0], [2.0, 1.0, 0.0]);
    assert_eq!(m.cell_names, ["M1", "M2", "M3"]);
    // Point p is coordinate 7 - p: the first quad (points 1 2 5 4).
    let first: Vec<&str> = m.cells[0]
        .nodes
        .iter()
        .map(|n| m.node_names[n.0 as usize].as_str())
        .collect();
    assert_eq!(first, ["N6", "N5", "N2", "N3"]);
    assert_eq!(names_of_group(&m, "PLAQ"), ["M1", "M2"]);
    assert_eq!(names_of_group(&m, "BAS"), ["M3"]);
    assert_eq!(
        m.node_names[m.group_no("PA").unwrap().members[0].0 as usize],
        "N1"
    );
}

/// comm/ideas_bar.unv (made by comm/ideas_bar.py) as PRE_IDEAS converts it.
#[test]
fn ideas_as_pre_ideas_converts_it() {
    let m = read_mesh(&comm("ideas_bar.unv")).unwrap();
    assert_eq!(m.dim, 3);
    // Every node, in file order, named from its label 10 + 3 k.
    assert_eq!(m.node_count(), 32);
    assert_eq!(m.node_names[0], "N10");
    assert_eq!(m.node_names[31], "N103");
    // Cells by graphic code (SEG3 is code 35, last), file order within.
    assert_eq!(m.cell_names, ["M20", "M5", "M9", "M21"]);
    let types: Vec<CellType> = m.cells.iter().map(|c| c.ty).collect();
    assert_eq!(
        types,
        [
            CellType::QUAD8,
            CellType::HEXA20,
            CellType::HEXA20,
            CellType::SEG3
        ]
    );
    // The SEG3's third node is its middle; the HEXA20's 9th the middle of
    // its edge 1-2; the QUAD8's 5th the middle of its edge 1-2.
    for (cell, a, b, mid) in [(3usize, 0usize, 1usize, 2usize), (1, 0, 1, 8), (0, 0, 1, 4)] {
        let n = &m.cells[cell].nodes;
        let (pa, pb, pm) = (m.coord(n[a]), m.coord(n[b]), m.coord(n[mid]));
        for d in 0..3 {
            assert_eq!(pm[d], (pa[d] + pb[d]) / 2.0, "cell {cell}");
        }
    }
    // Names: 8 characters, cut at a point, PERMANENT groups by number.
    let groups: Vec<&str> = m.groups_ma.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(groups, ["END", "SOFT", "GRMA7", "EDGE"]);
    let groups: Vec<&str> = m.groups_no.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(groups, ["LEFTSIDE", "BOTTOM", "BACK", "MID", "END"]);
    assert_eq!(names_of_group(&m, "GRMA7"), ["M9"]);
    assert!(m
        .group_no("MID")
        .unwrap()
        .members
        .iter()
        .all(|&n| m.coord(n)[0] == 1.0));
}
