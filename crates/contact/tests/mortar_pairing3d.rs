//! code_aster 17's pairing of 3D faces (`mortar_pairing3d`, DEFI_CONT's
//! mortar contact): on non-matching grids of a flat interface, the
//! intersection polygons of each slave face tile it exactly (their areas in
//! the slave's parametric space add up to the reference cell's: 4 for a
//! QUAD4, 1/2 for a TRIA3), and the quadrature on them (getQuadCont: FPG4
//! per triangle) integrates the interface's area — whatever the grids,
//! the faces' kinds, a gap between the sides, or a rotation of the whole.

use aster_contact::mortar_pairing3d::{intersect, polygon_area, quadrature, Face, PAIR_TOLE};
use aster_contact::{interpolate, SurfaceKind};

type Rot = [[f64; 3]; 3];

fn rotation(a: f64, b: f64) -> Rot {
    let (ca, sa, cb, sb) = (a.cos(), a.sin(), b.cos(), b.sin());
    // Rz(b) Rx(a)
    [
        [cb, -sb * ca, sb * sa],
        [sb, cb * ca, -cb * sa],
        [0.0, sa, ca],
    ]
}

fn apply(r: &Rot, p: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2])
}

/// The faces of an n × n grid on [0, 1]² at height z (counter-clockwise seen
/// from +z), as QUAD4 or as two TRIA3 per square.
fn grid(n: usize, z: f64, triangles: bool, r: &Rot) -> Vec<(SurfaceKind, Vec<[f64; 3]>)> {
    let p = |i: usize, j: usize| apply(r, [i as f64 / n as f64, j as f64 / n as f64, z]);
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            if triangles {
                out.push((SurfaceKind::Tria3, vec![a, b, c]));
                out.push((SurfaceKind::Tria3, vec![a, c, d]));
            } else {
                out.push((SurfaceKind::Quad4, vec![a, b, c, d]));
            }
        }
    }
    out
}

/// For every slave face: the sum of its polygons' parametric areas, and
/// the whole quadrature's measure of the interface.
fn tiling(
    slave: &[(SurfaceKind, Vec<[f64; 3]>)],
    master: &[(SurfaceKind, Vec<[f64; 3]>)],
) -> (Vec<f64>, f64) {
    let mut areas = Vec::new();
    let mut measure = 0.0;
    for (sk, sx) in slave {
        // The upper block's bottom: outward normal −z (grid order gives +z).
        let s = Face {
            kind: *sk,
            x: sx,
            sign: -1.0,
        };
        let mut a = 0.0;
        for (mk, mx) in master {
            let m = Face {
                kind: *mk,
                x: mx,
                sign: 1.0,
            };
            if let Some(poly) = intersect(s, m, PAIR_TOLE, None) {
                a += polygon_area(&poly);
                for (xi, w) in quadrature(&poly, true) {
                    let t = interpolate(*sk, sx, xi).tangents;
                    let c = [
                        t[0][1] * t[1][2] - t[0][2] * t[1][1],
                        t[0][2] * t[1][0] - t[0][0] * t[1][2],
                        t[0][0] * t[1][1] - t[0][1] * t[1][0],
                    ];
                    measure += w * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
                }
            }
        }
        areas.push(a);
    }
    (areas, measure)
}

#[test]
fn polygons_tile_every_slave_face_on_non_matching_grids() {
    for r in [rotation(0.0, 0.0), rotation(0.35, 0.52)] {
        for (ns, nm) in [(3, 2), (2, 3), (4, 3), (1, 1)] {
            for (st, mt) in [(false, false), (false, true), (true, false), (true, true)] {
                for gap in [0.0, 0.01] {
                    let slave = grid(ns, gap, st, &r);
                    let master = grid(nm, 0.0, mt, &r);
                    let (areas, measure) = tiling(&slave, &master);
                    let full = if st { 0.5 } else { 4.0 };
                    for a in &areas {
                        assert!(
                            (a - full).abs() < 1e-12,
                            "{ns}/{nm} tria {st}/{mt} gap {gap}: {a} instead of {full}"
                        );
                    }
                    assert!((measure - 1.0).abs() < 1e-12, "measure {measure}");
                }
            }
        }
    }
}

#[test]
fn a_slave_face_half_outside_the_master_is_half_paired() {
    let r = rotation(0.0, 0.0);
    let slave = vec![(
        SurfaceKind::Quad4,
        vec![
            [0.5, 0.0, 0.0],
            [1.5, 0.0, 0.0],
            [1.5, 1.0, 0.0],
            [0.5, 1.0, 0.0],
        ],
    )];
    let (areas, measure) = tiling(&slave, &grid(2, 0.0, false, &r));
    assert!((areas[0] - 2.0).abs() < 1e-12, "{areas:?}");
    assert!((measure - 0.5).abs() < 1e-12);
}

#[test]
fn faces_facing_away_are_not_paired() {
    let r = rotation(0.0, 0.0);
    // The master above the slave, with the slave's own outward normal.
    let s = grid(1, 0.0, false, &r);
    let m = grid(1, 0.5, false, &r);
    let slave = Face {
        kind: s[0].0,
        x: &s[0].1,
        sign: -1.0,
    };
    let master = Face {
        kind: m[0].0,
        x: &m[0].1,
        sign: -1.0,
    };
    assert!(intersect(slave, master, PAIR_TOLE, None).is_none());
    // COEF_MULT_APPA: a master farther than 2 × ratio × diameter is skipped.
    let below = grid(1, -10.0, false, &r);
    let far = Face {
        kind: below[0].0,
        x: &below[0].1,
        sign: 1.0,
    };
    assert!(intersect(slave, far, PAIR_TOLE, None).is_some());
    assert!(intersect(slave, far, PAIR_TOLE, Some(1.0)).is_none());
}
