//! code_aster's Gauss families (`elraga`), in code_aster's point order and
//! reference coordinates (see `refcells` for the reference cells). The
//! order matters: SIEF_ELGA values are tested by POINT number.

use crate::shape::GaussPoint;

fn gp(x: f64, y: f64, z: f64, weight: f64) -> GaussPoint {
    GaussPoint {
        xi: [x, y, z],
        weight,
    }
}

const A2: f64 = 0.577_350_269_189_625_8; // 1/√3

fn a3() -> f64 {
    0.6f64.sqrt()
}

/// Gauss–Legendre abscissae and weights, code_aster's order (−, [0,] +).
fn legendre(n: usize) -> Vec<(f64, f64)> {
    match n {
        2 => vec![(-A2, 1.), (A2, 1.)],
        _ => vec![(-a3(), 5. / 9.), (0., 8. / 9.), (a3(), 5. / 9.)],
    }
}

/// Hexahedra FPG8 (n = 2) and FPG27 (n = 3): ξ varies slowest, ζ fastest.
pub fn hexa(n: usize) -> Vec<GaussPoint> {
    let g = legendre(n);
    let mut v = Vec::with_capacity(n * n * n);
    for &(x, wx) in &g {
        for &(y, wy) in &g {
            for &(z, wz) in &g {
                v.push(gp(x, y, z, wx * wy * wz));
            }
        }
    }
    v
}

/// Triangle FPG6 (degree 4), code_aster's order: the three points near the
/// vertices first, then the three near the edge midpoints.
pub fn tria6() -> Vec<[f64; 3]> {
    let (xa, xb) = (0.445_948_490_915_965, 0.091_576_213_509_771);
    let (pa, pb) = (0.111_690_794_839_005, 0.054_975_871_827_661);
    vec![
        [xb, xb, pb],
        [1. - 2. * xb, xb, pb],
        [xb, 1. - 2. * xb, pb],
        [xa, 1. - 2. * xa, pa],
        [xa, xa, pa],
        [1. - 2. * xa, xa, pa],
    ]
}

/// Triangle FPG6 as points of a face (ξ, η).
pub fn tria_fpg6() -> Vec<GaussPoint> {
    tria6()
        .into_iter()
        .map(|p| gp(p[0], p[1], 0., p[2]))
        .collect()
}

/// Hammer's 7-point triangle rule (degree 5), code_aster's order, as
/// (first, second, weight) triangle coordinates.
fn hammer7() -> Vec<[f64; 3]> {
    let s = 15f64.sqrt();
    let (a, b) = ((6. + s) / 21., (6. - s) / 21.);
    let (wa, wb) = ((155. + s) / 2400., (155. - s) / 2400.);
    vec![
        [1. / 3., 1. / 3., 9. / 80.],
        [a, a, wa],
        [1. - 2. * a, a, wa],
        [a, 1. - 2. * a, wa],
        [b, b, wb],
        [1. - 2. * b, b, wb],
        [b, 1. - 2. * b, wb],
    ]
}

/// Pentahedra FPG6: 2 Gauss points along ξ × 3 points in the triangle
/// (η, ζ) ∈ {(½,½), (0,½), (½,0)}; ξ varies slowest.
pub fn penta6() -> Vec<GaussPoint> {
    let tri = [[0.5, 0.5], [0., 0.5], [0.5, 0.]];
    let mut v = Vec::with_capacity(6);
    for &(x, wx) in &legendre(2) {
        for t in tri {
            v.push(gp(x, t[0], t[1], wx / 6.));
        }
    }
    v
}

/// Pentahedra FPG21: 3 Gauss points along ξ × Hammer's 7 in (η, ζ).
pub fn penta21() -> Vec<GaussPoint> {
    let mut v = Vec::with_capacity(21);
    for &(x, wx) in &legendre(3) {
        for t in hammer7() {
            v.push(gp(x, t[0], t[1], wx * t[2]));
        }
    }
    v
}

/// Tetrahedra FPG4 (degree 2).
pub fn tetra4() -> Vec<GaussPoint> {
    let s5 = 5f64.sqrt();
    let (a, b) = ((5. - s5) / 20., (5. + 3. * s5) / 20.);
    let w = 1. / 24.;
    vec![
        gp(a, a, a, w),
        gp(a, a, b, w),
        gp(a, b, a, w),
        gp(b, a, a, w),
    ]
}

/// Tetrahedra FPG15 (degree 5, Touzot), code_aster's order (the MASS
/// family of TETRA10).
pub fn tetra15() -> Vec<GaussPoint> {
    let r = 15f64.sqrt();
    let (a1, b1) = ((7. + r) / 34., (13. - 3. * r) / 34.);
    let w1 = (2665. - 14. * r) / 226_800.;
    let (a2, b2) = ((7. - r) / 34., (13. + 3. * r) / 34.);
    let w2 = (2665. + 14. * r) / 226_800.;
    let (c, d) = ((5. - r) / 20., (5. + r) / 20.);
    let w3 = 5. / 567.;
    vec![
        gp(0.25, 0.25, 0.25, 8. / 405.),
        gp(a1, a1, a1, w1),
        gp(a1, a1, b1, w1),
        gp(a1, b1, a1, w1),
        gp(b1, a1, a1, w1),
        gp(a2, a2, a2, w2),
        gp(a2, a2, b2, w2),
        gp(a2, b2, a2, w2),
        gp(b2, a2, a2, w2),
        gp(c, c, d, w3),
        gp(c, d, c, w3),
        gp(d, c, c, w3),
        gp(c, d, d, w3),
        gp(d, c, d, w3),
        gp(d, d, c, w3),
    ]
}

/// Tetrahedra FPG5 (degree 3; its centre weight is negative, as in
/// code_aster's stiffness of TETRA10).
pub fn tetra5() -> Vec<GaussPoint> {
    let (b, c, w) = (1. / 6., 0.5, 3. / 40.);
    vec![
        gp(0.25, 0.25, 0.25, -2. / 15.),
        gp(b, b, b, w),
        gp(b, b, c, w),
        gp(b, c, b, w),
        gp(c, b, b, w),
    ]
}

/// Pyramids FPG5.
pub fn pyram5() -> Vec<GaussPoint> {
    let (h1, h2) = (0.153_175_416_344_814_6, 0.637_298_334_620_741_6);
    let w = 2. / 15.;
    vec![
        gp(0.5, 0., h1, w),
        gp(0., 0.5, h1, w),
        gp(-0.5, 0., h1, w),
        gp(0., -0.5, h1, w),
        gp(0., 0., h2, w),
    ]
}

/// Pyramids FPG27 (code_aster's PYRAM13 stiffness family up to v17).
pub fn pyram27() -> Vec<GaussPoint> {
    let (a1, b6, b1, c8, c1, d12, d1) = (
        0.788_073_483,
        0.499_369_002,
        0.848_418_011,
        0.478_508_449,
        0.652_816_472,
        0.032_303_742,
        1.106_412_899,
    );
    // (x, y, z, weight before the (1−z)²/4 factor), code_aster's order.
    let mut raw: Vec<[f64; 4]> = Vec::with_capacity(27);
    raw.push([0., 0., 0.5, a1]);
    let zb = 0.5;
    let r = 0.5 * b1 * (1. - zb);
    raw.extend([
        [r, r, zb, b6],
        [-r, r, zb, b6],
        [-r, -r, zb, b6],
        [r, -r, zb, b6],
    ]);
    raw.push([0., 0., 0.5 * (1. - b1), b6]);
    raw.push([0., 0., 0.5 * (1. + b1), b6]);
    for zc in [0.5 * (1. - c1), 0.5 * (1. + c1)] {
        let r = c1 * (1. - zc);
        raw.extend([
            [r, 0., zc, c8],
            [0., r, zc, c8],
            [-r, 0., zc, c8],
            [0., -r, zc, c8],
        ]);
    }
    let zd = 0.5 * (1. - d1);
    let r = 0.5 * d1 * (1. - zd);
    raw.extend([
        [r, r, zd, d12],
        [-r, r, zd, d12],
        [-r, -r, zd, d12],
        [r, -r, zd, d12],
    ]);
    let r = d1 * 0.5;
    raw.extend([
        [r, 0., 0.5, d12],
        [0., r, 0.5, d12],
        [-r, 0., 0.5, d12],
        [0., -r, 0.5, d12],
    ]);
    let zd = 0.5 * (1. + d1);
    let r = 0.5 * d1 * (1. - zd);
    raw.extend([
        [r, r, zd, d12],
        [-r, r, zd, d12],
        [-r, -r, zd, d12],
        [r, -r, zd, d12],
    ]);
    raw.into_iter()
        .map(|[x, y, z, w]| gp(x, y, z, w * 0.25 * (1. - z) * (1. - z)))
        .collect()
}
