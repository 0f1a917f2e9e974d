//! The tangent of code_aster 17's mortar Lagrangian contact on faces
//! (DEFI_CONT in 3D, `laMatr_ct_pr` with `elem_dime` = 3: the multiplier
//! terms, the slave normal turning (`dNs_du`), the master point sliding
//! along both of its parameters and the full derivative of the gap
//! (`dPi_du`)) is the derivative of its residual (`laVect_ct_pr`): checked
//! by central finite differences on a small tilted slave face (QUAD4, then
//! QUAD8 with its middle nodes moved off the plane) whose whole area is
//! paired with one larger master face (so the integration polygon does
//! not move), every point active, then every point inactive.

use std::path::Path;

use aster_contact::mortar_lagrangian::{MortarLagrangian, MortarZoneDef};
use aster_fem::{Comp, Contribution, DofNumbering, ForceSource, State, Unknown};
use aster_mesh::{CellId, Mesh};

/// A lower block whose top face z = 0 (MAIT) spans [-2, 3]², and an upper
/// block whose bottom face (ESCL), over [0, 1]², is tilted and dips
/// slightly below it.
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
N10 1.0 0.1 0.01
N11 1.1 1.0 -0.02
N12 0.05 0.9 0.04
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

/// The residual (forces on the displacement rows, then the own equations)
/// and the dense tangent at `u`, `own`.
fn residual(
    m: &mut MortarLagrangian,
    mesh: &Mesh,
    dofs: &DofNumbering,
    u: &[f64],
    own: &[f64],
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let state = State {
        mesh,
        dofs,
        displacement: u,
        time: 1.0,
    };
    let c: Contribution = m.evaluate(&state, own).unwrap();
    let (nd, no) = (u.len(), own.len());
    let mut r = vec![0.0; nd + no];
    for &(i, f) in &c.forces {
        r[i] += f;
    }
    for (k, v) in c.own_residual.iter().enumerate() {
        r[nd + k] += v;
    }
    let mut t = vec![vec![0.0; nd + no]; nd + no];
    let at = |x: Unknown| match x {
        Unknown::Dof(i) => i,
        Unknown::Own(k) => nd + k,
    };
    for &(a, b, v) in &c.tangent {
        t[at(a)][at(b)] += v;
    }
    (r, t)
}

/// Checks the tangent against central differences with the multipliers
/// `lam` × (1, 0.8, 0.9, 1.1) on the slave corners; returns the largest
/// entry of the tangent's displacement–displacement block.
fn check(mesh: &Mesh, lam: f64, what: &str) -> f64 {
    let nodes = mesh.coords.len();
    let dofs = DofNumbering::new(&[Comp::DX, Comp::DY, Comp::DZ], &vec![true; nodes]);
    let mut m =
        MortarLagrangian::with_dim(&[MortarZoneDef::new("MAIT", "ESCL")], mesh, false, 3).unwrap();
    let nd = 3 * nodes;
    let no = m.unknowns();
    assert_eq!(no, 4, "{what}: LAGS_C on the slave face's corners");
    // Past the first pairing (CONTACT_INIT): the status follows λ + γg.
    m.after_iteration(
        &State {
            mesh,
            dofs: &dofs,
            displacement: &vec![0.0; nd],
            time: 0.0,
        },
        &mut vec![0.0; no],
    )
    .unwrap();
    // A displacement that turns and shifts both faces a little.
    let u: Vec<f64> = (0..nd)
        .map(|i| 0.002 * ((i * 7 % 5) as f64 - 2.0) + 0.0003 * (i % 11) as f64)
        .collect();
    let own: Vec<f64> = [1.0, 0.8, 0.9, 1.1].iter().map(|f| f * lam).collect();
    let (_, t) = residual(&mut m, mesh, &dofs, &u, &own);
    let n = nd + no;
    let h = 1e-7;
    let mut largest_uu = 0.0f64;
    for j in 0..n {
        let (mut up, mut um) = (u.clone(), u.clone());
        let (mut op, mut om) = (own.clone(), own.clone());
        if j < nd {
            up[j] += h;
            um[j] -= h;
        } else {
            op[j - nd] += h;
            om[j - nd] -= h;
        }
        let (rp, _) = residual(&mut m, mesh, &dofs, &up, &op);
        let (rm, _) = residual(&mut m, mesh, &dofs, &um, &om);
        for i in 0..n {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            if i < nd && j < nd {
                largest_uu = largest_uu.max(t[i][j].abs());
            }
            let scale = 1.0 + fd.abs().max(t[i][j].abs());
            assert!(
                (fd - t[i][j]).abs() < 1e-5 * scale,
                "{what}, λ = {lam}: ∂R{i}/∂U{j}: tangent {} against {fd}",
                t[i][j]
            );
        }
    }
    largest_uu
}

fn base() -> Mesh {
    aster_mesh::parse_mail(MESH, Path::new("t.mail")).unwrap()
}

/// The mesh made quadratic, the nodes that are not corners of the slave
/// face moved off their places by a small smooth amount.
fn curved() -> Mesh {
    let mut mesh = base();
    let all: Vec<CellId> = (0..mesh.cells.len() as u32).map(CellId).collect();
    mesh.line_to_quad(&all);
    for (k, p) in mesh.coords.iter_mut().enumerate().skip(16) {
        let s = (k as f64 * 1.3).sin();
        p[0] += 0.01 * s;
        p[1] -= 0.008 * s;
        p[2] += 0.012 * (k as f64 * 0.7).cos();
    }
    mesh
}

#[test]
fn the_tangent_of_active_points_on_faces_is_the_derivative_of_the_residual() {
    // The normal's rotation and the master point's motion give the
    // displacement–displacement block (λ times geometric terms): frozen,
    // it would be zero.
    assert!(check(&base(), -500.0, "QUAD4") > 1.0);
    assert!(check(&curved(), -500.0, "QUAD8") > 1.0);
}

#[test]
fn the_tangent_of_inactive_points_on_faces_is_the_derivative_of_the_residual() {
    assert_eq!(check(&base(), 500.0, "QUAD4"), 0.0);
    assert_eq!(check(&curved(), 500.0, "QUAD8"), 0.0);
}
