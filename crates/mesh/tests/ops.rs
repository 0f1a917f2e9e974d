//! DEFI_GROUP and ORIE_PEAU on small meshes written here.

use aster_mesh::{parse_mail, CellId, Mesh, NodeId};
use std::path::Path;

/// Two unit squares side by side (M1 on the left, M2 on the right), their
/// outer edges as segments, some oriented clockwise on purpose.
const TWO_SQUARES: &str = "\
COOR_2D
N1 0 0
N2 1 0
N3 2 0
N4 0 1
N5 1 1
N6 2 1
FINSF
QUAD4
M1 N1 N2 N5 N4
M2 N2 N3 N6 N5
FINSF
SEG2
BOT1 N1 N2
BOT2 N3 N2
RIGHT N3 N6
TOP2 N5 N6
MID N2 N5
FINSF
GROUP_MA
LEFT_SQ M1
FINSF
GROUP_MA
RIGHT_SQ M2
FINSF
GROUP_MA
BOTTOM BOT1 BOT2
FINSF
GROUP_MA
OUTER BOT1 BOT2 RIGHT TOP2
FINSF
GROUP_MA
INNER MID
FINSF
GROUP_NO
CORNER N1
FINSF
GROUP_NO
EDGE N1 N4
FINSF
FIN
";

fn mesh() -> Mesh {
    parse_mail(TWO_SQUARES, Path::new("two.mail")).unwrap()
}

fn names(m: &Mesh, ids: &[NodeId]) -> Vec<String> {
    ids.iter()
        .map(|n| m.node_names[n.0 as usize].clone())
        .collect()
}

#[test]
fn tout_group_ma_makes_node_groups_in_node_order() {
    let mut m = mesh();
    let replaced = m.crea_group_no_tout_group_ma();
    assert!(replaced.is_empty());
    let g: Vec<&str> = m.groups_no.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(
        g,
        ["CORNER", "EDGE", "LEFT_SQ", "RIGHT_SQ", "BOTTOM", "OUTER", "INNER"]
    );
    assert_eq!(
        names(&m, &m.group_no("RIGHT_SQ").unwrap().members),
        ["N2", "N3", "N5", "N6"]
    );
    assert_eq!(
        names(&m, &m.group_no("BOTTOM").unwrap().members),
        ["N1", "N2", "N3"]
    );
}

#[test]
fn unions_intersections_differences() {
    let mut m = mesh();
    m.crea_group_no_from_group_ma("SQ", &["LEFT_SQ", "RIGHT_SQ"])
        .unwrap();
    assert_eq!(m.group_no("SQ").unwrap().members.len(), 6);
    m.crea_group_no_each_group_ma(&["LEFT_SQ", "RIGHT_SQ"])
        .unwrap();
    m.crea_group_no_intersec("SHARED", &["LEFT_SQ", "RIGHT_SQ"])
        .unwrap();
    assert_eq!(
        names(&m, &m.group_no("SHARED").unwrap().members),
        ["N2", "N5"]
    );
    m.crea_group_no_diffe("ONLY_LEFT", &["LEFT_SQ", "RIGHT_SQ"])
        .unwrap();
    assert_eq!(
        names(&m, &m.group_no("ONLY_LEFT").unwrap().members),
        ["N1", "N4"]
    );
    m.crea_group_no_union("U", &["CORNER", "EDGE"]).unwrap();
    assert_eq!(names(&m, &m.group_no("U").unwrap().members), ["N1", "N4"]);
    m.crea_group_no_from_nodes("P", &["N6", "N3"]).unwrap();
    assert_eq!(names(&m, &m.group_no("P").unwrap().members), ["N6", "N3"]);
    m.crea_group_ma_from_cells("C", &["MID", "M1"]).unwrap();
    assert_eq!(m.group_ma("C").unwrap().members, [CellId(6), CellId(0)]);
    m.crea_group_ma_intersec("I", &["OUTER", "BOTTOM"]).unwrap();
    assert_eq!(m.group_ma("I").unwrap().members, [CellId(2), CellId(3)]);
    m.crea_group_ma_diffe("D", &["OUTER", "BOTTOM"]).unwrap();
    assert_eq!(m.group_ma("D").unwrap().members, [CellId(4), CellId(5)]);
    assert!(m.crea_group_ma_tout("OUTER"), "replaces the existing group");
    assert_eq!(m.group_ma("OUTER").unwrap().members.len(), 7);
    m.detr_group_ma(&["OUTER"]).unwrap();
    assert!(m.group_ma("OUTER").is_none());
}

#[test]
fn unknown_names_suggest_the_closest() {
    let mut m = mesh();
    let e = m.crea_group_no_from_group_ma("X", &["BOTOM"]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "no GROUP_MA named `BOTOM` in the mesh; did you mean `BOTTOM`?"
    );
    let e = m.crea_group_no_union("X", &["CORNR"]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "no GROUP_NO named `CORNR` in the mesh; did you mean `CORNER`?"
    );
    let e = m.crea_group_no_from_nodes("X", &["N7"]).unwrap_err();
    assert!(e.to_string().starts_with("no node named `N7`"), "{e}");
    let e = m.orient_skin(&["OUTR"]).unwrap_err();
    assert!(e.to_string().contains("did you mean `OUTER`"), "{e}");
}

#[test]
fn orie_peau_2d_turns_normals_outwards() {
    let mut m = mesh();
    let report = m.orient_skin(&["OUTER"]).unwrap();
    assert_eq!(report.cells, 4);
    // BOT2 (N3→N2) and TOP2 (N5→N6) were clockwise around their square.
    assert_eq!(report.reversed, 2);
    let outward = [
        (2, [0.0, -1.0]),
        (3, [0.0, -1.0]),
        (4, [1.0, 0.0]),
        (5, [0.0, 1.0]),
    ];
    for (cell, expected) in outward {
        let n = m.skin_normal(m.cell(CellId(cell)));
        assert!(
            (n[0] - expected[0]).abs() < 1e-12 && (n[1] - expected[1]).abs() < 1e-12,
            "cell {cell}: {n:?}"
        );
    }
    // Idempotent.
    assert_eq!(m.orient_skin(&["OUTER"]).unwrap().reversed, 0);
}

#[test]
fn orie_peau_rejects_inner_boundaries_and_volumes() {
    let mut m = mesh();
    let e = m.orient_skin(&["INNER"]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "ORIE_PEAU: skin cell `MID` lies between cells `M1` and `M2`: an inner boundary has no outward side"
    );
    // Faces bounding no volume: left as they are, as code_aster's orilma.
    let before = m.clone();
    let r = m.orient_skin(&["LEFT_SQ"]).unwrap();
    assert_eq!((r.cells, r.reversed), (0, 0));
    assert!(r.untreated > 0);
    assert_eq!(m, before);
}

#[test]
fn orie_peau_3d_faces_of_a_hexahedron() {
    let text = "COOR_3D\nN1 0 0 0\nN2 1 0 0\nN3 1 1 0\nN4 0 1 0\nN5 0 0 1\nN6 1 0 1\nN7 1 1 1\nN8 0 1 1\nFINSF\n\
        HEXA8\nH N1 N2 N3 N4 N5 N6 N7 N8\nFINSF\nQUAD4\nBOTTOM N1 N2 N3 N4\nTOP N5 N6 N7 N8\nFINSF\n\
        TRIA3\nT N1 N2 N6\nFINSF\nGROUP_MA\nSKIN BOTTOM TOP T\nFINSF\nFIN\n";
    let mut m = parse_mail(text, Path::new("cube.mail")).unwrap();
    let r = m.orient_skin(&["SKIN"]).unwrap();
    assert_eq!((r.cells, r.reversed), (3, 1));
    let bottom = m.skin_normal(m.cell(CellId(1)));
    let top = m.skin_normal(m.cell(CellId(2)));
    let front = m.skin_normal(m.cell(CellId(3)));
    assert!(
        bottom[2] < 0.0 && top[2] > 0.0 && front[1] < 0.0,
        "{bottom:?} {top:?} {front:?}"
    );
    // code_aster's oriema: the corners in reverse order (N1 N2 N3 N4 →
    // N4 N3 N2 N1), not the first node kept.
    assert_eq!(
        m.cell(CellId(1)).nodes,
        [NodeId(3), NodeId(2), NodeId(1), NodeId(0)],
        "the corners reversed"
    );
}

#[test]
fn orie_peau_reverses_as_code_aster_oriema() {
    use aster_mesh::CellType;
    // Corners reversed, each edge middle following its edge, the centre kept.
    let cases: [(CellType, &[usize]); 5] = [
        (CellType::TRIA3, &[2, 1, 0]),
        (CellType::TRIA6, &[2, 1, 0, 4, 3, 5]),
        (CellType::QUAD8, &[3, 2, 1, 0, 6, 5, 4, 7]),
        (CellType::QUAD9, &[3, 2, 1, 0, 6, 5, 4, 7, 8]),
        (CellType::SEG3, &[1, 0, 2]),
    ];
    for (ty, perm) in cases {
        assert_eq!(ty.skin_reversal(), Some(perm), "{ty:?}");
    }
    // ORIE_NORM_COQUE's (iorim2) keeps the first node.
    assert_eq!(CellType::TRIA3.reversal(), Some(&[0, 2, 1][..]));
}
