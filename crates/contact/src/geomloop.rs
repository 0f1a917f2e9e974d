//! The geometric loop of a step (`REAC_GEOM`), as code_aster's fixed point
//! on the geometry does it (discrete contact: R5.03.50, the geometric
//! convergence test of the discrete methods; the continuous formulation's
//! `ALGO_RESO_GEOM='POINT_FIXE'` loop counts the same way):
//!
//! - each step starts with a pairing on the current geometry (pairing 1);
//! - after each converged solve the loop decides whether to pair again on
//!   the new geometry:
//!   - `SANS`: never (and the pairing of the very first step is kept);
//!   - `CONTROLE`: until `NB_ITER_GEOM` pairings were done in the step —
//!     exactly that many, no convergence test;
//!   - `AUTOMATIQUE`: the geometric residual is
//!     r = max‖uₖ − uₖ₋₁‖ / max‖uₖ₋₁ − u₀‖ (nodal translation norms; u₀ the
//!     start of the step, uₖ the solution after pairing k). After the first
//!     pairing there is no uₖ₋₁ and the loop always goes on, so there are at
//!     least two pairings; the loop stops when r < `RESI_GEOM` and fails
//!     when `ITER_GEOM_MAXI` pairings did not get there. A denominator below
//!     1e-6 × the largest one seen (a step that barely moves) counts as
//!     converged.

use crate::zone::GeomLoop;

/// What the loop wants after a solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GeomDecision {
    /// Pair on the current geometry (the first pairing of a step, or a
    /// geometric iteration).
    Pair,
    /// Keep the current pairing: the geometry of this step is settled.
    Keep,
    /// `AUTOMATIQUE` hit `ITER_GEOM_MAXI` with this residual.
    Diverged { pairings: usize, residual: f64 },
}

/// The state of the loop across the steps of one analysis.
#[derive(Clone, Debug)]
pub struct GeomLoopState {
    rule: GeomLoop,
    /// Time of the step being computed.
    step_time: Option<f64>,
    /// Pairings done in this step.
    pairings: usize,
    settled: bool,
    /// Nodal displacements at the start of the step (u₀) and after the
    /// previous pairing's solve (uₖ₋₁).
    start: Option<Vec<[f64; 3]>>,
    previous: Option<Vec<[f64; 3]>>,
    /// The largest denominator seen so far (code_aster's MAXD).
    largest: f64,
    /// Whether a pairing was ever done (SANS pairs once per analysis).
    ever_paired: bool,
    /// The last residual computed (`AUTOMATIQUE`), for reports.
    pub last_residual: Option<f64>,
}

impl GeomLoopState {
    pub fn new(rule: GeomLoop) -> Self {
        GeomLoopState {
            rule,
            step_time: None,
            pairings: 0,
            settled: false,
            start: None,
            previous: None,
            largest: 0.0,
            ever_paired: false,
            last_residual: None,
        }
    }

    /// Pairings done in the current step.
    pub fn pairings(&self) -> usize {
        self.pairings
    }

    /// Records the converged displacement of a step: the start of the next.
    pub fn step_converged(&mut self, u: Vec<[f64; 3]>) {
        self.start = Some(u);
    }

    /// Called whenever the solver asks for rows at time `time` with nodal
    /// displacements `u`: what to do with the pairing.
    pub fn decide(&mut self, time: f64, u: &[[f64; 3]]) -> GeomDecision {
        if self.step_time != Some(time) {
            self.step_time = Some(time);
            self.pairings = 0;
            self.settled = false;
            self.previous = None;
            if self.start.is_none() {
                // First step: the state the analysis starts from.
                self.start = Some(u.to_vec());
            }
        }
        if self.settled {
            return GeomDecision::Keep;
        }
        let decision = match self.rule {
            GeomLoop::Sans if self.ever_paired => GeomDecision::Keep,
            GeomLoop::Sans => GeomDecision::Pair,
            _ if self.pairings == 0 => GeomDecision::Pair,
            GeomLoop::Controle { nb_iter } => {
                if self.pairings >= nb_iter.max(1) {
                    GeomDecision::Keep
                } else {
                    GeomDecision::Pair
                }
            }
            GeomLoop::Automatique {
                iter_maxi,
                resi_geom,
            } => {
                let residual = self.residual(u);
                self.last_residual = Some(residual);
                if residual < resi_geom {
                    GeomDecision::Keep
                } else if self.pairings >= iter_maxi.max(1) {
                    GeomDecision::Diverged {
                        pairings: self.pairings,
                        residual,
                    }
                } else {
                    GeomDecision::Pair
                }
            }
        };
        match decision {
            GeomDecision::Pair => {
                self.pairings += 1;
                self.ever_paired = true;
                self.previous = Some(u.to_vec());
            }
            GeomDecision::Keep => self.settled = true,
            GeomDecision::Diverged { .. } => {}
        }
        decision
    }

    /// max‖uₖ − uₖ₋₁‖ / max‖uₖ₋₁ − u₀‖, with code_aster's conventions
    /// for a zero or negligible denominator.
    fn residual(&mut self, u: &[[f64; 3]]) -> f64 {
        // After the first pairing "previous" is the geometry it was done on;
        // the solve before it is the start of the step: the denominator is
        // max‖u₀ − u₀‖ = 0 and the loop goes on.
        let (Some(start), Some(previous)) = (&self.start, &self.previous) else {
            return f64::INFINITY;
        };
        if self.pairings <= 1 {
            // The change since the step start is not yet split into
            // "before" and "after" a re-pairing: no residual.
            return f64::INFINITY;
        }
        let change = max_norm(u, previous);
        if change == 0.0 {
            // Nothing moved since the last pairing: it cannot change.
            return 0.0;
        }
        let base = max_norm(previous, start);
        self.largest = self.largest.max(base);
        let rmin = 1e-6 * self.largest;
        if base <= rmin || base == 0.0 {
            if base == 0.0 {
                f64::INFINITY
            } else {
                0.0
            }
        } else {
            change / base
        }
    }
}

fn max_norm(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(v: f64) -> Vec<[f64; 3]> {
        vec![[0.0, v, 0.0], [0.0, 0.5 * v, 0.0]]
    }

    #[test]
    fn controle_pairs_exactly_nb_iter_geom_times_per_step() {
        let mut g = GeomLoopState::new(GeomLoop::Controle { nb_iter: 3 });
        for t in [1.0, 2.0] {
            // Whatever the displacements do, three pairings then keep.
            assert_eq!(g.decide(t, &at(t)), GeomDecision::Pair);
            assert_eq!(g.decide(t, &at(t + 0.5)), GeomDecision::Pair);
            assert_eq!(g.decide(t, &at(t + 0.5)), GeomDecision::Pair);
            assert_eq!(g.decide(t, &at(t + 0.7)), GeomDecision::Keep);
            assert_eq!(g.decide(t, &at(t + 0.9)), GeomDecision::Keep);
            assert_eq!(g.pairings(), 3);
            g.step_converged(at(t + 0.9));
        }
    }

    #[test]
    fn sans_pairs_once_per_analysis() {
        let mut g = GeomLoopState::new(GeomLoop::Sans);
        assert_eq!(g.decide(1.0, &at(0.0)), GeomDecision::Pair);
        assert_eq!(g.decide(1.0, &at(1.0)), GeomDecision::Keep);
        assert_eq!(g.decide(2.0, &at(1.0)), GeomDecision::Keep);
    }

    #[test]
    fn automatique_measures_the_change_against_the_step_displacement() {
        let rule = GeomLoop::Automatique {
            iter_maxi: 4,
            resi_geom: 0.01,
        };
        let mut g = GeomLoopState::new(rule);
        g.step_converged(at(0.0));
        assert_eq!(g.decide(1.0, &at(0.0)), GeomDecision::Pair);
        // First solve: no residual yet, always a second pairing.
        assert_eq!(g.decide(1.0, &at(1.0)), GeomDecision::Pair);
        // Second solve moved by 0.02 against a step displacement of 1: 2 %.
        assert_eq!(g.decide(1.0, &at(1.02)), GeomDecision::Pair);
        assert!((g.last_residual.unwrap() - 0.02).abs() < 1e-12);
        // Third: 0.005 against 1.02 → below 1 %: settled.
        assert_eq!(g.decide(1.0, &at(1.025)), GeomDecision::Keep);
        assert!((g.last_residual.unwrap() - 0.005 / 1.02).abs() < 1e-12);
        assert_eq!(g.pairings(), 3);
    }

    #[test]
    fn automatique_fails_after_iter_geom_maxi_pairings() {
        let rule = GeomLoop::Automatique {
            iter_maxi: 2,
            resi_geom: 0.01,
        };
        let mut g = GeomLoopState::new(rule);
        g.step_converged(at(0.0));
        assert_eq!(g.decide(1.0, &at(0.0)), GeomDecision::Pair);
        assert_eq!(g.decide(1.0, &at(1.0)), GeomDecision::Pair);
        match g.decide(1.0, &at(1.5)) {
            GeomDecision::Diverged { pairings, residual } => {
                assert_eq!(pairings, 2);
                assert!((residual - 0.5).abs() < 1e-12);
            }
            other => panic!("expected a divergence, got {other:?}"),
        }
    }

    #[test]
    fn a_step_that_does_not_move_is_settled() {
        let rule = GeomLoop::Automatique {
            iter_maxi: 3,
            resi_geom: 0.01,
        };
        let mut g = GeomLoopState::new(rule);
        g.step_converged(at(1.0));
        assert_eq!(g.decide(2.0, &at(1.0)), GeomDecision::Pair);
        assert_eq!(g.decide(2.0, &at(1.0)), GeomDecision::Pair);
        assert_eq!(g.decide(2.0, &at(1.0)), GeomDecision::Keep);
    }
}
