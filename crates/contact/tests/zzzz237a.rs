//! ZZZZ237 modelisation A through the contact API and fem's STAT_NON_LINE:
//! the soft square ABCD pressed 20 onto the near-rigid block EFGH (stiffness
//! ratio 1e7), slave AB on master HE. Expected values: code_aster's
//! (validation document V1.01.237 and the TEST_RESU of zzzz237a).

use aster_contact::scenes::{two_blocks_mesh, two_blocks_problem};
use aster_contact::*;
use aster_fem::{post, Comp, Dof, Model, NonLinearResult, StaticNonLinear};
use aster_mesh::{Mesh, NodeId};

fn node(mesh: &Mesh, name: &str) -> NodeId {
    mesh.group_no(name).unwrap().members[0]
}

fn run(def: &ContactDefinition) -> (Model, NonLinearResult, Vec<ZoneContact>) {
    let mesh = two_blocks_mesh(1).unwrap();
    let (model, loads) = two_blocks_problem(mesh, 1e7).unwrap();
    let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
    let res = {
        let mut snl = StaticNonLinear {
            instants: (0..=20).map(|i| i as f64).collect(),
            sources: zones
                .iter_mut()
                .map(|z| Box::new(z) as Box<dyn aster_fem::UnilateralSource>)
                .collect(),
            ..Default::default()
        };
        snl.solve(&model, &loads).unwrap()
    };
    (model, res, zones)
}

fn depl(model: &Model, res: &NonLinearResult, name: &str, comp: Comp) -> f64 {
    let step = res.at_time(20.0, 1e-6).unwrap();
    let n = node(model.mesh(), name);
    step.displacement[model.dofs().index(Dof::new(n, comp)).unwrap()]
}

fn forc_noda_dy(model: &Model, res: &NonLinearResult, name: &str) -> f64 {
    let step = res.at_time(20.0, 1e-6).unwrap();
    let f = post::forc_noda(model, &step.displacement).unwrap();
    f[model
        .dofs()
        .index(Dof::new(node(model.mesh(), name), Comp::DY))
        .unwrap()]
}

fn zone(dist_appa: Option<f64>, fixed_normal: bool) -> ZoneGeometry {
    let mut g = ZoneGeometry::new("HE", "AB");
    if fixed_normal {
        g = g.with_fixed_master_normal([0.0, 1.0, 0.0]).unwrap();
    }
    if let Some(d) = dist_appa {
        g = g.with_dist_appa(d);
    }
    g
}

fn discrete(algo: DiscreteAlgo, dist_appa: Option<f64>) -> ContactDefinition {
    ContactDefinition::discrete(
        vec![Zone {
            geometry: zone(dist_appa, dist_appa.is_none()),
            law: algo,
        }],
        Frottement::Sans,
    )
    .unwrap()
}

fn continuous(algo: ContinueAlgo, dist_appa: Option<f64>) -> ContactDefinition {
    ContactDefinition::continuous(
        vec![Zone {
            geometry: zone(dist_appa, false),
            law: ContinueLaw {
                algo,
                integration: Integration::Auto,
            },
        }],
        Frottement::Sans,
    )
    .unwrap()
}

/// The contact answer: A and B stay on the block (which yields by ~1e-6),
/// the square spreads by 3/7 of its height change × ν/(1−ν)…
fn check_contact(model: &Model, res: &NonLinearResult, tol_dy: f64, tol_rel: f64) {
    for (p, dx) in [("A", -4.28571), ("B", 4.28571)] {
        let dy = depl(model, res, p, Comp::DY);
        // code_aster: DY(A) = -9.14285676e-07 (TEST_RESU, CRITERE='ABSOLU').
        assert!((dy - -9.14285676e-07).abs() < tol_dy, "DY({p}) = {dy}");
        let got = depl(model, res, p, Comp::DX);
        assert!((got - dx).abs() < tol_rel * dx.abs(), "DX({p}) = {got}");
        let f = forc_noda_dy(model, res, p);
        assert!(
            (f - 2.1978e10).abs() < tol_rel * 2.1978e10,
            "FORC_NODA DY({p}) = {f}"
        );
    }
}

#[test]
fn discrete_contrainte_matches_code_aster() {
    let def = discrete(DiscreteAlgo::Contrainte, None);
    let (model, res, mut zones) = run(&def);
    check_contact(&model, &res, 1e-7, 1e-5);
    // CONT_NOEU: both slave nodes in contact, RN = the nodal reaction, JEU ≈ 0.
    let step = res.at_time(20.0, 1e-6).unwrap();
    let x = positions(model.mesh(), model.dofs(), &step.displacement);
    let cn = ContNoeu::at_step(&mut zones, model.mesh(), &x, &step.unilateral).unwrap();
    for p in ["A", "B"] {
        let n = node(model.mesh(), p);
        assert_eq!(cn.value(n, "CONT"), Some(1.0));
        let rn = cn.value(n, "RN").unwrap();
        assert!((rn - 2.1978e10).abs() < 1e-5 * 2.1978e10, "RN({p}) = {rn}");
        // RNY with code_aster's sign (`cfresa` on Aᵀμ): against the force
        // the block exerts on the slave node, which points up (SSNV193A).
        assert!((cn.value(n, "RNY").unwrap() + rn).abs() < 1e-6 * rn);
        assert!(cn.value(n, "JEU").unwrap().abs() < 1e-9, "JEU({p})");
    }
}

#[test]
fn discrete_penalisation_approaches_the_exact_answer() {
    // E_N = 1e15: penetration ≈ 2.2e10 / 1e15 = 2.2e-5.
    let def = discrete(DiscreteAlgo::Penalisation { e_n: 1e15 }, None);
    let (model, res, _) = run(&def);
    for p in ["A", "B"] {
        let dy = depl(&model, &res, p, Comp::DY);
        assert!(dy < 0.0 && (dy - -2.2e-5).abs() < 0.2e-5, "DY({p}) = {dy}");
    }
    check_contact(&model, &res, 3e-5, 1e-4);
}

#[test]
fn continuous_standard_matches_the_discrete_answer() {
    let def = continuous(ContinueAlgo::Standard { coef_cont: 100.0 }, None);
    let (model, res, _) = run(&def);
    check_contact(&model, &res, 1e-7, 1e-5);
}

#[test]
fn dist_appa_excludes_both_slave_nodes_in_every_formulation() {
    for def in [
        discrete(DiscreteAlgo::Contrainte, Some(1.0)),
        continuous(ContinueAlgo::default(), Some(1.0)),
    ] {
        let (model, res, mut zones) = run(&def);
        for p in ["A", "B"] {
            let dy = depl(&model, &res, p, Comp::DY);
            assert!((dy - -20.0).abs() < 1e-6, "DY({p}) = {dy}");
        }
        let step = res.at_time(20.0, 1e-6).unwrap();
        let x = positions(model.mesh(), model.dofs(), &step.displacement);
        let cn = ContNoeu::at_step(&mut zones, model.mesh(), &x, &step.unilateral).unwrap();
        assert_eq!(cn.value(node(model.mesh(), "A"), "CONT"), Some(-1.0));
    }
}
