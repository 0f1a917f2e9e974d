//! code_aster 17's mortar contact of `DEFI_CONT` (`MECA_NON_LINE`),
//! `ALGO_CONT='LAGRANGIEN'`, `VARIANTE='ROBUSTE'` (Poulios & Renard's
//! augmented Lagrangian), frictionless, in 2D on SEG2/SEG3 cells and in 3D
//! on faces, as a fem force source with the slave nodes' contact pressures
//! (`LAGS_C`) as unknowns.
//!
//! In 3D (`new(…, 3)`) the pairing and the polygons' quadrature are
//! `mortar_pairing3d`'s; at a point the outward slave normal is
//! t₁ × t₂ / |t₁ × t₂| (`apnorm`), the master point is found along it on
//! the full master face (`mmnewd`), the weights carry the slave face's
//! initial |t₁ × t₂| (`mmmjac`), and the multipliers are P1 on the slave
//! faces' corners (`shapeFuncLagr`: TRIA3 or QUAD4 functions, also on
//! TRIA6, QUAD8, QUAD9 faces).
//!
//! As code_aster's (2025 main: `laVect_ct_pr`, `laElemCont`,
//! `contact_module`, `getQuadCont`, `mesh_pairing_module`):
//!
//! - **Pairing** (`cellInteProj`, `addPoinInte2D`, `inteCellChck`), on the
//!   cells linearised on their ends: the slave ends are cast along the
//!   (full) slave cell's normal there onto the master's end-to-end line; the overlap, in the master's parametric space, is
//!   mapped back linearly into the slave's. A pair is kept when its length
//!   (slave parametric) exceeds `PAIR_TOLE` = 1e-8, the cells are not
//!   orthogonal (|n_s·n_m| > 1e-8), the projected edge keeps its direction
//!   and the master faces the slave. Pairs are searched over every master
//!   cell of the zone (code_aster walks neighbours from the closest cell:
//!   the same pairs on a connected master surface). `COEF_MULT_APPA` > 0
//!   skips master cells whose centre is farther than 2 × ratio × the larger
//!   diameter.
//! - **Quadrature** (`getQuadCont`, `lcptga`): FPG3 (both cells SEG2) or
//!   FPG4 on the intersection segment in slave parametric space; weights are the slave Jacobian on
//!   the **initial** coordinates (× the initial radius in AXIS).
//! - **At a point** (`laElemCont`, `projQpSl2Ma`): n_s the outward slave
//!   normal on the current geometry; the master point by ray tracing along
//!   n_s (exact on a SEG2 master, `shape::project_along` on a SEG3 one,
//!   code_aster's `mmnewd`); the gap g = −(x_s − x_m)·n_s; λ and the
//!   coefficient interpolated with the slave's functions; γ = COEF_CONT / h_F with h_F the slave
//!   cell's initial diameter. Active (H = 1) when λ + γg ≤ 0.
//! - **Residual** (`laVect_ct_pr`): on the displacements −w λ n_s·(v_s −
//!   v_m) at active points; on each multiplier w ([λ + γg]₋ − λ)/γ μ.
//! - Slave nodes of no paired cell: λ = 0 (code_aster's POI1 elements).
//! - `SANS_GROUP_NO` / `SANS_GROUP_MA` remove the slave cells holding those
//!   nodes (`MeshPairing::initObjects`); the slave nodes are those of the
//!   remaining cells.
//! - `CONTACT_INIT` (`ContactComputation::contactData`): at the first
//!   pairing of the computation only, 'OUI' makes every point active and
//!   'NON' every point inactive; later, and with 'INTERPENETRE', the status
//!   follows λ + γg.
//! - `ALGO_RESO_GEOM='NEWTON'`: the pairing and normals are those of the
//!   iterate (code_aster pairs before every Newton iteration); the tangent
//!   is code_aster's analytic one (`laMatr_ct_pr`): the slave normal
//!   turning, the master point sliding and the full derivative of the gap
//!   (`mortar_tangent::linearise` on segments, `linearise_3d` on faces),
//!   the intersections held (code_aster ignores their motion too).
//! - MECA_NON_LINE's line search (`ForceSource::evaluate_on_pairing`):
//!   the trial residuals keep the pairs, normals and master points of the
//!   iteration's start, the gaps on the trial positions
//!   (`mortar_point::on_current`), as code_aster 17 does not pair again.

use std::collections::HashMap;

use aster_fem::{Comp, Contribution, FemError, ForceSource, State, Unknown};
use aster_mesh::{Mesh, NodeId};

use crate::error::ContactError;
use crate::mortar_pairing3d::{self, Face};
use crate::mortar_tangent::FaceDof;
use crate::shape::{dot, interpolate, norm, sub, SurfaceKind};
use crate::source::current_positions;
use crate::surface::{ResolvedZone, SurfaceCell};
use crate::zone::ZoneGeometry;

/// code_aster's pairing tolerance (`ContactPairing::compute`).
const PAIR_TOLE: f64 = 1e-8;

/// `CONTACT_INIT` of a DEFI_CONT zone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum InitialState {
    /// `'INTERPENETRE'` (the default): the status follows λ + γg.
    #[default]
    Interpenetrated,
    /// `'NON'`: no point active at the first pairing.
    No,
    /// `'OUI'`: every point active at the first pairing.
    Yes,
}

impl InitialState {
    /// The status `CONTACT_INIT` imposes on a point at the first pairing
    /// (`None`: the status follows the point's own test, as after the
    /// first pairing).
    pub(crate) fn forced(self, first_pairing: bool) -> Option<bool> {
        match (first_pairing, self) {
            (true, InitialState::No) => Some(false),
            (true, InitialState::Yes) => Some(true),
            _ => None,
        }
    }
}

/// One zone of a mortar Lagrangian definition.
#[derive(Clone, Debug)]
pub struct MortarZoneDef {
    pub master_group: String,
    pub slave_group: String,
    pub excluded_node_groups: Vec<String>,
    pub excluded_cell_groups: Vec<String>,
    /// `COEF_CONT` (default 100).
    pub coef_cont: f64,
    pub contact_init: InitialState,
    /// `TYPE_CONT='BILATERAL'`: every paired point active at every
    /// iteration, whatever the sign of λ + γg (`laElemCont`, `niElemCont`:
    /// H = 1, projRm = λ + γg); `CONTACT_INIT` then plays no part.
    pub bilateral: bool,
    /// `COEF_MULT_APPA` when positive.
    pub dist_ratio: Option<f64>,
    /// `FROTTEMENT='OUI'`: the zone's `TYPE_FROT` (module
    /// [`crate::mortar_friction`]); `None`: frictionless.
    pub friction: Option<crate::mortar_friction::FrictionLaw>,
    /// `COEF_FROT` (default 100): the friction coefficient of the
    /// CLASSIQUE variant ([`crate::mortar_classique`]); ROBUSTE uses
    /// `COEF_CONT` for both.
    pub coef_frot: f64,
}

impl MortarZoneDef {
    pub fn new(master: impl Into<String>, slave: impl Into<String>) -> Self {
        MortarZoneDef {
            master_group: master.into(),
            slave_group: slave.into(),
            excluded_node_groups: Vec::new(),
            excluded_cell_groups: Vec::new(),
            coef_cont: 100.0,
            contact_init: InitialState::Interpenetrated,
            bilateral: false,
            dist_ratio: None,
            friction: None,
            coef_frot: 100.0,
        }
    }
}

#[derive(Clone, Debug)]
pub(crate) struct Seg {
    pub(crate) kind: SurfaceKind,
    /// SEG2: its two nodes; SEG3: its ends, then its middle node.
    pub(crate) nodes: Vec<NodeId>,
    pub(crate) sign: f64,
}

impl Seg {
    pub(crate) fn positions(&self, x: &[[f64; 3]]) -> Vec<[f64; 3]> {
        self.nodes.iter().map(|n| x[n.0 as usize]).collect()
    }

    /// The nodes carrying a multiplier: all of a segment's (P1 on SEG2, P2
    /// on SEG3), a face's corners (`shapeFuncLagr`: TR3 or QU4 functions).
    pub(crate) fn lagr_nodes(&self) -> &[NodeId] {
        if self.kind.dim() == 2 {
            &self.nodes[..self.kind.corner_count()]
        } else {
            &self.nodes
        }
    }

    /// The multipliers' functions at `xi` (`shapeFuncLagr`), given the
    /// displacement's `shape` there.
    pub(crate) fn lagr_shape(&self, xi: [f64; 2], shape: &[f64]) -> Vec<f64> {
        if self.kind.dim() == 2 && self.kind.node_count() > self.kind.corner_count() {
            crate::lac_mortar::linear_kind(self.kind).eval(xi).0
        } else {
            shape.to_vec()
        }
    }
}

/// Outward unit normal of a (possibly curved) segment at ξ (`apnorm`).
pub(crate) fn normal_at(kind: SurfaceKind, x: &[[f64; 3]], xi: f64, sign: f64) -> Option<[f64; 3]> {
    let t = interpolate(kind, x, [xi, 0.0]).tangents[0];
    let raw = [t[1], -t[0], 0.0];
    let l = norm(raw);
    (l > 0.0 && l.is_finite()).then(|| [sign * raw[0] / l, sign * raw[1] / l, 0.0])
}

#[derive(Clone, Debug)]
pub(crate) struct MZone {
    pub(crate) slave: Vec<Seg>,
    pub(crate) master: Vec<Seg>,
    pub(crate) coef: f64,
    pub(crate) init: InitialState,
    /// `TYPE_CONT='BILATERAL'` ([`MortarZoneDef::bilateral`]).
    pub(crate) bilateral: bool,
    dist_ratio: Option<f64>,
    /// Initial diameter and the FPG weights' Jacobian data of each slave cell.
    pub(crate) h: Vec<f64>,
}

impl MZone {
    /// The status imposed on every point of the zone: always active when
    /// bilateral, else what `CONTACT_INIT` imposes at the first pairing
    /// (`None`: the point's own test, Heaviside(−(λ + γg))).
    pub(crate) fn forced(&self, first_pairing: bool) -> Option<bool> {
        if self.bilateral {
            Some(true)
        } else {
            self.init.forced(first_pairing)
        }
    }
}

/// A pair: slave cell, master cell, intersection in slave parametric space
/// (2D: a segment `xi`; 3D: a polygon `poly`, module `mortar_pairing3d`).
#[derive(Clone, Debug)]
pub(crate) struct Pair {
    pub(crate) zone: usize,
    pub(crate) slave: usize,
    pub(crate) master: usize,
    pub(crate) xi: [f64; 2],
    pub(crate) poly: Vec<[f64; 2]>,
}

/// The mortar contact of a DEFI_CONT, as a fem force source.
#[derive(Clone, Debug)]
pub struct MortarLagrangian {
    pub(crate) zones: Vec<MZone>,
    pub(crate) lagr: Vec<NodeId>,
    pub(crate) lagr_of: HashMap<NodeId, usize>,
    pub(crate) axis: bool,
    /// Space dimension of the model (2, or 3: faces, `mortar_pairing3d`).
    pub(crate) dim: usize,
    /// No pairing has been made yet (CONTACT_INIT applies).
    pub(crate) first_pairing: bool,
    /// Whether the first pairing has been consumed by a Newton iteration.
    iterations: usize,
    /// Number of paired slave cells at the last evaluation.
    paired: usize,
    /// MECA_NON_LINE's `CONTACT/RESI_GEOM` (shared with the frictional
    /// sources built on this one).
    pub(crate) resi_geom: ResiGeom,
}

/// code_aster 17's geometric criterion (MECA_NON_LINE's `CONTACT/RESI_GEOM`,
/// `ConvergenceManager.evalGeometricResidual`), whatever `ALGO_CONT`: an
/// iterate is accepted only when the displacement increment of the solve
/// that led to it (from the converged state for the first one: the imposed
/// values included, as code_aster's primal increment), max |ΔDX|, |ΔDY|,
/// |ΔDZ| over the nodes, is at most `tol` × the diagonal of the mesh's
/// bounding box.
#[derive(Clone, Debug)]
pub(crate) struct ResiGeom {
    /// `None`: no geometric criterion.
    pub(crate) tol: Option<f64>,
    diagonal: f64,
    /// The displacement of the last iterate (or of the converged state at
    /// the start of the increment).
    last: Vec<f64>,
}

impl ResiGeom {
    pub(crate) fn new(mesh: &Mesh) -> Self {
        ResiGeom {
            tol: None,
            diagonal: aster_mesh::box_diagonal(aster_mesh::bounding_box(
                mesh.coords.iter().copied(),
            )),
            last: Vec::new(),
        }
    }

    /// At the start of an increment: the converged state.
    pub(crate) fn begin(&mut self, state: &State) {
        self.last = state.displacement.to_vec();
    }

    /// After a solve: whether its increment passes the criterion.
    pub(crate) fn accept(&mut self, state: &State) -> bool {
        let u = state.displacement;
        let mut increment = 0.0f64;
        for (i, v) in u.iter().enumerate() {
            if matches!(state.dofs.dof(i).comp, Comp::DX | Comp::DY | Comp::DZ) {
                let before = self.last.get(i).copied().unwrap_or(0.0);
                increment = increment.max((v - before).abs());
            }
        }
        self.last = u.to_vec();
        match self.tol {
            Some(tol) if self.diagonal > 0.0 => increment / self.diagonal <= tol,
            _ => true,
        }
    }
}

pub(crate) fn err(e: ContactError) -> FemError {
    FemError::Source(format!("DEFI_CONT: {e}"))
}

/// Outward unit normal of a segment (2D) on positions `a` → `b`.
fn seg_normal(a: [f64; 3], b: [f64; 3], sign: f64) -> Option<[f64; 3]> {
    // Tangent dx/dξ = (b − a)/2; code_aster's 2D normal (t_y, −t_x)
    // oriented out of the body.
    let t = [(b[0] - a[0]) / 2.0, (b[1] - a[1]) / 2.0, 0.0];
    let raw = [t[1], -t[0], 0.0];
    let l = norm(raw);
    (l > 0.0 && l.is_finite()).then(|| [sign * raw[0] / l, sign * raw[1] / l, 0.0])
}

fn lerp(a: [f64; 3], b: [f64; 3], xi: f64) -> [f64; 3] {
    let (na, nb) = ((1.0 - xi) / 2.0, (1.0 + xi) / 2.0);
    [
        na * a[0] + nb * b[0],
        na * a[1] + nb * b[1],
        na * a[2] + nb * b[2],
    ]
}

/// The parameter ξ ∈ ℝ of the point of line a–b hit by the ray p + t·v
/// (`poinProjByVect` on a SEG2: exact in one Newton step).
pub(crate) fn ray_hit(p: [f64; 3], v: [f64; 3], a: [f64; 3], b: [f64; 3]) -> Option<f64> {
    // a + s(b − a) = p + t v, s = (1 + ξ)/2.
    let e = sub(b, a);
    let det = e[0] * (-v[1]) - e[1] * (-v[0]);
    if det.abs() <= f64::EPSILON * (norm(e) * norm(v)).max(f64::MIN_POSITIVE) {
        return None;
    }
    let r = sub(p, a);
    let s = (r[0] * (-v[1]) - r[1] * (-v[0])) / det;
    Some(2.0 * s - 1.0)
}

/// Why a contact cell kind is not reproduced in dimension `dim`, if it is not.
fn unsupported_kind(dim: usize, kind: SurfaceKind) -> Option<&'static str> {
    if dim == 3 {
        (!matches!(
            kind,
            SurfaceKind::Tria3
                | SurfaceKind::Quad4
                | SurfaceKind::Tria6
                | SurfaceKind::Quad8
                | SurfaceKind::Quad9
        ))
        .then_some(
            "in 3D it is reproduced on TRIA3, TRIA6, QUAD4, QUAD8 and QUAD9 faces (code_aster's pairing has no TRIA7)",
        )
    } else {
        (!matches!(kind, SurfaceKind::Seg2 | SurfaceKind::Seg3))
            .then_some("it is reproduced on segments (2D)")
    }
}

impl MortarLagrangian {
    /// The contact of `zones` on `mesh` for a model of dimension `dim`: 2
    /// (segments; `axis`: AXIS weights) or 3 (TRIA3, TRIA6, QUAD4, QUAD8 and
    /// QUAD9 faces).
    pub fn new(
        zones: &[MortarZoneDef],
        mesh: &Mesh,
        axis: bool,
        dim: usize,
    ) -> Result<Self, ContactError> {
        let dim = if dim >= 3 { 3 } else { 2 };
        let mut out = Vec::new();
        let mut lagr = Vec::new();
        let mut lagr_of = HashMap::new();
        for (i, z) in zones.iter().enumerate() {
            let geometry = ZoneGeometry::new(z.master_group.clone(), z.slave_group.clone());
            let resolved = ResolvedZone::new_in(i, &geometry, mesh, dim)?;
            let segs =
                |cells: &[SurfaceCell], key: &'static str| -> Result<Vec<Seg>, ContactError> {
                    cells
                        .iter()
                        .map(|c| {
                            if let Some(hint) = unsupported_kind(dim, c.kind) {
                                return Err(ContactError::Unsupported {
                                    feature: format!(
                                        "{} cells in {key} (code_aster 17's mortar contact{})",
                                        c.kind.cell_type().name(),
                                        if dim == 3 { " in 3D" } else { "" }
                                    ),
                                    hint: hint.into(),
                                });
                            }
                            Ok(Seg {
                                kind: c.kind,
                                nodes: c.nodes.clone(),
                                sign: c.sign,
                            })
                        })
                        .collect()
                };
            let master = segs(&resolved.master, "GROUP_MA_MAIT")?;
            let mut slave = segs(&resolved.slave, "GROUP_MA_ESCL")?;
            // SANS_GROUP_NO / SANS_GROUP_MA: the slave cells holding those
            // nodes, or in those groups, are removed.
            let mut excluded_nodes = Vec::new();
            for g in &z.excluded_node_groups {
                let group = mesh.group_no(g).ok_or_else(|| ContactError::UnknownGroup {
                    keyword: "SANS_GROUP_NO",
                    name: g.clone(),
                    suggestion: crate::error::did_you_mean(
                        g,
                        mesh.groups_no.iter().map(|g| g.name.as_str()),
                    ),
                })?;
                excluded_nodes.extend(group.members.iter().copied());
            }
            let mut excluded_cells = Vec::new();
            for g in &z.excluded_cell_groups {
                let group = mesh.group_ma(g).ok_or_else(|| ContactError::UnknownGroup {
                    keyword: "SANS_GROUP_MA",
                    name: g.clone(),
                    suggestion: crate::error::did_you_mean(
                        g,
                        mesh.groups_ma.iter().map(|g| g.name.as_str()),
                    ),
                })?;
                excluded_cells.extend(group.members.iter().copied());
            }
            let kept: Vec<bool> = resolved
                .slave
                .iter()
                .map(|c| {
                    !excluded_cells.contains(&c.id)
                        && !c.nodes.iter().any(|n| excluded_nodes.contains(n))
                })
                .collect();
            slave = slave
                .into_iter()
                .zip(&kept)
                .filter_map(|(s, &k)| k.then_some(s))
                .collect();
            if slave.is_empty() {
                return Err(ContactError::Invalid {
                    keyword: "GROUP_MA_ESCL",
                    message: format!(
                        "no slave cell of {} is left once SANS_GROUP_NO/SANS_GROUP_MA are removed",
                        z.slave_group
                    ),
                });
            }
            // `diameter`: the largest distance between two nodes.
            let h = slave
                .iter()
                .map(|s| {
                    let p = s.positions(&mesh.coords);
                    let mut d = 0.0f64;
                    for i in 0..p.len() {
                        for j in i + 1..p.len() {
                            d = d.max(norm(sub(p[i], p[j])));
                        }
                    }
                    d
                })
                .collect();
            for s in &slave {
                for &n in s.lagr_nodes() {
                    if let std::collections::hash_map::Entry::Vacant(e) = lagr_of.entry(n) {
                        e.insert(lagr.len());
                        lagr.push(n);
                    }
                }
            }
            out.push(MZone {
                slave,
                master,
                coef: z.coef_cont,
                init: z.contact_init,
                bilateral: z.bilateral,
                dist_ratio: z.dist_ratio.filter(|r| *r > 0.0),
                h,
            });
        }
        Ok(MortarLagrangian {
            zones: out,
            lagr,
            lagr_of,
            axis,
            dim,
            first_pairing: true,
            iterations: 0,
            paired: 0,
            resi_geom: ResiGeom::new(mesh),
        })
    }

    /// code_aster 17's geometric criterion (MECA_NON_LINE's
    /// `CONTACT/RESI_GEOM`, `ConvergenceManager.evalGeometricResidual`):
    /// an iterate is accepted only when the displacement increment that
    /// led to it, max |ΔDX|, |ΔDY|, |ΔDZ| over the nodes, is at most
    /// `resi_geom` × the diagonal of the mesh's bounding box.
    pub fn set_resi_geom(&mut self, resi_geom: f64) {
        self.resi_geom.tol = Some(resi_geom);
    }

    /// The contact pressure of each slave node (`LAGS_C`).
    pub fn multipliers<'a>(&'a self, own: &'a [f64]) -> impl Iterator<Item = (NodeId, f64)> + 'a {
        self.lagr
            .iter()
            .enumerate()
            .map(move |(k, n)| (*n, own.get(k).copied().unwrap_or(0.0)))
    }

    /// The pairs on positions `x` (`fastPair` + `cellInteProj`, 2D): on
    /// the cells linearised on their ends, the slave ends cast along the
    /// full slave cell's normal there.
    pub(crate) fn pairs(&self, x: &[[f64; 3]]) -> Vec<Pair> {
        if self.dim == 3 {
            return pairs_3d_of(&self.zones, x);
        }
        pairs_of(&self.zones, x)
    }
}

/// The pairs of 3D faces of `zones` on positions `x` (`mortar_pairing3d`):
/// every master face is tried against every slave face.
pub(crate) fn pairs_3d_of(zones: &[MZone], x: &[[f64; 3]]) -> Vec<Pair> {
    let mut out = Vec::new();
    for (zi, z) in zones.iter().enumerate() {
        for (si, s) in z.slave.iter().enumerate() {
            let sp = s.positions(x);
            let slave = Face {
                kind: s.kind,
                x: &sp,
                sign: s.sign,
            };
            for (mi, m) in z.master.iter().enumerate() {
                let mp = m.positions(x);
                let master = Face {
                    kind: m.kind,
                    x: &mp,
                    sign: m.sign,
                };
                if let Some(poly) = mortar_pairing3d::intersect(
                    slave,
                    master,
                    mortar_pairing3d::PAIR_TOLE,
                    z.dist_ratio,
                ) {
                    out.push(Pair {
                        zone: zi,
                        slave: si,
                        master: mi,
                        xi: [0.0, 0.0],
                        poly,
                    });
                }
            }
        }
    }
    out
}

/// The pairs of `zones` on positions `x` (see [`MortarLagrangian::pairs`]).
pub(crate) fn pairs_of(zones: &[MZone], x: &[[f64; 3]]) -> Vec<Pair> {
    let mut out = Vec::new();
    for (zi, z) in zones.iter().enumerate() {
        for (si, s) in z.slave.iter().enumerate() {
            let sp = s.positions(x);
            let (sa, sb) = (sp[0], sp[1]);
            let (Some(ns), Some(na), Some(nb)) = (
                seg_normal(sa, sb, s.sign),
                normal_at(s.kind, &sp, -1.0, s.sign),
                normal_at(s.kind, &sp, 1.0, s.sign),
            ) else {
                continue;
            };
            let ds = s
                .positions(x)
                .iter()
                .flat_map(|p| sp.iter().map(move |q| norm(sub(*p, *q))))
                .fold(0.0f64, f64::max);
            for (mi, m) in z.master.iter().enumerate() {
                let mp = m.positions(x);
                let (ma, mb) = (mp[0], mp[1]);
                let Some(nm) = seg_normal(ma, mb, m.sign) else {
                    continue;
                };
                if dot(ns, nm).abs() <= PAIR_TOLE {
                    continue;
                }
                if let Some(r) = z.dist_ratio {
                    let dm = norm(sub(mb, ma));
                    let bs = lerp(sa, sb, 0.0);
                    let bm = lerp(ma, mb, 0.0);
                    if norm(sub(bm, bs)) >= 2.0 * r * dm.max(ds) {
                        continue;
                    }
                }
                // Slave ends cast along the slave normal onto the master.
                let (Some(k1), Some(k2)) = (ray_hit(sa, na, ma, mb), ray_hit(sb, nb, ma, mb))
                else {
                    continue;
                };
                let proj = [lerp(ma, mb, k1), lerp(ma, mb, k2)];
                // inteCellChck
                let orig = [sa, sb];
                let mut empty = false;
                for i in 0..2 {
                    let j = 1 - i;
                    let eo = sub(orig[j], orig[i]);
                    let ep = sub(proj[j], proj[i]);
                    let v = sub(proj[i], orig[i]);
                    let sig = dot(ep, eo);
                    let a = dot(ns, v);
                    let b = dot(nm, v);
                    if sig < -PAIR_TOLE
                        || (a < -PAIR_TOLE && b < -PAIR_TOLE)
                        || (a > PAIR_TOLE && b > PAIR_TOLE)
                    {
                        empty = true;
                        break;
                    }
                }
                if empty {
                    continue;
                }
                // addPoinInte2D
                let ksi = [k1, k2];
                let para = [-1.0, 1.0];
                let mut pts = Vec::new();
                for i in 0..2 {
                    if ksi[i] > -1.0 - PAIR_TOLE && ksi[i] < 1.0 + PAIR_TOLE {
                        pts.push(para[i]);
                    }
                }
                let (lo, hi) = (k1.min(k2), k1.max(k2));
                for end in [-1.0, 1.0] {
                    if lo - PAIR_TOLE <= end && end <= hi + PAIR_TOLE {
                        if (end - k1).abs() < PAIR_TOLE {
                            pts.push(-1.0);
                        } else {
                            let t = (end - k1) / (k2 - k1);
                            pts.push(2.0 * t - 1.0);
                        }
                    }
                }
                if pts.len() < 2 {
                    continue;
                }
                // intePoinSort (2D): the extreme points.
                let a = pts.iter().copied().fold(f64::INFINITY, f64::min);
                let b = pts.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                if (b - a) > PAIR_TOLE {
                    out.push(Pair {
                        zone: zi,
                        slave: si,
                        master: mi,
                        xi: [a, b],
                        poly: Vec::new(),
                    });
                }
            }
        }
    }
    out
}

impl MortarLagrangian {
    /// The residual and tangent at `state` (code_aster's `laVect_ct_pr`,
    /// `laMatr_ct_pr`), paired on `pairing`'s positions when given (a
    /// trial of MECA_NON_LINE's line search: the pairs, slave normals and
    /// master points of the iteration's start, `mortar_point::on_current`),
    /// else on the current ones. The tangent of a trial is not meaningful
    /// (the line search uses the residual only).
    fn contribution(
        &mut self,
        pairing: Option<&State>,
        state: &State,
        own: &[f64],
    ) -> Result<Contribution, FemError> {
        let x = current_positions(state);
        let x0 = &state.mesh.coords;
        let xp_owned;
        let xp: &[[f64; 3]] = match pairing {
            Some(p) => {
                xp_owned = current_positions(p);
                &xp_owned
            }
            None => &x,
        };
        let pairs = self.pairs(xp);
        let mut c = Contribution {
            forces: Vec::new(),
            own_residual: vec![0.0; self.lagr.len()],
            tangent: Vec::new(),
        };
        let mut paired = vec![false; self.lagr.len()];
        let mut paired_cells = 0;
        let mut seen = std::collections::HashSet::new();
        for p in &pairs {
            let z = &self.zones[p.zone];
            let s = &z.slave[p.slave];
            let m = &z.master[p.master];
            if seen.insert((p.zone, p.slave)) {
                paired_cells += 1;
            }
            let sp = s.positions(xp);
            let mp = m.positions(xp);
            let s0 = s.positions(x0);
            let hf = z.h[p.slave];
            let gamma = z.coef / hf;
            let lk: Vec<usize> = s.lagr_nodes().iter().map(|n| self.lagr_of[n]).collect();
            for &k in &lk {
                paired[k] = true;
            }
            let points = if self.dim == 3 {
                crate::mortar_point::points_3d(s, m, &p.poly, &sp, &mp, &s0)?
            } else {
                crate::mortar_point::points(s, m, p.xi, &sp, &mp, &s0, self.axis)?
            };
            // A trial of the line search: normals and master points of the
            // pairing configuration, gaps on the current positions.
            let points: Vec<_> = if pairing.is_some() {
                let (sc, mc) = (s.positions(&x), m.positions(&x));
                points
                    .into_iter()
                    .map(|pt| crate::mortar_point::on_current(pt, s, m, &sc, &mc))
                    .collect()
            } else {
                points
            };
            let dofs = crate::mortar_point::PairDofs::of(state, s, m, self.dim);
            for pt in points {
                // The multipliers' functions (P1 on a face's corners).
                let nsl = &s.lagr_shape(pt.xi, &pt.initial.shape);
                let w = pt.w;
                let ns = pt.ns;
                let gap = pt.gap;
                let lam: f64 = nsl.iter().zip(&lk).map(|(f, &k)| f * own[k]).sum();
                let lg = lam + gamma * gap;
                // CONTACT_INIT at the first pairing, then Heaviside(−(λ + γg)).
                let active = z.forced(self.first_pairing).unwrap_or(-lg >= 0.0);
                let (h, proj) = if active { (true, lg) } else { (false, 0.0) };
                // The point's DOFs with the derivatives of the normal, the
                // master point and the gap: code_aster's analytic tangent
                // (`laMatr_ct_pr`, module `mortar_tangent`), on segments
                // (2D) or faces (3D).
                let lin: Vec<FaceDof> = pt.linearise(s, m, &dofs);
                if h {
                    // −w λ n_s·(v_s − v_m)
                    for e in &lin {
                        let Some(i) = e.dof else { continue };
                        let f = dot(ns, e.jump);
                        c.forces.push((i, -w * lam * f));
                        for (a, &k) in lk.iter().enumerate() {
                            c.tangent
                                .push((Unknown::Dof(i), Unknown::Own(k), -w * nsl[a] * f));
                        }
                        // −w λ (v_s − v_m)·Dn_s + w λ n_s·(∂v_m/∂ζ_α) Dζ_α
                        let fm = [dot(ns, e.dtest_m[0]), dot(ns, e.dtest_m[1])];
                        for e2 in &lin {
                            let Some(j) = e2.dof else { continue };
                            let v = -w * lam * dot(e.jump, e2.dns)
                                + w * lam * (fm[0] * e2.dzeta[0] + fm[1] * e2.dzeta[1]);
                            if v != 0.0 {
                                c.tangent.push((Unknown::Dof(i), Unknown::Dof(j), v));
                            }
                        }
                    }
                }
                // w ([λ + γg]₋ − λ)/γ μ
                for (a, &ka) in lk.iter().enumerate() {
                    c.own_residual[ka] += w * (proj - lam) / gamma * nsl[a];
                    if h {
                        // d(γ g)/du / γ = Dg (dPi_du)
                        for e in &lin {
                            let Some(j) = e.dof else { continue };
                            c.tangent.push((
                                Unknown::Own(ka),
                                Unknown::Dof(j),
                                w * nsl[a] * e.dgap,
                            ));
                        }
                    } else {
                        for (b, &kb) in lk.iter().enumerate() {
                            c.tangent.push((
                                Unknown::Own(ka),
                                Unknown::Own(kb),
                                -w * nsl[a] * nsl[b] / gamma,
                            ));
                        }
                    }
                }
            }
        }
        // Slave nodes of no paired cell: λ = 0.
        for (k, p) in paired.iter().enumerate() {
            if !p {
                c.own_residual[k] += -own[k];
                c.tangent.push((Unknown::Own(k), Unknown::Own(k), -1.0));
            }
        }
        // A node whose every point is inactive solves −λ/γ ∫μ = 0 only:
        // nothing to add. Keep the diagonal present for the factorisation.
        for k in 0..self.lagr.len() {
            c.tangent.push((Unknown::Own(k), Unknown::Own(k), 0.0));
        }
        if pairing.is_none() {
            self.paired = paired_cells;
        }
        Ok(c)
    }
}

impl ForceSource for MortarLagrangian {
    fn name(&self) -> String {
        "DEFI_CONT (mortar Lagrangian contact)".into()
    }

    fn unknowns(&self) -> usize {
        self.lagr.len()
    }

    fn begin_increment(&mut self, state: &State, _own: &mut [f64]) -> Result<(), FemError> {
        self.resi_geom.begin(state);
        Ok(())
    }

    fn evaluate(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError> {
        self.contribution(None, state, own)
    }

    fn evaluate_on_pairing(
        &mut self,
        pairing: &State,
        state: &State,
        own: &[f64],
    ) -> Result<Contribution, FemError> {
        self.contribution(Some(pairing), state, own)
    }

    fn after_iteration(&mut self, state: &State, _own: &mut [f64]) -> Result<bool, FemError> {
        // The first pairing (CONTACT_INIT) was that of this iteration.
        self.iterations += 1;
        self.first_pairing = false;
        let geometry_ok = self.resi_geom.accept(state);
        // code_aster 17's Newton (`NewtonSolver.solve_iteration`) pairs
        // on the iterate, then tests the whole residual, the LAGS_C rows
        // included ([`ForceSource::own_rows_in_residual`]): the next
        // evaluation is that of the new pairing and statuses, and a change
        // of them does not by itself prevent convergence.
        Ok(geometry_ok)
    }

    fn own_rows_in_residual(&self) -> bool {
        true
    }

    fn converged(&mut self, _state: &State, _own: &[f64]) -> Result<(), FemError> {
        self.first_pairing = false;
        Ok(())
    }

    fn unknown_name(&self, k: usize, mesh: &Mesh) -> String {
        match self.lagr.get(k) {
            Some(n) => format!(
                "LAGS_C of node {}",
                mesh.node_names
                    .get(n.0 as usize)
                    .cloned()
                    .unwrap_or_else(|| format!("#{}", n.0 + 1))
            ),
            None => format!("unknown #{}", k + 1),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_hits_the_line_at_its_parameter() {
        let a = [0.0, 0.0, 0.0];
        let b = [2.0, 0.0, 0.0];
        let k = ray_hit([1.5, 1.0, 0.0], [0.0, -1.0, 0.0], a, b).unwrap();
        assert!((k - 0.5).abs() < 1e-15);
        assert!(ray_hit([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], a, b).is_none());
    }

    #[test]
    fn outward_normal_follows_the_sign() {
        let n = seg_normal([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0).unwrap();
        assert_eq!(n, [0.0, -1.0, 0.0]);
        let n = seg_normal([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], -1.0).unwrap();
        assert_eq!(n, [-0.0, 1.0, 0.0]);
    }
}
