//! Offset DKT/DKQ facets (`AFFE_CARA_ELEM/COQUE/EXCENTREMENT`): the
//! section's mid-surface lies at e along the facet's normal, the nodes in
//! the reference surface. Checked against the closed forms of an offset
//! plate: the strain energy of a constant membrane strain ε and curvature
//! κ is ½·area·[A(ε + eκ)² + D₀κ²] (a beam-like state with ν = 0), rigid
//! motions stay stress-free, the kinetic energy of a rigid rotation about
//! a line at height z₀ is that of the offset slab, ρA[h³/12 + h(e − z₀)²]
//! + ρh∫x², and a zero offset is the plain plate.
#![allow(clippy::needless_range_loop)]

use aster_fem::dkq::{self, Quad};
use aster_fem::dkt::{self, Facet, ShellSection};
use aster_fem::Elastic;
use nalgebra::DVector;

const E: f64 = 2e11;
const H: f64 = 0.02;
const OFFSET: f64 = 0.05;

fn section(offset: f64) -> ShellSection {
    ShellSection {
        offset,
        rotary_inertia: true,
        ..ShellSection::new(H)
    }
}

fn tria() -> [[f64; 3]; 3] {
    [[0.1, 0.05, 0.], [0.9, 0.2, 0.], [0.3, 0.8, 0.]]
}

fn quad() -> [[f64; 3]; 4] {
    [
        [0., 0., 0.],
        [1.1, 0.1, 0.],
        [1.0, 0.9, 0.],
        [-0.1, 0.8, 0.],
    ]
}

/// Nodal values (6 per node, in the plane z = 0, local = global) of the
/// state u = ε·x, w = −κ·x²/2 (βx = DRY = κ·x).
fn patch(xyz: &[[f64; 3]], eps: f64, kappa: f64) -> DVector<f64> {
    let mut u = DVector::zeros(6 * xyz.len());
    for (n, p) in xyz.iter().enumerate() {
        let x = p[0];
        u[6 * n] = eps * x;
        u[6 * n + 2] = -kappa * x * x / 2.;
        u[6 * n + 4] = kappa * x;
    }
    u
}

fn tria_area(p: &[[f64; 3]; 3]) -> f64 {
    0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]))
}

fn quad_area(p: &[[f64; 3]; 4]) -> f64 {
    0.5 * (0..4)
        .map(|i| {
            let j = (i + 1) % 4;
            p[i][0] * p[j][1] - p[j][0] * p[i][1]
        })
        .sum::<f64>()
}

/// ½ uᵀ K u of the patch state against ½·area·[A(ε + eκ)² + D₀κ²].
#[test]
fn offset_strain_energy_is_the_eccentric_sections() {
    let mat = Elastic::new(E, 0.0).unwrap();
    let (a, d0) = (E * H, E * H.powi(3) / 12.);
    let (eps, kappa) = (1e-4, 2e-3);
    let exact = |area: f64| 0.5 * area * (a * (eps + OFFSET * kappa).powi(2) + d0 * kappa * kappa);
    let t = tria();
    let k = dkt::stiffness(&t, &mat, &section(OFFSET)).unwrap();
    let u = patch(&t, eps, kappa);
    let w = 0.5 * u.dot(&(&k * &u));
    assert!((w / exact(tria_area(&t)) - 1.).abs() < 1e-10, "DKT {w}");
    let q = quad();
    let k = dkq::stiffness(&q, &mat, &section(OFFSET)).unwrap();
    let u = patch(&q, eps, kappa);
    let w = 0.5 * u.dot(&(&k * &u));
    assert!((w / exact(quad_area(&q)) - 1.).abs() < 1e-10, "DKQ {w}");
    // The coupling's sign: with κ = −ε/e the mid-surface is unstrained and
    // only the bending D₀κ² is left.
    let u = patch(&t, eps, -eps / OFFSET);
    let k = dkt::stiffness(&t, &mat, &section(OFFSET)).unwrap();
    let w = 0.5 * u.dot(&(&k * &u));
    let pure = 0.5 * tria_area(&t) * d0 * (eps / OFFSET).powi(2);
    assert!((w / pure - 1.).abs() < 1e-10, "{w} vs {pure}");
}

/// Symmetric matrices; rigid translations and rotations about the
/// in-plane axes give no force; a zero offset is the plain plate.
#[test]
fn offset_matrices_are_symmetric_rigid_and_reduce_to_the_plain_plate() {
    let mat = Elastic::new(E, 0.3).unwrap();
    let t = tria();
    let k = dkt::stiffness(&t, &mat, &section(OFFSET)).unwrap();
    let m = dkt::mass(&t, 7800., &section(OFFSET)).unwrap().0;
    let scale = k.abs().max();
    assert!((&k - k.transpose()).abs().max() < 1e-12 * scale);
    assert!((&m - m.transpose()).abs().max() < 1e-12 * m.abs().max());
    for mode in 0..5 {
        let mut u = DVector::zeros(18);
        for (n, p) in t.iter().enumerate() {
            match mode {
                0..=2 => u[6 * n + mode] = 1.,
                // Rotation about X: DZ = y·θ, DRX = θ.
                3 => {
                    u[6 * n + 2] = p[1];
                    u[6 * n + 3] = 1.;
                }
                // Rotation about Y: DZ = −x·θ, DRY = θ.
                _ => {
                    u[6 * n + 2] = -p[0];
                    u[6 * n + 4] = 1.;
                }
            }
        }
        let f = &k * &u;
        assert!(f.abs().max() < 1e-9 * scale, "mode {mode}: {f}");
    }
    let plain = ShellSection {
        rotary_inertia: true,
        ..ShellSection::new(H)
    };
    assert_eq!(
        dkt::stiffness(&t, &mat, &section(0.)).unwrap(),
        dkt::stiffness(&t, &mat, &plain).unwrap()
    );
    let q = quad();
    assert_eq!(
        dkq::mass(&q, 7800., &section(0.)).unwrap().0,
        dkq::mass(&q, 7800., &plain).unwrap().0
    );
    // The offset changes the matrices: coupling and e²·A.
    assert!((&k - dkt::stiffness(&t, &mat, &plain).unwrap()).abs().max() > 1e-3 * scale);
}

/// The kinetic energy of a rigid rotation θ about a line parallel to Y at
/// height z₀ (DX = −z₀θ, DZ = −xθ, DRY = θ at the nodes): the offset
/// slab's ρ·area·[h³/12 + h(e − z₀)²] + ρh∫x² (exact: FPG3 and FPG4
/// integrate these degrees; the membrane–rotation coupling e·ρh gives the
/// −2ez₀ term).
#[test]
fn offset_mass_gives_the_slabs_rigid_rotation_energy() {
    let rho = 7800.;
    let z0 = 0.3;
    let energy = |xyz: &[[f64; 3]], m: &nalgebra::DMatrix<f64>| {
        let mut u = DVector::zeros(6 * xyz.len());
        for (n, p) in xyz.iter().enumerate() {
            u[6 * n] = -z0;
            u[6 * n + 2] = -p[0];
            u[6 * n + 4] = 1.;
        }
        u.dot(&(m * &u))
    };
    // ∫x² over a triangle: area/6·(Σxᵢ² + Σ_{i<j} xᵢxⱼ)·… (exact formula).
    let t = tria();
    let area = tria_area(&t);
    let xs = [t[0][0], t[1][0], t[2][0]];
    let ix2 = area / 6.
        * (xs.iter().map(|x| x * x).sum::<f64>() + xs[0] * xs[1] + xs[1] * xs[2] + xs[0] * xs[2]);
    let exact = rho * area * (H.powi(3) / 12. + H * (OFFSET - z0).powi(2)) + rho * H * ix2;
    let m = dkt::mass(&t, rho, &section(OFFSET)).unwrap().0;
    let got = energy(&t, &m);
    assert!((got / exact - 1.).abs() < 1e-10, "{got} vs {exact}");
    // The quadrangle: a rectangle, whose ∫x² is exact with FPG4, and whose
    // membrane mass (dkqmas' parallelogram pattern) is then consistent.
    let r = [[0., 0., 0.], [1.2, 0., 0.], [1.2, 0.7, 0.], [0., 0.7, 0.]];
    let area = 1.2 * 0.7;
    let ix2 = 0.7 * 1.2f64.powi(3) / 3.;
    let exact = rho * area * (H.powi(3) / 12. + H * (OFFSET - z0).powi(2)) + rho * H * ix2;
    let m = dkq::mass(&r, rho, &section(OFFSET)).unwrap().0;
    let got = energy(&r, &m);
    assert!((got / exact - 1.).abs() < 1e-10, "{got} vs {exact}");
    let _ = (Facet::new(&t).unwrap(), Quad::new(&r).unwrap());
}
