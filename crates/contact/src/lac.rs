//! LAC contact (`ALGO_CONT='LAC'`, code_aster's mortar method on the
//! patches of `CREA_MAILLAGE/DECOUPE_LAC`), 2D.
//!
//! One contact pressure per **patch** (an original slave face): the
//! constraint is the patch's mortar-integrated gap
//!
//! G_P = ∫_{P ∩ master} g dΓ ≥ 0,   λ_P ≥ 0,   λ_P G_P = 0,
//!
//! with g = (x_s − x_m)·n, n the slave normal turned towards the slave
//! body, x_m the orthogonal projection of the slave point on the master
//! cell. The integral is cut at the projections of the master cells'
//! corners onto the slave cell, so every piece sees one master cell and a
//! smooth integrand (4-point Gauss per piece: exact for a flat
//! interface, which is what makes the patch test pass to round-off).
//! Measures are taken on the reference slave geometry (× radius under
//! AXIS), as code_aster's contact elements.
//!
//! The row handed to fem is Σₚ wₚ (linearised gₚ) ≥ 0: its multiplier is
//! the mean contact pressure over the paired part of the patch (LAGS_C is
//! minus it), force = pressure × paired measure.
//!
//! `CONT_ELEM` (per slave cell, the values of its patch): `PRES` (−λ,
//! negative in compression), `JEU` (mean gap G_P / paired measure),
//! `CONT` (1 in contact, 0 not), `COEFSURF` (paired / patch measure, 1
//! when the master covers the patch) and `PRESCOOR` (PRES × COEFSURF).

use std::collections::BTreeMap;

use aster_fem::Dof;
use aster_mesh::{CellId, LacZonePatches, Mesh, NodeId};

use crate::error::ContactError;
use crate::integration::Measure;
use crate::pairing::{jacobian, Pairing};
use crate::rows::contact_row;
use crate::shape::{dot, interpolate, norm, scale, sub};
use crate::surface::ResolvedZone;
use crate::zone::NormalSource;

/// Components of `CONT_ELEM`, in code_aster's names.
pub const CONT_ELEM_COMPONENTS: [&str; 5] = ["PRES", "JEU", "CONT", "COEFSURF", "PRESCOOR"];

/// A patch resolved on a zone: its slave cells (indices into
/// `ResolvedZone::slave`) and pressure nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct LacPatchRef {
    pub cells: Vec<usize>,
    pub pressure_nodes: Vec<NodeId>,
}

/// Resolves DECOUPE_LAC's patches of one slave group on a zone.
pub fn resolve_patches(
    zone: &ResolvedZone,
    patches: &LacZonePatches,
) -> Result<Vec<LacPatchRef>, ContactError> {
    if zone.space_dim != 2 {
        return Err(ContactError::Invalid {
            keyword: "ALGO_CONT",
            message: "ALGO_CONT='LAC' is supported in 2D (D_PLAN, C_PLAN, AXIS) only for now"
                .into(),
        });
    }
    let index: BTreeMap<CellId, usize> = zone
        .slave
        .iter()
        .enumerate()
        .map(|(i, c)| (c.id, i))
        .collect();
    let mut out = Vec::new();
    for p in &patches.patches {
        let cells = p
            .cells
            .iter()
            .map(|c| {
                index.get(c).copied().ok_or_else(|| ContactError::Invalid {
                    keyword: "GROUP_MA_ESCL",
                    message: format!(
                        "a cell of the LAC patches of '{}' is not in the slave surface: \
                         DEFI_CONTACT's GROUP_MA_ESCL must be the group cut by \
                         CREA_MAILLAGE/DECOUPE_LAC",
                        patches.group
                    ),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        out.push(LacPatchRef {
            cells,
            pressure_nodes: p.pressure_nodes.clone(),
        });
    }
    if out.is_empty() {
        return Err(ContactError::Invalid {
            keyword: "GROUP_MA_ESCL",
            message: format!("DECOUPE_LAC made no patch on '{}'", patches.group),
        });
    }
    Ok(out)
}

/// The mortar integrals of one patch on one geometry.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PatchIntegral {
    /// Measure of the whole patch (reference geometry, × r under AXIS).
    pub measure: f64,
    /// Measure of its part paired with a master cell.
    pub paired: f64,
    /// ∫ g over the paired part.
    pub gap: f64,
    /// The linearised constraint Σ w·row (terms and right-hand side).
    pub terms: BTreeMap<Dof, f64>,
    pub rhs: f64,
}

impl PatchIntegral {
    /// Mean gap over the paired part (0 when nothing is paired).
    pub fn mean_gap(&self) -> f64 {
        if self.paired > 0.0 {
            self.gap / self.paired
        } else {
            0.0
        }
    }

    /// COEFSURF: paired part / patch.
    pub fn coverage(&self) -> f64 {
        if self.measure > 0.0 {
            self.paired / self.measure
        } else {
            0.0
        }
    }
}

/// Gauss–Legendre, 4 points on [-1, 1].
const GAUSS4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
    (-0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
];

/// Parameter in [-1, 1] along the chord c0→c1 of the orthogonal projection
/// of `p` on the chord's line.
pub fn chord_parameter(c0: [f64; 3], c1: [f64; 3], p: [f64; 3]) -> f64 {
    let d = sub(c1, c0);
    -1.0 + 2.0 * dot(sub(p, c0), d) / dot(d, d)
}

/// The pieces of [-1, 1] cut at the given parameters (sorted, merged
/// within 1e-12, pieces shorter than 1e-10 dropped).
pub fn pieces(cuts: &[f64]) -> Vec<(f64, f64)> {
    let mut pts: Vec<f64> = vec![-1.0, 1.0];
    pts.extend(cuts.iter().copied().filter(|t| *t > -1.0 && *t < 1.0));
    pts.sort_by(|a, b| a.total_cmp(b));
    pts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    pts.windows(2)
        .filter(|w| w[1] - w[0] > 1e-10)
        .map(|w| (w[0], w[1]))
        .collect()
}

/// Mortar integrals of a patch on the current positions `x`.
pub fn patch_integral(
    mesh: &Mesh,
    zone: &ResolvedZone,
    patch: &LacPatchRef,
    x: &[[f64; 3]],
    measure: Measure,
) -> Result<PatchIntegral, ContactError> {
    let mut out = PatchIntegral::default();
    for &si in &patch.cells {
        let s = &zone.slave[si];
        let xs: Vec<[f64; 3]> = s.nodes.iter().map(|n| x[n.0 as usize]).collect();
        let xref: Vec<[f64; 3]> = s.nodes.iter().map(|n| mesh.coords[n.0 as usize]).collect();
        let (c0, c1) = (xs[0], xs[1]);
        let len_s = norm(sub(c1, c0));
        // Candidate master cells: overlapping the slave chord, facing it,
        // within one cell size.
        let ns_mid = zone.cell_normal(s, [0.0, 0.0], x, NormalSource::Auto)?;
        // code_aster's `lcnorm_line`: the normal of the straight cell
        // through the slave cell's corners, outwards.
        let d = sub(c1, c0);
        let chord_normal = {
            let raw = scale([d[1], -d[0], 0.0], 1.0 / len_s.max(f64::MIN_POSITIVE));
            if dot(raw, ns_mid) < 0.0 {
                scale(raw, -1.0)
            } else {
                raw
            }
        };
        let mut candidates: Vec<(usize, f64, f64)> = Vec::new();
        for (mi, m) in zone.master.iter().enumerate() {
            let (a, b) = (x[m.nodes[0].0 as usize], x[m.nodes[1].0 as usize]);
            let (ta, tb) = (chord_parameter(c0, c1, a), chord_parameter(c0, c1, b));
            let (lo, hi) = (ta.min(tb), ta.max(tb));
            if hi <= -1.0 + 1e-10 || lo >= 1.0 - 1e-10 {
                continue;
            }
            let nm = zone.cell_normal(m, [0.0, 0.0], x, zone.geometry.vect_mait)?;
            if dot(nm, ns_mid) >= 0.0 {
                continue;
            }
            let len_m = norm(sub(b, a));
            let mid = scale([a[0] + b[0], a[1] + b[1], a[2] + b[2]], 0.5);
            let dist = dot(sub(mid, c0), ns_mid).abs();
            if dist > len_s.max(len_m) {
                continue;
            }
            candidates.push((mi, lo, hi));
        }
        let cuts: Vec<f64> = candidates.iter().flat_map(|c| [c.1, c.2]).collect();
        for (a, b) in pieces(&cuts) {
            let half = 0.5 * (b - a);
            for (t, gw) in GAUSS4 {
                let xi = [0.5 * (a + b) + half * t, 0.0];
                let mut w = gw * half * jacobian(s.kind, &xref, xi);
                if measure == Measure::Axisymmetric {
                    let r = interpolate(s.kind, &xref, xi).x[0].abs();
                    w *= if r == 0.0 { 1e-7 } else { r };
                }
                out.measure += w;
                let sp = interpolate(s.kind, &xs, xi);
                let chord_t = chord_parameter(c0, c1, sp.x);
                let normal = scale(slave_normal(zone, si, xi, x, chord_normal)?, -1.0);
                // The nearest master cell hit along the slave normal.
                let mut best: Option<(f64, usize, crate::shape::CellPoint)> = None;
                for &(mi, lo, hi) in &candidates {
                    if chord_t < lo - 1e-9 || chord_t > hi + 1e-9 {
                        continue;
                    }
                    let m = &zone.master[mi];
                    let xm: Vec<[f64; 3]> = m.nodes.iter().map(|n| x[n.0 as usize]).collect();
                    let Some(mp) = ray_projection(m.kind, &xm, sp.x, normal) else {
                        continue;
                    };
                    let d = norm(sub(sp.x, mp.x));
                    if best.as_ref().is_none_or(|b| d < b.0) {
                        best = Some((d, mi, mp));
                    }
                }
                let Some((_, mi, mp)) = best else { continue };
                let m = &zone.master[mi];
                let gap = dot(sub(sp.x, mp.x), normal);
                let pairing = Pairing {
                    master_cell: Some((m.id, mp.xi)),
                    master: m
                        .nodes
                        .iter()
                        .copied()
                        .zip(mp.shape.iter().copied())
                        .collect(),
                    normal,
                    gap,
                    slave_x: sp.x,
                    master_x: mp.x,
                    nearest_master_node: m.nodes[0],
                };
                let slave: Vec<(NodeId, f64)> = s
                    .nodes
                    .iter()
                    .copied()
                    .zip(sp.shape.iter().copied())
                    .collect();
                let row = contact_row(mesh, x, &slave, &pairing, 2, 1.0, 0);
                for (d, c) in row.terms {
                    *out.terms.entry(d).or_default() += w * c;
                }
                out.rhs += w * row.rhs;
                out.paired += w;
                out.gap += w * gap;
            }
        }
    }
    Ok(out)
}

/// Outward normal of slave cell `si` at `xi`: the chord normal, or with
/// `LISSAGE='OUI'` the slave nodal normals (averaged over the cells around
/// each node) interpolated in the cell — a continuous normal field.
fn slave_normal(
    zone: &ResolvedZone,
    si: usize,
    xi: [f64; 2],
    x: &[[f64; 3]],
    chord_normal: [f64; 3],
) -> Result<[f64; 3], ContactError> {
    if !zone.geometry.lissage {
        return Ok(chord_normal);
    }
    let cell = &zone.slave[si];
    let (shape, _) = cell.kind.eval(xi);
    let mut sum = [0.0; 3];
    for (node, w) in cell.nodes.iter().zip(shape) {
        let n = zone.nodal_normal(*node, false, x)?;
        for c in 0..3 {
            sum[c] += w * n[c];
        }
    }
    let l = norm(sum);
    Ok(if l > 1e-12 {
        scale(sum, 1.0 / l)
    } else {
        chord_normal
    })
}

/// The point of a master segment on the line through `p` along `n` (the
/// mortar projection along the slave normal): Newton on
/// t·(x_m(η) − p) = 0 with t ⟂ n. `None` if the segment is parallel to
/// `n` or the point falls outside it (beyond 1e-6 in reference
/// coordinates).
pub fn ray_projection(
    kind: crate::shape::SurfaceKind,
    nodes: &[[f64; 3]],
    p: [f64; 3],
    n: [f64; 3],
) -> Option<crate::shape::CellPoint> {
    let t = [-n[1], n[0], 0.0];
    let mut eta = 0.0;
    for _ in 0..30 {
        let cp = interpolate(kind, nodes, [eta, 0.0]);
        let f = dot(sub(cp.x, p), t);
        let df = dot(cp.tangents[0], t);
        if df.abs() < 1e-300 {
            return None;
        }
        let step = f / df;
        eta -= step;
        if step.abs() < 1e-14 {
            break;
        }
    }
    let cp = interpolate(kind, nodes, [eta, 0.0]);
    (eta.is_finite() && kind.outside_distance(cp.xi) <= 1e-6).then_some(cp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_projection_follows_the_normal_not_the_perpendicular() {
        use crate::shape::SurfaceKind;
        // Master segment y = 0 from x = 0 to 2; a point above at (0.5, 1)
        // cast along a normal tilted by 45°: lands at x = 1.5.
        let nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let cp = ray_projection(SurfaceKind::Seg2, &nodes, [0.5, 1.0, 0.0], [-s, s, 0.0]).unwrap();
        assert!(
            (cp.x[0] - 1.5).abs() < 1e-14 && cp.x[1].abs() < 1e-14,
            "{:?}",
            cp.x
        );
        // Beyond the segment's end: none.
        assert!(ray_projection(SurfaceKind::Seg2, &nodes, [2.5, 1.0, 0.0], [-s, s, 0.0]).is_none());
    }

    #[test]
    fn chord_parameter_spans_minus_one_to_one() {
        let (a, b) = ([0.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        assert_eq!(chord_parameter(a, b, a), -1.0);
        assert_eq!(chord_parameter(a, b, b), 1.0);
        assert_eq!(chord_parameter(a, b, [0.5, 3.0, 0.0]), -0.5);
    }

    #[test]
    fn pieces_cut_at_inner_parameters_only() {
        assert_eq!(pieces(&[]), vec![(-1.0, 1.0)]);
        assert_eq!(
            pieces(&[-3.0, 0.25, 0.25 + 1e-14, 2.0]),
            vec![(-1.0, 0.25), (0.25, 1.0)]
        );
        let p = pieces(&[-0.5, 0.5, -0.5]);
        assert_eq!(p, vec![(-1.0, -0.5), (-0.5, 0.5), (0.5, 1.0)]);
    }
}
