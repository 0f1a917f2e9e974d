//! Material parameters that follow the temperature: E, NU, ALPHA
//! (`ELAS_FO`), D_SIGM_EPSI and SY (`ECRO_LINE_FO`) evaluated at each Gauss
//! point and each instant from the temperature there, and the small-strain
//! integration of ELAS, `VMIS_ISOT_LINE` and `VMIS_ISOT_TRAC` with them, as
//! code_aster's `nmelas` and `nmisot` do it.
//!
//! code_aster integrates incrementally: the previous stress scaled by the
//! ratios of the moduli, deviator by 2μ⁺/2μ⁻ and trace by 3K⁺/3K⁻, plus
//! D⁺ (Δε − Δε_th), Δε_th = α(T⁺)(T⁺ − T_ref) − α(T⁻)(T⁻ − T_ref) on the
//! diagonal, then the radial return with the hardening slope and yield
//! stress at T⁺. Since every converged stress is D⁻ (ε⁻ − εᵖ⁻ − ε_th⁻ +
//! ε_th⁰), the scaled stress is D⁺ (ε⁻ − εᵖ⁻ − ε_th⁻ + ε_th⁰) and the trial
//! is D⁺ (ε⁺ − εᵖ⁻ − (ε_th⁺ − ε_th⁰)): the total form of [`super::vmis`]
//! with the parameters at T⁺ and the thermal strain counted from its value
//! ε_th⁰ at the first instant of the analysis (code_aster's initial state
//! is stress-free whatever the temperature then). That is what
//! [`integrate_point`] computes.

use super::traction::TractionNappe;
use super::vmis::{integrate, CurveEnd, Hardening, Mat6, PointState, VonMises};
use crate::error::FemError;
use crate::material::{Elastic, Hypothesis};

/// A material parameter as a function of the temperature: a constant, or
/// a table interpolated linearly (code_aster's `DEFI_FONCTION`
/// `INTERPOL='LIN'`) with its prolongations.
#[derive(Clone, Debug, PartialEq)]
pub enum TempFn {
    Constant(f64),
    Table {
        t: Vec<f64>,
        v: Vec<f64>,
        left: CurveEnd,
        right: CurveEnd,
    },
}

impl TempFn {
    /// The value at temperature `temp`.
    pub fn at(&self, temp: f64) -> Result<f64, FemError> {
        let (t, v, left, right) = match self {
            TempFn::Constant(c) => return Ok(*c),
            TempFn::Table { t, v, left, right } => (t, v, *left, *right),
        };
        let n = t.len();
        if n == 0 || v.len() != n {
            return Err(FemError::Model(
                "a material function of TEMP has no points".into(),
            ));
        }
        if n == 1 {
            return Ok(v[0]);
        }
        let lin = |k: usize| v[k] + (v[k + 1] - v[k]) * (temp - t[k]) / (t[k + 1] - t[k]);
        // A point's temperature interpolated from equal nodal values may
        // miss an end abscissa by round-off: taken as at the end.
        let tol = |x: f64| 1e-10 * x.abs().max(1.0);
        let temp = if temp < t[0] && t[0] - temp <= tol(t[0]) {
            t[0]
        } else if temp > t[n - 1] && temp - t[n - 1] <= tol(t[n - 1]) {
            t[n - 1]
        } else {
            temp
        };
        if temp < t[0] {
            return match left {
                CurveEnd::Constant => Ok(v[0]),
                CurveEnd::Linear => Ok(lin(0)),
                CurveEnd::Excluded => Err(FemError::Model(format!(
                    "the temperature {temp} is below the first abscissa {} of a material function (PROL_GAUCHE='EXCLU')",
                    t[0]
                ))),
            };
        }
        if temp > t[n - 1] {
            return match right {
                CurveEnd::Constant => Ok(v[n - 1]),
                CurveEnd::Linear => Ok(lin(n - 2)),
                CurveEnd::Excluded => Err(FemError::Model(format!(
                    "the temperature {temp} is above the last abscissa {} of a material function (PROL_DROITE='EXCLU')",
                    t[n - 1]
                ))),
            };
        }
        let k = t.partition_point(|&x| x <= temp).clamp(1, n - 1) - 1;
        Ok(lin(k))
    }
}

/// The hardening of a temperature-dependent law.
#[derive(Clone, Debug, PartialEq)]
pub enum ThermoHardening {
    /// `ECRO_LINE(_FO)` (`VMIS_ISOT_LINE`): the slope and yield stress at
    /// T⁺ (`nmisot`: `rcvalb(..., '+', 'ECRO_LINE', ...)`).
    Linear { d_sigm_epsi: TempFn, sy: TempFn },
    /// `TRACTION` by one curve σ(ε) (`VMIS_ISOT_TRAC`): the law of
    /// [`VonMises::traction_curve`], Young's modulus σ₁/ε₁ of the curve.
    Curve(VonMises),
    /// `TRACTION` by a nappe of curves of TEMP (`VMIS_ISOT_TRAC`): the
    /// curve and its modulus at T⁺ ([`super::traction`], `rctrac`).
    Nappe(TractionNappe),
}

/// The temperature-dependent material of a cell.
#[derive(Clone, Debug, PartialEq)]
pub struct ThermoMaterial {
    pub e: TempFn,
    pub nu: TempFn,
    /// α of ε_th = α(T)(T − T_ref), already converted to T_ref
    /// (`alfint`); `None`: no thermal strain.
    pub alpha: Option<TempFn>,
    /// The reference temperature (`AFFE_VARC/VALE_REF`).
    pub tref: f64,
    /// `None`: ELAS.
    pub hardening: Option<ThermoHardening>,
}

impl ThermoMaterial {
    /// E and NU at temperature `temp`.
    pub fn elastic_at(&self, temp: f64) -> Result<Elastic, FemError> {
        let e = match &self.hardening {
            Some(ThermoHardening::Curve(law)) => law.young.unwrap_or(f64::NAN),
            Some(ThermoHardening::Nappe(n)) => n.young_at(temp)?,
            _ => self.e.at(temp)?,
        };
        Elastic::new(e, self.nu.at(temp)?)
            .map_err(|err| FemError::Model(format!("at TEMP = {temp}: {err}")))
    }

    /// ε_th = α(T)(T − T_ref).
    pub fn thermal_strain(&self, temp: f64) -> Result<f64, FemError> {
        match &self.alpha {
            None => Ok(0.0),
            Some(a) => Ok(a.at(temp)? * (temp - self.tref)),
        }
    }

    /// The von Mises law at temperature `temp` (E from `el`), `None` for
    /// ELAS.
    pub fn law_at(&self, temp: f64, el: &Elastic) -> Result<Option<VonMises>, FemError> {
        match &self.hardening {
            None => Ok(None),
            Some(ThermoHardening::Curve(law)) => Ok(Some(law.clone())),
            Some(ThermoHardening::Nappe(n)) => n.at(temp).map(Some),
            Some(ThermoHardening::Linear { d_sigm_epsi, sy }) => {
                let (et, sy) = (d_sigm_epsi.at(temp)?, sy.at(temp)?);
                VonMises::linear(el.e, sy, et)
                    .map(Some)
                    .map_err(|err| FemError::Model(format!("at TEMP = {temp}: {err}")))
            }
        }
    }

    /// A law of the same kind, for the shape of the internal variables.
    pub fn reference_law(&self) -> Option<VonMises> {
        match &self.hardening {
            None => None,
            Some(ThermoHardening::Curve(law)) => Some(law.clone()),
            Some(ThermoHardening::Nappe(_)) | Some(ThermoHardening::Linear { .. }) => {
                Some(VonMises {
                    sy: f64::INFINITY,
                    hardening: Hardening::Linear { h: 0.0 },
                    young: None,
                    search: Default::default(),
                })
            }
        }
    }
}

/// One Gauss point from `prev` for the total strain `eps` (the
/// hypothesis' components, engineering shears) at temperature `temp`
/// (T⁺), the thermal strain counted from `eps_th0` (its value at the first
/// instant): the new state and the consistent tangent (`prediction`: the
/// tangent at `prev`, state unchanged). See the module's documentation.
pub fn integrate_point(
    mat: &ThermoMaterial,
    hyp: Hypothesis,
    eps: &[f64],
    temp: f64,
    eps_th0: f64,
    prev: &PointState,
    prediction: bool,
) -> Result<(PointState, Mat6), FemError> {
    let el = mat.elastic_at(temp)?;
    let n = hyp.ncomp();
    let th = mat.thermal_strain(temp)? - eps_th0;
    let mut mech = [0.0; 6];
    mech[..n].copy_from_slice(&eps[..n]);
    for m in mech.iter_mut().take(3) {
        *m -= th;
    }
    if let Some(law) = mat.law_at(temp, &el)? {
        return integrate(&law, &el, hyp, &mech[..n], prev, prediction, 0.0);
    }
    // ELAS (nmelas): σ = D⁺ (ε − ε_th); in plane stress εzz follows from
    // σzz = 0 through the plane-stress Hooke matrix.
    let d = el.hooke(hyp);
    let mut c = [[0.0; 6]; 6];
    for a in 0..n.min(d.nrows()) {
        for b in 0..n.min(d.ncols()) {
            c[a][b] = d[(a, b)];
        }
    }
    if prediction {
        return Ok((*prev, c));
    }
    let mut next = PointState {
        plastic: false,
        ..*prev
    };
    for a in 0..n {
        next.stress[a] = (0..n).map(|b| c[a][b] * mech[b]).sum();
    }
    if hyp == Hypothesis::PlaneStress {
        next.stress[2] = 0.0;
        next.eps_zz = -el.nu / (1.0 - el.nu) * (mech[0] + mech[1]);
    }
    Ok((next, c))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(t: &[f64], v: &[f64]) -> TempFn {
        TempFn::Table {
            t: t.to_vec(),
            v: v.to_vec(),
            left: CurveEnd::Constant,
            right: CurveEnd::Linear,
        }
    }

    #[test]
    fn tables_interpolate_and_prolong() {
        let f = table(&[0.0, 100.0, 200.0], &[10.0, 20.0, 40.0]);
        assert_eq!(f.at(50.0).unwrap(), 15.0);
        assert_eq!(f.at(150.0).unwrap(), 30.0);
        assert_eq!(f.at(-10.0).unwrap(), 10.0);
        assert_eq!(f.at(300.0).unwrap(), 60.0);
        let g = TempFn::Table {
            t: vec![0.0, 1.0],
            v: vec![1.0, 2.0],
            left: CurveEnd::Excluded,
            right: CurveEnd::Excluded,
        };
        assert!(g.at(-1.0).is_err() && g.at(2.0).is_err());
    }

    /// One 3D point under a strain history hand-computed with nmisot's
    /// incremental update: the previous stress scaled by E⁺/E⁻ (ν = 0:
    /// 2μ = E = 3K), the thermal increment α⁺(T⁺ − T_ref) − α⁻(T⁻ −
    /// T_ref), then a shear returned with SY and H at T⁺.
    #[test]
    fn uniaxial_update_matches_the_incremental_hand_computation() {
        let mat = ThermoMaterial {
            e: table(&[0.0, 500.0], &[200_000.0, 100_000.0]),
            nu: TempFn::Constant(0.0),
            alpha: Some(table(&[0.0, 500.0], &[1e-5, 2e-5])),
            tref: 0.0,
            hardening: Some(ThermoHardening::Linear {
                d_sigm_epsi: table(&[0.0, 500.0], &[2000.0, 1000.0]),
                sy: table(&[0.0, 500.0], &[300.0, 100.0]),
            }),
        };
        // Step 1: T 0 → 100, ε_xx = 0 (clamped), the others free (ν = 0:
        // no coupling): elastic? ε_th = α(100)·100 = 1.2e-5·100 = 1.2e-3,
        // E(100) = 180000, σ = −216 < SY(100) = 260: elastic.
        let eps1 = [0.0; 6];
        let (s1, _) = integrate_point(
            &mat,
            Hypothesis::Solid3D,
            &eps1,
            100.0,
            0.0,
            &PointState::default(),
            false,
        )
        .unwrap();
        let eth = |t: f64| (1e-5 + 1e-5 * t / 500.0) * t;
        let e = |t: f64| 200_000.0 - 200.0 * t;
        assert!(
            (s1.stress[0] + e(100.0) * eth(100.0)).abs() < 1e-9,
            "{:?}",
            s1.stress
        );
        assert!(!s1.plastic);
        // Step 2: T 100 → 200, strain held: with ν = 0 the trial of
        // nmisot, σ₁ E⁺/E⁻ − E⁺ Δε_th on each diagonal term, is
        // hydrostatic: no deviator, elastic whatever SY.
        let sy = 300.0 - 0.4 * 200.0;
        let et = 2000.0 - 2.0 * 200.0;
        let h = e(200.0) * et / (e(200.0) - et);
        let (s2, _) =
            integrate_point(&mat, Hypothesis::Solid3D, &eps1, 200.0, 0.0, &s1, false).unwrap();
        assert!(!s2.plastic);
        for k in 0..3 {
            let trial = s1.stress[k] * e(200.0) / e(100.0) - e(200.0) * (eth(200.0) - eth(100.0));
            assert!((s2.stress[k] - trial).abs() < 1e-9);
        }
        // Step 3: a shear strain γ at T = 200 from s2: trial τ = μ⁺ γ,
        // q = √3 τ; plastic with Δp = (q − SY⁺)/(3μ⁺ + H⁺).
        let mu = e(200.0) / 2.0;
        let gamma = 4.0 * sy / (3f64.sqrt() * mu);
        let mut eps3 = [0.0; 6];
        eps3[3] = gamma;
        let (s3, _) =
            integrate_point(&mat, Hypothesis::Solid3D, &eps3, 200.0, 0.0, &s2, false).unwrap();
        let q = 3f64.sqrt() * mu * gamma;
        let dp = (q - sy) / (3.0 * mu + h);
        assert!(s3.plastic);
        assert!((s3.p - dp).abs() < 1e-15, "{} vs {dp}", s3.p);
        let tau = mu * gamma * (1.0 - 3.0 * mu * dp / q);
        assert!(
            (s3.stress[3] - tau).abs() < 1e-9 * tau,
            "{} vs {tau}",
            s3.stress[3]
        );
        // On the yield surface at T⁺: √3 τ = SY⁺ + H⁺ p.
        assert!((3f64.sqrt() * s3.stress[3] - (sy + h * dp)).abs() < 1e-9);
    }

    /// The previous stress is scaled by the ratio of the moduli when the
    /// temperature changes with the strain held (nmelas): σ⁺ = σ⁻ E⁺/E⁻.
    #[test]
    fn elastic_stress_follows_the_modulus() {
        let mat = ThermoMaterial {
            e: table(&[0.0, 100.0], &[100.0, 50.0]),
            nu: TempFn::Constant(0.25),
            alpha: None,
            tref: 0.0,
            hardening: None,
        };
        let eps = [1e-2, 0.0, 0.0, 0.0];
        let (s1, _) = integrate_point(
            &mat,
            Hypothesis::PlaneStrain,
            &eps,
            0.0,
            0.0,
            &PointState::default(),
            false,
        )
        .unwrap();
        let (s2, _) =
            integrate_point(&mat, Hypothesis::PlaneStrain, &eps, 100.0, 0.0, &s1, false).unwrap();
        for k in 0..4 {
            assert!((s2.stress[k] - 0.5 * s1.stress[k]).abs() < 1e-12);
        }
        // Plane stress: σzz = 0, σxx = E ε (uniaxial in x with εyy = 0:
        // σxx = E/(1 − ν²) ε).
        let (s3, _) = integrate_point(
            &mat,
            Hypothesis::PlaneStress,
            &eps,
            100.0,
            0.0,
            &PointState::default(),
            false,
        )
        .unwrap();
        assert!((s3.stress[0] - 50.0 / (1.0 - 0.0625) * 1e-2).abs() < 1e-12);
        assert_eq!(s3.stress[2], 0.0);
    }

    /// The thermal strain is counted from its value at the first instant.
    #[test]
    fn thermal_strain_counts_from_the_first_instant() {
        let mat = ThermoMaterial {
            e: TempFn::Constant(1000.0),
            nu: TempFn::Constant(0.0),
            alpha: Some(TempFn::Constant(1e-3)),
            tref: 0.0,
            hardening: None,
        };
        let eps = [0.0; 6];
        let th0 = mat.thermal_strain(20.0).unwrap();
        let (s, _) = integrate_point(
            &mat,
            Hypothesis::Solid3D,
            &eps,
            20.0,
            th0,
            &PointState::default(),
            false,
        )
        .unwrap();
        assert!(s.stress.iter().all(|v| v.abs() < 1e-15));
        let (s, _) = integrate_point(
            &mat,
            Hypothesis::Solid3D,
            &eps,
            30.0,
            th0,
            &PointState::default(),
            false,
        )
        .unwrap();
        assert!((s.stress[0] + 1000.0 * 1e-3 * 10.0).abs() < 1e-12);
    }

    /// code_aster's `nmisot` (VMIS_ISOT_LINE, 3D) written as in the
    /// Fortran, incrementally: the previous stress scaled by 2μ⁺/2μ⁻ on
    /// the deviator and 3K⁺/3K⁻ on the trace, plus the strain increment
    /// less Δε_th = α⁺(T⁺ − T_ref) − α⁻(T⁻ − T_ref), the return with
    /// R = SY⁺ + H⁺ p⁻. Returns (σ⁺, p⁺); engineering shears in `deps`.
    fn nmisot(
        mat: &ThermoMaterial,
        sigm: &[f64; 6],
        pm: f64,
        deps: &[f64; 6],
        tm: f64,
        tp: f64,
    ) -> ([f64; 6], f64) {
        let (em, num) = (mat.e.at(tm).unwrap(), mat.nu.at(tm).unwrap());
        let (e, nu) = (mat.e.at(tp).unwrap(), mat.nu.at(tp).unwrap());
        let (deumum, troikm) = (em / (1.0 + num), em / (1.0 - 2.0 * num));
        let (deuxmu, troisk) = (e / (1.0 + nu), e / (1.0 - 2.0 * nu));
        let Some(ThermoHardening::Linear { d_sigm_epsi, sy }) = &mat.hardening else {
            unreachable!()
        };
        let (dsde, sigy) = (d_sigm_epsi.at(tp).unwrap(), sy.at(tp).unwrap());
        let rprim = dsde * e / (e - dsde);
        let rp = rprim * pm + sigy;
        let coef = mat.thermal_strain(tp).unwrap() - mat.thermal_strain(tm).unwrap();
        // Tensor shears as code_aster's √2 convention reduces to: a
        // deviator component d and its norm Σ d² with shears counted twice.
        let mut depsth = [0.0; 6];
        for k in 0..3 {
            depsth[k] = deps[k] - coef;
        }
        for k in 3..6 {
            depsth[k] = deps[k] / 2.0;
        }
        let depsmo = (depsth[0] + depsth[1] + depsth[2]) / 3.0;
        let sigmmo = (sigm[0] + sigm[1] + sigm[2]) / 3.0;
        let mut sigmp = [0.0; 6];
        for k in 0..6 {
            let kr = if k < 3 { 1.0 } else { 0.0 };
            sigmp[k] = deuxmu / deumum * (sigm[k] - sigmmo * kr) + troisk / troikm * sigmmo * kr;
        }
        let sigmmo = (sigmp[0] + sigmp[1] + sigmp[2]) / 3.0;
        let mut sigel = [0.0; 6];
        let mut sieleq = 0.0;
        for k in 0..6 {
            let kr = if k < 3 { 1.0 } else { 0.0 };
            sigel[k] = sigmp[k] - sigmmo * kr + deuxmu * (depsth[k] - depsmo * kr);
            sieleq += sigel[k] * sigel[k] * if k < 3 { 1.0 } else { 2.0 };
        }
        let sieleq = (1.5 * sieleq).sqrt();
        let dp = if sieleq - rp > 0.0 {
            (sieleq - rp) / (1.5 * deuxmu + rprim)
        } else {
            0.0
        };
        let mut sigp = [0.0; 6];
        for k in 0..6 {
            let kr = if k < 3 { 1.0 } else { 0.0 };
            let scale = if dp > 0.0 {
                1.0 - 1.5 * deuxmu * dp / sieleq
            } else {
                1.0
            };
            sigp[k] = sigel[k] * scale + (sigmmo + troisk * depsmo) * kr;
        }
        (sigp, pm + dp)
    }

    /// A 3D point along a path of strains and temperatures (heating,
    /// cooling, tension and shear, plastic at varying E, NU, α, SY, ET):
    /// the total form of [`integrate_point`] equals nmisot's incremental
    /// update at every step.
    #[test]
    fn total_form_equals_nmisot_incremental_update() {
        let mat = ThermoMaterial {
            e: table(&[20.0, 520.0], &[200_000.0, 150_000.0]),
            nu: table(&[20.0, 520.0], &[0.3, 0.35]),
            alpha: Some(table(&[20.0, 520.0], &[1.0e-5, 1.6e-5])),
            tref: 20.0,
            hardening: Some(ThermoHardening::Linear {
                d_sigm_epsi: table(&[20.0, 520.0], &[3000.0, 1000.0]),
                sy: table(&[20.0, 520.0], &[250.0, 120.0]),
            }),
        };
        let path: [(f64, [f64; 6]); 5] = [
            (150.0, [8e-4, -2e-4, -1e-4, 1e-4, 0.0, 0.0]),
            (300.0, [2.5e-3, -6e-4, -5e-4, 6e-4, 2e-4, 0.0]),
            (250.0, [3.0e-3, -8e-4, -6e-4, 1.4e-3, 2e-4, -3e-4]),
            (400.0, [2.0e-3, -5e-4, -2e-4, 1.0e-3, 5e-4, -3e-4]),
            (60.0, [2.2e-3, -5e-4, -2e-4, 0.0, 5e-4, 0.0]),
        ];
        let t0 = 40.0;
        let th0 = mat.thermal_strain(t0).unwrap();
        let (mut state, mut sig, mut p) = (PointState::default(), [0.0; 6], 0.0);
        let (mut eps_prev, mut t_prev) = ([0.0; 6], t0);
        let mut plastic_steps = 0;
        for (t, eps) in path {
            let mut deps = [0.0; 6];
            for k in 0..6 {
                deps[k] = eps[k] - eps_prev[k];
            }
            (sig, p) = nmisot(&mat, &sig, p, &deps, t_prev, t);
            let (next, _) =
                integrate_point(&mat, Hypothesis::Solid3D, &eps, t, th0, &state, false).unwrap();
            plastic_steps += next.plastic as usize;
            for k in 0..6 {
                assert!(
                    (next.stress[k] - sig[k]).abs() < 1e-9 * 300.0,
                    "T={t} k={k}: {} vs {}",
                    next.stress[k],
                    sig[k]
                );
            }
            assert!((next.p - p).abs() < 1e-12, "T={t}: p {} vs {p}", next.p);
            state = next;
            eps_prev = eps;
            t_prev = t;
        }
        assert!(
            plastic_steps >= 2 && p > 0.0,
            "the path must yield: {plastic_steps}, p = {p}"
        );
    }
}
