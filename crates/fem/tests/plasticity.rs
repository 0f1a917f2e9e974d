//! Von Mises plasticity in STAT_NON_LINE: uniaxial tension against the
//! analytic elasto-plastic curve (linear and traction-curve hardening, 3D
//! and C_PLAN), homogeneous patches (D_PLAN, AXIS) against the Gauss-point
//! law, and Newton's quadratic convergence with the consistent tangent.

// Grid loops index rows and columns as the formulas do.
#![allow(clippy::needless_range_loop)]

mod common;

use aster_fem::behaviour::vmis::{integrate, PointState};
use aster_fem::behaviour::Hardening;
use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;
use std::sync::Arc;

const E: f64 = 200e3;
const NU: f64 = 0.3;
const SY: f64 = 200.;
const ET: f64 = 2000.;

/// The exactness tests converge Newton to round-off (quadratic
/// convergence makes that a couple of iterations more than the default).
const TIGHT: Convergence = Convergence {
    resi_glob_rela: Some(1e-12),
    resi_glob_maxi: None,
    iter_glob_maxi: 20,
    at_least_one: false,
};

fn steel() -> Elastic {
    Elastic::new(E, NU).unwrap()
}

/// Uniaxial stress σ(ε) of ECRO_LINE: SY + ET (ε − SY/E) beyond yield.
fn ecro_line_sigma(eps: f64) -> f64 {
    if eps <= SY / E {
        E * eps
    } else {
        SY + ET * (eps - SY / E)
    }
}

/// A traction curve starting on the elastic line (ε₁ = σ₁/E).
const CURVE_EPS: [f64; 4] = [1e-3, 3e-3, 1e-2, 2e-2];
const CURVE_SIG: [f64; 4] = [200., 260., 330., 360.];

/// Under uniaxial stress the (ε, σ) path runs along the traction curve:
/// σ and ε = σ/E + p are both linear in p on each segment of R(p).
fn curve_sigma(eps: f64) -> f64 {
    if eps <= CURVE_EPS[0] {
        return E * eps;
    }
    let k = CURVE_EPS.windows(2).position(|w| eps <= w[1]).unwrap();
    let (e0, e1, s0, s1) = (
        CURVE_EPS[k],
        CURVE_EPS[k + 1],
        CURVE_SIG[k],
        CURVE_SIG[k + 1],
    );
    s0 + (s1 - s0) * (eps - e0) / (e1 - e0)
}

fn ecro_line() -> Arc<VonMises> {
    Arc::new(VonMises::linear(E, SY, ET).unwrap())
}

fn traction() -> Arc<VonMises> {
    Arc::new(VonMises::traction(E, &CURVE_EPS, &CURVE_SIG, CurveEnd::Linear).unwrap())
}

fn plastic_everywhere(model: &Model, law: &Arc<VonMises>) -> Behaviours {
    let mut b = Behaviours::elastic();
    for el in model.elements() {
        b.assign(el.cell, law.clone());
    }
    b
}

fn idx(m: &Model, n: NodeId, c: Comp) -> usize {
    m.dofs().index(Dof::new(n, c)).unwrap()
}

/// The unit cube as one HEXA8 under DX = strain(t) on x = 1, with symmetry
/// planes x = 0, y = 0, z = 0: uniaxial stress σxx.
fn cube_tension(law: Arc<VonMises>, strains: &[f64]) -> (Model, NonLinearResult, Vec<NodeId>) {
    let mut mb = MeshBuilder::new(3);
    let mut nodes = Vec::new();
    for (x, y, z) in [
        (0., 0., 0.),
        (1., 0., 0.),
        (1., 1., 0.),
        (0., 1., 0.),
        (0., 0., 1.),
        (1., 0., 1.),
        (1., 1., 1.),
        (0., 1., 1.),
    ] {
        nodes.push(mb.node(&format!("N{}", nodes.len() + 1), [x, y, z]));
    }
    let cell = mb.cell("M1", CellType::HEXA8, &nodes);
    let model = Model::new(
        mb.mesh,
        vec![Element {
            cell,
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::Solid3D,
                material: steel(),
            },
        }],
    )
    .unwrap();
    let mut loads = Loads::new();
    let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| model.mesh().coord(n)).collect();
    let table: Vec<f64> = strains.to_vec();
    for (k, &n) in nodes.iter().enumerate() {
        for (c, comp) in [Comp::DX, Comp::DY, Comp::DZ].into_iter().enumerate() {
            if coords[k][c] == 0. {
                loads.push(Load::Eliminated {
                    dof: Dof::new(n, comp),
                    value: 0.,
                });
            }
        }
        if coords[k][0] == 1. {
            let table = table.clone();
            loads.add(
                Load::Eliminated {
                    dof: Dof::new(n, Comp::DX),
                    value: 1.,
                },
                Multiplier::from_fn(move |t| Ok(table[t.round() as usize])),
            );
        }
    }
    let mut snl = StaticNonLinear {
        instants: (0..strains.len()).map(|i| i as f64).collect(),
        convergence: TIGHT,
        behaviours: plastic_everywhere(&model, &law),
        ..Default::default()
    };
    let res = snl.solve(&model, &loads).unwrap();
    (model, res, nodes)
}

/// Strains up to 15 yield strains, then an unloading step.
const PATH: [f64; 8] = [0., 5e-4, 9e-4, 2e-3, 4e-3, 8e-3, 1.5e-2, 1.4e-2];

fn check_uniaxial(res: &NonLinearResult, sigma: impl Fn(f64) -> f64, plateau_strain: f64) {
    let mut sig_max: f64 = 0.;
    let mut p_max: f64 = 0.;
    let mut eps_max: f64 = 0.;
    for (k, &eps) in PATH.iter().enumerate().skip(1) {
        let step = res.by_order(k).unwrap();
        let (want, unloading) = if eps >= eps_max {
            (sigma(eps), false)
        } else {
            // Elastic unloading from the largest state reached.
            (sig_max - E * (eps_max - eps), true)
        };
        let cv = &step.stress[0];
        let vari = &step.internal_variables[0];
        for g in 0..cv.points.len() {
            let sxx = cv.get(g, "SIXX").unwrap();
            assert!(
                (sxx - want).abs() <= 1e-9 * want.abs().max(1.),
                "ε = {eps}: σxx = {sxx}, analytic {want}"
            );
            for other in ["SIYY", "SIZZ", "SIXY"] {
                assert!(cv.get(g, other).unwrap().abs() < 1e-9 * SY, "{other}");
            }
            // V1 = p = ε − σ/E under uniaxial stress (frozen on unloading);
            // V2 = 1 on a plastic increment only.
            let p = if unloading {
                p_max
            } else {
                (eps - want / E).max(0.)
            };
            let v1 = vari.get(g, "V1").unwrap();
            assert!(
                (v1 - p).abs() <= 1e-12 + 1e-9 * p,
                "ε = {eps}: p = {v1}, analytic {p}"
            );
            let plastic = !unloading && eps > plateau_strain;
            assert_eq!(
                vari.get(g, "V2").unwrap(),
                if plastic { 1.0 } else { 0.0 },
                "ε = {eps}"
            );
        }
        if !unloading {
            sig_max = want;
            p_max = (eps - want / E).max(0.);
            eps_max = eps;
        }
    }
}

#[test]
fn cube_in_uniaxial_tension_follows_the_ecro_line_curve() {
    let (model, res, nodes) = cube_tension(ecro_line(), &PATH);
    check_uniaxial(&res, ecro_line_sigma, SY / E);
    // Lateral contraction: εyy = −ν σ/E − p/2 (plastic flow is isochoric).
    let step = res.by_order(6).unwrap();
    let (eps, sig) = (PATH[6], ecro_line_sigma(PATH[6]));
    let p = eps - sig / E;
    let uy = step.displacement[idx(&model, nodes[6], Comp::DY)];
    let want = -NU * sig / E - p / 2.;
    assert!((uy - want).abs() < 1e-12, "{uy} vs {want}");
}

#[test]
fn cube_in_uniaxial_tension_follows_the_traction_curve() {
    let (_, res, _) = cube_tension(traction(), &PATH);
    check_uniaxial(&res, curve_sigma, CURVE_EPS[0]);
}

/// One QUAD4 [0,1]² in C_PLAN pulled along x: uniaxial stress with
/// σzz = 0 found at each Gauss point.
#[test]
fn plane_stress_strip_follows_the_uniaxial_curve() {
    let mut mb = MeshBuilder::new(2);
    let n: Vec<NodeId> = [(0., 0.), (1., 0.), (1., 1.), (0., 1.)]
        .iter()
        .enumerate()
        .map(|(k, &(x, y))| mb.node(&format!("N{k}"), [x, y, 0.]))
        .collect();
    let cell = mb.cell("M1", CellType::QUAD4, &n);
    let model = Model::new(
        mb.mesh,
        vec![Element {
            cell,
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::PlaneStress,
                material: steel(),
            },
        }],
    )
    .unwrap();
    let mut loads = Loads::new();
    for (node, comp) in [
        (n[0], Comp::DX),
        (n[0], Comp::DY),
        (n[1], Comp::DY),
        (n[3], Comp::DX),
    ] {
        loads.push(Load::Eliminated {
            dof: Dof::new(node, comp),
            value: 0.,
        });
    }
    for node in [n[1], n[2]] {
        loads.add(
            Load::Eliminated {
                dof: Dof::new(node, Comp::DX),
                value: 1.,
            },
            Multiplier::from_fn(|t| Ok(PATH[t.round() as usize])),
        );
    }
    // code_aster's plane-stress search (nmisot) stops at RESI_INTE·SY
    // (1e-6 by default): the exact uniaxial curve to 1e-9 needs it tight.
    let tight = LocalSearch {
        resi_inte: 1e-15,
        iter_maxi: 200,
    };
    for law in [ecro_line(), traction()] {
        let law = Arc::new((*law).clone().with_search(tight));
        let mut snl = StaticNonLinear {
            instants: (0..PATH.len()).map(|i| i as f64).collect(),
            convergence: TIGHT,
            behaviours: plastic_everywhere(&model, &law),
            ..Default::default()
        };
        let res = snl.solve(&model, &loads).unwrap();
        if law.sy == SY && matches!(law.hardening, Hardening::Linear { .. }) {
            check_uniaxial(&res, ecro_line_sigma, SY / E);
        } else {
            check_uniaxial(&res, curve_sigma, CURVE_EPS[0]);
        }
    }
}

/// A 3×3 QUAD4 patch with displaced interior nodes on [x0, x0+1]×[0, 1].
fn patch(x0: f64, hyp: Hypothesis) -> (Model, Vec<NodeId>, Vec<NodeId>) {
    let mut mb = MeshBuilder::new(2);
    let mut grid = vec![vec![NodeId(0); 4]; 4];
    let (mut boundary, mut interior) = (Vec::new(), Vec::new());
    for j in 0..4 {
        for i in 0..4 {
            let (mut x, mut y) = (i as f64 / 3., j as f64 / 3.);
            let inner = (1..3).contains(&i) && (1..3).contains(&j);
            if inner {
                x += 0.07 * ((i * 7 + j * 3) % 5) as f64 / 5. - 0.03;
                y += 0.06 * ((i * 3 + j * 5) % 4) as f64 / 4. - 0.02;
            }
            let n = mb.node(&format!("N{i}_{j}"), [x0 + x, y, 0.]);
            grid[j][i] = n;
            if inner {
                interior.push(n);
            } else {
                boundary.push(n);
            }
        }
    }
    let mut elements = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            let c = mb.cell(
                &format!("M{i}_{j}"),
                CellType::QUAD4,
                &[
                    grid[j][i],
                    grid[j][i + 1],
                    grid[j + 1][i + 1],
                    grid[j + 1][i],
                ],
            );
            elements.push(Element {
                cell: c,
                kind: ElementKind::Continuum {
                    hypothesis: hyp,
                    material: steel(),
                },
            });
        }
    }
    (Model::new(mb.mesh, elements).unwrap(), boundary, interior)
}

/// A homogeneous strain imposed through the boundary of a distorted patch:
/// interior nodes follow the linear field, and every Gauss point carries
/// the state the law gives for that strain history.
fn check_patch(hyp: Hypothesis, x0: f64, gradient: [[f64; 2]; 2], strain: [f64; 4]) {
    let (model, boundary, interior) = patch(x0, hyp);
    let scales = [0., 0.5, 1.0, 2.0, 3.0, 2.5];
    let field = |p: [f64; 3], s: f64| {
        [
            s * (gradient[0][0] * p[0] + gradient[0][1] * p[1]),
            s * (gradient[1][0] * p[0] + gradient[1][1] * p[1]),
        ]
    };
    let mut loads = Loads::new();
    for &n in &boundary {
        let p = model.mesh().coord(n);
        let u = field(p, 1.);
        for (c, comp) in [Comp::DX, Comp::DY].into_iter().enumerate() {
            loads.add(
                Load::Eliminated {
                    dof: Dof::new(n, comp),
                    value: u[c],
                },
                Multiplier::from_fn(move |t| Ok(scales[t.round() as usize])),
            );
        }
    }
    for law in [ecro_line(), traction()] {
        let mut snl = StaticNonLinear {
            instants: (0..scales.len()).map(|i| i as f64).collect(),
            convergence: TIGHT,
            behaviours: plastic_everywhere(&model, &law),
            ..Default::default()
        };
        let res = snl.solve(&model, &loads).unwrap();
        let mut state = PointState::default();
        let mut yielded = false;
        for (k, &s) in scales.iter().enumerate().skip(1) {
            let eps: Vec<f64> = strain.iter().map(|e| e * s).collect();
            state = integrate(&law, &steel(), hyp, &eps, &state, false, 0.0)
                .unwrap()
                .0;
            yielded |= state.plastic;
            let step = res.by_order(k).unwrap();
            for &n in &interior {
                let want = field(model.mesh().coord(n), s);
                for (c, comp) in [Comp::DX, Comp::DY].into_iter().enumerate() {
                    let got = step.displacement[idx(&model, n, comp)];
                    assert!(
                        (got - want[c]).abs() < 1e-10,
                        "{hyp:?} step {k}: {got} vs {}",
                        want[c]
                    );
                }
            }
            for (cv, vari) in step.stress.iter().zip(&step.internal_variables) {
                for g in 0..cv.points.len() {
                    for (c, name) in ["SIXX", "SIYY", "SIZZ", "SIXY"].iter().enumerate() {
                        let got = cv.get(g, name).unwrap();
                        assert!(
                            (got - state.stress[c]).abs() < 1e-7 * SY,
                            "{hyp:?} step {k} {name}: {got} vs {}",
                            state.stress[c]
                        );
                    }
                    assert!((vari.get(g, "V1").unwrap() - state.p).abs() < 1e-12);
                }
            }
        }
        assert!(yielded, "{hyp:?}: the patch should yield");
        assert!(state.p > 0.);
    }
}

#[test]
fn plane_strain_patch_carries_the_homogeneous_plastic_state() {
    // u = G x: εxx = 4e-3, εyy = −1e-3, γxy = 3e-3 at scale 1 (2 yield
    // strains), εzz = 0.
    let g = [[4e-3, 2e-3], [1e-3, -1e-3]];
    check_patch(Hypothesis::PlaneStrain, 0., g, [4e-3, -1e-3, 0., 3e-3]);
}

#[test]
fn axisymmetric_patch_carries_the_homogeneous_plastic_state() {
    // u_r = a r, u_z = b z: ε_rr = ε_θθ = a, ε_zz = b (x is r, y is z;
    // the third component is the hoop strain).
    let (a, b) = (-1.5e-3, 3e-3);
    check_patch(
        Hypothesis::Axisymmetric,
        1.,
        [[a, 0.], [0., b]],
        [a, b, a, 0.],
    );
}

/// A plane-strain block clamped at its base and pushed sideways and down at
/// its top by forces: a non-uniform plastic zone.
fn shear_block(newton: NewtonOptions, rela: f64, iter_glob_maxi: usize) -> NonLinearResult {
    shear_block_at(
        &[0., 0.5, 1.0, 1.25],
        newton,
        rela,
        iter_glob_maxi,
        Some(Subdivision::default()),
    )
    .unwrap()
}

fn shear_block_at(
    instants: &[f64],
    newton: NewtonOptions,
    rela: f64,
    iter_glob_maxi: usize,
    subdivision: Option<Subdivision>,
) -> Result<NonLinearResult, FemError> {
    let (nx, ny) = (6, 4);
    let mut mb = MeshBuilder::new(2);
    let mut grid = vec![vec![NodeId(0); nx + 1]; ny + 1];
    for j in 0..=ny {
        for i in 0..=nx {
            grid[j][i] = mb.node(
                &format!("N{i}_{j}"),
                [i as f64 / nx as f64 * 2., j as f64 / ny as f64, 0.],
            );
        }
    }
    let mut elements = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let c = mb.cell(
                &format!("M{i}_{j}"),
                CellType::QUAD4,
                &[
                    grid[j][i],
                    grid[j][i + 1],
                    grid[j + 1][i + 1],
                    grid[j + 1][i],
                ],
            );
            elements.push(Element {
                cell: c,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material: steel(),
                },
            });
        }
    }
    let model = Model::new(mb.mesh, elements).unwrap();
    let mut loads = Loads::new();
    for &n in &grid[0] {
        for comp in [Comp::DX, Comp::DY] {
            loads.push(Load::Eliminated {
                dof: Dof::new(n, comp),
                value: 0.,
            });
        }
    }
    // The elastic limit of the base is reached near 2·SY/√3 × 2 ≈ 460 in
    // shear; load up to ~1.5 times that, then some more.
    for &n in &grid[ny] {
        for (comp, f) in [(Comp::DX, 60.), (Comp::DY, -40.)] {
            loads.add(
                Load::NodalForce {
                    dof: Dof::new(n, comp),
                    value: f,
                },
                Multiplier::from_fn(Ok),
            );
        }
    }
    let mut snl = StaticNonLinear {
        instants: instants.to_vec(),
        newton,
        convergence: Convergence {
            resi_glob_rela: Some(rela),
            resi_glob_maxi: None,
            iter_glob_maxi,
            at_least_one: false,
        },
        behaviours: plastic_everywhere(&model, &ecro_line()),
        subdivision,
        ..Default::default()
    };
    snl.solve(&model, &loads)
}

#[test]
fn a_failed_plastic_increment_is_cut_into_four() {
    let newton = NewtonOptions::default();
    // One big increment with 5 residual checks allowed: Newton fails…
    let err = shear_block_at(&[0., 1.25], newton, 1e-8, 5, None)
        .map(|_| ())
        .unwrap_err();
    assert!(matches!(err, FemError::NoConvergence { .. }), "{err}");
    // …and succeeds cut in pieces (the harder quarters cut again), as
    // the four quarter instants given explicitly (cut the same way).
    let sd = Some(Subdivision::default());
    let cut = shear_block_at(&[0., 1.25], newton, 1e-8, 5, sd).unwrap();
    let quarters = [0., 0.3125, 0.625, 0.9375, 1.25];
    let listed = shear_block_at(&quarters, newton, 1e-8, 5, sd).unwrap();
    // Every converged piece is a step (code_aster archives the pieces it
    // inserts in its list of instants): the same instants either way,
    // the asked quarters among them.
    let times = |r: &NonLinearResult| r.steps.iter().map(|s| s.time).collect::<Vec<_>>();
    assert_eq!(times(&cut), times(&listed));
    assert!(cut.steps.len() > quarters.len(), "{:?}", times(&cut));
    for q in quarters {
        assert!(times(&cut).contains(&q), "{q}");
    }
    let (a, b) = (cut.last().unwrap(), listed.last().unwrap());
    assert_eq!(a.time, 1.25);
    let umax = b.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (x, y) in a.displacement.iter().zip(&b.displacement) {
        assert!((x - y).abs() < 1e-9 * umax, "{x} vs {y}");
    }
    for (p, q) in a.internal_variables.iter().zip(&b.internal_variables) {
        assert_eq!(p.points.len(), q.points.len());
        for (x, y) in p.points.iter().zip(&q.points) {
            assert!((x[0] - y[0]).abs() < 1e-12, "{x:?} vs {y:?}");
        }
    }
}

#[test]
fn newton_with_the_consistent_tangent_converges_quadratically() {
    let tangent = shear_block(
        NewtonOptions {
            prediction: Prediction::Elastique,
            ..NewtonOptions::default()
        },
        1e-12,
        20,
    );
    let last = tangent.last().unwrap();
    let plastic_points = last
        .internal_variables
        .iter()
        .flat_map(|cv| cv.points.iter())
        .filter(|p| p[0] > 0.)
        .count();
    assert!(
        plastic_points > 4,
        "a plastic zone forms ({plastic_points} points)"
    );
    // Each step: once the residual is small, it is (about) squared at each
    // iteration — log r_{k+1} / log r_k ≥ 1.7 — until round-off (1e-12).
    let mut observed = 0;
    for step in &tangent.steps[2..] {
        let r = &step.residual_history;
        assert!(r.len() <= 8, "{r:?}");
        for w in r.windows(2) {
            if w[0] < 1e-2 && w[1] > 1e-12 {
                let rate = w[1].ln() / w[0].ln();
                assert!(rate > 1.7, "convergence rate {rate} in {r:?}");
                observed += 1;
            }
        }
    }
    assert!(observed >= 1, "no iteration in the quadratic range");
    // The elastic matrix converges linearly (slowly: the hardening slope
    // is 1 % of E) to the same answer, in many more iterations.
    let elastic = shear_block(
        NewtonOptions {
            matrix: MatrixKind::Elastique,
            ..NewtonOptions::default()
        },
        1e-7,
        2000,
    );
    let (a, b) = (last, elastic.last().unwrap());
    assert!(
        b.iterations > 2 * a.iterations,
        "{} vs {}",
        b.iterations,
        a.iterations
    );
    let umax = a.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (x, y) in a.displacement.iter().zip(&b.displacement) {
        assert!((x - y).abs() < 1e-4 * umax, "{x} vs {y}");
    }
}

#[test]
fn a_plastic_initial_state_without_internal_variables_is_refused() {
    let (model, _, _) = patch(0., Hypothesis::PlaneStrain);
    let mut snl = StaticNonLinear {
        instants: vec![0., 1.],
        initial: Some(InitialState {
            time: Some(0.),
            displacement: vec![1e-3; model.dofs().len()],
            ..Default::default()
        }),
        behaviours: plastic_everywhere(&model, &ecro_line()),
        ..Default::default()
    };
    let err = snl.solve(&model, &Loads::new()).unwrap_err().to_string();
    assert!(
        err.contains("ETAT_INIT") && err.contains("internal variables"),
        "{err}"
    );
}

/// The shear block of [`shear_block`] resting on unilateral supports
/// (u_y ≥ 0 at every base node, one node pinned in x) instead of clamped:
/// the pushed side lifts off while the other yields.
fn block_on_supports(newton: NewtonOptions) -> (Model, NonLinearResult) {
    let (nx, ny) = (6, 4);
    let mut mb = MeshBuilder::new(2);
    let mut grid = vec![vec![NodeId(0); nx + 1]; ny + 1];
    for j in 0..=ny {
        for i in 0..=nx {
            grid[j][i] = mb.node(
                &format!("N{i}_{j}"),
                [i as f64 / nx as f64 * 2., j as f64 / ny as f64, 0.],
            );
        }
    }
    let mut elements = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let c = mb.cell(
                &format!("M{i}_{j}"),
                CellType::QUAD4,
                &[
                    grid[j][i],
                    grid[j][i + 1],
                    grid[j + 1][i + 1],
                    grid[j + 1][i],
                ],
            );
            elements.push(Element {
                cell: c,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material: steel(),
                },
            });
        }
    }
    let model = Model::new(mb.mesh, elements).unwrap();
    let mut loads = Loads::new();
    loads.push(Load::Eliminated {
        dof: Dof::new(grid[0][nx], Comp::DX),
        value: 0.,
    });
    // Pressed down on the right of the top, pushed sideways at the top
    // left: the left end of the base lifts, the right end is crushed.
    for &n in &grid[ny][4..] {
        loads.add(
            Load::NodalForce {
                dof: Dof::new(n, Comp::DY),
                value: -140.,
            },
            Multiplier::from_fn(Ok),
        );
    }
    loads.add(
        Load::NodalForce {
            dof: Dof::new(grid[ny][0], Comp::DX),
            value: 120.,
        },
        Multiplier::from_fn(Ok),
    );
    let rows = grid[0]
        .iter()
        .enumerate()
        .map(|(k, &n)| InequalityRow::new(vec![(Dof::new(n, Comp::DY), -1.)], 0., k))
        .collect();
    let mut snl = StaticNonLinear {
        instants: vec![0., 0.5, 1.0],
        newton,
        convergence: TIGHT,
        sources: vec![Box::new(FixedRows {
            name: "base".into(),
            rows,
            method: UnilateralMethod::ActiveSet,
        })],
        behaviours: plastic_everywhere(&model, &ecro_line()),
        ..Default::default()
    };
    let res = snl.solve(&model, &loads).unwrap();
    (model, res)
}

#[test]
fn plasticity_and_unilateral_supports_settle_together() {
    let (_, res) = block_on_supports(NewtonOptions::default());
    let last = res.last().unwrap();
    let out = &last.unilateral[0];
    // Vertical equilibrium: the supports carry the 3 × 140 pressing down.
    let total: f64 = out.iter().map(|o| o.multiplier).sum();
    assert!((total - 420.).abs() < 1e-8 * 420., "{total}");
    // Complementarity: pressed rows are closed, open rows carry nothing.
    for o in out {
        assert!(o.multiplier >= -1e-9, "{o:?}");
        if o.active {
            assert!(o.violation.abs() < 1e-12, "{o:?}");
        } else {
            assert!(o.violation < 0. && o.multiplier == 0., "{o:?}");
        }
    }
    assert!(out.iter().any(|o| !o.active), "part of the base lifts off");
    let plastic = last
        .internal_variables
        .iter()
        .flat_map(|cv| cv.points.iter())
        .filter(|p| p[0] > 0.)
        .count();
    assert!(plastic > 0, "the crushed corner yields");
    // The converged answer does not depend on the Newton path.
    for newton in [
        NewtonOptions {
            prediction: Prediction::Elastique,
            ..NewtonOptions::default()
        },
        NewtonOptions {
            reac_iter: 2,
            ..NewtonOptions::default()
        },
    ] {
        let (_, other) = block_on_supports(newton);
        let b = other.last().unwrap();
        let umax = last.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (x, y) in last.displacement.iter().zip(&b.displacement) {
            assert!((x - y).abs() < 1e-9 * umax, "{newton:?}: {x} vs {y}");
        }
    }
}
