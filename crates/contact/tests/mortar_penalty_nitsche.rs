//! code_aster 17's DEFI_CONT penalised and Nitsche mortar contact (modules
//! `mortar_penalty`, `mortar_nitsche`): two plates pressed together on
//! non-matching meshes (`scenes::two_plates_shear_problem`, no shear: the
//! top moved down by 0.1, E = 2e6, ν = 0, plane strain, plates of height 1
//! and width 2).
//!
//! - Penalised: the pressure p = γ δ with γ = COEF_CONT / h (h the slave
//!   cells' length 2 / n) and the interpenetration δ: 0.1 = 2 p / E + δ,
//!   δ = 0.05 E / (E / 2 + γ).
//! - Nitsche: the stress of the slave's cells is the body's (uniform), so
//!   the contact is exact: no gap, the interface at DY = −0.05.

use aster_contact::mortar_lagrangian::{InitialState, MortarZoneDef};
use aster_contact::mortar_nitsche::{MortarNitsche, NitscheMaterial};
use aster_contact::mortar_penalty::MortarPenalty;
use aster_contact::scenes::{two_plates_mesh, two_plates_shear_problem};
use aster_contact::ContactError;
use aster_fem::{Comp, Dof, ForceSource, StaticNonLinear};
use aster_mesh::{Cell, CellId, CellType, Group, Mesh, NodeId};

/// DY of the upper plate's bottom-left node A and the lower plate's
/// top-left node E at t = 1.
fn interface(
    n_up: usize,
    n_low: usize,
    source: impl Fn(&[MortarZoneDef], &Mesh) -> Box<dyn ForceSource>,
    init: InitialState,
    coef: f64,
) -> (f64, f64) {
    let mesh = two_plates_mesh(n_up, n_low).unwrap();
    let (model, loads) = two_plates_shear_problem(mesh, 0.0, false).unwrap();
    let mut zone = MortarZoneDef::new("EF", "AB");
    zone.contact_init = init;
    zone.coef_cont = coef;
    let m = source(&[zone], model.mesh());
    let res = {
        let mut snl = StaticNonLinear {
            instants: vec![0.0, 0.5, 1.0],
            forces: vec![m],
            ..Default::default()
        };
        snl.solve(&model, &loads).unwrap()
    };
    let s = res.last().unwrap();
    let dy = |group: &str| {
        let n: NodeId = model.mesh().group_no(group).unwrap().members[0];
        s.displacement[model.dofs().index(Dof::new(n, Comp::DY)).unwrap()]
    };
    (dy("A"), dy("E"))
}

fn penalised(zones: &[MortarZoneDef], mesh: &Mesh) -> Box<dyn ForceSource> {
    Box::new(MortarPenalty::new(zones, mesh, false, 2).unwrap())
}

fn nitsche(zones: &[MortarZoneDef], mesh: &Mesh) -> Box<dyn ForceSource> {
    let material = NitscheMaterial {
        young: 2e6,
        poisson: 0.0,
    };
    Box::new(MortarNitsche::new(zones, mesh, false, material).unwrap())
}

#[test]
fn penalised_plates_interpenetrate_by_the_pressure_over_the_penalty() {
    let e = 2e6;
    for (up, low) in [(1, 1), (3, 2), (2, 5)] {
        for coef in [1e5, 1e6, 1e8] {
            let gamma = coef / (2.0 / up as f64);
            let delta = 0.05 * e / (e / 2.0 + gamma);
            let (a, b) = interface(up, low, penalised, InitialState::Interpenetrated, coef);
            let (ya, yb) = (-(0.1 + delta) / 2.0, -(0.1 - delta) / 2.0);
            assert!(
                (a - ya).abs() < 1e-9,
                "{up}/{low} {coef}: DY(A) = {a}, {ya}"
            );
            assert!(
                (b - yb).abs() < 1e-9,
                "{up}/{low} {coef}: DY(E) = {b}, {yb}"
            );
        }
    }
}

#[test]
fn penalised_answer_does_not_depend_on_the_initial_state() {
    for init in [InitialState::Yes, InitialState::No] {
        let (a, _) = interface(3, 2, penalised, init, 1e6);
        assert!((a + 0.07).abs() < 1e-9, "{init:?}: DY(A) = {a}");
    }
}

#[test]
fn nitsche_plates_meet_exactly_whatever_the_coefficient() {
    for (up, low) in [(1, 1), (3, 2), (2, 5)] {
        for coef in [1e4, 1e6, 1e9] {
            for init in [InitialState::Interpenetrated, InitialState::Yes] {
                let (a, b) = interface(up, low, nitsche, init, coef);
                assert!((a + 0.05).abs() < 1e-9, "{up}/{low} {coef}: DY(A) = {a}");
                assert!((b + 0.05).abs() < 1e-9, "{up}/{low} {coef}: DY(E) = {b}");
            }
        }
    }
}

#[test]
fn nitsche_needs_one_volume_cell_under_each_slave_face() {
    let mut mesh = two_plates_mesh(3, 2).unwrap();
    // A second segment on the first slave face: three cells hold its
    // nodes, code_aster finds no volume cell for it (its map skips the
    // face; only a zone with no face mapped stops with CONTACT1_3).
    let ab = mesh.group_ma("AB").unwrap().members[0];
    let copy = Cell {
        ty: CellType::SEG2,
        nodes: mesh.cells[ab.0 as usize].nodes.clone(),
    };
    mesh.cells.push(copy);
    mesh.cell_names.push("DUP".into());
    let material = NitscheMaterial {
        young: 2e6,
        poisson: 0.0,
    };
    let err = MortarNitsche::new(&[MortarZoneDef::new("EF", "AB")], &mesh, false, material)
        .unwrap_err()
        .to_string();
    assert!(err.contains("has no single QUAD4"), "{err}");
    assert!(MortarPenalty::new(&[MortarZoneDef::new("EF", "AB")], &mesh, false, 2).is_ok());
    // The copy itself as the slave: no face of the zone has one volume
    // cell (CONTACT1_3).
    let dup = mesh.cells.len() - 1;
    mesh.groups_ma.push(Group {
        name: "DUPS".into(),
        members: vec![CellId(dup as u32)],
    });
    let err = MortarNitsche::new(&[MortarZoneDef::new("EF", "DUPS")], &mesh, false, material)
        .unwrap_err();
    assert!(
        matches!(err, ContactError::SlaveWithoutVolume { zone: 1 }),
        "{err}"
    );
}
