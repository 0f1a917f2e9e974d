//! Step cutting (`DEFI_LIST_INST/ECHEC=_F(ACTION='DECOUPE')`) on elastic
//! steps: an increment that fails is redone in `SUBD_PAS` pieces, at most
//! `SUBD_NIVEAU` levels deep and never below `SUBD_PAS_MINI`; beyond that
//! the error names the increment, the limit and the last failure.

mod common;

use aster_fem::*;
use aster_mesh::NodeId;
use common::pulled_square as square;

/// A unilateral source whose pairing only settles on small increments: the
/// stand-in for a contact zone whose geometric loop needs a smaller step.
/// Over an increment longer than `settles_below` (from the last converged
/// time it was told of) every request returns a new row, so the geometric
/// loop never settles.
struct SettlesOnSmallSteps {
    node: NodeId,
    settles_below: f64,
    last_converged: f64,
    requests: usize,
    converged_at: Vec<f64>,
}

impl UnilateralSource for SettlesOnSmallSteps {
    fn geometry_update(&self) -> GeometryUpdate {
        GeometryUpdate::EachIteration
    }

    fn rows(&mut self, state: &State) -> Result<Vec<InequalityRow>, FemError> {
        self.requests += 1;
        // DX of the top corner ≤ b: never reached (the corner moves by
        // ~1e-3), so the row never acts; b changes on every request while
        // the increment is too long.
        let b = if state.time - self.last_converged > self.settles_below {
            1.0 + self.requests as f64
        } else {
            1.0
        };
        Ok(vec![InequalityRow::new(
            vec![(Dof::new(self.node, Comp::DX), 1.0)],
            b,
            0,
        )])
    }

    fn converged(&mut self, state: &State, _outcomes: &[RowOutcome]) -> Result<(), FemError> {
        self.last_converged = state.time;
        self.converged_at.push(state.time);
        Ok(())
    }
}

fn solve(
    instants: &[f64],
    settles_below: f64,
    subdivision: Option<Subdivision>,
) -> (Result<NonLinearResult, FemError>, Vec<f64>) {
    let (model, loads, corner) = square();
    let mut source = SettlesOnSmallSteps {
        node: corner,
        settles_below,
        last_converged: 0.0,
        requests: 0,
        converged_at: Vec::new(),
    };
    let result = {
        let mut snl = StaticNonLinear {
            instants: instants.to_vec(),
            sources: vec![Box::new(&mut source)],
            active_set_max_iter: 5,
            subdivision,
            ..Default::default()
        };
        snl.solve(&model, &loads)
    };
    (result, source.converged_at)
}

#[test]
fn an_elastic_increment_that_fails_whole_converges_cut_in_four() {
    // Whole, the increment 0 → 1 fails (ARRET: the error as it is)…
    let (whole, _) = solve(&[0., 1.], 0.3, None);
    let err = whole.map(|_| ()).unwrap_err();
    assert!(matches!(err, FemError::ActiveSet { .. }), "{err}");
    // …cut in four (code_aster's default SUBD_PAS = 4) each piece of 0.25
    // settles; every piece is a step of the result, numbered in order
    // (code_aster inserts them in its list of instants and archives them,
    // `dinuar`), and the sources hear of every converged piece.
    let (cut, pieces) = solve(&[0., 1.], 0.3, Some(Subdivision::default()));
    let cut = cut.expect("converges once cut");
    assert_eq!(
        cut.steps.iter().map(|s| s.time).collect::<Vec<_>>(),
        vec![0., 0.25, 0.5, 0.75, 1.]
    );
    assert_eq!(
        cut.steps.iter().map(|s| s.nume_ordre).collect::<Vec<_>>(),
        vec![0, 1, 2, 3, 4]
    );
    assert_eq!(pieces, vec![0.25, 0.5, 0.75, 1.0]);
    // Linear elasticity: step by step the same states as the quarters
    // listed.
    let (listed, _) = solve(&[0., 0.25, 0.5, 0.75, 1.], 0.3, None);
    let listed = listed.expect("quarters converge");
    assert_eq!(cut.steps.len(), listed.steps.len());
    for (a, b) in cut.steps.iter().zip(&listed.steps) {
        assert_eq!((a.time, a.nume_ordre), (b.time, b.nume_ordre));
        for (x, y) in a.displacement.iter().zip(&b.displacement) {
            assert!((x - y).abs() <= 1e-14, "{x} vs {y}");
        }
    }
    let a = cut.last().unwrap();
    assert!((a.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs())) - 0.01).abs() < 1e-15);
}

#[test]
fn cutting_goes_as_deep_as_subd_niveau_and_no_deeper() {
    // Pieces of 1/16 are needed: two levels of 4 reach them…
    let two = Subdivision {
        pieces: 4,
        max_level: 2,
        min_step: 0.0,
    };
    let (ok, pieces) = solve(&[0., 1.], 0.07, Some(two));
    ok.expect("1/16 pieces settle");
    assert_eq!(pieces.len(), 16);
    assert!((pieces[0] - 0.0625).abs() < 1e-15);
    // …one level is not enough: a clear error naming the increment, the
    // limit and the last failure.
    let one = Subdivision {
        max_level: 1,
        ..two
    };
    let (err, _) = solve(&[0., 1.], 0.07, Some(one));
    let err = err.map(|_| ()).unwrap_err();
    let FemError::StepCutting {
        from,
        to,
        levels,
        pieces,
        smallest,
        ref cause,
        ..
    } = err
    else {
        panic!("{err}")
    };
    assert_eq!(
        (from, to, levels, pieces, smallest),
        (0.0, 0.25, 1, 4, 0.25)
    );
    assert!(matches!(**cause, FemError::ActiveSet { .. }));
    let message = err.to_string();
    assert!(
        message.contains("from t = 0 to t = 0.25")
            && message.contains("SUBD_NIVEAU = 1 reached")
            && message.contains("does not settle"),
        "{message}"
    );
}

#[test]
fn a_piece_below_subd_pas_mini_stops_the_cutting() {
    let sd = Subdivision {
        pieces: 4,
        max_level: 3,
        min_step: 0.1,
    };
    let (err, converged) = solve(&[0., 1.], 0.07, Some(sd));
    let err = err.map(|_| ()).unwrap_err();
    assert!(matches!(err, FemError::StepCutting { .. }), "{err}");
    assert!(
        err.to_string().contains("below SUBD_PAS_MINI = 1e-1"),
        "{err}"
    );
    assert!(converged.is_empty(), "{converged:?}");
    // SUBD_NIVEAU = 0: no cutting, the failure as it is.
    let none = Subdivision { max_level: 0, ..sd };
    let (err, _) = solve(&[0., 1.], 0.07, Some(none));
    assert!(matches!(err, Err(FemError::ActiveSet { .. })));
}

/// A source standing in for a contact zone whose first pairings move: a
/// row −DX(corner) ≤ bₖ (active: the corner contracts more) whose bound
/// changes for the first `moving` pairings of each step, then stays.
struct MovingPairing {
    node: NodeId,
    moving: usize,
    time: f64,
    pairings: usize,
    most_pairings: usize,
}

impl UnilateralSource for MovingPairing {
    fn geometry_update(&self) -> GeometryUpdate {
        GeometryUpdate::EachIteration
    }

    fn rows(&mut self, state: &State) -> Result<Vec<InequalityRow>, FemError> {
        if state.time != self.time {
            self.time = state.time;
            self.pairings = 0;
        }
        self.pairings += 1;
        self.most_pairings = self.most_pairings.max(self.pairings);
        let k = self.pairings.min(self.moving) as f64;
        Ok(vec![InequalityRow::new(
            vec![(Dof::new(self.node, Comp::DX), -1.0)],
            1e-3 * (1.0 + 0.2 * k),
            0,
        )])
    }
}

/// The square made plastic (SY = 1 against a stress of ~10), its corner
/// held by the moving pairing, one increment.
fn plastic_with_moving_pairing(
    iter_glob_maxi: usize,
) -> (Result<NonLinearResult, FemError>, usize) {
    let (model, loads, corner) = square();
    let mut behaviours = Behaviours::elastic();
    let law = std::sync::Arc::new(VonMises::linear(1000., 1.0, 50.).unwrap());
    for el in model.elements() {
        behaviours.assign(el.cell, law.clone());
    }
    let mut source = MovingPairing {
        node: corner,
        moving: 3,
        time: f64::NAN,
        pairings: 0,
        most_pairings: 0,
    };
    let result = {
        let mut snl = StaticNonLinear {
            instants: vec![0., 1.],
            sources: vec![Box::new(&mut source)],
            behaviours,
            convergence: Convergence {
                resi_glob_rela: Some(1e-10),
                resi_glob_maxi: None,
                iter_glob_maxi,
                at_least_one: false,
            },
            subdivision: None,
            ..Default::default()
        };
        snl.solve(&model, &loads)
    };
    (result, source.most_pairings)
}

#[test]
fn newton_iterations_count_over_the_whole_geometric_loop() {
    // Plenty of iterations: four pairings, each needing Newton iterations
    // of its own (the active row moves the plastic solution).
    let (ok, pairings) = plastic_with_moving_pairing(50);
    let ok = ok.expect("converges");
    assert!(pairings >= 4, "{pairings} pairings");
    let total = ok.last().unwrap().newton_iterations;
    assert!(
        total > pairings,
        "{total} iterations over {pairings} pairings"
    );
    // code_aster numbers them 0..ITER_GLOB_MAXI-1 over the whole loop
    // (`nmconv`: the step fails at iterat + 1 ≥ ITER_GLOB_MAXI, iterat = 0
    // the prediction): the same step with one iteration fewer fails,
    // although no pairing alone took that many (a per-pairing count would
    // accept it).
    let (exact, _) = plastic_with_moving_pairing(total);
    assert_eq!(
        exact
            .expect("just enough")
            .last()
            .unwrap()
            .newton_iterations,
        total
    );
    let (short, _) = plastic_with_moving_pairing(total - 1);
    let err = short.map(|_| ()).unwrap_err();
    assert!(
        matches!(err, FemError::NoConvergence { iterations, .. } if iterations == total - 1),
        "{err}"
    );
}
