//! The tangent of code_aster 17's mortar Lagrangian contact (DEFI_CONT,
//! `laMatr_ct_pr`'s analytic tangent: the slave normal turning, the master
//! point sliding, the full derivative of the gap) is the derivative of its
//! residual: checked by central finite differences on a tilted slave
//! segment whose whole length is paired with a longer master segment (so
//! the integration domain does not move), with every point active, then
//! with every point inactive.

use std::path::Path;

use aster_contact::mortar_lagrangian::{MortarLagrangian, MortarZoneDef};
use aster_fem::{Comp, Contribution, DofNumbering, ForceSource, State, Unknown};

const MESH: &str = "COOR_2D
N1 -2.0 0.0
N2 3.0 0.0
N3 3.0 -1.0
N4 -2.0 -1.0
N5 0.0 0.05
N6 1.0 0.1
N7 1.0 1.0
N8 0.0 1.0
FINSF
QUAD4
M1 N4 N3 N2 N1
M2 N5 N6 N7 N8
FINSF
SEG2
M3 N1 N2
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

/// The residual (forces on the displacement rows, then the own equations)
/// and the dense tangent at `u`, `own`.
fn residual(
    m: &mut MortarLagrangian,
    mesh: &aster_mesh::Mesh,
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

fn check(lam: f64) {
    let mesh = aster_mesh::parse_mail(MESH, Path::new("t.mail")).unwrap();
    let dofs = DofNumbering::new(&[Comp::DX, Comp::DY], &[true; 8]);
    let mut m = MortarLagrangian::new(&[MortarZoneDef::new("MAIT", "ESCL")], &mesh, false).unwrap();
    // Past the first pairing (CONTACT_INIT): the status follows λ + γg.
    m.after_iteration(
        &State {
            mesh: &mesh,
            dofs: &dofs,
            displacement: &[0.0; 16],
            time: 0.0,
        },
        &mut [0.0; 2],
    )
    .unwrap();
    // A displacement that turns and shifts both segments a little.
    let u: Vec<f64> = (0..16)
        .map(|i| 0.01 * ((i * 7 % 5) as f64 - 2.0) + 0.003 * i as f64)
        .collect();
    let own = [lam, 0.8 * lam];
    let (_, t) = residual(&mut m, &mesh, &dofs, &u, &own);
    let n = 18;
    let h = 1e-6;
    for j in 0..n {
        let (mut up, mut um) = (u.clone(), u.clone());
        let (mut op, mut om) = (own, own);
        if j < 16 {
            up[j] += h;
            um[j] -= h;
        } else {
            op[j - 16] += h;
            om[j - 16] -= h;
        }
        let (rp, _) = residual(&mut m, &mesh, &dofs, &up, &op);
        let (rm, _) = residual(&mut m, &mesh, &dofs, &um, &om);
        for i in 0..n {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            let scale = 1.0 + fd.abs().max(t[i][j].abs());
            assert!(
                (fd - t[i][j]).abs() < 1e-6 * scale,
                "λ = {lam}: ∂R{i}/∂U{j}: tangent {} against {fd}",
                t[i][j]
            );
        }
    }
}

#[test]
fn the_tangent_of_active_points_is_the_derivative_of_the_residual() {
    check(-500.0);
}

#[test]
fn the_tangent_of_inactive_points_is_the_derivative_of_the_residual() {
    check(500.0);
}
