//! The residual error estimator (`ERME_ELEM`, code_aster's te0377/te0375):
//! zero to round-off on a stress field the elements represent exactly and
//! in equilibrium with the loads (a patch test), positive and of order h
//! (energy norm, linear cells) on a real finite-element solution.

mod common;

use aster_fem::error_estimate::{residual_estimate, EstimatorInput};
use aster_fem::*;
use aster_mesh::{CellId, CellType, NodeId};
use common::MeshBuilder;

const E: f64 = 2.0e5;
const NU: f64 = 0.3;

/// An affine stress field σ(x) = S0 + x S1 + y S2 (+ z S3), components
/// SIXX SIYY SIZZ SIXY SIXZ SIYZ.
struct Affine([[f64; 6]; 4]);

impl Affine {
    fn at(&self, x: [f64; 3]) -> [f64; 6] {
        std::array::from_fn(|k| {
            self.0[0][k] + x[0] * self.0[1][k] + x[1] * self.0[2][k] + x[2] * self.0[3][k]
        })
    }
    /// The body force in equilibrium with it: f = −div σ.
    fn body_force(&self) -> [f64; 3] {
        let d = |c: usize, dir: usize| self.0[dir + 1][c];
        [
            -(d(0, 0) + d(3, 1) + d(4, 2)),
            -(d(3, 0) + d(1, 1) + d(5, 2)),
            -(d(4, 0) + d(5, 1) + d(2, 2)),
        ]
    }
}

/// A distorted 3×3 patch of QUAD4 (or TRIA3 pairs) on [0, 2]², with SEG2
/// skin cells on the right edge x = 2 (`right`).
fn patch_2d(ty: CellType) -> (Model, Vec<CellId>, Vec<CellId>) {
    let mut mb = MeshBuilder::new(2);
    let n = 3;
    let mut ids = vec![vec![NodeId(0); n + 1]; n + 1];
    for (j, row) in ids.iter_mut().enumerate() {
        for (i, id) in row.iter_mut().enumerate() {
            let mut x = 2.0 * i as f64 / n as f64;
            let mut y = 2.0 * j as f64 / n as f64;
            if i > 0 && i < n && j > 0 && j < n {
                x += 0.13 * (i as f64 * 1.7 + j as f64).sin();
                y -= 0.11 * (i as f64 + 2.3 * j as f64).cos();
            }
            *id = mb.node(&format!("N{i}_{j}"), [x, y, 0.0]);
        }
    }
    let mut cells = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (ids[j][i], ids[j][i + 1], ids[j + 1][i + 1], ids[j + 1][i]);
            if ty == CellType::QUAD4 {
                cells.push(mb.cell(&format!("M{i}_{j}"), ty, &[a, b, c, d]));
            } else {
                cells.push(mb.cell(&format!("M{i}_{j}a"), ty, &[a, b, c]));
                cells.push(mb.cell(&format!("M{i}_{j}b"), ty, &[a, c, d]));
            }
        }
    }
    let right: Vec<CellId> = (0..n)
        .map(|j| {
            mb.cell(
                &format!("R{j}"),
                CellType::SEG2,
                &[ids[j][n], ids[j + 1][n]],
            )
        })
        .collect();
    let mat = Elastic::new(E, NU).unwrap();
    let mut elements: Vec<Element> = cells
        .iter()
        .map(|&cell| Element {
            cell,
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::PlaneStrain,
                material: mat,
            },
        })
        .collect();
    elements.extend(right.iter().map(|&cell| Element {
        cell,
        kind: ElementKind::Boundary,
    }));
    (Model::new(mb.mesh, elements).unwrap(), cells, right)
}

/// The estimator's input for a stress field given at the nodes.
fn input_of(model: &Model, cells: &[CellId], field: &Affine) -> EstimatorInput {
    let mut input = EstimatorInput::default();
    for &c in cells {
        let nodes = &model.mesh().cell(c).nodes;
        input.stress.insert(
            c,
            nodes
                .iter()
                .map(|&n| field.at(model.mesh().coord(n)))
                .collect(),
        );
        input.volume_force.insert(c, field.body_force());
    }
    input
}

/// A uniform stress with the traction σ·n it exerts on the loaded right
/// edge, and an affine one with its body force (no skin load): every
/// term of every cell vanishes (relative to the stress norm), on QUAD4
/// and TRIA3 patches.
#[test]
fn an_exact_equilibrated_field_has_no_error() {
    for ty in [CellType::QUAD4, CellType::TRIA3] {
        let (model, cells, right) = patch_2d(ty);
        let uniform = Affine([
            [100.0, -40.0, 18.0, 25.0, 0.0, 0.0],
            [0.0; 6],
            [0.0; 6],
            [0.0; 6],
        ]);
        let mut input = input_of(&model, &cells, &uniform);
        for &r in &right {
            // n = (1, 0): σ·n = (σxx, σxy).
            input.skin_forces.insert(r, [100.0, 25.0, 0.0]);
        }
        let affine = Affine([
            [100.0, -40.0, 18.0, 25.0, 0.0, 0.0],
            [7.0, 3.0, -2.0, 5.0, 0.0, 0.0],
            [-4.0, 6.0, 1.0, -3.0, 0.0, 0.0],
            [0.0; 6],
        ]);
        let affine_input = input_of(&model, &cells, &affine);
        for (name, input) in [("uniform", input), ("affine", affine_input)] {
            let out = residual_estimate(&model, &input).unwrap();
            assert_eq!(out.len(), cells.len());
            for (cell, v) in out {
                // SIGCAL > 0, every estimate and term ~ round-off.
                assert!(v[2] > 10.0, "{ty:?} {name} {cell:?}: {v:?}");
                for k in [0, 3, 5, 7] {
                    assert!(v[k] < 1e-12 * v[2], "{ty:?} {name} {cell:?}: {v:?}");
                }
                assert!(v[9] > 0.5 && v[9] < 1.5, "{v:?}");
            }
        }
    }
}

/// The same uniform stress without its traction on the loaded edge: the
/// boundary term (TERMNO) of the right column of cells is |σ·n|·√(h_F …),
/// the others vanish; its value follows te0377's formula by hand.
#[test]
fn a_missing_traction_is_a_boundary_residual() {
    let (model, cells, right) = patch_2d(CellType::QUAD4);
    let uniform = Affine([
        [100.0, -40.0, 18.0, 25.0, 0.0, 0.0],
        [0.0; 6],
        [0.0; 6],
        [0.0; 6],
    ]);
    let mut input = input_of(&model, &cells, &uniform);
    // A load of (0, 0) counts as none (code_aster's 1e-15 test): give a
    // traction that misses σ·n by (−100, −25) + (1, 0)·… = (1, 0) − σ·n.
    for &r in &right {
        input.skin_forces.insert(r, [1.0, 0.0, 0.0]);
    }
    let out = residual_estimate(&model, &input).unwrap();
    let mesh = model.mesh();
    for (cell, v) in out {
        let on_right = mesh.cell(cell).nodes.iter().any(|&n| {
            let x = mesh.coord(n);
            (x[0] - 2.0).abs() < 1e-12
        });
        if !on_right {
            assert!(v[5] == 0.0, "{v:?}");
            continue;
        }
        // The edge on x = 2 of this cell (straight, vertical, length L):
        // ∫ |g − σ·n|² = L |(1 − 100, −25)|² (Newton–Cotes exact on a
        // constant), times h_F = L; TERMNO = √(L² |…|²) / √(24 E/(1 − ν)).
        let xs: Vec<[f64; 3]> = mesh
            .cell(cell)
            .nodes
            .iter()
            .map(|&n| mesh.coord(n))
            .collect();
        let ys: Vec<f64> = xs
            .iter()
            .filter(|x| (x[0] - 2.0).abs() < 1e-12)
            .map(|x| x[1])
            .collect();
        let l = (ys[0] - ys[1]).abs();
        let jump2 = 99.0_f64.powi(2) + 25.0_f64.powi(2);
        let expected = (l * l * jump2).sqrt() / (24.0 * E / (1.0 - NU)).sqrt();
        assert!(
            (v[5] - expected).abs() < 1e-12 * expected,
            "{cell:?}: {} vs {expected}",
            v[5]
        );
        assert!(v[3] < 1e-12 * v[2] && v[7] < 1e-12 * v[2], "{v:?}");
    }
}

/// The global estimate η = √(Σ ERREST²) of n×n QUAD4 plane-strain grids
/// of the unit square under its weight (rollers on x = 0 and y = 0: a
/// smooth solution, linear stresses, a displacement quadratic in y that
/// QUAD4 does not hold): positive, and halved when h is (order h in the
/// energy norm).
#[test]
fn the_estimate_converges_at_order_h() {
    let eta = |n: usize| {
        let mut mb = MeshBuilder::new(2);
        let mut ids = vec![vec![NodeId(0); n + 1]; n + 1];
        for (j, row) in ids.iter_mut().enumerate() {
            for (i, slot) in row.iter_mut().enumerate() {
                *slot = mb.node(
                    &format!("N{i}_{j}"),
                    [i as f64 / n as f64, j as f64 / n as f64, 0.0],
                );
            }
        }
        let mat = Elastic::new(E, NU).unwrap();
        let mut elements = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let c = mb.cell(
                    &format!("M{i}_{j}"),
                    CellType::QUAD4,
                    &[ids[j][i], ids[j][i + 1], ids[j + 1][i + 1], ids[j + 1][i]],
                );
                elements.push(Element {
                    cell: c,
                    kind: ElementKind::Continuum {
                        hypothesis: Hypothesis::PlaneStrain,
                        material: mat,
                    },
                });
            }
        }
        let model = Model::new(mb.mesh, elements).unwrap();
        let mut loads = Loads::new();
        let f = [0.0, -7.8e-2, 0.0];
        for el in model.elements() {
            loads.push(Load::VolumeForce {
                cell: el.cell,
                force: f,
            });
        }
        for (k, row) in ids.iter().enumerate() {
            loads.push(Load::Eliminated {
                dof: Dof::new(row[0], Comp::DX),
                value: 0.0,
            });
            loads.push(Load::Eliminated {
                dof: Dof::new(ids[0][k], Comp::DY),
                value: 0.0,
            });
        }
        let step = &meca_statique(&model, &loads, &[]).unwrap().steps[0];
        let elno = post::elno(&model, &step.stress);
        let mut input = EstimatorInput::default();
        for cv in &elno {
            let get = |p: usize, name: &str| cv.get(p, name).unwrap_or(0.0);
            input.stress.insert(
                cv.cell,
                (0..cv.points.len())
                    .map(|p| {
                        [
                            get(p, "SIXX"),
                            get(p, "SIYY"),
                            get(p, "SIZZ"),
                            get(p, "SIXY"),
                            0.0,
                            0.0,
                        ]
                    })
                    .collect(),
            );
            input.volume_force.insert(cv.cell, f);
        }
        let out = residual_estimate(&model, &input).unwrap();
        out.iter().map(|(_, v)| v[0] * v[0]).sum::<f64>().sqrt()
    };
    let etas: Vec<f64> = [4, 8, 16].iter().map(|&n| eta(n)).collect();
    eprintln!("η for 4, 8, 16 cells a side: {etas:?}");
    assert!(etas[0] > 0.0);
    for w in etas.windows(2) {
        let ratio = w[0] / w[1];
        assert!((1.8..2.2).contains(&ratio), "{etas:?}");
    }
}
