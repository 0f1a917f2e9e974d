//! The linearisation of a contact point of code_aster 17's mortar contact
//! (`DEFI_CONT`) as its analytic tangent (`TYPE_MATR_TANG='ANALYTIQUE'`, the
//! default) builds it, in 2D and on faces in 3D (the Lagrangian and the
//! 3D penalised methods): code_aster's `contact_algebra_module` (`jump`,
//! `dTs_du_ns`, `dNs_du`, `dPi_du`) and `contact_module` (`evalDtestM`),
//! used by `laMatr_ct_pr` and `peMatr_ct_pr`.
//!
//! At a slave point ξ (fixed in the slave's parametric space) the master
//! point ζ is found by ray tracing along the slave normal: x_m(ζ) = x_s +
//! g n_s. Differentiating, with v the variation of the displacements,
//!
//! ```text
//! τ_m Dζ[v] − Dg[v] n_s = (v_s − v_m) + g Dn_s[v]
//! Dn_s[v] = −τ_s (Dτ_s[v]·n_s) / |τ_s|²
//! ```
//!
//! (τ_s = ∂x_s/∂ξ, τ_m = ∂x_m/∂ζ, unnormalised as `apnorm` returns them),
//! a 2 × 2 system per DOF for (Dζ, Dg). The tangent of the point then has,
//! besides the multiplier terms, −w λ jump·Dn_s (the normal turning) and
//! w λ n_s·(∂N_m/∂ζ) Dζ (the master point sliding) on the displacement
//! rows, and w μ Dg (the full derivative of the gap) on the multiplier rows.
//!
//! On faces (3D, [`linearise_3d`]) the same quantities with two tangents
//! each side (`dNs_du`, `dPi_du` with `elem_dime` = 3):
//!
//! ```text
//! Dn_s[v] = −Σ_αβ τ_sα G^αβ (Dτ_sβ[v]·n_s),  G_αβ = τ_sα·τ_sβ
//! τ_m1 Dζ₁ + τ_m2 Dζ₂ − n_s Dg = (v_s − v_m) + g Dn_s
//! ```

use crate::shape::dot;

/// One displacement DOF of a contact point (slave nodes' DX, DY first,
/// then the master nodes'), with what the tangent needs of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointDof {
    /// The DOF's index in the model's numbering (`None`: not numbered).
    pub dof: Option<usize>,
    /// The jump of the test function v_s − v_m for a unit value of this DOF.
    pub jump: [f64; 3],
    /// Dn_s: the derivative of the unit slave normal.
    pub dns: [f64; 3],
    /// ∂(v_m)/∂ζ: the derivative of the master test function along ζ
    /// (`evalDtestM`; zero on a slave DOF).
    pub dtest_m: [f64; 3],
    /// Dζ: the derivative of the master point's parameter.
    pub dzeta: f64,
    /// Dg: the derivative of the gap g = −(x_s − x_m)·n_s.
    pub dgap: f64,
}

/// The geometry of a paired point, on the current coordinates.
pub struct PointGeometry<'a> {
    /// Slave shape functions and their ∂/∂ξ at the point.
    pub slave_shape: &'a [f64],
    pub slave_dshape: &'a [f64],
    /// Master shape functions and their ∂/∂ζ at the master point.
    pub master_shape: &'a [f64],
    pub master_dshape: &'a [f64],
    /// τ_s = ∂x_s/∂ξ, the unit outward slave normal n_s, τ_m = ∂x_m/∂ζ.
    pub tau_slave: [f64; 3],
    pub normal: [f64; 3],
    pub tau_master: [f64; 3],
    /// The gap g.
    pub gap: f64,
}

/// The DOFs of a point with their derivatives (`dofs`: the slave nodes'
/// (DX, DY) then the master nodes', in the order of the shape functions).
pub fn linearise(p: &PointGeometry, dofs: &[[Option<usize>; 2]]) -> Vec<PointDof> {
    let ns = p.normal;
    let ts = p.tau_slave;
    let tm = p.tau_master;
    let ts2 = dot(ts, ts);
    let nsl = p.slave_shape.len();
    let mut out = Vec::with_capacity(2 * dofs.len());
    for (node, ids) in dofs.iter().enumerate() {
        for (d, &dof) in ids.iter().enumerate() {
            let mut e = PointDof {
                dof,
                jump: [0.0; 3],
                dns: [0.0; 3],
                dtest_m: [0.0; 3],
                dzeta: 0.0,
                dgap: 0.0,
            };
            if node < nsl {
                e.jump[d] = p.slave_shape[node];
                // dTs_du_ns then dNs_du: −τ_s (∂N_a/∂ξ n_s[d]) / |τ_s|².
                if ts2 > 0.0 {
                    let c = -p.slave_dshape[node] * ns[d] / ts2;
                    e.dns = [c * ts[0], c * ts[1], c * ts[2]];
                }
            } else {
                let b = node - nsl;
                e.jump[d] = -p.master_shape[b];
                e.dtest_m[d] = p.master_dshape[b];
            }
            // dPi_du: (τ_m, −n_s) (Dζ, Dg) = jump + g Dn_s.
            let r = [e.jump[0] + p.gap * e.dns[0], e.jump[1] + p.gap * e.dns[1]];
            let det = -tm[0] * ns[1] + ns[0] * tm[1];
            if det.abs() > f64::EPSILON * (tm[0].abs() + tm[1].abs()) {
                e.dzeta = (-r[0] * ns[1] + ns[0] * r[1]) / det;
                e.dgap = (tm[0] * r[1] - tm[1] * r[0]) / det;
            } else {
                e.dgap = -(r[0] * ns[0] + r[1] * ns[1]);
            }
            out.push(e);
        }
    }
    out
}

/// One displacement DOF of a point on faces (3D, [`linearise_3d`]): the
/// slave nodes' DX, DY, DZ first, then the master nodes'.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceDof {
    /// The DOF's index in the model's numbering (`None`: not numbered).
    pub dof: Option<usize>,
    /// The jump of the test function v_s − v_m for a unit value of this DOF.
    pub jump: [f64; 3],
    /// Dn_s: the derivative of the unit slave normal.
    pub dns: [f64; 3],
    /// ∂(v_m)/∂ζ_α, α = 1, 2 (`evalDtestM`; zero on a slave DOF).
    pub dtest_m: [[f64; 3]; 2],
    /// Dζ_α: the derivatives of the master point's parameters.
    pub dzeta: [f64; 2],
    /// Dg: the derivative of the gap g = −(x_s − x_m)·n_s.
    pub dgap: f64,
}

impl From<PointDof> for FaceDof {
    /// A segment's point as a face's with one tangent (the second
    /// parameter's derivatives zero).
    fn from(e: PointDof) -> Self {
        FaceDof {
            dof: e.dof,
            jump: e.jump,
            dns: e.dns,
            dtest_m: [e.dtest_m, [0.0; 3]],
            dzeta: [e.dzeta, 0.0],
            dgap: e.dgap,
        }
    }
}

/// The geometry of a paired point on faces, on the current coordinates.
pub struct FaceGeometry<'a> {
    /// Slave shape functions and their ∂/∂ξ_α at the point.
    pub slave_shape: &'a [f64],
    pub slave_dshape: &'a [[f64; 2]],
    /// Master shape functions and their ∂/∂ζ_α at the master point.
    pub master_shape: &'a [f64],
    pub master_dshape: &'a [[f64; 2]],
    /// τ_sα = ∂x_s/∂ξ_α, the unit outward slave normal n_s, τ_mα = ∂x_m/∂ζ_α.
    pub tau_slave: [[f64; 3]; 2],
    pub normal: [f64; 3],
    pub tau_master: [[f64; 3]; 2],
    /// The gap g.
    pub gap: f64,
}

/// The DOFs of a point on faces with their derivatives (`dofs`: the slave
/// nodes' (DX, DY, DZ) then the master nodes', in the order of the shape
/// functions): code_aster's `dTs_du_ns`, `dNs_du` and `dPi_du` in 3D.
pub fn linearise_3d(p: &FaceGeometry, dofs: &[[Option<usize>; 3]]) -> Vec<FaceDof> {
    let ns = p.normal;
    let ts = p.tau_slave;
    let tm = p.tau_master;
    // The inverse metric of the slave tangents (`invMetricTensor`).
    let g = [
        [dot(ts[0], ts[0]), dot(ts[0], ts[1])],
        [dot(ts[1], ts[0]), dot(ts[1], ts[1])],
    ];
    let det_g = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    let ginv = if det_g > 0.0 {
        [
            [g[1][1] / det_g, -g[0][1] / det_g],
            [-g[1][0] / det_g, g[0][0] / det_g],
        ]
    } else {
        [[0.0; 2]; 2]
    };
    // (τ_m1, τ_m2, −n_s)⁻¹ by cofactors.
    let cols = [tm[0], tm[1], [-ns[0], -ns[1], -ns[2]]];
    let a = |i: usize, j: usize| cols[j][i];
    let det = a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1))
        - a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0))
        + a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
    let scale = crate::shape::norm(tm[0]) * crate::shape::norm(tm[1]);
    let inv = (det.abs() > f64::EPSILON * scale).then(|| {
        let mut m = [[0.0f64; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                let (r0, r1) = ((j + 1) % 3, (j + 2) % 3);
                let (c0, c1) = ((i + 1) % 3, (i + 2) % 3);
                m[i][j] = (a(r0, c0) * a(r1, c1) - a(r0, c1) * a(r1, c0)) / det;
            }
        }
        m
    });
    let nsl = p.slave_shape.len();
    let mut out = Vec::with_capacity(3 * dofs.len());
    for (node, ids) in dofs.iter().enumerate() {
        for (d, &dof) in ids.iter().enumerate() {
            let mut e = FaceDof {
                dof,
                jump: [0.0; 3],
                dns: [0.0; 3],
                dtest_m: [[0.0; 3]; 2],
                dzeta: [0.0; 2],
                dgap: 0.0,
            };
            if node < nsl {
                e.jump[d] = p.slave_shape[node];
                // dTs_du_ns: Dτ_sβ·n_s = ∂N_a/∂ξ_β n_s[d]; dNs_du.
                let c = [
                    p.slave_dshape[node][0] * ns[d],
                    p.slave_dshape[node][1] * ns[d],
                ];
                for al in 0..2 {
                    let k = -(ginv[al][0] * c[0] + ginv[al][1] * c[1]);
                    for i in 0..3 {
                        e.dns[i] += k * ts[al][i];
                    }
                }
            } else {
                let b = node - nsl;
                e.jump[d] = -p.master_shape[b];
                e.dtest_m[0][d] = p.master_dshape[b][0];
                e.dtest_m[1][d] = p.master_dshape[b][1];
            }
            // dPi_du: (τ_m1, τ_m2, −n_s) (Dζ₁, Dζ₂, Dg) = jump + g Dn_s.
            let r = [
                e.jump[0] + p.gap * e.dns[0],
                e.jump[1] + p.gap * e.dns[1],
                e.jump[2] + p.gap * e.dns[2],
            ];
            match inv {
                Some(m) => {
                    e.dzeta = [dot(m[0], r), dot(m[1], r)];
                    e.dgap = dot(m[2], r);
                }
                None => e.dgap = -dot(r, ns),
            }
            out.push(e);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::{interpolate, SurfaceKind};

    /// Gap and master parameter of a slave SEG2 point ξ cast along the
    /// slave normal onto a master SEG2, by formula (for the finite
    /// differences of the test).
    fn gap_and_zeta(x: &[[f64; 3]; 4], xi: f64) -> (f64, f64) {
        let s = interpolate(SurfaceKind::Seg2, &x[0..2], [xi, 0.0]);
        let t = s.tangents[0];
        let l = (t[0] * t[0] + t[1] * t[1]).sqrt();
        let n = [t[1] / l, -t[0] / l, 0.0];
        // x_a + (1 + ζ)/2 (x_b − x_a) = x_s + g n
        let e = [(x[3][0] - x[2][0]) / 2.0, (x[3][1] - x[2][1]) / 2.0];
        let m0 = [(x[3][0] + x[2][0]) / 2.0, (x[3][1] + x[2][1]) / 2.0];
        let r = [s.x[0] - m0[0], s.x[1] - m0[1]];
        // e ζ − n g = r
        let det = e[0] * (-n[1]) + n[0] * e[1];
        let zeta = (r[0] * (-n[1]) + n[0] * r[1]) / det;
        let g = (e[0] * r[1] - e[1] * r[0]) / det;
        (g, zeta)
    }

    #[test]
    fn derivatives_match_finite_differences() {
        // A tilted slave segment above a tilted master segment.
        let x = [
            [0.1, 0.3, 0.0],
            [1.2, 0.45, 0.0],
            [1.4, -0.1, 0.0],
            [-0.2, 0.05, 0.0],
        ];
        let xi = 0.3;
        let s = interpolate(SurfaceKind::Seg2, &x[0..2], [xi, 0.0]);
        let t = s.tangents[0];
        let l = (t[0] * t[0] + t[1] * t[1]).sqrt();
        let n = [t[1] / l, -t[0] / l, 0.0];
        let (g, zeta) = gap_and_zeta(&x, xi);
        let (nm, dm) = SurfaceKind::Seg2.eval([zeta, 0.0]);
        let (ns, ds) = SurfaceKind::Seg2.eval([xi, 0.0]);
        let m = interpolate(SurfaceKind::Seg2, &x[2..4], [zeta, 0.0]);
        let geo = PointGeometry {
            slave_shape: &ns,
            slave_dshape: &[ds[0][0], ds[1][0]],
            master_shape: &nm,
            master_dshape: &[dm[0][0], dm[1][0]],
            tau_slave: t,
            normal: n,
            tau_master: m.tangents[0],
            gap: g,
        };
        let ids: Vec<[Option<usize>; 2]> = (0..4).map(|k| [Some(2 * k), Some(2 * k + 1)]).collect();
        let lin = linearise(&geo, &ids);
        let h = 1e-7;
        for (k, e) in lin.iter().enumerate() {
            let mut xp = x;
            xp[k / 2][k % 2] += h;
            let mut xm = x;
            xm[k / 2][k % 2] -= h;
            let (gp, zp) = gap_and_zeta(&xp, xi);
            let (gm, zm) = gap_and_zeta(&xm, xi);
            let dg = (gp - gm) / (2.0 * h);
            let dz = (zp - zm) / (2.0 * h);
            assert!((dg - e.dgap).abs() < 1e-6, "dof {k}: Dg {} vs {dg}", e.dgap);
            assert!(
                (dz - e.dzeta).abs() < 1e-6,
                "dof {k}: Dζ {} vs {dz}",
                e.dzeta
            );
        }
    }
}

#[cfg(test)]
mod tests_3d {
    use super::*;
    use crate::mortar_pairing3d::face_normal;
    use crate::shape::{interpolate, project_along, sub, SurfaceKind};

    /// Gap, master parameters and normal of a slave point ξ cast along the
    /// slave normal onto the master face (for the finite differences).
    fn cast(
        sk: SurfaceKind,
        mk: SurfaceKind,
        x: &[[f64; 3]],
        xi: [f64; 2],
    ) -> (f64, [f64; 2], [f64; 3]) {
        let ns = sk.node_count();
        let n = face_normal(sk, &x[..ns], xi, 1.0).unwrap();
        let s = interpolate(sk, &x[..ns], xi);
        let m = project_along(mk, &x[ns..], s.x, n).unwrap();
        (-dot(sub(s.x, m.x), n), m.xi, n)
    }

    fn check(sk: SurfaceKind, mk: SurfaceKind, x: Vec<[f64; 3]>, xi: [f64; 2]) {
        let ns = sk.node_count();
        let (g, zeta, n) = cast(sk, mk, &x, xi);
        let s = interpolate(sk, &x[..ns], xi);
        let m = interpolate(mk, &x[ns..], zeta);
        let (sf, sd) = sk.eval(xi);
        let (mf, md) = mk.eval(zeta);
        let geo = FaceGeometry {
            slave_shape: &sf,
            slave_dshape: &sd,
            master_shape: &mf,
            master_dshape: &md,
            tau_slave: s.tangents,
            normal: n,
            tau_master: m.tangents,
            gap: g,
        };
        let ids: Vec<[Option<usize>; 3]> = (0..x.len())
            .map(|k| [Some(3 * k), Some(3 * k + 1), Some(3 * k + 2)])
            .collect();
        let lin = linearise_3d(&geo, &ids);
        let h = 1e-7;
        for (k, e) in lin.iter().enumerate() {
            let mut xp = x.clone();
            xp[k / 3][k % 3] += h;
            let mut xm = x.clone();
            xm[k / 3][k % 3] -= h;
            let (gp, zp, np) = cast(sk, mk, &xp, xi);
            let (gm, zm, nm) = cast(sk, mk, &xm, xi);
            let fd = |p: f64, m: f64| (p - m) / (2.0 * h);
            let close = |a: f64, b: f64| (a - b).abs() < 1e-6 * (1.0 + b.abs());
            assert!(
                close(e.dgap, fd(gp, gm)),
                "{sk:?} dof {k}: Dg {} vs {}",
                e.dgap,
                fd(gp, gm)
            );
            for a in 0..2 {
                assert!(
                    close(e.dzeta[a], fd(zp[a], zm[a])),
                    "{sk:?} dof {k}: Dζ{a} {} vs {}",
                    e.dzeta[a],
                    fd(zp[a], zm[a])
                );
            }
            for i in 0..3 {
                assert!(
                    close(e.dns[i], fd(np[i], nm[i])),
                    "{sk:?} dof {k}: Dn{i} {} vs {}",
                    e.dns[i],
                    fd(np[i], nm[i])
                );
            }
        }
    }

    /// A warped slave face above a tilted, curved master face: nodes of the
    /// reference face mapped by a smooth non-linear map, then moved apart.
    fn warp(kind: SurfaceKind, lift: f64, turn: f64) -> Vec<[f64; 3]> {
        kind.node_coords()
            .into_iter()
            .map(|[u, v]| {
                let (x, y) = (0.6 * u + 0.1 * v, 0.05 * u + 0.5 * v);
                [
                    x + 0.02 * u * v,
                    y,
                    lift + turn * x - 0.1 * y + 0.04 * u * u - 0.03 * v * v,
                ]
            })
            .collect()
    }

    #[test]
    fn face_derivatives_match_finite_differences() {
        use SurfaceKind::*;
        for (sk, mk) in [
            (Quad4, Quad4),
            (Tria3, Quad4),
            (Quad8, Tria6),
            (Tria6, Quad9),
            (Quad9, Quad8),
        ] {
            // The ray along the slave normal hits the master whichever
            // way the normal points.
            let mut x = warp(sk, 0.05, 0.2);
            let mut m = warp(mk, -0.02, -0.1);
            for p in &mut m {
                p[0] *= 1.8;
                p[1] *= 1.8;
            }
            x.extend(m);
            check(sk, mk, x, [0.1, 0.2]);
        }
    }
}
