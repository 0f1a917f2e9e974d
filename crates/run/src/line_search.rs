//! `RECH_LINEAIRE` of STAT_NON_LINE, DYNA_NON_LINE and MECA_NON_LINE: the
//! keywords → [`aster_fem::LineSearch`] (the search itself is
//! `aster_fem::line_search`), and what is refused before solving.
//!
//! STAT_NON_LINE and DYNA_NON_LINE follow code_aster's Fortran (`nmrelp`),
//! MECA_NON_LINE its Python `SecantLineSearch`. Refused: `METHODE='PILOTAGE'`
//! (needs PILOTAGE, the continuation method); any contact or unilateral
//! condition (code_aster forbids the line search with the continuous
//! contact, MECANONLINE3_91; with the discrete contact and LIAISON_UNIL it
//! searches on the residual without the contact correction `nmcoun`
//! applies after it, not reproduced; MECA_NON_LINE with a DEFI_CONT with
//! friction, `VARIANTE='CLASSIQUE'` or `NITSCHE`, [`with_defi_cont`]: the
//! trial residuals on the pairing of the iteration's start, as code_aster
//! 17 evaluates them, are written for the frictionless Lagrangian and
//! penalised methods only); `MIXTE` with a tangent not reassembled at every
//! iteration (code_aster then keeps the internal forces of the last ρ
//! tried with the displacement of the best one); DYNA_NON_LINE with HHT
//! (validated with NEWMARK only).

use crate::support::{Refusal, Values};
use aster_eval::CommandCall;
use aster_fem::{LineSearch, LineSearchMethod, LineSearchRule};

/// The methods reproduced.
pub(crate) const VALUES: Values = Values::new("RECH_LINEAIRE/METHODE", &["CORDE", "MIXTE"])
    .why("(METHODE='PILOTAGE' needs PILOTAGE, the continuation method)");

/// The search of `call`'s `RECH_LINEAIRE` (`None` when absent).
pub(crate) fn parse(call: &CommandCall) -> Option<LineSearch> {
    let occ = call.keywords.factor("RECH_LINEAIRE").first()?;
    let d = LineSearch::default();
    let method = match occ.str("METHODE") {
        Some("MIXTE") => LineSearchMethod::Mixte,
        _ => LineSearchMethod::Corde,
    };
    let rule = if call.command == "MECA_NON_LINE" {
        LineSearchRule::Python
    } else {
        LineSearchRule::Fortran
    };
    let iter_line_maxi = occ
        .first("ITER_LINE_MAXI")
        .and_then(|s| s.as_i64())
        .map_or(d.iter_line_maxi, |n| n.max(0) as usize);
    // MECA_NON_LINE: `isEnabled()` is ITER_LINE_MAXI > 0.
    if rule == LineSearchRule::Python && iter_line_maxi == 0 {
        return None;
    }
    Some(LineSearch {
        method,
        resi_line_rela: occ.f64("RESI_LINE_RELA").unwrap_or(d.resi_line_rela),
        iter_line_maxi,
        rho_min: occ.f64("RHO_MIN").unwrap_or(d.rho_min),
        rho_max: occ.f64("RHO_MAX").unwrap_or(d.rho_max),
        rho_excl: occ.f64("RHO_EXCL").unwrap_or(d.rho_excl),
        rule,
    })
}

/// Whether MECA_NON_LINE's line search is reproduced with a DEFI_CONT of
/// method `algo` and `zones` (code_aster 17 evaluates the search's trial
/// residuals on the pairing of the iteration's start, `ForceSource::
/// evaluate_on_pairing`): the frictionless Lagrangian (`ROBUSTE`) and
/// penalised methods, in 2D and 3D; else the reason.
pub(crate) fn with_defi_cont(
    algo: crate::defi_cont::MortarAlgo,
    zones: &[aster_contact::mortar_lagrangian::MortarZoneDef],
) -> Result<(), String> {
    use crate::defi_cont::MortarAlgo;
    if crate::defi_cont::has_friction(zones) {
        return Err("RECH_LINEAIRE with a DEFI_CONT with friction (FROTTEMENT='OUI'): the friction residual on the pairing of the iteration's start (code_aster 17's line search does not pair again) is not written".into());
    }
    match algo {
        MortarAlgo::Lagrangian | MortarAlgo::Penalised => Ok(()),
        MortarAlgo::Classique => Err("RECH_LINEAIRE with a DEFI_CONT of VARIANTE='CLASSIQUE': its residual on the pairing of the iteration's start (code_aster 17's line search does not pair again) is not written".into()),
        MortarAlgo::Nitsche => Err("RECH_LINEAIRE with a DEFI_CONT of ALGO_CONT='NITSCHE': its residual on the pairing of the iteration's start (code_aster 17's line search does not pair again) is not written".into()),
    }
}

/// The refusals that need the keywords only.
pub(crate) fn rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    let Some(occ) = kw.factor("RECH_LINEAIRE").first() else {
        return;
    };
    if occ.str("METHODE") == Some("MIXTE") {
        let newton = kw.factor("NEWTON").first();
        let reac_iter = newton
            .and_then(|n| n.first("REAC_ITER"))
            .and_then(|s| s.as_i64())
            .unwrap_or(1);
        let elastic = newton.and_then(|n| n.str("MATRICE")) == Some("ELASTIQUE");
        if call.command != "MECA_NON_LINE" && (reac_iter != 1 || elastic) {
            out.push(Refusal::at(
                format!(
                    "{}/RECH_LINEAIRE/METHODE='MIXTE' with a tangent not reassembled at every iteration (NEWTON/REAC_ITER other than 1 or MATRICE='ELASTIQUE'): code_aster's nmrelp then keeps the internal forces of the last ρ tried with the displacement of the best one, not reproduced",
                    call.command
                ),
                occ,
                "METHODE",
                call.span,
            ));
        }
    }
    if call.command == "DYNA_NON_LINE" {
        for st in kw.factor("SCHEMA_TEMPS") {
            if let Some(schema @ ("HHT" | "HHT_COMPLET")) = st.str("SCHEMA") {
                out.push(Refusal::at(
                    format!(
                        "DYNA_NON_LINE/RECH_LINEAIRE with SCHEMA_TEMPS/SCHEMA='{schema}' (the line search is validated with NEWMARK only: the weighting of HHT's internal forces in the searched residual is not)"
                    ),
                    kw,
                    "RECH_LINEAIRE",
                    call.span,
                ));
            }
        }
    }
    // MECA_NON_LINE with a DEFI_CONT: decided on the definition when the
    // command runs, before solving (`with_defi_cont`).
    if call.command != "MECA_NON_LINE"
        && (!kw.factor("CONTACT").is_empty() || kw.concept("CONTACT").is_some())
    {
        let why = "code_aster forbids it with the continuous contact (MECANONLINE3_91) and, with the discrete contact or LIAISON_UNIL, searches on the residual without the contact correction applied after it (nmdepl → nmcoun), not reproduced";
        out.push(Refusal::at(
            format!("{}/RECH_LINEAIRE with CONTACT: {why}", call.command),
            kw,
            "RECH_LINEAIRE",
            call.span,
        ));
    }
}
