//! Friction of code_aster 17's penalised mortar contact
//! (`DEFI_CONT(ZONE=_F(ALGO_CONT='PENALISATION', FROTTEMENT='OUI'))`,
//! `ALGO_FROT='PENALISATION'`), in 2D on SEG2 and SEG3 cells and in 3D on
//! TRIA3 and QUAD4 faces (as the Lagrangian friction), as a fem force
//! source without unknowns of its own.
//!
//! As code_aster's (2025 main: `te0352`, `peelem`, `peVect` →
//! `peVect_cf_pr`, `laElemCont`, `contact_module` (`thresEval`,
//! `speedEval`), `contact_algebra_module` (`projRm`, `projBs`, `dPi_du`,
//! `dv_du`), `defi_cont_ops`: a penalised zone gets `VARIANTE='ROBUSTE'`):
//!
//! - Pairing, quadrature, normals, master points and gaps are those of the
//!   Lagrangian method; the point's quantities are
//!   [`crate::mortar_friction::point_quantities`] without multipliers: the
//!   element has none (`nb_lagr_c` = 0), so λ = 0 in `laElemCont`.
//! - **Penalty**: γ = Σ N_a COEF_CONT / h_F (`mortar_penalty::gamma`),
//!   also the friction coefficient (`gamma_f = gamma_c` with the ROBUSTE
//!   variant: `COEF_FROT`, absent from the catalog's penalised block, is
//!   not read).
//! - **Status**: γg ≤ 0 is contact (`CONTACT_INIT` at the first pairing as
//!   for the Lagrangian method); `projRm` = γg there.
//! - **Threshold** (`thresEval`): `COULOMB`: s = −μ γg; `TRESCA`: the
//!   given value; `ADHERENT`: `THRES_STICK`; `SANS`: none.
//! - **Friction force** (`projBs`): of −γv (v = −(x_s⁻ − x_m⁻ + g n⁻), the
//!   relative motion over the step, `speedEval`) onto the disc of radius s
//!   of the tangent line: −γ v_T while γ|v_T| ≤ s (stick), else s times its
//!   direction (slip). The force has no memory of earlier steps: a
//!   sticking point carries γ times the slip of the current step.
//! - **Residual** (`peVect_cf_pr`): −w (projRm n + P)·(v_s − v_m) at contact
//!   points only (`l_cont_qp`: with `TRESCA` too, unlike the Lagrangian
//!   friction, whose multiplier rows act everywhere).
//! - **Tangent**: the exact derivative of that residual for the pairing of
//!   the iterate (intersections and weights held): normal rotation, master
//!   point motion, slip and threshold derivatives, checked against central
//!   differences (unit test). code_aster's `peMatr_cf_pr` changes the path,
//!   not the converged state.
//! - **Convergence**: code_aster 17's — the residual of the displacement
//!   rows and `CONTACT/RESI_GEOM` (`mortar_lagrangian::GeometricCriterion`).

use aster_fem::{Contribution, FemError, ForceSource, State, Unknown};
use aster_mesh::Mesh;

use crate::error::ContactError;
use crate::mortar_friction::{
    axpy, comb, lin, point_quantities, FrictionLaw, Lin, PointGeometry, PointLaw,
};
use crate::mortar_lagrangian::{MortarLagrangian, MortarZoneDef};
use crate::mortar_penalty::{gamma, MortarPenalty};
use crate::source::current_positions;

/// The forces of one point on its local unknowns (slave displacements,
/// then the master's, `dim` per node), with their derivatives.
fn point_forces(g: &PointGeometry, p: &PointLaw) -> Result<Option<Vec<(f64, Lin)>>, FemError> {
    let Some(q) = point_quantities(g, p, None)? else {
        return Ok(None);
    };
    let d = g.dim;
    let (ns, nm) = (q.shs.len(), q.shm.len());
    let mut forces = vec![(0.0, lin(q.nloc)); d * (ns + nm)];
    if !q.status.contact {
        return Ok(Some(forces));
    }
    // f = projRm n + P and its derivative.
    let mut f = [0.0; 3];
    let mut df = [lin(q.nloc), lin(q.nloc), lin(q.nloc)];
    for c in 0..d {
        f[c] = q.proj_rm * q.n[c] + q.pb[c];
        let mut dc = comb(q.n[c], &q.dproj_rm, q.proj_rm, &q.dn[c]);
        axpy(&mut dc, 1.0, &q.dpb[c]);
        df[c] = dc;
    }
    // −w f·(v_s − v_m): −w N_a f on the slave, +w N_b(ξ_m) f on the master
    // (whose functions move with ξ_m: one parameter on a segment, two on a
    // face).
    for a in 0..ns {
        for c in 0..d {
            forces[d * a + c] = (
                -p.w * q.shs[a] * f[c],
                df[c].iter().map(|v| -p.w * q.shs[a] * v).collect(),
            );
        }
    }
    for b in 0..nm {
        for c in 0..d {
            let mut dc = comb(p.w * q.shm[b], &df[c], p.w * f[c] * q.dshm[b][0], &q.dxi[0]);
            if d == 3 {
                axpy(&mut dc, p.w * f[c] * q.dshm[b][1], &q.dxi[1]);
            }
            forces[d * ns + d * b + c] = (p.w * q.shm[b] * f[c], dc);
        }
    }
    Ok(Some(forces))
}

/// The penalised mortar contact with friction of a DEFI_CONT, as a fem
/// force source.
#[derive(Clone, Debug)]
pub struct MortarFrictionPenalty {
    /// The zones and their pairing (shared with the Lagrangian method).
    base: MortarLagrangian,
    laws: Vec<FrictionLaw>,
    /// The zones without friction beside them
    /// ([`crate::mortar_friction::split_zones`]): code_aster's
    /// `peVect_ct_pr`.
    frictionless: Option<MortarPenalty>,
    /// Positions at the start of the step (`coor_*_prev`).
    x_prev: Vec<[f64; 3]>,
    /// No pairing has been made yet (CONTACT_INIT applies).
    first_pairing: bool,
}

impl MortarFrictionPenalty {
    /// The contact of `zones` on `mesh` for a model of dimension `dim`: 2
    /// (segments; `axis`: AXIS weights) or 3 (TRIA3, TRIA6, QUAD4, QUAD8 and
    /// QUAD9 faces, as [`MortarLagrangian::new`]);
    /// each zone's `coef_cont` is its COEF_CONT and its
    /// [`MortarZoneDef::friction`] its law (`None`: a frictionless zone,
    /// [`MortarPenalty`]'s formulation, as code_aster's `peVect_ct_pr`).
    pub fn new(
        zones: &[MortarZoneDef],
        mesh: &Mesh,
        axis: bool,
        dim: usize,
    ) -> Result<Self, ContactError> {
        let (with, laws, without) = crate::mortar_friction::split_zones(zones);
        // On faces of any kind in 3D: quadratic ones (QUAD8, TRIA6, QUAD9)
        // as the frictionless pairing; the penalised friction slides there
        // (comm/dc3d_penalised_friction.comm on its mesh made quadratic).
        let base = MortarLagrangian::new(&with, mesh, axis, dim)?;
        let frictionless = if without.is_empty() {
            None
        } else {
            let geometry = MortarLagrangian::new(&without, mesh, axis, dim)?;
            crate::mortar_friction::disjoint_slaves(&base, &geometry)?;
            Some(MortarPenalty::new(&without, mesh, axis, dim)?)
        };
        Ok(MortarFrictionPenalty {
            base,
            laws,
            frictionless,
            x_prev: mesh.coords.clone(),
            first_pairing: true,
        })
    }

    /// code_aster 17's geometric criterion (MECA_NON_LINE's
    /// `CONTACT/RESI_GEOM`), as [`MortarLagrangian::set_resi_geom`].
    pub fn set_resi_geom(&mut self, resi_geom: f64) {
        self.base.set_resi_geom(resi_geom);
        if let Some(m) = self.frictionless.as_mut() {
            m.set_resi_geom(resi_geom);
        }
    }
}

impl ForceSource for MortarFrictionPenalty {
    fn name(&self) -> String {
        "DEFI_CONT (mortar penalised contact with friction)".into()
    }

    fn unknowns(&self) -> usize {
        0
    }

    fn begin_increment(&mut self, state: &State, own: &mut [f64]) -> Result<(), FemError> {
        self.x_prev = current_positions(state);
        self.base.resi_geom.begin(state);
        if let Some(m) = self.frictionless.as_mut() {
            m.begin_increment(state, own)?;
        }
        Ok(())
    }

    fn evaluate(&mut self, state: &State, own: &[f64]) -> Result<Contribution, FemError> {
        let x = current_positions(state);
        let x0 = &state.mesh.coords;
        let base = &self.base;
        let d = base.dim;
        let mut c = Contribution::default();
        for p in base.pairs(&x) {
            let z = &base.zones[p.zone];
            let s = &z.slave[p.slave];
            let m = &z.master[p.master];
            let sp = s.positions(&x);
            let mp = m.positions(&x);
            let s0 = s.positions(x0);
            let sprev = s.positions(&self.x_prev);
            let mprev = m.positions(&self.x_prev);
            let map: Vec<Option<usize>> = s
                .nodes
                .iter()
                .chain(&m.nodes)
                .flat_map(|node| (0..d).map(move |e| (*node, e)))
                .map(|(node, e)| crate::mortar_point::dof(state, node, e))
                .collect();
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
            for (xi, w) in crate::mortar_point::quadrature(s, m, &p, &s0, d, base.axis) {
                // The slave functions at the point, for γ = Σ N_a
                // COEF_CONT / h_F.
                let shape = s.kind.eval(xi).0;
                let law = PointLaw {
                    xi,
                    w,
                    gamma: gamma(&shape, z.coef, z.h[p.slave]),
                    law: self.laws[p.zone],
                    forced,
                };
                let Some(forces) = point_forces(&geometry, &law)? else {
                    continue;
                };
                for (i, (value, d)) in forces.iter().enumerate() {
                    let Some(row) = map[i] else {
                        continue;
                    };
                    if *value != 0.0 {
                        c.forces.push((row, *value));
                    }
                    for (j, v) in d.iter().enumerate() {
                        if let (Some(col), true) = (map[j], *v != 0.0) {
                            c.tangent.push((Unknown::Dof(row), Unknown::Dof(col), *v));
                        }
                    }
                }
            }
        }
        // The zones without friction: the frictionless formulation.
        if let Some(m) = self.frictionless.as_mut() {
            let other = m.evaluate(state, own)?;
            crate::mortar_friction::append_contribution(&mut c, other, 0);
        }
        Ok(c)
    }

    fn after_iteration(&mut self, state: &State, own: &mut [f64]) -> Result<bool, FemError> {
        // The first pairing (CONTACT_INIT) was that of this iteration;
        // code_aster 17's Newton tests the residual and RESI_GEOM.
        self.first_pairing = false;
        let accepted = self.base.resi_geom.accept(state);
        match self.frictionless.as_mut() {
            // The same criterion on the same state: both record it.
            Some(m) => Ok(m.after_iteration(state, own)? && accepted),
            None => Ok(accepted),
        }
    }

    fn converged(&mut self, state: &State, own: &[f64]) -> Result<(), FemError> {
        self.first_pairing = false;
        if let Some(m) = self.frictionless.as_mut() {
            m.converged(state, own)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::SurfaceKind;

    /// The tangent of a point is the derivative of its forces (central
    /// differences on every displacement), in stick and in slip, on a
    /// tilted slave SEG2 over a SEG3 master, for COULOMB, TRESCA and
    /// ADHERENT.
    #[test]
    fn point_tangent_is_the_derivative_of_the_forces() {
        let sp0 = vec![[0.0, 0.01, 0.0], [1.0, -0.03, 0.0]];
        let mp0 = vec![[1.2, -0.02, 0.0], [-0.1, 0.0, 0.0], [0.55, 0.01, 0.0]];
        let sprev = vec![[0.05, 0.02, 0.0], [1.05, 0.04, 0.0]];
        let mprev = vec![[1.2, -0.01, 0.0], [-0.1, 0.0, 0.0], [0.55, 0.0, 0.0]];
        for (law, sliding) in [
            (FrictionLaw::Coulomb(0.3), true),
            (FrictionLaw::Coulomb(50.0), false),
            (FrictionLaw::Tresca(0.05), true),
            (FrictionLaw::Stick, false),
            (FrictionLaw::Without, false),
        ] {
            let forces = |z: &[f64]| {
                let mut sp = sp0.clone();
                let mut mp = mp0.clone();
                for a in 0..2 {
                    for c in 0..2 {
                        sp[a][c] += z[2 * a + c];
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
                let q = point_quantities(&g, &p, None).unwrap().unwrap();
                (point_forces(&g, &p).unwrap().unwrap(), q.status)
            };
            let z0 = vec![0.0; 10];
            let (f0, status) = forces(&z0);
            assert!(status.contact, "{law:?}");
            assert_eq!(status.slip, sliding, "{law:?}");
            let h = 1e-7;
            for j in 0..10 {
                let (mut zp, mut zm) = (z0.clone(), z0.clone());
                zp[j] += h;
                zm[j] -= h;
                let (fp, fm) = (forces(&zp).0, forces(&zm).0);
                for (i, (row, d)) in f0.iter().enumerate() {
                    let fd = (fp[i].0 - fm[i].0) / (2.0 * h);
                    assert!(
                        (fd - d[j]).abs() <= 1e-6 * (1.0 + fd.abs()),
                        "{law:?}: row {i} ({row}) column {j}: {} against {fd}",
                        d[j]
                    );
                }
            }
        }
    }

    /// Sliding, the friction force is μ times the normal one and opposes
    /// the slip of the step; sticking, it is −γ times the tangential slip.
    #[test]
    fn sliding_force_is_mu_times_the_normal_one_and_sticking_is_gamma_times_the_slip() {
        // A flat slave at y = −0.01 (gap −0.01, n = −Y) over a flat master
        // at y = 0, moved by (dx, 0) over the step.
        let mp = vec![[-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        let gam = 100.0;
        for (mu, dx) in [(0.3, 0.05), (0.3, 1e-3), (0.3, -0.05)] {
            let sp = vec![[-1.0, -0.01, 0.0], [1.0, -0.01, 0.0]];
            let sprev = vec![[-1.0 - dx, -0.01, 0.0], [1.0 - dx, -0.01, 0.0]];
            let g = PointGeometry {
                dim: 2,
                s_kind: SurfaceKind::Seg2,
                sign: 1.0,
                sp: &sp,
                sprev: &sprev,
                m_kind: SurfaceKind::Seg2,
                mp: &mp,
                mprev: &mp,
            };
            let p = PointLaw {
                xi: [0.0, 0.0],
                w: 1.0,
                gamma: gam,
                law: FrictionLaw::Coulomb(mu),
                forced: None,
            };
            let q = point_quantities(&g, &p, None).unwrap().unwrap();
            assert!((q.n[1] + 1.0).abs() < 1e-15);
            let normal = -q.proj_rm; // γ |g| = 1
            assert!((normal - 1.0).abs() < 1e-12);
            let expected = if gam * dx.abs() > mu * normal {
                -mu * normal * dx.signum()
            } else {
                -gam * dx
            };
            assert!(
                (q.pb[0] - expected).abs() < 1e-12 && q.pb[1].abs() < 1e-15,
                "dx {dx}: {:?} against {expected}",
                q.pb
            );
        }
    }
}
