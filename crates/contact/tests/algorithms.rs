//! ZZZZ237 A with every contact algorithm through the linear contact driver
//! (stiffness factorised once, contact solved in the multiplier space):
//! discrete CONTRAINTE / PENALISATION / GCP, continuous STANDARD with NEWTON
//! and POINT_FIXE, continuous PENALISATION; and the DIST_APPA exclusion.

use aster_contact::scenes::{two_blocks_mesh, two_blocks_problem};
use aster_contact::*;
use aster_fem::{post, Comp, Dof, Model};
use aster_mesh::NodeId;

struct Outcome {
    model: Model,
    u: Vec<f64>,
    instants: Vec<Instant>,
    zones: Vec<ZoneContact>,
}

fn run(def: &ContactDefinition) -> Outcome {
    let (model, loads) = two_blocks_problem(two_blocks_mesh(1).unwrap(), 1e7).unwrap();
    let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
    let times: Vec<f64> = (0..=20).map(|i| i as f64).collect();
    let instants = run_linear(def, &mut zones, &model, &loads, &times).unwrap();
    let u = instants.last().unwrap().report.u.clone();
    Outcome {
        model,
        u,
        instants,
        zones,
    }
}

fn node(o: &Outcome, name: &str) -> NodeId {
    o.model.mesh().group_no(name).unwrap().members[0]
}

fn depl(o: &Outcome, name: &str, comp: Comp) -> f64 {
    o.u[o.model.dofs().index(Dof::new(node(o, name), comp)).unwrap()]
}

fn geometry(dist_appa: Option<f64>) -> ZoneGeometry {
    let g = ZoneGeometry::new("HE", "AB");
    match dist_appa {
        Some(d) => g.with_dist_appa(d),
        None => g,
    }
}

fn discrete(algo: DiscreteAlgo, dist_appa: Option<f64>) -> ContactDefinition {
    ContactDefinition::discrete(
        vec![Zone {
            geometry: geometry(dist_appa),
            law: algo,
        }],
        Frottement::Sans,
    )
    .unwrap()
}

fn continuous(algo: ContinueAlgo, reso: Resolution, dist_appa: Option<f64>) -> ContactDefinition {
    let mut d = ContactDefinition::continuous(
        vec![Zone {
            geometry: geometry(dist_appa),
            law: ContinueLaw {
                algo,
                integration: Integration::Auto,
            },
        }],
        Frottement::Sans,
    )
    .unwrap();
    if let ContactDefinition::Continue(c) = &mut d {
        c.algo_reso_cont = reso;
        c.resi_cont = Some(1e-12);
    }
    d
}

/// DY(A), DY(B) on the block (code_aster −9.14285676e−7), DX(A) = −DX(B) =
/// −4.28571, FORC_NODA DY = 2.1978e10, contact force = FORC_NODA.
fn check_exact(o: &Outcome, tol_dy: f64, tol: f64) {
    let f = post::forc_noda(&o.model, &o.u).unwrap();
    for (p, dx) in [("A", -4.28571), ("B", 4.28571)] {
        let dy = depl(o, p, Comp::DY);
        assert!((dy - -9.14285676e-07).abs() < tol_dy, "DY({p}) = {dy:e}");
        let got = depl(o, p, Comp::DX);
        assert!((got - dx).abs() < tol * 4.28571, "DX({p}) = {got}");
        let fy = f[o
            .model
            .dofs()
            .index(Dof::new(node(o, p), Comp::DY))
            .unwrap()];
        assert!(
            (fy - 2.1978e10).abs() < tol * 2.1978e10,
            "FORC_NODA DY({p}) = {fy:e}"
        );
    }
    let total: f64 = o.zones[0].forces().iter().sum();
    assert!(
        (total - 2.0 * 2.1978e10).abs() < tol * 4.4e10,
        "contact forces {total:e}"
    );
}

#[test]
fn discrete_contrainte() {
    let o = run(&discrete(DiscreteAlgo::Contrainte, None));
    check_exact(&o, 1e-7, 1e-5);
    // The first step makes contact; later steps start from the right set.
    assert!(o.instants.iter().all(|i| i.report.active == 2));
}

#[test]
fn discrete_gcp_converges_to_the_exact_answer() {
    let o = run(&discrete(
        DiscreteAlgo::Gcp {
            resi_abso: None,
            iter_maxi: 0,
        },
        None,
    ));
    check_exact(&o, 1e-7, 1e-5);
    assert!(o.instants.iter().all(|i| i.report.contact_iterations < 20));
}

#[test]
fn discrete_penalisation_follows_the_penalty_law() {
    let e_n = 1e14;
    let o = run(&discrete(DiscreteAlgo::Penalisation { e_n }, None));
    // Penetration = force / E_N ≈ 2.2e-4 (the block itself yields 9e-7).
    for p in ["A", "B"] {
        let dy = depl(&o, p, Comp::DY);
        assert!(
            (dy - -(2.1978e10 / e_n) - -9.14e-7).abs() < 2e-6,
            "DY({p}) = {dy:e}"
        );
    }
    check_exact(&o, 3e-4, 1e-4);
}

#[test]
fn continuous_standard_newton_and_point_fixe() {
    for reso in [Resolution::Newton, Resolution::PointFixe] {
        let o = run(&continuous(
            ContinueAlgo::Standard { coef_cont: 100.0 },
            reso,
            None,
        ));
        check_exact(&o, 1e-7, 1e-5);
    }
}

#[test]
fn continuous_penalisation_pressure_law() {
    // Nodal integration measured on the reference slave side, as
    // code_aster's contact elements (`mmmjac` on the initial coordinates):
    // weight = half the initial length of AB (100 m) per node, so force =
    // c × weight × penetration. The square has widened by ~8.6 m when it
    // settles: weights on the current geometry would be 8.6 % larger.
    let c = 1e13;
    let o = run(&continuous(
        ContinueAlgo::Penalisation { coef_pena_cont: c },
        Resolution::Newton,
        None,
    ));
    let weight = 100.0 / 2.0;
    for p in ["A", "B"] {
        let dy = depl(&o, p, Comp::DY);
        let pen = 2.1978e10 / (c * weight);
        assert!(
            (dy + pen + 9.14e-7).abs() < 2e-7,
            "DY({p}) = {dy:e}, expected ≈ {:e}",
            -pen
        );
    }
}

#[test]
fn dist_appa_lets_the_square_through() {
    for def in [
        discrete(DiscreteAlgo::Contrainte, Some(1.0)),
        discrete(
            DiscreteAlgo::Gcp {
                resi_abso: None,
                iter_maxi: 0,
            },
            Some(1.0),
        ),
        continuous(ContinueAlgo::default(), Resolution::Newton, Some(1.0)),
    ] {
        let o = run(&def);
        for p in ["A", "B"] {
            assert!((depl(&o, p, Comp::DY) - -20.0).abs() < 1e-6);
        }
        assert!(
            o.zones[0].pairs().iter().all(|p| matches!(
                p.status,
                // 50 from E/H initially; measured on the deformed geometry.
                PairStatus::Excluded(Exclusion::DistAppa { distance, .. }) if distance >= 50.0
            )),
            "{:?}",
            o.zones[0].pairs()
        );
    }
    // DIST_APPA larger than the 50 to the nearest master node: paired again.
    let o = run(&discrete(DiscreteAlgo::Contrainte, Some(51.0)));
    check_exact(&o, 1e-7, 1e-5);
}

#[test]
fn pairing_only_zone_reports_without_enforcing() {
    let mut g = geometry(None);
    g.resolve = false;
    let def = ContactDefinition::discrete(
        vec![Zone {
            geometry: g,
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap();
    let o = run(&def);
    assert!((depl(&o, "A", Comp::DY) - -20.0).abs() < 1e-6);
    // The slave nodes are paired and report their interpenetration.
    for p in o.zones[0].pairs() {
        let pairing = p.pairing().unwrap();
        assert!((pairing.gap - -20.0).abs() < 1e-6, "gap {}", pairing.gap);
    }
}

#[test]
fn continuous_gauss_integration_points() {
    // Pressure rows are per slave node (weighted gaps over the integration
    // points), so several points on one straight edge are not redundant.
    // The square is held sideways only by 10 N/m springs under 2e10 N of
    // contact force: a 1e-8 relative asymmetry of the two reactions turns
    // it visibly. Two Gauss points keep it symmetric; with a point at the
    // middle of AB (Gauss 3 points, Simpson, Newton–Cotes) the two
    // reactions differ by ~1e-8 and the square turns (DX(A) = +1.85):
    // those rules are checked on the Hertz scene (tests/hertz.rs).
    for reso in [Resolution::Newton, Resolution::PointFixe] {
        let mut d = ContactDefinition::continuous(
            vec![Zone {
                geometry: geometry(None),
                law: ContinueLaw {
                    algo: ContinueAlgo::default(),
                    integration: Integration::Gauss(3),
                },
            }],
            Frottement::Sans,
        )
        .unwrap();
        if let ContactDefinition::Continue(c) = &mut d {
            c.algo_reso_cont = reso;
            c.resi_cont = Some(1e-12);
        }
        let o = run(&d);
        // The block now carries a distributed load instead of two nodal
        // ones: its ~1e-6 deflection under A and B changes by ~1e-7 (the
        // file's own check is absolute, 1e-6).
        check_exact(&o, 1e-6, 1e-5);
        let nodal: f64 = o.zones[0].nodal_forces().iter().map(|f| f.1).sum();
        assert!((nodal - 2.0 * 2.1978e10).abs() < 1e-5 * 4.4e10, "{nodal:e}");
    }
}
