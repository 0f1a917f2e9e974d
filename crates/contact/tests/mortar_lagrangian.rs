//! code_aster 17's DEFI_CONT mortar Lagrangian contact (module
//! `mortar_lagrangian`): two plates pressed together on non-matching
//! meshes (`scenes::two_plates_shear_problem`, no shear). With ν = 0 the
//! exact stress is uniform: σ_yy = E × 0.1 / 2 over the two plates'
//! heights, i.e. a contact pressure of 1e5 everywhere — a mortar method
//! passes this patch test exactly, whatever the mesh of each side.

use aster_contact::mortar_lagrangian::{InitialState, MortarLagrangian, MortarZoneDef};
use aster_contact::scenes::{two_plates_mesh, two_plates_shear_problem};
use aster_fem::{ForceSource, StaticNonLinear};

fn pressures(n_up: usize, n_low: usize, init: InitialState, coef: f64) -> Vec<f64> {
    let mesh = two_plates_mesh(n_up, n_low).unwrap();
    let (model, loads) = two_plates_shear_problem(mesh, 0.0, false).unwrap();
    let mut zone = MortarZoneDef::new("EF", "AB");
    zone.contact_init = init;
    zone.coef_cont = coef;
    let mut m = MortarLagrangian::new(&[zone], model.mesh(), false, 2).unwrap();
    let res = {
        let mut snl = StaticNonLinear {
            instants: vec![0.0, 0.5, 1.0],
            forces: vec![Box::new(&mut m) as Box<dyn ForceSource>],
            ..Default::default()
        };
        snl.solve(&model, &loads).unwrap()
    };
    let s = res.last().unwrap();
    m.multipliers(&s.own_unknowns[0]).map(|(_, p)| p).collect()
}

#[test]
fn pressed_plates_carry_a_uniform_pressure_on_non_matching_meshes() {
    for (up, low) in [(1, 1), (3, 2), (2, 5)] {
        let p = pressures(up, low, InitialState::Interpenetrated, 100.0);
        assert_eq!(p.len(), up + 1);
        for v in p {
            assert!((v + 1e5).abs() < 1e-6 * 1e5, "{up}/{low}: LAGS_C = {v}");
        }
    }
}

#[test]
fn the_answer_does_not_depend_on_the_coefficient_or_the_initial_state() {
    for init in [InitialState::Yes, InitialState::No] {
        for coef in [1.0, 1e4] {
            for v in pressures(3, 2, init, coef) {
                assert!(
                    (v + 1e5).abs() < 1e-6 * 1e5,
                    "{init:?} {coef}: LAGS_C = {v}"
                );
            }
        }
    }
}
