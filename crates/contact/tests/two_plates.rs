//! Two plates pressed together (`scenes::two_plates_mesh`, the SSNP121 kind
//! of scene, generated here): continuous contact gives the contact pressure
//! as code_aster's LAGS_C; the exact answer of a perfect interface is
//! σ_yy = −1e5 (LAGS_C = −1e5) and DY = −0.05 at the interface.

use aster_contact::scenes::{two_plates_mesh, two_plates_problem};
use aster_contact::*;
use aster_fem::{Comp, Dof, Model, StaticNonLinear, UnilateralSource};

fn continuous(integration: Integration, geom_loop: GeomLoop) -> ContactDefinition {
    let mut def = ContactDefinition::continuous(
        vec![Zone {
            geometry: ZoneGeometry::new("EF", "AB"),
            law: ContinueLaw {
                algo: ContinueAlgo::Standard { coef_cont: 1000.0 },
                integration,
            },
        }],
        Frottement::Sans,
    )
    .unwrap();
    def.set_geom_loop(geom_loop);
    def
}

/// Solves one step; returns the model, the displacement and the zones.
fn solve(
    n_up: usize,
    n_low: usize,
    def: &ContactDefinition,
) -> (Model, Vec<f64>, Vec<ZoneContact>) {
    let (model, loads) = two_plates_problem(two_plates_mesh(n_up, n_low).unwrap()).unwrap();
    let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
    let res = {
        let mut snl = StaticNonLinear {
            instants: vec![0.0, 1.0],
            sources: zones
                .iter_mut()
                .map(|z| Box::new(z) as Box<dyn UnilateralSource>)
                .collect(),
            ..Default::default()
        };
        snl.solve(&model, &loads).unwrap()
    };
    let u = res.last().unwrap().displacement.clone();
    (model, u, zones)
}

fn dy(model: &Model, u: &[f64], node: aster_mesh::NodeId) -> f64 {
    u[model.dofs().index(Dof::new(node, Comp::DY)).unwrap()]
}

#[test]
fn lags_c_is_minus_the_contact_pressure_exact_on_matching_meshes() {
    let def = continuous(Integration::Simpson(4), GeomLoop::Controle { nb_iter: 2 });
    let (model, u, zones) = solve(4, 4, &def);
    let lags = zones[0].lags_c().expect("continuous zone has LAGS_C");
    // Every slave node of AB (5 nodes) carries LAGS_C.
    assert_eq!(lags.len(), 5);
    for (n, p) in &lags {
        assert!((p + 1e5).abs() < 1e-6 * 1e5, "LAGS_C({n:?}) = {p}");
        assert!((dy(&model, &u, *n) + 0.05).abs() < 1e-9);
    }
}

#[test]
fn lags_c_on_non_matching_plates_is_within_one_percent_of_the_analytic_pressure() {
    // 12 cells on the slave side against 11 on the master side (SSNP121's
    // numbers), Simpson with ORDRE_INT = 4 and two geometric updates.
    let def = continuous(Integration::Simpson(4), GeomLoop::Controle { nb_iter: 2 });
    let (model, u, zones) = solve(12, 11, &def);
    let lags = zones[0].lags_c().unwrap();
    assert_eq!(lags.len(), 13);
    let mean: f64 = lags.iter().map(|(_, p)| p).sum::<f64>() / lags.len() as f64;
    for (n, p) in &lags {
        assert!((p + 1e5).abs() < 1e-2 * 1e5, "LAGS_C({n:?}) = {p}");
        assert!((dy(&model, &u, *n) + 0.05).abs() < 1e-2 * 0.05);
    }
    // Not a constant copied everywhere: the non-matching interface makes
    // the pressure vary from node to node.
    assert!(lags.iter().any(|(_, p)| (p - mean).abs() > 1.0));
}

#[test]
fn discrete_zones_have_no_lags_c() {
    let def = ContactDefinition::discrete(
        vec![Zone {
            geometry: ZoneGeometry::new("AB", "EF"),
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap();
    let (_, _, zones) = solve(3, 2, &def);
    assert!(zones[0].lags_c().is_none());
}
