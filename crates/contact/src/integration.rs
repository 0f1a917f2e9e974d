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
            (Integration::Gauss(o), k) => gauss(k, o),
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
    fn simpson_and_newton_cotes_integrate_cubics() {
        for r in [simpson(1), simpson(3), newton_cotes(3), newton_cotes(8)] {
            assert!((integrate(&r, |_, _| 1.0) - 2.0).abs() < 1e-13);
            assert!((integrate(&r, |x, _| x * x * x + x * x) - 2.0 / 3.0).abs() < 1e-13);
        }
        assert!((integrate(&newton_cotes(8), |x, _| x.powi(8)) - 2.0 / 9.0).abs() < 1e-12);
    }
}
