//! Traction curves given per temperature (`DEFI_MATERIAU/TRACTION/SIGM`
//! a `DEFI_NAPPE` of `TEMP`): the hardening curve R(p) and Young's
//! modulus at a temperature, built as code_aster's `rctrac` builds them
//! for `VMIS_ISOT_TRAC` (`nmisot`) and `ELAS_VMIS_TRAC` (`lcelnl`).
//!
//! - At a temperature of the nappe (within 1e-6 relative of a `PARA`
//!   value) or beyond its ends with `PROL_*='CONSTANT'`: that curve,
//!   read as [`VonMises::traction_curve`] (E = σ₁/ε₁, pᵢ = εᵢ − σᵢ/E).
//! - Between two curves i, i+1 (or beyond an end with `'LINEAIRE'`, the
//!   two end curves extrapolated): each curve is first turned into
//!   R(p) with its own modulus Eₖ = σ₁ᵏ/ε₁ᵏ; the result's abscissae
//!   are the union of both curves' plastic strains (two within 1e-6
//!   relative counted once), each curve read at every abscissa (linearly
//!   on its segments, beyond its last point by its own `PROL_DROITE`:
//!   the last segment, the last value, or the end of the merged curve
//!   for `EXCLU`), and R = R_i + c (R_{i+1} − R_i), E = E_i + c (E_{i+1}
//!   − E_i) with c = (T − T_i)/(T_{i+1} − T_i). The merged curve is
//!   prolonged `EXCLU` if either curve is, else linearly if either is,
//!   else by its last value.
//!
//! The interpolation is in the plastic strain p, not in ε at a common
//! stress: what code_aster does, documented in docs/fem.md.

use super::vmis::{CurveEnd, Hardening, LocalSearch, VonMises};
use crate::error::FemError;

/// One σ(ε) curve of a nappe, its first point the elastic limit.
#[derive(Clone, Debug, PartialEq)]
pub struct TractionCurve {
    pub eps: Vec<f64>,
    pub sig: Vec<f64>,
    /// The curve's own `PROL_DROITE`.
    pub right: CurveEnd,
}

/// `TRACTION=_F(SIGM=nappe)`: one curve per temperature.
#[derive(Clone, Debug, PartialEq)]
pub struct TractionNappe {
    /// `PARA`, increasing.
    pub temps: Vec<f64>,
    pub curves: Vec<TractionCurve>,
    /// The nappe's `PROL_GAUCHE`, `PROL_DROITE` (in the temperature).
    pub left: CurveEnd,
    pub right: CurveEnd,
}

/// `rctrac`'s tolerance on a temperature equal to a `PARA` value and on
/// two plastic strains taken as one.
const TOLE: f64 = 1e-6;

impl TractionNappe {
    /// Checks the nappe: increasing temperatures, one curve each, every
    /// curve with a positive first point and plastic strains that
    /// increase.
    pub fn new(
        temps: Vec<f64>,
        curves: Vec<TractionCurve>,
        left: CurveEnd,
        right: CurveEnd,
    ) -> Result<TractionNappe, FemError> {
        if temps.is_empty() || temps.len() != curves.len() {
            return Err(FemError::Model(format!(
                "TRACTION: the nappe needs one curve per temperature ({} temperatures, {} curves)",
                temps.len(),
                curves.len()
            )));
        }
        if temps
            .windows(2)
            .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
        {
            return Err(FemError::Model(
                "TRACTION: the temperatures (PARA) of the nappe must increase".into(),
            ));
        }
        for (t, c) in temps.iter().zip(&curves) {
            VonMises::traction_curve(&c.eps, &c.sig, c.right)
                .map_err(|e| FemError::Model(format!("the curve at TEMP = {t}: {e}")))?;
        }
        Ok(TractionNappe {
            temps,
            curves,
            left,
            right,
        })
    }

    /// The law at temperature `temp` (Young's modulus in `young`).
    pub fn at(&self, temp: f64) -> Result<VonMises, FemError> {
        let t = &self.temps;
        let n = t.len();
        // (index, whether that curve alone is used).
        let (ii, alone) = if temp < t[0] {
            match self.left {
                CurveEnd::Constant => (0, true),
                CurveEnd::Linear => (0, false),
                CurveEnd::Excluded => {
                    return Err(FemError::Model(format!(
                        "TRACTION: the temperature {temp} is below the first one of the nappe ({}, PROL_GAUCHE='EXCLU')",
                        t[0]
                    )))
                }
            }
        } else if temp > t[n - 1] {
            match self.right {
                CurveEnd::Constant => (n - 1, true),
                CurveEnd::Linear => (n.saturating_sub(2), false),
                CurveEnd::Excluded => {
                    return Err(FemError::Model(format!(
                        "TRACTION: the temperature {temp} is above the last one of the nappe ({}, PROL_DROITE='EXCLU')",
                        t[n - 1]
                    )))
                }
            }
        } else {
            let mut found = (0, true);
            for jj in 0..n.saturating_sub(1) {
                let (t1, t2) = (t[jj], t[jj + 1]);
                if (t1 - temp).abs() <= TOLE * t1.abs() {
                    found = (jj, true);
                    break;
                }
                if (t2 - temp).abs() <= TOLE * t2.abs() {
                    found = (jj + 1, true);
                    break;
                }
                if t1 < temp && temp < t2 {
                    found = (jj, false);
                    break;
                }
            }
            found
        };
        if alone || n == 1 {
            let c = &self.curves[ii.min(n - 1)];
            return VonMises::traction_curve(&c.eps, &c.sig, c.right);
        }
        let coef = (temp - t[ii]) / (t[ii + 1] - t[ii]);
        merge(&self.curves[ii], &self.curves[ii + 1], coef)
    }

    /// Young's modulus at `temp` (of the curve there).
    pub fn young_at(&self, temp: f64) -> Result<f64, FemError> {
        self.at(temp)?
            .young
            .ok_or_else(|| FemError::Model("TRACTION: a curve without modulus".into()))
    }
}

/// `rctrac`'s interpolation between curves `c1` and `c2` at `coef`.
fn merge(c1: &TractionCurve, c2: &TractionCurve, coef: f64) -> Result<VonMises, FemError> {
    let (x1, y1, n1) = (&c1.eps, &c1.sig, c1.eps.len());
    let (x2, y2, n2) = (&c2.eps, &c2.sig, c2.eps.len());
    let e1 = y1[0] / x1[0];
    let e2 = y2[0] / x2[0];
    let e = e1 + coef * (e2 - e1);
    let p1 = |k: usize| x1[k] - y1[k] / e1;
    let p2 = |k: usize| x2[k] - y2[k] / e2;
    let lerp = |a: f64, b: f64| a + coef * (b - a);
    let mut p = vec![0.0];
    let mut r = vec![lerp(y1[0], y2[0])];
    let (mut k1, mut k2) = (1usize, 1usize);
    let (mut z1, mut zp1, mut z2, mut zp2) = (0.0, 0.0, 0.0, 0.0);
    let single = || {
        FemError::Model(
            "TRACTION: a curve of one point cannot be prolonged linearly between two temperatures"
                .into(),
        )
    };
    'walk: while k1 < n1 || k2 < n2 {
        if k1 >= n1 {
            // Curve 1 exhausted: prolonged by its PROL_DROITE.
            let rprim1 = match c1.right {
                CurveEnd::Excluded => break 'walk,
                CurveEnd::Linear => {
                    if n1 < 2 {
                        return Err(single());
                    }
                    (y1[k1 - 1] - y1[k1 - 2]) / (z1 - zp1)
                }
                CurveEnd::Constant => 0.0,
            };
            z2 = p2(k2);
            let rp1 = y1[k1 - 1] + rprim1 * (z2 - z1);
            p.push(z2);
            r.push(lerp(rp1, y2[k2]));
            k2 += 1;
            continue;
        }
        zp1 = p1(k1 - 1);
        z1 = p1(k1);
        if k2 >= n2 {
            let rprim2 = match c2.right {
                CurveEnd::Excluded => break 'walk,
                CurveEnd::Linear => {
                    if n2 < 2 {
                        return Err(single());
                    }
                    (y2[k2 - 1] - y2[k2 - 2]) / (z2 - zp2)
                }
                CurveEnd::Constant => 0.0,
            };
            let rp2 = y2[k2 - 1] + rprim2 * (z1 - z2);
            p.push(z1);
            r.push(lerp(y1[k1], rp2));
            k1 += 1;
            continue;
        }
        zp2 = p2(k2 - 1);
        z2 = p2(k2);
        let (x, rp1, rp2);
        if (z2 - z1).abs() <= TOLE * z1 {
            x = z1;
            rp1 = y1[k1];
            rp2 = y2[k2];
            k1 += 1;
            k2 += 1;
        } else if z2 > z1 {
            x = z1;
            rp1 = y1[k1];
            let rprim2 = (y2[k2] - y2[k2 - 1]) / (z2 - zp2);
            rp2 = y2[k2 - 1] + rprim2 * (z1 - zp2);
            k1 += 1;
        } else {
            x = z2;
            rp2 = y2[k2];
            let rprim1 = (y1[k1] - y1[k1 - 1]) / (z1 - zp1);
            rp1 = y1[k1 - 1] + rprim1 * (z2 - zp1);
            k2 += 1;
        }
        p.push(x);
        r.push(lerp(rp1, rp2));
    }
    let end = if c1.right == CurveEnd::Excluded || c2.right == CurveEnd::Excluded {
        CurveEnd::Excluded
    } else if c1.right == CurveEnd::Linear || c2.right == CurveEnd::Linear {
        CurveEnd::Linear
    } else {
        CurveEnd::Constant
    };
    let sy = r[0];
    if !(e.is_finite() && e > 0.0 && sy.is_finite() && sy > 0.0) {
        return Err(FemError::Model(format!(
            "TRACTION: the curve interpolated between two temperatures (coefficient {coef}) has E = {e} and σ_y = {sy}: both must be positive"
        )));
    }
    if let Some(w) = p
        .windows(2)
        .position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
    {
        return Err(FemError::Model(format!(
            "TRACTION: the curve interpolated between two temperatures has plastic strains that do not increase (point {}: {:e} after {:e})",
            w + 2,
            p[w + 1],
            p[w]
        )));
    }
    Ok(VonMises {
        sy,
        hardening: Hardening::Curve { p, r, end },
        young: Some(e),
        search: LocalSearch::default(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(pts: &[(f64, f64)], right: CurveEnd) -> TractionCurve {
        TractionCurve {
            eps: pts.iter().map(|p| p.0).collect(),
            sig: pts.iter().map(|p| p.1).collect(),
            right,
        }
    }

    /// hsnv100's nappe: two curves of E = 200 000 at 0 and 50 °C.
    fn hsnv100() -> TractionNappe {
        TractionNappe::new(
            vec![0.0, 50.0],
            vec![
                curve(&[(0.002, 400.0), (0.004, 500.0)], CurveEnd::Linear),
                curve(&[(0.001, 200.0), (0.003, 300.0)], CurveEnd::Linear),
            ],
            CurveEnd::Linear,
            CurveEnd::Linear,
        )
        .unwrap()
    }

    fn curve_of(law: &VonMises) -> (Vec<f64>, Vec<f64>, CurveEnd) {
        let Hardening::Curve { p, r, end } = &law.hardening else {
            panic!("not a curve")
        };
        (p.clone(), r.clone(), *end)
    }

    #[test]
    fn at_a_tabulated_temperature_the_curve_itself() {
        let n = hsnv100();
        let law = n.at(50.0).unwrap();
        assert_eq!(law.young, Some(200_000.0));
        let (p, r, _) = curve_of(&law);
        assert_eq!(r, vec![200.0, 300.0]);
        assert!((p[1] - (0.003 - 300.0 / 200_000.0)).abs() < 1e-15);
        // Within 1e-6 relative of 50 inside the range: still that curve;
        // above the last temperature rctrac extrapolates, tolerance or not.
        assert_eq!(curve_of(&n.at(50.0 - 1e-6).unwrap()).1, vec![200.0, 300.0]);
        assert_ne!(curve_of(&n.at(50.0 + 1e-6).unwrap()).1, vec![200.0, 300.0]);
    }

    /// Between and beyond (PROL_DROITE='LINEAIRE'): R interpolated at the
    /// common plastic strains 0 and 1.5e-3: at T = 66.666 (c = 1.33332)
    /// σ_y = 400 − 200c, the slope kept (100/1.5e-3).
    #[test]
    fn interpolated_and_extrapolated_in_temperature() {
        let n = hsnv100();
        let law = n.at(25.0).unwrap();
        let (p, r, end) = curve_of(&law);
        assert_eq!(end, CurveEnd::Linear);
        assert_eq!(p.len(), 2, "the common abscissa counted once: {p:?}");
        assert!((r[0] - 300.0).abs() < 1e-12 && (r[1] - 400.0).abs() < 1e-12);
        let c = 66.666 / 50.0;
        let law = n.at(66.666).unwrap();
        let (_, r, _) = curve_of(&law);
        assert!((law.sy - (400.0 - 200.0 * c)).abs() < 1e-9);
        assert!((r[1] - (500.0 - 200.0 * c)).abs() < 1e-9);
        assert!((law.young.unwrap() - 200_000.0).abs() < 1e-6);
    }

    /// Curves with different moduli and abscissae: the union of the
    /// plastic strains, each curve read on its segments and prolonged by
    /// its own PROL_DROITE; E interpolated.
    #[test]
    fn union_of_abscissae_and_own_prolongations() {
        // Curve 1: E = 1000, p at 0, 0.1 (σ 100 → 200 at ε 0.3).
        // Curve 2: E = 2000, p at 0, 0.05, 0.2 (σ 50, 100, 130), constant.
        let c1 = curve(&[(0.1, 100.0), (0.3, 200.0)], CurveEnd::Linear);
        let c2 = curve(
            &[(0.025, 50.0), (0.1, 100.0), (0.265, 130.0)],
            CurveEnd::Constant,
        );
        let n = TractionNappe::new(
            vec![0.0, 100.0],
            vec![c1, c2],
            CurveEnd::Constant,
            CurveEnd::Constant,
        )
        .unwrap();
        let law = n.at(25.0).unwrap();
        let (p, r, end) = curve_of(&law);
        assert_eq!(end, CurveEnd::Linear);
        let expect_p = [0.0, 0.05, 0.1, 0.2];
        // Curve 1 R1(p) = 100 + 1000 p (prolonged linearly); curve 2
        // 50 + 1000 p up to 0.05, then 100 + 200 (p − 0.05).
        let r1 = |p: f64| 100.0 + 1000.0 * p;
        let r2 = |p: f64| {
            if p <= 0.05 {
                50.0 + 1000.0 * p
            } else {
                100.0 + 200.0 * (p - 0.05)
            }
        };
        assert_eq!(p.len(), 4, "{p:?}");
        for (k, &pk) in expect_p.iter().enumerate() {
            assert!((p[k] - pk).abs() < 1e-12, "{p:?}");
            let want = r1(pk) + 0.25 * (r2(pk) - r1(pk));
            assert!((r[k] - want).abs() < 1e-9, "R({pk}) = {} vs {want}", r[k]);
        }
        assert!((law.young.unwrap() - 1250.0).abs() < 1e-9);
        // Below the first temperature, PROL_GAUCHE='CONSTANT': curve 1.
        assert_eq!(n.at(-10.0).unwrap().young, Some(1000.0));
    }

    #[test]
    fn excluded_ends_are_errors() {
        let mut n = hsnv100();
        n.right = CurveEnd::Excluded;
        assert!(n.at(60.0).is_err());
        assert!(n.at(40.0).is_ok());
        assert!(TractionNappe::new(
            vec![10.0, 0.0],
            n.curves.clone(),
            CurveEnd::Linear,
            CurveEnd::Linear
        )
        .is_err());
    }
}
