//! Layered plate sections (`DEFI_COMPOSITE`, aster-fem's `laminate`):
//! classical laminate theory, the energy-consistent shear compliance of a
//! sandwich, one ply equal to the homogeneous plate, and the ply
//! orientation.

use aster_fem::laminate::{Laminate, Ply};

fn iso(thickness: f64, e: f64, orientation: f64) -> Ply {
    Ply {
        thickness,
        orientation,
        e_l: e,
        e_t: e,
        nu_lt: 0.0,
        g_lt: e / 2.0,
        g_ln: Some(e / 2.0),
        g_tn: Some(e / 2.0),
        rho: None,
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1e-300)
}

/// A symmetric sandwich: D = Σ E_k (z_k³ − z_{k−1}³)/3, no coupling, and
/// the shear compliance ∫ (S(z)/D)²/G(z) dz with S(z) = ∫_z^{h/2} E ζ dζ
/// (the shear stress of cylindrical bending), integrated exactly.
#[test]
fn sandwich_matches_laminate_theory() {
    let (es, ec) = (2e11, 2e10);
    let l = Laminate::new(&[iso(0.02, es, 0.), iso(0.16, ec, 0.), iso(0.02, es, 0.)]).unwrap();
    let d = es * (0.1f64.powi(3) - 0.08f64.powi(3)) * 2. / 3. + ec * 2. * 0.08f64.powi(3) / 3.;
    assert!(close(l.df[0][0], d, 1e-12), "{} {d}", l.df[0][0]);
    assert!(close(l.dm[0][0], es * 0.04 + ec * 0.16, 1e-12));
    assert!(l.is_uncoupled());
    assert!(close(l.thickness, 0.2, 1e-15));
    // S(z) on the core (|z| < a) and on a skin; G = E/2.
    let (a, t) = (0.08f64, 0.1f64);
    let s_core = |z: f64| es * (t * t - a * a) / 2. + ec * (a * a - z * z) / 2.;
    let s_skin = |z: f64| es * (t * t - z * z) / 2.;
    // Three-point Gauss–Legendre on integrands of degree 4: exact.
    let gauss3 = |f: &dyn Fn(f64) -> f64, x0: f64, x1: f64| {
        let (m, r) = ((x0 + x1) / 2., (x1 - x0) / 2.);
        let q = (0.6f64).sqrt() * r;
        r * (5. * f(m - q) + 8. * f(m) + 5. * f(m + q)) / 9.
    };
    let c11 = 2. / (d * d)
        * (gauss3(&|z| s_core(z).powi(2) / (ec / 2.), 0., a)
            + gauss3(&|z| s_skin(z).powi(2) / (es / 2.), a, t));
    assert!(close(l.dci[0][0], c11, 1e-12), "{} {c11}", l.dci[0][0]);
    assert!(close(l.dci[1][1], c11, 1e-12));
    assert!(l.dci[0][1].abs() < 1e-12 * c11);
    assert!(close(l.dc[0][0], 1. / c11, 1e-12));
}

/// One ply is the homogeneous plate: A = E h/(1−ν²)…, D = A h²/12 and the
/// shear stiffness 5/6·G·h of `dxmate` (op0056's compliance gives 6/5).
#[test]
fn one_ply_is_the_homogeneous_plate() {
    let (e, nu, h) = (2e11, 0.3, 0.05);
    let g = e / 2. / (1. + nu);
    let l = Laminate::new(&[Ply {
        thickness: h,
        orientation: 30.,
        e_l: e,
        e_t: e,
        nu_lt: nu,
        g_lt: g,
        g_ln: Some(g),
        g_tn: Some(g),
        rho: Some(7800.),
    }])
    .unwrap();
    let a = e * h / (1. - nu * nu);
    let expect = [
        [a, a * nu, 0.],
        [a * nu, a, 0.],
        [0., 0., a * (1. - nu) / 2.],
    ];
    for (i, row) in expect.iter().enumerate() {
        for (j, &e) in row.iter().enumerate() {
            assert!((l.dm[i][j] - e).abs() < 1e-9 * a, "A{i}{j}");
            let dij = e * h * h / 12.;
            assert!((l.df[i][j] - dij).abs() < 1e-9 * a * h * h, "D{i}{j}");
        }
    }
    assert!(close(l.dc[0][0], 5. / 6. * g * h, 1e-12));
    assert!(close(l.dc[1][1], 5. / 6. * g * h, 1e-12));
    assert!(l.dc[0][1].abs() < 1e-9 * g * h);
    assert_eq!(l.density, Some(7800.));
}

/// A ply turned by 90° swaps the longitudinal and transverse moduli, and
/// its shear moduli G_LN and G_TN.
#[test]
fn orientation_turns_the_ply() {
    let ply = |orientation| Ply {
        thickness: 0.01,
        orientation,
        e_l: 4e10,
        e_t: 1.6e9,
        nu_lt: 0.25,
        g_lt: 8e8,
        g_ln: None,
        g_tn: Some(3.2e8),
        rho: None,
    };
    let l0 = Laminate::new(&[ply(0.)]).unwrap();
    let l90 = Laminate::new(&[ply(90.)]).unwrap();
    assert!(close(l90.dm[0][0], l0.dm[1][1], 1e-12));
    assert!(close(l90.dm[1][1], l0.dm[0][0], 1e-12));
    assert!(close(l90.dm[2][2], l0.dm[2][2], 1e-12));
    assert!(l90.dm[0][2].abs() < 1e-9 * l0.dm[0][0]);
    // G_LN defaults to G_LT: the shear stiffnesses 5/6·G·h swap too.
    assert!(
        close(l0.dc[0][0], 5. / 6. * 8e8 * 0.01, 1e-9),
        "{:?}",
        l0.dc
    );
    assert!(close(l0.dc[1][1], 5. / 6. * 3.2e8 * 0.01, 1e-9));
    assert!(close(l90.dc[0][0], l0.dc[1][1], 1e-9));
    assert!(l90.dci[0][1].abs() < 1e-9 * l90.dci[0][0]);
}

/// An unsymmetric stack couples membrane and bending (B ≠ 0); RHO on some
/// plies only is refused.
#[test]
fn coupling_and_partial_density() {
    let l = Laminate::new(&[iso(0.01, 2e11, 0.), iso(0.01, 2e10, 0.)]).unwrap();
    assert!(!l.is_uncoupled());
    let mut p = iso(0.01, 2e11, 0.);
    p.rho = Some(1.);
    let err = Laminate::new(&[p, iso(0.01, 2e11, 0.)]).unwrap_err();
    assert!(err.contains("RHO"), "{err}");
    assert!(Laminate::new(&[]).is_err());
}
