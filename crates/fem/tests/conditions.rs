//! Kinematic conditions, loads, unilateral rows and error cases.

mod common;

use aster_fem::*;
use aster_mesh::{CellId, CellType, NodeId};
use common::MeshBuilder;

/// A strip of `n` QUAD4 cells [0, n]×[0, 1] (bottom nodes first, then top).
fn strip(n: usize, hyp: Hypothesis) -> (Model, Vec<NodeId>, Vec<NodeId>, Vec<CellId>) {
    let mut mb = MeshBuilder::new(2);
    let bottom: Vec<NodeId> = (0..=n)
        .map(|i| mb.node(&format!("B{i}"), [i as f64, 0., 0.]))
        .collect();
    let top: Vec<NodeId> = (0..=n)
        .map(|i| mb.node(&format!("T{i}"), [i as f64, 1., 0.]))
        .collect();
    let mut cells = Vec::new();
    for i in 0..n {
        cells.push(mb.cell(
            &format!("M{i}"),
            CellType::QUAD4,
            &[bottom[i], bottom[i + 1], top[i + 1], top[i]],
        ));
    }
    let mut edges = Vec::new();
    for i in 0..n {
        edges.push(mb.cell(&format!("E{i}"), CellType::SEG2, &[top[i + 1], top[i]]));
    }
    let material = Elastic::new(1000., 0.25).unwrap();
    let mut elements: Vec<Element> = cells
        .iter()
        .map(|&c| Element {
            cell: c,
            kind: ElementKind::Continuum {
                hypothesis: hyp,
                material,
            },
        })
        .collect();
    elements.extend(edges.iter().map(|&c| Element {
        cell: c,
        kind: ElementKind::Boundary,
    }));
    (Model::new(mb.mesh, elements).unwrap(), bottom, top, edges)
}

fn idx(m: &Model, n: NodeId, c: Comp) -> usize {
    m.dofs().index(Dof::new(n, c)).unwrap()
}

/// Holds `comps` of `nodes` at 0: eliminated (AFFE_CHAR_CINE) or dualised
/// (DDL_IMPO).
fn hold(loads: &mut Loads, nodes: &[NodeId], comps: &[Comp], dualised: bool) {
    for &n in nodes {
        for &c in comps {
            let dof = Dof::new(n, c);
            loads.push(if dualised {
                Load::Imposed { dof, value: 0. }
            } else {
                Load::Eliminated { dof, value: 0. }
            });
        }
    }
}

#[test]
fn dualised_and_eliminated_supports_agree_and_reactions_balance() {
    let mut results = Vec::new();
    for dualised in [false, true] {
        let (m, bottom, top, _) = strip(3, Hypothesis::PlaneStrain);
        let mut loads = Loads::new();
        hold(&mut loads, &bottom, &[Comp::DX, Comp::DY], dualised);
        loads.push(Load::NodalForce {
            dof: Dof::new(top[3], Comp::DY),
            value: -2.,
        });
        loads.push(Load::NodalForce {
            dof: Dof::new(top[0], Comp::DX),
            value: 1.5,
        });
        let res = meca_statique(&m, &loads, &[]).unwrap();
        let s = &res.steps[0];
        let r = post::reac_noda(&m, &loads, 0., &s.displacement).unwrap();
        // Reactions balance the applied forces.
        let (sx, sy): (f64, f64) = bottom
            .iter()
            .map(|&n| (r[idx(&m, n, Comp::DX)], r[idx(&m, n, Comp::DY)]))
            .fold((0., 0.), |a, b| (a.0 + b.0, a.1 + b.1));
        assert!(
            (sx + 1.5).abs() < 1e-10 && (sy - 2.).abs() < 1e-10,
            "{sx} {sy}"
        );
        // Free nodes carry no reaction.
        for &n in &top {
            assert!(r[idx(&m, n, Comp::DX)].abs() < 1e-10);
        }
        if dualised {
            // Multipliers are the reactions with the opposite sign.
            let rows = loads.equality_rows(&m, 0.).unwrap();
            for (row, lam) in rows.iter().zip(&s.multipliers) {
                let i = row.terms[0].0;
                assert!(
                    (r[i] + lam).abs() < 1e-9,
                    "reaction {} multiplier {lam}",
                    r[i]
                );
            }
        }
        results.push(s.displacement.clone());
    }
    for (a, b) in results[0].iter().zip(&results[1]) {
        assert!((a - b).abs() < 1e-12 * (1. + a.abs()));
    }
}

#[test]
fn linear_relation_ties_dofs() {
    let (m, bottom, top, _) = strip(2, Hypothesis::PlaneStress);
    let mut loads = Loads::new();
    hold(&mut loads, &bottom, &[Comp::DX, Comp::DY], false);
    // DY(T0) - DY(T2) = 0.01 and DX(T1) = 2 DX(T2) (LIAISON_DDL).
    loads.push(Load::Relation {
        terms: vec![
            (Dof::new(top[0], Comp::DY), 1.),
            (Dof::new(top[2], Comp::DY), -1.),
        ],
        rhs: 0.01,
    });
    loads.push(Load::Relation {
        terms: vec![
            (Dof::new(top[1], Comp::DX), 1.),
            (Dof::new(top[2], Comp::DX), -2.),
        ],
        rhs: 0.,
    });
    loads.push(Load::NodalForce {
        dof: Dof::new(top[2], Comp::DX),
        value: 3.,
    });
    let s = &meca_statique(&m, &loads, &[]).unwrap().steps[0];
    let u = |n, c| s.displacement[idx(&m, n, c)];
    assert!((u(top[0], Comp::DY) - u(top[2], Comp::DY) - 0.01).abs() < 1e-12);
    assert!((u(top[1], Comp::DX) - 2. * u(top[2], Comp::DX)).abs() < 1e-12);
    assert!(u(top[2], Comp::DX) != 0.);
}

#[test]
fn pressure_on_top_edge_gives_uniform_stress_whatever_the_edge_orientation() {
    for reversed in [false, true] {
        let (m0, bottom, top, edges) = strip(2, Hypothesis::PlaneStrain);
        let mut mesh = m0.mesh().clone();
        if reversed {
            for &e in &edges {
                mesh.cells[e.0 as usize].nodes.reverse();
            }
        }
        let m = Model::new(mesh, m0.elements().to_vec()).unwrap();
        let mut loads = Loads::new();
        hold(&mut loads, &bottom, &[Comp::DY], false);
        hold(&mut loads, &bottom[..1], &[Comp::DX], false);
        for &e in &edges {
            loads.add(
                Load::Pressure {
                    cell: e,
                    pressure: 5.,
                },
                Multiplier::constant(2.),
            );
        }
        let s = &meca_statique(&m, &loads, &[]).unwrap().steps[0];
        for cv in &s.stress {
            for p in &cv.points {
                // σyy = −p·f = −10, σxx = 0 (free sides).
                assert!((cv.get(0, "SIYY").unwrap() + 10.).abs() < 1e-9, "{p:?}");
                assert!(p[0].abs() < 1e-9);
            }
        }
        let _ = top;
    }
}

#[test]
fn edge_force_in_axis_is_per_radian() {
    // A ring r ∈ [1, 2], z ∈ [0, 1] with an axial traction on its top: the
    // reactions per radian equal q ∫ r dr = q (2² − 1²)/2.
    let mut mb = MeshBuilder::new(2);
    let a = mb.node("A", [1., 0., 0.]);
    let b = mb.node("B", [2., 0., 0.]);
    let c = mb.node("C", [2., 1., 0.]);
    let d = mb.node("D", [1., 1., 0.]);
    let q = mb.cell("Q", CellType::QUAD4, &[a, b, c, d]);
    let e = mb.cell("E", CellType::SEG2, &[c, d]);
    let mat = Elastic::new(100., 0.3).unwrap();
    let m = Model::new(
        mb.mesh,
        vec![
            Element {
                cell: q,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::Axisymmetric,
                    material: mat,
                },
            },
            Element {
                cell: e,
                kind: ElementKind::Boundary,
            },
        ],
    )
    .unwrap();
    let mut loads = Loads::new();
    loads.push(Load::SurfaceForce {
        cell: e,
        force: [0., 4., 0.],
    });
    for n in [a, b] {
        loads.push(Load::Eliminated {
            dof: Dof::new(n, Comp::DY),
            value: 0.,
        });
    }
    let s = &meca_statique(&m, &loads, &[0.]).unwrap().steps[0];
    let r = post::reac_noda(&m, &loads, 0., &s.displacement).unwrap();
    let total = r[idx(&m, a, Comp::DY)] + r[idx(&m, b, Comp::DY)];
    assert!((total + 4. * 1.5).abs() < 1e-10, "{total}");
}

#[test]
fn missing_support_names_the_free_dofs() {
    let (m, bottom, _, _) = strip(2, Hypothesis::PlaneStrain);
    let mut loads = Loads::new();
    hold(&mut loads, &bottom, &[Comp::DY], false);
    let err = meca_statique(&m, &loads, &[]).unwrap_err();
    let FemError::Singular { free_dofs } = &err else {
        panic!("expected a singular-system error, got {err}");
    };
    // The whole strip can slide along x: every DX is free, no DY is.
    assert_eq!(free_dofs.len(), 6, "{free_dofs:?}");
    assert!(
        free_dofs.iter().all(|d| d.ends_with(" DX")),
        "{free_dofs:?}"
    );
    let msg = err.to_string();
    assert!(
        msg.contains("B0 DX") && msg.contains("free degrees of freedom"),
        "{msg}"
    );

    // A rotation left free: DX and DY held at one node only.
    let mut loads = Loads::new();
    loads.push(Load::Imposed {
        dof: Dof::new(bottom[0], Comp::DX),
        value: 0.,
    });
    loads.push(Load::Imposed {
        dof: Dof::new(bottom[0], Comp::DY),
        value: 0.,
    });
    let err = meca_statique(&m, &loads, &[]).unwrap_err();
    let FemError::Singular { free_dofs } = &err else {
        panic!("{err}")
    };
    assert!(
        !free_dofs.is_empty() && !free_dofs.iter().any(|d| d == "B0 DX" || d == "B0 DY"),
        "{free_dofs:?}"
    );
}

#[test]
fn bad_inputs_are_errors_not_panics() {
    let (m, _, top, _) = strip(1, Hypothesis::PlaneStrain);
    let mut loads = Loads::new();
    loads.push(Load::Imposed {
        dof: Dof::new(top[0], Comp::DZ),
        value: 0.,
    });
    let err = meca_statique(&m, &loads, &[]).unwrap_err().to_string();
    assert!(err.contains("T0 DZ") && err.contains("DX, DY"), "{err}");
    assert!(Elastic::new(-1., 0.3).is_err());
    assert!(Elastic::new(1., 0.5).is_err());
    // A volume under a plane modelisation.
    let mut mesh = m.mesh().clone();
    mesh.cells[0].ty = CellType::TETRA4;
    let err = Model::new(
        mesh,
        vec![Element {
            cell: CellId(0),
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::PlaneStrain,
                material: Elastic::new(1., 0.).unwrap(),
            },
        }],
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("M0 is a TETRA4") && err.contains("D_PLAN"),
        "{err}"
    );
    // A cell whose node count does not match its type.
    let mut mesh = m.mesh().clone();
    mesh.cells[0].nodes.pop();
    let err = Model::new(mesh, m.elements().to_vec())
        .unwrap_err()
        .to_string();
    assert!(err.contains("M0") && err.contains("3 nodes"), "{err}");
}

/// A strip resting on unilateral supports along its bottom, loaded so
/// that its right end lifts off.
fn lift_off(method: UnilateralMethod) -> (Model, NonLinearResult, Vec<NodeId>) {
    let (m, bottom, top, _) = strip(6, Hypothesis::PlaneStrain);
    let mut loads = Loads::new();
    hold(&mut loads, &bottom[..1], &[Comp::DX], false);
    loads.add(
        Load::NodalForce {
            dof: Dof::new(top[1], Comp::DY),
            value: -10.,
        },
        Multiplier::from_fn(Ok),
    );
    loads.add(
        Load::NodalForce {
            dof: Dof::new(top[6], Comp::DY),
            value: 1.,
        },
        Multiplier::from_fn(Ok),
    );
    let rows = bottom
        .iter()
        .enumerate()
        .map(|(k, &n)| InequalityRow::new(vec![(Dof::new(n, Comp::DY), -1.)], 0., k))
        .collect();
    let mut snl = StaticNonLinear {
        instants: vec![0., 0.5, 1.],
        sources: vec![Box::new(FixedRows {
            name: "base".into(),
            rows,
            method,
        })],
        ..Default::default()
    };
    let res = snl.solve(&m, &loads).unwrap();
    (m, res, bottom)
}

#[test]
fn active_set_finds_the_contact_zone() {
    let (m, res, bottom) = lift_off(UnilateralMethod::ActiveSet);
    let last = res.last().unwrap();
    let out = &last.unilateral[0];
    let total: f64 = out.iter().map(|o| o.multiplier).sum();
    // Vertical equilibrium: the supports carry the net 9 downward.
    assert!((total - 9.).abs() < 1e-9, "{total}");
    assert!(out.iter().all(|o| o.multiplier >= 0.));
    assert!(out[0].active && !out[6].active, "{out:?}");
    for o in out {
        if o.active {
            assert!(o.violation.abs() < 1e-12);
        } else {
            assert!(o.violation < 0. && o.multiplier == 0.);
        }
    }
    // The lifted end moved up.
    let dy = last.displacement[idx(&m, bottom[6], Comp::DY)];
    assert!(dy > 0.);
}

#[test]
fn penalty_converges_to_the_active_set_solution() {
    let (_, exact, _) = lift_off(UnilateralMethod::ActiveSet);
    let (_, pen, _) = lift_off(UnilateralMethod::Penalty { coef: 1e9 });
    let (e, p) = (exact.last().unwrap(), pen.last().unwrap());
    let umax = e.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (a, b) in e.displacement.iter().zip(&p.displacement) {
        assert!((a - b).abs() < 1e-4 * umax, "{a} vs {b}");
    }
    for (a, b) in e.unilateral[0].iter().zip(&p.unilateral[0]) {
        assert_eq!(a.active, b.active);
        assert!((a.multiplier - b.multiplier).abs() < 1e-3 * 9.);
    }
}

#[test]
fn instants_honour_inst_init_and_inst_fin() {
    let (m, bottom, top, _) = strip(1, Hypothesis::PlaneStrain);
    let mut loads = Loads::new();
    hold(&mut loads, &bottom, &[Comp::DX, Comp::DY], false);
    loads.add(
        Load::Imposed {
            dof: Dof::new(top[0], Comp::DY),
            value: 0.1,
        },
        Multiplier::from_fn(|t| Ok(t * t)),
    );
    let mut snl = StaticNonLinear {
        instants: vec![0., 1., 2., 3., 4.],
        init_time: Some(1.),
        final_time: Some(3.),
        ..Default::default()
    };
    let res = snl.solve(&m, &loads).unwrap();
    let times: Vec<f64> = res.steps.iter().map(|s| s.time).collect();
    assert_eq!(times, vec![1., 2., 3.]);
    let s = res.by_order(2).unwrap();
    assert!((s.displacement[idx(&m, top[0], Comp::DY)] - 0.9).abs() < 1e-12);
    // A multiplier function that fails is reported with the time.
    loads.add(
        Load::NodalForce {
            dof: Dof::new(top[1], Comp::DX),
            value: 1.,
        },
        Multiplier::from_fn(|t| {
            if t > 2.5 {
                Err("outside the function's range (EXCLU)".into())
            } else {
                Ok(1.)
            }
        }),
    );
    let err = snl.solve(&m, &loads).unwrap_err().to_string();
    assert!(err.contains("time 3") && err.contains("EXCLU"), "{err}");
}

#[test]
fn continuum_on_boundary_cells_gives_boundary_elements_and_last_assignment_wins() {
    let mut mb = MeshBuilder::new(2);
    let a = mb.node("A", [0., 0., 0.]);
    let b = mb.node("B", [1., 0., 0.]);
    let c = mb.node("C", [1., 1., 0.]);
    let d = mb.node("D", [0., 1., 0.]);
    let p = mb.node("P", [5., 5., 0.]);
    let q = mb.cell("Q", CellType::QUAD4, &[a, b, c, d]);
    let e = mb.cell("E", CellType::SEG2, &[c, d]);
    let pt = mb.cell("PT", CellType::POI1, &[p]);
    let mat = Elastic::new(1., 0.2).unwrap();
    let cont = ElementKind::Continuum {
        hypothesis: Hypothesis::PlaneStrain,
        material: mat,
    };
    let m = Model::new(
        mb.mesh,
        vec![
            Element {
                cell: q,
                kind: ElementKind::Spring {
                    stiffness: vec![1., 1.],
                    frame: Frame::Global,
                },
            },
            Element {
                cell: q,
                kind: cont.clone(),
            },
            Element {
                cell: e,
                kind: cont.clone(),
            },
            Element {
                cell: pt,
                kind: cont,
            },
        ],
    )
    .unwrap();
    assert_eq!(m.elements().len(), 2);
    assert!(matches!(
        m.elements()[0].kind,
        ElementKind::Continuum { .. }
    ));
    assert_eq!(m.elements()[1].kind, ElementKind::Boundary);
    // The POI1 got no element, so its node has no DOF.
    assert!(!m.dofs().has_node(p));
    assert_eq!(m.dofs().len(), 8);
}

/// A source that re-computes its rows from the current geometry, as a
/// contact zone does, and records what the solver hands back.
struct GeometricSource {
    nodes: Vec<NodeId>,
    rows_calls: usize,
    converged: Vec<(f64, Vec<RowOutcome>)>,
}

impl UnilateralSource for GeometricSource {
    fn name(&self) -> String {
        "geometric".into()
    }
    fn geometry_update(&self) -> GeometryUpdate {
        GeometryUpdate::EachIteration
    }
    fn rows(&mut self, state: &State) -> Result<Vec<InequalityRow>, FemError> {
        self.rows_calls += 1;
        // Gap to the plane y = 0 measured on the current geometry:
        // −(y + Δ) ≤ 0 written on the total displacement as −u ≤ y₀.
        Ok(self
            .nodes
            .iter()
            .enumerate()
            .map(|(k, &n)| {
                let y0 = state.mesh.coord(n)[1];
                InequalityRow::new(vec![(Dof::new(n, Comp::DY), -1.)], y0, k)
            })
            .collect())
    }
    fn converged(&mut self, state: &State, outcomes: &[RowOutcome]) -> Result<(), FemError> {
        self.converged.push((state.time, outcomes.to_vec()));
        Ok(())
    }
}

#[test]
fn sources_with_geometry_updates_get_their_outcomes_each_step() {
    let (m, bottom, top, _) = strip(2, Hypothesis::PlaneStrain);
    let mut loads = Loads::new();
    hold(&mut loads, &bottom[..1], &[Comp::DX], false);
    for &n in &top {
        loads.add(
            Load::NodalForce {
                dof: Dof::new(n, Comp::DY),
                value: -1.,
            },
            Multiplier::from_fn(Ok),
        );
    }
    let mut src = GeometricSource {
        nodes: bottom.clone(),
        rows_calls: 0,
        converged: Vec::new(),
    };
    {
        let mut snl = StaticNonLinear {
            instants: vec![0., 1., 2.],
            sources: vec![Box::new(&mut src)],
            ..Default::default()
        };
        let res = snl.solve(&m, &loads).unwrap();
        let last = res.last().unwrap();
        let total: f64 = last.unilateral[0].iter().map(|o| o.multiplier).sum();
        assert!((total - 6.).abs() < 1e-9, "{total}");
    }
    assert_eq!(src.converged.len(), 2);
    assert_eq!(src.converged[1].0, 2.);
    assert!(src.converged[1]
        .1
        .iter()
        .all(|o| o.active && o.violation.abs() < 1e-12));
    // Asked at each step and again at each converged iterate.
    assert!(src.rows_calls >= 4, "{}", src.rows_calls);
}

#[test]
fn unreachable_convergence_criterion_is_a_clear_error() {
    let (m, bottom, top, _) = strip(2, Hypothesis::PlaneStrain);
    let mut loads = Loads::new();
    hold(&mut loads, &bottom, &[Comp::DX, Comp::DY], false);
    loads.push(Load::NodalForce {
        dof: Dof::new(top[1], Comp::DX),
        value: 1.234567,
    });
    let mut snl = StaticNonLinear {
        instants: vec![0., 1.],
        convergence: Convergence {
            resi_glob_rela: Some(1e-300),
            resi_glob_maxi: None,
            iter_glob_maxi: 3,
            at_least_one: false,
        },
        // ECHEC ACTION='ARRET': the failure itself (cutting would only
        // fail again on smaller pieces, see tests/step_cutting.rs).
        subdivision: None,
        ..Default::default()
    };
    match snl.solve(&m, &loads) {
        // Round-off may vanish exactly: then the step converges legitimately.
        Ok(res) => assert_eq!(res.last().unwrap().resi_glob_rela, 0.0),
        Err(e) => {
            let FemError::NoConvergence {
                time, iterations, ..
            } = e
            else {
                panic!("{e}")
            };
            // code_aster numbers the iterations from 0 and stops at
            // iterat + 1 = ITER_GLOB_MAXI (`nmconv`): 3 residual checks.
            assert_eq!((time, iterations), (1.0, 3));
            assert!(e.to_string().contains("ITER_GLOB_MAXI"));
        }
    }
    // The default criterion converges in one iteration (linear elasticity).
    snl.convergence = Convergence::default();
    let res = snl.solve(&m, &loads).unwrap();
    assert_eq!(res.last().unwrap().iterations, 1);
}

#[test]
fn loads_given_point_by_point_integrate_their_values() {
    // The ring of `edge_force_in_axis_is_per_radian`: an axial traction
    // q(r) = r at the edge's points gives reactions ∫ r·r dr = 7/3 per
    // radian; a body force b(r) = r on the cell ∫∫ r·r dr dz = 7/3; a
    // pressure p(r) = r on the top pushes down by the same.
    let mut mb = MeshBuilder::new(2);
    let a = mb.node("A", [1., 0., 0.]);
    let b = mb.node("B", [2., 0., 0.]);
    let c = mb.node("C", [2., 1., 0.]);
    let d = mb.node("D", [1., 1., 0.]);
    let q = mb.cell("Q", CellType::QUAD4, &[a, b, c, d]);
    let e = mb.cell("E", CellType::SEG2, &[c, d]);
    let mat = Elastic::new(100., 0.3).unwrap();
    let m = Model::new(
        mb.mesh,
        vec![
            Element {
                cell: q,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::Axisymmetric,
                    material: mat,
                },
            },
            Element {
                cell: e,
                kind: ElementKind::Boundary,
            },
        ],
    )
    .unwrap();
    let skin = Loads::skin_points(m.mesh(), e);
    assert_eq!(skin.len(), 2);
    let vol = Loads::volume_points(m.mesh(), q);
    assert_eq!(vol.len(), 4);
    let cases: Vec<(Load, f64)> = vec![
        (
            Load::SurfaceForceAt {
                cell: e,
                forces: skin.iter().map(|x| [0., x[0], 0.]).collect(),
            },
            7. / 3.,
        ),
        (
            Load::VolumeForceAt {
                cell: q,
                forces: vol.iter().map(|x| [0., x[0], 0.]).collect(),
            },
            7. / 3.,
        ),
        (
            Load::PressureAt {
                cell: e,
                pressures: skin.iter().map(|x| x[0]).collect(),
            },
            -7. / 3.,
        ),
    ];
    for (load, resultant) in cases {
        let mut loads = Loads::new();
        loads.add(load, Multiplier::constant(2.));
        for n in [a, b] {
            loads.push(Load::Eliminated {
                dof: Dof::new(n, Comp::DY),
                value: 0.,
            });
        }
        let s = &meca_statique(&m, &loads, &[0.]).unwrap().steps[0];
        let r = post::reac_noda(&m, &loads, 0., &s.displacement).unwrap();
        let total = r[idx(&m, a, Comp::DY)] + r[idx(&m, b, Comp::DY)];
        assert!((total + 2. * resultant).abs() < 1e-10, "{total}");
    }
    // Values at the wrong number of points: a located error, no panic.
    let mut loads = Loads::new();
    loads.push(Load::PressureAt {
        cell: e,
        pressures: vec![1.; 3],
    });
    loads.push(Load::Eliminated {
        dof: Dof::new(a, Comp::DY),
        value: 0.,
    });
    let err = meca_statique(&m, &loads, &[0.]).unwrap_err().to_string();
    assert!(err.contains("given at 3 points"), "{err}");
}

/// A pressure on the concave inner face of a thin curved HEXA20 (a sector
/// of a tube: r ∈ [0.975, 1], θ ∈ [0°, 15°], z ∈ [0, 0.25]) pushes the tube
/// outward with the resultant p h r_i (sin θ₁, 1 − cos θ₁), whichever way
/// the QUAD8 face is numbered. The corners' centroid of so thin and curved
/// a cell lies beyond some points of the face, so the outward side is
/// decided once per face, from the cell's corners off the face (ssls114g:
/// a tube under internal pressure got a ninth of its load, some Gauss
/// points pushing inward).
#[test]
fn pressure_on_the_inner_face_of_a_thin_curved_hexa20_pushes_outward() {
    let (ri, ro, h, t1) = (0.975f64, 1.0f64, 0.25f64, 15f64.to_radians());
    for reversed in [false, true] {
        let mut mb = MeshBuilder::new(3);
        let at = |r: f64, th: f64, z: f64| [r * th.cos(), r * th.sin(), z];
        let rm = 0.5 * (ri + ro);
        let tm = 0.5 * t1;
        let pts = [
            at(ri, 0., 0.),
            at(ro, 0., 0.),
            at(ro, t1, 0.),
            at(ri, t1, 0.),
            at(ri, 0., h),
            at(ro, 0., h),
            at(ro, t1, h),
            at(ri, t1, h),
            at(rm, 0., 0.),
            at(ro, tm, 0.),
            at(rm, t1, 0.),
            at(ri, tm, 0.),
            at(ri, 0., h / 2.),
            at(ro, 0., h / 2.),
            at(ro, t1, h / 2.),
            at(ri, t1, h / 2.),
            at(rm, 0., h),
            at(ro, tm, h),
            at(rm, t1, h),
            at(ri, tm, h),
        ];
        let n: Vec<NodeId> = pts
            .iter()
            .enumerate()
            .map(|(i, p)| mb.node(&format!("N{}", i + 1), *p))
            .collect();
        let hexa = mb.cell("H", CellType::HEXA20, &n);
        // The inner face r = ri: corners 1 5 8 4, middles 13 20 16 12.
        let face = if reversed {
            [0, 3, 7, 4, 11, 15, 19, 12]
        } else {
            [0, 4, 7, 3, 12, 19, 15, 11]
        };
        let f: Vec<NodeId> = face.iter().map(|&i| n[i]).collect();
        let q = mb.cell("F", CellType::QUAD8, &f);
        let m = Model::new(
            mb.mesh,
            vec![Element {
                cell: hexa,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::Solid3D,
                    material: Elastic::new(2e11, 0.3).unwrap(),
                },
            }],
        )
        .unwrap();
        let mut loads = Loads::new();
        loads.add(
            Load::Pressure {
                cell: q,
                pressure: 10.,
            },
            Multiplier::constant(1.),
        );
        let fv = loads.external_forces(&m, 1.0).unwrap();
        let mut total = [0.0; 3];
        for &node in &n {
            for (k, c) in [Comp::DX, Comp::DY, Comp::DZ].into_iter().enumerate() {
                total[k] += fv[idx(&m, node, c)];
            }
        }
        let want = [10. * h * ri * t1.sin(), 10. * h * ri * (1. - t1.cos()), 0.];
        for k in 0..3 {
            assert!(
                (total[k] - want[k]).abs() < 1e-5 * 10. * h * ri,
                "reversed {reversed}: resultant {total:?}, want {want:?}"
            );
        }
    }
}
