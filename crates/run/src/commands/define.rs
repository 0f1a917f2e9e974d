//! Materials, model, element characteristics, functions and lists.

use crate::concept::*;
use crate::executor::{store_result, Executor};
use crate::function::{Extension, Function, Scale, Tabulated};
use crate::list::{self, Interval};
use crate::select;
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use std::collections::BTreeMap;
use std::rc::Rc;

pub(super) fn reals(kw: &Keywords, name: &str) -> Vec<f64> {
    kw.simple(name).iter().filter_map(|s| s.as_f64()).collect()
}

/// What DEFI_MATERIAU reads (`crate::support`).
pub(crate) const DEFI_MATERIAU: Support = Support::keywords(&[
    "ELAS",
    "ELAS/E",
    "ELAS/NU",
    "ELAS/RHO",
    "ELAS/ALPHA",
    "ELAS/AMOR_ALPHA",
    "ELAS/AMOR_BETA",
    "ECRO_LINE",
    "ECRO_LINE/D_SIGM_EPSI",
    "ECRO_LINE/SY",
    "ECRO_LINE_FO",
    "ECRO_LINE_FO/D_SIGM_EPSI",
    "ECRO_LINE_FO/SY",
    "TRACTION",
    "TRACTION/SIGM",
    "LEMAITRE",
    "LEMAITRE/N",
    "LEMAITRE/UN_SUR_K",
    "LEMAITRE/UN_SUR_M",
    "ECRO_NL",
    "ECRO_NL/R0",
    "ECRO_NL/RH",
    "ECRO_NL/R1",
    "ECRO_NL/GAMMA_1",
    "ECRO_NL/R2",
    "ECRO_NL/GAMMA_2",
    "ECRO_NL/RK",
    "ECRO_NL/P0",
    "ECRO_NL/GAMMA_M",
    "ECRO_COOK",
    "ECRO_COOK/A",
    "ECRO_COOK/B",
    "ECRO_COOK/C",
    "ECRO_COOK/N_PUIS",
    "ECRO_COOK/M_PUIS",
    "ECRO_COOK/EPSP0",
    "ECRO_COOK/TROOM",
    "ECRO_COOK/TMELT",
    "THER",
    "THER/LAMBDA",
    "THER/RHO_CP",
    "THER_NL",
    "THER_NL/LAMBDA",
    "THER_NL/BETA",
    "THER_NL/RHO_CP",
    "RUPT_FRAG",
    "RUPT_FRAG/GC",
    "RUPT_FRAG/SIGM_C",
    "RUPT_FRAG/PENA_ADHERENCE",
    "RUPT_FRAG/PENA_CONTACT",
    "RUPT_TURON",
    "RUPT_TURON/K",
    "RUPT_TURON/SIGM_C_N",
    "RUPT_TURON/SIGM_C_T",
    "RUPT_TURON/GC_N",
    "RUPT_TURON/GC_T",
    "RUPT_TURON/C_RUPT",
    "RUPT_TURON/ETA_BK",
    "RUPT_TURON/CRIT_INIT",
    "ELAS_ORTH",
    "ELAS_ORTH/E_L",
    "ELAS_ORTH/E_T",
    "ELAS_ORTH/E_N",
    "ELAS_ORTH/NU_LT",
    "ELAS_ORTH/NU_LN",
    "ELAS_ORTH/NU_TN",
    "ELAS_ORTH/G_LT",
    "ELAS_ORTH/G_LN",
    "ELAS_ORTH/G_TN",
    "ELAS_ORTH/RHO",
    "ELAS_FO",
    "ELAS_FO/E",
    "ELAS_FO/NU",
    "ELAS_FO/RHO",
    "ELAS_FO/ALPHA",
    "ELAS_FO/TEMP_DEF_ALPHA",
    "ELAS_FO/PRECISION",
    "ELAS_FO/AMOR_ALPHA",
    "ELAS_FO/AMOR_BETA",
    // The drying and endogenous shrinkages K_DESSIC (SECH − SECH_REF) and
    // B_ENDOGE HYDR: zero, since aster's only command variable is the
    // temperature (AFFE_VARC refuses SECH and HYDR).
    "ELAS_FO/K_DESSIC",
    "ELAS_FO/B_ENDOGE",
    "ELAS/K_DESSIC",
    "ELAS/B_ENDOGE",
    "INFO",
]);

/// The blocks of the plastic and viscoplastic laws (isotropic, on ELAS).
const PLASTIC_BLOCKS: [&str; 6] = [
    "ECRO_LINE",
    "ECRO_LINE_FO",
    "TRACTION",
    "LEMAITRE",
    "ECRO_NL",
    "ECRO_COOK",
];

/// A material without `ELAS` (its E and NU NaN), no law, conduction
/// `thermal`: what a thermal or orthotropic material starts from.
pub(crate) fn without_elas(thermal: Option<aster_fem::thermal::Conduction>) -> Material {
    Material {
        elastic: false,
        young: f64::NAN,
        poisson: f64::NAN,
        density: None,
        alpha: None,
        amor_alpha: None,
        amor_beta: None,
        ecro_line: None,
        ecro_line_fo: None,
        traction: None,
        traction_nappe: None,
        lemaitre: None,
        ecro_nl: None,
        ecro_cook: None,
        thermal,
        thermal_nl: None,
        rupt_frag: None,
        rupt_turon: None,
        orthotropic: None,
        composite: None,
        elas_fo: None,
        alpha_fo: None,
        unresolved: None,
    }
}

/// `DEFI_MATERIAU/ELAS_ORTH`: the orthotropic moduli (in the material
/// frame, the cells' `AFFE_CARA_ELEM/MASSIF` one given at the model) and
/// the density. The optional moduli code_aster's elements still read
/// (E_N, NU_LN, NU_TN, G_LN, G_TN) are NaN when absent: the model refuses
/// them, naming the missing one. The plastic laws of this crate are
/// isotropic: with ELAS_ORTH they are refused.
fn elas_orth(
    ex: &Executor,
    kw: &Keywords,
) -> Result<Option<(aster_fem::orthotropic::Orthotropic, Option<f64>)>, ExecError> {
    let Some(occ) = kw.factor("ELAS_ORTH").first() else {
        return Ok(None);
    };
    let at = "DEFI_MATERIAU/ELAS_ORTH";
    if let Some(k) = PLASTIC_BLOCKS.iter().find(|k| !kw.factor(k).is_empty()) {
        let span = kw.keyword(k).map(|k| k.span).unwrap_or_default();
        return Err(ex.unsupported(
            &format!("DEFI_MATERIAU/{k} with ELAS_ORTH (the plastic laws here are isotropic)"),
            span,
        ));
    }
    let req = |name: &str| {
        occ.f64(name)
            .ok_or_else(|| ex.kw_error(at, occ, name, format!("{name} is required")))
    };
    let opt = |name: &str| occ.f64(name).unwrap_or(f64::NAN);
    let o = aster_fem::orthotropic::Orthotropic {
        e_l: req("E_L")?,
        e_t: req("E_T")?,
        e_n: opt("E_N"),
        g_lt: req("G_LT")?,
        g_ln: opt("G_LN"),
        g_tn: opt("G_TN"),
        nu_lt: req("NU_LT")?,
        nu_ln: opt("NU_LN"),
        nu_tn: opt("NU_TN"),
        angles: [0.0; 3],
    };
    Ok(Some((o, occ.f64("RHO"))))
}

/// `DEFI_MATERIAU/THER`: conductivity and volumic heat capacity.
fn ther(
    ex: &Executor,
    kw: &aster_eval::Keywords,
) -> Result<Option<aster_fem::thermal::Conduction>, ExecError> {
    let Some(occ) = kw.factor("THER").first() else {
        return Ok(None);
    };
    let get = |name: &str, what: &str| -> Result<f64, ExecError> {
        let v = occ.f64(name).ok_or_else(|| {
            ex.kw_error(
                "DEFI_MATERIAU/THER",
                occ,
                name,
                format!("{what} is required"),
            )
        })?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(ex.kw_error(
                "DEFI_MATERIAU/THER",
                occ,
                name,
                format!("{name} must be positive, got {v}"),
            ))
        }
    };
    Ok(Some(aster_fem::thermal::Conduction {
        lambda: get("LAMBDA", "the conductivity LAMBDA")?,
        // code_aster's default: no heat capacity (stationary use); an
        // explicit 0 means the same (hsnv100f), a negative one is refused.
        rho_cp: match occ.f64("RHO_CP") {
            Some(0.0) | None => 0.0,
            Some(_) => get("RHO_CP", "RHO_CP")?,
        },
    }))
}

/// A `THER_NL` function of the temperature as `rcfode` reads it: a
/// `DEFI_CONSTANTE` or a `DEFI_FONCTION` of `TEMP` (linear between its
/// points, its prolongations).
fn ther_nl_curve(
    ex: &Executor,
    occ: &Keywords,
    key: &str,
) -> Result<Option<aster_fem::thermal_nl::Curve>, ExecError> {
    use aster_fem::thermal_nl::{Curve, CurveEnd};
    let at = "DEFI_MATERIAU/THER_NL";
    let Some(c) = occ.first(key).and_then(|s| s.as_concept()) else {
        return Ok(None);
    };
    let end = |e: Extension| match e {
        Extension::Excluded => CurveEnd::Excluded,
        Extension::Constant => CurveEnd::Constant,
        Extension::Linear => CurveEnd::Linear,
    };
    match &*ex.function(c)? {
        Function::Constant { value, .. } => Ok(Some(Curve::Constant(*value))),
        Function::Tabulated(t) if t.parameter == "TEMP" && t.abscissae().len() >= 2 => {
            Curve::table(
                t.abscissae().to_vec(),
                t.values().to_vec(),
                end(t.left),
                end(t.right),
            )
            .map(Some)
            .map_err(|e| ex.kw_error(at, occ, key, e))
        }
        _ => Err(ex.kw_error(
            at,
            occ,
            key,
            format!(
                "`{}` must be a DEFI_CONSTANTE or a DEFI_FONCTION of TEMP with two points at least",
                c.name
            ),
        )),
    }
}

/// `DEFI_MATERIAU/THER_NL`: λ(T) and the enthalpy β(T), given (`BETA`) or
/// integrated from `RHO_CP` as code_aster does.
fn ther_nl(
    ex: &Executor,
    kw: &Keywords,
) -> Result<Option<Rc<aster_fem::thermal_nl::NlConduction>>, ExecError> {
    use aster_fem::thermal_nl::{Curve, NlConduction};
    let Some(occ) = kw.factor("THER_NL").first() else {
        return Ok(None);
    };
    let at = "DEFI_MATERIAU/THER_NL";
    let lambda = ther_nl_curve(ex, occ, "LAMBDA")?
        .ok_or_else(|| ex.kw_error(at, occ, "LAMBDA", "the conductivity LAMBDA is required"))?;
    let beta = match (
        ther_nl_curve(ex, occ, "BETA")?,
        ther_nl_curve(ex, occ, "RHO_CP")?,
    ) {
        (Some(b), _) => b,
        (None, Some(rho_cp)) => Curve::enthalpy_of(&rho_cp),
        (None, None) => {
            return Err(ex.kw_error(at, occ, "LAMBDA", "BETA or RHO_CP is required with THER_NL"))
        }
    };
    Ok(Some(Rc::new(NlConduction { lambda, beta })))
}

pub fn defi_materiau(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let thermal = ther(ex, kw)?;
    let thermal_nl = ther_nl(ex, kw)?;
    let orthotropic = elas_orth(ex, kw)?;
    if let (Some((o, density)), None) = (orthotropic, kw.factor("ELAS").first()) {
        let m = Material {
            elastic: true,
            density,
            rupt_frag: rupt_frag(ex, kw)?,
            rupt_turon: rupt_turon(ex, kw)?,
            orthotropic: Some(o),
            thermal_nl,
            ..without_elas(thermal)
        };
        return store_result(ex, call, Concept::Material(Rc::new(m)));
    }
    let elas_fo = match kw.factor("ELAS_FO").first() {
        Some(occ) => Some(elas_fo(ex, occ)?),
        None => None,
    };
    let elas = kw.factor("ELAS").first();
    if elas.is_none() && elas_fo.is_none() {
        if let (true, None) = (
            thermal.is_some() || thermal_nl.is_some(),
            PLASTIC_BLOCKS.iter().find(|k| !kw.factor(k).is_empty()),
        ) {
            let m = Material {
                thermal_nl,
                ..without_elas(thermal)
            };
            return store_result(ex, call, Concept::Material(Rc::new(m)));
        }
        return Err(ExecError::new(
            "DEFI_MATERIAU: ELAS (or ELAS_FO) is required (with the plastic behaviours; THER alone makes a thermal material)",
        ));
    }
    // ELAS, or ELAS_FO's values when its functions are constants (NaN
    // and None otherwise: AFFE_MATERIAU resolves them per cell).
    let (young, poisson, density, alpha, amor_alpha, amor_beta) = match (elas, &elas_fo) {
        (Some(elas), _) => {
            let young = elas.f64("E").ok_or_else(|| {
                ex.kw_error("DEFI_MATERIAU", elas, "E", "Young's modulus E is required")
            })?;
            let poisson = elas.f64("NU").ok_or_else(|| {
                ex.kw_error(
                    "DEFI_MATERIAU",
                    elas,
                    "NU",
                    "Poisson's ratio NU is required",
                )
            })?;
            if young <= 0.0 {
                return Err(ex.kw_error(
                    "DEFI_MATERIAU",
                    elas,
                    "E",
                    format!("E must be positive, got {young}"),
                ));
            }
            if !(-1.0 < poisson && poisson < 0.5) {
                return Err(ex.kw_error(
                    "DEFI_MATERIAU",
                    elas,
                    "NU",
                    format!("NU must be in (-1, 0.5), got {poisson}"),
                ));
            }
            (
                young,
                poisson,
                elas.f64("RHO"),
                elas.f64("ALPHA"),
                elas.f64("AMOR_ALPHA"),
                elas.f64("AMOR_BETA"),
            )
        }
        (None, Some(fo)) => {
            let c = |a: Option<&crate::elas_fo::FoArg>| {
                a.and_then(|a| crate::elas_fo::constant(&a.function.0))
            };
            (
                c(Some(&fo.e)).unwrap_or(f64::NAN),
                c(Some(&fo.nu)).unwrap_or(f64::NAN),
                c(fo.rho.as_ref()),
                c(fo.alpha.as_ref()),
                c(fo.amor_alpha.as_ref()),
                c(fo.amor_beta.as_ref()),
            )
        }
        (None, None) => {
            return Err(ExecError::new(
                "DEFI_MATERIAU: ELAS (or ELAS_FO) is required",
            ))
        }
    };
    let ecro_line = match kw.factor("ECRO_LINE").first() {
        Some(occ) => {
            let get = |name: &str, what: &str| {
                occ.f64(name).ok_or_else(|| {
                    ex.kw_error(
                        "DEFI_MATERIAU/ECRO_LINE",
                        occ,
                        name,
                        format!("{what} is required"),
                    )
                })
            };
            let d_sigm_epsi = get("D_SIGM_EPSI", "the slope after yield D_SIGM_EPSI")?;
            let sy = get("SY", "the yield stress SY")?;
            // Checked here so the error points at the keyword (fem checks
            // again when it builds the law).
            // (E resolved per cell from ELAS_FO: checked when the law is
            // built.)
            if young.is_finite() {
                aster_fem::VonMises::linear(young, sy, d_sigm_epsi).map_err(|e| {
                    ex.kw_error("DEFI_MATERIAU/ECRO_LINE", occ, "D_SIGM_EPSI", e.to_string())
                })?;
            }
            Some(EcroLine { d_sigm_epsi, sy })
        }
        None => None,
    };
    let ecro_line_fo = match kw.factor("ECRO_LINE_FO").first() {
        Some(occ) => Some(Rc::new(ecro_line_fo(ex, occ)?)),
        None => None,
    };
    // Constant functions are an ECRO_LINE.
    let ecro_line = match (&ecro_line, &ecro_line_fo) {
        (None, Some(fo)) => match (
            crate::elas_fo::constant(&fo.d_sigm_epsi.function.0),
            crate::elas_fo::constant(&fo.sy.function.0),
        ) {
            (Some(d_sigm_epsi), Some(sy)) => Some(EcroLine { d_sigm_epsi, sy }),
            _ => None,
        },
        _ => ecro_line,
    };
    let mut traction_nappe = None;
    let traction = match kw.factor("TRACTION").first() {
        Some(occ) => {
            let f = ex.required("DEFI_MATERIAU/TRACTION", occ, "SIGM")?;
            match &*ex.function(f)? {
                Function::Nappe(n) => {
                    let nappe = traction_nappe_of(n).map_err(|e| {
                        ex.kw_error(
                            "DEFI_MATERIAU/TRACTION",
                            occ,
                            "SIGM",
                            format!("`{}`: {e}", f.name),
                        )
                    })?;
                    traction_nappe = Some(Rc::new(nappe));
                    None
                }
                Function::Tabulated(t) if !young.is_finite() => Some(t.clone()),
                Function::Tabulated(t) => {
                    aster_fem::VonMises::traction(
                        young,
                        t.abscissae(),
                        t.values(),
                        aster_fem::CurveEnd::Linear,
                    )
                    .map_err(|e| ex.kw_error("DEFI_MATERIAU/TRACTION", occ, "SIGM", e.to_string()))?;
                    Some(t.clone())
                }
                _ => {
                    return Err(ex.kw_error(
                        "DEFI_MATERIAU/TRACTION",
                        occ,
                        "SIGM",
                        format!(
                            "`{}` must be a tabulated function of EPSI (DEFI_FONCTION), or a nappe of TEMP of such functions (DEFI_NAPPE): the traction curve σ(ε)",
                            f.name
                        ),
                    ))
                }
            }
        }
        None => None,
    };
    let lemaitre = match kw.factor("LEMAITRE").first() {
        Some(occ) => {
            let get = |name: &str| {
                occ.f64(name).ok_or_else(|| {
                    ex.kw_error(
                        "DEFI_MATERIAU/LEMAITRE",
                        occ,
                        name,
                        format!("{name} is required"),
                    )
                })
            };
            let coefs = LemaitreCoefs {
                n: get("N")?,
                un_sur_k: get("UN_SUR_K")?,
                un_sur_m: occ.f64("UN_SUR_M").unwrap_or(0.0),
            };
            // Checked here so the error points at the keyword.
            aster_fem::Lemaitre::new(coefs.n, coefs.un_sur_k, coefs.un_sur_m, 1.0, 1e-6, 20)
                .map_err(|e| ex.kw_error("DEFI_MATERIAU/LEMAITRE", occ, "N", e.to_string()))?;
            Some(coefs)
        }
        None => None,
    };
    let ecro_nl = match kw.factor("ECRO_NL").first() {
        Some(occ) => {
            let r0 = occ.f64("R0").ok_or_else(|| {
                ex.kw_error(
                    "DEFI_MATERIAU/ECRO_NL",
                    occ,
                    "R0",
                    "the yield stress R0 is required",
                )
            })?;
            // The catalog's defaults.
            let get = |name: &str, default: f64| occ.f64(name).unwrap_or(default);
            let c = aster_fem::EcroNl {
                r0,
                rh: get("RH", 0.0),
                r1: get("R1", 0.0),
                gamma_1: get("GAMMA_1", 0.0),
                r2: get("R2", 0.0),
                gamma_2: get("GAMMA_2", 0.0),
                rk: get("RK", 0.0),
                p0: get("P0", 0.0),
                gamma_m: get("GAMMA_M", 1.0),
                resi_inte: 1e-6,
            };
            aster_fem::VonMises::nonlinear(c)
                .map_err(|e| ex.kw_error("DEFI_MATERIAU/ECRO_NL", occ, "R0", e.to_string()))?;
            Some(c)
        }
        None => None,
    };
    let ecro_cook = match kw.factor("ECRO_COOK").first() {
        Some(occ) => {
            let req = |name: &str| {
                occ.f64(name).ok_or_else(|| {
                    ex.kw_error(
                        "DEFI_MATERIAU/ECRO_COOK",
                        occ,
                        name,
                        format!("{name} is required"),
                    )
                })
            };
            // nmtevp's defaults: without C, no rate term (C = 0, EPSP0 =
            // 1); without M_PUIS, no thermal softening.
            let c = aster_fem::JohnsonCook {
                a: req("A")?,
                b: req("B")?,
                n: req("N_PUIS")?,
                c: occ.f64("C").unwrap_or(0.0),
                epsp0: if occ.f64("C").is_some() {
                    occ.f64("EPSP0").unwrap_or(1.0)
                } else {
                    1.0
                },
                thermal: match (occ.f64("M_PUIS"), occ.f64("TROOM"), occ.f64("TMELT")) {
                    (Some(m), Some(troom), Some(tmelt)) => Some((m, troom, tmelt)),
                    _ => None,
                },
                resi_inte: 1e-6,
                iter_maxi: 20,
            };
            aster_fem::VonMises::johnson_cook(c)
                .map_err(|e| ex.kw_error("DEFI_MATERIAU/ECRO_COOK", occ, "A", e.to_string()))?;
            Some(c)
        }
        None => None,
    };
    let m = Material {
        elastic: true,
        young,
        poisson,
        density,
        alpha,
        amor_alpha,
        amor_beta,
        ecro_line,
        ecro_line_fo,
        traction,
        traction_nappe,
        lemaitre,
        ecro_nl,
        ecro_cook,
        thermal,
        thermal_nl,
        rupt_frag: rupt_frag(ex, kw)?,
        rupt_turon: rupt_turon(ex, kw)?,
        orthotropic: None,
        composite: None,
        elas_fo: elas_fo.map(Rc::new),
        alpha_fo: None,
        unresolved: None,
    };
    store_result(ex, call, Concept::Material(Rc::new(m)))
}

/// `DEFI_MATERIAU/ELAS_FO`: the functions, checked where they are constant
/// (E > 0, −1 < NU < 0.5); the others are resolved per cell by
/// AFFE_MATERIAU ([`crate::elas_fo`]).
fn elas_fo(ex: &Executor, occ: &Keywords) -> Result<crate::elas_fo::ElasFo, ExecError> {
    let cmd = "DEFI_MATERIAU/ELAS_FO";
    let arg = |name: &'static str| -> Result<Option<crate::elas_fo::FoArg>, ExecError> {
        let Some(c) = occ.concept(name) else {
            return Ok(None);
        };
        let function = ex.function(c)?;
        let span = occ.keyword(name).map(|k| k.span).unwrap_or_default();
        Ok(Some(crate::elas_fo::FoArg {
            keyword: name,
            name: c.name.clone(),
            function: LoadFunction(function),
            span,
        }))
    };
    let e = arg("E")?.ok_or_else(|| ex.kw_error(cmd, occ, "E", "E is required"))?;
    let nu = arg("NU")?.ok_or_else(|| ex.kw_error(cmd, occ, "NU", "NU is required"))?;
    if let Some(v) = crate::elas_fo::constant(&e.function.0) {
        if !(v.is_finite() && v > 0.0) {
            return Err(ex.kw_error(cmd, occ, "E", format!("E must be positive, got {v}")));
        }
    }
    if let Some(v) = crate::elas_fo::constant(&nu.function.0) {
        if !(-1.0 < v && v < 0.5) {
            return Err(ex.kw_error(cmd, occ, "NU", format!("NU must be in (-1, 0.5), got {v}")));
        }
    }
    Ok(crate::elas_fo::ElasFo {
        e,
        nu,
        rho: arg("RHO")?,
        alpha: arg("ALPHA")?,
        amor_alpha: arg("AMOR_ALPHA")?,
        amor_beta: arg("AMOR_BETA")?,
        temp_def_alpha: occ.f64("TEMP_DEF_ALPHA"),
        precision: occ.f64("PRECISION").unwrap_or(1.0),
    })
}

/// `DEFI_MATERIAU/ECRO_LINE_FO`: the slope after yield and the yield
/// stress as functions (of TEMP), evaluated in STAT_NON_LINE at each Gauss
/// point and instant ([`crate::thermo_mat`]).
fn ecro_line_fo(ex: &Executor, occ: &Keywords) -> Result<EcroLineFo, ExecError> {
    let cmd = "DEFI_MATERIAU/ECRO_LINE_FO";
    let arg = |name: &'static str| -> Result<crate::elas_fo::FoArg, ExecError> {
        let c = ex.required(cmd, occ, name)?;
        let function = ex.function(c)?;
        let span = occ.keyword(name).map(|k| k.span).unwrap_or_default();
        Ok(crate::elas_fo::FoArg {
            keyword: if name == "SY" {
                "ECRO_LINE_FO/SY"
            } else {
                "ECRO_LINE_FO/D_SIGM_EPSI"
            },
            name: c.name.clone(),
            function: LoadFunction(function),
            span,
        })
    };
    Ok(EcroLineFo {
        d_sigm_epsi: arg("D_SIGM_EPSI")?,
        sy: arg("SY")?,
    })
}

/// `DEFI_MATERIAU/RUPT_FRAG` (`CZM_LIN_REG`'s parameters).
fn rupt_frag(
    ex: &Executor,
    kw: &aster_eval::Keywords,
) -> Result<Option<crate::concept::RuptFrag>, ExecError> {
    let Some(occ) = kw.factor("RUPT_FRAG").first() else {
        return Ok(None);
    };
    let positive = |name: &str| -> Result<Option<f64>, ExecError> {
        match occ.f64(name) {
            Some(v) if v > 0.0 => Ok(Some(v)),
            Some(v) => Err(ex.kw_error(
                "DEFI_MATERIAU/RUPT_FRAG",
                occ,
                name,
                format!("{name} must be positive, got {v}"),
            )),
            None => Ok(None),
        }
    };
    let gc = positive("GC")?
        .ok_or_else(|| ex.kw_error("DEFI_MATERIAU/RUPT_FRAG", occ, "GC", "GC is required"))?;
    Ok(Some(crate::concept::RuptFrag {
        gc,
        sigm_c: positive("SIGM_C")?,
        pena_adherence: positive("PENA_ADHERENCE")?,
        pena_contact: occ.f64("PENA_CONTACT").unwrap_or(1.0),
    }))
}

/// `DEFI_MATERIAU/RUPT_TURON` (`CZM_TURON`'s parameters; code_aster's
/// `lcejtu` stops on a non-positive K, SIGM_C_N, SIGM_C_T, GC_N or GC_T,
/// `COMPOR4_74`).
fn rupt_turon(
    ex: &Executor,
    kw: &aster_eval::Keywords,
) -> Result<Option<aster_fem::cohesive::Turon>, ExecError> {
    let Some(occ) = kw.factor("RUPT_TURON").first() else {
        return Ok(None);
    };
    let what = "DEFI_MATERIAU/RUPT_TURON";
    let get = |name: &str| -> Result<f64, ExecError> {
        occ.f64(name)
            .ok_or_else(|| ex.kw_error(what, occ, name, format!("{name} is required")))
    };
    let positive = |name: &str| -> Result<f64, ExecError> {
        let v = get(name)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(ex.kw_error(what, occ, name, format!("{name} must be positive, got {v}")))
        }
    };
    let criterion = match occ.str("CRIT_INIT") {
        Some("TURON") => aster_fem::cohesive::TuronCriterion::Turon,
        Some("YE") => aster_fem::cohesive::TuronCriterion::Ye,
        _ => {
            return Err(ex.kw_error(
                what,
                occ,
                "CRIT_INIT",
                "CRIT_INIT='TURON' or 'YE' is required",
            ))
        }
    };
    Ok(Some(aster_fem::cohesive::Turon {
        k: positive("K")?,
        sigma_c_n: positive("SIGM_C_N")?,
        sigma_c_t: positive("SIGM_C_T")?,
        gc_n: positive("GC_N")?,
        gc_t: positive("GC_T")?,
        c_rupt: occ.f64("C_RUPT").unwrap_or(1e-3),
        eta_bk: get("ETA_BK")?,
        criterion,
    }))
}

/// What AFFE_MATERIAU reads (`crate::support`).
pub(crate) const AFFE_MATERIAU: Support = Support {
    values: &[
        Values::new("AFFE_VARC/NOM_VARC", &["TEMP"])
            .why("(aster's command variables: the temperature only)"),
        Values::new("AFFE_VARC/NOM_CHAM", &["TEMP"]),
        Values::listed("AFFE_VARC/PROL_GAUCHE", &["EXCLU", "CONSTANT"]),
        Values::listed("AFFE_VARC/PROL_DROITE", &["EXCLU", "CONSTANT"]),
    ],
    ..Support::keywords(&[
        "MAILLAGE",
        "MODELE",
        "AFFE",
        "AFFE/TOUT",
        "AFFE/GROUP_MA",
        "AFFE/MAILLE",
        "AFFE/MATER",
        "INFO",
        "AFFE_VARC",
        "AFFE_VARC/NOM_VARC",
        "AFFE_VARC/TOUT",
        "AFFE_VARC/GROUP_MA",
        "AFFE_VARC/EVOL",
        "AFFE_VARC/CHAM_GD",
        "AFFE_VARC/NOM_CHAM",
        "AFFE_VARC/VALE_REF",
        "AFFE_VARC/PROL_GAUCHE",
        "AFFE_VARC/PROL_DROITE",
    ])
};

pub fn affe_materiau(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let mesh_id = if let Some(m) = kw.concept("MAILLAGE") {
        m.id
    } else if let Some(m) = kw.concept("MODELE") {
        match ex.thermal_model(m) {
            Ok(t) => t.mesh,
            Err(_) => ex.model(m)?.mesh,
        }
    } else {
        return Err(ExecError::new("AFFE_MATERIAU: give MAILLAGE or MODELE"));
    };
    let mesh = ex.mesh_by_id(mesh_id)?;
    let mut cells = BTreeMap::new();
    for occ in kw.factor("AFFE") {
        let mat = ex.required("AFFE_MATERIAU", occ, "MATER")?;
        let mat = ex.material(mat)?;
        let sel = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_MATERIAU/AFFE: {e}")))?;
        for c in sel {
            cells.insert(c, mat.clone());
        }
    }
    let temperature = affe_varc(ex, kw, &mesh)?;
    let locate = |span| ex.location(span).unwrap_or_else(|| "DEFI_MATERIAU".into());
    let cells = crate::elas_fo::resolve_cells(&mesh, cells, temperature.as_deref(), &locate);
    store_result(
        ex,
        call,
        Concept::MaterialField(Rc::new(MaterialField {
            mesh: mesh_id,
            cells,
            temperature,
        })),
    )
}

/// `AFFE_VARC(NOM_VARC='TEMP')`: the temperature of the cells, from a
/// result's `TEMP` fields (`EVOL`, `NOM_CHAM='TEMP'`) or one nodal field
/// (`CHAM_GD`), with its reference `VALE_REF`.
fn affe_varc(
    ex: &Executor,
    kw: &aster_eval::Keywords,
    mesh: &aster_mesh::Mesh,
) -> Result<Option<Rc<crate::concept::Temperature>>, ExecError> {
    let occs = kw.factor("AFFE_VARC");
    if occs.is_empty() {
        return Ok(None);
    }
    let [occ] = occs else {
        return Err(ExecError::new(
            "AFFE_MATERIAU/AFFE_VARC: one occurrence (one temperature) only",
        ));
    };
    let cmd = "AFFE_MATERIAU";
    let tref = occ
        .f64("VALE_REF")
        .ok_or_else(|| ex.kw_error(cmd, occ, "NOM_VARC", "VALE_REF is required with TEMP"))?;
    // Neither TOUT nor GROUP_MA: the whole mesh, as code_aster.
    let cells: std::collections::BTreeSet<_> = if occ.contains("GROUP_MA") {
        select::cells(occ, mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_MATERIAU/AFFE_VARC: {e}")))?
            .into_iter()
            .collect()
    } else {
        (0..mesh.cells.len() as u32)
            .map(aster_mesh::CellId)
            .collect()
    };
    let nodal = |f: &crate::field::Field, what: &str| -> Result<Rc<Vec<f64>>, ExecError> {
        let crate::field::Field::Nodal(f) = f else {
            return Err(ex.kw_error(
                cmd,
                occ,
                what,
                "the temperature is a nodal field (NOEU_TEMP_R)",
            ));
        };
        Ok(Rc::new(f.per_node("TEMP", mesh.node_count())))
    };
    let mut fields = Vec::new();
    let mut shell = None;
    if let Some(r) = occ.concept("EVOL") {
        let result = ex.result(r)?;
        let name = occ.str("NOM_CHAM").unwrap_or("TEMP");
        // A temperature through the shells' thickness (CREA_RESU/PREP_VARC):
        // TEMP_MIL, TEMP_INF, TEMP_SUP per node, no TEMP.
        let mut layers: Vec<(f64, Rc<[Vec<f64>; 3]>)> = Vec::new();
        for step in &result.steps {
            if let Some(f) = step.fields.get(name) {
                if result.prep_varc {
                    let crate::field::Field::Nodal(nf) = f else {
                        return Err(ex.kw_error(
                            cmd,
                            occ,
                            "EVOL",
                            "the temperature is a nodal field",
                        ));
                    };
                    let n = mesh.node_count();
                    layers.push((
                        step.inst,
                        Rc::new([
                            nf.per_node("TEMP_MIL", n),
                            nf.per_node("TEMP_INF", n),
                            nf.per_node("TEMP_SUP", n),
                        ]),
                    ));
                    fields.push((step.inst, Rc::new(vec![f64::NAN; n])));
                } else {
                    fields.push((step.inst, nodal(f, "EVOL")?));
                }
            }
        }
        if result.prep_varc {
            layers.sort_by(|a, b| a.0.total_cmp(&b.0));
            shell = Some(layers.into_iter().map(|(_, l)| l).collect());
        }
        if fields.is_empty() {
            return Err(ex.kw_error(
                cmd,
                occ,
                "EVOL",
                format!("`{}` holds no {name} field", r.name),
            ));
        }
        fields.sort_by(|a, b| a.0.total_cmp(&b.0));
    } else if let Some(c) = occ.concept("CHAM_GD") {
        fields.push((0.0, nodal(&*ex.field(c)?, "CHAM_GD")?));
    }
    Ok(Some(Rc::new(crate::concept::Temperature {
        cells,
        tref,
        fields,
        constant_before: occ.str("PROL_GAUCHE") == Some("CONSTANT"),
        constant_after: occ.str("PROL_DROITE") == Some("CONSTANT"),
        shell,
        at: kw
            .keyword("AFFE_VARC")
            .and_then(|k| ex.location(k.span))
            .unwrap_or_else(|| "AFFE_VARC".into()),
    })))
}

/// What AFFE_MODELE reads (`crate::support`).
pub(crate) const AFFE_MODELE: Support = Support {
    values: &[
        Values::new("AFFE/PHENOMENE", &["MECANIQUE", "THERMIQUE"])
            .why("(aster solves mechanics and linear heat conduction (THER_LINEAIRE))"),
        Values::listed("AFFE/MODELISATION", &MODELISATIONS),
    ],
    ..Support::keywords(&[
        "MAILLAGE",
        "AFFE",
        "AFFE/TOUT",
        "AFFE/GROUP_MA",
        "AFFE/MAILLE",
        "AFFE/PHENOMENE",
        "AFFE/MODELISATION",
        "AFFE_SOUS_STRUC",
        "AFFE_SOUS_STRUC/TOUT",
        "AFFE_SOUS_STRUC/SUPER_MAILLE",
        "AFFE_SOUS_STRUC/PHENOMENE",
        "INFO",
        "VERI_JACOBIEN",
        "VERI_NORM_IFS",
        "VERI_PLAN",
        "DISTRIBUTION",
        "DISTRIBUTION/*",
    ])
};

/// The modelisations AFFE_MODELE accepts: the mechanical ones and the
/// thermal `PLAN` (`AXIS` and `3D` are both).
const MODELISATIONS: [&str; Modelisation::KEYWORDS.len() + 1] = {
    let mut all = [""; Modelisation::KEYWORDS.len() + 1];
    let mut i = 0;
    while i < Modelisation::KEYWORDS.len() {
        all[i] = Modelisation::KEYWORDS[i];
        i += 1;
    }
    all[Modelisation::KEYWORDS.len()] = "PLAN";
    all
};

pub fn affe_modele(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let thermal = kw
        .factor("AFFE")
        .iter()
        .map(|occ| occ.str("PHENOMENE") == Some("THERMIQUE"))
        .collect::<Vec<_>>();
    if thermal.iter().any(|&t| t) {
        if !thermal.iter().all(|&t| t) {
            return Err(ExecError::new(
                "AFFE_MODELE: PHENOMENE='THERMIQUE' and 'MECANIQUE' in one model: define one model per phenomenon",
            ));
        }
        return super::thermal::affe_modele(ex, call);
    }
    let mesh_ref = ex.required("AFFE_MODELE", kw, "MAILLAGE")?;
    let mesh = ex.mesh(mesh_ref)?;
    let mut cells = BTreeMap::new();
    let mut reduced = std::collections::BTreeSet::new();
    let mut mixed = std::collections::BTreeSet::new();
    let mut edges = std::collections::BTreeSet::new();
    // Where MODELISATION='3D' is first written, to name it when no volume
    // cell receives it.
    let mut solid3d_at = None;
    for occ in kw.factor("AFFE") {
        let names: Vec<&str> = occ
            .simple("MODELISATION")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        let [name] = names.as_slice() else {
            return Err(ex.kw_error(
                "AFFE_MODELE",
                occ,
                "MODELISATION",
                "exactly one modelisation per occurrence is supported",
            ));
        };
        let Some((modelisation, under_integrated)) = Modelisation::from_keyword_si(name) else {
            let span = occ
                .keyword("MODELISATION")
                .map(|k| k.span)
                .unwrap_or_default();
            return Err(ex.unsupported(
                &format!(
                    "AFFE_MODELE/AFFE/MODELISATION='{name}' (supported: {})",
                    Modelisation::KEYWORDS.join(", ")
                ),
                span,
            ));
        };
        if modelisation == Modelisation::Solid3D && solid3d_at.is_none() {
            solid3d_at = Some(occ);
        }
        let sel = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_MODELE/AFFE: {e}")))?;
        for c in sel {
            let ty = mesh.cell(c).ty;
            // As code_aster: a modelisation goes only to the cells it has
            // elements for (a 2D modelisation on TOUT skips volumes…).
            let fits = match modelisation {
                Modelisation::Discrete2D
                | Modelisation::Discrete3D
                | Modelisation::DiscreteRot3D => ty.dim() <= 1,
                // code_aster's MECA_POU_D_E, MECA_POU_D_T, MECA_BARRE: SEG2.
                Modelisation::BeamEuler | Modelisation::BeamTimoshenko | Modelisation::Bar => {
                    ty == aster_mesh::CellType::SEG2
                }
                Modelisation::Solid3D => ty.dim() >= 2,
                // code_aster's plate elements: MEDKTR3, MEDKQU4 (DKT),
                // MEDSTR3, MEDSQU4 (DST), MET3TR3, MEQ4QU4 (Q4G)
                // (FORCE_ARETE loads the edges' nodes directly: loads_more).
                Modelisation::Plate(_) => {
                    matches!(
                        ty,
                        aster_mesh::CellType::TRIA3 | aster_mesh::CellType::QUAD4
                    )
                }
                // code_aster's MEGMTR3, MEGMTR6, MEGMQU4, MEGMQU8.
                Modelisation::GridMembrane => matches!(
                    ty,
                    aster_mesh::CellType::TRIA3
                        | aster_mesh::CellType::TRIA6
                        | aster_mesh::CellType::QUAD4
                        | aster_mesh::CellType::QUAD8
                ),
                // code_aster's MEGCTR3, MEGCQU4.
                Modelisation::GridExcentre => matches!(
                    ty,
                    aster_mesh::CellType::TRIA3 | aster_mesh::CellType::QUAD4
                ),
                // code_aster's MEC3QU9H (QUAD9) and MEC3TR7H (TRIA7).
                Modelisation::Coque3d => {
                    matches!(
                        ty,
                        aster_mesh::CellType::QUAD9 | aster_mesh::CellType::TRIA7
                    )
                }
                // code_aster's MFPLQU4 (QUAD4) and MFPLQU8 (QUAD8); the
                // latter's element (te0206-family) is not reproduced.
                Modelisation::PlaneJoint => {
                    if ty == aster_mesh::CellType::QUAD8 {
                        return Err(ex.kw_error(
                            "AFFE_MODELE",
                            occ,
                            "MODELISATION",
                            format!(
                                "not supported yet: MODELISATION='PLAN_JOINT' on QUAD8 cell {} (code_aster's MFPLQU8); the QUAD4 joint (MFPLQU4) is",
                                crate::select::cell_name(&mesh, c)
                            ),
                        ));
                    }
                    ty == aster_mesh::CellType::QUAD4
                }
                _ => (1..=2).contains(&ty.dim()),
            };
            if modelisation == Modelisation::Solid3D && ty.dim() == 1 {
                edges.insert(c);
            } else if fits {
                edges.remove(&c);
            }
            if !fits {
                continue;
            }
            let continuum = ty.dim() as usize == modelisation.dim();
            let inco = Modelisation::is_mixed_keyword(name);
            if inco && continuum {
                let has = crate::fembridge::hypothesis(modelisation)
                    .is_some_and(|h| aster_fem::mixed_upg::has_element(ty, h));
                // No element of the modelisation (a TRIA3, QUAD4, HEXA8…):
                // the cell keeps an earlier occurrence's, as code_aster.
                if !has {
                    continue;
                }
                mixed.insert(c);
                reduced.remove(&c);
            } else if continuum {
                mixed.remove(&c);
            }
            if under_integrated && continuum && !inco {
                match si_element(modelisation, ty) {
                    SiElement::Reduced => {
                        reduced.insert(c);
                    }
                    // No element of the modelisation: the cell keeps an
                    // earlier occurrence's (code_aster's AFFE_MODELE).
                    SiElement::None => continue,
                    SiElement::Stabilised => {
                        return Err(ex.kw_error(
                            "AFFE_MODELE",
                            occ,
                            "MODELISATION",
                            format!(
                                "not supported yet: MODELISATION='{name}' on {} cells (code_aster's one-point element with hourglass stabilisation in 2D; QUAD8, and in 3D_SI HEXA8, HEXA20 and TETRA10 cells are supported)",
                                ty.name()
                            ),
                        ));
                    }
                }
            } else {
                reduced.remove(&c);
            }
            cells.insert(c, modelisation);
        }
    }
    if cells.is_empty() && !kw.contains("AFFE_SOUS_STRUC") {
        return Err(ExecError::new(
            "AFFE_MODELE: no cell of the mesh received an element",
        ));
    }
    // A 3D model whose 3D elements are all faces (a 2D mesh, or only
    // surface groups) has no stiffness: say so here, not as a singular
    // system later.
    if let Some(occ) = solid3d_at {
        let has_volume = cells
            .iter()
            .any(|(c, m)| *m == Modelisation::Solid3D && mesh.cell(*c).ty.dim() == 3);
        if !has_volume {
            return Err(ex.kw_error(
                "AFFE_MODELE",
                occ,
                "MODELISATION",
                "MODELISATION='3D' needs volume cells, and the cells it is given have none \
                 (a 2D mesh takes D_PLAN, C_PLAN or AXIS)",
            ));
        }
    }
    let mut rotations = vec![false; mesh.node_count()];
    for (c, m) in &cells {
        if m.has_rotations() {
            for n in &mesh.cell(*c).nodes {
                rotations[n.0 as usize] = true;
            }
        }
    }
    let substructures = super::substructure::affe_sous_struc(ex, call, mesh_ref.id)?;
    let model = ModelDef {
        mesh: mesh_ref.id,
        cells,
        reduced,
        mixed,
        edges,
        rotations,
        substructures,
    };
    store_result(ex, call, Concept::Model(Rc::new(model)))
}

/// What an under-integrated (`_SI`) modelisation puts on a continuum cell.
enum SiElement {
    /// Reduced integration (`MEDPQS8`, `MECPQS8`, `MEAXQS8`,
    /// `MECA_HEXS20`, `MECA_TETRS10`), or for HEXA8 the stabilised
    /// one-point `MECA_HEXS8`.
    Reduced,
    /// One point with hourglass stabilisation in 2D (`MEDPQS4`,
    /// `MECPQS4`): not reproduced.
    Stabilised,
    /// No element of the modelisation for this cell type.
    None,
}

/// code_aster's catalogue (`phenomenons_modelisations.py`): `D_PLAN_SI`
/// and `C_PLAN_SI` have QUAD8 and QUAD4; `AXIS_SI` QUAD8 only; `3D_SI`
/// HEXA20, HEXA8 and TETRA10.
fn si_element(m: Modelisation, ty: aster_mesh::CellType) -> SiElement {
    use aster_mesh::CellType as T;
    match (m, ty) {
        (_, T::QUAD8) if m != Modelisation::Solid3D => SiElement::Reduced,
        (Modelisation::PlaneStrain | Modelisation::PlaneStress, T::QUAD4) => SiElement::Stabilised,
        (Modelisation::Solid3D, T::HEXA20 | T::TETRA10) => SiElement::Reduced,
        // MECA_HEXS8: one point with hourglass stabilisation (aster-fem's
        // `hexs8`, in the non-linear operators).
        (Modelisation::Solid3D, T::HEXA8) => SiElement::Reduced,
        _ => SiElement::None,
    }
}

/// The DISCRET keywords AFFE_CARA_ELEM reads.
const CARA_DISCRET: [&str; 16] = [
    "MODELE",
    "INFO",
    "DISCRET",
    "DISCRET/GROUP_MA",
    "DISCRET/MAILLE",
    "DISCRET/CARA",
    "DISCRET/VALE",
    "DISCRET/REPERE",
    "DISCRET/SYME",
    "DISCRET_2D",
    "DISCRET_2D/GROUP_MA",
    "DISCRET_2D/MAILLE",
    "DISCRET_2D/CARA",
    "DISCRET_2D/VALE",
    "DISCRET_2D/REPERE",
    "DISCRET_2D/SYME",
];

/// What AFFE_CARA_ELEM reads (`crate::support`): DISCRET(_2D) here, COQUE
/// in [`super::cara_coque`], POUTRE in [`super::cara_poutre`], MASSIF in
/// [`super::cara_massif`].
pub(crate) const AFFE_CARA_ELEM: Support = Support {
    values: &[
        Values::listed(
            "DISCRET/CARA",
            &[
                "K_T_D_L", "K_T_D_N", "M_T_D_N", "M_T_N", "M_T_L", "K_TR_D_L", "K_TR_D_N",
                "M_TR_D_N", "M_TR_D_L", "M_TR_N", "M_TR_L",
            ],
        ),
        Values::listed(
            "DISCRET_2D/CARA",
            &["K_T_D_L", "K_T_D_N", "M_T_D_N", "M_T_N", "M_T_L"],
        ),
        super::cara_coque::VALUES[0],
        super::cara_poutre::VALUES[0],
        super::cara_poutre::VALUES[1],
        super::cara_poutre::VALUES[2],
        super::cara_poutre::VALUES[3],
        super::cara_grille::VALUES[0],
    ],
    ..Support::keywords(&crate::support::joined::<_, 56>(
        &crate::support::joined::<_, 46>(
            &crate::support::joined::<_, 41>(
                &crate::support::joined::<_, 27>(&CARA_DISCRET, &super::cara_coque::KEYWORDS),
                &super::cara_poutre::KEYWORDS,
            ),
            &super::cara_massif::KEYWORDS,
        ),
        &super::cara_grille::KEYWORDS,
    ))
};

pub fn affe_cara_elem(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model_ref = ex.required("AFFE_CARA_ELEM", kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let mut discrete = Vec::new();
    let mut masses = Vec::new();
    let shells = super::cara_coque::shells(ex, kw, &mesh, &model)?;
    let beams = super::cara_poutre::beams(ex, kw, &mesh)?;
    let bars = super::cara_poutre::bars(ex, kw, &mesh)?;
    let massif = super::cara_massif::frames(ex, kw, &mesh)?;
    let grids = super::cara_grille::grids(ex, kw, &mesh)?;
    for f in ["DISCRET", "DISCRET_2D"] {
        for occ in kw.factor(f) {
            let cara = occ.str("CARA").unwrap_or_default().to_string();
            let dim = if f == "DISCRET_2D" { 2 } else { 3 };
            if let Some(m) = discrete_mass(ex, f, occ, &cara, dim, &mesh)? {
                masses.push(m);
                continue;
            }
            let rotational = cara == "K_TR_D_L" || cara == "K_TR_D_N";
            if !(cara == "K_T_D_L" || cara == "K_T_D_N" || rotational && dim == 3) {
                let span = occ.keyword("CARA").map(|k| k.span).unwrap_or_default();
                return Err(ex.unsupported(
                    &format!(
                        "AFFE_CARA_ELEM/{f}/CARA='{cara}' (supported: K_T_D_L, K_T_D_N, M_T_D_N, M_T_N, M_T_L; in DISCRET also K_TR_D_L, K_TR_D_N, M_TR_D_N, M_TR_D_L, M_TR_N, M_TR_L)"
                    ),
                    span,
                ));
            }
            let values = reals(occ, "VALE");
            let dim = if rotational { 6 } else { dim };
            if values.len() != dim {
                return Err(ex.kw_error(
                    "AFFE_CARA_ELEM",
                    occ,
                    "VALE",
                    format!(
                        "{cara} in {f} needs {dim} stiffnesses, got {}",
                        values.len()
                    ),
                ));
            }
            let cells = select::cells(occ, &mesh, "")
                .map_err(|e| ExecError::new(format!("AFFE_CARA_ELEM/{f}: {e}")))?;
            let want_dim = if cara == "K_T_D_L" || cara == "K_TR_D_L" {
                1
            } else {
                0
            };
            if let Some(bad) = select::misfit(&mesh, &cells, |c| c.ty.dim() == want_dim) {
                return Err(ExecError::new(format!(
                    "AFFE_CARA_ELEM/{f}: {cara} applies to {} cells, but {bad}",
                    if want_dim == 1 { "SEG2" } else { "POI1" },
                )));
            }
            discrete.push(DiscreteStiffness {
                cells,
                cara,
                values,
                local: occ.str("REPERE") == Some("LOCAL"),
            });
        }
    }
    store_result(
        ex,
        call,
        Concept::CaraElem(Rc::new(CaraElem {
            model: model_ref.id,
            discrete,
            masses,
            shells,
            beams,
            bars,
            massif,
            grids,
        })),
    )
}

/// A mass of `DISCRET(_2D)` (`M_T_D_N`, `M_TR_D_N`, `M_T_N`, `M_TR_N` on
/// POI1, `M_T_L`, `M_TR_D_L`, `M_TR_L` on SEG2; symmetric, upper triangle
/// by columns), or `None` for another `CARA`.
fn discrete_mass(
    ex: &Executor,
    factor: &str,
    occ: &Keywords,
    cara: &str,
    dim: usize,
    mesh: &aster_mesh::Mesh,
) -> Result<Option<DiscreteMassDef>, ExecError> {
    let (nodes, count) = match cara {
        "M_T_D_N" => (1, 1),
        "M_T_N" => (1, dim * (dim + 1) / 2),
        "M_T_L" => (2, 2 * dim * (2 * dim + 1) / 2),
        // m, Ixx, Iyy, Izz, Ixy, Iyz, Ixz, ex, ey, ez.
        "M_TR_D_N" if dim == 3 => (1, 10),
        // m, Ixx, Iyy, Izz at each node.
        "M_TR_D_L" if dim == 3 => (2, 4),
        "M_TR_N" if dim == 3 => (1, 21),
        "M_TR_L" if dim == 3 => (2, 78),
        _ => return Ok(None),
    };
    let at = format!("AFFE_CARA_ELEM/{factor}");
    if occ.str("SYME") == Some("NON") {
        let span = occ.keyword("SYME").map(|k| k.span).unwrap_or_default();
        return Err(ex.unsupported(&format!("{at}/SYME='NON' (a non-symmetric {cara})"), span));
    }
    let values = reals(occ, "VALE");
    if values.len() != count {
        return Err(ex.kw_error(
            &at,
            occ,
            "VALE",
            format!(
                "{cara} in {factor} needs {count} values, got {}",
                values.len()
            ),
        ));
    }
    let cells = select::cells(occ, mesh, "").map_err(|e| ExecError::new(format!("{at}: {e}")))?;
    if let Some(bad) = select::misfit(mesh, &cells, |c| {
        c.nodes.len() == nodes && c.ty.dim() as usize + 1 == nodes
    }) {
        return Err(ExecError::new(format!(
            "{at}: {cara} applies to {} cells, but {bad}",
            if nodes == 2 { "SEG2" } else { "POI1" },
        )));
    }
    Ok(Some(DiscreteMassDef {
        cells,
        cara: cara.to_string(),
        values,
        local: occ.str("REPERE") == Some("LOCAL"),
    }))
}

/// What DEFI_FONCTION reads (`crate::support`).
pub(crate) const DEFI_FONCTION: Support = Support::keywords(&[
    "NOM_PARA",
    "NOM_RESU",
    "VALE",
    "ABSCISSE",
    "ORDONNEE",
    "INTERPOL",
    "PROL_GAUCHE",
    "PROL_DROITE",
    "VERIF",
    "INFO",
    "TITRE",
]);

pub fn defi_fonction(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let para = kw.str("NOM_PARA").unwrap_or("INST");
    let mut f = if kw.contains("VALE") {
        Tabulated::from_pairs(para, &reals(kw, "VALE"))
    } else if kw.contains("ABSCISSE") {
        let xs = reals(kw, "ABSCISSE");
        let ys = reals(kw, "ORDONNEE");
        if xs.len() != ys.len() {
            return Err(ex.kw_error(
                "DEFI_FONCTION",
                kw,
                "ORDONNEE",
                format!("{} ordinates for {} abscissae", ys.len(), xs.len()),
            ));
        }
        Tabulated::new(para, xs, ys)
    } else {
        return Err(ExecError::new("DEFI_FONCTION: give VALE (or ABSCISSE and ORDONNEE); VALE_C/NOEUD_PARA are not supported yet"));
    }
    .map_err(|e| ex.kw_error("DEFI_FONCTION", kw, "VALE", e.to_string()))?;
    f.result = kw.str("NOM_RESU").map(str::to_string);
    super::functions::apply_options(ex, "DEFI_FONCTION", kw, &mut f)?;
    store_result(ex, call, Concept::Function(Rc::new(Function::Tabulated(f))))
}

/// What DEFI_NAPPE reads (`crate::support`).
pub(crate) const DEFI_NAPPE: Support = Support::keywords(&[
    "NOM_PARA",
    "NOM_RESU",
    "PARA",
    "FONCTION",
    "NOM_PARA_FONC",
    "DEFI_FONCTION",
    "DEFI_FONCTION/VALE",
    "DEFI_FONCTION/INTERPOL",
    "DEFI_FONCTION/PROL_DROITE",
    "DEFI_FONCTION/PROL_GAUCHE",
    "INTERPOL",
    "PROL_DROITE",
    "PROL_GAUCHE",
    "INFO",
    "VERIF",
    "TITRE",
]);

/// DEFI_NAPPE (code_aster's op0004): a function of `NOM_PARA` and
/// `NOM_PARA_FONC`, one function of the second per `PARA` value, given
/// as `FONCTION` (DEFI_FONCTION or DEFI_CONSTANTE concepts, their
/// parameter the second one) or as `DEFI_FONCTION` occurrences (`VALE`,
/// its abscissae sorted as code_aster does). `VERIF='CROISSANT'`: `PARA`
/// must increase strictly; otherwise the values are sorted, each with its
/// function (`ordonn`).
pub fn defi_nappe(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    const CMD: &str = "DEFI_NAPPE";
    let kw = &call.keywords;
    let para = reals(kw, "PARA");
    let mut functions: Vec<Function> = Vec::new();
    let parameter_fonc;
    if kw.contains("FONCTION") {
        let mut own: Option<String> = None;
        for s in kw.simple("FONCTION") {
            let c = s
                .as_concept()
                .ok_or_else(|| ex.kw_error(CMD, kw, "FONCTION", "functions are required"))?;
            let f = ex.function(c)?;
            match &*f {
                Function::Tabulated(t) => {
                    if own.as_ref().is_some_and(|p| *p != t.parameter) {
                        return Err(ex.kw_error(
                            CMD,
                            kw,
                            "FONCTION",
                            format!(
                                "the functions must share their parameter: {} is a function of {}, the first of {}",
                                c.name,
                                t.parameter,
                                own.unwrap_or_default()
                            ),
                        ));
                    }
                    own = Some(t.parameter.clone());
                }
                Function::Constant { .. } => {}
                _ => {
                    return Err(ex.kw_error(
                        CMD,
                        kw,
                        "FONCTION",
                        format!(
                            "{} is not a tabulated function (DEFI_FONCTION, DEFI_CONSTANTE)",
                            c.name
                        ),
                    ))
                }
            }
            functions.push((*f).clone());
        }
        parameter_fonc = own.unwrap_or_else(|| "TOUTPARA".to_string());
    } else {
        parameter_fonc = kw.str("NOM_PARA_FONC").unwrap_or("TOUTPARA").to_string();
        for occ in kw.factor("DEFI_FONCTION") {
            let vale = reals(occ, "VALE");
            if !vale.len().is_multiple_of(2) {
                return Err(ex.kw_error(
                    CMD,
                    occ,
                    "VALE",
                    format!(
                        "VALE must hold (abscissa, value) pairs, but it has {} numbers",
                        vale.len()
                    ),
                ));
            }
            // code_aster sorts a function's points by abscissa (uttrif).
            let mut points: Vec<(f64, f64)> = vale.chunks(2).map(|p| (p[0], p[1])).collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let (xs, ys): (Vec<f64>, Vec<f64>) = points.into_iter().unzip();
            let mut t = Tabulated::new(&parameter_fonc, xs, ys)
                .map_err(|e| ex.kw_error(CMD, occ, "VALE", e.to_string()))?;
            super::functions::apply_options(ex, CMD, occ, &mut t)?;
            functions.push(Function::Tabulated(t));
        }
    }
    let nappe = nappe(ex, CMD, kw, para, functions, parameter_fonc)?;
    store_result(ex, call, Concept::Function(Rc::new(Function::Nappe(nappe))))
}

/// The nappe of `NOM_PARA` (the command's keywords `kw`) whose function at
/// `para[i]` is `functions[i]` (their parameter `parameter_fonc`), as
/// code_aster's op0004 builds it: one function per value, `PARA` strictly
/// increasing under `VERIF='CROISSANT'` and sorted otherwise, `INTERPOL`,
/// `PROL_GAUCHE`, `PROL_DROITE` of the parameter. Shared by DEFI_NAPPE and
/// LIRE_FONCTION(TYPE='NAPPE').
pub(crate) fn nappe(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    para: Vec<f64>,
    functions: Vec<Function>,
    parameter_fonc: String,
) -> Result<crate::function::Nappe, ExecError> {
    use crate::function::Nappe;
    if para.len() != functions.len() || para.is_empty() {
        return Err(ex.kw_error(
            cmd,
            kw,
            "PARA",
            format!(
                "{} parameter values for {} functions (UTILITAI8_3: one function per value)",
                para.len(),
                functions.len()
            ),
        ));
    }
    let mut pairs: Vec<(f64, Function)> = para.into_iter().zip(functions).collect();
    if kw.str("VERIF") == Some("CROISSANT") {
        if pairs
            .windows(2)
            .any(|w| w[0].0.partial_cmp(&w[1].0) != Some(std::cmp::Ordering::Less))
        {
            return Err(ex.kw_error(
                cmd,
                kw,
                "PARA",
                "PARA must increase strictly (VERIF='CROISSANT', UTILITAI2_72)",
            ));
        }
    } else {
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    if pairs.windows(2).any(|w| w[0].0 == w[1].0) {
        return Err(ex.kw_error(
            cmd,
            kw,
            "PARA",
            "two functions for the same parameter value",
        ));
    }
    let (scale_x, scale_y, left, right) = super::functions::options(
        ex,
        cmd,
        kw,
        (
            Scale::Linear,
            Scale::Linear,
            Extension::Excluded,
            Extension::Excluded,
        ),
    )?;
    let (para, functions) = pairs.into_iter().unzip();
    let nappe = Nappe {
        parameter: kw.str("NOM_PARA").unwrap_or("TOUTPARA").to_string(),
        parameter_fonc,
        para,
        functions,
        scale_x,
        scale_y,
        left,
        right,
    };
    Ok(nappe)
}

/// What DEFI_CONSTANTE reads (`crate::support`).
pub(crate) const DEFI_CONSTANTE: Support = Support::keywords(&["VALE", "NOM_RESU", "TITRE"]);

pub fn defi_constante(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let value = kw
        .f64("VALE")
        .ok_or_else(|| ex.kw_error("DEFI_CONSTANTE", kw, "VALE", "a real value is required"))?;
    let f = Function::Constant {
        parameter: "TOUTPARA".into(),
        value,
    };
    store_result(ex, call, Concept::Function(Rc::new(f)))
}

/// What DEFI_LIST_REEL reads (`crate::support`).
pub(crate) const DEFI_LIST_REEL: Support = Support::keywords(&[
    "DEBUT",
    "INTERVALLE",
    "INTERVALLE/JUSQU_A",
    "INTERVALLE/NOMBRE",
    "INTERVALLE/PAS",
    "VALE",
    "INFO",
    "TITRE",
]);

pub fn defi_list_reel(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let values = if kw.contains("VALE") {
        list::from_values(&reals(kw, "VALE"))
    } else {
        let start = kw.f64("DEBUT").ok_or_else(|| {
            ex.kw_error(
                "DEFI_LIST_REEL",
                kw,
                "DEBUT",
                "DEBUT is required with INTERVALLE",
            )
        })?;
        let mut intervals = Vec::new();
        for occ in kw.factor("INTERVALLE") {
            let end = occ.f64("JUSQU_A").ok_or_else(|| {
                ex.kw_error("DEFI_LIST_REEL", occ, "JUSQU_A", "JUSQU_A is required")
            })?;
            if let Some(n) = occ.first("NOMBRE").and_then(|s| s.as_i64()) {
                intervals.push(Interval::Count {
                    end,
                    count: n.max(0) as usize,
                });
            } else if let Some(step) = occ.f64("PAS") {
                intervals.push(Interval::Step { end, step });
            } else {
                return Err(ex.kw_error("DEFI_LIST_REEL", occ, "JUSQU_A", "give NOMBRE or PAS"));
            }
        }
        list::from_intervals(start, &intervals)
    }
    .map_err(|e| ExecError::new(format!("DEFI_LIST_REEL: {e}")))?;
    store_result(ex, call, Concept::RealList(Rc::new(values)))
}

/// What DEFI_LIST_INST reads (`crate::support`).
pub(crate) const DEFI_LIST_INST: Support = Support {
    values: &[
        Values::new("METHODE", &["MANUEL"]),
        Values::new("DEFI_LIST/METHODE", &["MANUEL"]),
        Values::new("ECHEC/EVENEMENT", &["ERREUR", "INTERPENETRATION"]),
        Values::new("ECHEC/ACTION", &["ARRET", "DECOUPE", "ADAPT_COEF_PENA"]),
        // SUBD_METHODE='AUTO' chooses the pieces by extrapolating the
        // residuals; it is read as MANUEL's default cutting (4 pieces, 3
        // levels) bounded by its SUBD_PAS_MINI: the converged steps are
        // the same, the path between them may differ.
        Values::new("ECHEC/SUBD_METHODE", &["MANUEL", "AUTO"]),
    ],
    ..Support::keywords(&[
        // code_aster 17 writes METHODE at the top, older files in DEFI_LIST.
        "METHODE",
        "DEFI_LIST",
        "DEFI_LIST/METHODE",
        "DEFI_LIST/LIST_INST",
        "DEFI_LIST/VALE",
        "INFO",
        // Failure handling (code_aster's semantics): a failed increment
        // is cut (DECOUPE) or stops the run (ARRET).
        "ECHEC",
        "ECHEC/EVENEMENT",
        "ECHEC/ACTION",
        "ECHEC/SUBD_METHODE",
        "ECHEC/SUBD_PAS",
        "ECHEC/SUBD_PAS_MINI",
        "ECHEC/SUBD_NIVEAU",
        // EVENEMENT='INTERPENETRATION' with ACTION='ADAPT_COEF_PENA': the
        // penalty of a discrete penalised contact doubled (docs/friction.md).
        "ECHEC/PENE_MAXI",
        "ECHEC/COEF_MAXI",
    ])
};

pub fn defi_list_inst(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let Some(def) = kw.factor("DEFI_LIST").first() else {
        return Err(ExecError::new("DEFI_LIST_INST: DEFI_LIST is required"));
    };
    // ECHEC is present by default (EVENEMENT='ERREUR', ACTION='DECOUPE',
    // SUBD_PAS=4, SUBD_NIVEAU=3, SUBD_PAS_MINI=0).
    let mut subdivision = Some(aster_fem::Subdivision::default());
    let mut penalty_adaptation = None;
    for occ in kw.factor("ECHEC") {
        if occ.str("EVENEMENT") == Some("INTERPENETRATION") {
            // code_aster's `nmevin` (the event, on a converged increment)
            // and `nmadcp` (its action).
            if occ.str("ACTION") != Some("ADAPT_COEF_PENA") {
                let span = occ.keyword("ACTION").map_or(call.span, |k| k.span);
                return Err(ex.unsupported(
                    &format!(
                        "DEFI_LIST_INST/ECHEC/EVENEMENT='INTERPENETRATION' with ACTION='{}' (ADAPT_COEF_PENA only)",
                        occ.str("ACTION").unwrap_or("")
                    ),
                    span,
                ));
            }
            let Some(pene_maxi) = occ.f64("PENE_MAXI") else {
                return Err(ex.kw_error(
                    "DEFI_LIST_INST/ECHEC",
                    occ,
                    "EVENEMENT",
                    "EVENEMENT='INTERPENETRATION' needs PENE_MAXI",
                ));
            };
            penalty_adaptation = Some(aster_fem::PenaltyAdaptation {
                pene_maxi,
                coef_maxi: occ.f64("COEF_MAXI").unwrap_or(1e12),
            });
            continue;
        }
        if occ.str("ACTION") == Some("ARRET") {
            subdivision = None;
            continue;
        }
        let mut sd = aster_fem::Subdivision::default();
        if occ.str("SUBD_METHODE") != Some("AUTO") {
            if let Some(n) = occ.first("SUBD_PAS").and_then(|s| s.as_i64()) {
                if n < 2 {
                    return Err(ex.kw_error(
                        "DEFI_LIST_INST/ECHEC",
                        occ,
                        "SUBD_PAS",
                        format!("SUBD_PAS = {n}: a failed increment is cut into at least 2 pieces"),
                    ));
                }
                sd.pieces = n as usize;
            }
            if let Some(n) = occ.first("SUBD_NIVEAU").and_then(|s| s.as_i64()) {
                sd.max_level = n.max(0) as usize;
            }
        }
        if let Some(m) = occ.f64("SUBD_PAS_MINI") {
            sd.min_step = m.max(0.0);
        }
        subdivision = Some(sd);
    }
    let values = if let Some(l) = def.concept("LIST_INST") {
        (*ex.real_list(l)?).clone()
    } else if def.contains("VALE") {
        list::from_values(&reals(def, "VALE"))
            .map_err(|e| ExecError::new(format!("DEFI_LIST_INST: {e}")))?
    } else {
        return Err(ExecError::new(
            "DEFI_LIST_INST/DEFI_LIST: give LIST_INST or VALE",
        ));
    };
    let location = ex.location(call.span);
    store_result(
        ex,
        call,
        Concept::TimeList(Rc::new(crate::concept::TimeList {
            instants: Rc::new(values),
            subdivision,
            penalty_adaptation,
            location,
        })),
    )
}

/// `TRACTION=_F(SIGM=nappe)`: a `DEFI_NAPPE` of `TEMP` whose functions are
/// σ(ε) curves (linear interpolation), as `aster_fem`'s
/// [`aster_fem::TractionNappe`] (code_aster's `rctrac`).
fn traction_nappe_of(n: &crate::function::Nappe) -> Result<aster_fem::TractionNappe, String> {
    use crate::function::Scale;
    use crate::thermo_mat::extension;
    if n.parameter != "TEMP" {
        return Err(format!(
            "a nappe of {}: aster reads traction curves per temperature (NOM_PARA='TEMP')",
            n.parameter
        ));
    }
    let mut curves = Vec::with_capacity(n.functions.len());
    for (t, f) in n.para.iter().zip(&n.functions) {
        let Function::Tabulated(c) = f else {
            return Err(format!(
                "the curve at TEMP = {t} is not a tabulated function of EPSI"
            ));
        };
        if c.scale_x != Scale::Linear || c.scale_y != Scale::Linear {
            return Err(format!(
                "the curve at TEMP = {t} is interpolated on a LOG scale (code_aster's traction curves are linear)"
            ));
        }
        curves.push(aster_fem::TractionCurve {
            eps: c.abscissae().to_vec(),
            sig: c.values().to_vec(),
            right: extension(c.right),
        });
    }
    aster_fem::TractionNappe::new(
        n.para.clone(),
        curves,
        extension(n.left),
        extension(n.right),
    )
    .map_err(|e| e.to_string())
}
