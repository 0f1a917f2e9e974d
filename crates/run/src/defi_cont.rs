//! `DEFI_CONT`, code_aster 17's contact definition for `MECA_NON_LINE`
//! (`code_aster.MacroCommands.defi_cont`): its keywords turned into
//! `aster_contact::mortar_lagrangian`'s zones, and the force source built
//! from them at the solve.
//!
//! Reproduced: `ALGO_CONT='LAGRANGIEN'` with `VARIANTE='ROBUSTE'` (the
//! defaults), unilateral, on 2D models (D_PLAN, C_PLAN, AXIS) whose contact
//! cells are SEG2 or SEG3; `COEF_CONT`, `CONTACT_INIT`, `SANS_GROUP_NO`,
//! `SANS_GROUP_MA`, `COEF_MULT_APPA`; friction (`FROTTEMENT='OUI'`,
//! `TYPE_FROT` `SANS`/`COULOMB`/`TRESCA`/`ADHERENT`,
//! `aster_contact::mortar_friction`) when every zone has it. Refused,
//! located: NITSCHE, PENALISATION, CLASSIQUE, BILATERAL, LISSAGE, zones
//! with and without friction in one definition, DIST_SUPP/CARA_ELEM and 3D
//! models (docs/contact.md, "DEFI_CONT").

use std::rc::Rc;

use aster_contact::mortar_friction::{FrictionLaw, MortarFriction};
use aster_contact::mortar_lagrangian::{InitialState, MortarLagrangian, MortarZoneDef};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_mesh::Mesh;

use crate::concept::{Concept, ContactDef, Modelisation};
use crate::executor::{store_result, Executor};
use crate::support::{Support, Values};

/// What DEFI_CONT reads (`crate::support`).
pub(crate) const DEFI_CONT: Support = Support {
    keywords: &[
        "MODELE",
        "INFO",
        "ZONE",
        "ZONE/GROUP_MA_MAIT",
        "ZONE/GROUP_MA_ESCL",
        "ZONE/ALGO_CONT",
        "ZONE/VARIANTE",
        "ZONE/TYPE_MATR_TANG",
        "ZONE/TYPE_CONT",
        "ZONE/COEF_CONT",
        "ZONE/APPARIEMENT",
        "ZONE/COEF_MULT_APPA",
        "ZONE/SANS_GROUP_NO",
        "ZONE/SANS_GROUP_MA",
        "ZONE/CONTACT_INIT",
        "ZONE/LISSAGE",
        "ZONE/VERI_NORM",
        "ZONE/FROTTEMENT",
        // FROTTEMENT='OUI' (module aster_contact::mortar_friction).
        "ZONE/TYPE_FROT",
        "ZONE/COULOMB",
        "ZONE/TRESCA",
        "ZONE/ALGO_FROT",
        // Only present with VARIANTE='CLASSIQUE' or ALGO_CONT='NITSCHE',
        // both refused by their values: one refusal, at the value.
        "ZONE/COEF_FROT",
        "ZONE/SYME",
    ],
    values: &[
        Values::new("ZONE/ALGO_CONT", &["LAGRANGIEN"])
            .why("(code_aster 17's Nitsche and penalised mortar contact)"),
        Values::new("ZONE/VARIANTE", &["ROBUSTE"])
            .why("(the CLASSIQUE variant of the Lagrangian mortar contact)"),
        Values::new("ZONE/TYPE_CONT", &["UNILATERAL"]).why("(bilateral mortar contact)"),
        Values::new("ZONE/LISSAGE", &["NON"]).why("(smoothed normals of the mortar contact)"),
        Values::new("ZONE/ALGO_FROT", &["LAGRANGIEN"])
            .why("(friction of code_aster 17's Nitsche and penalised mortar contact)"),
    ],
    hints: &[
        (
            "ZONE/DIST_SUPP",
            "an added distance of code_aster 17's mortar contact",
        ),
        (
            "ZONE/CARA_ELEM",
            "beam and shell thicknesses in code_aster 17's mortar contact",
        ),
    ],
    reuse: false,
    rules: None,
};

/// The zones of a DEFI_CONT call.
fn zones(kw: &Keywords) -> Vec<MortarZoneDef> {
    let strings = |occ: &Keywords, name: &str| -> Vec<String> {
        occ.simple(name)
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect()
    };
    kw.factor("ZONE")
        .iter()
        .map(|occ| {
            let mut z = MortarZoneDef::new(
                occ.str("GROUP_MA_MAIT").unwrap_or_default(),
                occ.str("GROUP_MA_ESCL").unwrap_or_default(),
            );
            z.coef_cont = occ.f64("COEF_CONT").unwrap_or(100.0);
            z.contact_init = match occ.str("CONTACT_INIT").unwrap_or("INTERPENETRE") {
                "OUI" => InitialState::Yes,
                "NON" => InitialState::No,
                _ => InitialState::Interpenetrated,
            };
            z.dist_ratio = occ.f64("COEF_MULT_APPA").filter(|r| *r > 0.0);
            z.excluded_node_groups = strings(occ, "SANS_GROUP_NO");
            z.excluded_cell_groups = strings(occ, "SANS_GROUP_MA");
            if occ.str("FROTTEMENT") == Some("OUI") {
                z.friction = Some(match occ.str("TYPE_FROT").unwrap_or("SANS") {
                    "COULOMB" => FrictionLaw::Coulomb(occ.f64("COULOMB").unwrap_or(0.0)),
                    "TRESCA" => FrictionLaw::Tresca(occ.f64("TRESCA").unwrap_or(0.0)),
                    "ADHERENT" => FrictionLaw::Stick,
                    _ => FrictionLaw::Without,
                });
            }
            z
        })
        .collect()
}

/// Whether a definition has friction (its zones all have; a mixed one is
/// refused by DEFI_CONT).
pub(crate) fn has_friction(zones: &[MortarZoneDef]) -> bool {
    zones.iter().any(|z| z.friction.is_some())
}

/// The frictional force source of a definition on the model's current
/// mesh.
pub(crate) fn friction_source(
    zones: &[MortarZoneDef],
    mesh: &Mesh,
    axis: bool,
) -> Result<MortarFriction, ExecError> {
    MortarFriction::new(zones, mesh, axis).map_err(|e| ExecError::new(format!("DEFI_CONT: {e}")))
}

/// The force source of a definition on the model's current mesh.
pub(crate) fn source(
    zones: &[MortarZoneDef],
    mesh: &Mesh,
    axis: bool,
) -> Result<MortarLagrangian, ExecError> {
    MortarLagrangian::new(zones, mesh, axis).map_err(|e| ExecError::new(format!("DEFI_CONT: {e}")))
}

pub fn defi_cont(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model_ref = ex.required("DEFI_CONT", kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    if model.dim() != 2 {
        return Err(ex.kw_error(
            "DEFI_CONT",
            kw,
            "MODELE",
            "not supported yet: code_aster 17's mortar contact in 3D (reproduced on 2D models: D_PLAN, C_PLAN, AXIS)",
        ));
    }
    let axis = model
        .cells
        .values()
        .any(|m| *m == Modelisation::Axisymmetric);
    let mesh = ex.mesh_by_id(model.mesh)?;
    let zones = zones(kw);
    // code_aster builds one kind of definition (FrictionNew or ContactNew)
    // for all its zones: zones with and without friction together are not
    // reproduced.
    if has_friction(&zones) {
        if let Some((occ, _)) = kw
            .factor("ZONE")
            .iter()
            .zip(&zones)
            .find(|(_, z)| z.friction.is_none())
        {
            return Err(ex.kw_error(
                "DEFI_CONT/ZONE",
                occ,
                "FROTTEMENT",
                "not supported yet: zones with and without friction in one DEFI_CONT (code_aster 17's mortar friction is reproduced when every zone has FROTTEMENT='OUI'; TYPE_FROT='SANS' gives no friction force)",
            ));
        }
    }
    // The groups and cell kinds are checked now, located at the zone.
    for (occ, z) in kw.factor("ZONE").iter().zip(&zones) {
        if let Err(e) = MortarLagrangian::new(std::slice::from_ref(z), &mesh, axis) {
            let at = match &e {
                aster_contact::ContactError::UnknownGroup { keyword, .. } => keyword,
                aster_contact::ContactError::Unsupported { feature, .. }
                    if feature.contains("GROUP_MA_MAIT") =>
                {
                    "GROUP_MA_MAIT"
                }
                _ => "GROUP_MA_ESCL",
            };
            return Err(ex.kw_error("DEFI_CONT/ZONE", occ, at, e.to_string()));
        }
    }
    let def = ContactDef::Mortar {
        model: model_ref.id,
        zones,
    };
    store_result(ex, call, Concept::Contact(Rc::new(def)))
}
