//! code_aster's continuous formulation with Coulomb friction (`FORMULATION=
//! 'CONTINUE'`, `FROTTEMENT='COULOMB'`): one contact element per slave
//! integration point (`te0364`/`te0365`), the contact pressure `LAGS_C` and
//! the friction multipliers `LAGS_F1`, `LAGS_F2` (a direction: |Λ| ≤ 1, the
//! friction force being μ λ Λ) as unknowns of the slave nodes, solved with
//! the displacements by fem's generalised Newton method.
//!
//! At a point of weight W (∫ on the initial slave geometry, × r under AXIS,
//! as `mmmjac`), with the code_aster normal `n` (into the master body),
//! tangents `τ₁ τ₂` built from it (`mmmron`), P = I − n nᵀ:
//!
//! - gap (penetration > 0) `g = DIST + (x_s − x_m)·n` on the current
//!   geometry, the master point at the reference coordinates of the last
//!   pairing (`mmmjeu`);
//! - slip increment `v = Δu_s − Δu_m(ξ)` since the start of the step
//!   (`mmdepm`), its tangential part `P v`;
//! - λ = Σ N_l λ_l (`LAGS_C`, negative in compression), Λ = Σ N_l Λ_l τ.
//!
//! Contact status (`mmstac`, updated after each Newton iteration with
//! `ALGO_RESO_CONT='NEWTON'`): in contact when λ − ρ g < 0. Friction status
//! inside the element (`mmtrpr`): stick when |Λ + ρ_f P v| ≤ 1. The
//! residuals (internal-force side, `mmmvee`, `mmmvmm`, `mmmvcc`, `mmmvff`):
//!
//! | phase | slave forces (master: opposite, with N_m) | λ equation | Λ equation |
//! | --- | --- | --- | --- |
//! | open | — | −W λ/ρ | W Λ·τ |
//! | contact | −W n (λ − ρ g) | −W g | … |
//! | stick | − W μλ (P Λ + ρ_f P v) | | −W μλ (P v)·τ |
//! | slip | − W μλ P d, d = r/|r|, r = Λ + ρ_f P v | | W μλ/ρ_f (Λ − d)·τ |
//!
//! (penalised variants: `mmmvee`, `mmmvff`). With nodal integration the
//! converged state is Coulomb's law at each slave node whatever ρ and ρ_f:
//! stick (P v = 0) or slip at μ|λ| against the slip. The tangent is the
//! derivative of these residuals at fixed geometry, as code_aster's
//! matrices (`mmCompMatrCont`, `mmCompMatrFric`): no derivative of the
//! friction equations with respect to the threshold, none of the
//! penalised friction forces either. `SANS_GROUP_NO_FR`/`DIRE_EXCL_FROT`
//! freeze the excluded components as code_aster's `mmmtex`/`mmmvex` do
//! (unit diagonal, no coupling with the displacements, zero residual).

use std::collections::HashMap;

use aster_fem::{Comp, Contribution, Dof, FemError, ForceSource, LoopVerdict, State, Unknown};
use aster_mesh::{Mesh, NodeId};

use super::{adaptation, cycling};
use super::{ContactInit, ContinueFriction, FrictionAlgo, FrictionGeometry};
use crate::error::ContactError;
use crate::geomloop::{GeomDecision, GeomLoopState};
use crate::integration::Measure;
use crate::pairing::{jacobian, pair_point, PairStatus, SlavePoint};
use crate::post::ContNoeu;
use crate::shape::{cross, dot, norm, scale, sub, SurfaceKind};
use crate::surface::ResolvedZone;
use crate::zone::{ContinueAlgo, ContinueDefinition, Integration, Resolution};

/// The radius code_aster substitutes for a point on the axis (`mmmjac`).
const AXIS_RADIUS: f64 = 1e-7;

/// One zone: its surfaces, its contact and friction coefficients.
#[derive(Clone, Debug)]
struct FZone {
    zone: ResolvedZone,
    /// ρ (`COEF_CONT`) or the penalty (`COEF_PENA_CONT`).
    coef_cont: f64,
    pena_cont: bool,
    /// ρ_f (`COEF_FROT`) or the penalty (`COEF_PENA_FROT`).
    coef_frot: f64,
    pena_frot: bool,
    mu: f64,
    frictional: bool,
    seuil_init: f64,
    contact_init: ContactInit,
    /// `CONTACT_INIT='INTERPENETRE'`: a point starts in contact when its
    /// initial gap is at most this (`mmopti`: 1e-6 × `DIST_MAXI` or the
    /// shortest edge of the zone's cells, `contSetInit`).
    init_threshold: f64,
    dire_excl: Option<[f64; 3]>,
    /// `GLIS_MAXI` (penalised friction beside augmented contact).
    glis_maxi: f64,
}

/// The pairing of a point: the master point and the local basis.
#[derive(Clone, Debug, PartialEq)]
struct PointPair {
    master: Vec<(NodeId, f64)>,
    /// code_aster's normal: into the master body.
    n: [f64; 3],
    tau: [[f64; 3]; 2],
    /// `DIST_MAIT + DIST_ESCL` at the pairing.
    jeusup: f64,
    /// Where the master point was at the pairing (PROJ_X… of CONT_NOEU).
    master_x: [f64; 3],
    slave_x: [f64; 3],
}

/// A contact point (code_aster: a contact element).
#[derive(Clone, Debug)]
struct Point {
    zone: usize,
    /// The slave cell (index in the zone) and the reference coordinates.
    cell: usize,
    xi: [f64; 2],
    /// W: integration weight × jacobian on the initial geometry (× r AXIS).
    weight: f64,
    /// Slave cell nodes and their shape values at the point.
    slave: Vec<(NodeId, f64)>,
    /// The Lagrange node of each slave cell node (index into the layout).
    lagr: Vec<usize>,
    /// The slave node the point sits on (nodal integration).
    node: Option<NodeId>,
    /// `SANS_GROUP_NO` (the point never takes part in contact).
    sans: bool,
    /// The excluded friction components (local Lagrange node, component)
    /// when the point sits on a `SANS_GROUP_NO_FR` node (`mmmtex`).
    fric_excl: Vec<(usize, usize)>,
    pair: Option<PointPair>,
    /// Whether the last pairing excluded the point (CONT = -1).
    unpaired: bool,
    /// Contact status (`indco`).
    contact: bool,
    /// The friction threshold of the last status update (`lambds`).
    threshold: f64,
    /// Penetration (code_aster's sign: > 0 interpenetrated) at the last
    /// status update.
    gap: f64,
    /// Positions of the slave point and its projection at the last status
    /// update (code_aster's geometric criterion).
    last_x: Option<([f64; 3], [f64; 3])>,
    /// The penalty the cycling treatment switched the point to for the
    /// rest of the step (module `cycling`).
    cycl_pena: Option<f64>,
    /// The master nodes of the pairing at the last status update.
    last_master: Option<Vec<NodeId>>,
    /// The point's friction coefficient and its history in the step
    /// (module `adaptation`).
    fric: adaptation::History,
    /// The coefficient the element reads when it differs from the
    /// history's (`mmchml_c` at Newton iteration 1 builds its field before
    /// it rewrites the penalised-friction coefficients).
    coef_elem: Option<f64>,
}

/// Values of one point at the current iterate.
struct PointValues {
    jeu: f64,
    v: [f64; 3],
    lambda: f64,
    lam_f: [f64; 3],
}

/// Local element: unknowns, residual and (row-major) tangent.
struct Local {
    unknowns: Vec<Unknown>,
    r: Vec<f64>,
    k: Vec<f64>,
    /// The contact part of the slave rows' residual (the rest is friction).
    slave_cont: Vec<f64>,
    /// Whether the point was in contact, and sticking or sliding.
    contact: bool,
    friction: bool,
}

/// A Lagrange node: its first own unknown and component count.
#[derive(Clone, Copy, Debug)]
struct LagrNode {
    node: NodeId,
    first: usize,
    comps: usize,
}

/// Friction CONT_NOEU snapshots, by step time.
type Snapshots = Vec<(f64, ContNoeu)>;

/// code_aster's continuous contact–friction elements of a `DEFI_CONTACT`,
/// as a fem force source.
#[derive(Clone, Debug)]
pub struct ContinuousFriction {
    zones: Vec<FZone>,
    points: Vec<Point>,
    lagr: Vec<LagrNode>,
    unknowns: usize,
    dim: usize,
    reso_cont: Resolution,
    reso_frot: Resolution,
    geometry: FrictionGeometry,
    resi_frot: f64,
    iter_cont_maxi: usize,
    iter_frot_maxi: usize,
    /// code_aster's contact-side cycling treatment (module `cycling`).
    cycling: bool,
    /// code_aster's adaptation of `COEF_FROT` (module `adaptation`) and
    /// each zone's smallest and largest coefficient in the step.
    adapt_coef: bool,
    coef_ranges: Vec<adaptation::Range>,
    /// Displacement per DOF index at the start of the increment.
    u_start: Vec<f64>,
    geom: GeomLoopState,
    /// Passes of the contact and friction fixed-point loops in the step.
    cont_loops: usize,
    frot_loops: usize,
    /// Own unknowns after the previous solve (RESI_FROT of Newton).
    own_prev: Option<Vec<f64>>,
    newton_iterations: usize,
    first_increment: bool,
    /// Smallest and largest master edge (code_aster's `arete_min/max`).
    edge_min: f64,
    edge_max: f64,
    snapshots: Snapshots,
    /// Per Lagrange node, from the last evaluation: whether its equations
    /// were those of an open point only (λ = 0) and of a point without
    /// friction only (Λ = 0), so that the solved values are exactly zero.
    decoupled: Vec<(bool, bool)>,
    /// The contact and friction nodal forces of the last evaluation.
    forces_cont: HashMap<NodeId, [f64; 3]>,
    forces_frot: HashMap<NodeId, [f64; 3]>,
}

/// Orthonormal tangents from code_aster's normal (`mmmron`, `mmtann`).
pub(super) fn tangents(dim: usize, n: [f64; 3]) -> [[f64; 3]; 2] {
    if dim == 2 {
        let t1 = [n[1], -n[0], 0.0];
        let l = norm(t1);
        return [scale(t1, 1.0 / l), [0.0; 3]];
    }
    let eps = f64::EPSILON;
    let t1 = if n[0].abs() > eps {
        [-n[1] / n[0], 1.0, 0.0]
    } else if n[1].abs() > eps {
        [1.0, -n[0] / n[1], 0.0]
    } else {
        [0.0, 1.0, -n[1] / n[2]]
    };
    let t1 = scale(t1, 1.0 / norm(t1));
    let t2 = cross(t1, n);
    let l2 = norm(t2);
    [t1, scale(t2, 1.0 / l2)]
}

/// x − (x·n) n: the part of x in the tangent plane of the unit normal n
/// (code_aster's projector `mmmtpe`/`pmat`).
fn tangential_part(x: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    let s = dot(x, n);
    [x[0] - s * n[0], x[1] - s * n[1], x[2] - s * n[2]]
}

fn comp_of(d: usize) -> Comp {
    match d {
        0 => Comp::DX,
        1 => Comp::DY,
        _ => Comp::DZ,
    }
}

/// Integration points of a slave cell with `INTEGRATION='AUTO'`
/// (code_aster's `mmgaus`, type 1): the nodes with their Newton–Cotes
/// weights; TRIA6/TRIA7 6 Gauss points; QUAD8/QUAD9 the 9 points of the
/// 3×3 Simpson rule. Returns (reference coordinates, weight, node index
/// the point sits on).
fn auto_points(kind: SurfaceKind) -> Vec<([f64; 2], f64, Option<usize>)> {
    let nodes = kind.node_coords();
    let at_nodes = |w: &[f64]| -> Vec<([f64; 2], f64, Option<usize>)> {
        w.iter()
            .enumerate()
            .map(|(i, &wi)| (nodes[i], wi, Some(i)))
            .collect()
    };
    match kind {
        SurfaceKind::Seg2 => at_nodes(&[1.0, 1.0]),
        SurfaceKind::Seg3 => at_nodes(&[1.0 / 3.0, 1.0 / 3.0, 4.0 / 3.0]),
        SurfaceKind::Tria3 => at_nodes(&[1.0 / 6.0; 3]),
        SurfaceKind::Quad4 => at_nodes(&[1.0; 4]),
        SurfaceKind::Quad8 | SurfaceKind::Quad9 => {
            let w = [
                1.0 / 9.0,
                1.0 / 9.0,
                1.0 / 9.0,
                1.0 / 9.0,
                4.0 / 9.0,
                4.0 / 9.0,
                4.0 / 9.0,
                4.0 / 9.0,
            ];
            let mut pts = at_nodes(&w);
            let centre = if kind == SurfaceKind::Quad9 {
                Some(8)
            } else {
                None
            };
            pts.push(([0.0, 0.0], 16.0 / 9.0, centre));
            pts
        }
        SurfaceKind::Tria6 | SurfaceKind::Tria7 => {
            let a = 0.445948490915965;
            let b = 0.091576213509771;
            let p1 = 0.111690794839005;
            let p2 = 0.054975871827661;
            vec![
                ([b, b], p2, None),
                ([1.0 - 2.0 * b, b], p2, None),
                ([b, 1.0 - 2.0 * b], p2, None),
                ([a, 1.0 - 2.0 * a], p1, None),
                ([a, a], p1, None),
                ([1.0 - 2.0 * a, a], p1, None),
            ]
        }
    }
}

impl ContinuousFriction {
    /// The elements of a continuous definition with friction, on `mesh`,
    /// in a problem whose dimension is the mesh's (3 when its nodes have
    /// three coordinates); `measure`: AXIS weights carry the radius.
    pub fn new(
        def: &ContinueDefinition,
        mesh: &Mesh,
        measure: Measure,
    ) -> Result<ContinuousFriction, ContactError> {
        Self::new_in(def, mesh, measure, if mesh.dim >= 3 { 3 } else { 2 })
    }

    /// As [`ContinuousFriction::new`] in a problem of dimension `space_dim`
    /// (the model's, as code_aster's `model_ndim`: a plane model on a mesh
    /// whose nodes have three coordinates is 2D, its segments have normals).
    pub fn new_in(
        def: &ContinueDefinition,
        mesh: &Mesh,
        measure: Measure,
        space_dim: usize,
    ) -> Result<ContinuousFriction, ContactError> {
        let friction: &ContinueFriction =
            def.friction.as_ref().ok_or_else(|| ContactError::Invalid {
                keyword: "FROTTEMENT",
                message: "the definition has no friction".into(),
            })?;
        let dim = if space_dim >= 3 { 3 } else { 2 };
        let mut zones = Vec::new();
        for (i, (z, f)) in def.zones.iter().zip(&friction.zones).enumerate() {
            // code_aster's Gauss, Simpson and Newton–Cotes rules (`mmgaus`,
            // ORDRE_INT) place points with no node of their own: the
            // multipliers are interpolated there as at any point. code_aster
            // refuses excluded nodes with them (`cazocc`, CONTACT_97), as
            // `run::friction` does before the solve.
            let (coef_cont, pena_cont) = match z.law.algo {
                ContinueAlgo::Standard { coef_cont } => (coef_cont, false),
                ContinueAlgo::Penalisation { coef_pena_cont } => (coef_pena_cont, true),
                ContinueAlgo::Lac => {
                    return Err(ContactError::Unsupported {
                        feature: "ALGO_CONT='LAC' with FROTTEMENT='COULOMB'".into(),
                        hint: "code_aster's LAC method is frictionless".into(),
                    })
                }
            };
            let (coef_frot, pena_frot) = match f.algo {
                FrictionAlgo::Standard { coef_frot } => (coef_frot, false),
                FrictionAlgo::Penalisation { coef_pena_frot } => (coef_pena_frot, true),
            };
            let mut geometry = z.geometry.clone();
            geometry.lissage = z.geometry.lissage;
            let zone = ResolvedZone::new_in(i, &geometry, mesh, dim)?;
            let init_threshold = zone.contact_init_threshold(mesh);
            zones.push(FZone {
                init_threshold,
                zone,
                coef_cont,
                pena_cont,
                coef_frot,
                pena_frot,
                mu: f.coulomb,
                frictional: f.frictional(),
                seuil_init: -f.seuil_init.unwrap_or(0.0).abs(),
                contact_init: f.contact_init,
                dire_excl: f.dire_excl_frot,
                glis_maxi: f.glis_maxi,
            });
        }
        // The friction-excluded nodes of each zone.
        let mut fric_excluded: Vec<Vec<NodeId>> = Vec::new();
        for f in &friction.zones {
            let mut nodes = Vec::new();
            for g in &f.excluded_node_groups {
                let group = mesh.group_no(g).ok_or_else(|| ContactError::UnknownGroup {
                    keyword: "SANS_GROUP_NO_FR",
                    name: g.clone(),
                    suggestion: crate::error::did_you_mean(
                        g,
                        mesh.groups_no.iter().map(|g| g.name.as_str()),
                    ),
                })?;
                nodes.extend(group.members.iter().copied());
            }
            nodes.sort();
            nodes.dedup();
            fric_excluded.push(nodes);
        }
        // Lagrange nodes: every slave node (SANS_GROUP_NO included: its
        // multiplier is held at zero by its open status).
        let mut lagr: Vec<LagrNode> = Vec::new();
        let mut lagr_of: HashMap<NodeId, usize> = HashMap::new();
        let mut unknowns = 0;
        for fz in &zones {
            let comps = if fz.frictional { dim } else { 1 };
            for c in &fz.zone.slave {
                for n in &c.nodes {
                    if let Some(&k) = lagr_of.get(n) {
                        if lagr[k].comps != comps {
                            return Err(ContactError::Unsupported {
                                feature: format!(
                                    "a slave node in a frictional and a frictionless zone (node {})",
                                    mesh.node_name(*n)
                                ),
                                hint: "give both zones the same COULOMB".into(),
                            });
                        }
                        continue;
                    }
                    lagr_of.insert(*n, lagr.len());
                    lagr.push(LagrNode {
                        node: *n,
                        first: unknowns,
                        comps,
                    });
                    unknowns += comps;
                }
            }
        }
        let fz_rule: Vec<Integration> = def.zones.iter().map(|z| z.law.integration).collect();
        let mut points = Vec::new();
        for (zi, fz) in zones.iter().enumerate() {
            let z = &fz.zone;
            for (ci, cell) in z.slave.iter().enumerate() {
                let reference: Vec<[f64; 3]> = cell
                    .nodes
                    .iter()
                    .map(|n| mesh.coords[n.0 as usize])
                    .collect();
                let rule = match fz_rule[zi] {
                    Integration::Gauss(o) => crate::integration::ordre_int_gauss(cell.kind, o)
                        .into_iter()
                        .map(|(xi, w)| (xi, w, None))
                        .collect(),
                    r @ (Integration::Simpson(_) | Integration::NCotes(_)) => {
                        crate::integration::closed_rule(cell.kind, r)
                            .unwrap_or_default()
                            .into_iter()
                            .map(|(xi, w)| (xi, w, None))
                            .collect()
                    }
                    Integration::Auto => auto_points(cell.kind),
                };
                for (xi, w, on) in rule {
                    let (shape, _) = cell.kind.eval(xi);
                    let mut j = jacobian(cell.kind, &reference, xi);
                    if measure == Measure::Axisymmetric {
                        let r: f64 = shape.iter().zip(&reference).map(|(s, p)| s * p[0]).sum();
                        j *= if r == 0.0 { AXIS_RADIUS } else { r.abs() };
                    }
                    let node = on.map(|i| cell.nodes[i]);
                    let sans = node.is_some_and(|n| z.slave_nodes.binary_search(&n).is_err());
                    let mut fric_excl = Vec::new();
                    if let Some(n) = node {
                        if fz.frictional && fric_excluded[zi].binary_search(&n).is_ok() {
                            let comps: &[usize] = if dim == 3 && fz.dire_excl.is_none() {
                                &[0, 1]
                            } else {
                                &[0]
                            };
                            for (l, m) in cell.nodes.iter().enumerate() {
                                if fric_excluded[zi].binary_search(m).is_ok() {
                                    for &k in comps {
                                        fric_excl.push((l, k));
                                    }
                                }
                            }
                        }
                    }
                    points.push(Point {
                        zone: zi,
                        cell: ci,
                        xi,
                        weight: w * j,
                        slave: cell.nodes.iter().copied().zip(shape).collect(),
                        lagr: cell.nodes.iter().map(|n| lagr_of[n]).collect(),
                        node,
                        sans,
                        fric_excl,
                        pair: None,
                        unpaired: false,
                        contact: false,
                        threshold: fz.seuil_init,
                        gap: 0.0,
                        last_x: None,
                        cycl_pena: None,
                        last_master: None,
                        fric: adaptation::History::new(fz.coef_frot),
                        coef_elem: None,
                    });
                }
            }
        }
        // code_aster's `arete_min/max` (mmopti): master cell sizes.
        let mut edge_min = f64::INFINITY;
        let mut edge_max: f64 = 0.0;
        for fz in &zones {
            for c in &fz.zone.master {
                let p: Vec<[f64; 3]> = c.nodes.iter().map(|n| mesh.coords[n.0 as usize]).collect();
                let l = match c.kind {
                    SurfaceKind::Seg2 | SurfaceKind::Seg3 => norm(sub(p[1], p[0])),
                    k if k.is_triangle() => {
                        let m = scale(
                            [p[0][0] + p[1][0], p[0][1] + p[1][1], p[0][2] + p[1][2]],
                            0.5,
                        );
                        norm(sub(p[2], m))
                    }
                    _ => norm(sub(p[2], p[0])) + norm(sub(p[3], p[1])),
                };
                if l > 0.0 {
                    edge_min = edge_min.min(l);
                    edge_max = edge_max.max(l);
                }
            }
        }
        if !edge_min.is_finite() {
            edge_min = 1.0;
            edge_max = 1.0;
        }
        let geometry = match def.algo_reso_geom {
            Resolution::Newton => FrictionGeometry::Newton {
                resi_geom: match def.geom_loop {
                    crate::zone::GeomLoop::Automatique { resi_geom, .. } => resi_geom,
                    _ => 1e-6,
                },
            },
            Resolution::PointFixe => FrictionGeometry::FixedPoint(def.geom_loop),
        };
        let geom_rule = match geometry {
            FrictionGeometry::FixedPoint(g) => g,
            FrictionGeometry::Newton { .. } => crate::zone::GeomLoop::Sans,
        };
        Ok(ContinuousFriction {
            zones,
            points,
            lagr,
            unknowns,
            dim,
            reso_cont: def.algo_reso_cont,
            reso_frot: friction.algo_reso_frot,
            geometry,
            resi_frot: friction.resi_frot,
            iter_cont_maxi: def.iter_cont_maxi,
            iter_frot_maxi: friction.iter_frot_maxi,
            cycling: friction.cycling,
            adapt_coef: friction.adapt_coef,
            coef_ranges: Vec::new(),
            u_start: Vec::new(),
            geom: GeomLoopState::new(geom_rule),
            cont_loops: 0,
            frot_loops: 0,
            own_prev: None,
            newton_iterations: 0,
            first_increment: true,
            edge_min,
            edge_max,
            snapshots: Vec::new(),
            decoupled: Vec::new(),
            forces_cont: HashMap::new(),
            forces_frot: HashMap::new(),
        })
    }

    /// The slave nodes and their multipliers `[LAGS_C, LAGS_F1, LAGS_F2]`
    /// (missing components 0) from the source's unknowns.
    pub fn multipliers(&self, own: &[f64]) -> Vec<(NodeId, [f64; 3])> {
        self.lagr
            .iter()
            .map(|l| {
                let mut v = [0.0; 3];
                for k in 0..l.comps {
                    v[k] = own.get(l.first + k).copied().unwrap_or(0.0);
                }
                (l.node, v)
            })
            .collect()
    }

    /// Whether the zones carry friction multipliers (`LAGS_F1`…).
    pub fn has_friction_unknowns(&self) -> bool {
        self.lagr.iter().any(|l| l.comps > 1)
    }

    /// CONT_NOEU of the converged step at `time` (within 1e-9 relative).
    pub fn cont_noeu_at(&self, time: f64) -> Option<&ContNoeu> {
        self.snapshots
            .iter()
            .rev()
            .find(|(t, _)| (t - time).abs() <= 1e-9 * time.abs().max(1.0))
            .map(|(_, c)| c)
    }

    /// Pairs every point on the current geometry `x` at `time` (the
    /// `DIST_MAIT`/`DIST_ESCL` functions of `INST` are taken there).
    fn pair_all(&mut self, x: &[[f64; 3]], time: f64) -> Result<(), ContactError> {
        let dim = self.dim;
        for p in self.points.iter_mut() {
            let fz = &self.zones[p.zone];
            let z = &fz.zone;
            let sp = SlavePoint {
                zone: z.index,
                nodes: p.slave.iter().copied().filter(|(_, s)| *s != 0.0).collect(),
                weight: p.weight,
                cell: Some((p.cell, p.xi)),
            };
            let cp = pair_point(z, &sp, x)?;
            match cp.status {
                PairStatus::Paired(pp) => {
                    let n = scale(pp.normal, -1.0);
                    let mut tau = tangents(dim, n);
                    if let (Some(d), false, 3) = (fz.dire_excl, p.fric_excl.is_empty(), dim) {
                        // mmexfr: the first tangent along the excluded
                        // direction projected on the tangent plane.
                        let e1 = dot(d, tau[0]);
                        let e2 = dot(d, tau[1]);
                        let t = [
                            e1 * tau[0][0] + e2 * tau[1][0],
                            e1 * tau[0][1] + e2 * tau[1][1],
                            e1 * tau[0][2] + e2 * tau[1][2],
                        ];
                        let l = norm(t);
                        if l <= f64::EPSILON {
                            return Err(ContactError::Invalid {
                                keyword: "DIRE_EXCL_FROT",
                                message: format!(
                                    "the direction {d:?} is normal to the master surface of zone {}",
                                    z.index + 1
                                ),
                            });
                        }
                        let t1 = scale(t, 1.0 / l);
                        tau = [t1, cross(t1, n)];
                    }
                    // code_aster's cfdist: DIST_MAIT + DIST_ESCL + the
                    // structural offset (DIST_POUTRE, DIST_COQUE).
                    let jeusup = z.geometry.dist_mait.at_time(pp.master_x, time)
                        + z.geometry.dist_escl.at_time(pp.slave_x, time)
                        + z.structural_gap(&sp);
                    p.pair = Some(PointPair {
                        master: pp.master,
                        n,
                        tau,
                        jeusup,
                        master_x: pp.master_x,
                        slave_x: pp.slave_x,
                    });
                    p.unpaired = false;
                }
                PairStatus::Excluded(_) => {
                    p.pair = None;
                    p.unpaired = true;
                }
            }
        }
        Ok(())
    }

    /// Values of a point at the state.
    fn values(
        &self,
        p: &Point,
        pair: Option<&PointPair>,
        state: &State,
        own: &[f64],
    ) -> PointValues {
        let mut xs = [0.0; 3];
        let mut v = [0.0; 3];
        for &(n, s) in &p.slave {
            let x = state.current_coord(n);
            let u = state.node_displacement(n);
            let u0 = self.start_displacement(state, n);
            for c in 0..3 {
                xs[c] += s * x[c];
                v[c] += s * (u[c] - u0[c]);
            }
        }
        let mut lambda = 0.0;
        let mut lf = [0.0; 2];
        for (i, &(_, s)) in p.slave.iter().enumerate() {
            let l = self.lagr[p.lagr[i]];
            lambda += s * own[l.first];
            for k in 0..l.comps.saturating_sub(1) {
                lf[k] += s * own[l.first + 1 + k];
            }
        }
        let (jeu, lam_f) = match pair {
            Some(pp) => {
                let mut xm = [0.0; 3];
                for &(n, s) in &pp.master {
                    let x = state.current_coord(n);
                    let u = state.node_displacement(n);
                    let u0 = self.start_displacement(state, n);
                    for c in 0..3 {
                        xm[c] += s * x[c];
                        v[c] -= s * (u[c] - u0[c]);
                    }
                }
                let jeu = pp.jeusup + dot(sub(xs, xm), pp.n);
                let mut lam_f = [0.0; 3];
                for c in 0..3 {
                    lam_f[c] = lf[0] * pp.tau[0][c] + lf[1] * pp.tau[1][c];
                }
                (jeu, lam_f)
            }
            None => (0.0, [lf[0], lf[1], 0.0]),
        };
        PointValues {
            jeu,
            v,
            lambda,
            lam_f,
        }
    }

    fn start_displacement(&self, state: &State, n: NodeId) -> [f64; 3] {
        let mut u = [0.0; 3];
        if let Some(first) = state.dofs.node_first(n) {
            for (k, c) in state.dofs.node_comps(n).iter().enumerate() {
                let slot = match c {
                    Comp::DX => 0,
                    Comp::DY => 1,
                    Comp::DZ => 2,
                    _ => continue,
                };
                u[slot] = self.u_start.get(first + k).copied().unwrap_or(0.0);
            }
        }
        u
    }

    /// The element of a point: local unknowns, residual and tangent.
    fn element(&self, p: &Point, state: &State, own: &[f64]) -> Result<Local, FemError> {
        let fz = &self.zones[p.zone];
        let dim = self.dim;
        let nf = if fz.frictional { dim - 1 } else { 0 };
        let pair = if p.sans || p.unpaired {
            None
        } else {
            p.pair.as_ref()
        };
        let nne = p.slave.len();
        let nnm = pair.map(|pp| pp.master.len()).unwrap_or(0);
        let nnl = nne;
        let ne = nne * dim;
        let nm = nnm * dim;
        let base_l = ne + nm;
        let base_f = base_l + nnl;
        let size = base_f + nnl * nf;
        let mut unknowns = Vec::with_capacity(size);
        let dof = |n: NodeId, d: usize| -> Result<Unknown, FemError> {
            state
                .dofs
                .index(Dof::new(n, comp_of(d)))
                .map(Unknown::Dof)
                .ok_or_else(|| {
                    FemError::Model(format!(
                        "contact: node {} has no {} in the model",
                        state.mesh.node_name(n),
                        comp_of(d).name()
                    ))
                })
        };
        for &(n, _) in &p.slave {
            for d in 0..dim {
                unknowns.push(dof(n, d)?);
            }
        }
        if let Some(pp) = pair {
            for &(n, _) in &pp.master {
                for d in 0..dim {
                    unknowns.push(dof(n, d)?);
                }
            }
        }
        for &l in &p.lagr {
            unknowns.push(Unknown::Own(self.lagr[l].first));
        }
        for &l in &p.lagr {
            for k in 0..nf {
                unknowns.push(Unknown::Own(self.lagr[l].first + 1 + k));
            }
        }
        let mut r = vec![0.0; size];
        let mut kmat = vec![0.0; size * size];
        let w = p.weight;
        let ne_s: Vec<f64> = p.slave.iter().map(|s| s.1).collect();
        let nm_s: Vec<f64> = pair
            .map(|pp| pp.master.iter().map(|m| m.1).collect())
            .unwrap_or_default();
        let vals = self.values(p, pair, state, own);
        let (rho, pena_cont) = match p.cycl_pena {
            Some(k) => (k, true),
            None => (fz.coef_cont, fz.pena_cont),
        };
        let rho_f = p.coef_elem.unwrap_or(p.fric.coef);
        let contact = p.contact && pair.is_some();
        let (n, tau) = match pair {
            Some(pp) => (pp.n, pp.tau),
            None => {
                let t = if dim == 2 {
                    [[1.0, 0.0, 0.0], [0.0; 3]]
                } else {
                    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
                };
                ([0.0; 3], t)
            }
        };
        // Intermediate variables z = (g, v[3], λ, Λvec[3], lam): their
        // derivatives with respect to each local unknown.
        const NZ: usize = 9;
        let mut dz = vec![[0.0; NZ]; size];
        for a in 0..nne {
            for d in 0..dim {
                let j = a * dim + d;
                dz[j][0] = ne_s[a] * n[d];
                dz[j][1 + d] = ne_s[a];
            }
        }
        for b in 0..nnm {
            for d in 0..dim {
                let j = ne + b * dim + d;
                dz[j][0] = -nm_s[b] * n[d];
                dz[j][1 + d] = -nm_s[b];
            }
        }
        // The threshold: LAGS_C at the point with Newton friction (when not
        // zero), else the stored one (`mmlagc`).
        let newton_frot = self.reso_frot == Resolution::Newton;
        let (lam, lam_is_lambda) = if newton_frot && vals.lambda != 0.0 {
            (vals.lambda, true)
        } else {
            (p.threshold, false)
        };
        for l in 0..nnl {
            dz[base_l + l][4] = ne_s[l];
            if lam_is_lambda {
                dz[base_l + l][8] = ne_s[l];
            }
            for k in 0..nf {
                for c in 0..3 {
                    dz[base_f + l * nf + k][5 + c] = ne_s[l] * tau[k][c];
                }
            }
        }
        // F (slave force, 3), Gc (λ eq.), Gf (Λ eq., nf) and their partial
        // derivatives with respect to z.
        let mut fe = [0.0; 3];
        let mut fe_cont = [0.0; 3];
        let mut dfe = [[0.0; NZ]; 3];
        let gc: f64;
        let mut dgc = [0.0; NZ];
        let mut gf = [0.0; 2];
        let mut dgf = [[0.0; NZ]; 2];
        // Which derivatives code_aster's matrices leave out (`mmmtec`: the
        // friction force's derivative with respect to λ only without
        // friction penalisation).
        let mut keep_dfe_lam = true;
        let keep_dgf_lam = false;
        let pmat = |x: [f64; 3]| tangential_part(x, n);
        if contact {
            if pena_cont {
                for c in 0..3 {
                    fe[c] += n[c] * rho * vals.jeu;
                    fe_cont[c] += n[c] * rho * vals.jeu;
                    dfe[c][0] += n[c] * rho;
                }
                gc = -(vals.lambda / rho + vals.jeu);
                dgc[4] = -1.0 / rho;
                dgc[0] = -1.0;
            } else {
                let cc = vals.lambda - rho * vals.jeu;
                for c in 0..3 {
                    fe[c] += -n[c] * cc;
                    fe_cont[c] += -n[c] * cc;
                    dfe[c][4] += -n[c];
                    dfe[c][0] += n[c] * rho;
                }
                gc = -vals.jeu;
                dgc[0] = -1.0;
            }
        } else {
            gc = -vals.lambda / rho;
            dgc[4] = -1.0 / rho;
        }
        let mut phase = "SANS";
        if fz.frictional {
            let tt: Vec<f64> = (0..nf).map(|k| dot(vals.lam_f, tau[k])).collect();
            let vt = pmat(vals.v);
            let fric_no = lam == 0.0;
            let mu = fz.mu;
            let s = mu * lam;
            if contact && !fric_no {
                let rese = if fz.pena_frot {
                    scale(vt, rho_f)
                } else {
                    [
                        vals.lam_f[0] + rho_f * vt[0],
                        vals.lam_f[1] + rho_f * vt[1],
                        vals.lam_f[2] + rho_f * vt[2],
                    ]
                };
                let nrese = norm(rese);
                if nrese <= 1.0 {
                    phase = "ADHE";
                    if fz.pena_frot {
                        keep_dfe_lam = false;
                        let f = scale(vt, rho_f);
                        for c in 0..3 {
                            fe[c] += -s * f[c];
                            for cc in 0..3 {
                                let pcc = if c == cc { 1.0 } else { 0.0 } - n[c] * n[cc];
                                dfe[c][1 + cc] += -s * rho_f * pcc;
                            }
                            dfe[c][8] += -mu * f[c];
                        }
                        for k in 0..nf {
                            gf[k] = s * (tt[k] / rho_f - dot(vt, tau[k]));
                            let ptk = pmat(tau[k]);
                            for c in 0..3 {
                                dgf[k][5 + c] += s * tau[k][c] / rho_f;
                                dgf[k][1 + c] += -s * ptk[c];
                            }
                            dgf[k][8] += mu * (tt[k] / rho_f - dot(vt, tau[k]));
                        }
                    } else {
                        let pl = pmat(vals.lam_f);
                        let f = [
                            pl[0] + rho_f * vt[0],
                            pl[1] + rho_f * vt[1],
                            pl[2] + rho_f * vt[2],
                        ];
                        for c in 0..3 {
                            fe[c] += -s * f[c];
                            for cc in 0..3 {
                                let pcc = if c == cc { 1.0 } else { 0.0 } - n[c] * n[cc];
                                dfe[c][5 + cc] += -s * pcc;
                                dfe[c][1 + cc] += -s * rho_f * pcc;
                            }
                            dfe[c][8] += -mu * f[c];
                        }
                        for k in 0..nf {
                            gf[k] = -s * dot(vt, tau[k]);
                            let ptk = pmat(tau[k]);
                            for c in 0..3 {
                                dgf[k][1 + c] += -s * ptk[c];
                            }
                            dgf[k][8] += -mu * dot(vt, tau[k]);
                        }
                    }
                } else {
                    phase = "GLIS";
                    if fz.pena_frot {
                        keep_dfe_lam = false;
                    }
                    let dvec = scale(rese, 1.0 / nrese);
                    // D = (I − d dᵀ)/|r|.
                    let dd = |a: usize, b: usize| -> f64 {
                        ((if a == b { 1.0 } else { 0.0 }) - dvec[a] * dvec[b]) / nrese
                    };
                    // ∂r/∂v = ρ_f P; ∂r/∂Λvec = I (standard) or 0.
                    let pd = pmat(dvec);
                    for c in 0..3 {
                        fe[c] += -s * pd[c];
                        dfe[c][8] += -mu * pd[c];
                    }
                    // ∂(P d)/∂r = P D.
                    for c in 0..3 {
                        for e in 0..3 {
                            // (P D)[c][e]
                            let mut pdce = 0.0;
                            for m in 0..3 {
                                let pcm = if c == m { 1.0 } else { 0.0 } - n[c] * n[m];
                                pdce += pcm * dd(m, e);
                            }
                            if !fz.pena_frot {
                                dfe[c][5 + e] += -s * pdce;
                            }
                            // ∂r_e/∂v_f = ρ_f P[e][f]
                            for f in 0..3 {
                                let pef = if e == f { 1.0 } else { 0.0 } - n[e] * n[f];
                                dfe[c][1 + f] += -s * pdce * rho_f * pef;
                            }
                        }
                    }
                    for k in 0..nf {
                        gf[k] = s / rho_f * dot(sub(vals.lam_f, dvec), tau[k]);
                        // τ_kᵀ D
                        let mut td = [0.0; 3];
                        for e in 0..3 {
                            for m in 0..3 {
                                td[e] += tau[k][m] * dd(m, e);
                            }
                        }
                        for e in 0..3 {
                            let from_r = if fz.pena_frot { 0.0 } else { td[e] };
                            dgf[k][5 + e] += s / rho_f * (tau[k][e] - from_r);
                            for f in 0..3 {
                                let pef = if e == f { 1.0 } else { 0.0 } - n[e] * n[f];
                                dgf[k][1 + f] += -s / rho_f * td[e] * rho_f * pef;
                            }
                        }
                        dgf[k][8] += mu / rho_f * dot(sub(vals.lam_f, dvec), tau[k]);
                    }
                }
            } else {
                phase = if contact { "NCON" } else { "SANS" };
                let sgn = if pena_cont || fz.pena_frot {
                    -1.0 / rho_f
                } else {
                    1.0
                };
                for k in 0..nf {
                    gf[k] = sgn * tt[k];
                    for c in 0..3 {
                        dgf[k][5 + c] += sgn * tau[k][c];
                    }
                }
            }
        }
        if !keep_dfe_lam {
            for row in dfe.iter_mut() {
                row[8] = 0.0;
            }
        }
        if !keep_dgf_lam {
            for row in dgf.iter_mut() {
                row[8] = 0.0;
            }
        }
        // Residual and tangent.
        let chain = |dfz: &[f64; NZ], j: usize| -> f64 {
            let mut s = 0.0;
            for q in 0..NZ {
                s += dfz[q] * dz[j][q];
            }
            s
        };
        for a in 0..nne {
            for d in 0..dim {
                let i = a * dim + d;
                r[i] = w * ne_s[a] * fe[d];
                for j in 0..size {
                    kmat[i * size + j] = w * ne_s[a] * chain(&dfe[d], j);
                }
            }
        }
        for b in 0..nnm {
            for d in 0..dim {
                let i = ne + b * dim + d;
                r[i] = -w * nm_s[b] * fe[d];
                for j in 0..size {
                    kmat[i * size + j] = -w * nm_s[b] * chain(&dfe[d], j);
                }
            }
        }
        for l in 0..nnl {
            let i = base_l + l;
            r[i] = w * ne_s[l] * gc;
            for j in 0..size {
                kmat[i * size + j] = w * ne_s[l] * chain(&dgc, j);
            }
        }
        for l in 0..nnl {
            for k in 0..nf {
                let i = base_f + l * nf + k;
                r[i] = w * ne_s[l] * gf[k];
                for j in 0..size {
                    kmat[i * size + j] = w * ne_s[l] * chain(&dgf[k], j);
                }
            }
        }
        // SANS_GROUP_NO_FR / DIRE_EXCL_FROT (mmmvex, mmmtex): the excluded
        // components keep their value.
        for &(l, k) in &p.fric_excl {
            if k >= nf {
                continue;
            }
            let i = base_f + l * nf + k;
            r[i] = 0.0;
            kmat[i * size + i] = 1.0;
            for j in 0..base_l {
                kmat[i * size + j] = 0.0;
                kmat[j * size + i] = 0.0;
            }
        }
        let mut slave_cont = vec![0.0; ne];
        for a in 0..nne {
            for d in 0..dim {
                slave_cont[a * dim + d] = w * ne_s[a] * fe_cont[d];
            }
        }
        Ok(Local {
            unknowns,
            r,
            k: kmat,
            slave_cont,
            contact,
            friction: phase == "ADHE" || phase == "GLIS",
        })
    }

    /// The contact status of every point at the state (`mmmbca`): returns
    /// whether any changed, and the largest motion of the contact points
    /// relative to the longest master edge (code_aster's Newton geometric
    /// criterion).
    fn update_statuses(&mut self, state: &State, own: &[f64]) -> Result<(bool, f64), FemError> {
        let mut changed = false;
        let mut motion: f64 = 0.0;
        for i in 0..self.points.len() {
            let p = &self.points[i];
            let pair = if p.sans || p.unpaired {
                None
            } else {
                p.pair.clone()
            };
            let vals = self.values(p, pair.as_ref(), state, own);
            let rho = p.cycl_pena.unwrap_or(self.zones[p.zone].coef_cont);
            let mut now = match &pair {
                Some(_) => vals.lambda - rho * vals.jeu < 0.0,
                None => false,
            };
            // code_aster's adaptation of COEF_FROT (`mm_cycl_d2`,
            // `mm_cycl_trait`), on the evaluated statuses.
            if let (true, true, Some(pp)) = (self.adapt_coef, self.zones[p.zone].frictional, &pair)
            {
                let slip = tangential_part(vals.v, pp.n);
                let before = p.fric.coef;
                let zone = p.zone;
                let coef = adaptation::update(&mut self.points[i].fric, now, vals.lam_f, slip)
                    .map_err(|_| {
                        FemError::Source(format!(
                            "{}: code_aster stops on an assertion here (mm_cycl_adaf: a point whose COEF_FROT is adapted as sliding reaches a clear slip) at time {}",
                            self.describe(),
                            state.time
                        ))
                    })?;
                if let Some(r) = self.coef_ranges.get_mut(zone) {
                    r.record(coef);
                }
                if coef != before && std::env::var_os("ASTER_CONTACT_TRACE").is_some() {
                    eprintln!("[friction] point {i}: COEF_FROT adapted {before:e} -> {coef:e}");
                }
            }
            let p = &self.points[i];
            let mut lambda = vals.lambda;
            let mut jeu = vals.jeu;
            let master: Option<Vec<NodeId>> = pair
                .as_ref()
                .map(|pp| pp.master.iter().map(|m| m.0).collect());
            // code_aster's cycling treatment (`mm_cycl_algo`), driven by
            // its Newton count (0 after the prediction).
            let same_master = master.is_some() && master == p.last_master;
            let flipped_now = now != p.contact;
            if cycling::applies(
                self.cycling,
                same_master,
                self.newton_iterations.saturating_sub(1),
                flipped_now,
            ) {
                let newton_contact = self.reso_cont == Resolution::Newton;
                let proj = cycling::project(
                    cycling::PointState {
                        contact: now,
                        pres: vals.lambda,
                        gap: vals.jeu,
                    },
                    cycling::PointState {
                        contact: p.contact,
                        pres: p.threshold,
                        gap: p.gap,
                    },
                    newton_contact,
                );
                if std::env::var_os("ASTER_CONTACT_TRACE").is_some() {
                    eprintln!(
                        "[friction] cycling: point {i} (node {:?}) at Newton iteration {}: {:?}",
                        p.node,
                        self.newton_iterations.saturating_sub(1),
                        proj
                    );
                }
                now = proj.current.contact;
                lambda = proj.current.pres;
                jeu = proj.current.gap;
                let fz = &self.zones[p.zone];
                let pena = cycling::penalty(fz.pena_cont.then_some(fz.coef_cont), self.edge_min);
                let settled = proj.current.contact == proj.previous.contact;
                let p = &mut self.points[i];
                p.cycl_pena = Some(pena);
                // The statuses compared are the projected ones.
                if !settled {
                    changed = true;
                }
                p.contact = proj.previous.contact;
            }
            // Penalised friction beside augmented contact: the point's
            // coefficient after its update (`mm_cycl_algo`, last block).
            let fz = &self.zones[self.points[i].zone];
            if let (true, false, true, Some(pp)) =
                (fz.pena_frot, fz.pena_cont, fz.frictional, &pair)
            {
                let slip = tangential_part(vals.v, pp.n);
                let p = &mut self.points[i];
                let before = p.fric.coef;
                p.fric.coef = adaptation::pena_frot_update(
                    before,
                    now,
                    slip,
                    fz.glis_maxi,
                    self.edge_min,
                    self.edge_max,
                );
                if p.fric.coef != before && std::env::var_os("ASTER_CONTACT_TRACE").is_some() {
                    eprintln!(
                        "[friction] point {i}: COEF_PENA_FROT {before:e} -> {:e} (slip {:e})",
                        p.fric.coef,
                        norm(slip)
                    );
                }
            }
            let p = &self.points[i];
            let positions = pair.as_ref().map(|pp| {
                let mut xs = [0.0; 3];
                for &(n, s) in &p.slave {
                    let x = state.current_coord(n);
                    for c in 0..3 {
                        xs[c] += s * x[c];
                    }
                }
                let mut xm = [0.0; 3];
                for &(n, s) in &pp.master {
                    let x = state.current_coord(n);
                    for c in 0..3 {
                        xm[c] += s * x[c];
                    }
                }
                (xs, xm)
            });
            let p = &mut self.points[i];
            if now != p.contact {
                changed = true;
                if std::env::var_os("ASTER_CONTACT_TRACE").is_some() {
                    eprintln!(
                        "[friction] point {i} (node {:?}) contact {} -> {now}: lambda {:.4e} gap {:.4e}",
                        p.node, p.contact, vals.lambda, vals.jeu
                    );
                }
            }
            if let (Some((xs, xm)), Some((ps, pm)), true) = (positions, p.last_x, now) {
                motion = motion.max(norm(sub(xs, ps)) + norm(sub(xm, pm)));
            }
            p.last_x = positions;
            p.last_master = master;
            p.contact = now;
            p.gap = jeu;
            p.threshold = lambda;
        }
        // `mm_cycl_prop`: the zone's largest coefficient given to the others.
        if self.adapt_coef {
            for p in &mut self.points {
                if let (true, Some(&r)) =
                    (self.zones[p.zone].frictional, self.coef_ranges.get(p.zone))
                {
                    adaptation::propagate(&mut p.fric, r);
                }
            }
        }
        // `mmchml_c` after the update: at code_aster's Newton iteration 1
        // (ours counts solves, so 2) the field keeps each penalised-friction
        // point's coefficient and the history takes 1e-3 ×
        // `estimated_coefficient` × `arete_min` / `GLIS_MAXI`.
        let first = self.newton_iterations == 2;
        for p in &mut self.points {
            p.coef_elem = None;
            let fz = &self.zones[p.zone];
            if first && fz.pena_frot && !fz.pena_cont && fz.frictional {
                p.coef_elem = Some(p.fric.coef);
                p.fric.coef = adaptation::pena_frot_first_iteration(
                    adaptation::ESTIMATED_COEFFICIENT,
                    self.edge_min,
                    fz.glis_maxi,
                );
            }
        }
        Ok((changed, motion / self.edge_max.max(1e-300)))
    }

    /// Node of the first own unknown of each Lagrange node, for messages.
    fn name_of_unknown(&self, k: usize, mesh: &Mesh) -> String {
        for l in &self.lagr {
            if k >= l.first && k < l.first + l.comps {
                let c = ["LAGS_C", "LAGS_F1", "LAGS_F2"][k - l.first];
                return format!("{c} of node {}", mesh.node_name(l.node));
            }
        }
        format!("unknown #{k}")
    }

    /// CONT_NOEU at the converged state (`mmmres`).
    fn cont_noeu(&self, state: &State, own: &[f64]) -> ContNoeu {
        let mut nodes = Vec::new();
        let mut values: Vec<[f64; 19]> = Vec::new();
        let mut index: HashMap<NodeId, usize> = HashMap::new();
        // PROJ_X/Y(/Z): the master point of each paired slave node on the
        // current geometry (`mmmres` → `mcopco`, whatever the status; PROJ_Z
        // only in 3D); NaN where not written.
        let mut proj: Vec<[f64; 3]> = Vec::new();
        for p in &self.points {
            let Some(node) = p.node else { continue };
            let fz = &self.zones[p.zone];
            let mut v = [0.0; 19];
            let mut xm = [f64::NAN; 3];
            if p.unpaired {
                v[0] = -1.0;
            }
            v[1] = -p.gap;
            if let Some(pp) = &p.pair {
                for c in 0..self.dim {
                    xm[c] = 0.0;
                }
                for &(n, sh) in &pp.master {
                    let x = state.current_coord(n);
                    for c in 0..self.dim {
                        xm[c] += sh * x[c];
                    }
                }
            }
            if p.contact && !p.sans && !p.unpaired {
                v[0] = 1.0;
                let rn = self.forces_cont.get(&node).copied().unwrap_or([0.0; 3]);
                v[3] = rn[0];
                v[4] = rn[1];
                v[5] = rn[2];
                v[2] = norm(rn);
                if fz.frictional {
                    if let Some(pp) = &p.pair {
                        let vals = self.values(p, Some(pp), state, own);
                        let g1 = dot(vals.v, pp.tau[0]);
                        let g2 = if self.dim == 3 {
                            dot(vals.v, pp.tau[1])
                        } else {
                            0.0
                        };
                        v[6] = g1;
                        v[7] = g2;
                        v[8] = (g1 * g1 + g2 * g2).sqrt();
                    }
                    let l = self.lagr.iter().find(|l| l.node == node);
                    let lagsf = l
                        .map(|l| {
                            (1..l.comps)
                                .map(|k| own[l.first + k] * own[l.first + k])
                                .sum::<f64>()
                                .sqrt()
                        })
                        .unwrap_or(0.0);
                    let rt = self.forces_frot.get(&node).copied().unwrap_or([0.0; 3]);
                    if lagsf >= 0.999 {
                        v[0] = 2.0;
                        v[12] = rt[0];
                        v[13] = rt[1];
                        v[14] = rt[2];
                    } else {
                        v[9] = rt[0];
                        v[10] = rt[1];
                        v[11] = rt[2];
                    }
                } else {
                    v[0] = 2.0;
                }
            }
            for c in 0..3 {
                v[15 + c] = v[3 + c] + v[9 + c] + v[12 + c];
            }
            v[18] = (v[15] * v[15] + v[16] * v[16] + v[17] * v[17]).sqrt();
            match index.get(&node) {
                Some(&k) => {
                    values[k] = v;
                    proj[k] = xm;
                }
                None => {
                    index.insert(node, nodes.len());
                    nodes.push(node);
                    values.push(v);
                    proj.push(xm);
                }
            }
        }
        // code_aster's CONT_NOEU holds every slave node, zero where no
        // contact point is that node (`cfmxr0`; `mmmres` writes the points
        // that are nodes only, `mmnumn`: AUTO/NOEUD integration), so with
        // GAUSS, SIMPSON or NCOTES points it is zero at every node.
        for fz in &self.zones {
            for &n in &fz.zone.slave_nodes {
                if let std::collections::hash_map::Entry::Vacant(e) = index.entry(n) {
                    e.insert(nodes.len());
                    nodes.push(n);
                    values.push([0.0; 19]);
                    proj.push([f64::NAN; 3]);
                }
            }
        }
        ContNoeu {
            nodes,
            values,
            proj,
        }
    }

    /// The contact and friction forces at the slave nodes (the assembled
    /// element vectors, internal-force side), recorded for CONT_NOEU.
    fn record_forces(&mut self, state: &State, own: &[f64]) -> Result<(), FemError> {
        let mut cont: HashMap<NodeId, [f64; 3]> = HashMap::new();
        let mut frot: HashMap<NodeId, [f64; 3]> = HashMap::new();
        for p in &self.points {
            let e = self.element(p, state, own)?;
            for (a, &(n, _)) in p.slave.iter().enumerate() {
                for d in 0..self.dim {
                    let i = a * self.dim + d;
                    cont.entry(n).or_insert([0.0; 3])[d] += e.slave_cont[i];
                    frot.entry(n).or_insert([0.0; 3])[d] += e.r[i] - e.slave_cont[i];
                }
            }
        }
        self.forces_cont = cont;
        self.forces_frot = frot;
        Ok(())
    }

    /// Nodal translations of the state (the geometric loop's measure).
    fn nodal(state: &State) -> Vec<[f64; 3]> {
        (0..state.mesh.coords.len())
            .map(|i| state.node_displacement(NodeId(i as u32)))
            .collect()
    }

    fn positions(state: &State) -> Vec<[f64; 3]> {
        crate::source::current_positions(state)
    }

    /// The contact statuses of the first step (`CONTACT_INIT`, `mmopti`).
    fn initial_statuses(&mut self, state: &State) {
        for i in 0..self.points.len() {
            let p = &self.points[i];
            let init = self.zones[p.zone].contact_init;
            let eps = self.zones[p.zone].init_threshold;
            let now = match (&p.pair, p.sans || p.unpaired) {
                (Some(pp), false) => match init {
                    ContactInit::Non => false,
                    ContactInit::Oui => true,
                    ContactInit::Interpenetre => {
                        let mut xs = [0.0; 3];
                        for &(n, s) in &p.slave {
                            let x = state.current_coord(n);
                            for c in 0..3 {
                                xs[c] += s * x[c];
                            }
                        }
                        let mut xm = [0.0; 3];
                        for &(n, s) in &pp.master {
                            let x = state.current_coord(n);
                            for c in 0..3 {
                                xm[c] += s * x[c];
                            }
                        }
                        -dot(sub(xs, xm), pp.n) <= eps
                    }
                },
                _ => false,
            };
            self.points[i].contact = now;
        }
    }

    fn err(&self, e: ContactError) -> FemError {
        FemError::Source(format!("{}: {e}", self.describe()))
    }

    fn describe(&self) -> String {
        let groups: Vec<String> = self
            .zones
            .iter()
            .map(|z| {
                format!(
                    "{} on {}",
                    z.zone.geometry.slave_group, z.zone.geometry.master_group
                )
            })
            .collect();
        format!("contact with friction ({})", groups.join(", "))
    }

    /// Largest |Δ LAGS_C| of the last solve relative to the largest
    /// |LAGS_C| (code_aster's Newton friction criterion, `mmmcrf`).
    fn lags_c_change(&self, own: &[f64]) -> f64 {
        let Some(prev) = &self.own_prev else {
            return f64::INFINITY;
        };
        let mut dmax: f64 = 0.0;
        let mut vmax: f64 = 0.0;
        for l in &self.lagr {
            dmax = dmax.max((own[l.first] - prev[l.first]).abs());
            vmax = vmax.max(own[l.first].abs());
        }
        if vmax > 1.0 {
            dmax / vmax
        } else if vmax > 0.0 {
            dmax
        } else {
            0.0
        }
    }
}

impl ForceSource for ContinuousFriction {
    fn name(&self) -> String {
        self.describe()
    }

    fn unknowns(&self) -> usize {
        self.unknowns
    }

    fn begin_increment(&mut self, state: &State, own: &mut [f64]) -> Result<(), FemError> {
        self.u_start = state.displacement.to_vec();
        // code_aster zeroes the multipliers of the previous state at each
        // step (`misazl`): the increment carries their whole value.
        own.iter_mut().for_each(|v| *v = 0.0);
        let x = Self::positions(state);
        let pair = match self.geometry {
            FrictionGeometry::Newton { .. } => true,
            FrictionGeometry::FixedPoint(_) => {
                match self.geom.decide(state.time, &Self::nodal(state)) {
                    GeomDecision::Pair => true,
                    GeomDecision::Keep => self.first_increment,
                    GeomDecision::Diverged { .. } => true,
                }
            }
        };
        if pair {
            self.pair_all(&x, state.time).map_err(|e| self.err(e))?;
        }
        if self.first_increment {
            self.initial_statuses(state);
        }
        self.cont_loops = 0;
        self.frot_loops = 0;
        self.newton_iterations = 0;
        // code_aster's cycling history is initialised at each step
        // (`mminit` → `mm_cycl_init`): no penalised point, no master cell
        // of a previous update (so no treatment at the step's first).
        for p in &mut self.points {
            p.cycl_pena = None;
            p.last_master = None;
            p.fric = adaptation::History::new(self.zones[p.zone].coef_frot);
            p.coef_elem = None;
        }
        self.coef_ranges = vec![adaptation::Range::default(); self.zones.len()];
        self.own_prev = Some(own.to_vec());
        Ok(())
    }

    fn evaluate(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError> {
        let mut c = Contribution {
            forces: Vec::new(),
            own_residual: vec![0.0; self.unknowns],
            tangent: Vec::new(),
        };
        let mut decoupled = vec![(true, true); self.lagr.len()];
        for p in &self.points {
            let e = self.element(p, state, own)?;
            for (i, &(n, shape)) in p.slave.iter().enumerate() {
                if shape == 0.0 {
                    continue;
                }
                let l = p.lagr[i];
                if p.node != Some(n) {
                    decoupled[l] = (false, false);
                }
                if e.contact {
                    decoupled[l].0 = false;
                }
                if e.friction || !p.fric_excl.is_empty() {
                    decoupled[l].1 = false;
                }
            }
            let size = e.unknowns.len();
            for (i, ui) in e.unknowns.iter().enumerate() {
                match *ui {
                    Unknown::Dof(d) => c.forces.push((d, e.r[i])),
                    Unknown::Own(k) => c.own_residual[k] += e.r[i],
                }
                for (j, uj) in e.unknowns.iter().enumerate() {
                    let v = e.k[i * size + j];
                    if v != 0.0 {
                        c.tangent.push((*ui, *uj, v));
                    }
                }
            }
        }
        self.decoupled = decoupled;
        Ok(c)
    }

    fn after_iteration(&mut self, state: &State, own: &mut [f64]) -> Result<bool, FemError> {
        self.newton_iterations += 1;
        // An open node's pressure and a node without friction's directions
        // solve equations of their own (λ/ρ = 0, Λ·τ = 0): their values are
        // exactly zero; the factorisation leaves round-off there, which the
        // status tests must not read.
        for (l, &(open, free)) in self.lagr.iter().zip(&self.decoupled) {
            if open {
                own[l.first] = 0.0;
            }
            if free {
                for k in 1..l.comps {
                    own[l.first + k] = 0.0;
                }
            }
        }
        if let FrictionGeometry::Newton { .. } = self.geometry {
            let x = Self::positions(state);
            self.pair_all(&x, state.time).map_err(|e| self.err(e))?;
        }
        let mut settled = true;
        if self.reso_cont == Resolution::Newton {
            let (changed, motion) = self.update_statuses(state, own)?;
            settled &= !changed;
            if let FrictionGeometry::Newton { resi_geom } = self.geometry {
                if self.newton_iterations >= 2 {
                    settled &= motion <= resi_geom;
                } else {
                    settled = false;
                }
            }
        }
        if self.reso_frot == Resolution::Newton && self.has_friction_unknowns() {
            settled &= self.lags_c_change(own) <= self.resi_frot;
        }
        self.own_prev = Some(own.to_vec());
        Ok(settled)
    }

    fn after_convergence(&mut self, state: &State, own: &[f64]) -> Result<LoopVerdict, FemError> {
        let verdict = self.loops_verdict(state, own)?;
        if verdict == LoopVerdict::Again {
            // A new pass restarts the step and code_aster's Newton count
            // (`nmnewt`: `iterat = 0` at label 100), which the cycling
            // treatment reads (`ds_contact%iteration_newton`).
            self.newton_iterations = 0;
        }
        Ok(verdict)
    }

    fn unknown_name(&self, k: usize, mesh: &Mesh) -> String {
        self.name_of_unknown(k, mesh)
    }

    fn residual_before_update(&self) -> bool {
        true
    }

    fn converged(&mut self, state: &State, own: &[f64]) -> Result<(), FemError> {
        self.record_forces(state, own)?;
        let cn = self.cont_noeu(state, own);
        self.snapshots.push((state.time, cn));
        self.geom.step_converged(Self::nodal(state));
        self.first_increment = false;
        Ok(())
    }
}

impl ContinuousFriction {
    /// The contact, friction and geometric fixed-point loops after a
    /// converged Newton (`nmtble`: `nmctcc`, `nmctcf`, `nmctgo`).
    fn loops_verdict(&mut self, state: &State, own: &[f64]) -> Result<LoopVerdict, FemError> {
        if self.reso_cont == Resolution::PointFixe {
            let before: Vec<f64> = self.points.iter().map(|p| p.threshold).collect();
            let (changed, _) = self.update_statuses(state, own)?;
            if changed {
                self.cont_loops += 1;
                if self.cont_loops >= self.iter_cont_maxi {
                    return Err(FemError::Source(format!(
                        "{}: the contact statuses did not settle after ITER_CONT_MAXI = {} loops at time {} (raise ITER_CONT_MAXI or use ALGO_RESO_CONT='NEWTON')",
                        self.describe(),
                        self.iter_cont_maxi,
                        state.time
                    )));
                }
                return Ok(LoopVerdict::Again);
            }
            if self.reso_frot == Resolution::PointFixe && self.has_friction_unknowns() {
                let mut dmax: f64 = 0.0;
                let mut vmax: f64 = 0.0;
                for (p, b) in self.points.iter().zip(&before) {
                    dmax = dmax.max((p.threshold - b).abs());
                    vmax = vmax.max(p.threshold.abs());
                }
                let change = if vmax > 0.0 { dmax / vmax } else { 0.0 };
                if change > self.resi_frot {
                    self.frot_loops += 1;
                    if self.frot_loops >= self.iter_frot_maxi {
                        return Err(FemError::Source(format!(
                            "{}: the friction threshold loop did not converge after ITER_FROT_MAXI = {} loops at time {} (change {change:.3e} > RESI_FROT = {:e}): raise ITER_FROT_MAXI or use ALGO_RESO_FROT='NEWTON'",
                            self.describe(),
                            self.iter_frot_maxi,
                            state.time,
                            self.resi_frot
                        )));
                    }
                    return Ok(LoopVerdict::Again);
                }
            }
        } else if self.reso_frot == Resolution::PointFixe && self.has_friction_unknowns() {
            return Err(FemError::Source(format!(
                "{}: ALGO_RESO_FROT='POINT_FIXE' needs ALGO_RESO_CONT='POINT_FIXE' here",
                self.describe()
            )));
        }
        if let FrictionGeometry::FixedPoint(_) = self.geometry {
            match self.geom.decide(state.time, &Self::nodal(state)) {
                GeomDecision::Keep => {}
                GeomDecision::Pair => {
                    let x = Self::positions(state);
                    self.pair_all(&x, state.time).map_err(|e| self.err(e))?;
                    return Ok(LoopVerdict::Again);
                }
                GeomDecision::Diverged { pairings, residual } => {
                    return Err(FemError::Source(format!(
                        "{}: the geometric loop did not converge at time {}: after {pairings} pairings the displacement still changes by {residual:.3e} of the step's displacement (raise ITER_GEOM_MAXI or RESI_GEOM)",
                        self.describe(),
                        state.time
                    )));
                }
            }
        }
        Ok(LoopVerdict::Done)
    }
}
