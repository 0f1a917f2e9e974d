//! `DEFI_CONTACT(FROTTEMENT='COULOMB')`: the friction keywords turned into
//! `aster_contact::friction`'s plain types (the contact bridge calls these
//! while it reads the zones).

use aster_contact::friction::{
    ContactInit, ContinueFriction, ContinueZoneFriction, DiscreteFrictionDef, DiscreteZoneFriction,
    FrictionAlgo,
};
use aster_contact::Resolution;
use aster_eval::{CommandCall, ExecError, Keywords};

use crate::support::Refusal;

/// The friction of a continuous definition: one setting per zone and the
/// friction loop. Refuses, located, what the elements do not reproduce.
pub fn continuous(kw: &Keywords) -> Result<ContinueFriction, ExecError> {
    let frictionless = kw.str("FROTTEMENT") != Some("COULOMB");
    let mut zones = Vec::new();
    for occ in kw.factor("ZONE") {
        // Without FROTTEMENT='COULOMB' the zones are frictionless (μ = 0):
        // code_aster's contact-only elements.
        let coulomb = match occ.f64("COULOMB") {
            Some(c) => c,
            None if frictionless => 0.0,
            None => {
                return Err(ExecError::new(
                    "DEFI_CONTACT/ZONE: COULOMB is required with FROTTEMENT='COULOMB'",
                ))
            }
        };
        let mut z = ContinueZoneFriction::new(coulomb);
        z.algo = match occ.str("ALGO_FROT").unwrap_or("STANDARD") {
            "PENALISATION" => FrictionAlgo::Penalisation {
                coef_pena_frot: occ.f64("COEF_PENA_FROT").unwrap_or(1e7),
            },
            _ => FrictionAlgo::Standard {
                coef_frot: occ.f64("COEF_FROT").unwrap_or(100.0),
            },
        };
        if let Some(g) = occ.f64("GLIS_MAXI") {
            z.glis_maxi = g;
        }
        z.seuil_init = occ.f64("SEUIL_INIT");
        z.contact_init = match occ.str("CONTACT_INIT").unwrap_or("INTERPENETRE") {
            "OUI" => ContactInit::Oui,
            "NON" => ContactInit::Non,
            _ => ContactInit::Interpenetre,
        };
        z.excluded_node_groups = occ
            .simple("SANS_GROUP_NO_FR")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        let dir: Vec<f64> = occ
            .simple("DIRE_EXCL_FROT")
            .iter()
            .filter_map(|s| s.as_f64())
            .collect();
        if !dir.is_empty() {
            z.dire_excl_frot = Some([
                dir.first().copied().unwrap_or(0.0),
                dir.get(1).copied().unwrap_or(0.0),
                dir.get(2).copied().unwrap_or(0.0),
            ]);
        }
        zones.push(z);
    }
    let mut f = ContinueFriction::new(zones);
    f.algo_reso_frot = match kw.str("ALGO_RESO_FROT") {
        Some("POINT_FIXE") => Resolution::PointFixe,
        _ => Resolution::Newton,
    };
    // code_aster's TYPE_ADAPT (`cazocc`: one value for the definition, the
    // last zone's) and whether `mm_cycl_algo` treats cycling points with it.
    let newton_fr = !frictionless && f.algo_reso_frot == Resolution::Newton;
    let mut type_adapt = 0;
    for occ in kw.factor("ZONE") {
        type_adapt = cycling_type(
            occ.str("ADAPTATION").unwrap_or("CYCLAGE"),
            newton_fr,
            occ.str("ALGO_CONT") == Some("PENALISATION"),
            !frictionless && occ.str("ALGO_FROT") == Some("PENALISATION"),
        );
    }
    f.cycling = matches!(type_adapt, 4 | 5 | 6 | 7 | 11);
    f.adapt_coef = matches!(type_adapt, 1 | 2 | 5 | 6);
    if let Some(r) = kw.f64("RESI_FROT") {
        f.resi_frot = r;
    }
    if let Some(n) = kw.first("ITER_FROT_MAXI").and_then(|s| s.as_i64()) {
        f.iter_frot_maxi = n.max(1) as usize;
    }
    Ok(f)
}

/// code_aster's `TYPE_ADAPT` of a continuous zone (`cazocc`) from
/// `ADAPTATION`, Newton friction (`FROT_NEWTON`), penalised contact and
/// penalised friction.
fn cycling_type(adaptation: &str, newton_fr: bool, pena_cont: bool, pena_frot: bool) -> i32 {
    match adaptation {
        "NON" => 0,
        "CYCLAGE" => 4,
        "ADAPT_COEF" => {
            if newton_fr {
                if pena_frot && !pena_cont {
                    7
                } else if pena_cont {
                    2
                } else {
                    1
                }
            } else if pena_cont {
                3
            } else {
                0
            }
        }
        // 'TOUT'
        _ => {
            if newton_fr {
                if pena_frot && !pena_cont {
                    12
                } else if pena_cont {
                    7
                } else {
                    5
                }
            } else if pena_cont {
                7
            } else {
                4
            }
        }
    }
}

/// The friction of a discrete definition (`ALGO_FROT='PENALISATION'`, the
/// only discrete friction algorithm): μ, `E_T`, `COEF_MATR_FROT` per zone.
pub fn discrete(kw: &Keywords) -> Result<DiscreteFrictionDef, ExecError> {
    let mut zones = Vec::new();
    for occ in kw.factor("ZONE") {
        let coulomb = occ.f64("COULOMB").ok_or_else(|| {
            ExecError::new("DEFI_CONTACT/ZONE: COULOMB is required with FROTTEMENT='COULOMB'")
        })?;
        let e_t = occ.f64("E_T").ok_or_else(|| {
            ExecError::new(
                "DEFI_CONTACT/ZONE: E_T is required with FROTTEMENT='COULOMB' and FORMULATION='DISCRETE'",
            )
        })?;
        zones.push(DiscreteZoneFriction {
            coulomb,
            e_t,
            coef_matr_frot: occ.f64("COEF_MATR_FROT").unwrap_or(0.0),
        });
    }
    Ok(DiscreteFrictionDef { zones })
}

/// The stiffest normal penalty with which discrete friction is validated
/// (ssnv128d, E_N = 1e15, matches code_aster to 3e-9; ssnv128c, E_N =
/// 1e18, stops one Newton iteration early).
const DISCRETE_FRICTION_E_N_MAX: f64 = 1e16;

/// The static refusals of DEFI_CONTACT's friction (`crate::support`):
/// what the friction module does not reproduce, located at its keyword.
/// The loosest `CONVERGENCE/RESI_GLOB_RELA` accepted with continuous
/// friction: above it code_aster's answer is a partly converged iterate
/// (ssnv128r, 1e-2; the validated cases use 1e-5 or tighter).
pub(crate) const CONTINUOUS_FRICTION_RESI_GLOB_RELA_MAX: f64 = 1e-4;

/// Whether a DEFI_CONTACT is continuous with Coulomb friction on some zone.
pub(crate) fn is_continuous_frictional(kw: &Keywords) -> bool {
    kw.str("FORMULATION") == Some("CONTINUE")
        && kw.str("FROTTEMENT") == Some("COULOMB")
        && kw
            .factor("ZONE")
            .iter()
            .any(|o| o.f64("COULOMB").is_some_and(|m| m > f64::EPSILON))
}

pub(crate) fn rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    continuous_rules(call, out);
    let kw = &call.keywords;
    if kw.str("FROTTEMENT") != Some("COULOMB") {
        return;
    }
    if kw.str("FORMULATION").unwrap_or("DISCRETE") == "DISCRETE" {
        // aster_contact::friction::discrete reproduces code_aster's
        // `frogdp` iterate by iterate (its prediction, its symmetric
        // tangent, the friction switched on one pass late): the answer is
        // where that linearly converging Newton stops, at RESI_GLOB_RELA.
        // With a very stiff normal penalty the stop is not reproduced:
        // ssnv128c (E_N = 1e18) ends its last step at RESI_GLOB_RELA =
        // 0.9993e-5 against 1e-5, one iteration before code_aster, and is
        // 1.3e-6..4.9e-6 off; every case with E_N ≤ 1e15 matches.
        for occ in kw.factor("ZONE") {
            if occ
                .f64("E_N")
                .is_some_and(|e| e > DISCRETE_FRICTION_E_N_MAX)
            {
                out.push(Refusal::at(
                    format!(
                        "DEFI_CONTACT/ZONE/E_N above {DISCRETE_FRICTION_E_N_MAX:e} with FROTTEMENT='COULOMB' and FORMULATION='DISCRETE' (code_aster's penalised friction converges linearly and its answer is where Newton stops at RESI_GLOB_RELA; with so stiff a normal penalty that stop is not reproduced)"
                    ),
                    occ,
                    "E_N",
                    call.span,
                ));
            }
        }
        // code_aster's discrete friction is penalised contact and friction
        // (`cfalgo`: `frogdp`); with CONTRAINTE or GCP its contact
        // algorithms ignore or refuse the friction.
        for occ in kw.factor("ZONE") {
            let algo = occ.str("ALGO_CONT").unwrap_or("CONTRAINTE");
            if algo != "PENALISATION" {
                let at = if occ.keyword("ALGO_CONT").is_some_and(|k| !k.defaulted) {
                    "ALGO_CONT"
                } else {
                    "COULOMB"
                };
                out.push(Refusal::at(
                    format!("DEFI_CONTACT/ZONE/ALGO_CONT='{algo}' with FROTTEMENT='COULOMB' and FORMULATION='DISCRETE' (code_aster's discrete friction is penalised: ALGO_CONT='PENALISATION')"),
                    occ,
                    at,
                    call.span,
                ));
            }
        }
    }
    if kw.str("FORMULATION") == Some("CONTINUE") {
        newton_friction_rules(call, out);
        // A zone with COULOMB = 0 (≤ r8prem) beside frictional ones is
        // frictionless in code_aster: `cazocc` sets its ALGO_FROT to 0, so
        // FROTTEMENT_ZONE is false, its slave cells get contact-only
        // elements (`mmprel`: CONT_SL_2D/3D) and `mmmbca` evaluates no
        // friction status there — what `friction::continuous` does with
        // μ = 0 (one LAGS_C unknown per slave node). ssna102f all-OK.
        //
        // The frictional elements integrate at the slave nodes ('AUTO') or
        // at code_aster's Gauss points (`mmgaus`, ssnp156b all-OK). Its
        // Simpson and Newton–Cotes points are placed (the frictionless
        // elements use them: ssnp167, ssnp121), but no real case checks
        // them with friction.
        for occ in kw.factor("ZONE") {
            let rule = occ.str("INTEGRATION").unwrap_or("AUTO");
            if occ.f64("COULOMB").is_some_and(|m| m > f64::EPSILON)
                && matches!(rule, "SIMPSON" | "NCOTES")
            {
                out.push(Refusal::at(
                    format!("DEFI_CONTACT/ZONE/INTEGRATION='{rule}' with FROTTEMENT='COULOMB' (the frictional contact elements on code_aster's Simpson and Newton–Cotes points are not checked against code_aster: no case; 'AUTO' and 'GAUSS' are reproduced)"),
                    occ,
                    "INTEGRATION",
                    call.span,
                ));
            }
        }
    }
    // code_aster's TYPE_ADAPT of the definition (the last zone's, `cazocc`)
    // and whether `contMatrModi` then estimates the coefficients from the
    // prediction matrix (`EXIS_ADAP`: 1, 2, 3, 5, 6, 7; `echmat`, not
    // reproduced).
    let newton_fr = kw.str("ALGO_RESO_FROT").unwrap_or("NEWTON") == "NEWTON";
    let zone_type = |occ: &Keywords| {
        cycling_type(
            occ.str("ADAPTATION").unwrap_or("CYCLAGE"),
            newton_fr,
            occ.str("ALGO_CONT") == Some("PENALISATION"),
            occ.str("ALGO_FROT") == Some("PENALISATION"),
        )
    };
    let exis_adap = kw
        .factor("ZONE")
        .last()
        .is_some_and(|o| matches!(zone_type(o), 1 | 2 | 3 | 5 | 6 | 7));
    let newton_cont = kw.str("ALGO_RESO_CONT").unwrap_or("NEWTON") == "NEWTON";
    for occ in kw.factor("ZONE") {
        // Penalised friction beside augmented contact, reproduced where
        // code_aster neither treats cycling nor adapts from the matrix:
        // TYPE_ADAPT 12 ('TOUT' with Newton friction) or 0 ('NON'), with
        // Newton contact (the status update that `mmbclc` follows with
        // `mmchml`), the definition without `EXIS_ADAP`.
        let pena_frot_reproduced = kw.str("FORMULATION") == Some("CONTINUE")
            && occ.str("ALGO_FROT") == Some("PENALISATION")
            && occ.str("ALGO_CONT").unwrap_or("STANDARD") == "STANDARD"
            && matches!(zone_type(occ), 0 | 12)
            && newton_cont
            && !exis_adap;
        // A penalised zone with ADAPTATION='ADAPT_COEF'/'TOUT': code_aster
        // replaces COEF_PENA_CONT/COEF_PENA_FROT by coefficients adapted
        // to PENE_MAXI/GLIS_MAXI (`cazocc`, iadapt 2/3/7): the converged
        // answer depends on them.
        let penalised = occ.str("ALGO_CONT") == Some("PENALISATION")
            || occ.str("ALGO_FROT") == Some("PENALISATION");
        if penalised
            && !pena_frot_reproduced
            && matches!(occ.str("ADAPTATION"), Some("ADAPT_COEF" | "TOUT"))
        {
            out.push(Refusal::at(
                format!(
                    "DEFI_CONTACT/ZONE/ADAPTATION='{}' with penalisation (penalty coefficients adapted to PENE_MAXI/GLIS_MAXI)",
                    occ.str("ADAPTATION").unwrap_or_default()
                ),
                occ,
                "ADAPTATION",
                call.span,
            ));
        }
        // Penalised continuous contact under code_aster's cycling
        // treatment (the default ADAPTATION='CYCLAGE', module
        // `aster_contact::friction::cycling`): with it ssnv128w converges
        // to all OK but ssnv128y (the same scene cut in 4 instead of 2
        // pieces, RESI_GLOB_RELA 1e-10) 4.4e-6..9.2e-6 off code_aster's
        // DX, which is the same for both to 12 digits: our answer still
        // depends on the cutting path there, code_aster's does not.
        if kw.str("FORMULATION") == Some("CONTINUE")
            && occ.str("ALGO_CONT") == Some("PENALISATION")
            && occ.str("ADAPTATION").unwrap_or("CYCLAGE") == "CYCLAGE"
        {
            out.push(Refusal::at(
                "DEFI_CONTACT/ZONE/ALGO_CONT='PENALISATION' with FROTTEMENT='COULOMB' and ADAPTATION='CYCLAGE' (code_aster's cycling treatment of penalised points: the answer reproduced to 1e-5 only, depending on the step cutting)".into(),
                occ,
                "ALGO_CONT",
                call.span,
            ));
        }
        // ADAPTATION='TOUT' on an augmented frictional zone with Newton
        // friction (code_aster's TYPE_ADAPT 5, `cazocc`) is accepted: its
        // cycling treatment (`friction::cycling`) and its adaptation of
        // COEF_FROT (`friction::adaptation`) are reproduced; its estimate
        // of COEF_CONT from the matrix (`nmprma` → `echmat`) only changes
        // Newton's path (ssnv209a all-OK without it).
        // Penalised friction beside augmented contact: code_aster's
        // `mm_cycl_algo` replaces, at every status update of a point in
        // contact whose slip exceeds 1e-6 × GLIS_MAXI (default 0.1 ×
        // arete_min, `mmmbca`), the point's COEF_PENA_FROT by
        // 10 × arete_max / arete_min / GLIS_MAXI, whatever ADAPTATION —
        // the penalised answer depends on it. Not reproduced; its one real
        // case (ssnv128p) also tests code_aster's contact statistics
        // (RECU_TABLE NOM_TABLE='STAT': Count_Cont_NCont of its Newton
        // path).
        if kw.str("FORMULATION") == Some("CONTINUE")
            && occ.str("ALGO_FROT") == Some("PENALISATION")
            && occ.str("ALGO_CONT").unwrap_or("STANDARD") == "STANDARD"
            && occ.f64("COULOMB").is_some_and(|m| m > f64::EPSILON)
            && !pena_frot_reproduced
        {
            let at = if occ.keyword("ADAPTATION").is_some_and(|k| !k.defaulted) {
                "ADAPTATION"
            } else if !newton_cont {
                "ALGO_FROT"
            } else if occ.contains("GLIS_MAXI") {
                "GLIS_MAXI"
            } else {
                "ALGO_FROT"
            };
            out.push(Refusal::at(
                "DEFI_CONTACT/ZONE/ALGO_FROT='PENALISATION' with ALGO_CONT='STANDARD' in the continuous formulation, except with ADAPTATION='TOUT' (Newton friction) or 'NON' and ALGO_RESO_CONT='NEWTON' (code_aster's adaptation of COEF_PENA_FROT, mm_cycl_algo and mmchml_c, is reproduced there; beside its cycling treatment, its estimate from the matrix or the fixed-point contact loop it is not)"
                    .into(),
                occ,
                at,
                call.span,
            ));
        }
        if occ.str("GRAND_GLIS") == Some("OUI") {
            out.push(Refusal::at(
                "DEFI_CONTACT/ZONE/GRAND_GLIS='OUI' (large-slip friction terms)".into(),
                occ,
                "GRAND_GLIS",
                call.span,
            ));
        }
    }
}

/// Largest `RESI_FROT` accepted with `ALGO_RESO_FROT='NEWTON'`: the
/// loosest of the all-OK cases is ssnv128n's 2e-3.
const NEWTON_RESI_FROT_MAX: f64 = 5e-3;

/// Largest `COEF_FROT` of an augmented (`ALGO_FROT='STANDARD'`) zone
/// accepted under code_aster's cycling treatment.
const CYCLING_COEF_FROT_MAX: f64 = 1e6;

/// Continuous friction solved by the generalised Newton
/// (`ALGO_RESO_FROT='NEWTON'`, the default): the settings whose increments
/// code_aster converges and ours do not, refused before the solve.
fn newton_friction_rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    if kw.str("ALGO_RESO_FROT").unwrap_or("NEWTON") != "NEWTON" {
        return;
    }
    // code_aster ends the generalised Newton when the friction
    // multipliers change by less than RESI_FROT of their largest value
    // (`nmresi` → `mmconv` → `mmmcrf`), beside RESI_GLOB_RELA on the
    // forces: with a loose RESI_FROT its answer is an iterate whose
    // friction is partly converged, which only its own Newton path
    // reproduces. ssnv128x (RESI_FROT = 0.01, the fixed-point contact and
    // geometry, the default COEF_FROT = 100): our Newton cycles between
    // stick and slip at its first increment (cut 5 times); with
    // COEF_FROT = 1e5 it converges, 2.2e-5 off code_aster's DX (3 OK,
    // 4 NOOK), and with RESI_FROT 1e-4 it still cycles.
    if let Some(resi) = kw.f64("RESI_FROT").filter(|r| *r > NEWTON_RESI_FROT_MAX) {
        if kw.keyword("RESI_FROT").is_some_and(|k| !k.defaulted) {
            out.push(Refusal::at(
                format!(
                    "DEFI_CONTACT/RESI_FROT={resi:e} (above {NEWTON_RESI_FROT_MAX:e}) with ALGO_RESO_FROT='NEWTON' and FORMULATION='CONTINUE' (code_aster's answer is its Newton iterate whose friction multipliers are converged to RESI_FROT only; our Newton path does not reproduce it: measured on ssnv128x, stick/slip cycling, 2.2e-5 off when it converges)"
                ),
                kw,
                "RESI_FROT",
                call.span,
            ));
        }
    }
    // A very large augmentation of the friction (COEF_FROT) under the
    // cycling treatment (`mm_cycl_algo`, TYPE_ADAPT 4, 5, 6, 7, 11):
    // ssnv128z (COEF_FROT = 1e8, ALGO_RESO_CONT/GEOM='NEWTON', CYCLAGE)
    // closes its step to t = 0.4 at Newton iteration 10 through the
    // contact-side treatment (points clipped open while interpenetrated
    // by 1.8e-6), and the next step cycles with period 2 however cut
    // (10 times). The same scene with COEF_FROT 1e5 or 1e6 runs to its
    // end, with 1e7 it fails the same way. code_aster's friction side of
    // the treatment (`mm_cycl_d2`/`d3`: the matrix blended with the
    // previous statuses') is not reproduced.
    let newton_fr = true;
    let pena_cont_zone = |o: &Keywords| o.str("ALGO_CONT") == Some("PENALISATION");
    for occ in kw.factor("ZONE") {
        if occ.f64("COULOMB").is_none_or(|m| m <= f64::EPSILON)
            || occ.str("ALGO_FROT").unwrap_or("STANDARD") != "STANDARD"
        {
            continue;
        }
        let Some(coef) = occ.f64("COEF_FROT").filter(|c| *c > CYCLING_COEF_FROT_MAX) else {
            continue;
        };
        let adaptation = occ.str("ADAPTATION").unwrap_or("CYCLAGE");
        let ty = cycling_type(adaptation, newton_fr, pena_cont_zone(occ), false);
        if matches!(ty, 4 | 5 | 6 | 7 | 11) {
            out.push(Refusal::at(
                format!(
                    "DEFI_CONTACT/ZONE/COEF_FROT={coef:e} (above {CYCLING_COEF_FROT_MAX:e}) with ALGO_FROT='STANDARD', ALGO_RESO_FROT='NEWTON' and ADAPTATION='{adaptation}' (code_aster's cycling treatment of stick/slip flips, mm_cycl_d2/d3, is not reproduced: measured on ssnv128z, the increment after a treated one cycles however cut; COEF_FROT up to 1e6 runs)"
                ),
                occ,
                "COEF_FROT",
                call.span,
            ));
        }
    }
}

/// Continuous zones (with or without friction): what code_aster's contact
/// elements do that is not reproduced.
fn continuous_rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    // A sliding zone (GLISSIERE='OUI', the node-row stand-in
    // `aster_contact::glissiere`) beside a penalised zone: ssnv504k
    // (LISSAGE, the fixed-point contact and geometry, the second zone
    // ALGO_CONT='PENALISATION' with ADAPTATION='ADAPT_COEF') solves to
    // t = 146.6 in 23 s, then the sliding zone's geometric loop does not
    // converge (its displacement still changes by 1.4e-2 of the step's
    // after ITER_GEOM_MAXI = 10 pairings, cut 3 times); ssnv504j, the same
    // scene with the second zone augmented, is all-OK. code_aster links
    // the sliding nodes at each convergence of its contact loop, where the
    // penalised zone's adapted coefficient (`mm_cycl_algo`, Bussetta)
    // moves the statuses: not reproduced.
    if kw.str("FORMULATION") == Some("CONTINUE") {
        let zones = kw.factor("ZONE");
        if zones.iter().any(|o| o.str("GLISSIERE") == Some("OUI")) {
            for occ in zones
                .iter()
                .filter(|o| o.str("ALGO_CONT") == Some("PENALISATION"))
            {
                out.push(Refusal::at(
                    "DEFI_CONTACT/ZONE/ALGO_CONT='PENALISATION' beside a zone with GLISSIERE='OUI' (the sliding zone's links and geometric loop beside a penalised zone are not reproduced: measured on ssnv504k, the geometric loop does not converge at t = 146.8)".into(),
                    occ,
                    "ALGO_CONT",
                    call.span,
                ));
            }
        }
    }
    for occ in kw.factor("ZONE") {
        // code_aster stops on excluded nodes without the nodal
        // integration ('AUTO'): `cazocc`, CONTACT_97.
        if kw.str("FORMULATION") == Some("CONTINUE")
            && occ.str("INTEGRATION").unwrap_or("AUTO") != "AUTO"
        {
            for key in [
                "SANS_GROUP_NO",
                "SANS_NOEUD",
                "SANS_GROUP_NO_FR",
                "SANS_NOEUD_FR",
            ] {
                if occ.contains(key) {
                    out.push(Refusal::at(
                        format!("DEFI_CONTACT/ZONE/{key} with INTEGRATION='{}' (code_aster refuses excluded nodes without the nodal integration 'AUTO': cazocc, message CONTACT_97)", occ.str("INTEGRATION").unwrap_or_default()),
                        occ,
                        key,
                        call.span,
                    ));
                }
            }
        }
        // Augmented (STANDARD) zones with ADAPTATION='ADAPT_COEF'/'TOUT'
        // and the fixed-point contact loop: code_aster's status treatment
        // (`mmmbca` → `mm_cycl_algo`, `mm_cycl_prop`) changes COEF_CONT
        // point by point when a status flips between the loops; ssnp154a's
        // indentation is then 2.3e-4 off code_aster's (the same scene with
        // ALGO_RESO_CONT='NEWTON', ssnp154b, matches).
        if kw.str("FORMULATION") == Some("CONTINUE")
            && occ.str("ALGO_CONT").unwrap_or("STANDARD") == "STANDARD"
            && kw.str("ALGO_RESO_CONT") == Some("POINT_FIXE")
            && matches!(occ.str("ADAPTATION"), Some("ADAPT_COEF" | "TOUT"))
        {
            out.push(Refusal::at(
                format!(
                    "DEFI_CONTACT/ZONE/ADAPTATION='{}' with ALGO_RESO_CONT='POINT_FIXE' (COEF_CONT adapted point by point when contact statuses flip between the fixed-point loops, code_aster's mm_cycl_algo; ALGO_RESO_CONT='NEWTON' or ADAPTATION='CYCLAGE' are reproduced)",
                    occ.str("ADAPTATION").unwrap_or_default()
                ),
                occ,
                "ADAPTATION",
                call.span,
            ));
        }
    }
}

#[cfg(test)]
mod cycling_tests {
    use super::cycling_type;

    #[test]
    fn type_adapt_as_cazocc() {
        assert_eq!(cycling_type("CYCLAGE", true, false, false), 4);
        assert_eq!(cycling_type("NON", true, true, false), 0);
        assert_eq!(cycling_type("ADAPT_COEF", true, false, false), 1);
        assert_eq!(cycling_type("ADAPT_COEF", true, true, false), 2);
        assert_eq!(cycling_type("ADAPT_COEF", true, false, true), 7);
        assert_eq!(cycling_type("ADAPT_COEF", false, true, false), 3);
        assert_eq!(cycling_type("ADAPT_COEF", false, false, false), 0);
        assert_eq!(cycling_type("TOUT", true, false, false), 5);
        assert_eq!(cycling_type("TOUT", true, true, false), 7);
        assert_eq!(cycling_type("TOUT", true, false, true), 12);
        assert_eq!(cycling_type("TOUT", false, true, false), 7);
    }
}
