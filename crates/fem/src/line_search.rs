//! Line search along the Newton direction (`RECH_LINEAIRE`), as code_aster.
//!
//! After a Newton correction Δ (not after the prediction), the iterate
//! becomes u + ρ Δ with ρ a root of the projected residual
//!
//! ```text
//! f(ρ) = Δ · R(u + ρ Δ),   R = f_int + f_src − f_ext
//! ```
//!
//! (code_aster's `nmrecz`; MECA_NON_LINE's `compute_f`). The caller
//! evaluates f; this module only chooses the ρ's:
//!
//! - `CORDE` (`nmrech`; `SecantLineSearch` of code_aster 17): the secant
//!   through the last two points, from (0, f(0)) and ρ = 1, each new ρ
//!   brought into [RHO_MIN, RHO_MAX] and out of [−RHO_EXCL, RHO_EXCL]
//!   (`zbinte`); when the last two values of f are equal, RHO_MAX or
//!   RHO_MIN by the sign of the slope;
//! - `MIXTE` (`nmrebo` → `zbiter`, `zbborn`, `zbroot`, `zbproj`): the
//!   bracket [ρ₋, ρ₊] of the last points where f < 0 and f ≥ 0; ρ tripled
//!   until f changes sign, then the secant of the last two points (the
//!   middle of the bracket when the last point is not better than the one
//!   before, or the secant leaves the bracket or is too flat).
//!
//! In both, the ρ of the smallest |f| seen is kept (the first ρ = 1
//! included); the search stops when that |f| is below RESI_LINE_RELA ×
//! |f(0)|, after ITER_LINE_MAXI + 1 evaluations, or (MIXTE) when the secant
//! cannot be formed; an evaluation that fails (a behaviour that cannot be
//! integrated) ends the search on the best ρ so far, or fails the
//! iteration when it is the first one.
//!
//! code_aster's two implementations differ in details reproduced through
//! [`Rule`]: STAT_NON_LINE's Fortran keeps a new best ρ when |f| is
//! strictly smaller and takes the secant when |f − f_m| > ε (2.2e-16),
//! MECA_NON_LINE's Python on |f| ≤ |f_best| and |f − f_m| > 2.2e-308.
//! Both, when f(0) > 0 (Δ is not a descent direction), search along −Δ
//! and then apply +|ρ| (MIXTE; CORDE searches along Δ whatever the sign):
//! that case is refused ([`LineSearchError::Ascent`]).

/// `RECH_LINEAIRE/METHODE` (PILOTAGE needs the continuation method).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineSearchMethod {
    /// `CORDE`: the secant method (the default).
    Corde,
    /// `MIXTE`: bracketing, then secant.
    Mixte,
}

/// Which of code_aster's two implementations the search follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Rule {
    /// STAT_NON_LINE, DYNA_NON_LINE (`bibfor/nonlinear/nmrelp.F90`).
    #[default]
    Fortran,
    /// MECA_NON_LINE (`code_aster/Solvers/IterationSolver/line_search.py`).
    Python,
}

/// `RECH_LINEAIRE` keywords (code_aster 17's defaults in [`Default`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineSearch {
    pub method: LineSearchMethod,
    /// `RESI_LINE_RELA` (0.1).
    pub resi_line_rela: f64,
    /// `ITER_LINE_MAXI` (3): at most ITER_LINE_MAXI + 1 evaluations.
    pub iter_line_maxi: usize,
    /// `RHO_MIN` (0.01).
    pub rho_min: f64,
    /// `RHO_MAX` (10).
    pub rho_max: f64,
    /// `RHO_EXCL` (0.009).
    pub rho_excl: f64,
    pub rule: Rule,
}

impl Default for LineSearch {
    fn default() -> Self {
        LineSearch {
            method: LineSearchMethod::Corde,
            resi_line_rela: 0.1,
            iter_line_maxi: 3,
            rho_min: 0.01,
            rho_max: 10.0,
            rho_excl: 0.009,
            rule: Rule::Fortran,
        }
    }
}

/// The chosen step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineSearchOutcome {
    /// ρ: the iterate is u + ρ Δ.
    pub rho: f64,
    /// |f(ρ)|.
    pub f: f64,
    /// The evaluations after ρ = 1 (code_aster's `line_sear_iter`: the
    /// index of the last evaluation).
    pub iterations: usize,
    /// Whether |f(ρ)| ≤ RESI_LINE_RELA |f(0)| was reached.
    pub converged: bool,
    /// The last ρ evaluated (the caller's state is there).
    pub last: f64,
}

impl LineSearchOutcome {
    /// The `ASTER_FEM_TRACE` line of a search from f(0) = `f0`.
    pub fn trace(&self, f0: f64) -> String {
        format!(
            "line search: f(0) {f0:.6e}, rho {} |f| {:.6e} after {} iterations{}",
            self.rho,
            self.f,
            self.iterations,
            if self.converged {
                ""
            } else {
                " (not converged)"
            }
        )
    }
}

/// Why a search cannot be reproduced, or the first evaluation's failure.
#[derive(Debug)]
pub enum LineSearchError<E> {
    /// f(0) > 0 with MIXTE: code_aster searches along −Δ and applies +|ρ|
    /// (its fields then belong to another iterate than its displacement).
    Ascent { f0: f64 },
    /// The evaluation at ρ = 1 failed.
    Evaluation(E),
}

/// `zbinte`: ρ into [RHO_MIN, RHO_MAX], out of [−RHO_EXCL, RHO_EXCL].
pub fn bounded(p: &LineSearch, rho: f64) -> f64 {
    let mut r = rho;
    if rho < p.rho_min {
        r = p.rho_min;
    }
    if rho > p.rho_max {
        r = p.rho_max;
    }
    if rho < 0.0 && rho >= -p.rho_excl {
        r = -p.rho_excl;
    }
    if (0.0..=p.rho_excl).contains(&rho) {
        r = p.rho_excl;
    }
    r
}

impl LineSearch {
    fn better(&self, f: f64, fopt: f64) -> bool {
        match self.rule {
            Rule::Fortran => f.abs() < fopt,
            Rule::Python => f.abs() <= fopt,
        }
    }

    fn distinct(&self, a: f64, b: f64) -> bool {
        match self.rule {
            Rule::Fortran => (a - b).abs() > f64::EPSILON,
            Rule::Python => (a - b).abs() > f64::MIN_POSITIVE,
        }
    }

    /// The search from f(0) = `f0`, `eval(ρ)` returning f(ρ) (and leaving
    /// the caller's state at u + ρ Δ).
    pub fn search<E>(
        &self,
        f0: f64,
        mut eval: impl FnMut(f64) -> Result<f64, E>,
    ) -> Result<LineSearchOutcome, LineSearchError<E>> {
        let fcvg = (self.resi_line_rela * f0).abs();
        let mut fopt = f64::MAX;
        let mut rhoopt = 1.0;
        let mut rho = 1.0;
        let mut rhom = 0.0;
        let mut fm = f0;
        let mut last = rho;
        // MIXTE's bracket (`zbborn`): ρ₋ (f < 0), ρ₊ (f ≥ 0) once seen.
        let mut rhoneg = 0.0;
        let mut rhopos: Option<f64> = None;
        if self.method == LineSearchMethod::Mixte && f0 > 0.0 {
            return Err(LineSearchError::Ascent { f0 });
        }
        let done = |rho, f, iterations, converged, last| LineSearchOutcome {
            rho,
            f,
            iterations,
            converged,
            last,
        };
        for iter in 0..=self.iter_line_maxi {
            let f = match eval(rho) {
                Ok(f) => f,
                Err(e) if iter == 0 => return Err(LineSearchError::Evaluation(e)),
                Err(_) => return Ok(done(rhoopt, fopt, iter, false, last)),
            };
            last = rho;
            if self.better(f, fopt) {
                rhoopt = rho;
                fopt = f.abs();
                if f.abs() < fcvg {
                    return Ok(done(rhoopt, fopt, iter, true, last));
                }
            }
            let previous = rho;
            match self.method {
                LineSearchMethod::Corde => {
                    rho = if self.distinct(f, fm) {
                        bounded(self, (f * rhom - fm * rho) / (f - fm))
                    } else if f * (rho - rhom) * (f - fm) <= 0.0 {
                        self.rho_max
                    } else {
                        self.rho_min
                    };
                }
                LineSearchMethod::Mixte => {
                    if f < 0.0 {
                        rhoneg = rho;
                    } else {
                        rhopos = Some(rho);
                    }
                    let mut next = match rhopos {
                        None => 3.0 * rho,
                        Some(pos) => {
                            if f.abs() >= fm.abs() {
                                0.5 * (rhoneg + pos)
                            } else if !self.distinct(rho, rhom) {
                                return Ok(done(rhoopt, fopt, iter, false, last));
                            } else {
                                let p1 = (f - fm) / (rho - rhom);
                                let p0 = fm - p1 * rhom;
                                if p1.abs() <= fm.abs() / (pos + rhom) {
                                    0.5 * (rhoneg + pos)
                                } else {
                                    -p0 / p1
                                }
                            }
                        }
                    };
                    // `zbproj`.
                    if next < rhoneg {
                        match rhopos {
                            Some(pos) => next = 0.5 * (rhoneg + pos),
                            None => return Ok(done(rhoopt, fopt, iter, false, last)),
                        }
                    }
                    if let Some(pos) = rhopos {
                        if next > pos {
                            next = 0.5 * (rhoneg + pos);
                        }
                    }
                    rho = bounded(self, next);
                }
            }
            rhom = previous;
            fm = f;
        }
        Ok(done(rhoopt, fopt, self.iter_line_maxi, false, last))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corde(iter: usize) -> LineSearch {
        LineSearch {
            iter_line_maxi: iter,
            resi_line_rela: 1e-3,
            ..LineSearch::default()
        }
    }

    /// f(ρ) = ρ² − 4 from f(0) = −4: the secant iterates by hand.
    /// ρ₁ = 1, f = −3: secant through (0, −4), (1, −3) → ρ = 4 (f = 12);
    /// through (1, −3), (4, 12) → ρ = 1 + 3·3/15 = 1.6 (f = −1.44);
    /// through (4, 12), (1.6, −1.44) → ρ = 1.6 + 1.44·2.4/13.44
    /// = 1.857142857… (f = −0.551…).
    #[test]
    fn corde_iterates_are_the_hand_computed_secants() {
        let mut seen = Vec::new();
        let out = corde(3)
            .search::<()>(-4.0, |r| {
                seen.push(r);
                Ok(r * r - 4.0)
            })
            .unwrap();
        let expected = [1.0, 4.0, 1.6, 1.6 + 1.44 * 2.4 / 13.44];
        assert_eq!(seen.len(), expected.len());
        for (a, b) in seen.iter().zip(expected) {
            assert!((a - b).abs() < 1e-14, "{seen:?}");
        }
        // Not converged (|f| > 4e-3 after 4 evaluations): the best ρ kept.
        let r4 = expected[3];
        assert!(!out.converged);
        assert_eq!(out.iterations, 3);
        assert!((out.rho - r4).abs() < 1e-14);
        assert!((out.f - (r4 * r4 - 4.0).abs()).abs() < 1e-14);
    }

    /// RHO_MAX caps the secant, then it converges on a linear f in one
    /// more evaluation.
    #[test]
    fn corde_bounds_and_converges_on_a_linear_function() {
        let p = LineSearch {
            rho_max: 2.0,
            ..corde(5)
        };
        let mut seen = Vec::new();
        // f(ρ) = ρ − 3, f(0) = −3: secant from (0,−3), (1,−2) → 3, capped
        // at 2 (f = −1); through (1,−2), (2,−1) → 3 again, capped: 2 again,
        // f equal: RHO_MAX or RHO_MIN by the slope's sign (f·Δρ·Δf = 0 → max).
        let out = p
            .search::<()>(-3.0, |r| {
                seen.push(r);
                Ok(r - 3.0)
            })
            .unwrap();
        assert_eq!(seen, vec![1.0, 2.0, 2.0, 2.0, 2.0, 2.0]);
        assert_eq!(out.rho, 2.0);
        assert!(!out.converged);
        // Without the cap the secant is exact: ρ = 3 on the second evaluation.
        let out = corde(5).search::<()>(-3.0, |r| Ok(r - 3.0)).unwrap();
        assert!(out.converged);
        assert_eq!((out.rho, out.iterations), (3.0, 1));
    }

    /// ρ = 1 good enough: one evaluation, ρ = 1.
    #[test]
    fn a_full_newton_step_within_resi_line_rela_is_kept() {
        let out = LineSearch::default()
            .search::<()>(-1.0, |r| Ok(0.05 * r))
            .unwrap();
        assert_eq!((out.rho, out.iterations, out.converged), (1.0, 0, true));
    }

    /// RHO_EXCL: a secant landing at 0.005 is moved to 0.009.
    #[test]
    fn rho_excl_moves_a_step_near_zero() {
        let p = LineSearch::default();
        assert_eq!(bounded(&p, 0.005), 0.009);
        // code_aster's tests run in turn on the value given: below RHO_MIN,
        // then inside the exclusion, which wins.
        assert_eq!(bounded(&p, -0.005), -0.009);
        assert_eq!(bounded(&p, 50.0), 10.0);
        assert_eq!(bounded(&p, 0.5), 0.5);
    }

    /// MIXTE on f(ρ) = ρ − 5: ρ tripled (1, 3, 9: f changes sign); at 9
    /// |f| = 4 is not below the previous 2: the middle of [3, 9], 6
    /// (f = 1); then the secant of (9, 4) and (6, 1) is exact (ρ = 5).
    #[test]
    fn mixte_brackets_then_secant() {
        let p = LineSearch {
            method: LineSearchMethod::Mixte,
            iter_line_maxi: 5,
            resi_line_rela: 1e-6,
            ..LineSearch::default()
        };
        let mut seen = Vec::new();
        let out = p
            .search::<()>(-5.0, |r| {
                seen.push(r);
                Ok(r - 5.0)
            })
            .unwrap();
        assert_eq!(seen, [1.0, 3.0, 9.0, 6.0, 5.0]);
        assert!(out.converged);
        assert!((out.rho - 5.0).abs() < 1e-14);
        // An ascent direction is refused.
        assert!(matches!(
            p.search::<()>(1.0, Ok),
            Err(LineSearchError::Ascent { .. })
        ));
    }

    /// A failed evaluation keeps the best ρ, or fails at ρ = 1.
    #[test]
    fn a_failed_evaluation_ends_on_the_best_rho() {
        let p = corde(3);
        let out = p
            .search(-4.0, |r| if r > 2.0 { Err("no") } else { Ok(r * r - 4.0) })
            .unwrap();
        assert_eq!((out.rho, out.iterations), (1.0, 1));
        assert!(matches!(
            p.search(-4.0, |_| Err::<f64, _>("no")),
            Err(LineSearchError::Evaluation("no"))
        ));
    }
}
