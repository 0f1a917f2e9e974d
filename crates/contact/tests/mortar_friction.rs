//! code_aster 17's DEFI_CONT mortar contact with friction (module
//! `mortar_friction`), numerics only: two plates on non-matching meshes,
//! the lower one held (a rigid base), the upper one pressed by 0.1 then its
//! top dragged by 0.1 along X (`scenes::two_plates_shear_problem`), far
//! beyond the elastic shear μ E·0.1 / G = 0.06: every slave node slides and
//! its multipliers — the global components of the contact force — lie on
//! Coulomb's cone, λx = −μ λy, whatever the mesh of each side.

use aster_contact::mortar_friction::{FrictionLaw, MortarFriction};
use aster_contact::mortar_lagrangian::MortarZoneDef;
use aster_contact::scenes::{two_plates_mesh, two_plates_shear_problem};
use aster_fem::{ForceSource, StaticNonLinear};

fn multipliers(n_up: usize, n_low: usize, law: FrictionLaw) -> Vec<[f64; 2]> {
    let mesh = two_plates_mesh(n_up, n_low).unwrap();
    let (model, loads) = two_plates_shear_problem(mesh, 0.1, true).unwrap();
    let mut zone = MortarZoneDef::new("EF", "AB");
    zone.friction = Some(law);
    let mut m = MortarFriction::new(&[zone], model.mesh(), false, 2).unwrap();
    let res = {
        let mut snl = StaticNonLinear {
            instants: vec![0.0, 1.0, 1.25, 1.5, 1.75, 2.0],
            forces: vec![Box::new(&mut m) as Box<dyn ForceSource>],
            ..Default::default()
        };
        snl.solve(&model, &loads).unwrap()
    };
    let s = res.last().unwrap();
    m.multipliers(&s.own_unknowns[0])
        .map(|(_, l)| [l[0], l[1]])
        .collect()
}

#[test]
fn sliding_nodes_lie_on_the_coulomb_cone() {
    for (up, low) in [(3, 2), (6, 5)] {
        let l = multipliers(up, low, FrictionLaw::Coulomb(0.3));
        assert_eq!(l.len(), up + 1);
        for [lx, ly] in l {
            assert!(ly > 0.0, "{up}/{low}: LAGS_F1 = {ly}");
            assert!((lx / ly + 0.3).abs() < 1e-8, "{up}/{low}: {lx} / {ly}");
        }
    }
}

#[test]
fn tresca_slides_at_its_threshold_and_sans_carries_no_tangential_force() {
    for [lx, _] in multipliers(3, 2, FrictionLaw::Tresca(1e4)) {
        assert!((lx + 1e4).abs() < 1e-8 * 1e4, "TRESCA: LAGS_C = {lx}");
    }
    for [lx, ly] in multipliers(3, 2, FrictionLaw::Without) {
        assert!(
            lx.abs() < 1e-8 * ly.abs(),
            "SANS: LAGS_C = {lx}, LAGS_F1 = {ly}"
        );
    }
}

/// Zones with and without friction in one definition: the frictional
/// zone's slave nodes carry `LAGS_C`, `LAGS_F1` (global components), the
/// frictionless zone's `LAGS_C` only (code_aster's `CONT_LAG_SL_2D`
/// elements beside `FRIC_LAG_SL_2D` ones), numbered after them; zones
/// sharing slave nodes stop as code_aster's CONTACT1_1.
#[test]
fn a_frictionless_zone_beside_a_frictional_one_has_pressures_only() {
    let mesh = two_plates_mesh(6, 5).unwrap();
    let mut with = MortarZoneDef::new("EF", "AB");
    with.friction = Some(FrictionLaw::Coulomb(0.3));
    let without = MortarZoneDef::new("GH", "CD");
    let m = MortarFriction::new(&[with.clone(), without], &mesh, false, 2).unwrap();
    assert_eq!(m.unknowns(), 2 * 7 + 7);
    assert!(m.unknown_name(0, &mesh).starts_with("LAGS_C of node"));
    assert!(m.unknown_name(1, &mesh).starts_with("LAGS_F1 of node"));
    for k in 14..21 {
        assert!(m.unknown_name(k, &mesh).starts_with("LAGS_C of node"));
    }
    let own: Vec<f64> = (0..21).map(|k| k as f64).collect();
    let p: Vec<f64> = m.pressures(&own).map(|(_, p)| p).collect();
    assert_eq!(p, (14..21).map(|k| k as f64).collect::<Vec<_>>());
    assert_eq!(m.multipliers(&own).count(), 7);
    let shared = MortarZoneDef::new("GH", "AB");
    let e = MortarFriction::new(&[with, shared], &mesh, false, 2).unwrap_err();
    assert!(e.to_string().contains("CONTACT1_1"), "{e}");
}
