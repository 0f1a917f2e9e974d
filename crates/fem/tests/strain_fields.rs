//! CALC_CHAMP's finite-strain measures (`EPSG_ELGA`, `EPSL_ELGA`) on
//! homogeneous deformations u = (F − I) X, against the measures computed
//! here independently from F: E = ½(FᵀF − I), ε = ½ ln FᵀF (through the
//! eigenvectors of FᵀF), at every Gauss point of QUAD4, QUAD8, TRIA3,
//! HEXA8 and TETRA10 cells, in D_PLAN, AXIS and 3D; in C_PLAN EPZZ is
//! code_aster's −ν/(1 − ν)(EPXX + EPYY).

mod common;

use aster_fem::strain::{finite_strain_elga_on, StrainMeasure};
use aster_fem::*;
use aster_mesh::{CellType, NodeId};
use common::MeshBuilder;
use nalgebra::{Matrix3, SymmetricEigen};

fn material() -> Elastic {
    Elastic::new(1000.0, 0.3).unwrap()
}

/// One cell of type `ty` on the given nodes, as a model of `hyp`, and the
/// DOF vector of u = (F − I) X.
fn homogeneous(
    hyp: Hypothesis,
    ty: CellType,
    coords: &[[f64; 3]],
    f: &Matrix3<f64>,
) -> (Model, Vec<f64>) {
    let dim = hyp.dim();
    let mut mb = MeshBuilder::new(dim as u8);
    let nodes: Vec<NodeId> = coords
        .iter()
        .enumerate()
        .map(|(i, x)| mb.node(&format!("N{}", i + 1), *x))
        .collect();
    let cell = mb.cell("M1", ty, &nodes);
    let model = Model::new(
        mb.mesh,
        vec![Element {
            cell,
            kind: ElementKind::Continuum {
                hypothesis: hyp,
                material: material(),
            },
        }],
    )
    .unwrap();
    let comps = [Comp::DX, Comp::DY, Comp::DZ];
    let mut u = vec![0.0; model.dofs().len()];
    for (n, x) in nodes.iter().zip(coords) {
        for i in 0..dim {
            let v: f64 = (0..dim)
                .map(|j| (f[(i, j)] - if i == j { 1.0 } else { 0.0 }) * x[j])
                .sum();
            u[model.dofs().index(Dof::new(*n, comps[i])).unwrap()] = v;
        }
    }
    (model, u)
}

/// The expected tensor: Green–Lagrange or logarithmic, from F.
fn expected(f: &Matrix3<f64>, measure: StrainMeasure) -> Matrix3<f64> {
    let c = f.transpose() * f;
    match measure {
        StrainMeasure::GreenLagrange => 0.5 * (c - Matrix3::identity()),
        StrainMeasure::Logarithmic => {
            let e = SymmetricEigen::new(c);
            let mut out = Matrix3::zeros();
            for k in 0..3 {
                let g = e.eigenvectors.column(k);
                out += 0.5 * e.eigenvalues[k].ln() * g * g.transpose();
            }
            out
        }
    }
}

fn check(
    hyp: Hypothesis,
    ty: CellType,
    coords: &[[f64; 3]],
    f: &Matrix3<f64>,
    npg: usize,
) -> usize {
    let (model, u) = homogeneous(hyp, ty, coords, f);
    let mut checked = 0;
    for measure in [StrainMeasure::GreenLagrange, StrainMeasure::Logarithmic] {
        let cells = finite_strain_elga_on(&model, &u, measure, false, |_| true).unwrap();
        assert_eq!(cells.len(), 1);
        let cv = &cells[0];
        assert_eq!(cv.points.len(), npg, "{ty:?} {measure:?}");
        let mut want = expected(f, measure);
        if hyp == Hypothesis::PlaneStress {
            // code_aster's epsvmc: EPZZ = −ν/(1 − ν)(EPXX + EPYY).
            want[(2, 2)] = -0.3 / 0.7 * (want[(0, 0)] + want[(1, 1)]);
        }
        let pairs: &[(usize, usize, &str)] = &[
            (0, 0, "EPXX"),
            (1, 1, "EPYY"),
            (2, 2, "EPZZ"),
            (0, 1, "EPXY"),
            (0, 2, "EPXZ"),
            (1, 2, "EPYZ"),
        ];
        let n = if hyp == Hypothesis::Solid3D { 6 } else { 4 };
        assert_eq!(cv.names, pairs[..n].iter().map(|p| p.2).collect::<Vec<_>>());
        for p in 0..npg {
            for &(i, j, name) in &pairs[..n] {
                let got = cv.get(p, name).unwrap();
                let w = want[(i, j)];
                assert!(
                    (got - w).abs() <= 1e-12 * (1.0 + w.abs()),
                    "{hyp:?} {ty:?} {measure:?} point {p} {name}: {got} against {w}"
                );
                checked += 1;
            }
        }
    }
    checked
}

const QUAD4: [[f64; 3]; 4] = [
    [1.0, 0.0, 0.0],
    [2.0, 0.0, 0.0],
    [2.2, 1.0, 0.0],
    [0.9, 1.3, 0.0],
];

#[test]
fn plane_strain_stretch_and_shear() {
    // λ = 2 along x, simple shear γ = 0.7 and a rotation of the whole.
    let (a, gamma) = (0.4f64, 0.7);
    let rot = Matrix3::new(a.cos(), -a.sin(), 0.0, a.sin(), a.cos(), 0.0, 0.0, 0.0, 1.0);
    let f = rot * Matrix3::new(2.0, gamma, 0.0, 0.0, 0.8, 0.0, 0.0, 0.0, 1.0);
    assert_eq!(
        check(Hypothesis::PlaneStrain, CellType::QUAD4, &QUAD4, &f, 4),
        32
    );
    let tria = [QUAD4[0], QUAD4[1], QUAD4[3]];
    assert_eq!(
        check(Hypothesis::PlaneStrain, CellType::TRIA3, &tria, &f, 1),
        8
    );
    let mut quad8 = QUAD4.to_vec();
    for k in 0..4 {
        let (p, q) = (QUAD4[k], QUAD4[(k + 1) % 4]);
        quad8.push([0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.0]);
    }
    assert_eq!(
        check(Hypothesis::PlaneStrain, CellType::QUAD8, &quad8, &f, 9),
        72
    );
}

#[test]
fn axisymmetric_hoop_strain() {
    // u_r = 0.5 r, u_z = −0.2 z + 0.3 r: F₃₃ = 1 + u_r/r = 1.5.
    let f = Matrix3::new(1.5, 0.0, 0.0, 0.3, 0.8, 0.0, 0.0, 0.0, 1.5);
    assert_eq!(
        check(Hypothesis::Axisymmetric, CellType::QUAD4, &QUAD4, &f, 4),
        32
    );
}

#[test]
fn solid_stretch_shear_rotation() {
    let hexa: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            let (x, y, z) = (
                [0, 1, 1, 0][k % 4] as f64,
                [0, 0, 1, 1][k % 4] as f64,
                (k / 4) as f64,
            );
            [x + 0.1 * y * z, y + 0.05 * x, z * (1.0 + 0.2 * x)]
        })
        .collect();
    let (a, b) = (0.3f64, -0.5f64);
    let rz = Matrix3::new(a.cos(), -a.sin(), 0.0, a.sin(), a.cos(), 0.0, 0.0, 0.0, 1.0);
    let rx = Matrix3::new(1.0, 0.0, 0.0, 0.0, b.cos(), -b.sin(), 0.0, b.sin(), b.cos());
    let f = rz * rx * Matrix3::new(2.0, 0.4, 0.1, 0.0, 1.3, -0.3, 0.2, 0.0, 0.6);
    assert_eq!(
        check(Hypothesis::Solid3D, CellType::HEXA8, &hexa, &f, 8),
        96
    );
    let tet = [
        [0.0, 0.0, 0.0],
        [1.0, 0.1, 0.0],
        [0.2, 1.0, 0.1],
        [0.1, 0.2, 1.2],
    ];
    let mut tet10 = tet.to_vec();
    for (p, q) in [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)] {
        tet10.push([
            0.5 * (tet[p][0] + tet[q][0]),
            0.5 * (tet[p][1] + tet[q][1]),
            0.5 * (tet[p][2] + tet[q][2]),
        ]);
    }
    assert_eq!(
        check(Hypothesis::Solid3D, CellType::TETRA10, &tet10, &f, 5),
        60
    );
}

#[test]
fn plane_stress_epzz_from_the_material() {
    let f = Matrix3::new(1.6, 0.5, 0.0, -0.2, 0.9, 0.0, 0.0, 0.0, 1.0);
    assert_eq!(
        check(Hypothesis::PlaneStress, CellType::QUAD4, &QUAD4, &f, 4),
        32
    );
}

#[test]
fn refusals_name_the_cell() {
    let f = Matrix3::new(1.2, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
    let (model, u) = homogeneous(Hypothesis::PlaneStress, CellType::QUAD4, &QUAD4, &f);
    let err = finite_strain_elga_on(&model, &u, StrainMeasure::Logarithmic, true, |_| true)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("C_PLAN") && err.contains("thermal") && err.contains("M1"),
        "{err}"
    );
    // A cell turned inside out: F with a zero stretch has no log strain.
    let f = Matrix3::new(0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
    let (model, u) = homogeneous(Hypothesis::PlaneStrain, CellType::QUAD4, &QUAD4, &f);
    let err = finite_strain_elga_on(&model, &u, StrainMeasure::Logarithmic, false, |_| true)
        .unwrap_err()
        .to_string();
    assert!(err.contains("crushed") && err.contains("M1"), "{err}");
    // Green–Lagrange is defined there: E_xx = −½.
    let cells =
        finite_strain_elga_on(&model, &u, StrainMeasure::GreenLagrange, false, |_| true).unwrap();
    assert!((cells[0].get(0, "EPXX").unwrap() + 0.5).abs() < 1e-14);
}
