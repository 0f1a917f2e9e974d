//! One quadrature point of a mortar contact pair of `DEFI_CONT`: what
//! code_aster 17's Lagrangian (`laVect_ct_pr`), penalised (`peVect_ct_pr`)
//! and Nitsche (`niVect`) residuals share, computed once here for the three
//! (`mortar_lagrangian`, `mortar_penalty`, `mortar_nitsche`).
//!
//! As code_aster's (2025 main):
//!
//! - **Quadrature** (`getQuadCont`, `lcptga`): FPG3 when both cells are
//!   SEG2, FPG4 otherwise, on the intersection segment in the slave's
//!   parametric space; the weight is the slave Jacobian on the **initial**
//!   coordinates (× the initial radius in AXIS, 1e-7 on the axis).
//! - **Projection** (`projQpSl2Ma`): n_s the outward slave normal on the
//!   current geometry, the master point by ray tracing along n_s (exact on
//!   a SEG2 master, `shape::project_along` — code_aster's `mmnewd` — on a
//!   SEG3 one), the gap g = −(x_s − x_m)·n_s. A point whose ray misses the
//!   master line is skipped.
//! - **Jump** (`jump`): the displacement DOFs of n_s·(v_s − v_m) with
//!   their factors.
//! - **Pairing configuration** (`on_current`): code_aster's `projQpSl2Ma`
//!   takes n_s and the master point on the coordinates of the last pairing
//!   (`coor_slav_pair`, `coor_mast_pair`: the iterate at the start of the
//!   Newton iteration) and only the gap on the current ones. Within an
//!   iteration the two coincide; in MECA_NON_LINE's line search the trial
//!   residuals at u + ρΔ keep the pairing, normals and master points of u.

use aster_fem::{Comp, Dof, FemError, State};

use crate::error::ContactError;
use crate::lac_mortar::{piece_points, Family};
use crate::mortar_lagrangian::{err, normal_at, ray_hit, Seg};
use crate::mortar_pairing3d::{self, face_normal};
use crate::shape::{cross, dot, interpolate, norm, project_along, sub, CellPoint, SurfaceKind};

/// A quadrature point of a slave/master pair.
#[derive(Clone, Debug)]
pub(crate) struct MortarPoint {
    /// The point in the slave's parametric space.
    pub xi: [f64; 2],
    /// Weight: reference weight × initial Jacobian (× initial radius in
    /// AXIS).
    pub w: f64,
    /// The slave point on the initial coordinates (its shape values are
    /// the slave functions at the point).
    pub initial: CellPoint,
    /// The slave point on the current coordinates.
    pub slave: CellPoint,
    /// Outward unit slave normal (current).
    pub ns: [f64; 3],
    /// The master point hit by the ray along n_s.
    pub master: CellPoint,
    /// g = −(x_s − x_m)·n_s (negative when interpenetrated).
    pub gap: f64,
}

impl MortarPoint {
    /// The point's DOFs on faces (`dofs`: the slave nodes' (DX, DY, DZ),
    /// then the master's) with the derivatives of code_aster's analytic
    /// tangent (`dNs_du`, `dPi_du`: [`crate::mortar_tangent::linearise_3d`]).
    pub(crate) fn linearise_3d(
        &self,
        s: &Seg,
        m: &Seg,
        dofs: &[[Option<usize>; 3]],
    ) -> Vec<crate::mortar_tangent::FaceDof> {
        let (_, sd) = s.kind.eval(self.xi);
        let (_, md) = m.kind.eval(self.master.xi);
        crate::mortar_tangent::linearise_3d(
            &crate::mortar_tangent::FaceGeometry {
                slave_shape: &self.initial.shape,
                slave_dshape: &sd,
                master_shape: &self.master.shape,
                master_dshape: &md,
                tau_slave: self.slave.tangents,
                normal: self.ns,
                tau_master: self.master.tangents,
                gap: self.gap,
            },
            dofs,
        )
    }
}

impl MortarPoint {
    /// The point's DOFs with the derivatives of code_aster's analytic
    /// tangent (`dNs_du`, `dPi_du`), on segments (2D,
    /// [`crate::mortar_tangent::linearise`], one tangent direction) or on
    /// faces ([`MortarPoint::linearise_3d`]).
    pub(crate) fn linearise(
        &self,
        s: &Seg,
        m: &Seg,
        dofs: &PairDofs,
    ) -> Vec<crate::mortar_tangent::FaceDof> {
        let dofs = match dofs {
            PairDofs::Faces(dofs) => return self.linearise_3d(s, m, dofs),
            PairDofs::Segments(dofs) => dofs,
        };
        let (_, sd) = s.kind.eval(self.xi);
        let (_, md) = m.kind.eval(self.master.xi);
        crate::mortar_tangent::linearise(
            &crate::mortar_tangent::PointGeometry {
                slave_shape: &self.initial.shape,
                slave_dshape: &sd.iter().map(|d| d[0]).collect::<Vec<_>>(),
                master_shape: &self.master.shape,
                master_dshape: &md.iter().map(|d| d[0]).collect::<Vec<_>>(),
                tau_slave: self.slave.tangents[0],
                normal: self.ns,
                tau_master: self.master.tangents[0],
                gap: self.gap,
            },
            dofs,
        )
        .into_iter()
        .map(crate::mortar_tangent::FaceDof::from)
        .collect()
    }
}

/// The displacement DOFs of a pair's nodes, slave then master, as
/// [`MortarPoint::linearise`] takes them: DX, DY on segments (2D), DX, DY,
/// DZ on faces (3D).
pub(crate) enum PairDofs {
    Segments(Vec<[Option<usize>; 2]>),
    Faces(Vec<[Option<usize>; 3]>),
}

impl PairDofs {
    /// The DOFs of the pair `s`, `m` in a model of dimension `dim`.
    pub(crate) fn of(state: &State, s: &Seg, m: &Seg, dim: usize) -> PairDofs {
        if dim == 3 {
            PairDofs::Faces(face_dofs(state, s, m))
        } else {
            PairDofs::Segments(
                s.nodes
                    .iter()
                    .chain(&m.nodes)
                    .map(|n| [dof(state, *n, 0), dof(state, *n, 1)])
                    .collect(),
            )
        }
    }
}

/// The displacement DOFs (DX, DY, DZ) of a 3D pair's nodes, slave then
/// master, as [`MortarPoint::linearise_3d`] takes them.
pub(crate) fn face_dofs(state: &State, s: &Seg, m: &Seg) -> Vec<[Option<usize>; 3]> {
    s.nodes
        .iter()
        .chain(&m.nodes)
        .map(|n| [0, 1, 2].map(|d| dof(state, *n, d)))
        .collect()
}

/// The integration points of a 2D pair on the intersection `xi` (slave
/// parametric space, `getQuadCont`, `lcptga`): FPG3 when both cells are
/// SEG2, FPG4 otherwise; each with its weight — the reference weight times
/// the slave Jacobian on the initial coordinates `s0` (× the initial
/// radius in AXIS, 1e-7 on the axis) — and the slave point there on `s0`.
pub(crate) fn quadrature_2d(
    s: &Seg,
    m: &Seg,
    xi: [f64; 2],
    s0: &[[f64; 3]],
    axis: bool,
) -> Vec<([f64; 2], f64, CellPoint)> {
    let family = if s.kind == SurfaceKind::Seg2 && m.kind == SurfaceKind::Seg2 {
        Family::Fpg3
    } else {
        Family::Fpg4
    };
    piece_points(2, &[[xi[0], 0.0], [xi[1], 0.0]], family)
        .into_iter()
        .map(|(xi, w_ref)| {
            let at0 = interpolate(s.kind, s0, xi);
            let mut w = w_ref * norm(at0.tangents[0]);
            if axis {
                let r = at0.x[0];
                w *= if r == 0.0 { 1e-7 } else { r };
            }
            (xi, w, at0)
        })
        .collect()
}

/// The quadrature points of the pair of slave `s` and master `m` on the
/// intersection `xi` (slave parametric space): `sp`, `mp` the cells'
/// current node positions, `s0` the slave's initial ones.
pub(crate) fn points(
    s: &Seg,
    m: &Seg,
    xi: [f64; 2],
    sp: &[[f64; 3]],
    mp: &[[f64; 3]],
    s0: &[[f64; 3]],
    axis: bool,
) -> Result<Vec<MortarPoint>, FemError> {
    let mut out = Vec::new();
    for (xi, w, at0) in quadrature_2d(s, m, xi, s0, axis) {
        let ns = normal_at(s.kind, sp, xi[0], s.sign).ok_or_else(|| {
            err(ContactError::Invalid {
                keyword: "GROUP_MA_ESCL",
                message: "a slave cell is degenerate (zero length)".into(),
            })
        })?;
        let slave = interpolate(s.kind, sp, xi);
        let hit = if m.kind == SurfaceKind::Seg2 {
            ray_hit(slave.x, ns, mp[0], mp[1]).map(|k| interpolate(m.kind, mp, [k, 0.0]))
        } else {
            project_along(m.kind, mp, slave.x, ns)
        };
        let Some(hit) = hit else {
            continue;
        };
        let gap = -dot(sub(slave.x, hit.x), ns);
        out.push(MortarPoint {
            xi,
            w,
            initial: at0,
            slave,
            ns,
            master: hit,
            gap,
        });
    }
    Ok(out)
}

/// The integration points of the pair `p` of slave `s` and master `m`, in
/// the slave's parametric space with their weights: on its intersection
/// segment in 2D ([`quadrature_2d`]), on its polygon in 3D
/// ([`quadrature_3d`]).
pub(crate) fn quadrature(
    s: &Seg,
    m: &Seg,
    p: &crate::mortar_lagrangian::Pair,
    s0: &[[f64; 3]],
    dim: usize,
    axis: bool,
) -> Vec<([f64; 2], f64)> {
    if dim == 3 {
        quadrature_3d(s, m, &p.poly, s0)
    } else {
        quadrature_2d(s, m, p.xi, s0, axis)
            .into_iter()
            .map(|(xi, w, _)| (xi, w))
            .collect()
    }
}

/// The integration points of a 3D pair on its polygon `poly` (slave
/// parametric space): FPG4 per triangle when both faces are linear, FPG7
/// otherwise, each weight times the slave face's initial |t₁ × t₂| on `s0`
/// (`mmmjac`).
pub(crate) fn quadrature_3d(
    s: &Seg,
    m: &Seg,
    poly: &[[f64; 2]],
    s0: &[[f64; 3]],
) -> Vec<([f64; 2], f64)> {
    let linear = |k: SurfaceKind| matches!(k, SurfaceKind::Tria3 | SurfaceKind::Quad4);
    mortar_pairing3d::quadrature(poly, linear(s.kind) && linear(m.kind))
        .into_iter()
        .map(|(xi, w_ref)| {
            let at0 = interpolate(s.kind, s0, xi);
            (xi, w_ref * norm(cross(at0.tangents[0], at0.tangents[1])))
        })
        .collect()
}

/// The quadrature points of the pair of slave face `s` and master face
/// `m` (3D) on their intersection polygon `poly` (slave parametric space,
/// `mortar_pairing3d`): FPG4 on each triangle of the polygon when both
/// faces are linear, FPG7 otherwise; the weight carries the slave face's
/// initial |t₁ × t₂| (`mmmjac`), the normal is t₁ × t₂ / |t₁ × t₂|
/// (`apnorm`), the master point is found along it on the full master face
/// (`mmnewd`).
pub(crate) fn points_3d(
    s: &Seg,
    m: &Seg,
    poly: &[[f64; 2]],
    sp: &[[f64; 3]],
    mp: &[[f64; 3]],
    s0: &[[f64; 3]],
) -> Result<Vec<MortarPoint>, FemError> {
    let mut out = Vec::new();
    for (xi, w) in quadrature_3d(s, m, poly, s0) {
        let at0 = interpolate(s.kind, s0, xi);
        let ns = face_normal(s.kind, sp, xi, s.sign).ok_or_else(|| {
            err(ContactError::Invalid {
                keyword: "GROUP_MA_ESCL",
                message: "a slave cell is degenerate (zero area)".into(),
            })
        })?;
        let slave = interpolate(s.kind, sp, xi);
        let Some(hit) = project_along(m.kind, mp, slave.x, ns) else {
            continue;
        };
        let gap = -dot(sub(slave.x, hit.x), ns);
        out.push(MortarPoint {
            xi,
            w,
            initial: at0,
            slave,
            ns,
            master: hit,
            gap,
        });
    }
    Ok(out)
}

/// A point found on the pairing configuration (its intersection, normal
/// and master parametric point) carried to the current node positions
/// `sp` (slave) and `mp` (master): the slave and master points are moved
/// with their cells, n_s is kept, and the gap is −(x_s − x_m)·n_s on the
/// current positions (`projQpSl2Ma`: `gapEval` on `coor_*_curr` with the
/// pairing's `norm_slav` and `coor_qp_ma`).
pub(crate) fn on_current(
    mut pt: MortarPoint,
    s: &Seg,
    m: &Seg,
    sp: &[[f64; 3]],
    mp: &[[f64; 3]],
) -> MortarPoint {
    pt.slave = interpolate(s.kind, sp, pt.xi);
    pt.master = interpolate(m.kind, mp, pt.master.xi);
    pt.gap = -dot(sub(pt.slave.x, pt.master.x), pt.ns);
    pt
}

/// The displacement DOF of node `n`'s component `c` (0: DX, 1: DY, 2: DZ).
pub(crate) fn dof(state: &State, n: aster_mesh::NodeId, c: usize) -> Option<usize> {
    let comp = match c {
        0 => Comp::DX,
        1 => Comp::DY,
        _ => Comp::DZ,
    };
    state.dofs.index(Dof::new(n, comp))
}
