//! LAC mortar integrals (module `lac`) on small meshes written here: a
//! slave block above a master block, with a known gap and overlap.

use aster_contact::lac::{patch_integral, resolve_patches};
use aster_contact::{Measure, ResolvedZone, ZoneGeometry};
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

fn integral(x0: f64, gap: f64, measure: Measure) -> aster_contact::lac::PatchIntegral {
    let (mesh, patches) = decoupe_lac(&blocks(x0, gap), &["S"]).unwrap();
    let zone = ResolvedZone::new(0, &ZoneGeometry::new("M", "S"), &mesh).unwrap();
    let refs = resolve_patches(&zone, patches.zone("S").unwrap()).unwrap();
    assert_eq!(refs.len(), 1);
    assert_eq!(refs[0].cells.len(), 3, "a QUAD4 edge is cut in three");
    patch_integral(&mesh, &zone, &refs[0], &mesh.coords, measure).unwrap()
}

#[test]
fn covered_patch_integrates_its_gap_exactly() {
    // The slave edge [0.3, 1.3] straddles the two master edges at x = 1.
    let int = integral(0.3, 0.1, Measure::Plane);
    assert!((int.measure - 1.0).abs() < 1e-14, "{}", int.measure);
    assert!((int.paired - 1.0).abs() < 1e-14);
    assert!((int.mean_gap() - 0.1).abs() < 1e-14, "{}", int.mean_gap());
    assert!((int.coverage() - 1.0).abs() < 1e-14);
    // The row is the gap's integral: -DY on the slave side (total weight
    // -1), +DY on the master side (+1), no DX on a horizontal interface.
    let (mut slave, mut master) = (0.0, 0.0);
    for (d, c) in &int.terms {
        assert_eq!(d.comp, aster_fem::Comp::DY, "{d:?}");
        if d.node.0 < 4 || d.node.0 >= 10 {
            slave += c;
        } else {
            master += c;
        }
    }
    assert!((slave + 1.0).abs() < 1e-14 && (master - 1.0).abs() < 1e-14);
    // The master nodes share the load as the overlap says: node x = 1
    // (N9) takes the integral of its hat over [0.3, 1.3]:
    // 1 - 0.7²/2 - 0.3²/2 = 0.71.
    let n9 = int
        .terms
        .iter()
        .find(|(d, _)| d.node == NodeId(8))
        .map(|t| *t.1)
        .unwrap();
    assert!(
        (n9 - (1.0 - 0.5 * 0.7 * 0.7 - 0.5 * 0.3 * 0.3)).abs() < 1e-14,
        "{n9}"
    );
}

#[test]
fn half_uncovered_patch_has_half_its_surface_paired() {
    // The slave edge [1.5, 2.5] overhangs the master block (ends at 2).
    let int = integral(1.5, 0.0, Measure::Plane);
    assert!((int.measure - 1.0).abs() < 1e-14);
    assert!((int.coverage() - 0.5).abs() < 1e-12, "{}", int.coverage());
    assert!(int.mean_gap().abs() < 1e-14);
}

#[test]
fn axis_weights_carry_the_radius() {
    // ∫ r ds over [0.3, 1.3] = (1.3² - 0.3²) / 2 = 0.8.
    let int = integral(0.3, 0.0, Measure::Axisymmetric);
    assert!((int.measure - 0.8).abs() < 1e-14, "{}", int.measure);
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
        (jeu - 0.1).abs() < 1e-14 && (coef - 0.5).abs() < 1e-12,
        "{jeu} {coef}"
    );
    // Closed with multiplier 7 (the mean pressure over the paired half).
    z.set_multipliers(&[7.0]);
    let [pres, _, cont, coef, prescoor] = z.cont_elem().unwrap()[2].1;
    assert!((pres + 7.0).abs() < 1e-12 && cont == 1.0, "{pres}");
    assert!((prescoor - pres * coef).abs() < 1e-14);
    let lags: Vec<f64> = z.lags_c().unwrap().iter().map(|(_, v)| *v).collect();
    assert_eq!(lags.len(), 2, "the two pressure nodes of a cut QUAD4 edge");
    assert!(lags.iter().all(|v| (v + 7.0).abs() < 1e-12), "{lags:?}");
}
