//! Friction of code_aster 17's mortar contact (`DEFI_CONT(ZONE=_F(…,
//! FROTTEMENT='OUI'))` with `ALGO_CONT='LAGRANGIEN'`,
//! `VARIANTE='ROBUSTE'`, `ALGO_FROT='LAGRANGIEN'`), in 2D on SEG2 and SEG3
//! cells and in 3D on TRIA3 and QUAD4 faces (`new(…, 3)`), as a fem force
//! source whose unknowns are two (2D) or three (3D: `LAGS_F2`, on the
//! faces' corners) multipliers per slave node. On faces the normal is
//! t₁ × t₂ / |t₁ × t₂|, the master point moves along both of its
//! parameters and the friction force lies in the tangent plane; the same
//! code serves both dimensions ([`point_quantities`] with `dim`).
//!
//! As code_aster's (2025 main: `laVect` → `laVect_cf_pr`, `laElemCont`,
//! `contact_module` (`projQpSl2Ma`, `speedEval`, `thresEval`),
//! `contact_algebra_module` (`projRm`, `projBs`, `dPi_du`, `dv_du`),
//! `laQuantities`, `ContactComputation::contactData`):
//!
//! - **Multipliers in global coordinates** (Poulios & Renard): with
//!   friction and the ROBUSTE variant (`glob_coor` in `laElemCont`) the
//!   slave node's unknowns `LAGS_C`, `LAGS_F1` are the x and y components
//!   of one contact force vector λ (per unit slave length), not a pressure
//!   and a tangential component. λ is interpolated with the slave's
//!   functions at each integration point.
//! - **Status**: with n the outward slave normal and g the ray-traced gap
//!   (pairing, points, weights and gap as [`crate::mortar_lagrangian`]),
//!   λ·n + γg ≤ 0 is contact (`Heaviside`, `TOLE_BORNE` = 0;
//!   `CONTACT_INIT` at the first pairing as there); γ = COEF_CONT / h_F is
//!   also the friction coefficient (`gamma_f = gamma_c`: `COEF_FROT` only
//!   exists in the CLASSIQUE variant).
//! - **Threshold** (`thresEval`): `COULOMB`: s = −μ [λ·n + γg]₋ on contact
//!   points, 0 elsewhere; `TRESCA`: s = the given value at every point
//!   (in contact or not); `ADHERENT`: 1e301 on contact points (stick);
//!   `SANS` (code_aster's default `TYPE_FROT`): no friction force.
//! - **Slip** (`speedEval`): v = −(x_s⁻ − x_m⁻ + g n⁻), the slave point and
//!   its current master point on the configuration at the start of the
//!   step, n⁻ the slave normal there: the relative motion over the step.
//! - **Projection** (`projBs`): of λ − γv onto the disc of radius s of the
//!   tangent line: (I − n n)(λ − γv) when its length is at most s (stick),
//!   else s times its direction (slip); nothing when |s| ≤ `r8prem`.
//! - **Residual** (`laVect_cf_pr`): −w λ·(v_s − v_m) on the displacements
//!   at contact points (the whole vector λ, normal and tangential); on
//!   each multiplier component w ([λ·n + γg]₋ n − λ + P)/γ μ; slave nodes of
//!   no paired cell: λ = 0 (code_aster's POI1 elements).
//! - **Tangent**: the exact derivative of that residual for the pairing of
//!   the iterate (the intersection segments and weights held), with the
//!   master point's motion along the master cell and the slave normal's
//!   rotation (`dPi_du`, `dNs_du`, `dv_du`). code_aster's own matrix
//!   (`laMatr_cf_pr`) only changes Newton's path: the converged state is the
//!   zero of the residual above.
//! - **Convergence**: code_aster 17's (`NewtonSolver`, `ConvergenceManager`):
//!   the whole residual, the multiplier rows included, and `RESI_GEOM`
//!   (`mortar_lagrangian::GeometricCriterion`); a change of status does not
//!   by itself prevent convergence.

use aster_fem::{Contribution, FemError, ForceSource, State, Unknown};
use aster_mesh::{Mesh, NodeId};

use crate::error::ContactError;
use crate::mortar_lagrangian::{err, normal_at, ray_hit, MortarLagrangian, MortarZoneDef};
use crate::shape::{dot, interpolate, norm, project_along, sub, SurfaceKind};
use crate::source::current_positions;

/// `TYPE_FROT` of a DEFI_CONT zone with `FROTTEMENT='OUI'`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FrictionLaw {
    /// `'SANS'` (the default): friction unknowns, no friction force.
    Without,
    /// `'TRESCA'`: a given threshold (a force per unit length).
    Tresca(f64),
    /// `'COULOMB'`: the coefficient μ.
    Coulomb(f64),
    /// `'ADHERENT'`: no slip at contact points.
    Stick,
}

/// code_aster's `THRES_STICK` (`contact_module.h`).
pub(crate) const THRES_STICK: f64 = 10e300;
/// code_aster's `r8prem()` (`DBL_EPSILON`).
pub(crate) const R8PREM: f64 = f64::EPSILON;

/// The status of an integration point: contact, and for friction whether
/// the projection slid (its tangential part reached the threshold).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PointStatus {
    pub(crate) contact: bool,
    pub(crate) slip: bool,
}

/// Dense derivatives with respect to a point's local unknowns: slave
/// displacements (2 per node), master displacements, slave multipliers
/// (λx, λy per node).
pub(crate) type Lin = Vec<f64>;

pub(crate) fn lin(n: usize) -> Lin {
    vec![0.0; n]
}

pub(crate) fn axpy(y: &mut Lin, a: f64, x: &Lin) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

pub(crate) fn comb(a: f64, x: &Lin, b: f64, y: &Lin) -> Lin {
    x.iter().zip(y).map(|(p, q)| a * p + b * q).collect()
}

/// What one integration point contributes, on its local unknowns.
struct PointTerms {
    /// Forces on the displacements (slave then master, 2 per node) and
    /// their derivatives.
    forces: Vec<(f64, Lin)>,
    /// Equations of the multipliers (2 per slave node) and derivatives.
    own: Vec<(f64, Lin)>,
}

/// Geometry of a point: slave and master cells on the current and the
/// start-of-step configurations.
pub(crate) struct PointGeometry<'a> {
    /// Space dimension: 2 (segments) or 3 (faces).
    pub(crate) dim: usize,
    pub(crate) s_kind: SurfaceKind,
    pub(crate) sign: f64,
    pub(crate) sp: &'a [[f64; 3]],
    pub(crate) sprev: &'a [[f64; 3]],
    pub(crate) m_kind: SurfaceKind,
    pub(crate) mp: &'a [[f64; 3]],
    pub(crate) mprev: &'a [[f64; 3]],
}

/// The law's data at a point.
pub(crate) struct PointLaw {
    /// The point in the slave's parametric space (ξ, 0 on a segment).
    pub(crate) xi: [f64; 2],
    pub(crate) w: f64,
    pub(crate) gamma: f64,
    pub(crate) law: FrictionLaw,
    /// `CONTACT_INIT` forcing the status (first pairing only).
    pub(crate) forced: Option<bool>,
}

/// The quantities of code_aster's `laElemCont` at a point with friction
/// (`projQpSl2Ma`, `projRm`, `thresEval`, `speedEval`, `projBs`), each
/// with its derivatives on the point's local unknowns: the slave
/// displacements (`dim` per node), the master's, then — with multipliers —
/// the slave multipliers (`dim` per multiplier node: the slave's nodes on
/// a segment, a face's corners). Shared by the Lagrangian friction here
/// and the penalised one ([`crate::mortar_friction_penalty`]).
pub(crate) struct PointQuantities {
    pub(crate) status: PointStatus,
    /// Number of local unknowns.
    pub(crate) nloc: usize,
    /// The slave functions at the point.
    pub(crate) shs: Vec<f64>,
    /// The multipliers' functions at the point (`shapeFuncLagr`).
    pub(crate) shl: Vec<f64>,
    /// The master functions and their derivatives at the master point.
    pub(crate) shm: Vec<f64>,
    pub(crate) dshm: Vec<[f64; 2]>,
    /// The outward slave normal and its derivatives.
    pub(crate) n: [f64; 3],
    pub(crate) dn: [Lin; 3],
    /// The derivatives of the master point's parameters (`dPi_du`).
    pub(crate) dxi: [Lin; 2],
    /// λ at the point (0 without multipliers).
    pub(crate) lam: [f64; 3],
    pub(crate) dlam: [Lin; 3],
    /// `projRm`: [λ·n + γg]₋ at contact points, 0 elsewhere.
    pub(crate) proj_rm: f64,
    pub(crate) dproj_rm: Lin,
    /// `projBs`: the friction force at the point.
    pub(crate) pb: [f64; 3],
    pub(crate) dpb: [Lin; 3],
}

/// The inverse of the 3 × 3 matrix of columns `cols`, `None` when singular
/// relative to `scale`.
fn inverse_of_columns(cols: [[f64; 3]; 3], scale: f64) -> Option<[[f64; 3]; 3]> {
    let a = |i: usize, j: usize| cols[j][i];
    let det = a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1))
        - a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0))
        + a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
    if det.abs() <= f64::EPSILON * scale || !det.is_finite() {
        return None;
    }
    let mut m = [[0.0f64; 3]; 3];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            let (r0, r1) = ((j + 1) % 3, (j + 2) % 3);
            let (c0, c1) = ((i + 1) % 3, (i + 2) % 3);
            *v = (a(r0, c0) * a(r1, c1) - a(r0, c1) * a(r1, c0)) / det;
        }
    }
    Some(m)
}

/// The unnormalised outward slave normal of a segment (sign·(t_y, −t_x))
/// or a face (sign·t₁ × t₂) from its tangents.
fn raw_normal(dim: usize, sign: f64, t: &[[f64; 3]; 2]) -> [f64; 3] {
    if dim == 2 {
        [sign * t[0][1], -sign * t[0][0], 0.0]
    } else {
        let c = crate::shape::cross(t[0], t[1]);
        [sign * c[0], sign * c[1], sign * c[2]]
    }
}

/// One integration point (`laElemCont`), `None` when the ray from the
/// slave point misses the master cell; `lam_nodes`: the multipliers of the
/// slave's multiplier nodes (`None`: a penalised element, λ = 0 and no
/// multiplier unknowns, code_aster's `nb_lagr_c` = 0).
pub(crate) fn point_quantities(
    g: &PointGeometry,
    p: &PointLaw,
    lam_nodes: Option<&[[f64; 3]]>,
) -> Result<Option<PointQuantities>, FemError> {
    let d = g.dim;
    let ns = g.sp.len();
    let nm = g.mp.len();
    let nl = lam_nodes.map_or(0, |l| l.len());
    let nloc = d * (ns + nm + nl);
    let u_s = |a: usize, e: usize| d * a + e;
    let u_m = |b: usize, e: usize| d * ns + d * b + e;
    let l_s = |a: usize, e: usize| d * (ns + nm) + d * a + e;
    let nt = d - 1;

    let (shs, dshs) = g.s_kind.eval(p.xi);
    let shl = if d == 3 && g.s_kind.node_count() > g.s_kind.corner_count() {
        crate::lac_mortar::linear_kind(g.s_kind).eval(p.xi).0
    } else {
        shs.clone()
    };
    // Slave tangents, normal and its derivative.
    let mut t = [[0.0; 3]; 2];
    let mut xs = [0.0; 3];
    for a in 0..ns {
        for c in 0..d {
            for (al, ta) in t.iter_mut().enumerate().take(nt) {
                ta[c] += dshs[a][al] * g.sp[a][c];
            }
            xs[c] += shs[a] * g.sp[a][c];
        }
    }
    let raw = raw_normal(d, g.sign, &t);
    let lt = norm(raw);
    if !(lt > 0.0 && lt.is_finite()) {
        return Err(err(ContactError::Invalid {
            keyword: "GROUP_MA_ESCL",
            message: "a slave cell is degenerate (zero length or area)".into(),
        }));
    }
    let n = [raw[0] / lt, raw[1] / lt, raw[2] / lt];
    let mut dn = [lin(nloc), lin(nloc), lin(nloc)];
    for a in 0..ns {
        for e in 0..d {
            // δt_α = ∂N_a/∂ξ_α e_e; d(raw) from it; dn = (I − nn) d(raw)/|raw|.
            let mut dt = [[0.0; 3]; 2];
            let draw = if d == 2 {
                dt[0][e] = dshs[a][0];
                raw_normal(2, g.sign, &dt)
            } else {
                let mut e1 = [[0.0; 3]; 2];
                e1[0][e] = dshs[a][0];
                e1[1] = t[1];
                let mut e2 = [[0.0; 3]; 2];
                e2[0] = t[0];
                e2[1][e] = dshs[a][1];
                let (r1, r2) = (raw_normal(3, g.sign, &e1), raw_normal(3, g.sign, &e2));
                [r1[0] + r2[0], r1[1] + r2[1], r1[2] + r2[2]]
            };
            let proj = dot(n, draw);
            for c in 0..d {
                dn[c][u_s(a, e)] = (draw[c] - proj * n[c]) / lt;
            }
        }
    }
    // The master point along the slave normal (projQpSl2Ma).
    let hit = if g.m_kind == SurfaceKind::Seg2 {
        ray_hit(xs, n, g.mp[0], g.mp[1]).map(|k| interpolate(g.m_kind, g.mp, [k, 0.0]))
    } else {
        project_along(g.m_kind, g.mp, xs, n)
    };
    let Some(hit) = hit else {
        return Ok(None);
    };
    let (shm, dshm) = g.m_kind.eval(hit.xi);
    let xm = hit.x;
    let tm = hit.tangents;
    let gap = -dot(sub(xs, xm), n);
    // dPi_du: [τ_m1, (τ_m2,) −n] (dξ_m, dg) = δx_s − δx_m + g dn (in 2D
    // code_aster's third column e_z).
    let mut r = [lin(nloc), lin(nloc), lin(nloc)];
    for c in 0..d {
        for a in 0..ns {
            r[c][u_s(a, c)] += shs[a];
        }
        for b in 0..nm {
            r[c][u_m(b, c)] -= shm[b];
        }
        axpy(&mut r[c], gap, &dn[c]);
    }
    let minus_n = [-n[0], -n[1], -n[2]];
    let cols = if d == 2 {
        [tm[0], minus_n, [0.0, 0.0, 1.0]]
    } else {
        [tm[0], tm[1], minus_n]
    };
    let scale = if d == 2 {
        norm(tm[0])
    } else {
        norm(tm[0]) * norm(tm[1])
    };
    let Some(inv) = inverse_of_columns(cols, scale) else {
        return Ok(None);
    };
    let solve = |row: usize| {
        let mut out = comb(inv[row][0], &r[0], inv[row][1], &r[1]);
        axpy(&mut out, inv[row][2], &r[2]);
        out
    };
    let dxi = [solve(0), if d == 3 { solve(1) } else { lin(nloc) }];
    let dg = solve(d - 1);
    // λ at the point.
    let mut lam = [0.0; 3];
    let mut dlam = [lin(nloc), lin(nloc), lin(nloc)];
    if let Some(lam_nodes) = lam_nodes {
        for a in 0..nl {
            for c in 0..d {
                lam[c] += shl[a] * lam_nodes[a][c];
                dlam[c][l_s(a, c)] = shl[a];
            }
        }
    }
    // λ·n + γ g and its negative part (projRm).
    let lg = dot(lam, n) + p.gamma * gap;
    let mut dlg = lin(nloc);
    for c in 0..d {
        axpy(&mut dlg, n[c], &dlam[c]);
        axpy(&mut dlg, lam[c], &dn[c]);
    }
    axpy(&mut dlg, p.gamma, &dg);
    let contact = p.forced.unwrap_or(lg <= 0.0);
    let (proj_rm, dproj_rm) = if contact && (p.forced.is_some() || lg <= 0.0) {
        (lg, dlg.clone())
    } else {
        (0.0, lin(nloc))
    };
    // thresEval.
    let (s, ds) = match p.law {
        FrictionLaw::Without => (0.0, lin(nloc)),
        FrictionLaw::Tresca(v) => (v, lin(nloc)),
        FrictionLaw::Coulomb(mu) if contact => {
            (-mu * proj_rm, dproj_rm.iter().map(|d| -mu * d).collect())
        }
        FrictionLaw::Stick if contact => (THRES_STICK, lin(nloc)),
        _ => (0.0, lin(nloc)),
    };
    // speedEval and dv_du, on the start-of-step configuration.
    let mut xs_prev = [0.0; 3];
    for a in 0..ns {
        for c in 0..d {
            xs_prev[c] += shs[a] * g.sprev[a][c];
        }
    }
    let mut xm_prev = [0.0; 3];
    let mut tm_prev = [[0.0; 3]; 2];
    for b in 0..nm {
        for c in 0..d {
            xm_prev[c] += shm[b] * g.mprev[b][c];
            for (al, ta) in tm_prev.iter_mut().enumerate().take(nt) {
                ta[c] += dshm[b][al] * g.mprev[b][c];
            }
        }
    }
    let n_prev = if d == 2 {
        normal_at(g.s_kind, g.sprev, p.xi[0], g.sign)
    } else {
        crate::mortar_pairing3d::face_normal(g.s_kind, g.sprev, p.xi, g.sign)
    }
    .ok_or_else(|| {
        err(ContactError::Invalid {
            keyword: "GROUP_MA_ESCL",
            message: "a slave cell is degenerate (zero length or area) at the start of the step"
                .into(),
        })
    })?;
    let mut v = [0.0; 3];
    let mut dv = [lin(nloc), lin(nloc), lin(nloc)];
    for c in 0..d {
        v[c] = -(xs_prev[c] - xm_prev[c] + gap * n_prev[c]);
        let mut dvc = comb(tm_prev[0][c], &dxi[0], -n_prev[c], &dg);
        axpy(&mut dvc, tm_prev[1][c], &dxi[1]);
        dv[c] = dvc;
    }
    // projBs of x = λ − γ v.
    let mut x = [0.0; 3];
    let mut dx = [lin(nloc), lin(nloc), lin(nloc)];
    for c in 0..d {
        x[c] = lam[c] - p.gamma * v[c];
        dx[c] = comb(1.0, &dlam[c], -p.gamma, &dv[c]);
    }
    let mut pb = [0.0; 3];
    let mut dpb = [lin(nloc), lin(nloc), lin(nloc)];
    let mut slip = false;
    if p.law != FrictionLaw::Without && s.abs() > R8PREM {
        let xn = dot(x, n);
        let mut xt = [0.0; 3];
        for c in 0..d {
            xt[c] = x[c] - xn * n[c];
        }
        // d(Tx) = T dx + dT x, dT x = −dn (n·x) − n (dn·x).
        let mut dxn = lin(nloc);
        let mut dnx = lin(nloc);
        for c in 0..d {
            axpy(&mut dxn, n[c], &dx[c]);
            axpy(&mut dnx, x[c], &dn[c]);
        }
        let mut dxt = dx.clone();
        for c in 0..d {
            axpy(&mut dxt[c], -n[c], &dxn);
            axpy(&mut dxt[c], -xn, &dn[c]);
            axpy(&mut dxt[c], -n[c], &dnx);
        }
        let lxt = norm(xt);
        if lxt <= s {
            pb = xt;
            dpb = dxt;
        } else {
            slip = true;
            let u = [xt[0] / lxt, xt[1] / lxt, xt[2] / lxt];
            let mut udx = lin(nloc);
            for c in 0..d {
                axpy(&mut udx, u[c], &dxt[c]);
            }
            for c in 0..d {
                pb[c] = s * u[c];
                let mut dc = comb(u[c], &ds, s / lxt, &dxt[c]);
                axpy(&mut dc, -s / lxt * u[c], &udx);
                dpb[c] = dc;
            }
        }
    }
    Ok(Some(PointQuantities {
        status: PointStatus { contact, slip },
        nloc,
        shs: shs[..ns].to_vec(),
        shl: shl[..nl].to_vec(),
        shm: shm[..nm].to_vec(),
        dshm: dshm[..nm].to_vec(),
        n,
        dn,
        dxi,
        lam,
        dlam,
        proj_rm,
        dproj_rm,
        pb,
        dpb,
    }))
}

/// One integration point of the Lagrangian friction (`laVect_cf_pr`),
/// `None` when the ray from the slave point misses the master cell.
fn point_terms(
    g: &PointGeometry,
    p: &PointLaw,
    lam_nodes: &[[f64; 3]],
) -> Result<Option<PointTerms>, FemError> {
    let Some(q) = point_quantities(g, p, Some(lam_nodes))? else {
        return Ok(None);
    };
    let PointQuantities {
        status,
        nloc,
        shs,
        shl,
        shm,
        dshm,
        n,
        dn,
        dxi,
        lam,
        dlam,
        proj_rm,
        dproj_rm,
        pb,
        dpb,
    } = q;
    let d = g.dim;
    let (ns, nm) = (shs.len(), shm.len());
    let contact = status.contact;
    // Equations of the multipliers: w ([λ·n + γg]₋ n − λ + P)/γ μ.
    let f = p.w / p.gamma;
    let mut own = Vec::with_capacity(d * shl.len());
    for &mu in &shl {
        for c in 0..d {
            let value = f * mu * (proj_rm * n[c] - lam[c] + pb[c]);
            let mut dc = comb(n[c], &dproj_rm, proj_rm, &dn[c]);
            axpy(&mut dc, -1.0, &dlam[c]);
            axpy(&mut dc, 1.0, &dpb[c]);
            dc.iter_mut().for_each(|v| *v *= f * mu);
            own.push((value, dc));
        }
    }
    // Forces at contact points: −w λ·(v_s − v_m).
    let mut forces = Vec::with_capacity(d * (ns + nm));
    for &na in &shs {
        for c in 0..d {
            if contact {
                let dc = dlam[c].iter().map(|v| -p.w * na * v).collect();
                forces.push((-p.w * na * lam[c], dc));
            } else {
                forces.push((0.0, lin(nloc)));
            }
        }
    }
    for b in 0..nm {
        for c in 0..d {
            if contact {
                let mut dc = comb(p.w * shm[b], &dlam[c], p.w * lam[c] * dshm[b][0], &dxi[0]);
                axpy(&mut dc, p.w * lam[c] * dshm[b][1], &dxi[1]);
                forces.push((p.w * shm[b] * lam[c], dc));
            } else {
                forces.push((0.0, lin(nloc)));
            }
        }
    }
    Ok(Some(PointTerms { forces, own }))
}

/// The Lagrangian friction in 3D is reproduced on TRIA3 and QUAD4 faces:
/// on quadratic faces the sliding scenes (comm/dc3d_friction.comm,
/// comm/dc3d_penalised_friction.comm's loading, on their mesh made
/// quadratic) stall in a two-iteration cycle (docs/contact.md); the
/// penalised friction is reproduced there.
pub(crate) fn linear_faces_only(
    base: &MortarLagrangian,
    zones: &[MortarZoneDef],
) -> Result<(), ContactError> {
    for (z, def) in base.zones.iter().zip(zones) {
        for (cells, group, which) in [
            (&z.slave, &def.slave_group, "GROUP_MA_ESCL"),
            (&z.master, &def.master_group, "GROUP_MA_MAIT"),
        ] {
            if let Some(c) = cells
                .iter()
                .find(|c| c.kind.node_count() > c.kind.corner_count())
            {
                return Err(ContactError::Unsupported {
                    feature: format!(
                        "DEFI_CONT friction on the quadratic faces ({:?}) of {which} {group} in 3D",
                        c.kind
                    ),
                    hint: "the Lagrangian friction is reproduced on TRIA3 and QUAD4 faces (on quadratic faces the project's sliding scenes stall in a two-iteration cycle); the penalised friction (ALGO_CONT='PENALISATION') is reproduced on quadratic faces".into(),
                });
            }
        }
    }
    Ok(())
}

/// The frictional zones, their laws, the frictionless zones ([`split_zones`]).
pub(crate) type SplitZones = (Vec<MortarZoneDef>, Vec<FrictionLaw>, Vec<MortarZoneDef>);

/// The zones of a definition with friction, split as code_aster 17 builds
/// them (`ContactNew::build`, `ContactPairing::createVirtualElemForContact`,
/// `ContactComputation::contactData`): a zone's elements are chosen by its
/// own `FROTTEMENT` (`FRIC_LAG_SL_*` with `LAGS_C`, `LAGS_F1`(, `LAGS_F2`)
/// or `CONT_LAG_SL_*` with `LAGS_C` only; the penalised elements are the
/// same for both) and its element data carry its own `l_fric`
/// (`zr(jcont+30)`), so a frictionless zone of a `FrictionNew` is computed
/// by the frictionless formulation (`laVect_ct_pr`, `peVect_ct_pr`; its
/// `LAGS_C` a pressure). Returns the frictional zones with their laws,
/// then the frictionless ones.
pub(crate) fn split_zones(zones: &[MortarZoneDef]) -> SplitZones {
    let mut with = Vec::new();
    let mut laws = Vec::new();
    let mut without = Vec::new();
    for z in zones {
        match z.friction {
            Some(law) => {
                with.push(z.clone());
                laws.push(law);
            }
            None => without.push(z.clone()),
        }
    }
    (with, laws, without)
}

/// code_aster's `CONTACT1_1` (`ContactNew::build`): zones sharing slave
/// nodes stop the definition; checked here between the frictional and the
/// frictionless zones of one definition, computed by two sources.
pub(crate) fn disjoint_slaves(
    with: &MortarLagrangian,
    without: &MortarLagrangian,
) -> Result<(), ContactError> {
    let shared = without
        .zones
        .iter()
        .flat_map(|z| &z.slave)
        .flat_map(|s| &s.nodes)
        .any(|n| {
            with.zones
                .iter()
                .flat_map(|z| &z.slave)
                .any(|s| s.nodes.contains(n))
        });
    if shared {
        return Err(ContactError::Invalid {
            keyword: "GROUP_MA_ESCL",
            message: "a zone with friction and a zone without share slave nodes (code_aster stops with CONTACT1_1: the slave nodes of the zones of one DEFI_CONT must be distinct)".into(),
        });
    }
    Ok(())
}

/// Adds `other` (a source whose own unknowns follow this one's, from
/// `offset`) to `c`.
pub(crate) fn append_contribution(c: &mut Contribution, other: Contribution, offset: usize) {
    let shift = |u: Unknown| match u {
        Unknown::Own(k) => Unknown::Own(k + offset),
        dof => dof,
    };
    c.forces.extend(other.forces);
    c.own_residual.extend(other.own_residual);
    c.tangent.extend(
        other
            .tangent
            .into_iter()
            .map(|(r, col, v)| (shift(r), shift(col), v)),
    );
}

/// The name of own unknown `k` of a frictional source with `per` unknowns
/// per slave node (`LAGS_C`, then `LAGS_F1`, then `LAGS_F2` in 3D).
pub(crate) fn friction_unknown_name(lagr: &[NodeId], per: usize, k: usize, mesh: &Mesh) -> String {
    match lagr.get(k / per) {
        Some(n) => format!(
            "{} of node {}",
            ["LAGS_C", "LAGS_F1", "LAGS_F2"][(k % per).min(2)],
            mesh.node_name(*n)
        ),
        None => format!("unknown #{}", k + 1),
    }
}

/// The frictional mortar contact of a DEFI_CONT, as a fem force source.
#[derive(Clone, Debug)]
pub struct MortarFriction {
    /// The zones, their pairing and the slave nodes (shared with the
    /// frictionless formulation).
    base: MortarLagrangian,
    laws: Vec<FrictionLaw>,
    /// The zones without friction beside them ([`split_zones`]): the
    /// frictionless formulation, their `LAGS_C` pressures numbered after
    /// the frictional multipliers.
    frictionless: Option<MortarLagrangian>,
    /// Positions at the start of the step (`coor_*_prev`).
    x_prev: Vec<[f64; 3]>,
    first_pairing: bool,
}

impl MortarFriction {
    /// The contact of `zones` on `mesh` for a model of dimension `dim`: 2
    /// (segments) or 3 (faces, as [`MortarLagrangian::new`]; the
    /// multipliers `LAGS_C`, `LAGS_F1`, `LAGS_F2` on the faces' corners;
    /// `axis`: AXIS weights). Each zone's [`MortarZoneDef::friction`] is its
    /// law; a zone without one is frictionless, as code_aster computes it
    /// ([`split_zones`]: `LAGS_C` its pressure, no `LAGS_F*`).
    pub fn new(
        zones: &[MortarZoneDef],
        mesh: &Mesh,
        axis: bool,
        dim: usize,
    ) -> Result<Self, ContactError> {
        let (with, laws, without) = split_zones(zones);
        let base = MortarLagrangian::new(&with, mesh, axis, dim)?;
        if base.dim == 3 {
            linear_faces_only(&base, &with)?;
        }
        let frictionless = if without.is_empty() {
            None
        } else {
            let m = MortarLagrangian::new(&without, mesh, axis, dim)?;
            disjoint_slaves(&base, &m)?;
            Some(m)
        };
        Ok(MortarFriction {
            base,
            laws,
            frictionless,
            x_prev: mesh.coords.clone(),
            first_pairing: true,
        })
    }

    /// The number of multipliers of the frictional zones (the frictionless
    /// zones' `LAGS_C` follow).
    fn frictional_unknowns(&self) -> usize {
        self.base.dim * self.base.lagr.len()
    }

    /// The contact pressure (`LAGS_C`) of each slave node of the zones
    /// without friction.
    pub fn pressures<'a>(&'a self, own: &'a [f64]) -> impl Iterator<Item = (NodeId, f64)> + 'a {
        let rest = own.get(self.frictional_unknowns()..).unwrap_or(&[]);
        self.frictionless
            .iter()
            .flat_map(move |m| m.multipliers(rest))
    }

    /// code_aster 17's geometric criterion (MECA_NON_LINE's
    /// `CONTACT/RESI_GEOM`), as [`MortarLagrangian::set_resi_geom`].
    pub fn set_resi_geom(&mut self, resi_geom: f64) {
        self.base.set_resi_geom(resi_geom);
        if let Some(m) = self.frictionless.as_mut() {
            m.set_resi_geom(resi_geom);
        }
    }

    /// Space dimension of the model (2 or 3): the multipliers per slave node.
    pub fn dim(&self) -> usize {
        self.base.dim
    }

    /// The multipliers of each slave node of the frictional zones: (`LAGS_C`, `LAGS_F1`, `LAGS_F2`),
    /// the x, y (and z in 3D, else 0) components of the contact force per
    /// unit length or area.
    pub fn multipliers<'a>(
        &'a self,
        own: &'a [f64],
    ) -> impl Iterator<Item = (NodeId, [f64; 3])> + 'a {
        let d = self.base.dim;
        self.base.lagr.iter().enumerate().map(move |(k, n)| {
            let mut v = [0.0; 3];
            for (c, vc) in v.iter_mut().enumerate().take(d) {
                *vc = own.get(d * k + c).copied().unwrap_or(0.0);
            }
            (*n, v)
        })
    }
}

impl ForceSource for MortarFriction {
    fn name(&self) -> String {
        "DEFI_CONT (mortar Lagrangian contact with friction)".into()
    }

    fn unknowns(&self) -> usize {
        self.frictional_unknowns() + self.frictionless.as_ref().map_or(0, |m| m.unknowns())
    }

    fn begin_increment(&mut self, state: &State, own: &mut [f64]) -> Result<(), FemError> {
        self.x_prev = current_positions(state);
        self.base.resi_geom.begin(state);
        let off = self.frictional_unknowns();
        if let Some(m) = self.frictionless.as_mut() {
            m.begin_increment(state, &mut own[off..])?;
        }
        Ok(())
    }

    fn evaluate(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError> {
        let x = current_positions(state);
        let x0 = &state.mesh.coords;
        let base = &self.base;
        let d = base.dim;
        let pairs = base.pairs(&x);
        let nl = base.lagr.len();
        let mut c = Contribution {
            forces: Vec::new(),
            own_residual: vec![0.0; d * nl],
            tangent: Vec::new(),
        };
        let mut paired = vec![false; nl];
        for p in &pairs {
            let z = &base.zones[p.zone];
            let s = &z.slave[p.slave];
            let m = &z.master[p.master];
            let sp = s.positions(&x);
            let mp = m.positions(&x);
            let s0 = s.positions(x0);
            let sprev = s.positions(&self.x_prev);
            let mprev = m.positions(&self.x_prev);
            let gamma = z.coef / z.h[p.slave];
            let lk: Vec<usize> = s.lagr_nodes().iter().map(|n| base.lagr_of[n]).collect();
            for &k in &lk {
                paired[k] = true;
            }
            let lam_nodes: Vec<[f64; 3]> = lk
                .iter()
                .map(|&k| {
                    let mut l = [0.0; 3];
                    for (e, le) in l.iter_mut().enumerate().take(d) {
                        *le = own[d * k + e];
                    }
                    l
                })
                .collect();
            // Global unknowns of the local ones.
            let mut map: Vec<Option<Unknown>> = Vec::new();
            for node in s.nodes.iter().chain(&m.nodes) {
                for e in 0..d {
                    map.push(crate::mortar_point::dof(state, *node, e).map(Unknown::Dof));
                }
            }
            for &k in &lk {
                for e in 0..d {
                    map.push(Some(Unknown::Own(d * k + e)));
                }
            }
            let geometry = PointGeometry {
                dim: d,
                s_kind: s.kind,
                sign: s.sign,
                sp: &sp,
                sprev: &sprev,
                m_kind: m.kind,
                mp: &mp,
                mprev: &mprev,
            };
            let forced = z.forced(self.first_pairing);
            for (xi, w) in crate::mortar_point::quadrature(s, m, p, &s0, d, base.axis) {
                let law = PointLaw {
                    xi,
                    w,
                    gamma,
                    law: self.laws[p.zone],
                    forced,
                };
                let Some(terms) = point_terms(&geometry, &law, &lam_nodes)? else {
                    continue;
                };
                for (i, (value, dv)) in terms.forces.iter().enumerate() {
                    let Some(Unknown::Dof(row)) = map[i] else {
                        continue;
                    };
                    if *value != 0.0 {
                        c.forces.push((row, *value));
                    }
                    for (j, v) in dv.iter().enumerate() {
                        if let (Some(col), true) = (map[j], *v != 0.0) {
                            c.tangent.push((Unknown::Dof(row), col, *v));
                        }
                    }
                }
                for (i, (value, dv)) in terms.own.iter().enumerate() {
                    let row = d * lk[i / d] + i % d;
                    c.own_residual[row] += value;
                    for (j, v) in dv.iter().enumerate() {
                        if let (Some(col), true) = (map[j], *v != 0.0) {
                            c.tangent.push((Unknown::Own(row), col, *v));
                        }
                    }
                }
            }
        }
        // Slave nodes of no paired cell: λ = 0.
        for (k, p) in paired.iter().enumerate() {
            if !p {
                for r in d * k..d * (k + 1) {
                    c.own_residual[r] += -own[r];
                    c.tangent.push((Unknown::Own(r), Unknown::Own(r), -1.0));
                }
            }
        }
        for r in 0..d * nl {
            c.tangent.push((Unknown::Own(r), Unknown::Own(r), 0.0));
        }
        // The zones without friction: the frictionless formulation.
        let off = d * nl;
        if let Some(m) = self.frictionless.as_mut() {
            let other = m.evaluate(state, &own[off..])?;
            append_contribution(&mut c, other, off);
        }
        Ok(c)
    }

    fn after_iteration(&mut self, state: &State, own: &mut [f64]) -> Result<bool, FemError> {
        // The first pairing (CONTACT_INIT) was that of this iteration.
        self.first_pairing = false;
        // code_aster 17's acceptance, as without friction: the whole
        // residual (the LAGS_C, LAGS_F1 rows included) and RESI_GEOM; a
        // change of contact or stick/slip status does not by itself
        // prevent convergence.
        let accepted = self.base.resi_geom.accept(state);
        let off = self.frictional_unknowns();
        match self.frictionless.as_mut() {
            // The same criterion on the same state: both record it.
            Some(m) => Ok(m.after_iteration(state, &mut own[off..])? && accepted),
            None => Ok(accepted),
        }
    }

    fn own_rows_in_residual(&self) -> bool {
        true
    }

    fn converged(&mut self, state: &State, own: &[f64]) -> Result<(), FemError> {
        self.first_pairing = false;
        let off = self.frictional_unknowns();
        if let Some(m) = self.frictionless.as_mut() {
            m.converged(state, &own[off..])?;
        }
        Ok(())
    }

    fn unknown_name(&self, k: usize, mesh: &Mesh) -> String {
        let off = self.frictional_unknowns();
        match self.frictionless.as_ref() {
            Some(m) if k >= off => m.unknown_name(k - off, mesh),
            _ => friction_unknown_name(&self.base.lagr, self.base.dim, k, mesh),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every derivative of `t0` (the terms at `z0`) against central
    /// differences of `terms` on each local unknown.
    fn assert_tangent_is_the_derivative(
        t0: &PointTerms,
        z0: &[f64],
        terms: impl Fn(&[f64]) -> PointTerms,
        what: &str,
    ) {
        let h = 1e-7;
        for j in 0..z0.len() {
            let (mut zp, mut zm) = (z0.to_vec(), z0.to_vec());
            zp[j] += h;
            zm[j] -= h;
            let (tp, tm) = (terms(&zp), terms(&zm));
            for (i, (row, d)) in t0.forces.iter().chain(&t0.own).enumerate() {
                let vp = tp.forces.iter().chain(&tp.own).nth(i).unwrap().0;
                let vm = tm.forces.iter().chain(&tm.own).nth(i).unwrap().0;
                let fd = (vp - vm) / (2.0 * h);
                assert!(
                    (fd - d[j]).abs() <= 1e-5 * (1.0 + fd.abs()),
                    "{what}: row {i} ({row}) column {j}: {} against {fd}",
                    d[j]
                );
            }
        }
    }

    /// The tangent of a point is the derivative of its residual (central
    /// differences on every local unknown), in stick and in slip, on a
    /// tilted slave SEG2 over a SEG3 master.
    #[test]
    fn point_tangent_is_the_derivative_of_the_residual() {
        let sp0 = vec![[0.0, 0.01, 0.0], [1.0, 0.03, 0.0]];
        let mp0 = vec![[1.2, -0.02, 0.0], [-0.1, 0.0, 0.0], [0.55, 0.01, 0.0]];
        let sprev = vec![[0.01, 0.02, 0.0], [1.0, 0.04, 0.0]];
        let mprev = vec![[1.2, -0.01, 0.0], [-0.1, 0.0, 0.0], [0.55, 0.0, 0.0]];
        let lam0 = vec![[0.8, 2.0, 0.0], [0.6, 1.5, 0.0]];
        for (law, sliding) in [
            (FrictionLaw::Coulomb(0.3), true),
            (FrictionLaw::Coulomb(50.0), false),
            (FrictionLaw::Tresca(0.05), true),
        ] {
            let terms = |z: &[f64]| {
                let mut sp = sp0.clone();
                let mut mp = mp0.clone();
                let mut lam = lam0.clone();
                for a in 0..2 {
                    for c in 0..2 {
                        sp[a][c] += z[2 * a + c];
                        lam[a][c] += z[10 + 2 * a + c];
                    }
                }
                for b in 0..3 {
                    for c in 0..2 {
                        mp[b][c] += z[4 + 2 * b + c];
                    }
                }
                let g = PointGeometry {
                    dim: 2,
                    s_kind: SurfaceKind::Seg2,
                    sign: 1.0,
                    sp: &sp,
                    sprev: &sprev,
                    m_kind: SurfaceKind::Seg3,
                    mp: &mp,
                    mprev: &mprev,
                };
                let p = PointLaw {
                    xi: [0.3, 0.0],
                    w: 0.7,
                    gamma: 3.0,
                    law,
                    forced: None,
                };
                let status = point_quantities(&g, &p, Some(&lam))
                    .unwrap()
                    .unwrap()
                    .status;
                (point_terms(&g, &p, &lam).unwrap().unwrap(), status)
            };
            let z0 = vec![0.0; 14];
            let (t0, status) = terms(&z0);
            assert!(status.contact);
            assert_eq!(status.slip, sliding, "{law:?}");
            assert_tangent_is_the_derivative(&t0, &z0, |z| terms(z).0, &format!("{law:?}"));
        }
    }
    /// The point tangent of a slave face `sk` at `sp0` (multipliers on its
    /// 4 corners) over a curved master QUAD8 against central differences,
    /// in stick and in slip (the slip with both tangential components),
    /// with the normal's rotation and the master point's motion along both
    /// parameters.
    fn check_face_tangent(sk: SurfaceKind, sp0: Vec<[f64; 3]>) {
        let mk = SurfaceKind::Quad8;
        let mp0: Vec<[f64; 3]> = mk
            .node_coords()
            .into_iter()
            .map(|[u, v]| {
                let (x, y) = (0.5 + 1.2 * u, 0.5 + 1.1 * v);
                [x, y, -0.02 + 0.01 * x - 0.005 * y + 0.01 * u * u]
            })
            .collect();
        let sprev: Vec<[f64; 3]> = sp0
            .iter()
            .map(|p| [p[0] - 0.02, p[1] - 0.01, p[2] + 0.01])
            .collect();
        let mprev: Vec<[f64; 3]> = mp0.iter().map(|p| [p[0], p[1], p[2] + 0.001]).collect();
        let lam0: Vec<[f64; 3]> = vec![
            [1.0, 0.6, 2.0],
            [0.8, 0.4, 1.5],
            [1.2, 0.2, 1.8],
            [0.6, 0.8, 1.7],
        ];
        let (ns, nm, nl) = (sp0.len(), mp0.len(), lam0.len());
        let nloc = 3 * (ns + nm + nl);
        for (law, sliding) in [
            (FrictionLaw::Coulomb(0.3), true),
            (FrictionLaw::Coulomb(50.0), false),
            (FrictionLaw::Tresca(0.05), true),
        ] {
            let terms = |z: &[f64]| {
                let mut sp = sp0.clone();
                let mut mp = mp0.clone();
                let mut lam = lam0.clone();
                for a in 0..ns {
                    for c in 0..3 {
                        sp[a][c] += z[3 * a + c];
                    }
                }
                for b in 0..nm {
                    for c in 0..3 {
                        mp[b][c] += z[3 * ns + 3 * b + c];
                    }
                }
                for a in 0..nl {
                    for c in 0..3 {
                        lam[a][c] += z[3 * (ns + nm) + 3 * a + c];
                    }
                }
                let g = PointGeometry {
                    dim: 3,
                    s_kind: sk,
                    sign: 1.0,
                    sp: &sp,
                    sprev: &sprev,
                    m_kind: mk,
                    mp: &mp,
                    mprev: &mprev,
                };
                let p = PointLaw {
                    xi: [0.3, -0.2],
                    w: 0.7,
                    gamma: 3.0,
                    law,
                    forced: None,
                };
                let q = point_quantities(&g, &p, Some(&lam)).unwrap().unwrap();
                (point_terms(&g, &p, &lam).unwrap().unwrap(), q.status, q.n)
            };
            let z0 = vec![0.0; nloc];
            let (t0, status, n) = terms(&z0);
            assert!(n[2] < -0.99, "the slave normal points down: {n:?}");
            assert!(status.contact, "{sk:?} {law:?}");
            assert_eq!(status.slip, sliding, "{sk:?} {law:?}");
            assert_tangent_is_the_derivative(&t0, &z0, |z| terms(z).0, &format!("{sk:?} {law:?}"));
        }
    }

    /// The same on faces (3D): a tilted, warped slave QUAD4.
    #[test]
    fn point_tangent_on_faces_is_the_derivative_of_the_residual() {
        let sp0: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.01],
            [0.0, 1.0, 0.03],
            [1.05, 1.0, 0.02],
            [1.0, 0.05, -0.01],
        ];
        check_face_tangent(SurfaceKind::Quad4, sp0);
    }

    /// The same on a curved, warped slave QUAD8 face (multipliers on its
    /// corners only, code_aster's `shapeFuncLagr`).
    #[test]
    fn point_tangent_on_quadratic_slave_faces_is_the_derivative_of_the_residual() {
        let sk = SurfaceKind::Quad8;
        let sp0: Vec<[f64; 3]> = sk
            .node_coords()
            .into_iter()
            .map(|[u, v]| {
                let (x, y) = (0.5 + 0.5 * v + 0.02 * u * v, 0.5 + 0.5 * u);
                [x, y, 0.01 + 0.01 * x - 0.02 * y + 0.005 * v * v]
            })
            .collect();
        check_face_tangent(sk, sp0);
    }
}
