//! `DEFI_CONT`, code_aster 17's contact definition for `MECA_NON_LINE`
//! (`code_aster.MacroCommands.defi_cont`): its keywords turned into
//! `aster_contact::mortar_lagrangian`'s zones, and the force source built
//! from them at the solve.
//!
//! Reproduced: `ALGO_CONT='LAGRANGIEN'` with `VARIANTE='ROBUSTE'` (the
//! defaults), frictionless, unilateral, on 2D models (D_PLAN, C_PLAN,
//! AXIS) whose contact cells are SEG2 or SEG3 and on 3D models whose
//! contact faces are TRIA3 or QUAD4 (`aster_contact::mortar_pairing3d`);
//! `COEF_CONT`, `CONTACT_INIT`, `SANS_GROUP_NO`, `SANS_GROUP_MA`,
//! `COEF_MULT_APPA`. Refused, located: NITSCHE, PENALISATION, CLASSIQUE,
//! BILATERAL, LISSAGE, friction, DIST_SUPP/CARA_ELEM and quadratic faces in
//! 3D (docs/contact.md, "DEFI_CONT").

use std::rc::Rc;

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
        // Only present with FROTTEMENT='OUI' or ALGO_CONT='NITSCHE', both
        // refused by their values: one refusal, at the value.
        "ZONE/TYPE_FROT",
        "ZONE/COULOMB",
        "ZONE/TRESCA",
        "ZONE/ALGO_FROT",
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
        Values::new("ZONE/FROTTEMENT", &["NON"])
            .why("(friction of code_aster 17's mortar contact)"),
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
            z
        })
        .collect()
}

/// The force source of a definition on the model's current mesh (`dim`:
/// the model's space dimension).
pub(crate) fn source(
    zones: &[MortarZoneDef],
    mesh: &Mesh,
    axis: bool,
    dim: usize,
) -> Result<MortarLagrangian, ExecError> {
    MortarLagrangian::with_dim(zones, mesh, axis, dim)
        .map_err(|e| ExecError::new(format!("DEFI_CONT: {e}")))
}

pub fn defi_cont(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model_ref = ex.required("DEFI_CONT", kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    let dim = model.dim();
    // Shells: code_aster pairs their mid-surfaces with the thickness of
    // ZONE/CARA_ELEM and its own shell contact elements; not reproduced.
    if model.has_shells() {
        return Err(ex.kw_error(
            "DEFI_CONT",
            kw,
            "MODELE",
            "not supported yet: code_aster 17's mortar contact on a model with shells (DKT): reproduced on 2D models (D_PLAN, C_PLAN, AXIS) and 3D solids",
        ));
    }
    let axis = model
        .cells
        .values()
        .any(|m| *m == Modelisation::Axisymmetric);
    let mesh = ex.mesh_by_id(model.mesh)?;
    let zones = zones(kw);
    // The groups and cell kinds are checked now, located at the zone.
    for (occ, z) in kw.factor("ZONE").iter().zip(&zones) {
        if let Err(e) = MortarLagrangian::with_dim(std::slice::from_ref(z), &mesh, axis, dim) {
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
