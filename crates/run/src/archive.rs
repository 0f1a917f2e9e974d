//! `ARCHIVAGE` of STAT_NON_LINE, DYNA_NON_LINE and MECA_NON_LINE: which
//! computed steps are stored, as code_aster's `dinuar`/`nmcrpo`: the
//! initial state always, the last computed step always, and the others
//! when their instant is in `LIST_INST`/`INST` (within `PRECISION`,
//! `CRITERE`) or their index in the time list is a multiple of `PAS_ARCH`;
//! every step when none is given. The stored steps are numbered
//! consecutively (NUME_ORDRE), as code_aster does. `CHAM_EXCLU` (fields
//! not stored) changes nothing here: every field stays available.

use aster_fem::NonLinearResult;

/// What `ARCHIVAGE` keeps.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Archive {
    /// `LIST_INST`/`INST`, with the precision and whether it is absolute.
    pub instants: Option<(Vec<f64>, f64, bool)>,
    /// `PAS_ARCH`.
    pub every: Option<usize>,
}

impl Archive {
    /// Whether the step of index `index` (in the time list) at `time` is
    /// stored (the first and last are, whatever this says).
    pub fn keeps(&self, index: usize, time: f64) -> bool {
        if let Some((list, precision, absolute)) = &self.instants {
            return list.iter().any(|&t| {
                let d = (t - time).abs();
                if *absolute {
                    d <= *precision
                } else {
                    d <= precision * t.abs() || d == 0.0
                }
            });
        }
        match self.every {
            Some(k) if k > 1 => index.is_multiple_of(k),
            _ => true,
        }
    }

    /// Drops the steps not archived from a result whose first step is the
    /// initial state, and renumbers the others.
    pub fn apply(&self, raw: &mut NonLinearResult) {
        if self.instants.is_none() && self.every.is_none_or(|k| k <= 1) {
            return;
        }
        let n = raw.steps.len();
        let Some(first) = raw.steps.first().map(|s| s.nume_ordre) else {
            return;
        };
        let mut index = 0usize;
        raw.steps.retain(|s| {
            let i = index;
            index += 1;
            i == 0 || i + 1 == n || self.keeps(i, s.time)
        });
        for (k, s) in raw.steps.iter_mut().enumerate() {
            s.nume_ordre = first + k;
        }
    }
}
