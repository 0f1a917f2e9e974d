//! Slave-side integration points of the continuous formulation
//! (`INTEGRATION`, `ORDRE_INT`).
//!
//! `AUTO` integrates at the slave nodes (Newton–Cotes weights: SEG2 L/2,
//! SEG3 L/6·(1, 1, 4), TRIA3 A/3, QUAD4 A/4) and merges the contributions of
//! the cells around a node into one point per node — the contact pressure
//! is then a nodal field, as code_aster's LAGS_C. Quadratic faces (TRIA6,
//! QUAD8) have corner weights ≤ 0 with nodal rules, so `AUTO` falls back to
//! Gauss points there. `SIMPSON` and `NCOTES` on faces are code_aster's
//! face rules (`shape::face_simpson`, `shape::face_newton_cotes`), except
//! on TRIA6/QUAD8 faces, whose pressure lives on the corners
//! (`SurfaceKind::linear_pressure`): a uniform pressure is reproduced only
//! if its products with the quadratic functions are integrated exactly,
//! which the Simpson and low Newton–Cotes rules do not; they get Gauss
//! points of degree 4.
//!
//! Weights are measured as code_aster's contact elements do (`mmmjac`):
//! on the **reference** slave geometry (the mesh as read, not the current
//! positions), times the radius under AXIS. The contact pressure LAGS_C is
//! then a force per unit of initial area (per radian under AXIS, as fem's
//! nodal forces); measuring on the current geometry moved SSNP121 A's
//! LAGS_C by up to 8.7e-5 from code_aster's values.

use std::collections::BTreeMap;

use aster_mesh::NodeId;

use crate::pairing::{jacobian, SlavePoint};
use crate::shape::SurfaceKind;
use crate::surface::ResolvedZone;
use crate::zone::Integration;

/// How the weight of an integration point measures the slave surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Measure {
    /// Length (2D) or area (3D).
    #[default]
    Plane,
    /// Length × radius x (AXIS, per radian); a point on the axis counts
    /// with radius 1e-7, as code_aster's `mmmjac`.
    Axisymmetric,
}

/// Radius code_aster substitutes for a point on the axis.
const AXIS_RADIUS: f64 = 1e-7;

/// Integration points of the slave surface of `zone`, weights measured on
/// geometry `x` (plane measure).
pub fn integration_points(
    zone: &ResolvedZone,
    rule: Integration,
    x: &[[f64; 3]],
) -> Vec<SlavePoint> {
    integration_points_measured(zone, rule, x, Measure::Plane)
}

/// Integration points of the slave surface of `zone`, weights measured on
/// geometry `reference` (code_aster: the mesh's initial coordinates) with
/// `measure`. The points themselves are reference coordinates of the
/// slave cells and do not depend on the geometry.
pub fn integration_points_measured(
    zone: &ResolvedZone,
    rule: Integration,
    reference: &[[f64; 3]],
    measure: Measure,
) -> Vec<SlavePoint> {
    let x = reference;
    let measured = |kind: SurfaceKind, nodes: &[[f64; 3]], xi: [f64; 2]| {
        let j = jacobian(kind, nodes, xi);
        match measure {
            Measure::Plane => j,
            Measure::Axisymmetric => {
                let r = crate::shape::interpolate(kind, nodes, xi).x[0].abs();
                j * if r == 0.0 { AXIS_RADIUS } else { r }
            }
        }
    };
    let excluded = |n: &NodeId| zone.slave_nodes.binary_search(n).is_err();
    let mut nodal: BTreeMap<NodeId, f64> = BTreeMap::new();
    let mut points = Vec::new();
    for (ci, cell) in zone.slave.iter().enumerate() {
        let nodes: Vec<[f64; 3]> = cell.nodes.iter().map(|n| x[n.0 as usize]).collect();
        let quad = match (rule, cell.kind) {
            (
                Integration::Auto,
                SurfaceKind::Tria6 | SurfaceKind::Tria7 | SurfaceKind::Quad8 | SurfaceKind::Quad9,
            ) => gauss(cell.kind, 3),
            (Integration::Auto, k) => {
                // Nodal rule: weight of node i = ∫ N_i, exact for these cells.
                let w: &[f64] = match k {
                    SurfaceKind::Seg2 => &[1.0, 1.0],
                    SurfaceKind::Seg3 => &[1.0 / 3.0, 1.0 / 3.0, 4.0 / 3.0],
                    SurfaceKind::Tria3 => &[1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0],
                    _ => &[1.0, 1.0, 1.0, 1.0],
                };
                for (i, n) in cell.nodes.iter().enumerate() {
                    let xi = k.node_coords()[i];
                    *nodal.entry(*n).or_default() += w[i] * measured(k, &nodes, xi);
                }
                continue;
            }
            (Integration::Gauss(o), k) => ordre_int_gauss(k, o),
            (Integration::Simpson(o), k) if k.dim() == 1 => simpson(o.max(1)),
            (Integration::NCotes(o), k) if k.dim() == 1 => newton_cotes(o.clamp(1, 8)),
            // Corner pressures on TRIA6/QUAD8 need the products of pressure
            // and displacement functions integrated exactly: Gauss, degree 4.
            (Integration::Simpson(o) | Integration::NCotes(o), k) if k.linear_pressure() => {
                gauss(k, o.max(4))
            }
            (Integration::Simpson(o), k) => {
                crate::shape::face_simpson(k, o).unwrap_or_else(|| gauss(k, o))
            }
            (Integration::NCotes(o), k) => {
                crate::shape::face_newton_cotes(k, o).unwrap_or_else(|| gauss(k, o))
            }
        };
        for (xi, w) in quad {
            let (shape, _) = cell.kind.eval(xi);
            let on_nodes: Vec<(NodeId, f64)> = cell
                .nodes
                .iter()
                .copied()
                .zip(shape)
                .filter(|(_, s)| *s != 0.0)
                .collect();
            // A point carried only by excluded nodes is not a contact point.
            if on_nodes.iter().all(|(n, _)| excluded(n)) {
                continue;
            }
            points.push(SlavePoint {
                zone: zone.index,
                nodes: on_nodes,
                weight: w * measured(cell.kind, &nodes, xi),
                cell: Some((ci, xi)),
            });
        }
    }
    for (n, w) in nodal {
        if !excluded(&n) {
            points.push(SlavePoint {
                zone: zone.index,
                nodes: vec![(n, 1.0)],
                weight: w,
                cell: None,
            });
        }
    }
    points
}

/// Gauss–Legendre points on [-1, 1] exact to degree `2n - 1`.
fn gauss_1d(n: usize) -> Vec<(f64, f64)> {
    match n {
        1 => vec![(0.0, 2.0)],
        2 => {
            let a = 1.0 / 3f64.sqrt();
            vec![(-a, 1.0), (a, 1.0)]
        }
        3 => {
            let a = (0.6f64).sqrt();
            vec![(-a, 5.0 / 9.0), (0.0, 8.0 / 9.0), (a, 5.0 / 9.0)]
        }
        _ => {
            let a = (3.0 / 7.0 - 2.0 / 7.0 * (1.2f64).sqrt()).sqrt();
            let b = (3.0 / 7.0 + 2.0 / 7.0 * (1.2f64).sqrt()).sqrt();
            let wa = (18.0 + 30f64.sqrt()) / 36.0;
            let wb = (18.0 - 30f64.sqrt()) / 36.0;
            vec![(-b, wb), (-a, wa), (a, wa), (b, wb)]
        }
    }
}

/// code_aster's `INTEGRATION='GAUSS'` rule of rank `ordre_int` (`mmgaus`):
/// `ORDRE_INT` is the number of Gauss–Legendre points on a segment (1 to
/// 6), their tensor square on a quadrangle, and on a triangle the rank of
/// the rule in code_aster's table (1, 3, 4, 6, 7, 12 points, exact to
/// degree 1 to 6). It is not a polynomial degree: reading ORDRE_INT = 3 as
/// "exact to degree 3" gave 2 points per SEG3 instead of 3 and moved
/// ssnp154b's indentation by 2.5e-4.
pub(crate) fn ordre_int_gauss(kind: SurfaceKind, ordre_int: u8) -> Vec<([f64; 2], f64)> {
    let n = ordre_int.clamp(1, 6) as usize;
    match kind {
        SurfaceKind::Seg2 | SurfaceKind::Seg3 => gauss_legendre(n)
            .into_iter()
            .map(|(x, w)| ([x, 0.0], w))
            .collect(),
        SurfaceKind::Quad4 | SurfaceKind::Quad8 | SurfaceKind::Quad9 => {
            // Point g: i = (g−1) mod n along ξ, j = (g−1) div n along η.
            let g = gauss_legendre(n);
            let mut out = Vec::with_capacity(n * n);
            for &(y, wy) in &g {
                for &(x, wx) in &g {
                    out.push(([x, y], wx * wy));
                }
            }
            out
        }
        SurfaceKind::Tria3 | SurfaceKind::Tria6 | SurfaceKind::Tria7 => triangle_rule(n),
    }
}

/// Gauss–Legendre points on [-1, 1], `n` = 1 … 6 (code_aster's `fpgseg`).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let sym = |pairs: &[(f64, f64)], centre: Option<f64>| {
        let mut v = Vec::new();
        for &(x, w) in pairs {
            v.push((-x, w));
            v.push((x, w));
        }
        if let Some(w) = centre {
            v.push((0.0, w));
        }
        v
    };
    match n {
        1..=4 => gauss_1d(n),
        5 => sym(
            &[
                (0.906_179_845_938_664, 0.236_926_885_056_189),
                (0.538_469_310_105_683, 0.478_628_670_499_366),
            ],
            Some(0.568_888_888_888_889),
        ),
        _ => sym(
            &[
                (0.238_619_186_083_197, 0.467_913_934_572_691),
                (0.661_209_386_466_265, 0.360_761_573_048_139),
                (0.932_469_514_203_152, 0.171_324_492_379_17),
            ],
            None,
        ),
    }
}

/// code_aster's triangle rules of rank 1 … 6 (`fpgtri`) on the reference
/// triangle (0,0) (1,0) (0,1).
fn triangle_rule(rank: usize) -> Vec<([f64; 2], f64)> {
    let orbit3 = |a: f64, w: f64| {
        vec![
            ([a, a], w),
            ([1.0 - 2.0 * a, a], w),
            ([a, 1.0 - 2.0 * a], w),
        ]
    };
    match rank {
        1 => vec![([1.0 / 3.0, 1.0 / 3.0], 0.5)],
        2 => vec![
            ([1.0 / 6.0, 1.0 / 6.0], 1.0 / 6.0),
            ([2.0 / 3.0, 1.0 / 6.0], 1.0 / 6.0),
            ([1.0 / 6.0, 2.0 / 3.0], 1.0 / 6.0),
        ],
        3 => vec![
            ([0.2, 0.2], 25.0 / 96.0),
            ([0.6, 0.2], 25.0 / 96.0),
            ([0.2, 0.6], 25.0 / 96.0),
            ([1.0 / 3.0, 1.0 / 3.0], -27.0 / 96.0),
        ],
        4 => {
            let (a, b) = (0.445_948_490_915_965, 0.091_576_213_509_771);
            let (p1, p2) = (0.111_690_794_839_005, 0.054_975_871_827_661);
            let mut v = orbit3(b, p2);
            v.extend([
                ([a, 1.0 - 2.0 * a], p1),
                ([a, a], p1),
                ([1.0 - 2.0 * a, a], p1),
            ]);
            v
        }
        5 => {
            let (a, b) = (0.470_142_064_105_115, 0.101_286_507_323_456);
            let (p1, p2) = (0.066_197_076_394_253, 0.062_969_590_272_413);
            let mut v = vec![([1.0 / 3.0, 1.0 / 3.0], 9.0 / 80.0)];
            v.extend([
                ([a, a], p1),
                ([1.0 - 2.0 * a, a], p1),
                ([a, 1.0 - 2.0 * a], p1),
            ]);
            v.extend(orbit3(b, p2));
            v
        }
        _ => {
            let (a, b) = (0.063_089_014_491_502, 0.249_286_745_170_91);
            let (c, d) = (0.310_352_451_033_785, 0.053_145_049_844_816);
            let (p1, p2, p3) = (
                0.025_422_453_185_103,
                0.058_393_137_863_189,
                0.041_425_537_809_187,
            );
            let mut v = orbit3(a, p1);
            v.extend(orbit3(b, p2));
            let e = 1.0 - c - d;
            v.extend([
                ([c, d], p3),
                ([d, c], p3),
                ([e, c], p3),
                ([e, d], p3),
                ([c, e], p3),
                ([d, e], p3),
            ]);
            v
        }
    }
}

/// Gauss rule of a cell, exact for polynomials of degree `order`.
pub(crate) fn gauss(kind: SurfaceKind, order: u8) -> Vec<([f64; 2], f64)> {
    let n = (order as usize / 2 + 1).clamp(1, 4);
    match kind {
        SurfaceKind::Seg2 | SurfaceKind::Seg3 => gauss_1d(n)
            .into_iter()
            .map(|(x, w)| ([x, 0.0], w))
            .collect(),
        SurfaceKind::Quad4 | SurfaceKind::Quad8 | SurfaceKind::Quad9 => {
            let g = gauss_1d(n);
            let mut out = Vec::new();
            for &(x, wx) in &g {
                for &(y, wy) in &g {
                    out.push(([x, y], wx * wy));
                }
            }
            out
        }
        SurfaceKind::Tria3 | SurfaceKind::Tria6 | SurfaceKind::Tria7 => match order {
            0 | 1 => vec![([1.0 / 3.0, 1.0 / 3.0], 0.5)],
            2 => vec![
                ([1.0 / 6.0, 1.0 / 6.0], 1.0 / 6.0),
                ([2.0 / 3.0, 1.0 / 6.0], 1.0 / 6.0),
                ([1.0 / 6.0, 2.0 / 3.0], 1.0 / 6.0),
            ],
            _ => {
                // 7-point rule, degree 5.
                let a1 = (6.0 - 15f64.sqrt()) / 21.0;
                let a2 = (6.0 + 15f64.sqrt()) / 21.0;
                let w1 = (155.0 - 15f64.sqrt()) / 2400.0;
                let w2 = (155.0 + 15f64.sqrt()) / 2400.0;
                let b1 = 1.0 - 2.0 * a1;
                let b2 = 1.0 - 2.0 * a2;
                vec![
                    ([1.0 / 3.0, 1.0 / 3.0], 9.0 / 80.0),
                    ([a1, a1], w1),
                    ([b1, a1], w1),
                    ([a1, b1], w1),
                    ([a2, a2], w2),
                    ([b2, a2], w2),
                    ([a2, b2], w2),
                ]
            }
        },
    }
}

/// code_aster's own `SIMPSON` / `NCOTES` rule of `ORDRE_INT` on a cell of
/// `kind` (`mmgaus`), reference coordinates and weights: segments the
/// composite Simpson / closed Newton–Cotes rule, faces their code_aster
/// grids ([`crate::shape::face_simpson`], [`crate::shape::face_newton_cotes`]).
/// `None` for the other rules. Unlike [`integration_points_measured`], no
/// Gauss substitution on quadratic faces: the contact elements interpolate
/// the pressure with every node's function, as code_aster's.
pub(crate) fn closed_rule(kind: SurfaceKind, rule: Integration) -> Option<Vec<([f64; 2], f64)>> {
    match (rule, kind.dim()) {
        (Integration::Simpson(o), 1) => Some(simpson(o.max(1))),
        (Integration::NCotes(o), 1) => Some(newton_cotes(o.clamp(1, 8))),
        (Integration::Simpson(o), _) => crate::shape::face_simpson(kind, o),
        (Integration::NCotes(o), _) => crate::shape::face_newton_cotes(kind, o),
        _ => None,
    }
}

/// Composite Simpson rule on [-1, 1] with `2m` sub-intervals.
fn simpson(m: u8) -> Vec<([f64; 2], f64)> {
    let k = 2 * m as usize;
    let h = 2.0 / k as f64;
    (0..=k)
        .map(|i| {
            let c = if i == 0 || i == k {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            ([-1.0 + i as f64 * h, 0.0], c * h / 3.0)
        })
        .collect()
}

/// Closed Newton–Cotes rule with `order + 1` points on [-1, 1]; the weights
/// are the integrals of the Lagrange polynomials (computed exactly with a
/// Gauss rule of sufficient degree).
fn newton_cotes(order: u8) -> Vec<([f64; 2], f64)> {
    let n = order as usize;
    let xs: Vec<f64> = (0..=n).map(|i| -1.0 + 2.0 * i as f64 / n as f64).collect();
    // 8 Gauss points integrate degree ≤ 15 exactly: enough for order 8.
    let g8 = gauss_legendre_8();
    xs.iter()
        .enumerate()
        .map(|(i, &xi)| {
            let w = g8
                .iter()
                .map(|&(t, wt)| {
                    let l: f64 = xs
                        .iter()
                        .enumerate()
                        .filter(|(j, _)| *j != i)
                        .map(|(_, &xj)| (t - xj) / (xi - xj))
                        .product();
                    l * wt
                })
                .sum();
            ([xi, 0.0], w)
        })
        .collect()
}

fn gauss_legendre_8() -> Vec<(f64, f64)> {
    // The 8-point Gauss–Legendre rule (exact to degree 15).
    const X: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_2,
    ];
    const W: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_3,
    ];
    let mut v = Vec::with_capacity(8);
    for i in 0..4 {
        v.push((-X[i], W[i]));
        v.push((X[i], W[i]));
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn integrate(rule: &[([f64; 2], f64)], f: impl Fn(f64, f64) -> f64) -> f64 {
        rule.iter().map(|(p, w)| w * f(p[0], p[1])).sum()
    }

    #[test]
    fn closed_rules_keep_code_asters_points_on_quadratic_faces() {
        // QUAD8, ORDRE_INT=4: code_aster's 9 × 9 Simpson grid (`mmgaus`),
        // not the Gauss points the node rows substitute there.
        let q = closed_rule(SurfaceKind::Quad8, Integration::Simpson(4)).unwrap();
        assert_eq!(q.len(), 81);
        assert!(q.iter().any(|(p, _)| *p == [-1.0, -1.0]));
        assert!(q.iter().any(|(p, _)| *p == [0.25, -0.75]));
        assert!((integrate(&q, |_, _| 1.0) - 4.0).abs() < 1e-14);
        // Corner weight 1/(9·16), centre-of-subcell weight 16/(9·16).
        let w = |p: [f64; 2]| q.iter().find(|(x, _)| *x == p).unwrap().1;
        assert!((w([-1.0, -1.0]) - 1.0 / 144.0).abs() < 1e-16);
        assert!((w([-0.75, -0.75]) - 16.0 / 144.0).abs() < 1e-16);
        let t = closed_rule(SurfaceKind::Tria6, Integration::NCotes(2)).unwrap();
        assert_eq!(t.len(), 6);
        assert!((integrate(&t, |x, y| x * y) - 1.0 / 24.0).abs() < 1e-14);
        let s = closed_rule(SurfaceKind::Seg3, Integration::Simpson(2)).unwrap();
        assert_eq!(s.len(), 5);
        assert!(closed_rule(SurfaceKind::Quad8, Integration::Gauss(3)).is_none());
        assert!(closed_rule(SurfaceKind::Quad8, Integration::Auto).is_none());
    }

    #[test]
    fn gauss_rules_are_exact_to_their_order() {
        for o in 1..=6u8 {
            let r = gauss(SurfaceKind::Seg2, o);
            let exact = if o % 2 == 0 {
                2.0 / (o as f64 + 1.0)
            } else {
                0.0
            };
            assert!(
                (integrate(&r, |x, _| x.powi(o as i32)) - exact).abs() < 1e-13,
                "order {o}"
            );
        }
        // ∫_T x² dA = 1/12 on the unit triangle; ∫ x y = 1/24.
        let t = gauss(SurfaceKind::Tria3, 2);
        assert!((integrate(&t, |x, _| x * x) - 1.0 / 12.0).abs() < 1e-14);
        let t = gauss(SurfaceKind::Tria3, 5);
        assert!((integrate(&t, |x, y| x * x * y * y) - 1.0 / 180.0).abs() < 1e-14);
        let q = gauss(SurfaceKind::Quad4, 3);
        assert!((integrate(&q, |x, y| x * x * y * y) - 4.0 / 9.0).abs() < 1e-14);
    }

    #[test]
    fn ordre_int_is_code_aster_rank_of_the_gauss_rule() {
        // Segments: ORDRE_INT points, exact to degree 2n − 1.
        for n in 1..=6u8 {
            let r = ordre_int_gauss(SurfaceKind::Seg3, n);
            assert_eq!(r.len(), n as usize);
            for d in 0..(2 * n as i32) {
                let exact = if d % 2 == 0 {
                    2.0 / (d as f64 + 1.0)
                } else {
                    0.0
                };
                assert!(
                    (integrate(&r, |x, _| x.powi(d)) - exact).abs() < 1e-13,
                    "n {n} degree {d}"
                );
            }
            let q = ordre_int_gauss(SurfaceKind::Quad8, n);
            assert_eq!(q.len(), (n * n) as usize);
            let d = 2 * n as i32 - 2;
            let e = 2.0 / (d as f64 + 1.0);
            assert!((integrate(&q, |x, y| x.powi(d) * y.powi(d)) - e * e).abs() < 1e-13);
        }
        // Triangles: 1, 3, 4, 6, 7, 12 points, exact to degree 1 … 6:
        // ∫_T x^a y^b = a! b! / (a + b + 2)!.
        let fact = |k: u32| (1..=k).map(f64::from).product::<f64>();
        for (rank, count) in [(1u8, 1usize), (2, 3), (3, 4), (4, 6), (5, 7), (6, 12)] {
            let t = ordre_int_gauss(SurfaceKind::Tria6, rank);
            assert_eq!(t.len(), count);
            for a in 0..=rank as u32 {
                for b in 0..=(rank as u32 - a) {
                    let exact = fact(a) * fact(b) / fact(a + b + 2);
                    let got = integrate(&t, |x, y| x.powi(a as i32) * y.powi(b as i32));
                    assert!((got - exact).abs() < 1e-13, "rank {rank} x^{a} y^{b}");
                }
            }
        }
    }

    #[test]
    fn simpson_and_newton_cotes_integrate_cubics() {
        for r in [simpson(1), simpson(3), newton_cotes(3), newton_cotes(8)] {
            assert!((integrate(&r, |_, _| 1.0) - 2.0).abs() < 1e-13);
            assert!((integrate(&r, |x, _| x * x * x + x * x) - 2.0 / 3.0).abs() < 1e-13);
        }
        assert!((integrate(&newton_cotes(8), |x, _| x.powi(8)) - 2.0 / 9.0).abs() < 1e-12);
    }
}
