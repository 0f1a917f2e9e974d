//! LAC contact (`ALGO_CONT='LAC'`, code_aster's mortar method on the
//! patches of `CREA_MAILLAGE/DECOUPE_LAC`), 2D and 3D.
//!
//! One contact pressure λ per **patch** (an original slave face), the
//! constraint being the patch's mortar-integrated gap (code_aster's
//! `lac_gapi`, `mmmbca_lac`, `lcvect`):
//!
//! G_P = Σ_pairs ∫_{slave ∩ master} d dΓ ≥ 0,  λ_P ≥ 0,  λ_P G_P = 0,
//!
//! d the distance from the slave point to the master cell along the slave
//! normal (positive apart). Pairs, their intersection polygons and the
//! integration points are code_aster's (module `lac_mortar`). The gap's
//! measure is taken on the current positions (`gapint` measures on the
//! updated geometry); the force on each side is λ Σ w J₀ N n with each
//! side's own normal and integration points, J₀ on the reference
//! positions (`TYPE_JACOBIEN='INITIAL'`, the default).
//!
//! fem's row for a patch is `a·u ≤ b` with `a` the force direction above
//! (the force is −λ a) and `b = a·u⁰ + G_P(u⁰)`: at the fixed point of the
//! geometric loop, G_P = 0 on active patches — code_aster's converged
//! Newton state, whose tangent is the same approximation of ∂G_P.
//! A patch gets a row only if its paired measure exceeds 1e-8 and covers
//! at least 1e-5 of its (paired) cells (code_aster's `tole_inter`).
//!
//! `CONT_ELEM` (per slave cell, its patch's values): `PRES` (LAGS_C = −λ),
//! `JEU` (mean gap G_P / paired measure, −1 without pairing), `CONT`
//! (1 contact, 0 not, −1 not paired), `COEFSURF` (paired measure over the
//! measure of the patch's cells that face a master cell, `clpoma`) and
//! `PRESCOOR` (COEFSURF × PRES).

use std::collections::BTreeMap;

use aster_fem::{Comp, Dof, InequalityRow};
use aster_mesh::{CellId, LacZonePatches, Mesh, NodeId};

use crate::error::ContactError;
use crate::lac_mortar::{
    cell_measure, gap_integral, intersect, master_images, pair_force, ForceCells, MortarCell,
    MortarPair, PAIR_TOLE,
};
use crate::shape::{dot, sub};
use crate::surface::{ResolvedZone, SurfaceCell};

/// Components of `CONT_ELEM`, in code_aster's names.
pub const CONT_ELEM_COMPONENTS: [&str; 5] = ["PRES", "JEU", "CONT", "COEFSURF", "PRESCOOR"];

/// Smallest coverage of a patch in contact (code_aster's `tole_inter`).
pub const TOLE_INTER: f64 = 1e-5;

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

/// What one pairing gives a patch (code_aster's `.WPAT`, `.POID`, `.GAPI`
/// × `.POID`, `.NMCP`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PatchState {
    /// Measure of the patch's cells that face some master cell (`clpoma`).
    pub measure: f64,
    /// Measure of the intersections (Σ w·J, × r under AXIS).
    pub paired: f64,
    /// ∫ d over the intersections (positive apart).
    pub gap: f64,
    /// Number of pairs (contact elements) of the patch.
    pub pairs: usize,
}

impl PatchState {
    /// No intersection worth the name (code_aster's NaN gap).
    pub fn unpaired(&self) -> bool {
        self.paired <= PAIR_TOLE
    }

    /// Mean gap (`JEU`), −1 when unpaired.
    pub fn mean_gap(&self) -> f64 {
        if self.unpaired() {
            -1.0
        } else {
            self.gap / self.paired
        }
    }

    /// COEFSURF: paired measure over the patch's paired cells' measure.
    pub fn coverage(&self) -> f64 {
        if self.unpaired() || self.measure <= 0.0 {
            0.0
        } else {
            self.paired / self.measure
        }
    }

    /// Whether the patch may be in contact (gets a row).
    pub fn can_touch(&self) -> bool {
        !self.unpaired() && self.coverage() >= TOLE_INTER
    }
}

/// The zone keywords of LAC (`TYPE_JACOBIEN`, `RESI_APPA`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LacOptions {
    /// `TYPE_JACOBIEN='ACTUALISE'`: the force's measures on the current
    /// geometry (default `'INITIAL'`: on the reference one).
    pub updated_jacobian: bool,
    /// `RESI_APPA`: tolerance of the pairing (default 1e-8).
    pub resi_appa: f64,
}

impl Default for LacOptions {
    fn default() -> Self {
        LacOptions {
            updated_jacobian: false,
            resi_appa: PAIR_TOLE,
        }
    }
}

/// A LAC zone: its patches, the pairs and patch values of the last
/// pairing, and the patch pressures of the last converged step.
#[derive(Clone, Debug)]
pub struct LacZone {
    pub patches: Vec<LacPatchRef>,
    patch_of: Vec<Option<usize>>,
    pub pairs: Vec<MortarPair>,
    pub state: Vec<PatchState>,
    /// Pairs code_aster would drop with an alarm (CONTACT4_6).
    pub abandoned: usize,
    /// λ ≥ 0 per patch (LAGS_C = −λ).
    pub pressures: Vec<f64>,
    /// AXIS: measures × r.
    pub axis: bool,
    /// `TYPE_JACOBIEN='ACTUALISE'`.
    pub updated_jacobian: bool,
    /// `RESI_APPA`: tolerance of the pairing.
    pub tole: f64,
}

/// Positions of a cell's nodes.
fn positions(cell: &SurfaceCell, x: &[[f64; 3]]) -> Vec<[f64; 3]> {
    cell.nodes.iter().map(|n| x[n.0 as usize]).collect()
}

/// In-plane bounding boxes of two cells do not overlap (a master cell
/// that cannot intersect the slave cell whatever its distance).
fn apart_in_plane(slave: &[[f64; 3]], master: &[[f64; 3]], dim: usize) -> bool {
    let c = slave[0];
    let (e1, e2) = if dim == 2 {
        let t = sub(slave[1], slave[0]);
        (t, [0.0; 3])
    } else {
        let t1 = sub(slave[1], slave[0]);
        let t2 = sub(slave[2], slave[0]);
        let n = crate::shape::cross(t1, t2);
        (t1, crate::shape::cross(n, t1))
    };
    let span = |pts: &[[f64; 3]], e: [f64; 3]| {
        let l = dot(e, e).sqrt();
        if l == 0.0 {
            return (0.0, 0.0);
        }
        pts.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            let s = dot(sub(*p, c), e) / l;
            (lo.min(s), hi.max(s))
        })
    };
    let axes: &[[f64; 3]] = if dim == 2 { &[e1] } else { &[e1, e2] };
    axes.iter().any(|&e| {
        let (a, b) = (span(slave, e), span(master, e));
        let margin = 1e-6 * ((a.1 - a.0).abs() + (b.1 - b.0).abs());
        a.1 + margin < b.0 || b.1 + margin < a.0
    })
}

impl LacZone {
    pub fn new(zone: &ResolvedZone, patches: &LacZonePatches) -> Result<Self, ContactError> {
        let patches = resolve_patches(zone, patches)?;
        let mut patch_of = vec![None; zone.slave.len()];
        for (k, p) in patches.iter().enumerate() {
            for &c in &p.cells {
                patch_of[c] = Some(k);
            }
        }
        Ok(LacZone {
            pressures: vec![0.0; patches.len()],
            state: vec![PatchState::default(); patches.len()],
            patches,
            patch_of,
            pairs: Vec::new(),
            abandoned: 0,
            axis: false,
            updated_jacobian: false,
            tole: PAIR_TOLE,
        })
    }

    /// Pairs the zone on the positions `x` and integrates every patch's gap
    /// (code_aster's `aplcpg` then `lac_gapi`).
    pub fn pair(&mut self, zone: &ResolvedZone, x: &[[f64; 3]]) {
        let dim = zone.space_dim;
        self.pairs.clear();
        self.abandoned = 0;
        self.state = vec![PatchState::default(); self.patches.len()];
        let masters: Vec<Vec<[f64; 3]>> = zone.master.iter().map(|m| positions(m, x)).collect();
        for (si, s) in zone.slave.iter().enumerate() {
            let Some(k) = self.patch_of[si] else { continue };
            let xs = positions(s, x);
            let sc = MortarCell {
                kind: s.kind,
                x: &xs,
                sign: s.sign,
            };
            let mut faced = false;
            for (mi, m) in zone.master.iter().enumerate() {
                let xm = &masters[mi];
                if apart_in_plane(&xs, xm, dim) {
                    continue;
                }
                let mc = MortarCell {
                    kind: m.kind,
                    x: xm,
                    sign: m.sign,
                };
                let inter = match intersect(sc, mc, self.tole) {
                    Ok(i) => i,
                    Err(()) => {
                        self.abandoned += 1;
                        continue;
                    }
                };
                if inter.weight <= self.tole {
                    continue;
                }
                faced = true;
                let Some((master_points, gauss_master)) =
                    master_images(sc, mc, &inter.points, self.tole)
                else {
                    self.abandoned += 1;
                    continue;
                };
                let pair = MortarPair {
                    slave: si,
                    master: mi,
                    slave_points: inter.points,
                    master_points,
                    gauss_master,
                };
                let (gap, w) = gap_integral(sc, mc, &pair, self.axis);
                let st = &mut self.state[k];
                st.gap -= gap;
                st.paired += w;
                st.pairs += 1;
                self.pairs.push(pair);
            }
            if faced {
                self.state[k].measure += cell_measure(sc);
            }
        }
    }

    /// The rows of the patches that may touch (id = patch index), for the
    /// pairs of the last [`LacZone::pair`] on the same positions `x`.
    /// `smooth`: exterior nodal normals (LISSAGE='OUI') by node.
    pub fn rows(
        &self,
        mesh: &Mesh,
        zone: &ResolvedZone,
        x: &[[f64; 3]],
        smooth: Option<&BTreeMap<NodeId, [f64; 3]>>,
    ) -> Vec<InequalityRow> {
        let comps = Comp::translations(zone.space_dim);
        let mut acc: Vec<BTreeMap<Dof, f64>> = vec![BTreeMap::new(); self.patches.len()];
        for pair in &self.pairs {
            let Some(k) = self.patch_of[pair.slave] else {
                continue;
            };
            if !self.state[k].can_touch() {
                continue;
            }
            let (s, m) = (&zone.slave[pair.slave], &zone.master[pair.master]);
            let (xs, xm) = (positions(s, x), positions(m, x));
            let (rs, rm) = (positions(s, &mesh.coords), positions(m, &mesh.coords));
            let normals = |c: &SurfaceCell| -> Option<Vec<[f64; 3]>> {
                let map = smooth?;
                c.nodes.iter().map(|n| map.get(n).copied()).collect()
            };
            let (ns, nm) = (normals(s), normals(m));
            let cells = ForceCells {
                slave: MortarCell {
                    kind: s.kind,
                    x: &xs,
                    sign: s.sign,
                },
                slave_ref: MortarCell {
                    kind: s.kind,
                    x: &rs,
                    sign: s.sign,
                },
                master: MortarCell {
                    kind: m.kind,
                    x: &xm,
                    sign: m.sign,
                },
                master_ref: MortarCell {
                    kind: m.kind,
                    x: &rm,
                    sign: m.sign,
                },
                slave_normals: ns.as_deref(),
                master_normals: nm.as_deref(),
                axis: self.axis,
                updated_jacobian: self.updated_jacobian,
            };
            let f = pair_force(&cells, pair);
            for (nodes, vals) in [(&s.nodes, &f.slave), (&m.nodes, &f.master)] {
                for (node, v) in nodes.iter().zip(vals) {
                    for (c, comp) in comps.iter().enumerate() {
                        if v[c] != 0.0 {
                            *acc[k].entry(Dof::new(*node, *comp)).or_default() += v[c];
                        }
                    }
                }
            }
        }
        let mut rows = Vec::new();
        for (k, terms) in acc.into_iter().enumerate() {
            if terms.is_empty() {
                continue;
            }
            // Round-off terms (1e-12 of the largest) come and go between
            // pairings; drop them so that a settled geometry repeats its rows.
            let big = terms.values().fold(0.0_f64, |a, c| a.max(c.abs()));
            let terms: Vec<(Dof, f64)> = terms
                .into_iter()
                .filter(|(_, c)| c.abs() > 1e-12 * big)
                .collect();
            let au: f64 = terms
                .iter()
                .map(|(d, c)| {
                    let i = d.node.0 as usize;
                    let j = match d.comp {
                        Comp::DX => 0,
                        Comp::DY => 1,
                        _ => 2,
                    };
                    c * (x[i][j] - mesh.coords[i][j])
                })
                .sum();
            rows.push(InequalityRow::new(terms, au + self.state[k].gap, k));
        }
        rows
    }

    /// code_aster's contact status of a patch: 1 when LAGS_C + JEU ≤ 0
    /// with enough coverage, 0 otherwise, −1 unpaired.
    pub fn status(&self, k: usize) -> f64 {
        let st = &self.state[k];
        if st.unpaired() {
            return -1.0;
        }
        let lagc = -self.pressures.get(k).copied().unwrap_or(0.0);
        if lagc + st.mean_gap() <= f64::EPSILON && st.coverage() >= TOLE_INTER {
            1.0
        } else {
            0.0
        }
    }

    /// `CONT_ELEM`: per slave cell of every patch, its patch's values.
    pub fn cont_elem(&self, zone: &ResolvedZone) -> Vec<(CellId, [f64; 5])> {
        let mut out = Vec::new();
        for (k, p) in self.patches.iter().enumerate() {
            let st = &self.state[k];
            let lagc = match self.pressures.get(k) {
                Some(&l) if l > 0.0 => -l,
                _ => 0.0,
            };
            let coef = st.coverage();
            let vals = [lagc, st.mean_gap(), self.status(k), coef, coef * lagc];
            for &c in &p.cells {
                out.push((zone.slave[c].id, vals));
            }
        }
        out
    }

    /// LAGS_C (= −λ) on every pressure node.
    pub fn lags_c(&self) -> Vec<(NodeId, f64)> {
        let mut out = BTreeMap::new();
        for (k, p) in self.patches.iter().enumerate() {
            let v = match self.pressures.get(k) {
                Some(&l) if l > 0.0 => -l,
                _ => 0.0,
            };
            for n in &p.pressure_nodes {
                out.insert(*n, v);
            }
        }
        out.into_iter().collect()
    }
}
