//! TEST_RESU / TEST_TABLE checks: which comparisons an occurrence asks for,
//! their verdict, and their text as code_aster prints it in its `.resu`
//! file (a header naming what is tested, then one line per comparison:
//! verdict, reference kind, legend, expected value, computed value, error,
//! tolerance; relative errors in percent).
//!
//! code_aster 17 semantics:
//! - `VALE_CALC` is the non-regression value, checked with `TOLE_MACHINE`
//!   (default 1e-6), relative unless `CRITERE='ABSOLU'`;
//! - `VALE_REFE` (with `REFERENCE`) is checked with `PRECISION` (default 1e-3);
//! - when `VALE_CALC` is zero (below 1e-16) the check needs
//!   `ORDRE_GRANDEUR`: without it the check is skipped (`SKIP`) whatever
//!   `CRITERE`; with it an absolute check has the tolerance
//!   TOLE_MACHINE × ORDRE_GRANDEUR and a relative one passes only on an
//!   exact zero (code_aster's `tresu_ordgrd` and `TestResult.showResult`);
//!   `ORDRE_GRANDEUR` is not read for a non-zero `VALE_CALC`;
//! - of several expected values, the one compared is the last that is
//!   closer to the computed value than the first (code_aster's
//!   `tresu_print` loop, which never lowers its running minimum);
//! - legacy `VALE=` (code_aster ≤ 11) is checked with `PRECISION` (default
//!   1e-3) against `REFERENCE` (default `NON_REGRESSION`).

use crate::pyfmt::{c_exp_lower_width, py_repr};
use aster_eval::Keywords;

/// Below this magnitude a `VALE_CALC` counts as zero (code_aster's bound).
const ZERO_VALUE: f64 = 1e-16;

/// One comparison of a computed value with an expected one.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// `NON_REGRESSION`, `ANALYTIQUE`, `AUTRE_ASTER`, `SOURCE_EXTERNE`…
    pub kind: String,
    pub legend: String,
    /// The expected values (the closest one is used).
    pub expected: Vec<f64>,
    pub tolerance: f64,
    pub relative: bool,
    /// Scale of an absolute test (`ORDRE_GRANDEUR`), 1 otherwise.
    pub order: f64,
    /// The value is zero and no order of magnitude was given.
    pub skip: bool,
    /// `VALE_ABS='OUI'`: compare absolute values (of the computed and the
    /// expected values, as code_aster's `tresu_print`).
    pub absolute_value: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    Ok,
    Nook,
    Skip,
}

/// The evaluated comparison, ready to print.
#[derive(Clone, Debug, PartialEq)]
pub struct Judged {
    pub verdict: Verdict,
    pub expected: f64,
    pub computed: f64,
    /// |expected − computed|, in percent of |expected| when relative.
    pub error: f64,
    /// The tolerance as printed (percent when relative).
    pub tolerance: f64,
}

impl Comparison {
    pub fn judge(&self, computed: f64) -> Judged {
        let computed = if self.absolute_value {
            computed.abs()
        } else {
            computed
        };
        // VALE_ABS='OUI': code_aster's tresu_print takes the absolute value
        // of the reference too.
        let values: Vec<f64> = self
            .expected
            .iter()
            .map(|v| if self.absolute_value { v.abs() } else { *v })
            .collect();
        // code_aster's `tresu_print`: the last value closer than the first.
        let expected = match values.split_first() {
            Some((first, rest)) => {
                let d0 = (first - computed).abs();
                rest.iter()
                    .rev()
                    .find(|v| (*v - computed).abs() < d0)
                    .copied()
                    .unwrap_or(*first)
            }
            None => f64::NAN,
        };
        if self.skip {
            return Judged {
                verdict: Verdict::Skip,
                expected,
                computed,
                error: f64::NAN,
                tolerance: f64::NAN,
            };
        }
        let diff = (expected - computed).abs();
        let (ok, error, tolerance) = if self.relative {
            let ok = diff <= (self.tolerance * expected).abs();
            let error = if expected != 0.0 {
                diff / expected.abs() * 100.0
            } else if ok {
                0.0
            } else {
                999.999999
            };
            (ok, error, self.tolerance * 100.0)
        } else {
            let tol = (self.tolerance * self.order).abs();
            (diff <= tol, diff, tol)
        };
        // A NaN computed value is never OK (the comparisons above are false).
        Judged {
            verdict: if ok { Verdict::Ok } else { Verdict::Nook },
            expected,
            computed,
            error,
            tolerance,
        }
    }
}

fn first_real(kw: &Keywords, name: &str) -> Option<f64> {
    kw.f64(name)
}

fn reals(kw: &Keywords, name: &str) -> Vec<f64> {
    kw.simple(name).iter().filter_map(|s| s.as_f64()).collect()
}

/// The comparisons one TEST_RESU/TEST_TABLE occurrence asks for, in print
/// order (non-regression first, then the reference).
pub fn comparisons(kw: &Keywords) -> Result<Vec<Comparison>, String> {
    let criteria: Vec<&str> = kw
        .simple("CRITERE")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let relative = criteria.first().map(|c| *c != "ABSOLU").unwrap_or(true);
    let legend = kw.str("LEGENDE").unwrap_or("XXXX").to_string();
    let reference = kw.str("REFERENCE").map(str::to_string);
    let absolute_value = kw.str("VALE_ABS") == Some("OUI");
    let mut out = Vec::new();

    let calc = {
        let mut v = reals(kw, "VALE_CALC");
        if v.is_empty() {
            v = reals(kw, "VALE_CALC_I");
        }
        v
    };
    let refe = {
        let mut v = reals(kw, "VALE_REFE");
        if v.is_empty() {
            v = reals(kw, "VALE_REFE_I");
        }
        v
    };
    if !kw.simple("VALE_CALC_C").is_empty() || !kw.simple("VALE_REFE_C").is_empty() {
        return Err("not supported yet: complex values (VALE_CALC_C/VALE_REFE_C)".into());
    }
    if !calc.is_empty() {
        let tole = first_real(kw, "TOLE_MACHINE").unwrap_or(1e-6);
        let zero = calc[0].abs() < ZERO_VALUE;
        let order = first_real(kw, "ORDRE_GRANDEUR");
        // code_aster's `tresu_ordgrd`: ORDRE_GRANDEUR is read only when
        // VALE_CALC is zero, and without it the check is skipped whatever
        // CRITERE; the criterion itself is kept (a relative test of a zero
        // value then passes only on an exact zero, as `showResult`).
        let (order, skip) = match (zero, order) {
            (true, Some(o)) => (o, false),
            (true, None) => (1.0, true),
            (false, _) => (1.0, false),
        };
        // Without a reference value, the line carries the REFERENCE kind.
        let kind = if refe.is_empty() {
            reference.clone().unwrap_or_else(|| "NON_REGRESSION".into())
        } else {
            "NON_REGRESSION".into()
        };
        out.push(Comparison {
            kind,
            legend: legend.clone(),
            expected: calc,
            tolerance: tole,
            relative,
            order,
            skip,
            absolute_value,
        });
    }
    if !refe.is_empty() {
        out.push(Comparison {
            kind: reference.clone().unwrap_or_else(|| "NON_DEFINI".into()),
            legend: legend.clone(),
            expected: refe,
            tolerance: first_real(kw, "PRECISION").unwrap_or(1e-3),
            relative,
            order: 1.0,
            skip: false,
            absolute_value,
        });
    }
    // Legacy `VALE=` (code_aster ≤ 11).
    let legacy = {
        let mut v = reals(kw, "VALE");
        if v.is_empty() {
            v = reals(kw, "VALE_I");
        }
        v
    };
    if !legacy.is_empty() {
        out.push(Comparison {
            kind: reference.unwrap_or_else(|| "NON_REGRESSION".into()),
            legend,
            expected: legacy,
            tolerance: first_real(kw, "PRECISION").unwrap_or(1e-3),
            relative,
            order: 1.0,
            skip: false,
            absolute_value,
        });
    }
    if out.is_empty() {
        return Err("no expected value: give VALE_CALC (and VALE_REFE with REFERENCE)".into());
    }
    Ok(out)
}

/// The two header lines: names of what is tested, and their values, in
/// columns of 16 characters.
pub fn header(fields: &[(&str, String)]) -> String {
    let mut names = String::new();
    let mut values = String::new();
    for (i, (name, value)) in fields.iter().enumerate() {
        if i == 0 {
            names.push_str(&format!(" ---- {name:<16}"));
            values.push_str(&format!("      {value:<16}"));
        } else {
            names.push_str(&format!(" {name:<16}"));
            values.push_str(&format!(" {value:<16}"));
        }
    }
    format!("{}\n{}\n", names.trim_end(), values.trim_end())
}

fn row(width: usize, cells: [&str; 7]) -> String {
    let line = format!(
        "{:<4}  {:<16} {:<16} {:<width$} {:<width$} {:<16} {:<16}",
        cells[0], cells[1], cells[2], cells[3], cells[4], cells[5], cells[6]
    );
    line.trim_end().to_string()
}

/// The printed lines of one comparison (the column labels first when
/// `labels`).
pub fn render(c: &Comparison, j: &Judged, labels: bool) -> String {
    let mut sref = py_repr(j.expected);
    let mut scalc = py_repr(j.computed);
    let width = 16.max(sref.len()).max(scalc.len()) + 2;
    let mut serr = py_repr(j.error);
    if serr.len() > 15 {
        serr = c_exp_lower_width(j.error);
    }
    let mut stol = py_repr(j.tolerance);
    if c.relative {
        serr.push('%');
        stol.push('%');
    }
    let mut legend = c.legend.as_str();
    let diag = match j.verdict {
        Verdict::Ok => " OK ",
        Verdict::Nook => "NOOK",
        Verdict::Skip => {
            legend = "-";
            sref = "-".into();
            scalc = "-".into();
            serr = "-".into();
            stol = "-".into();
            "SKIP"
        }
    };
    let mut out = String::new();
    if c.order != 1.0 {
        out.push_str(&format!(
            "{}\n",
            format!(
                "{:<4}  {:<16} {}",
                " ",
                "ORDRE DE GRANDEUR :",
                py_repr(c.order)
            )
            .trim_end()
        ));
    }
    if labels {
        out.push_str(&row(
            width,
            [
                " ",
                "REFERENCE",
                "LEGENDE",
                "VALE_REFE",
                "VALE_CALC",
                "ERREUR",
                "TOLE",
            ],
        ));
        out.push('\n');
    }
    out.push_str(&row(
        width,
        [diag, &c.kind, legend, &sref, &scalc, &serr, &stol],
    ));
    out.push('\n');
    out
}

/// Counts of verdicts over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    pub ok: usize,
    pub nook: usize,
    pub skipped: usize,
}

impl Tally {
    pub fn add(&mut self, v: Verdict) {
        match v {
            Verdict::Ok => self.ok += 1,
            Verdict::Nook => self.nook += 1,
            Verdict::Skip => self.skipped += 1,
        }
    }

    /// The final line of `aster run`.
    pub fn summary(&self) -> String {
        format!("TEST_RESU: {} OK, {} NOOK", self.ok, self.nook)
    }
}

/// Runs the comparisons of one occurrence against a computed value:
/// the printed block and the verdicts.
pub fn check_block(
    fields: &[(&str, String)],
    comparisons: &[Comparison],
    computed: f64,
) -> (String, Vec<Verdict>) {
    let mut text = header(fields);
    let mut verdicts = Vec::new();
    for (i, c) in comparisons.iter().enumerate() {
        let j = c.judge(computed);
        text.push_str(&render(c, &j, i == 0));
        verdicts.push(j.verdict);
    }
    text.push('\n');
    (text, verdicts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_eval::{Keyword, KwValue, Scalar};
    use aster_syntax::Span;

    fn kw(entries: Vec<(&str, Scalar)>) -> Keywords {
        Keywords {
            entries: entries
                .into_iter()
                .map(|(n, v)| Keyword {
                    name: n.to_string(),
                    value: KwValue::Simple(vec![v]),
                    span: Span::default(),
                    defaulted: false,
                })
                .collect(),
        }
    }

    fn fields() -> Vec<(&'static str, String)> {
        vec![
            ("RESULTAT", "RESU".into()),
            ("NUME_ORDRE", "20".into()),
            ("NOM_CHAM", "DEPL".into()),
            ("NOM_CMP", "DX".into()),
            ("GROUP_NO", "A".into()),
        ]
    }

    #[test]
    fn calc_and_refe_relative() {
        let k = kw(vec![
            ("VALE_CALC", Scalar::Real(-4.285714318)),
            ("VALE_REFE", Scalar::Real(-4.28571)),
            ("REFERENCE", Scalar::Str("AUTRE_ASTER".into())),
        ]);
        let cs = comparisons(&k).unwrap();
        assert_eq!(cs.len(), 2);
        assert_eq!(cs[0].kind, "NON_REGRESSION");
        assert_eq!(cs[0].tolerance, 1e-6);
        assert_eq!(cs[1].tolerance, 1e-3);
        let (text, v) = check_block(&fields(), &cs, -4.285714285714286);
        assert_eq!(v, vec![Verdict::Ok, Verdict::Ok]);
        insta::assert_snapshot!(text);
    }

    #[test]
    fn absolute_near_zero() {
        let k = kw(vec![
            ("VALE_CALC", Scalar::Real(-1.55431223e-15)),
            ("VALE_REFE", Scalar::Real(0.0)),
            ("REFERENCE", Scalar::Str("ANALYTIQUE".into())),
            ("CRITERE", Scalar::Str("ABSOLU".into())),
        ]);
        let cs = comparisons(&k).unwrap();
        let (text, v) = check_block(&fields(), &cs, 0.0);
        assert_eq!(v, vec![Verdict::Ok, Verdict::Ok]);
        insta::assert_snapshot!(text);
    }

    #[test]
    fn nook_when_out_of_tolerance() {
        let k = kw(vec![
            ("VALE_CALC", Scalar::Real(2.1978e10)),
            ("TOLE_MACHINE", Scalar::Real(1e-3)),
        ]);
        let cs = comparisons(&k).unwrap();
        assert_eq!(cs[0].judge(2.1978021987206e10).verdict, Verdict::Ok);
        assert_eq!(cs[0].judge(2.2e10).verdict, Verdict::Nook);
        assert_eq!(cs[0].judge(f64::NAN).verdict, Verdict::Nook);
        let (text, _) = check_block(&fields(), &cs, 2.2e10);
        insta::assert_snapshot!(text);
    }

    #[test]
    fn zero_relative_needs_order_of_magnitude() {
        let k = kw(vec![("VALE_CALC", Scalar::Real(0.0))]);
        assert!(comparisons(&k).unwrap()[0].skip);
        let k = kw(vec![
            ("VALE_CALC", Scalar::Real(0.0)),
            ("ORDRE_GRANDEUR", Scalar::Real(1e3)),
        ]);
        let c = &comparisons(&k).unwrap()[0];
        // The criterion stays relative: only an exact zero passes
        // (code_aster's TestResult.showResult, tolerance × 0).
        assert!(c.relative);
        assert_eq!(c.judge(0.0).verdict, Verdict::Ok);
        assert_eq!(c.judge(5e-4).verdict, Verdict::Nook);
        let k = kw(vec![
            ("VALE_CALC", Scalar::Real(0.0)),
            ("ORDRE_GRANDEUR", Scalar::Real(1e3)),
            ("CRITERE", Scalar::Str("ABSOLU".into())),
        ]);
        let cs = comparisons(&k).unwrap();
        assert_eq!(cs[0].judge(5e-4).verdict, Verdict::Ok);
        assert_eq!(cs[0].judge(2e-3).verdict, Verdict::Nook);
        let (text, _) = check_block(&fields(), &cs, 5e-4);
        insta::assert_snapshot!(text);
    }

    #[test]
    fn zero_absolute_without_order_of_magnitude_is_skipped() {
        // code_aster's tresu_ordgrd: whatever CRITERE (zzzz285a).
        let k = kw(vec![
            ("VALE_CALC", Scalar::Real(0.0)),
            ("CRITERE", Scalar::Str("ABSOLU".into())),
        ]);
        let cs = comparisons(&k).unwrap();
        assert!(cs[0].skip);
        assert_eq!(cs[0].judge(6.3e-3).verdict, Verdict::Skip);
        let (text, _) = check_block(&fields(), &cs, 6.3e-3);
        insta::assert_snapshot!(text);
        // ORDRE_GRANDEUR is read only for a zero VALE_CALC: a non-zero one
        // is checked at TOLE_MACHINE itself.
        let k = kw(vec![
            ("VALE_CALC", Scalar::Real(1.0)),
            ("CRITERE", Scalar::Str("ABSOLU".into())),
            ("ORDRE_GRANDEUR", Scalar::Real(1e3)),
        ]);
        let c = &comparisons(&k).unwrap()[0];
        assert_eq!(c.order, 1.0);
        assert_eq!(c.judge(1.0 + 5e-7).verdict, Verdict::Ok);
        assert_eq!(c.judge(1.0 + 5e-4).verdict, Verdict::Nook);
    }

    #[test]
    fn of_several_values_the_last_closer_than_the_first_is_compared() {
        // code_aster's tresu_print never lowers its running minimum: with
        // 1, 2, 3 expected and 2.9 computed, 3 (the last value closer than
        // 1) is compared; with 2.4 computed, 3 again although 2 is closer.
        let mut k = kw(vec![("VALE_CALC", Scalar::Real(1.0))]);
        k.entries[0].value = KwValue::Simple(vec![
            Scalar::Real(1.0),
            Scalar::Real(2.0),
            Scalar::Real(3.0),
        ]);
        let c = &comparisons(&k).unwrap()[0];
        assert_eq!(c.judge(2.9).expected, 3.0);
        assert_eq!(c.judge(2.4).expected, 3.0);
        assert_eq!(c.judge(1.2).expected, 1.0);
        assert_eq!(c.judge(1.6).expected, 2.0);
        assert_eq!(c.judge(1.4).expected, 1.0);
    }

    #[test]
    fn legacy_vale_uses_precision() {
        let k = kw(vec![
            ("VALE", Scalar::Real(4.28571)),
            ("REFERENCE", Scalar::Str("ANALYTIQUE".into())),
            ("PRECISION", Scalar::Real(1e-4)),
        ]);
        let cs = comparisons(&k).unwrap();
        assert_eq!(cs.len(), 1);
        assert_eq!(cs[0].kind, "ANALYTIQUE");
        assert_eq!(cs[0].judge(4.2857142857).verdict, Verdict::Ok);
        assert_eq!(cs[0].judge(4.2867).verdict, Verdict::Nook);
    }

    #[test]
    fn vale_abs_compares_the_absolute_values_of_both_sides() {
        // SSNP167E: VALE_CALC=-0.00505517006413 with VALE_ABS='OUI' and a
        // computed -0.005055170.
        let k = kw(vec![
            ("VALE_CALC", Scalar::Real(-0.00505517006413)),
            ("VALE_ABS", Scalar::Str("OUI".into())),
        ]);
        let c = &comparisons(&k).unwrap()[0];
        assert_eq!(c.judge(-0.005055170).verdict, Verdict::Ok);
        assert_eq!(c.judge(0.005055170).verdict, Verdict::Ok);
        assert_eq!(c.judge(-0.0051).verdict, Verdict::Nook);
    }

    #[test]
    fn tally_summary() {
        let mut t = Tally::default();
        t.add(Verdict::Ok);
        t.add(Verdict::Nook);
        t.add(Verdict::Skip);
        assert_eq!(t.summary(), "TEST_RESU: 1 OK, 1 NOOK");
    }
}
