//! code_aster 17's penalised mortar contact of `DEFI_CONT`
//! (`ALGO_CONT='PENALISATION'`, `MECA_NON_LINE`), frictionless, in 2D on
//! SEG2 and SEG3 cells and in 3D on TRIA3, TRIA6, QUAD4, QUAD8 and QUAD9
//! faces, as a fem force source without unknowns of its own (no `LAGS_C`).
//!
//! In 3D (`new(…, 3)`) the pairing, the polygons' quadrature, the
//! normals and master points are those of the 3D Lagrangian method
//! (`mortar_lagrangian::pairs_3d_of`, `mortar_point::points_3d`). In 2D and
//! 3D alike the tangent is `peMatr_ct_pr`'s, the exact derivative of the
//! residual for the iterate's pairing (intersections and weights held):
//! −w γ Dg (n_s·jump) − w [γg]₋ jump·Dn_s + w [γg]₋ n_s·(∂v_m/∂ζ_α) Dζ_α,
//! the slave normal turning and the master point sliding
//! (`mortar_tangent::linearise` on segments, `linearise_3d` on faces).
//!
//! As code_aster's (2025 main: `te0352`, `peelem`, `peVect_ct_pr`,
//! `laElemCont`, `laQuantities`, `ContactComputation::contactCoefficient`):
//!
//! - Pairing, quadrature, normals, master points and gaps are those of the
//!   Lagrangian method (`mortar_lagrangian::pairs_of`, `mortar_point`).
//! - **At a point**: the contact element has no multiplier (`peelem`:
//!   `nb_lagr_c` = 0), so λ = 0 in `laElemCont` and γ = Σ N_a COEF_CONT / h_F,
//!   interpolated with the slave's displacement functions (COEF_CONT is
//!   given at every slave node), h_F the slave cell's initial diameter.
//!   COEF_CONT is a stiffness per unit area times a length: the penalty is
//!   γ = COEF_CONT/h_F. Active (H = 1) when γg ≤ 0; `CONTACT_INIT` at the
//!   first pairing as for the Lagrangian method ('OUI': H = 1 and the
//!   force γg whatever its sign; 'NON': H = 0).
//! - **Residual** (`peVect_ct_pr`): −w [γg]₋ n_s·(v_s − v_m) at active
//!   points. Slave nodes of no paired cell get nothing (POI1 elements carry
//!   no term without multipliers).
//! - The converged state has the interpenetration −g = p h_F / COEF_CONT
//!   under a contact pressure p.
//! - **Newton**: code_aster tests the residual (pairing before every
//!   iteration, no status criterion) and, with MECA_NON_LINE's
//!   `CONTACT/RESI_GEOM`, the displacement increment (`ResiGeom`, as for
//!   the Lagrangian method), with code_aster's tangent above: the same
//!   Newton path, quadratic once the pairing settles.
//! - **Line search** (MECA_NON_LINE's `RECH_LINEAIRE`,
//!   `ForceSource::evaluate_on_pairing`): the trial residuals on the pairs,
//!   normals and master points of the iteration's start, the gaps on the
//!   trial positions (`mortar_point::on_current`).

use aster_fem::{Contribution, FemError, ForceSource, State, Unknown};
use aster_mesh::Mesh;

use crate::error::ContactError;
use crate::mortar_lagrangian::{
    pairs_3d_of, pairs_of, MZone, MortarLagrangian, MortarZoneDef, Pair, ResiGeom,
};
use crate::mortar_point::{on_current, points, points_3d, MortarPoint, PairDofs};
use crate::shape::dot;
use crate::source::current_positions;

/// The status and force of a point: `x` = λ + γg (here γg); code_aster's
/// `Heaviside(−x)` and `projRm(x)`, or the status `forced` on the zone
/// ([`MZone::forced`]: `CONTACT_INIT` at the first pairing, always active
/// when bilateral; `laElemCont`, `niElemCont`).
pub(crate) fn status(x: f64, forced: Option<bool>) -> (bool, f64) {
    match forced {
        Some(false) => (false, 0.0),
        Some(true) => (true, x),
        None => {
            if -x >= 0.0 {
                (true, x)
            } else {
                (false, 0.0)
            }
        }
    }
}

/// γ at a point: COEF_CONT interpolated with the slave's displacement
/// functions (`evalPoly(nb_node_slav, shape_func_sl, coef_cont)`) over h_F.
pub(crate) fn gamma(shape: &[f64], coef: f64, hf: f64) -> f64 {
    shape.iter().map(|n| n * coef).sum::<f64>() / hf
}

/// The penalised mortar contact of a DEFI_CONT, as a fem force source.
#[derive(Clone, Debug)]
pub struct MortarPenalty {
    zones: Vec<MZone>,
    axis: bool,
    /// No pairing has been made yet (CONTACT_INIT applies).
    first_pairing: bool,
    /// The largest interpenetration −g of an active point at the last
    /// evaluation.
    penetration: f64,
    /// Space dimension of the model (2: segments; 3: faces).
    dim: usize,
    /// MECA_NON_LINE's `CONTACT/RESI_GEOM` ([`MortarPenalty::set_resi_geom`]).
    resi_geom: ResiGeom,
}

impl MortarPenalty {
    /// The contact of `zones` on `mesh` for a model of dimension `dim`: 2
    /// (segments; `axis`: AXIS weights) or 3 (TRIA3, TRIA6, QUAD4, QUAD8
    /// and QUAD9 faces, as [`MortarLagrangian::new`]); each zone's
    /// `coef_cont` is its COEF_CONT.
    pub fn new(
        zones: &[MortarZoneDef],
        mesh: &Mesh,
        axis: bool,
        dim: usize,
    ) -> Result<Self, ContactError> {
        let geometry = MortarLagrangian::new(zones, mesh, axis, dim)?;
        Ok(MortarPenalty {
            zones: geometry.zones,
            axis,
            first_pairing: true,
            penetration: 0.0,
            dim: geometry.dim,
            resi_geom: ResiGeom::new(mesh),
        })
    }

    /// code_aster 17's geometric criterion, applied whatever `ALGO_CONT`
    /// (MECA_NON_LINE's `CONTACT/RESI_GEOM`, as
    /// [`MortarLagrangian::set_resi_geom`]).
    pub fn set_resi_geom(&mut self, resi_geom: f64) {
        self.resi_geom.tol = Some(resi_geom);
    }

    /// The largest interpenetration of an active point at the last
    /// evaluation.
    pub fn penetration(&self) -> f64 {
        self.penetration
    }
}

impl MortarPenalty {
    /// The quadrature points of every pair of the zones, paired on the
    /// positions `xp` (segments in 2D, faces in 3D).
    fn paired_points(
        &self,
        xp: &[[f64; 3]],
        x0: &[[f64; 3]],
    ) -> Result<Vec<(Pair, Vec<MortarPoint>)>, FemError> {
        let pairs = if self.dim == 3 {
            pairs_3d_of(&self.zones, xp)
        } else {
            pairs_of(&self.zones, xp)
        };
        let mut out = Vec::with_capacity(pairs.len());
        for p in pairs {
            let z = &self.zones[p.zone];
            let (s, m) = (&z.slave[p.slave], &z.master[p.master]);
            let (sp, mp, s0) = (s.positions(xp), m.positions(xp), s.positions(x0));
            let points = if self.dim == 3 {
                points_3d(s, m, &p.poly, &sp, &mp, &s0)?
            } else {
                points(s, m, p.xi, &sp, &mp, &s0, self.axis)?
            };
            out.push((p, points));
        }
        Ok(out)
    }

    /// The residual and tangent at `state` (`peVect_ct_pr`, `peMatr_ct_pr`
    /// on segments and faces), paired on `pairing`'s positions when given
    /// (a trial of MECA_NON_LINE's line search: the pairs, slave normals
    /// and master points of the iteration's start,
    /// `mortar_point::on_current`), else on the current ones.
    fn contribution(
        &mut self,
        pairing: Option<&State>,
        state: &State,
    ) -> Result<Contribution, FemError> {
        let x = current_positions(state);
        let xp = pairing.map(current_positions);
        let xp: &[[f64; 3]] = xp.as_deref().unwrap_or(&x);
        let mut c = Contribution::default();
        let mut penetration = 0.0f64;
        for (p, pair_points) in self.paired_points(xp, &state.mesh.coords)? {
            let z = &self.zones[p.zone];
            let (s, m) = (&z.slave[p.slave], &z.master[p.master]);
            let (sc, mc) = (s.positions(&x), m.positions(&x));
            let hf = z.h[p.slave];
            let dofs = PairDofs::of(state, s, m, self.dim);
            for pt in pair_points {
                let pt = match pairing {
                    Some(_) => on_current(pt, s, m, &sc, &mc),
                    None => pt,
                };
                let g = gamma(&pt.initial.shape, z.coef, hf);
                let (h, proj) = status(g * pt.gap, z.forced(self.first_pairing));
                if !h {
                    continue;
                }
                penetration = penetration.max(-pt.gap);
                let w = pt.w;
                let ns = pt.ns;
                let lin = pt.linearise(s, m, &dofs);
                // −w [γg]₋ n_s·(v_s − v_m); its derivative (peMatr_ct_pr):
                // −w γ Dg (n·jump) − w [γg]₋ jump·Dn_s + w [γg]₋ n·∂v_m/∂ζ_α Dζ_α.
                for e in &lin {
                    let Some(i) = e.dof else { continue };
                    let fi = dot(ns, e.jump);
                    c.forces.push((i, -w * proj * fi));
                    let fm = [dot(ns, e.dtest_m[0]), dot(ns, e.dtest_m[1])];
                    for e2 in &lin {
                        let Some(j) = e2.dof else { continue };
                        let v = -w * g * fi * e2.dgap - w * proj * dot(e.jump, e2.dns)
                            + w * proj * (fm[0] * e2.dzeta[0] + fm[1] * e2.dzeta[1]);
                        if v != 0.0 {
                            c.tangent.push((Unknown::Dof(i), Unknown::Dof(j), v));
                        }
                    }
                }
            }
        }
        if pairing.is_none() {
            self.penetration = penetration;
        }
        Ok(c)
    }
}

impl ForceSource for MortarPenalty {
    fn name(&self) -> String {
        "DEFI_CONT (mortar penalised contact)".into()
    }

    fn unknowns(&self) -> usize {
        0
    }

    fn begin_increment(&mut self, state: &State, _own: &mut [f64]) -> Result<(), FemError> {
        self.resi_geom.begin(state);
        Ok(())
    }

    fn evaluate(&mut self, state: &State, _own: &[f64]) -> Result<Contribution, FemError> {
        self.contribution(None, state)
    }

    fn evaluate_on_pairing(
        &mut self,
        pairing: &State,
        state: &State,
        _own: &[f64],
    ) -> Result<Contribution, FemError> {
        self.contribution(Some(pairing), state)
    }

    fn after_iteration(&mut self, state: &State, _own: &mut [f64]) -> Result<bool, FemError> {
        // The first pairing (CONTACT_INIT) was that of this iteration;
        // code_aster's Newton tests the residual (no status criterion) and,
        // with RESI_GEOM, the increment.
        self.first_pairing = false;
        Ok(self.resi_geom.accept(state))
    }

    fn converged(&mut self, _state: &State, _own: &[f64]) -> Result<(), FemError> {
        self.first_pairing = false;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mortar_lagrangian::InitialState;

    #[test]
    fn status_follows_code_aster_projection_and_contact_init() {
        let st = |x: f64, first: bool, init: InitialState| status(x, init.forced(first));
        assert_eq!(st(-2.0, false, InitialState::Interpenetrated), (true, -2.0));
        assert_eq!(st(0.0, false, InitialState::Interpenetrated), (true, 0.0));
        assert_eq!(st(1.0, false, InitialState::Interpenetrated), (false, 0.0));
        assert_eq!(st(1.0, true, InitialState::Yes), (true, 1.0));
        assert_eq!(st(-1.0, true, InitialState::No), (false, 0.0));
        assert_eq!(st(1.0, false, InitialState::Yes), (false, 0.0));
        // TYPE_CONT='BILATERAL': active whatever the sign, projRm = x.
        assert_eq!(status(1.0, Some(true)), (true, 1.0));
    }
}
