//! The tangent of code_aster 17's penalised mortar contact (DEFI_CONT,
//! `ALGO_CONT='PENALISATION'`, `peMatr_ct_pr`: the penalty on the full
//! derivative of the gap, the slave normal turning, the master point
//! sliding) is the derivative of its residual: checked by central finite
//! differences in 3D on a small tilted slave face (QUAD4, then QUAD8 and
//! QUAD9 with their middle nodes moved off the plane) whose whole area is
//! paired with one larger master face (so the integration polygon does not
//! move), and in 2D (D_PLAN and AXIS) on a tilted slave segment (SEG2, then
//! SEG3 with its middle node moved off the line) over a longer master,
//! every point interpenetrating.

use std::path::Path;

use aster_contact::mortar_lagrangian::MortarZoneDef;
use aster_contact::mortar_penalty::MortarPenalty;
use aster_fem::{Comp, Contribution, DofNumbering, ForceSource, State, Unknown};
use aster_mesh::{CellId, CentreNodes, Mesh};

/// A lower block whose top face z = 0 (MAIT) spans [-2, 3]², and an upper
/// block whose bottom face (ESCL), over [0, 1]², dips slightly below it
/// and is tilted.
const MESH: &str = "COOR_3D
N1 -2.0 -2.0 -1.0
N2 3.0 -2.0 -1.0
N3 3.0 3.0 -1.0
N4 -2.0 3.0 -1.0
N5 -2.0 -2.0 0.0
N6 3.0 -2.0 0.0
N7 3.0 3.0 0.0
N8 -2.0 3.0 0.0
N9 0.0 0.0 -0.03
N10 1.0 0.1 -0.01
N11 1.1 1.0 -0.02
N12 0.05 0.9 -0.04
N13 0.0 0.0 1.0
N14 1.0 0.0 1.0
N15 1.0 1.0 1.0
N16 0.0 1.0 1.0
FINSF
HEXA8
M1 N1 N2 N3 N4 N5 N6 N7 N8
M2 N9 N10 N11 N12 N13 N14 N15 N16
FINSF
QUAD4
M3 N5 N6 N7 N8
M4 N9 N12 N11 N10
FINSF
GROUP_MA NOM=MAIT
M3
FINSF
GROUP_MA NOM=ESCL
M4
FINSF
FIN
";

/// The forces and the dense tangent at `u`.
fn residual(
    m: &mut MortarPenalty,
    mesh: &Mesh,
    dofs: &DofNumbering,
    u: &[f64],
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let state = State {
        mesh,
        dofs,
        displacement: u,
        time: 1.0,
    };
    let c: Contribution = m.evaluate(&state, &[]).unwrap();
    let n = u.len();
    let mut r = vec![0.0; n];
    for &(i, f) in &c.forces {
        r[i] += f;
    }
    let mut t = vec![vec![0.0; n]; n];
    for &(a, b, v) in &c.tangent {
        let (Unknown::Dof(i), Unknown::Dof(j)) = (a, b) else {
            panic!("the penalised contact has no unknowns of its own");
        };
        t[i][j] += v;
    }
    (r, t)
}

fn check(mesh: Mesh, what: &str) {
    check_in(mesh, what, 3, false)
}

/// [`check`] in a model of dimension `dim` (2: DX, DY; `axis`: AXIS weights).
fn check_in(mesh: Mesh, what: &str, dim: usize, axis: bool) {
    let nodes = mesh.coords.len();
    let comps: &[Comp] = if dim == 3 {
        &[Comp::DX, Comp::DY, Comp::DZ]
    } else {
        &[Comp::DX, Comp::DY]
    };
    let dofs = DofNumbering::new(comps, &vec![true; nodes]);
    let mut zone = MortarZoneDef::new("MAIT", "ESCL");
    zone.coef_cont = 1e3;
    let mut m = MortarPenalty::new(&[zone], &mesh, axis, dim).unwrap();
    let n = dim * nodes;
    // Past the first pairing (CONTACT_INIT).
    m.after_iteration(
        &State {
            mesh: &mesh,
            dofs: &dofs,
            displacement: &vec![0.0; n],
            time: 0.0,
        },
        &mut [],
    )
    .unwrap();
    // A displacement that turns and shifts both faces a little.
    let u: Vec<f64> = (0..n)
        .map(|i| 0.002 * ((i * 7 % 5) as f64 - 2.0) + 0.0003 * (i % 11) as f64)
        .collect();
    let (r, t) = residual(&mut m, &mesh, &dofs, &u);
    assert!(m.penetration() > 0.0, "{what}: the faces interpenetrate");
    assert!(
        r.iter().any(|f| f.abs() > 1.0),
        "{what}: contact forces are there"
    );
    let h = 1e-7;
    let mut largest = 0.0f64;
    for j in 0..n {
        let (mut up, mut um) = (u.clone(), u.clone());
        up[j] += h;
        um[j] -= h;
        let (rp, _) = residual(&mut m, &mesh, &dofs, &up);
        let (rm, _) = residual(&mut m, &mesh, &dofs, &um);
        for i in 0..n {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            largest = largest.max(fd.abs());
            let scale = 1.0 + fd.abs().max(t[i][j].abs());
            assert!(
                (fd - t[i][j]).abs() < 1e-5 * scale,
                "{what}: ∂R{i}/∂U{j}: tangent {} against {fd}",
                t[i][j]
            );
        }
    }
    assert!(largest > 10.0, "{what}: the tangent is not trivial");
}

fn base() -> Mesh {
    aster_mesh::parse_mail(MESH, Path::new("t.mail")).unwrap()
}

/// Moves every node that is not a corner of the slave face's cell off its
/// place by a small smooth amount (the quadratic faces become curved).
fn bend(mesh: &mut Mesh) {
    for (k, p) in mesh.coords.iter_mut().enumerate().skip(16) {
        let s = (k as f64 * 1.3).sin();
        p[0] += 0.01 * s;
        p[1] -= 0.008 * s;
        p[2] += 0.012 * (k as f64 * 0.7).cos();
    }
}

#[test]
fn the_tangent_on_quad4_faces_is_the_derivative_of_the_residual() {
    check(base(), "QUAD4");
}

#[test]
fn the_tangent_on_quad8_faces_is_the_derivative_of_the_residual() {
    let mut mesh = base();
    let all: Vec<CellId> = (0..mesh.cells.len() as u32).map(CellId).collect();
    mesh.line_to_quad(&all);
    bend(&mut mesh);
    check(mesh, "QUAD8");
}

#[test]
fn the_tangent_on_quad9_faces_is_the_derivative_of_the_residual() {
    let mut mesh = base();
    let all: Vec<CellId> = (0..mesh.cells.len() as u32).map(CellId).collect();
    mesh.line_to_quad(&all);
    mesh.add_centre_nodes(&all, CentreNodes::Hexa20To27);
    bend(&mut mesh);
    check(mesh, "QUAD9");
}

/// A lower plate whose top edge y = 0 (MAIT) spans [1, 6] and an upper one
/// whose bottom edge (ESCL), over [2, 3], dips slightly below it and is
/// tilted (x > 0: also an AXIS section).
const MESH_2D: &str = "COOR_2D
N1 1.0 -1.0
N2 6.0 -1.0
N3 6.0 0.0
N4 1.0 0.0
N5 2.0 -0.03
N6 3.0 -0.01
N7 3.1 1.0
N8 2.05 0.9
FINSF
QUAD4
M1 N1 N2 N3 N4
M2 N5 N6 N7 N8
FINSF
SEG2
M3 N3 N4
M4 N5 N6
FINSF
GROUP_MA NOM=MAIT
M3
FINSF
GROUP_MA NOM=ESCL
M4
FINSF
FIN
";

fn base_2d() -> Mesh {
    aster_mesh::parse_mail(MESH_2D, Path::new("t.mail")).unwrap()
}

/// The 2D mesh made quadratic, every middle node moved off its edge.
fn quadratic_2d() -> Mesh {
    let mut mesh = base_2d();
    let all: Vec<CellId> = (0..mesh.cells.len() as u32).map(CellId).collect();
    mesh.line_to_quad(&all);
    for (k, p) in mesh.coords.iter_mut().enumerate().skip(8) {
        p[0] += 0.01 * (k as f64 * 1.3).sin();
        p[1] += 0.012 * (k as f64 * 0.7).cos();
    }
    mesh
}

#[test]
fn the_tangent_on_seg2_edges_is_the_derivative_of_the_residual() {
    check_in(base_2d(), "SEG2", 2, false);
    check_in(base_2d(), "SEG2 AXIS", 2, true);
}

#[test]
fn the_tangent_on_seg3_edges_is_the_derivative_of_the_residual() {
    check_in(quadratic_2d(), "SEG3", 2, false);
    check_in(quadratic_2d(), "SEG3 AXIS", 2, true);
}
