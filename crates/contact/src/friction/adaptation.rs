//! code_aster's adaptation of the friction coefficient `COEF_FROT` point by
//! point (`ADAPTATION='ADAPT_COEF'` or `'TOUT'` with Newton friction,
//! `TYPE_ADAPT` 1, 2, 5 or 6: `l_coef_adap` of `mm_cycl_algo`), at each
//! contact status update of the continuous formulation (`mmmbca`).
//!
//! Read in `bibfor/cont_algo`: `mm_cycl_d2` (detection), `mm_cycl_trait` →
//! `mm_cycl_t2` → `mm_cycl_adaf` (adaptation), `mm_cycl_prop`
//! (propagation), `mm_cycl_laugf`, `mm_cycl_zonf`, `iscycl`, `mm_cycl_init`:
//!
//! - each point keeps its own coefficient (`CYCHIS(6)`, the one its element
//!   and its stick/slip test use), reset to the zone's `COEF_FROT` at each
//!   step (`mm_cycl_init`), with the friction multiplier `Λ` (a vector in
//!   the tangent plane) and the tangential slip of the step `v` of its last
//!   update;
//! - detection (`d2`): while the point is in contact, its stick/slip
//!   statuses (`|Λ + ρ_f v| ≤ 1`: stick) are recorded; three successive
//!   ones alternating (stick-slip-stick or slip-stick-slip) flag the point;
//!   an open point's record is erased;
//! - adaptation (`t2`/`adaf`), for a flagged point whose augmented
//!   multiplier `|Λ + ρ_f v|` now lies in [0.95, 1] ("sticking"; else the
//!   previous update's, when it did): ρ_f is doubled until the point sticks
//!   clearly (`|Λ + ρ_f v| ≤ 0.95`), and kept when that needs 1e8 or more;
//!   in (1, 1.05] ("sliding") code_aster doubles it until it slides clearly
//!   and stops on an assertion when that happens (`ASSERT(.false.)`), so
//!   that branch is a refusal here;
//! - propagation (`prop`): the zone's largest coefficient of the step is
//!   given to every point in contact at its last update whose stick/slip
//!   zone (`mm_cycl_zonf`'s five around 0.95, 1 and 1.05) it leaves
//!   unchanged — or, failing that, whose zone the step's smallest
//!   coefficient leaves unchanged, which code_aster tests next and which
//!   holds whenever that smallest coefficient is the point's own.
//!
//! The adapted coefficient changes the path of Newton, not the converged
//! answer of the augmented Lagrangian: it is what lets a zone whose
//! `COEF_FROT` is far too small for its slips (ssnv128m: ρ_f = 1 against
//! slips of 1e-5, so `ρ_f v` does not weigh in the status) converge.

/// `tole_stick`, `tole_slide` of `mm_cycl_t2` / `mm_cycl_prop`.
const TOLE_STICK: f64 = 0.95;
const TOLE_SLIDE: f64 = 1.05;

/// `|Λ + ρ v|` (`mm_cycl_laugf`).
pub fn laugf(pres: [f64; 3], dist: [f64; 3], coef: f64) -> f64 {
    let mut s = 0.0;
    for c in 0..3 {
        let a = pres[c] + coef * dist[c];
        s += a * a;
    }
    s.sqrt()
}

/// The stick/slip zone of an augmented multiplier's norm (`mm_cycl_zonf`,
/// its tests in its order): −2 below 0.95, −1 in [0.95, 1], 0 in
/// (1, 1.05), +1 at 1.05 exactly (the `+1` test comes after the `0` one),
/// +2 above 1.05.
pub fn zonf(n: f64) -> i32 {
    if n < TOLE_STICK {
        -2
    } else if n <= 1.0 {
        -1
    } else if n < TOLE_SLIDE {
        0
    } else if n <= TOLE_SLIDE {
        1
    } else {
        2
    }
}

/// The friction history of one point in a step.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// The point's coefficient (`CYCHIS(6)`).
    pub coef: f64,
    /// Λ and the slip at the last update (`CYCHIS(7..12)`).
    pub pres: [f64; 3],
    pub dist: [f64; 3],
    /// The recorded stick (true) / slip statuses (`CYCLIS(2)`, `CYCNBR(2)`).
    record: [bool; 3],
    len: usize,
    /// `CYCETA(2)`: −1 erased, 0 nothing, 10 cycling detected.
    stat: i32,
}

impl History {
    /// The history at a step's start (`mm_cycl_init`).
    pub fn new(coef: f64) -> Self {
        History {
            coef,
            pres: [0.0; 3],
            dist: [0.0; 3],
            record: [false; 3],
            len: 0,
            stat: -1,
        }
    }

    /// Whether detection flagged the point at its last update.
    pub fn cycling(&self) -> bool {
        self.stat > 0
    }

    /// `mm_cycl_d2`: records the point's statuses at an update.
    fn detect(&mut self, in_contact: bool, sticking: bool) {
        if !in_contact {
            self.record = [false; 3];
            self.len = 0;
            self.stat = -1;
            return;
        }
        self.record[self.len] = sticking;
        self.len += 1;
        self.stat = 0;
        if self.len == 3 {
            let r = self.record;
            if r[0] == r[2] && r[0] != r[1] {
                self.stat = 10;
            }
            self.record = [r[1], r[2], false];
            self.len = 2;
        }
    }
}

/// code_aster stops on an assertion (`mm_cycl_adaf`, a point adapted as
/// sliding reaching a clear slip).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptAssertion;

/// `mm_cycl_adaf`: the adapted coefficient.
fn adaf(
    sticking: bool,
    coef_init: f64,
    pres: [f64; 3],
    dist: [f64; 3],
) -> Result<f64, AdaptAssertion> {
    // First pass: doubling. The second (halving) pass of code_aster starts
    // with its stop flag still raised: it tests `coef_init` only, already
    // tested, and ends with `coef_init`.
    let mut coef = coef_init;
    for _ in 0..30 {
        let n = laugf(pres, dist, coef);
        if sticking && n <= TOLE_STICK {
            return Ok(coef);
        }
        if !sticking && n >= TOLE_SLIDE {
            return Err(AdaptAssertion);
        }
        coef *= 2.0;
        if coef >= 1e8 || coef <= 1e-8 {
            return Ok(coef_init);
        }
    }
    // Thirty doublings without reaching 1e8 (a coefficient below 0.093):
    // code_aster keeps the last one.
    Ok(coef)
}

/// One status update of a point (`mm_cycl_d2` then `mm_cycl_trait`):
/// `in_contact` is the evaluated contact status, `pres` Λ and `dist` the
/// tangential slip of the step at the update. Returns the point's new
/// coefficient, stored in the history with `pres` and `dist`.
pub fn update(
    h: &mut History,
    in_contact: bool,
    pres: [f64; 3],
    dist: [f64; 3],
) -> Result<f64, AdaptAssertion> {
    let coef_prev = h.coef;
    let sticking = laugf(pres, dist, coef_prev) <= 1.0;
    h.detect(in_contact, sticking);
    let mut coef = coef_prev;
    if h.stat > 0 {
        // mm_cycl_t2
        let zc = zonf(laugf(pres, dist, coef_prev));
        let zp = zonf(laugf(h.pres, h.dist, coef_prev));
        let adapt = match (zc, zp) {
            (-1, _) => Some((true, pres, dist)),
            (1, _) => Some((false, pres, dist)),
            (_, -1) => Some((true, h.pres, h.dist)),
            (_, 1) => Some((false, h.pres, h.dist)),
            _ => None,
        };
        if let Some((stick, p, d)) = adapt {
            coef = adaf(stick, coef_prev, p, d)?;
        }
    }
    h.coef = coef;
    h.pres = pres;
    h.dist = dist;
    Ok(coef)
}

/// The zone's smallest and largest coefficient of the step
/// (`CYCCOE(5/6)`, reset to ±1e12 at each step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    pub min: f64,
    pub max: f64,
}

impl Default for Range {
    fn default() -> Self {
        Range {
            min: 1e12,
            max: -1e12,
        }
    }
}

impl Range {
    pub fn record(&mut self, coef: f64) {
        if coef >= self.max {
            self.max = coef;
        }
        if coef <= self.min {
            self.min = coef;
        }
    }
}

/// `mm_cycl_prop` for one point of a frictional zone: the zone's largest
/// coefficient when it leaves the point's stick/slip zone unchanged (or,
/// failing that, when the smallest one does).
pub fn propagate(h: &mut History, range: Range) {
    if h.stat == -1 {
        return;
    }
    let zone_of = |c: f64| zonf(laugf(h.pres, h.dist, c));
    let z = zone_of(h.coef);
    let agrees = |zp: i32| -> bool {
        if z == zp {
            return true;
        }
        match z {
            -2 | 2 => false,
            -1 => zp == -2,
            0 => true,
            _ => zp == 2,
        }
    };
    if agrees(zone_of(range.max)) || agrees(zone_of(range.min)) {
        h.coef = range.max.max(h.coef);
    }
}

/// Penalised friction beside augmented contact (`ALGO_FROT='PENALISATION'`,
/// `ALGO_CONT='STANDARD'`): the coefficient code_aster gives a point at a
/// status update (`mm_cycl_algo`, its last block, whatever `TYPE_ADAPT`):
/// a point in contact (its status after the update) whose tangential slip
/// of the step exceeds 1e-6 × `GLIS_MAXI` takes
/// 10 × `arete_max` / `arete_min` / `GLIS_MAXI`; any other keeps `coef`.
/// `glis_maxi` is `mmmbca`'s (the zone's, 0.1 × `arete_min` when ≤ r8prem).
pub fn pena_frot_update(
    coef: f64,
    in_contact: bool,
    slip: [f64; 3],
    glis_maxi: f64,
    edge_min: f64,
    edge_max: f64,
) -> f64 {
    let glis_maxi = if glis_maxi <= f64::EPSILON {
        0.1 * edge_min
    } else {
        glis_maxi
    };
    let norm = (slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]).sqrt();
    if in_contact && norm > 1e-6 * glis_maxi {
        10.0 * edge_max / edge_min / glis_maxi
    } else {
        coef
    }
}

/// code_aster's `estimated_coefficient` when no zone adapts its
/// coefficients from the matrix (`nonlinDSContactCreate`; `contMatrModi`
/// replaces it only with `EXIS_ADAP`, `TYPE_ADAPT` 1, 2, 3, 5, 6 or 7).
pub const ESTIMATED_COEFFICIENT: f64 = 100.0;

/// The coefficient every point of a penalised-friction zone beside
/// augmented contact takes when code_aster builds its contact field at
/// Newton iteration 1 (`mmchml_c`: 1e-3 × `estimated_coefficient` ×
/// `arete_min` / `GLIS_MAXI`, the zone's value unguarded). The field built
/// then still carries the point's previous coefficient: the new one is
/// read from the next status update on.
pub fn pena_frot_first_iteration(estimated: f64, edge_min: f64, glis_maxi: f64) -> f64 {
    1e-3 * estimated * edge_min / glis_maxi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zones_around_the_stick_slip_limit() {
        assert_eq!(zonf(0.5), -2);
        assert_eq!(zonf(0.97), -1);
        assert_eq!(zonf(1.0), -1);
        assert_eq!(zonf(1.02), 0);
        assert_eq!(zonf(1.05), 1);
        assert_eq!(zonf(1.2), 2);
    }

    #[test]
    fn three_alternating_statuses_in_contact_flag_the_point() {
        let mut h = History::new(1.0);
        h.detect(true, true);
        h.detect(true, false);
        assert!(!h.cycling());
        h.detect(true, true);
        assert!(h.cycling());
        h.detect(true, true);
        assert!(!h.cycling());
        // Opening erases the record.
        h.detect(true, false);
        h.detect(false, false);
        h.detect(true, true);
        h.detect(true, false);
        assert!(!h.cycling());
    }

    #[test]
    fn a_sticking_point_near_the_limit_doubles_its_coefficient_until_it_sticks_clearly() {
        // Λ = 0.97 along x, slip −1e-3 along x: |Λ + ρ v| ≤ 0.95 for ρ ≥ 20.
        let pres = [0.97, 0.0, 0.0];
        let dist = [-1e-3, 0.0, 0.0];
        assert_eq!(adaf(true, 1.0, pres, dist), Ok(32.0));
        // A slip along Λ never sticks: the coefficient is kept.
        assert_eq!(adaf(true, 1.0, pres, [1e-3, 0.0, 0.0]), Ok(1.0));
        // Sliding reaching 1.05: code_aster's assertion.
        assert_eq!(
            adaf(false, 1.0, [1.01, 0.0, 0.0], [1e-3, 0.0, 0.0]),
            Err(AdaptAssertion)
        );
    }

    #[test]
    fn a_cycling_point_is_adapted_and_its_coefficient_propagated() {
        let mut h = History::new(1.0);
        let dist = [-1e-3, 0.0, 0.0];
        assert_eq!(update(&mut h, true, [0.5, 0.0, 0.0], dist), Ok(1.0));
        assert_eq!(update(&mut h, true, [1.5, 0.0, 0.0], dist), Ok(1.0));
        // Stick, slip, stick: flagged, Λ + ρ v = 0.97 − 1e-3 ρ.
        assert_eq!(update(&mut h, true, [0.97, 0.0, 0.0], dist), Ok(32.0));
        let mut range = Range::default();
        range.record(1.0);
        range.record(32.0);
        // A clearly sticking neighbour stays clearly sticking with 32.
        let mut other = History::new(1.0);
        update(&mut other, true, [0.1, 0.0, 0.0], [0.0; 3]).unwrap();
        propagate(&mut other, range);
        assert_eq!(other.coef, 32.0);
        // A clearly sliding one would stick with 32, but its zone with the
        // smallest coefficient (its own) is its zone: code_aster gives it
        // the largest all the same.
        let mut sliding = History::new(1.0);
        update(&mut sliding, true, [1.2, 0.0, 0.0], [-1e-2, 0.0, 0.0]).unwrap();
        propagate(&mut sliding, range);
        assert_eq!(sliding.coef, 32.0);
        // A point never in contact in the step is left alone.
        let mut open = History::new(1.0);
        propagate(&mut open, range);
        assert_eq!(open.coef, 1.0);
    }
    #[test]
    fn a_slipping_point_in_contact_takes_the_edge_ratio_over_glis_maxi() {
        // Edges 0.01 to 0.04, GLIS_MAXI 1e-4: 10 × 4 / 1e-4 = 4e5.
        let (amin, amax, gm) = (0.01, 0.04, 1e-4);
        let points = [
            // (in contact, slip) → coefficient after the update
            (true, [2e-10, 0.0, 0.0], 4e5),
            (true, [0.0, -3e-5, 0.0], 4e5),
            // Slip of exactly 1e-6 × GLIS_MAXI: kept.
            (true, [1e-10, 0.0, 0.0], 1e7),
            (false, [1e-3, 0.0, 0.0], 1e7),
        ];
        for (contact, slip, want) in points {
            let c = pena_frot_update(1e7, contact, slip, gm, amin, amax);
            assert!((c - want).abs() <= 1e-9 * want, "{contact} {slip:?}: {c}");
        }
        // GLIS_MAXI zero: 0.1 × arete_min (1e-3) instead, threshold 1e-9.
        let c = pena_frot_update(1e7, true, [2e-9, 0.0, 0.0], 0.0, amin, amax);
        assert!((c - 4e4).abs() < 1e-6);
        assert_eq!(
            pena_frot_update(1e7, true, [5e-10, 0.0, 0.0], 0.0, amin, amax),
            1e7
        );
        // At Newton iteration 1: 1e-3 × 100 × 0.01 / 1e-4 = 10.
        assert!((pena_frot_first_iteration(ESTIMATED_COEFFICIENT, amin, gm) - 10.0).abs() < 1e-12);
    }
}
