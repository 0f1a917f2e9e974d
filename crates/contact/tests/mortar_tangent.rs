//! The tangent of code_aster 17's mortar Lagrangian contact (DEFI_CONT,
//! `laMatr_ct_pr`'s analytic tangent: the slave normal turning, the master
//! point sliding, the full derivative of the gap) is the derivative of its
//! residual: checked by central finite differences on a tilted slave
//! segment whose whole length is paired with a longer master segment (so
//! the integration domain does not move), with every point active, then
//! with every point inactive. And where an open point switches status the
//! residual itself jumps (by w λ on the displacement rows), as
//! code_aster's: what leaves cont012a without a root.
//!
//! On faces (DEFI_CONT in 3D, `laMatr_ct_pr` with `elem_dime` = 3: the
//! slave normal turning, `dNs_du`, the master point sliding along both of
//! its parameters and the full derivative of the gap, `dPi_du`) the same
//! check on a small tilted slave face (QUAD4, then QUAD8 with its middle
//! nodes moved off the plane) paired whole with one larger master face.

use std::path::Path;

use aster_contact::mortar_lagrangian::{MortarLagrangian, MortarZoneDef};
use aster_fem::{Comp, Contribution, DofNumbering, ForceSource, State, Unknown};
use aster_mesh::{CellId, Mesh};

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

fn check(lam: f64) {
    let mesh = aster_mesh::parse_mail(MESH, Path::new("t.mail")).unwrap();
    let dofs = DofNumbering::new(&[Comp::DX, Comp::DY], &[true; 8]);
    let mut m =
        MortarLagrangian::new(&[MortarZoneDef::new("MAIT", "ESCL")], &mesh, false, 2).unwrap();
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

/// code_aster's ROBUSTE residual (`laVect_ct_pr`) is discontinuous where an
/// open point (g > 0) switches status: the displacement rows carry
/// −w λ n·(v_s − v_m) at active points only, and the switch happens at
/// λ + γg = 0, i.e. at λ = −γg ≠ 0, so the slave force jumps by w λ; the
/// multiplier rows, w([λ + γg]₋ − λ)/γ μ, stay continuous. This is what
/// stops cont012a (a point of the sheet, open by 0.47 mm, switching with
/// w λ ≈ 145 N: Newton cycles, no root; docs/contact.md, DEFI_CONT).
/// Slave segment open by 0.05 to 0.1 over the master, a uniform multiplier
/// λ swept from −4 to −10: each of the three points closes at its own
/// λ* = −γ g (g along the slave normal, γ = COEF_CONT / h_F), and there the
/// slave's total force jumps by w λ*.
#[test]
fn the_residual_jumps_by_w_lambda_where_an_open_point_switches() {
    let mesh = aster_mesh::parse_mail(MESH, Path::new("t.mail")).unwrap();
    let dofs = DofNumbering::new(&[Comp::DX, Comp::DY], &[true; 8]);
    let mut m =
        MortarLagrangian::new(&[MortarZoneDef::new("MAIT", "ESCL")], &mesh, false, 2).unwrap();
    let zero = State {
        mesh: &mesh,
        dofs: &dofs,
        displacement: &[0.0; 16],
        time: 0.0,
    };
    m.after_iteration(&zero, &mut [0.0; 2]).unwrap();
    let u = [0.0; 16];
    // Slave nodes N5, N6: DOFs 8..12; their multipliers: rows 16, 17.
    let at = |m: &mut MortarLagrangian, lam: f64| {
        let (r, _) = residual(m, &mesh, &dofs, &u, &[lam, lam]);
        ([r[8] + r[10], r[9] + r[11]], [r[16], r[17]])
    };
    let step = 2e-5;
    let (mut jumps, mut worst_own) = (Vec::new(), 0.0f64);
    let mut prev = at(&mut m, -4.0);
    let mut lam = -4.0;
    while lam > -10.0 {
        let next_lam = lam - step;
        let next = at(&mut m, next_lam);
        let df = ((next.0[0] - prev.0[0]).powi(2) + (next.0[1] - prev.0[1]).powi(2)).sqrt();
        let dl = (next.1[0] - prev.1[0])
            .abs()
            .max((next.1[1] - prev.1[1]).abs());
        worst_own = worst_own.max(dl);
        if df > 1e-2 {
            jumps.push((0.5 * (lam + next_lam), df));
        }
        prev = next;
        lam = next_lam;
    }
    // The slave segment N5 (0, 0.05) – N6 (1, 0.1): FPG3 points at
    // (1 ± √0.6)/2 and 1/2 of its length, weights 5/9, 8/9, 5/9 × L/2.
    let len = (1.0f64 + 0.05 * 0.05).sqrt();
    let gamma = 100.0 / len;
    let cos = 1.0 / len;
    let r = 0.6f64.sqrt();
    let points = [
        (0.5 * (1.0 - r), 5.0 / 9.0),
        (0.5, 8.0 / 9.0),
        (0.5 * (1.0 + r), 5.0 / 9.0),
    ];
    assert_eq!(jumps.len(), points.len(), "{jumps:?}");
    for ((lam_star, df), (s, w)) in jumps.iter().zip(points) {
        // Gap along the slave normal, cast to the line y = 0.
        let g = (0.05 + 0.05 * s) / cos;
        assert!(
            (lam_star + gamma * g).abs() < 2.0 * step,
            "switch at λ = {lam_star}, −γg = {}",
            -gamma * g
        );
        let expected = w * 0.5 * len * lam_star.abs();
        assert!(
            (df - expected).abs() < 1e-3 * expected,
            "jump {df} against w|λ*| = {expected}"
        );
    }
    // The multiplier rows move by O(step) only.
    assert!(worst_own < 1e-3, "{worst_own}");
}

/// A lower block whose top face z = 0 (MAIT) spans [-2, 3]², and an upper
/// block whose bottom face (ESCL), over [0, 1]², is tilted and dips
/// slightly below it.
const MESH_3D: &str = "COOR_3D
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

/// Checks the tangent against central differences with the multipliers
/// `lam` × (1, 0.8, 0.9, 1.1) on the slave corners; returns the largest
/// entry of the tangent's displacement–displacement block.
fn check_3d(mesh: &Mesh, lam: f64, what: &str) -> f64 {
    let nodes = mesh.coords.len();
    let dofs = DofNumbering::new(&[Comp::DX, Comp::DY, Comp::DZ], &vec![true; nodes]);
    let mut m =
        MortarLagrangian::new(&[MortarZoneDef::new("MAIT", "ESCL")], mesh, false, 3).unwrap();
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
    aster_mesh::parse_mail(MESH_3D, Path::new("t.mail")).unwrap()
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
    assert!(check_3d(&base(), -500.0, "QUAD4") > 1.0);
    assert!(check_3d(&curved(), -500.0, "QUAD8") > 1.0);
}

#[test]
fn the_tangent_of_inactive_points_on_faces_is_the_derivative_of_the_residual() {
    assert_eq!(check_3d(&base(), 500.0, "QUAD4"), 0.0);
    assert_eq!(check_3d(&curved(), 500.0, "QUAD8"), 0.0);
}
