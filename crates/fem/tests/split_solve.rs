//! Large positive definite systems take the nested dissection path (split
//! in two halves factorised on two threads when there are two cores); it
//! must give the solution of the default (AMD) Cholesky.

use aster_fem::assembly::{assemble_stiffness, restrict};
use aster_fem::linalg::solve_with;
use aster_fem::scenes::{free_coords, quad4_grid};

#[test]
fn nested_dissection_solve_matches_the_default_ordering() {
    // 111×111 QUAD4: 24,864 free DOFs, above the 20,000 threshold.
    let (model, map) = quad4_grid(111).expect("grid");
    let k = assemble_stiffness(&model).expect("assembles");
    let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
    assert!(nfree > 20_000);
    let kff = restrict(&k, &map, nfree);
    let coords = free_coords(&model, &map);
    // A horizontal pull on the top right corner and a downward one on the
    // top left corner.
    let mut b = vec![0.0; nfree];
    b[nfree - 2] = 1e6;
    b[nfree - 2 * 112 + 1] = -1e6;
    let nd = solve_with(&kff, &b, nfree, true, Some(&coords)).expect("solves");
    let amd = solve_with(&kff, &b, nfree, true, None).expect("solves");
    assert!(nd.cholesky && amd.cholesky);
    assert!(nd.backward_error <= 1e-14, "{}", nd.backward_error);
    let scale = amd.x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    let diff =
        nd.x.iter()
            .zip(&amd.x)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(
        diff <= 1e-9 * scale,
        "max difference {diff} against {scale}"
    );
}

#[test]
fn nested_dissection_solve_of_a_3d_grid_is_exact() {
    // 20³ HEXA8 clamped at z = 0: 26,460 free unknowns, above the 20,000
    // threshold: the dissection (split axis chosen by separator size) and
    // the split Cholesky. The right-hand side is K x for a known x.
    let (model, map) = aster_fem::scenes::hexa8_grid(20).expect("grid");
    let k = assemble_stiffness(&model).expect("assembles");
    let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
    assert_eq!(nfree, 26_460);
    let kff = restrict(&k, &map, nfree);
    let coords = free_coords(&model, &map);
    let x: Vec<f64> = (0..nfree)
        .map(|i| ((i * 7919) % 1000) as f64 * 1e-6 - 5e-4)
        .collect();
    let b = kff.mul(&x);
    let nd = solve_with(&kff, &b, nfree, true, Some(&coords)).expect("solves");
    assert!(nd.cholesky);
    assert!(nd.backward_error <= 1e-14, "{}", nd.backward_error);
    let err =
        nd.x.iter()
            .zip(&x)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(err <= 1e-10 * 5e-4, "max error {err}");
}
