//! Automatic master normals (`VECT_MAIT='AUTO'`) on a refined ZZZZ237
//! two-block scene (`scenes::two_blocks_mesh(4)`: every slave node of AB
//! starts exactly on a master node of HE). With the cell normals and the
//! averaged normal on master nodes (default), and with smoothed normals
//! (`LISSAGE='OUI'`), the geometric loop settles in both drivers and the
//! answer is the one of the fixed normal (0, 1) — the independent
//! reference here, since the near-rigid block (1e7 × stiffer) stays flat.

use aster_contact::scenes::{two_blocks_mesh, two_blocks_problem};
use aster_contact::*;
use aster_fem::{Comp, Dof, Model, StaticNonLinear, UnilateralSource};

const N: usize = 4;
const STEPS: usize = 5;

fn definition(normal: Option<[f64; 3]>, lissage: bool) -> ContactDefinition {
    let mut g = ZoneGeometry::new("HE", "AB");
    if let Some(v) = normal {
        g = g.with_fixed_master_normal(v).unwrap();
    }
    g.lissage = lissage;
    ContactDefinition::discrete(
        vec![Zone {
            geometry: g,
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap()
}

fn instants() -> Vec<f64> {
    (0..=STEPS)
        .map(|i| 20.0 * i as f64 / STEPS as f64)
        .collect()
}

/// fem's STAT_NON_LINE path: the displacement at the last instant and
/// the total contact force, or fem's error message.
fn through_fem(def: &ContactDefinition) -> Result<(Model, Vec<f64>, f64), String> {
    let (model, loads) = two_blocks_problem(two_blocks_mesh(N).unwrap(), 1e7).unwrap();
    let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
    let res = {
        let mut snl = StaticNonLinear {
            instants: instants(),
            sources: zones
                .iter_mut()
                .map(|z| Box::new(z) as Box<dyn UnilateralSource>)
                .collect(),
            ..Default::default()
        };
        snl.solve(&model, &loads).map_err(|e| e.to_string())?
    };
    let u = res.last().unwrap().displacement.clone();
    let force = zones[0].forces().iter().sum();
    Ok((model, u, force))
}

fn through_linear_driver(def: &ContactDefinition) -> (Model, Vec<f64>, f64) {
    let (model, loads) = two_blocks_problem(two_blocks_mesh(N).unwrap(), 1e7).unwrap();
    let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
    let out = run_linear(def, &mut zones, &model, &loads, &instants()).unwrap();
    let u = out.last().unwrap().report.u.clone();
    let force = zones[0].forces().iter().sum();
    (model, u, force)
}

fn depl(model: &Model, u: &[f64], node: &str, comp: Comp) -> f64 {
    let n = model.mesh().group_no(node).unwrap().members[0];
    u[model.dofs().index(Dof::new(n, comp)).unwrap()]
}

fn assert_close(what: &str, got: f64, want: f64, rel: f64) {
    assert!(
        (got - want).abs() <= rel * want.abs(),
        "{what}: {got} vs reference {want}"
    );
}

#[test]
fn auto_normals_settle_and_match_the_fixed_normal() {
    let (model, u_ref, f_ref) = through_fem(&definition(Some([0.0, 1.0, 0.0]), false)).unwrap();
    // The reference is a real contact solution: ~1e10 N pushing 20 m.
    assert!(f_ref > 1e10, "{f_ref}");
    for lissage in [false, true] {
        let auto = definition(None, lissage);
        let (_, u, f) = through_fem(&auto).unwrap();
        let (_, u_lin, f_lin) = through_linear_driver(&auto);
        check_against_reference(
            &model,
            &u_ref,
            f_ref,
            &[("fem", &u, f), ("linear driver", &u_lin, f_lin)],
            lissage,
        );
    }
}

fn check_against_reference(
    model: &Model,
    u_ref: &[f64],
    f_ref: f64,
    runs: &[(&str, &Vec<f64>, f64)],
    lissage: bool,
) {
    for &(label, u, f) in runs {
        let label = format!("{label} (LISSAGE {lissage})");
        assert_close(&format!("{label} contact force"), f, f_ref, 1e-6);
        for node in ["A", "B"] {
            for comp in [Comp::DX, Comp::DY] {
                let want = depl(model, u_ref, node, comp);
                let got = depl(model, u, node, comp);
                // DY(A) is the block's ~1e-6 m dent: compare it to its own size.
                assert_close(&format!("{label} {comp:?}({node})"), got, want, 1e-4);
            }
        }
    }
}

/// The pair of the slave node at x = 50 when the master node under it is
/// lifted by `lift` (the two master cells around it lean opposite ways).
fn pair_on_lifted_hub(lift: f64) -> aster_contact::ContactPair {
    let mesh = two_blocks_mesh(N).unwrap();
    let zone = ResolvedZone::new(0, &ZoneGeometry::new("HE", "AB"), &mesh).unwrap();
    let mut x = mesh.coords.clone();
    let at_50 = |nodes: &[aster_mesh::NodeId]| {
        nodes
            .iter()
            .copied()
            .find(|n| (mesh.coord(*n)[0] - 50.0).abs() < 1e-9)
            .unwrap()
    };
    let hub = at_50(&zone.master_nodes);
    let slave = at_50(&zone.slave_nodes);
    x[hub.0 as usize][1] += lift;
    x[slave.0 as usize][1] += lift;
    let point = nodal_points(&zone)
        .into_iter()
        .find(|p| p.node() == Some(slave))
        .unwrap();
    pair_point(&zone, &point, &x).unwrap()
}

#[test]
fn a_slave_node_on_a_flat_master_node_takes_the_averaged_normal() {
    // Cells flat to ~1e-9 rad: which cell the projection picks is noise,
    // so the normal is the average of the two cells' — exactly vertical.
    let pair = pair_on_lifted_hub(1e-8);
    let p = pair.pairing().unwrap();
    assert!(p.normal[0].abs() < 1e-12, "{:?}", p.normal);
    assert!((p.normal[1] - 1.0).abs() < 1e-12);
    assert!(p.gap.abs() < 1e-12);
    assert_eq!(p.master.iter().filter(|(_, w)| *w > 0.5).count(), 1);
}

#[test]
fn a_slave_node_on_a_kinked_master_node_keeps_its_cell_normal() {
    // Cells kinked by ~0.1 rad: code_aster keeps the normal of the cell the
    // projection was attributed to (SSNV104B depends on it at 1e-6).
    let pair = pair_on_lifted_hub(1.0);
    let p = pair.pairing().unwrap();
    assert!(p.normal[0].abs() > 1e-2, "{:?}", p.normal);
    let len = (p.normal[0].powi(2) + p.normal[1].powi(2)).sqrt();
    assert!((len - 1.0).abs() < 1e-12);
    assert_eq!(p.master.iter().filter(|(_, w)| *w > 0.5).count(), 1);
}
