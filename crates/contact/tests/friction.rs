//! Coulomb friction (module `friction`): two plates pressed then sheared
//! (`scenes::two_plates_shear_problem`), continuous formulation.

use aster_contact::friction::{ContinueFriction, ContinueZoneFriction, ContinuousFriction};
use aster_contact::scenes::{two_plates_mesh, two_plates_shear_problem};
use aster_contact::*;
use aster_fem::{ForceSource, Model, NonLinearResult, StaticNonLinear};

fn definition(mu: f64, geom: Resolution) -> ContactDefinition {
    let mut def = ContactDefinition::continuous_with_friction(
        vec![Zone {
            geometry: ZoneGeometry::new("EF", "AB"),
            law: ContinueLaw {
                algo: ContinueAlgo::Standard { coef_cont: 100.0 },
                integration: Integration::Auto,
            },
        }],
        ContinueFriction::new(vec![ContinueZoneFriction::new(mu)]),
    )
    .unwrap();
    if let ContactDefinition::Continue(c) = &mut def {
        c.algo_reso_geom = geom;
        c.geom_loop = GeomLoop::Automatique {
            iter_maxi: 10,
            resi_geom: 1e-6,
        };
    }
    def
}

fn solve(
    n_up: usize,
    n_low: usize,
    mu: f64,
    shear: f64,
    rigid_base: bool,
    instants: Vec<f64>,
) -> (Model, NonLinearResult, ContinuousFriction) {
    let mesh = two_plates_mesh(n_up, n_low).unwrap();
    let (model, loads) = two_plates_shear_problem(mesh, shear, rigid_base).unwrap();
    let def = definition(mu, Resolution::Newton);
    let ContactDefinition::Continue(c) = &def else {
        unreachable!()
    };
    let mut f = ContinuousFriction::new(c, model.mesh(), Measure::Plane).unwrap();
    let res = {
        let mut snl = StaticNonLinear {
            instants,
            forces: vec![Box::new(&mut f) as Box<dyn ForceSource>],
            ..Default::default()
        };
        snl.solve(&model, &loads).unwrap()
    };
    (model, res, f)
}

#[test]
fn pressed_plates_carry_the_pressure() {
    let (_model, res, f) = solve(1, 1, 0.3, 0.0, false, vec![0.0, 1.0]);
    let s = res.last().unwrap();
    for (_, v) in f.multipliers(&s.own_unknowns[0]) {
        assert!((v[0] + 1e5).abs() < 1e-6 * 1e5, "LAGS_C = {}", v[0]);
    }
}

/// Internal forces Σ over the nodes of a group, per component (0 = X).
fn group_force(model: &Model, u: &[f64], group: &str, comp: aster_fem::Comp) -> f64 {
    let k = aster_fem::assembly::assemble_stiffness(model).unwrap();
    let f = k.mul(u);
    model
        .mesh()
        .group_no(group)
        .unwrap()
        .members
        .iter()
        .map(|&n| f[model.dofs().index(aster_fem::Dof::new(n, comp)).unwrap()])
        .sum()
}

/// The CONT_NOEU components of a node (by name).
fn component(cn: &ContNoeu, k: usize, name: &str) -> f64 {
    cn.values[k][ContNoeu::component(name).unwrap()]
}

#[test]
fn sheared_plates_slide_at_mu_times_the_normal_force() {
    let mu = 0.3;
    let instants = vec![0.0, 1.0, 1.25, 1.5, 1.75, 2.0];
    let (model, res, f) = solve(4, 3, mu, 0.2, true, instants);
    let s = res.last().unwrap();
    let fx = group_force(&model, &s.displacement, "CD", aster_fem::Comp::DX);
    let fy = group_force(&model, &s.displacement, "CD", aster_fem::Comp::DY);
    assert!(
        (fx.abs() - mu * fy.abs()).abs() <= 1e-8 * fy.abs(),
        "FX {fx} FY {fy}: ratio {}",
        fx / fy
    );
    // Every slave node slides (CONT 2), the friction force at μ RN
    // against the slip, |LAGS_F1| = 1.
    let cn = f.cont_noeu_at(2.0).unwrap();
    for k in 0..cn.nodes.len() {
        assert_eq!(component(cn, k, "CONT"), 2.0);
        let rn = component(cn, k, "RN");
        let rt = (component(cn, k, "RTGX").powi(2) + component(cn, k, "RTGY").powi(2)).sqrt();
        assert!((rt - mu * rn).abs() <= 1e-8 * rn, "RT {rt} RN {rn}");
        let glix = component(cn, k, "GLIX");
        // Slip of the last step (0.05 imposed on top): the node moves +x,
        // τ₁ = (n_y, −n_x) with n = (0, −1): GLIX < 0; the friction on
        // the internal-force side follows the slip.
        assert!(glix < -0.04, "GLIX {glix}");
        assert!(component(cn, k, "RTGX") > 0.0);
    }
    for (_, v) in f.multipliers(&s.own_unknowns[0]) {
        assert!((v[1].abs() - 1.0).abs() < 1e-9, "LAGS_F1 {}", v[1]);
    }
}

#[test]
fn sheared_plates_below_the_threshold_stick() {
    // Stick: shear stress G γ with the interface stuck is 1e6 × 0.01 = 1e4
    // < μ σ_n = 0.3 × 1e5.
    let (model, res, f) = solve(2, 2, 0.3, 0.01, true, vec![0.0, 1.0, 2.0]);
    let s = res.last().unwrap();
    let cn = f.cont_noeu_at(2.0).unwrap();
    for k in 0..cn.nodes.len() {
        assert_eq!(component(cn, k, "CONT"), 1.0);
        assert!(component(cn, k, "GLI").abs() < 1e-12);
        let ux = s.displacement[model
            .dofs()
            .index(aster_fem::Dof::new(cn.nodes[k], aster_fem::Comp::DX))
            .unwrap()];
        assert!(ux.abs() < 1e-12, "stuck node moved by {ux}");
    }
    for (_, v) in f.multipliers(&s.own_unknowns[0]) {
        assert!(v[1].abs() < 1.0);
    }
}

#[test]
fn deformable_base_keeps_coulomb_at_each_node() {
    let mu = 0.3;
    let (_model, _res, f) = solve(1, 1, mu, 0.2, false, vec![0.0, 1.0, 1.5, 2.0]);
    let cn = f.cont_noeu_at(2.0).unwrap();
    for k in 0..cn.nodes.len() {
        let rn = component(cn, k, "RN");
        let rt = (component(cn, k, "RTGX").powi(2) + component(cn, k, "RTGY").powi(2)).sqrt();
        assert!((rt - mu * rn).abs() <= 1e-8 * rn, "RT {rt} RN {rn}");
    }
}

#[test]
fn small_coefficients_converge_to_the_same_answer() {
    let mesh = two_plates_mesh(4, 3).unwrap();
    let (model, loads) = two_plates_shear_problem(mesh, 0.2, true).unwrap();
    let mut def = definition(0.3, Resolution::Newton);
    if let ContactDefinition::Continue(c) = &mut def {
        c.zones[0].law.algo = ContinueAlgo::Standard { coef_cont: 1.0 };
        if let Some(f) = &mut c.friction {
            f.zones[0].algo = aster_contact::friction::FrictionAlgo::Standard { coef_frot: 1.0 };
        }
    }
    let ContactDefinition::Continue(c) = &def else {
        unreachable!()
    };
    let mut f = ContinuousFriction::new(c, model.mesh(), Measure::Plane).unwrap();
    let res = {
        let mut snl = StaticNonLinear {
            instants: vec![0.0, 1.0, 1.25, 1.5, 1.75, 2.0],
            forces: vec![Box::new(&mut f) as Box<dyn ForceSource>],
            ..Default::default()
        };
        snl.solve(&model, &loads).unwrap()
    };
    let s = res.last().unwrap();
    let fx = group_force(&model, &s.displacement, "CD", aster_fem::Comp::DX);
    let fy = group_force(&model, &s.displacement, "CD", aster_fem::Comp::DY);
    assert!((fx.abs() - 0.3 * fy.abs()).abs() <= 1e-8 * fy.abs());
}

/// The slave's normal (`NORMALE='ESCL'`, `'MAIT_ESCL'`) on a flat
/// interface that stays flat is the master's: a plate (4 cells) pressed on
/// a rigid base (3 cells), frictionless, gives the master normal's answer
/// and the applied pressure at every slave node. (On a deformable base the
/// non-matching meshes dent the interface and the three normals differ.)
#[test]
fn slave_normals_on_a_flat_interface_give_the_master_normals_answer() {
    let run = |normale: NormalChoice| {
        let mesh = two_plates_mesh(4, 3).unwrap();
        let (model, loads) = two_plates_shear_problem(mesh, 0.0, true).unwrap();
        let mut def = definition(0.0, Resolution::Newton);
        let ContactDefinition::Continue(c) = &mut def else {
            unreachable!()
        };
        c.zones[0].geometry.normale = normale;
        let mut f = ContinuousFriction::new(c, model.mesh(), Measure::Plane).unwrap();
        let res = {
            let mut snl = StaticNonLinear {
                instants: vec![0.0, 1.0],
                forces: vec![Box::new(&mut f) as Box<dyn ForceSource>],
                ..Default::default()
            };
            snl.solve(&model, &loads).unwrap()
        };
        let s = res.last().unwrap();
        let lags: Vec<f64> = f
            .multipliers(&s.own_unknowns[0])
            .iter()
            .map(|(_, v)| v[0])
            .collect();
        (s.displacement.clone(), lags)
    };
    // σ = E × 0.1 / 1 = 2e5 in the pressed plate.
    let (u_mait, lags_mait) = run(NormalChoice::Mait);
    for l in lags_mait {
        assert!((l + 2e5).abs() < 1e-6 * 2e5, "MAIT: LAGS_C = {l}");
    }
    let scale = u_mait.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    for normale in [NormalChoice::Escl, NormalChoice::MaitEscl] {
        let (u, lags) = run(normale);
        for (a, b) in u.iter().zip(&u_mait) {
            assert!(
                (a - b).abs() <= 1e-10 * scale,
                "{normale:?}: {a} against {b}"
            );
        }
        for l in lags {
            assert!((l + 2e5).abs() < 1e-6 * 2e5, "{normale:?}: LAGS_C = {l}");
        }
    }
}
