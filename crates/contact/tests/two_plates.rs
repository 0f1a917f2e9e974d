//! Two plates pressed together (`scenes::two_plates_mesh`, the SSNP121 kind
//! of scene, generated here): continuous contact gives the contact pressure
//! as code_aster's LAGS_C; the exact answer of a perfect interface is
//! σ_yy = −1e5 (LAGS_C = −1e5) and DY = −0.05 at the interface.

use aster_contact::scenes::{two_plates_mesh, two_plates_problem, two_plates_problem_as};
use aster_contact::*;
use aster_fem::{Comp, Dof, Hypothesis, Model, NonLinearResult, StaticNonLinear, UnilateralSource};

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

/// Solves one step; returns the model, the result and the zones.
fn solve_step(
    n_up: usize,
    n_low: usize,
    def: &ContactDefinition,
) -> (Model, NonLinearResult, Vec<ZoneContact>) {
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
    (model, res, zones)
}

/// Solves one step; returns the model, the displacement and the zones.
fn solve(
    n_up: usize,
    n_low: usize,
    def: &ContactDefinition,
) -> (Model, Vec<f64>, Vec<ZoneContact>) {
    let (model, res, zones) = solve_step(n_up, n_low, def);
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

fn discrete(geom_loop: GeomLoop) -> ContactDefinition {
    let mut def = ContactDefinition::discrete(
        vec![Zone {
            geometry: ZoneGeometry::new("AB", "EF"),
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap();
    def.set_geom_loop(geom_loop);
    def
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

#[test]
fn controle_pairs_exactly_nb_iter_geom_times() {
    for nb_iter in 1..=3 {
        let (_, _, zones) = solve(12, 11, &discrete(GeomLoop::Controle { nb_iter }));
        assert_eq!(zones[0].geom_pairings(), nb_iter);
    }
    // One pairing is the pairing on the initial geometry, i.e. SANS.
    let (_, once, _) = solve(12, 11, &discrete(GeomLoop::Controle { nb_iter: 1 }));
    let (_, sans, _) = solve(12, 11, &discrete(GeomLoop::Sans));
    assert!(max_diff(&once, &sans) < 1e-14);
}

/// The reference for two geometric updates, computed by hand: solve with
/// the pairing of the initial geometry, pair again on that solution, solve
/// with those frozen rows.
#[test]
fn controle_two_is_one_explicit_re_pairing() {
    let (model, first, _) = solve(12, 11, &discrete(GeomLoop::Sans));
    let def = discrete(GeomLoop::Sans);
    let mut zone = ZoneContact::build_all(&def, model.mesh())
        .unwrap()
        .remove(0);
    let x = positions(model.mesh(), model.dofs(), &first);
    let rows = zone.pair(model.mesh(), &x).unwrap();
    let (model, loads) = two_plates_problem(two_plates_mesh(12, 11).unwrap()).unwrap();
    let mut snl = StaticNonLinear {
        instants: vec![0.0, 1.0],
        sources: vec![Box::new(aster_fem::FixedRows {
            name: "second pairing".into(),
            rows,
            method: aster_fem::UnilateralMethod::ActiveSet,
        }) as Box<dyn UnilateralSource>],
        ..Default::default()
    };
    let reference = snl.solve(&model, &loads).unwrap();
    let reference = &reference.last().unwrap().displacement;

    let (_, two, zones) = solve(12, 11, &discrete(GeomLoop::Controle { nb_iter: 2 }));
    assert_eq!(zones[0].geom_pairings(), 2);
    assert!(
        max_diff(&two, reference) < 1e-12,
        "{}",
        max_diff(&two, reference)
    );
    // The re-pairing matters here (the interface bends): not the SANS answer.
    assert!(max_diff(&two, &first) > 1e-6);
}

#[test]
fn automatique_stops_below_resi_geom_after_at_least_two_pairings() {
    let default = GeomLoop::default();
    let (_, u2, zones) = solve(12, 11, &discrete(default));
    let GeomLoop::Automatique { resi_geom, .. } = default else {
        unreachable!()
    };
    assert!(zones[0].geom_pairings() >= 2);
    assert!(zones[0].geom_residual().unwrap() < resi_geom);
    // A tighter RESI_GEOM iterates further, to a nearby fixed point.
    let tight = GeomLoop::Automatique {
        iter_maxi: 30,
        resi_geom: 1e-10,
    };
    let (_, uk, zones) = solve(12, 11, &discrete(tight));
    let r = zones[0].geom_residual().unwrap();
    eprintln!("{} pairings, residual {r:e}", zones[0].geom_pairings());
    assert!(zones[0].geom_pairings() > 2);
    // The loop ends on the residual, or earlier when a new pairing gives
    // the same rows to round-off (a fixed point reached exactly).
    assert!(r < 1e-6, "{r}");
    let d = max_diff(&u2, &uk);
    assert!(d > 0.0 && d < 1e-2 * 0.05, "{d}");
}

#[test]
fn axisymmetric_lags_c_is_the_pressure_when_weights_carry_the_radius() {
    // The plates as two discs (x = r ∈ [0, 2]) under AXIS, ν = 0: the same
    // uniaxial answer, σ_yy = −1e5 on the interface. fem's nodal forces are
    // per radian (∫ … r dr), so the contact integrals must carry r too
    // (code_aster's `mmmjac`): with plane weights LAGS_C would come out as
    // pressure × r / (mean r of the node's cells), 20 % to 100 % off here.
    let mut mesh = two_plates_mesh(4, 4).unwrap();
    for c in &mut mesh.coords {
        c[0] += 1.0;
    }
    let (model, loads) = two_plates_problem_as(mesh, Hypothesis::Axisymmetric).unwrap();
    let def = continuous(Integration::Gauss(3), GeomLoop::Controle { nb_iter: 2 });
    let mut zones = ZoneContact::build_all(&def, model.mesh()).unwrap();
    zones[0].set_measure(Measure::Axisymmetric);
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
    let u = &res.last().unwrap().displacement;
    let lags = zones[0].lags_c().unwrap();
    assert_eq!(lags.len(), 5);
    for (n, p) in &lags {
        assert!((p + 1e5).abs() < 1e-6 * 1e5, "LAGS_C({n:?}) = {p}");
        assert!((dy(&model, u, *n) + 0.05).abs() < 1e-9);
    }
}

/// CONT_NOEU of a continuous zone: code_aster (`mmmres`) reads the vector
/// components from the assembled contact vector, so on the upper plate
/// pressed down onto the lower one RNY = RY = −RN (a discrete zone too,
/// `cfresa` on Aᵀμ: see zzzz237a.rs; SSNV193A tests both). A frictionless continuous node in contact has CONT = 2
/// ("sliding", `mmmres`; a discrete one 1).
#[test]
fn continuous_cont_noeu_components_carry_the_contact_vector_sign() {
    let def = continuous(Integration::Auto, GeomLoop::Controle { nb_iter: 2 });
    let (model, res, mut zones) = solve_step(4, 4, &def);
    let step = res.last().unwrap();
    let x = positions(model.mesh(), model.dofs(), &step.displacement);
    let cn = ContNoeu::at_step(&mut zones, model.mesh(), &x, &step.unilateral).unwrap();
    let lags = zones[0].lags_c().expect("continuous zone has LAGS_C");
    let mut total = 0.0;
    for (n, _) in &lags {
        assert_eq!(cn.value(*n, "CONT"), Some(2.0), "CONT({n:?})");
        let rn = cn.value(*n, "RN").unwrap();
        assert!(rn > 0.0, "RN({n:?}) = {rn}");
        for c in ["RNY", "RY"] {
            let v = cn.value(*n, c).unwrap();
            assert!((v + rn).abs() < 1e-9 * rn, "{c}({n:?}) = {v}, RN = {rn}");
        }
        total += rn;
    }
    // σ_yy = −1e5 over the width of AB: the nodal forces add up to it.
    let xs: Vec<f64> = lags.iter().map(|(n, _)| x[n.0 as usize][0]).collect();
    let width =
        xs.iter().cloned().fold(f64::MIN, f64::max) - xs.iter().cloned().fold(f64::MAX, f64::min);
    assert!(
        (total - 1e5 * width).abs() < 1e-6 * 1e5 * width,
        "sum RN = {total}, width {width}"
    );
}

/// A discrete zone's CONT_NOEU has every component at the `SANS_GROUP_NO`
/// slave nodes too, all zero (code_aster initialises the field at every
/// slave node of the zone, `cfmxr0`, and fills only the contact links):
/// RECU_FONCTION on such a node reads zeros (ssnp501a).
#[test]
fn discrete_cont_noeu_has_zeros_at_sans_group_no_nodes() {
    let mut def = ContactDefinition::discrete(
        vec![Zone {
            geometry: {
                let mut g = ZoneGeometry::new("EF", "AB");
                g.excluded_node_groups = vec!["A".into()];
                g
            },
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Sans,
    )
    .unwrap();
    def.set_geom_loop(GeomLoop::Controle { nb_iter: 2 });
    let (model, res, mut zones) = solve_step(4, 4, &def);
    let step = res.last().unwrap();
    let x = positions(model.mesh(), model.dofs(), &step.displacement);
    let cn = ContNoeu::at_step(&mut zones, model.mesh(), &x, &step.unilateral).unwrap();
    let a = model.mesh().group_no("A").unwrap().members[0];
    for c in ["CONT", "JEU", "RN", "RNY", "R"] {
        assert_eq!(cn.value(a, c), Some(0.0), "{c}(A)");
    }
    let in_contact = cn
        .nodes
        .iter()
        .filter(|n| **n != a && cn.value(**n, "CONT") == Some(1.0))
        .count();
    assert_eq!(in_contact, cn.nodes.len() - 1, "{cn:?}");
}
