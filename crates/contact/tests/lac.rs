//! LAC mortar integrals (module `lac`) on small meshes written here: a
//! slave block above a master block, with a known gap and overlap.

use aster_contact::lac::LacZone;
use aster_contact::{ResolvedZone, ZoneGeometry};
use aster_mesh::{decoupe_lac, Cell, CellId, CellType, Group, Mesh, NodeId};

/// Upper unit square [x0, x0 + 1] x [gap, gap + 1] (one QUAD4, bottom edge
/// "S") over a lower block [0, 2] x [-1, 0] (two QUAD4, top edges "M").
fn blocks(x0: f64, gap: f64) -> Mesh {
    let coords = vec![
        [x0, gap, 0.0],
        [x0 + 1.0, gap, 0.0],
        [x0 + 1.0, gap + 1.0, 0.0],
        [x0, gap + 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [2.0, -1.0, 0.0],
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
    ];
    let n = |i: u32| NodeId(i);
    let cells = vec![
        Cell {
            ty: CellType::QUAD4,
            nodes: vec![n(0), n(1), n(2), n(3)],
        },
        Cell {
            ty: CellType::QUAD4,
            nodes: vec![n(4), n(5), n(8), n(7)],
        },
        Cell {
            ty: CellType::QUAD4,
            nodes: vec![n(5), n(6), n(9), n(8)],
        },
        Cell {
            ty: CellType::SEG2,
            nodes: vec![n(0), n(1)],
        },
        Cell {
            ty: CellType::SEG2,
            nodes: vec![n(8), n(7)],
        },
        Cell {
            ty: CellType::SEG2,
            nodes: vec![n(9), n(8)],
        },
    ];
    Mesh {
        dim: 2,
        node_names: (1..=coords.len()).map(|i| format!("N{i}")).collect(),
        cell_names: (1..=cells.len()).map(|i| format!("M{i}")).collect(),
        coords,
        cells,
        groups_ma: vec![
            Group {
                name: "S".into(),
                members: vec![CellId(3)],
            },
            Group {
                name: "M".into(),
                members: vec![CellId(4), CellId(5)],
            },
        ],
        groups_no: vec![],
    }
}

fn zone_of(x0: f64, gap: f64, axis: bool) -> (Mesh, ResolvedZone, LacZone) {
    let (mesh, patches) = decoupe_lac(&blocks(x0, gap), &["S"]).unwrap();
    let zone = ResolvedZone::new(0, &ZoneGeometry::new("M", "S"), &mesh).unwrap();
    let mut lac = LacZone::new(&zone, patches.zone("S").unwrap()).unwrap();
    assert_eq!(lac.patches.len(), 1);
    assert_eq!(
        lac.patches[0].cells.len(),
        3,
        "a QUAD4 edge is cut in three"
    );
    lac.axis = axis;
    lac.pair(&zone, &mesh.coords);
    (mesh, zone, lac)
}

#[test]
fn covered_patch_integrates_its_gap_exactly() {
    // The slave edge [0.3, 1.3] straddles the two master edges at x = 1.
    let (mesh, zone, lac) = zone_of(0.3, 0.1, false);
    let st = &lac.state[0];
    assert!((st.measure - 1.0).abs() < 1e-14, "{}", st.measure);
    assert!((st.paired - 1.0).abs() < 1e-14);
    assert!((st.mean_gap() - 0.1).abs() < 1e-14, "{}", st.mean_gap());
    assert!((st.coverage() - 1.0).abs() < 1e-14);
    // Three pieces, the last one on both master edges: 4 pairs.
    assert_eq!((lac.pairs.len(), st.pairs), (4, 4));
    // The row is the force direction: -DY on the slave side (total
    // measure 1), +DY on the master side, no DX on a horizontal interface;
    // its right-hand side the integrated gap.
    let rows = lac.rows(&mesh, &zone, &mesh.coords, None);
    assert_eq!(rows.len(), 1);
    let (mut slave, mut master) = (0.0, 0.0);
    for (d, c) in &rows[0].terms {
        assert_eq!(d.comp, aster_fem::Comp::DY, "{d:?}");
        if d.node.0 < 4 || d.node.0 >= 10 {
            slave += c;
        } else {
            master += c;
        }
    }
    assert!((slave + 1.0).abs() < 1e-14 && (master - 1.0).abs() < 1e-14);
    assert!((rows[0].rhs - 0.1).abs() < 1e-14, "{}", rows[0].rhs);
    // The master nodes share the load as the overlap says: node x = 1
    // (N9) takes the integral of its hat over [0.3, 1.3]:
    // 1 - 0.7²/2 - 0.3²/2 = 0.71.
    let n9 = rows[0]
        .terms
        .iter()
        .find(|(d, _)| d.node == NodeId(8))
        .map(|t| t.1)
        .unwrap();
    assert!(
        (n9 - (1.0 - 0.5 * 0.7 * 0.7 - 0.5 * 0.3 * 0.3)).abs() < 1e-14,
        "{n9}"
    );
}

#[test]
fn overhanging_patch_counts_only_its_facing_cells() {
    // The slave edge [1.5, 2.5] overhangs the master block (ends at 2):
    // pieces [1.5, 1.83] and [1.83, 2.17] face it, [2.17, 2.5] does not.
    // code_aster measures COEFSURF against the facing pieces only:
    // 0.5 / (2/3) = 0.75.
    let (_, _, lac) = zone_of(1.5, 0.0, false);
    let st = &lac.state[0];
    assert!((st.measure - 2.0 / 3.0).abs() < 1e-14, "{}", st.measure);
    assert!((st.paired - 0.5).abs() < 1e-12);
    assert!((st.coverage() - 0.75).abs() < 1e-12, "{}", st.coverage());
    assert!(st.mean_gap().abs() < 1e-14);
    // Far away: not paired at all, JEU = -1, CONT = -1.
    let (_, zone, lac) = zone_of(3.5, 0.0, false);
    assert!(lac.state[0].unpaired() && lac.pairs.is_empty());
    let [_, jeu, cont, coef, _] = lac.cont_elem(&zone)[0].1;
    assert_eq!((jeu, cont, coef), (-1.0, -1.0, 0.0));
}

#[test]
fn axis_weights_carry_the_radius_but_not_the_patch_measure() {
    // ∫ r ds over [0.3, 1.3] = (1.3² - 0.3²) / 2 = 0.8; the patch measure
    // (clpoma) is a length.
    let (_, _, lac) = zone_of(0.3, 0.0, true);
    assert!((lac.state[0].paired - 0.8).abs() < 1e-14);
    assert!((lac.state[0].measure - 1.0).abs() < 1e-14);
}

/// A LAC zone on the blocks: rows, CONT_ELEM and LAGS_C from a multiplier.
#[test]
fn zone_reports_cont_elem_and_lags_c_per_patch() {
    use aster_contact::{ContinueAlgo, ContinueLaw, GeomLoop, ZoneContact, ZoneLaw};
    let (mesh, patches) = decoupe_lac(&blocks(1.5, 0.1), &["S"]).unwrap();
    let zone = ResolvedZone::new(0, &ZoneGeometry::new("M", "S"), &mesh).unwrap();
    let law = ZoneLaw::Continue(ContinueLaw {
        algo: ContinueAlgo::Lac,
        ..ContinueLaw::default()
    });
    let mut z = ZoneContact::new(zone, law, GeomLoop::default());
    assert!(z.is_lac());
    // Without patches the zone says what to do.
    let e = z.pair(&mesh, &mesh.coords).unwrap_err().to_string();
    assert!(e.contains("DECOUPE_LAC"), "{e}");
    z.set_lac_patches(patches.zone("S").unwrap()).unwrap();
    let rows = z.pair(&mesh, &mesh.coords).unwrap();
    assert_eq!(rows.len(), 1, "one row per patch");
    // Open: no force.
    let cells = z.cont_elem().unwrap();
    assert_eq!(cells.len(), 3, "one entry per slave cell of the patch");
    let [pres, jeu, cont, coef, prescoor] = cells[0].1;
    assert_eq!((pres, cont, prescoor), (0.0, 0.0, 0.0));
    assert!(
        (jeu - 0.1).abs() < 1e-14 && (coef - 0.75).abs() < 1e-12,
        "{jeu} {coef}"
    );
    // Closed with multiplier 7 (the patch pressure).
    z.set_multipliers(&[7.0]);
    let [pres, _, cont, coef, prescoor] = z.cont_elem().unwrap()[2].1;
    assert!((pres + 7.0).abs() < 1e-12 && cont == 1.0, "{pres}");
    assert!((prescoor - pres * coef).abs() < 1e-14);
    let lags: Vec<f64> = z.lags_c().unwrap().iter().map(|(_, v)| *v).collect();
    assert_eq!(lags.len(), 2, "the two pressure nodes of a cut QUAD4 edge");
    assert!(lags.iter().all(|v| (v + 7.0).abs() < 1e-12), "{lags:?}");
}
