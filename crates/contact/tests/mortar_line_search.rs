//! The residual of code_aster 17's mortar contact (DEFI_CONT) at a trial of
//! MECA_NON_LINE's line search (`ForceSource::evaluate_on_pairing`): the
//! pairing, slave normals and master points of the iteration's start
//! (`projQpSl2Ma` on `coor_*_pair`), the gap on the current positions.
//! A flat slave segment touching a long master is paired at rest, then
//! tilted and pushed in: the trial forces stay along the pairing's normal
//! (no DX force) and the LAGS_C rows are ∫ g μ with the gap measured along
//! it, computed by hand; paired again (`evaluate`) both differ; on its own
//! pairing the trial is `evaluate`.

use std::path::Path;

use aster_contact::mortar_lagrangian::{MortarLagrangian, MortarZoneDef};
use aster_contact::mortar_penalty::MortarPenalty;
use aster_fem::{Comp, Contribution, Dof, DofNumbering, ForceSource, State};
use aster_mesh::NodeId;

const MESH: &str = "COOR_2D
N1 -2.0 0.0
N2 3.0 0.0
N3 3.0 -1.0
N4 -2.0 -1.0
N5 0.0 0.0
N6 1.0 0.0
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

struct Scene {
    mesh: aster_mesh::Mesh,
    dofs: DofNumbering,
    /// At rest (the pairing configuration).
    rest: Vec<f64>,
    /// The slave tilted and pushed in: DY = −0.01 at N5, −0.03 at N6.
    trial: Vec<f64>,
}

fn scene() -> Scene {
    let mesh = aster_mesh::parse_mail(MESH, Path::new("t.mail")).unwrap();
    let dofs = DofNumbering::new(&[Comp::DX, Comp::DY], &[true; 8]);
    let mut trial = vec![0.0; 16];
    trial[dofs.index(Dof::new(NodeId(4), Comp::DY)).unwrap()] = -0.01;
    trial[dofs.index(Dof::new(NodeId(5), Comp::DY)).unwrap()] = -0.03;
    Scene {
        mesh,
        dofs,
        rest: vec![0.0; 16],
        trial,
    }
}

impl Scene {
    fn state<'a>(&'a self, u: &'a [f64]) -> State<'a> {
        State {
            mesh: &self.mesh,
            dofs: &self.dofs,
            displacement: u,
            time: 1.0,
        }
    }

    /// Σ of the forces on the slave's DX and DY.
    fn slave_forces(&self, c: &Contribution) -> [f64; 2] {
        let mut f = [0.0; 2];
        for n in [4u32, 5] {
            for (k, comp) in [Comp::DX, Comp::DY].into_iter().enumerate() {
                let i = self.dofs.index(Dof::new(NodeId(n), comp)).unwrap();
                f[k] += c
                    .forces
                    .iter()
                    .filter(|(j, _)| *j == i)
                    .map(|(_, v)| v)
                    .sum::<f64>();
            }
        }
        f
    }
}

fn same(a: &Contribution, b: &Contribution) {
    assert_eq!(a.forces.len(), b.forces.len());
    for (x, y) in a.forces.iter().zip(&b.forces) {
        assert_eq!(x.0, y.0);
        assert!(
            (x.1 - y.1).abs() <= 1e-15 * (1.0 + x.1.abs()),
            "{x:?} {y:?}"
        );
    }
    for (x, y) in a.own_residual.iter().zip(&b.own_residual) {
        assert!((x - y).abs() <= 1e-15 * (1.0 + x.abs()), "{x} {y}");
    }
}

#[test]
fn lagrangian_trial_keeps_the_pairing_normal_and_master_points() {
    let sc = scene();
    let mut m =
        MortarLagrangian::new(&[MortarZoneDef::new("MAIT", "ESCL")], &sc.mesh, false, 2).unwrap();
    // Past the first pairing (CONTACT_INIT): the status follows λ + γg.
    m.after_iteration(&sc.state(&sc.rest), &mut [0.0; 2])
        .unwrap();
    let own = [-1.0, -1.0];
    let frozen = m
        .evaluate_on_pairing(&sc.state(&sc.rest), &sc.state(&sc.trial), &own)
        .unwrap();
    // n_s = (0, −1) of the pairing: −w λ n_s·(v_s − v_m) has no DX part;
    // its DY part sums to λ × the slave's initial length.
    let f = sc.slave_forces(&frozen);
    assert!(f[0].abs() < 1e-15, "{f:?}");
    assert!((f[1] + 1.0).abs() < 1e-14, "{f:?}");
    // Active everywhere (λ + γg < 0): the LAGS_C rows are ∫ g μ_k with
    // g(s) = −0.01 − 0.02 s along the pairing normal: −0.01/2 − 0.02/6 at
    // N5, −0.01/2 − 0.02/3 at N6.
    let order: Vec<u32> = m.multipliers(&own).map(|(n, _)| n.0).collect();
    for (k, n) in order.iter().enumerate() {
        let expected = if *n == 4 {
            -0.005 - 0.02 / 6.0
        } else {
            -0.005 - 0.02 / 3.0
        };
        let got = frozen.own_residual[k];
        assert!(
            (got - expected).abs() < 1e-15,
            "node {n}: {got} against {expected}"
        );
    }
    // Paired again on the trial geometry: the normal turns (a DX force)
    // and the gaps are measured along it.
    let repaired = m.evaluate(&sc.state(&sc.trial), &own).unwrap();
    let g = sc.slave_forces(&repaired);
    assert!(g[0].abs() > 1e-3, "{g:?}");
    let moved = frozen
        .own_residual
        .iter()
        .zip(&repaired.own_residual)
        .fold(0.0f64, |d, (a, b)| d.max((a - b).abs()));
    assert!(moved > 1e-7, "{moved}");
    // On its own pairing a trial is the iteration's evaluation.
    same(
        &m.evaluate_on_pairing(&sc.state(&sc.trial), &sc.state(&sc.trial), &own)
            .unwrap(),
        &repaired,
    );
}

#[test]
fn penalised_trial_keeps_the_pairing_normal_and_master_points() {
    let sc = scene();
    let mut zone = MortarZoneDef::new("MAIT", "ESCL");
    zone.coef_cont = 1000.0;
    let mut m = MortarPenalty::new(&[zone], &sc.mesh, false, 2).unwrap();
    m.after_iteration(&sc.state(&sc.rest), &mut []).unwrap();
    let frozen = m
        .evaluate_on_pairing(&sc.state(&sc.rest), &sc.state(&sc.trial), &[])
        .unwrap();
    // −w [γg]₋ n_s·(v_s − v_m), n_s = (0, −1), γ = COEF_CONT / h_F = 1000:
    // the DY forces sum to γ ∫ g = 1000 × (−0.02).
    let f = sc.slave_forces(&frozen);
    assert!(f[0].abs() < 1e-15, "{f:?}");
    assert!((f[1] + 20.0).abs() < 1e-12, "{f:?}");
    let repaired = m.evaluate(&sc.state(&sc.trial), &[]).unwrap();
    let g = sc.slave_forces(&repaired);
    assert!(g[0].abs() > 1e-3, "{g:?}");
    same(
        &m.evaluate_on_pairing(&sc.state(&sc.trial), &sc.state(&sc.trial), &[])
            .unwrap(),
        &repaired,
    );
}
