//! code_aster 17's mortar contact of `DEFI_CONT` with
//! `ALGO_CONT='LAGRANGIEN'`, `VARIANTE='CLASSIQUE'` (the classical
//! augmented Lagrangian), frictionless and with friction, in 2D on SEG2 and
//! SEG3 cells, and frictionless in 3D on faces, as a fem force source
//! whose unknowns are the slave nodes' `LAGS_C` (and `LAGS_F1` with
//! friction).
//!
//! In 3D (`FacePair`) the residual is `laVect_ct_std`'s on the 3D
//! pairing's polygons (Dg from `mortar_tangent::linearise_3d`) and the
//! matrix code_aster's own one-sided differences of it (`laMatr_diff`,
//! the only `TYPE_MATR_TANG` of CLASSIQUE), so that Newton follows its
//! path; the 2D items below keep their exact dual-number tangent.
//!
//! Pairing, integration points, weights, normals, ray tracing, γ_c =
//! COEF_CONT / h_F, `CONTACT_INIT`, the POI1 treatment of unpaired slave
//! nodes and the acceptance of an iterate (`RESI_GEOM`) are those of
//! [`crate::mortar_lagrangian`] (ROBUSTE); what differs is the residual,
//! code_aster 2025's `laVect_ct_std` and `laVect_cf_std` with `laElemCont`
//! (`glob_coor` false), `contact_module` (`projQpSl2Ma`, `thresEval`,
//! `speedEval`) and `contact_algebra_module` (`projRm`, `projBs`,
//! `dPi_du`, `dNs_du`, `dProjTn_du`, `dv_du`, `dvT_du`, `cmpTang`):
//!
//! - **Contact** (`laVect_ct_std`): with λ the pressure `LAGS_C`
//!   interpolated at the point and [x]₋ = min(x, 0) (`projRm`), on the
//!   displacements w [λ + γ_c g]₋ Dg[v] at active points (λ + γ_c g ≤ 0),
//!   Dg the full derivative of the ray-traced gap (`dPi_du`: (τ_m, −n_s)
//!   (Dζ, Dg) = v_s − v_m + g Dn_s, Dn_s = −τ_s (Dτ_s·n_s) / |τ_s|²); on
//!   each multiplier w ([λ + γ_c g]₋ − λ)/γ_c μ, as ROBUSTE. Where ROBUSTE's
//!   displacement rows carry −w λ n_s·(v_s − v_m), these are the derivative
//!   of the augmented Lagrangian, continuous across a change of status.
//! - **Friction** (`laVect_cf_std`), local multipliers: `LAGS_F1` is the
//!   tangential multiplier λ_f in the **unnormalised** slave tangent
//!   τ_s = ∂x_s/∂ξ (|τ_s| = L/2 on a straight SEG2 of length L), the
//!   tangential force per unit length being τ_s λ_f. γ_f = COEF_FROT / h_F.
//!   The threshold s is `thresEval`'s (COULOMB: −μ [λ + γ_c g]₋ at contact
//!   points, 0 elsewhere; TRESCA: the value everywhere; ADHERENT:
//!   `THRES_STICK` at contact points; SANS: none), the slip v =
//!   −(x_s⁻ − x_m⁻ + g n_s⁻) on the start-of-step configuration
//!   (`speedEval`), and P = `projBs`(λ n_s + τ_s λ_f − γ_f v): the
//!   tangential part of its argument, scaled back to length s when longer.
//!   On the displacements −w P·Dv_T[v] (v_T = (I − n_s⊗n_s) v, `dvT_du`:
//!   Dv_T = −(Dn_s⊗n_s + n_s⊗Dn_s) v + (I − n_s⊗n_s)(τ_m⁻ Dζ − Dg n_s⁻)) at
//!   points with friction; on each `LAGS_F1` w (τ_s·P − |τ_s|² λ_f)/γ_f μ
//!   (`metricTens` × (`cmpTang`(P) − λ_f) / γ_f).
//! - **Tangent**: the exact derivative of that residual (the pairing of the
//!   iterate, intersections and weights held), by forward-mode dual numbers
//!   ([`aster_fem::autodiff::Dual`]) over the point's local unknowns: the
//!   residual already holds first derivatives of the geometry (Dg, Dv_T), so
//!   its tangent needs their second ones (code_aster's `d2Gap_du2`, the
//!   master's curvature included), which the dual arithmetic carries
//!   through the same formulas. code_aster builds this variant's matrix by
//!   one-sided finite differences of the residual (`TYPE_MATR_TANG` can
//!   only be `'PERTURBATION'` with CLASSIQUE: `laMatr_diff`, step 1e-6 h_F;
//!   `laMatr` has no CLASSIQUE friction matrix): the path differs, not the
//!   converged state.

use aster_fem::autodiff::Dual;
use aster_fem::{Contribution, FemError, ForceSource, State, Unknown};
use aster_mesh::{Mesh, NodeId};

use crate::error::ContactError;
use crate::mortar_friction::{FrictionLaw, R8PREM, THRES_STICK};
use crate::mortar_lagrangian::{err, normal_at, MortarLagrangian, MortarZoneDef, Seg};
use crate::shape::SurfaceKind;
use crate::source::current_positions;

/// Local unknowns of a point at most: a SEG3 slave and a SEG3 master
/// (2 × 3 + 2 × 3 displacements) and three slave nodes' `LAGS_C` and
/// `LAGS_F1`.
const NLOC: usize = 18;

/// A value and its derivatives with respect to a point's local unknowns.
type D = Dual<NLOC>;

fn cst(v: f64) -> D {
    D::constant(v)
}

fn dot2(a: [D; 2], b: [D; 2]) -> D {
    a[0] * b[0] + a[1] * b[1]
}

/// Solves [a, b] (x, y) = f for 2-vectors a, b (Cramer); `None` when the
/// columns are parallel.
fn solve2(a: [D; 2], b: [D; 2], f: [D; 2]) -> Option<(D, D)> {
    let det = a[0] * b[1] - b[0] * a[1];
    if det.v.abs() <= f64::EPSILON * (a[0].v.abs() + a[1].v.abs()) * (b[0].v.abs() + b[1].v.abs()) {
        return None;
    }
    Some((
        (f[0] * b[1] - b[0] * f[1]) / det,
        (a[0] * f[1] - f[0] * a[1]) / det,
    ))
}

/// The geometry of a point: the slave and master cells on the current and
/// (with friction) start-of-step configurations.
struct PointCells<'a> {
    s_kind: SurfaceKind,
    sign: f64,
    sp: &'a [[f64; 3]],
    sprev: &'a [[f64; 3]],
    m_kind: SurfaceKind,
    mp: &'a [[f64; 3]],
    mprev: &'a [[f64; 3]],
}

/// The friction data of a point: its law, γ_f and the nodal `LAGS_F1`.
struct PointFriction<'a> {
    law: FrictionLaw,
    gamma_f: f64,
    lam_f: &'a [f64],
}

/// The data of an integration point.
struct PointData<'a> {
    /// Slave parametric coordinate, weight.
    xi: f64,
    w: f64,
    /// The master point and gap found by ray tracing (`mortar_point`).
    zeta: f64,
    gap: f64,
    gamma_c: f64,
    /// The multipliers' functions at the point and the nodal `LAGS_C`.
    lagr_shape: &'a [f64],
    lam_c: &'a [f64],
    /// `CONTACT_INIT` forcing the status (first pairing only).
    forced: Option<bool>,
    friction: Option<PointFriction<'a>>,
}

/// The status of a point: in contact, and sliding (`projBs` scaled its
/// argument back onto the threshold).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct PointStatus {
    contact: bool,
    slip: bool,
}

/// The residual of a point on its local unknowns — slave displacements
/// (2 per node), master displacements, `LAGS_C` per multiplier node, then
/// `LAGS_F1` per multiplier node with friction — each with its derivatives
/// with respect to them, and the point's status. `None` when the slave
/// normal is parallel to the master cell.
fn point_residual(
    c: &PointCells,
    p: &PointData,
) -> Result<Option<(Vec<D>, PointStatus)>, FemError> {
    let ns = c.sp.len();
    let nm = c.mp.len();
    let nl = p.lagr_shape.len();
    let nf = if p.friction.is_some() { nl } else { 0 };
    let nloc = 2 * ns + 2 * nm + nl + nf;
    if nloc > NLOC {
        return Err(err(ContactError::Invalid {
            keyword: "GROUP_MA_ESCL",
            message: format!("a contact pair with {nloc} local unknowns (at most {NLOC})"),
        }));
    }
    let us = |a: usize, e: usize| 2 * a + e;
    let um = |b: usize, e: usize| 2 * ns + 2 * b + e;
    let lc = |k: usize| 2 * ns + 2 * nm + k;
    let lf = |k: usize| 2 * ns + 2 * nm + nl + k;
    let xs_nodes: Vec<[D; 2]> = (0..ns)
        .map(|a| [0, 1].map(|e| D::variable(c.sp[a][e], us(a, e))))
        .collect();
    let xm_nodes: Vec<[D; 2]> = (0..nm)
        .map(|b| [0, 1].map(|e| D::variable(c.mp[b][e], um(b, e))))
        .collect();

    // The slave point, its tangent τ_s (oriented as code_aster's, whose
    // outward normal is (τ_y, −τ_x)/|τ|) and normal (`apnorm`).
    let (shs, dshs) = c.s_kind.eval([p.xi, 0.0]);
    let mut xs = [cst(0.0); 2];
    let mut tau = [cst(0.0); 2];
    for a in 0..ns {
        for e in 0..2 {
            xs[e] = xs[e] + xs_nodes[a][e] * shs[a];
            tau[e] = tau[e] + xs_nodes[a][e] * (c.sign * dshs[a][0]);
        }
    }
    let tau2 = dot2(tau, tau);
    if !(tau2.v > 0.0 && tau2.v.is_finite()) {
        return Err(err(ContactError::Invalid {
            keyword: "GROUP_MA_ESCL",
            message: "a slave cell is degenerate (zero length)".into(),
        }));
    }
    let lt = tau2.sqrt();
    let n = [tau[1] / lt, -tau[0] / lt];

    // The master point: one Newton step of the ray tracing from the point
    // found (its residual is zero there, so the step carries the exact
    // derivatives of ζ and g: `dPi_du`).
    let (shm, dshm) = c.m_kind.eval([p.zeta, 0.0]);
    let ddshm = c.m_kind.segment_second_derivatives().ok_or_else(|| {
        err(ContactError::Invalid {
            keyword: "GROUP_MA_MAIT",
            message: "the CLASSIQUE mortar contact is reproduced on segments (2D)".into(),
        })
    })?;
    let mut xm0 = [cst(0.0); 2];
    let mut tm0 = [cst(0.0); 2];
    for b in 0..nm {
        for e in 0..2 {
            xm0[e] = xm0[e] + xm_nodes[b][e] * shm[b];
            tm0[e] = tm0[e] + xm_nodes[b][e] * dshm[b][0];
        }
    }
    let r = [0, 1].map(|e| -(xm0[e] - xs[e] - n[e] * p.gap));
    let Some((dzeta0, dgap0)) = solve2(tm0, [-n[0], -n[1]], r) else {
        return Ok(None);
    };
    let gap = dgap0 + p.gap;
    // Master functions and their ∂/∂ζ at ζ = ζ₀ + Δζ.
    let nmf: Vec<D> = (0..nm).map(|b| dzeta0 * dshm[b][0] + shm[b]).collect();
    let dnmf: Vec<D> = (0..nm).map(|b| dzeta0 * ddshm[b] + dshm[b][0]).collect();
    let mut tm = [cst(0.0); 2];
    for b in 0..nm {
        for e in 0..2 {
            tm[e] = tm[e] + xm_nodes[b][e] * dnmf[b];
        }
    }

    // Per displacement DOF j: Dn_s, the jump of the test function, and
    // (Dζ, Dg) from (τ_m, −n_s)(Dζ, Dg) = jump + g Dn_s.
    let ndisp = 2 * ns + 2 * nm;
    let mut dn = vec![[cst(0.0); 2]; ndisp];
    let mut dzeta = vec![cst(0.0); ndisp];
    let mut dgap = vec![cst(0.0); ndisp];
    for j in 0..ndisp {
        let mut jump = [cst(0.0); 2];
        if j < 2 * ns {
            let (a, e) = (j / 2, j % 2);
            // dNs_du: Dn = −τ (Dτ·n)/|τ|², Dτ = sign N'_a e.
            let f = n[e] * (-c.sign * dshs[a][0]) / tau2;
            dn[j] = [tau[0] * f, tau[1] * f];
            jump[e] = cst(shs[a]);
        } else {
            let (b, e) = ((j - 2 * ns) / 2, j % 2);
            jump[e] = -nmf[b];
        }
        let rhs = [jump[0] + gap * dn[j][0], jump[1] + gap * dn[j][1]];
        let Some((dz, dg)) = solve2(tm, [-n[0], -n[1]], rhs) else {
            return Ok(None);
        };
        dzeta[j] = dz;
        dgap[j] = dg;
    }

    let mut res = vec![cst(0.0); nloc];
    // Contact (laVect_ct_std).
    let mut lam_c = cst(0.0);
    for k in 0..nl {
        lam_c = lam_c + D::variable(p.lam_c[k], lc(k)) * p.lagr_shape[k];
    }
    let lg = lam_c + gap * p.gamma_c;
    // CONTACT_INIT at the first pairing, then Heaviside(−(λ + γg)).
    let contact = p.forced.unwrap_or(-lg.v >= 0.0);
    let proj_rm = if contact { lg } else { cst(0.0) };
    if contact {
        for j in 0..ndisp {
            res[j] = res[j] + proj_rm * dgap[j] * p.w;
        }
    }
    for k in 0..nl {
        res[lc(k)] = res[lc(k)] + (proj_rm - lam_c) * (p.w * p.lagr_shape[k] / p.gamma_c);
    }

    // Friction (laVect_cf_std).
    let mut slip = false;
    if let Some(f) = &p.friction {
        // thresEval.
        let (s, with_friction) = match f.law {
            FrictionLaw::Without => (cst(0.0), false),
            FrictionLaw::Tresca(v) => (cst(v), true),
            FrictionLaw::Coulomb(mu) if contact => {
                let s = proj_rm * (-mu);
                (s, s.v != 0.0)
            }
            FrictionLaw::Stick if contact => (cst(THRES_STICK), true),
            _ => (cst(0.0), false),
        };
        let mut lam_f = cst(0.0);
        for k in 0..nl {
            lam_f = lam_f + D::variable(f.lam_f[k], lf(k)) * p.lagr_shape[k];
        }
        // speedEval: v = −(x_s⁻ − x_m⁻ + g n_s⁻).
        let n_prev = normal_at(c.s_kind, c.sprev, p.xi, c.sign).ok_or_else(|| {
            err(ContactError::Invalid {
                keyword: "GROUP_MA_ESCL",
                message: "a slave cell is degenerate (zero length) at the start of the step".into(),
            })
        })?;
        let mut xs_prev = [0.0; 2];
        for a in 0..ns {
            for e in 0..2 {
                xs_prev[e] += shs[a] * c.sprev[a][e];
            }
        }
        let mut xm_prev = [cst(0.0); 2];
        let mut tm_prev = [cst(0.0); 2];
        for b in 0..nm {
            for e in 0..2 {
                xm_prev[e] = xm_prev[e] + nmf[b] * c.mprev[b][e];
                tm_prev[e] = tm_prev[e] + dnmf[b] * c.mprev[b][e];
            }
        }
        let v = [0, 1].map(|e| -(cst(xs_prev[e]) - xm_prev[e] + gap * n_prev[e]));
        // projBs of λ n + τ λ_f − γ_f v.
        let x = [0, 1].map(|e| lam_c * n[e] + tau[e] * lam_f - v[e] * f.gamma_f);
        let mut proj = [cst(0.0); 2];
        if f.law != FrictionLaw::Without && s.v.abs() > R8PREM {
            let xn = dot2(x, n);
            let xt = [x[0] - n[0] * xn, x[1] - n[1] * xn];
            let lxt = (xt[0].v * xt[0].v + xt[1].v * xt[1].v).sqrt();
            if lxt <= s.v {
                proj = xt;
            } else {
                slip = true;
                let l = dot2(xt, xt).sqrt();
                proj = [s * xt[0] / l, s * xt[1] / l];
            }
        }
        if with_friction {
            // −w P·Dv_T[v], Dv_T = −(Dn⊗n + n⊗Dn) v + (I − n⊗n)(τ_m⁻ Dζ − Dg n⁻).
            let nv = dot2(n, v);
            for j in 0..ndisp {
                let dnv = dot2(dn[j], v);
                let dv = [0, 1].map(|e| tm_prev[e] * dzeta[j] - dgap[j] * n_prev[e]);
                let ndv = dot2(n, dv);
                let dvt = [0, 1].map(|e| -(dn[j][e] * nv + n[e] * dnv) + dv[e] - n[e] * ndv);
                res[j] = res[j] - dot2(proj, dvt) * p.w;
            }
        }
        // w (τ·P − |τ|² λ_f)/γ_f μ.
        let term = dot2(tau, proj) - tau2 * lam_f;
        for k in 0..nl {
            res[lf(k)] = res[lf(k)] + term * (p.w * p.lagr_shape[k] / f.gamma_f);
        }
    }
    Ok(Some((res, PointStatus { contact, slip })))
}

/// The CLASSIQUE mortar contact of a DEFI_CONT, as a fem force source.
#[derive(Clone, Debug)]
pub struct MortarClassique {
    /// The zones, their pairing, slave nodes and acceptance (shared with
    /// the ROBUSTE formulation).
    base: MortarLagrangian,
    /// Each zone's friction law and `COEF_FROT` (`None`: frictionless).
    friction: Option<Vec<(FrictionLaw, f64)>>,
    /// Positions at the start of the step (`coor_*_prev`).
    x_prev: Vec<[f64; 3]>,
}

impl MortarClassique {
    /// The contact of `zones` on `mesh` (`dim` 2, `axis`: AXIS weights, or
    /// 3: faces, frictionless only): frictionless when no zone has
    /// [`MortarZoneDef::friction`], with friction when all have (code_aster's zones of one DEFI_CONT are all
    /// with friction or all without).
    pub fn new(
        zones: &[MortarZoneDef],
        mesh: &Mesh,
        axis: bool,
        dim: usize,
    ) -> Result<Self, ContactError> {
        if dim == 3 && zones.iter().any(|z| z.friction.is_some()) {
            return Err(ContactError::Unsupported {
                feature: "friction with VARIANTE='CLASSIQUE' in 3D".into(),
                hint: "CLASSIQUE friction is reproduced on 2D models (D_PLAN, C_PLAN, AXIS); VARIANTE='ROBUSTE' has friction in 3D".into(),
            });
        }
        let friction = if zones.iter().any(|z| z.friction.is_some()) {
            Some(
                zones
                    .iter()
                    .map(|z| {
                        z.friction.map(|law| (law, z.coef_frot)).ok_or_else(|| {
                            ContactError::Unsupported {
                                feature: format!(
                                    "a zone without friction ({} on {}) beside zones with friction in one DEFI_CONT",
                                    z.slave_group, z.master_group
                                ),
                                hint: "give every zone FROTTEMENT='OUI' (TYPE_FROT='SANS' for no friction force)".into(),
                            }
                        })
                    })
                    .collect::<Result<Vec<_>, _>>()?,
            )
        } else {
            None
        };
        Ok(MortarClassique {
            base: MortarLagrangian::new(zones, mesh, axis, dim)?,
            friction,
            x_prev: mesh.coords.clone(),
        })
    }

    /// MECA_NON_LINE's `CONTACT/RESI_GEOM` (see
    /// [`MortarLagrangian::set_resi_geom`]).
    pub fn set_resi_geom(&mut self, resi_geom: f64) {
        self.base.set_resi_geom(resi_geom);
    }

    /// Whether the zones have friction (two unknowns per slave node).
    pub fn has_friction(&self) -> bool {
        self.friction.is_some()
    }

    fn per_node(&self) -> usize {
        if self.friction.is_some() {
            2
        } else {
            1
        }
    }

    /// The multipliers of each slave node: `LAGS_C` (the contact pressure)
    /// and, with friction, `LAGS_F1` (the tangential multiplier along the
    /// unnormalised slave tangent); 0 without friction.
    pub fn multipliers<'a>(
        &'a self,
        own: &'a [f64],
    ) -> impl Iterator<Item = (NodeId, [f64; 2])> + 'a {
        let k = self.per_node();
        self.base.lagr.iter().enumerate().map(move |(i, n)| {
            let at = |r: usize| own.get(r).copied().unwrap_or(0.0);
            (*n, [at(k * i), if k == 2 { at(k * i + 1) } else { 0.0 }])
        })
    }
}

/// A 3D slave/master pair of the CLASSIQUE variant, frictionless: what
/// its residual needs besides the current positions and multipliers
/// (`laVect_ct_std` on faces).
struct FacePair<'a> {
    s: &'a Seg,
    m: &'a Seg,
    /// The intersection polygon (slave parametric space), held.
    poly: &'a [[f64; 2]],
    /// The slave face's initial positions (weights, `LAGS_C` functions).
    s0: &'a [[f64; 3]],
    gamma_c: f64,
    forced: Option<bool>,
}

impl FacePair<'_> {
    /// The pair's residual on its local unknowns — the slave nodes' DX,
    /// DY, DZ, the master nodes', then the slave corners' `LAGS_C` —
    /// at slave positions `sp`, master positions `mp` and multipliers
    /// `lam` (`laVect_ct_std`): w [λ + γ_c g]₋ Dg at active points,
    /// w ([λ + γ_c g]₋ − λ)/γ_c μ on the multipliers; the master point
    /// found afresh by ray tracing.
    fn residual(
        &self,
        sp: &[[f64; 3]],
        mp: &[[f64; 3]],
        lam: &[f64],
    ) -> Result<Vec<f64>, FemError> {
        let ndisp = 3 * (sp.len() + mp.len());
        let mut r = vec![0.0; ndisp + lam.len()];
        // Dg does not depend on which global DOFs the nodes carry.
        let local: Vec<[Option<usize>; 3]> = vec![[None; 3]; sp.len() + mp.len()];
        for pt in crate::mortar_point::points_3d(self.s, self.m, self.poly, sp, mp, self.s0)? {
            let nsl = self.s.lagr_shape(pt.xi, &pt.initial.shape);
            let lam_p: f64 = nsl.iter().zip(lam).map(|(f, l)| f * l).sum();
            let lg = lam_p + self.gamma_c * pt.gap;
            // CONTACT_INIT at the first pairing, then Heaviside(−(λ + γg)).
            let active = self.forced.unwrap_or(-lg >= 0.0);
            let proj = if active { lg } else { 0.0 };
            if active {
                for (j, e) in pt.linearise_3d(self.s, self.m, &local).iter().enumerate() {
                    r[j] += pt.w * proj * e.dgap;
                }
            }
            for (a, f) in nsl.iter().enumerate() {
                r[ndisp + a] += pt.w * (proj - lam_p) / self.gamma_c * f;
            }
        }
        Ok(r)
    }

    /// code_aster's matrix of the variant (`laMatr_diff`, order 1: the
    /// catalog allows only `TYPE_MATR_TANG='PERTURBATION'` with
    /// CLASSIQUE): one-sided differences of [`FacePair::residual`] with
    /// ε = 1e-6 h_F, a slave DOF pushed by ε n_d (n the slave normal at
    /// the pair's first quadrature point) when |n_d| > ε, else by ε, a
    /// master DOF pulled the same way, a multiplier scaled by (1 − ε) when
    /// |λ| > ε, else set to −ε. Column j: ∂r/∂(local unknown j), `r0` the
    /// residual at the unperturbed state.
    fn jacobian(
        &self,
        sp: &[[f64; 3]],
        mp: &[[f64; 3]],
        lam: &[f64],
        r0: &[f64],
        hf: f64,
    ) -> Result<Vec<Vec<f64>>, FemError> {
        let eps = 1e-6 * hf;
        let n = crate::mortar_point::quadrature_3d(self.s, self.m, self.poly, self.s0)
            .first()
            .and_then(|(xi, _)| {
                crate::mortar_pairing3d::face_normal(self.s.kind, sp, *xi, self.s.sign)
            })
            .unwrap_or([0.0; 3]);
        let step = |d: usize| if n[d].abs() > eps { eps * n[d] } else { eps };
        let column = |r: Vec<f64>, delta: f64| -> Vec<f64> {
            r.iter().zip(r0).map(|(p, q)| (p - q) / delta).collect()
        };
        let mut cols = Vec::with_capacity(r0.len());
        let mut x = sp.to_vec();
        for a in 0..sp.len() {
            for d in 0..3 {
                let saved = x[a][d];
                x[a][d] = saved + step(d);
                let delta = x[a][d] - saved;
                cols.push(column(self.residual(&x, mp, lam)?, delta));
                x[a][d] = saved;
            }
        }
        let mut y = mp.to_vec();
        for b in 0..mp.len() {
            for d in 0..3 {
                let saved = y[b][d];
                y[b][d] = saved - step(d);
                let delta = y[b][d] - saved;
                cols.push(column(self.residual(sp, &y, lam)?, delta));
                y[b][d] = saved;
            }
        }
        let mut l = lam.to_vec();
        for k in 0..lam.len() {
            let saved = l[k];
            l[k] = if saved.abs() > eps {
                saved * (1.0 - eps)
            } else {
                -eps
            };
            let delta = l[k] - saved;
            cols.push(column(self.residual(sp, mp, &l)?, delta));
            l[k] = saved;
        }
        Ok(cols)
    }
}

impl MortarClassique {
    /// The residual and code_aster's finite-difference matrix on faces
    /// (3D, frictionless: `laVect_ct_std`, `laMatr_diff`).
    fn evaluate_3d(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError> {
        let x = current_positions(state);
        let x0 = &state.mesh.coords;
        let base = &self.base;
        let nl = base.lagr.len();
        let mut c = Contribution {
            forces: Vec::new(),
            own_residual: vec![0.0; nl],
            tangent: Vec::new(),
        };
        let mut paired = vec![false; nl];
        for p in &base.pairs(&x) {
            let z = &base.zones[p.zone];
            let s = &z.slave[p.slave];
            let m = &z.master[p.master];
            let (sp, mp, s0) = (s.positions(&x), m.positions(&x), s.positions(x0));
            let hf = z.h[p.slave];
            let lk: Vec<usize> = s.lagr_nodes().iter().map(|n| base.lagr_of[n]).collect();
            for &k in &lk {
                paired[k] = true;
            }
            let lam: Vec<f64> = lk.iter().map(|&k| own[k]).collect();
            let pair = FacePair {
                s,
                m,
                poly: &p.poly,
                s0: &s0,
                gamma_c: z.coef / hf,
                forced: z.forced(base.first_pairing),
            };
            let r0 = pair.residual(&sp, &mp, &lam)?;
            let cols = pair.jacobian(&sp, &mp, &lam, &r0, hf)?;
            let map: Vec<Option<Unknown>> = crate::mortar_point::face_dofs(state, s, m)
                .into_iter()
                .flatten()
                .map(|d| d.map(Unknown::Dof))
                .chain(lk.iter().map(|&k| Some(Unknown::Own(k))))
                .collect();
            for (i, row) in map.iter().enumerate() {
                let Some(row) = *row else { continue };
                match row {
                    Unknown::Dof(d) if r0[i] != 0.0 => c.forces.push((d, r0[i])),
                    Unknown::Dof(_) => {}
                    Unknown::Own(k) => c.own_residual[k] += r0[i],
                }
                for (j, col) in map.iter().enumerate() {
                    if let (Some(col), true) = (col, cols[j][i] != 0.0) {
                        c.tangent.push((row, *col, cols[j][i]));
                    }
                }
            }
        }
        // Slave nodes of no paired cell: their multipliers are 0.
        for (k, p) in paired.iter().enumerate() {
            if !p {
                c.own_residual[k] += -own[k];
                c.tangent.push((Unknown::Own(k), Unknown::Own(k), -1.0));
            }
        }
        for k in 0..nl {
            c.tangent.push((Unknown::Own(k), Unknown::Own(k), 0.0));
        }
        Ok(c)
    }
}

impl ForceSource for MortarClassique {
    fn name(&self) -> String {
        "DEFI_CONT (mortar Lagrangian contact, CLASSIQUE)".into()
    }

    fn unknowns(&self) -> usize {
        self.per_node() * self.base.lagr.len()
    }

    fn begin_increment(&mut self, state: &State, own: &mut [f64]) -> Result<(), FemError> {
        self.x_prev = current_positions(state);
        self.base.begin_increment(state, own)
    }

    fn evaluate(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError> {
        if self.base.dim == 3 {
            return self.evaluate_3d(state, own);
        }
        let x = current_positions(state);
        let x0 = &state.mesh.coords;
        let base = &self.base;
        let per = self.per_node();
        let nl = base.lagr.len();
        let pairs = base.pairs(&x);
        let mut c = Contribution {
            forces: Vec::new(),
            own_residual: vec![0.0; per * nl],
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
            let hf = z.h[p.slave];
            let lk: Vec<usize> = s.lagr_nodes().iter().map(|n| base.lagr_of[n]).collect();
            for &k in &lk {
                paired[k] = true;
            }
            let lam_c: Vec<f64> = lk.iter().map(|&k| own[per * k]).collect();
            let lam_f: Vec<f64> = if per == 2 {
                lk.iter().map(|&k| own[2 * k + 1]).collect()
            } else {
                Vec::new()
            };
            // Global unknowns of the local ones.
            let mut map: Vec<Option<Unknown>> = Vec::new();
            for node in s.nodes.iter().chain(&m.nodes) {
                for d in 0..2 {
                    map.push(crate::mortar_point::dof(state, *node, d).map(Unknown::Dof));
                }
            }
            map.extend(lk.iter().map(|&k| Some(Unknown::Own(per * k))));
            if per == 2 {
                map.extend(lk.iter().map(|&k| Some(Unknown::Own(2 * k + 1))));
            }
            let cells = PointCells {
                s_kind: s.kind,
                sign: s.sign,
                sp: &sp,
                sprev: &sprev,
                m_kind: m.kind,
                mp: &mp,
                mprev: &mprev,
            };
            let forced = z.forced(base.first_pairing);
            for pt in crate::mortar_point::points(s, m, p.xi, &sp, &mp, &s0, base.axis)? {
                let lagr_shape = s.lagr_shape(pt.xi, &pt.initial.shape);
                let data = PointData {
                    xi: pt.xi[0],
                    w: pt.w,
                    zeta: pt.master.xi[0],
                    gap: pt.gap,
                    gamma_c: z.coef / hf,
                    lagr_shape: &lagr_shape,
                    lam_c: &lam_c,
                    forced,
                    friction: self.friction.as_ref().map(|laws| PointFriction {
                        law: laws[p.zone].0,
                        gamma_f: laws[p.zone].1 / hf,
                        lam_f: &lam_f,
                    }),
                };
                let Some((res, _)) = point_residual(&cells, &data)? else {
                    continue;
                };
                for (i, r) in res.iter().enumerate() {
                    let row = match map[i] {
                        Some(Unknown::Dof(row)) => {
                            if r.v != 0.0 {
                                c.forces.push((row, r.v));
                            }
                            Unknown::Dof(row)
                        }
                        Some(Unknown::Own(row)) => {
                            c.own_residual[row] += r.v;
                            Unknown::Own(row)
                        }
                        None => continue,
                    };
                    for (j, col) in map.iter().enumerate() {
                        if let (Some(col), true) = (col, r.d[j] != 0.0) {
                            c.tangent.push((row, *col, r.d[j]));
                        }
                    }
                }
            }
        }
        // Slave nodes of no paired cell: their multipliers are 0.
        for (k, p) in paired.iter().enumerate() {
            if !p {
                for r in per * k..per * (k + 1) {
                    c.own_residual[r] += -own[r];
                    c.tangent.push((Unknown::Own(r), Unknown::Own(r), -1.0));
                }
            }
        }
        for r in 0..per * nl {
            c.tangent.push((Unknown::Own(r), Unknown::Own(r), 0.0));
        }
        Ok(c)
    }

    fn after_iteration(&mut self, state: &State, own: &mut [f64]) -> Result<bool, FemError> {
        self.base.after_iteration(state, own)
    }

    fn own_rows_in_residual(&self) -> bool {
        true
    }

    fn converged(&mut self, state: &State, own: &[f64]) -> Result<(), FemError> {
        self.base.converged(state, own)
    }

    fn unknown_name(&self, k: usize, mesh: &Mesh) -> String {
        let per = self.per_node();
        crate::mortar_friction::friction_unknown_name(&self.base.lagr, per, k, mesh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::{dot, interpolate, project_along, sub};

    /// The residual of a SEG2 slave point over a SEG3 master, the local
    /// unknowns shifted by `z` (slave, master displacements, LAGS_C,
    /// LAGS_F1), the master point found afresh by ray tracing.
    fn residual(
        z: &[f64],
        law: Option<FrictionLaw>,
        lam: ([f64; 2], [f64; 2]),
    ) -> (Vec<D>, PointStatus) {
        let mut sp = vec![[0.0, 0.01, 0.0], [1.0, 0.03, 0.0]];
        let mut mp = vec![[1.2, -0.02, 0.0], [-0.1, 0.0, 0.0], [0.55, 0.01, 0.0]];
        let sprev = vec![[0.01, 0.02, 0.0], [1.0, 0.04, 0.0]];
        let mprev = vec![[1.2, -0.01, 0.0], [-0.1, 0.0, 0.0], [0.55, 0.0, 0.0]];
        for a in 0..2 {
            for e in 0..2 {
                sp[a][e] += z[2 * a + e];
            }
        }
        for b in 0..3 {
            for e in 0..2 {
                mp[b][e] += z[4 + 2 * b + e];
            }
        }
        let lam_c = [lam.0[0] + z[10], lam.0[1] + z[11]];
        let lam_f = [lam.1[0] + z[12], lam.1[1] + z[13]];
        let xi = 0.3;
        let s = interpolate(SurfaceKind::Seg2, &sp, [xi, 0.0]);
        let n = normal_at(SurfaceKind::Seg2, &sp, xi, 1.0).unwrap();
        let hit = project_along(SurfaceKind::Seg3, &mp, s.x, n).unwrap();
        let gap = -dot(sub(s.x, hit.x), n);
        let (shape, _) = SurfaceKind::Seg2.eval([xi, 0.0]);
        let cells = PointCells {
            s_kind: SurfaceKind::Seg2,
            sign: 1.0,
            sp: &sp,
            sprev: &sprev,
            m_kind: SurfaceKind::Seg3,
            mp: &mp,
            mprev: &mprev,
        };
        let data = PointData {
            xi,
            w: 0.7,
            zeta: hit.xi[0],
            gap,
            gamma_c: 3.0,
            lagr_shape: &shape,
            lam_c: &lam_c,
            forced: None,
            friction: law.map(|law| PointFriction {
                law,
                gamma_f: 5.0,
                lam_f: &lam_f,
            }),
        };
        point_residual(&cells, &data).unwrap().unwrap()
    }

    /// The tangent of a point is the derivative of its residual: central
    /// differences on every local unknown (the master point found again
    /// each time by ray tracing), in contact and out of it, without
    /// friction, sticking and sliding (Coulomb, Tresca). Without friction
    /// it is symmetric (the derivative of the augmented Lagrangian: its
    /// displacement block holds the gap's second derivative).
    #[test]
    fn point_tangent_is_the_derivative_of_the_residual() {
        let pressed = [-2.0, -1.5];
        let open = [0.5, 0.4];
        let cases = [
            (None, (pressed, [0.0; 2]), true, false),
            (None, (open, [0.0; 2]), false, false),
            (
                Some(FrictionLaw::Coulomb(0.3)),
                (pressed, [8.0, 6.0]),
                true,
                true,
            ),
            (
                Some(FrictionLaw::Coulomb(50.0)),
                (pressed, [0.01, 0.02]),
                true,
                false,
            ),
            (
                Some(FrictionLaw::Tresca(0.05)),
                (pressed, [0.8, 0.6]),
                true,
                true,
            ),
            (Some(FrictionLaw::Stick), (pressed, [0.8, 0.6]), true, false),
            (
                Some(FrictionLaw::Coulomb(0.3)),
                (open, [0.8, 0.6]),
                false,
                false,
            ),
        ];
        for (law, lam, contact, slip) in cases {
            let nloc = if law.is_some() { 14 } else { 12 };
            let (res, status) = residual(&[0.0; 14], law, lam);
            assert_eq!(status, PointStatus { contact, slip }, "{law:?} {lam:?}");
            assert_eq!(res.len(), nloc);
            let h = 1e-7;
            for j in 0..nloc {
                let mut zp = [0.0; 14];
                let mut zm = [0.0; 14];
                zp[j] += h;
                zm[j] -= h;
                let (rp, _) = residual(&zp, law, lam);
                let (rm, _) = residual(&zm, law, lam);
                for i in 0..nloc {
                    let fd = (rp[i].v - rm[i].v) / (2.0 * h);
                    assert!(
                        (fd - res[i].d[j]).abs() <= 1e-6 * (1.0 + fd.abs()),
                        "{law:?} {lam:?}: row {i} column {j}: {} against {fd}",
                        res[i].d[j]
                    );
                }
            }
            if law.is_none() {
                for i in 0..nloc {
                    for j in 0..nloc {
                        assert!(
                            (res[i].d[j] - res[j].d[i]).abs() <= 1e-12 * (1.0 + res[i].d[j].abs()),
                            "({i}, {j}): {} against {}",
                            res[i].d[j],
                            res[j].d[i]
                        );
                    }
                }
            }
        }
    }

    /// A warped QUAD4 slave face above a curved QUAD8 master face, the
    /// polygon the whole slave square: the 3D residual is the gradient
    /// of the augmented Lagrangian Σ w ([λ + γg]₋² − λ²)/(2γ) (central
    /// differences, the master point found afresh by ray tracing), and
    /// code_aster's one-sided matrix (`laMatr_diff`) is its derivative to
    /// the differences' accuracy.
    #[test]
    fn face_residual_is_the_gradient_of_the_augmented_lagrangian() {
        let s = Seg {
            kind: SurfaceKind::Quad4,
            nodes: (0..4).map(NodeId).collect(),
            sign: -1.0,
        };
        let m = Seg {
            kind: SurfaceKind::Quad8,
            nodes: (4..12).map(NodeId).collect(),
            sign: 1.0,
        };
        let s0 = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let sp = vec![
            [0.01, 0.0, 0.012],
            [1.0, 0.02, -0.004],
            [1.02, 1.0, 0.03],
            [0.0, 0.99, 0.0],
        ];
        let mp: Vec<[f64; 3]> = SurfaceKind::Quad8
            .node_coords()
            .iter()
            .map(|q| {
                let (x, y) = (0.5 + q[0], 0.5 + 0.9 * q[1]);
                [
                    x,
                    y,
                    -0.02 * (x - 0.4) * (x - 0.4) - 0.01 * y * y + 0.01 * x * y,
                ]
            })
            .collect();
        let poly = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        let pair = FacePair {
            s: &s,
            m: &m,
            poly: &poly,
            s0: &s0,
            gamma_c: 30.0,
            forced: None,
        };
        // Two corners pressed, two nearly free: active and inactive points.
        let lam = [-0.9, -0.5, 0.2, -0.05];
        let functional = |sp: &[[f64; 3]], mp: &[[f64; 3]], lam: &[f64]| -> f64 {
            let mut l = 0.0;
            for pt in crate::mortar_point::points_3d(&s, &m, &poly, sp, mp, &s0).unwrap() {
                let (shape, _) = SurfaceKind::Quad4.eval(pt.xi);
                let lp: f64 = shape.iter().zip(lam).map(|(f, v)| f * v).sum();
                let x = (lp + pair.gamma_c * pt.gap).min(0.0);
                l += pt.w * (x * x - lp * lp) / (2.0 * pair.gamma_c);
            }
            l
        };
        let r = pair.residual(&sp, &mp, &lam).unwrap();
        assert_eq!(r.len(), 12 + 24 + 4);
        let unknown = |z: &[f64]| {
            let mut a = sp.clone();
            let mut b = mp.clone();
            let mut c = lam.to_vec();
            for (j, v) in z.iter().enumerate() {
                match j {
                    0..=11 => a[j / 3][j % 3] += v,
                    12..=35 => b[(j - 12) / 3][(j - 12) % 3] += v,
                    _ => c[j - 36] += v,
                }
            }
            (a, b, c)
        };
        let h = 1e-6;
        let (mut active, mut inactive) = (false, false);
        for pt in crate::mortar_point::points_3d(&s, &m, &poly, &sp, &mp, &s0).unwrap() {
            let (shape, _) = SurfaceKind::Quad4.eval(pt.xi);
            let lp: f64 = shape.iter().zip(&lam).map(|(f, v)| f * v).sum();
            if lp + pair.gamma_c * pt.gap <= 0.0 {
                active = true;
            } else {
                inactive = true;
            }
        }
        assert!(active && inactive, "both statuses are exercised");
        for j in 0..r.len() {
            let mut zp = vec![0.0; r.len()];
            let mut zm = vec![0.0; r.len()];
            zp[j] = h;
            zm[j] = -h;
            let (a, b, c) = unknown(&zp);
            let lp = functional(&a, &b, &c);
            let (a, b, c) = unknown(&zm);
            let lm = functional(&a, &b, &c);
            let fd = (lp - lm) / (2.0 * h);
            assert!(
                (fd - r[j]).abs() <= 1e-7 * (1.0 + fd.abs()),
                "row {j}: {} against {fd}",
                r[j]
            );
        }
        let cols = pair.jacobian(&sp, &mp, &lam, &r, 1.0).unwrap();
        assert_eq!(cols.len(), r.len());
        for (j, col) in cols.iter().enumerate() {
            let mut zp = vec![0.0; r.len()];
            let mut zm = vec![0.0; r.len()];
            zp[j] = h;
            zm[j] = -h;
            let (a, b, c) = unknown(&zp);
            let rp = pair.residual(&a, &b, &c).unwrap();
            let (a, b, c) = unknown(&zm);
            let rm = pair.residual(&a, &b, &c).unwrap();
            for i in 0..r.len() {
                let fd = (rp[i] - rm[i]) / (2.0 * h);
                assert!(
                    (fd - col[i]).abs() <= 1e-4 * (1.0 + fd.abs()),
                    "({i}, {j}): {} against {fd}",
                    col[i]
                );
            }
        }
    }
}
