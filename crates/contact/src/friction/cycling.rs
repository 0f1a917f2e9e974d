//! The contact side of code_aster's cycling treatment of the continuous
//! formulation (`mm_cycl_algo`, called by `mmmbca` at each contact status
//! update), the part that changes a converged answer: late in a step's
//! Newton iterations, a point whose contact status flips has its pressure
//! and gap clipped and is switched to penalised contact.
//!
//! Read in `bibfor/cont_algo/mm_cycl_algo.F90` (code_aster 17):
//!
//! - the treatment is on for `TYPE_ADAPT` 4, 5, 6, 7 and 11 (`cazocc`:
//!   `ADAPTATION='CYCLAGE'`, the default, is 4), and for a point whose
//!   master cell is the one of the previous status update (`CYCHIS(24)`
//!   against `CYCHIS(48)`);
//! - when its status differs from the previous update's and code_aster's
//!   Newton iteration count (`ds_contact%iteration_newton`: 0 after the
//!   prediction, the count of the step, not reset by the contact loops) is
//!   above `it_cycl_maxi + 3` = 9 (`nonlinDSContactInit`): a penetration
//!   above 1e-6 becomes 0, a tension above 1e-6 becomes −1e-15 (for the
//!   current values and those of the previous update); with
//!   `ALGO_RESO_CONT='NEWTON'` both statuses are taken again from the sign
//!   of the clipped pressure alone (`mmstac` with a zero coefficient); the
//!   point is switched to penalised contact (`CYCHIS(51)` = 4, read as
//!   `l_pena_cont` by `mmGetAlgo`) with the coefficient 1/`arete_min`
//!   (kept when the zone is already penalised) for the rest of the step
//!   (`mm_cycl_init` at the next one); the point counts as settled when
//!   the two statuses agree.
//!
//! The rest of `mm_cycl_algo` for these types (`mm_cycl_d2`/`d3`: the
//! friction history reaching the matrices as a 1e-4 blend; `d1`'s
//! alphas) changes the path, not the converged answer (docs/friction.md,
//! session 11), and is not reproduced.

/// code_aster's `it_cycl_maxi` (`nonlinDSContactInit`).
pub const IT_CYCL_MAXI: usize = 6;

/// Clip limits of `mm_cycl_algo`.
const CLIP: f64 = 1e-6;
const TENSION_CLIPPED: f64 = -1e-15;

/// One point's values at a status update, code_aster's signs: `pres` the
/// contact pressure (LAGS_C, negative in compression), `gap` the
/// penetration (positive interpenetrated).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointState {
    pub contact: bool,
    pub pres: f64,
    pub gap: f64,
}

/// What the treatment made of a status change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    /// The current and previous states after the clip (statuses recomputed
    /// with `ALGO_RESO_CONT='NEWTON'`).
    pub current: PointState,
    pub previous: PointState,
}

/// Whether the treatment applies at this update: `newton_iteration` is
/// code_aster's count (0 after the prediction).
pub fn applies(enabled: bool, same_master: bool, newton_iteration: usize, flipped: bool) -> bool {
    enabled && same_master && flipped && newton_iteration > IT_CYCL_MAXI + 3
}

fn clip(s: PointState, recompute: bool) -> PointState {
    let gap = if s.gap > CLIP { 0.0 } else { s.gap };
    let pres = if s.pres > CLIP {
        TENSION_CLIPPED
    } else {
        s.pres
    };
    let contact = if recompute { pres < 0.0 } else { s.contact };
    PointState { contact, pres, gap }
}

/// The projection of a point whose status flipped (see the module's doc);
/// `newton_contact`: `ALGO_RESO_CONT='NEWTON'`.
pub fn project(current: PointState, previous: PointState, newton_contact: bool) -> Projected {
    Projected {
        current: clip(current, newton_contact),
        previous: clip(previous, newton_contact),
    }
}

/// The penalty of a projected point: 1/`arete_min`, or the zone's own when
/// it is already penalised.
pub fn penalty(zone_penalised: Option<f64>, edge_min: f64) -> f64 {
    zone_penalised.unwrap_or(1.0 / edge_min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_late_flips_of_points_on_the_same_master_cell() {
        assert!(!applies(true, true, 9, true));
        assert!(applies(true, true, 10, true));
        assert!(!applies(true, false, 12, true));
        assert!(!applies(false, true, 12, true));
        assert!(!applies(true, true, 12, false));
    }

    #[test]
    fn a_released_point_in_tension_is_put_back_in_contact_with_newton_statuses() {
        let cur = PointState {
            contact: false,
            pres: 7.4e6,
            gap: -1e-3,
        };
        let prev = PointState {
            contact: true,
            pres: -2.0e6,
            gap: 2e-6,
        };
        let p = project(cur, prev, true);
        assert_eq!(p.current.pres, -1e-15);
        assert_eq!(p.current.gap, -1e-3);
        assert!(p.current.contact);
        assert!(p.previous.contact);
        assert_eq!(p.previous.gap, 0.0);
        // With the fixed-point contact loop the statuses stay.
        let q = project(cur, prev, false);
        assert!(!q.current.contact);
        assert!(q.previous.contact);
        assert_eq!(penalty(None, 0.5), 2.0);
        assert_eq!(penalty(Some(1e12), 0.5), 1e12);
    }
}
