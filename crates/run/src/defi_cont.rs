//! `DEFI_CONT`, code_aster 17's contact definition for `MECA_NON_LINE`
//! (`code_aster.MacroCommands.defi_cont`): its keywords turned into
//! `aster_contact::mortar_lagrangian`'s zones, and the force source built
//! from them at the solve.
//!
//! Reproduced: `ALGO_CONT='LAGRANGIEN'` with `VARIANTE='ROBUSTE'` (the
//! defaults) or `'CLASSIQUE'` (`aster_contact::mortar_classique`: 2D, with
//! `COEF_FROT`; 3D frictionless), `'PENALISATION'` (`aster_contact::mortar_penalty`) and
//! `'NITSCHE'` (`aster_contact::mortar_nitsche`, any `SYME`/`VARIANTE`:
//! code_aster's residual is the same for all), unilateral, on 2D models
//! (D_PLAN, C_PLAN, AXIS) whose contact cells are SEG2 or SEG3, zones of
//! different methods side by side (one force source per method,
//! [`groups`]), and — the
//! Lagrangian and penalised methods, frictionless — on 3D solid models
//! whose contact faces are TRIA3, QUAD4, TRIA6, QUAD8 or QUAD9
//! (`aster_contact::mortar_pairing3d`); `COEF_CONT`, `CONTACT_INIT`,
//! `SANS_GROUP_NO`, `SANS_GROUP_MA`, `COEF_MULT_APPA`, `TYPE_CONT`
//! (`BILATERAL`: every paired point active, frictionless), `DIST_SUPP` and
//! `CARA_ELEM` (`DIST_POUTRE`, `DIST_COQUE`: stored by code_aster 17 and
//! used by none of its computations, so without effect); with the Lagrangian
//! and penalised methods in 2D and on 3D solids (the Lagrangian on TRIA3,
//! QUAD4 faces; the penalised on every face kind),
//! friction (`FROTTEMENT='OUI'`, `TYPE_FROT`
//! `SANS`/`COULOMB`/`TRESCA`/`ADHERENT`, `aster_contact::mortar_friction`,
//! `aster_contact::mortar_friction_penalty`), its zones with or without
//! it; the CLASSIQUE variant in 2D, with or without friction, and
//! frictionless in 3D (`aster_contact::mortar_classique`). Refused,
//! located: CLASSIQUE friction in 3D, BILATERAL with friction, LISSAGE,
//! friction with NITSCHE, the Lagrangian friction on quadratic faces in
//! 3D, zones with and without friction with CLASSIQUE, Nitsche contact in
//! 3D (code_aster 2025 has no 3D Nitsche contact element), models with
//! shells (docs/contact.md, "DEFI_CONT"); zones sharing slave nodes stop
//! as code_aster's CONTACT1_1.

use std::rc::Rc;

use aster_contact::mortar_classique::MortarClassique;
use aster_contact::mortar_friction::{FrictionLaw, MortarFriction};
use aster_contact::mortar_friction_penalty::MortarFrictionPenalty;
use aster_contact::mortar_lagrangian::{InitialState, MortarLagrangian, MortarZoneDef};
use aster_contact::mortar_nitsche::{MortarNitsche, NitscheMaterial};
use aster_contact::mortar_penalty::MortarPenalty;
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_fem::ForceSource;
use aster_mesh::Mesh;

use crate::concept::{Concept, ContactDef, Material, MaterialField, Modelisation};
use crate::executor::{store_result, Executor};
use crate::support::{Refusal, Support, Values};

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
        // FROTTEMENT='OUI' (module aster_contact::mortar_friction) or
        // ALGO_CONT='NITSCHE' (SYME: every value gives code_aster's same
        // residual, see aster_contact::mortar_nitsche).
        "ZONE/TYPE_FROT",
        "ZONE/COULOMB",
        "ZONE/TRESCA",
        // ALGO_FROT follows ALGO_CONT in the catalog (one value each):
        // friction with NITSCHE is refused at FROTTEMENT (`rules`).
        "ZONE/ALGO_FROT",
        // VARIANTE='CLASSIQUE' with friction (aster_contact::mortar_classique).
        "ZONE/COEF_FROT",
        "ZONE/SYME",
        // Stored by code_aster 17's DEFI_CONT (`defi_cont_ops`:
        // PairingParameter.setDistanceFunction, setElementaryCharacteristics,
        // hasBeamDistance, hasShellDistance) and read by none of its
        // pairing or elementary computations (bibcxx/Contact,
        // bibfor/cont_elem): accepted, no effect, as there.
        "ZONE/DIST_SUPP",
        "ZONE/CARA_ELEM",
        "ZONE/DIST_POUTRE",
        "ZONE/DIST_COQUE",
    ],
    values: &[
        Values::new("ZONE/VARIANTE", &["ROBUSTE", "RAPIDE", "CLASSIQUE"]),
        Values::new("ZONE/LISSAGE", &["NON"]).why("(smoothed normals of the mortar contact: code_aster 17 stops on an assertion at the pairing, ContactPairing::compute, whenever a zone asks for them)"),
    ],
    hints: &[],
    reuse: false,
    rules: Some(rules),
};

/// `ALGO_CONT` of a DEFI_CONT: one for the whole definition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MortarAlgo {
    /// `'LAGRANGIEN'` (the default) with `VARIANTE='ROBUSTE'`: `LAGS_C`
    /// unknowns.
    #[default]
    Lagrangian,
    /// `'LAGRANGIEN'` with `VARIANTE='CLASSIQUE'`
    /// (`aster_contact::mortar_classique`).
    Classique,
    /// `'PENALISATION'`.
    Penalised,
    /// `'NITSCHE'`.
    Nitsche,
}

impl MortarAlgo {
    /// The method of a ZONE occurrence: its ALGO_CONT, and VARIANTE for
    /// the Lagrangian one.
    fn of(occ: &Keywords) -> MortarAlgo {
        match (occ.str("ALGO_CONT"), occ.str("VARIANTE")) {
            (Some("PENALISATION"), _) => MortarAlgo::Penalised,
            (Some("NITSCHE"), _) => MortarAlgo::Nitsche,
            (_, Some("CLASSIQUE")) => MortarAlgo::Classique,
            _ => MortarAlgo::Lagrangian,
        }
    }

    fn is_lagrangian(self) -> bool {
        matches!(self, MortarAlgo::Lagrangian | MortarAlgo::Classique)
    }
}

/// What the value lists cannot say: friction is built for the Lagrangian
/// and penalised methods only.
fn rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    for occ in call.keywords.factor("ZONE") {
        let algo = MortarAlgo::of(occ);
        if algo == MortarAlgo::Nitsche && occ.str("FROTTEMENT") == Some("OUI") {
            out.push(Refusal::at(
                "DEFI_CONT/ZONE/FROTTEMENT='OUI' with ALGO_CONT='NITSCHE' (friction of code_aster 17's Nitsche mortar contact: niVect/niMatr's friction terms)".into(),
                occ,
                "FROTTEMENT",
                call.span,
            ));
        }
        if occ.str("TYPE_CONT") == Some("BILATERAL") && occ.str("FROTTEMENT") == Some("OUI") {
            out.push(Refusal::at(
                "DEFI_CONT/ZONE/TYPE_CONT='BILATERAL' with FROTTEMENT='OUI' (code_aster's friction threshold −μ·projRm(λ + γg) turns negative where a bilateral zone is in tension: not validated)".into(),
                occ,
                "TYPE_CONT",
                call.span,
            ));
        }
    }
}

/// The method of each zone of a definition: code_aster 17 gives every
/// zone its own `ContactParameter` (`defi_cont_ops`), each zone's contact
/// cells computing with their zone's algorithm.
fn algos(kw: &Keywords) -> Vec<MortarAlgo> {
    kw.factor("ZONE").iter().map(MortarAlgo::of).collect()
}

/// The zones of a definition grouped by method, in the order the methods
/// first appear: one force source per method (the zones of a group keep
/// their relative order).
pub(crate) fn groups(
    zones: &[MortarZoneDef],
    algos: &[MortarAlgo],
) -> Vec<(MortarAlgo, Vec<MortarZoneDef>)> {
    let mut out: Vec<(MortarAlgo, Vec<MortarZoneDef>)> = Vec::new();
    for (z, &a) in zones.iter().zip(algos) {
        match out.iter_mut().find(|(b, _)| *b == a) {
            Some((_, g)) => g.push(z.clone()),
            None => out.push((a, vec![z.clone()])),
        }
    }
    out
}

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
            z.bilateral = occ.str("TYPE_CONT") == Some("BILATERAL");
            z.dist_ratio = occ.f64("COEF_MULT_APPA").filter(|r| *r > 0.0);
            z.excluded_node_groups = strings(occ, "SANS_GROUP_NO");
            z.excluded_cell_groups = strings(occ, "SANS_GROUP_MA");
            z.coef_frot = occ.f64("COEF_FROT").unwrap_or(100.0);
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

/// Whether a definition has friction (one of its zones has: code_aster's
/// `_hasFriction` builds a FrictionNew).
pub(crate) fn has_friction(zones: &[MortarZoneDef]) -> bool {
    zones.iter().any(|z| z.friction.is_some())
}

/// The frictional force source of a definition on the model's current
/// mesh.
pub(crate) fn friction_source(
    zones: &[MortarZoneDef],
    mesh: &Mesh,
    axis: bool,
    dim: usize,
    resi_geom: Option<f64>,
) -> Result<MortarFriction, ExecError> {
    let mut m = MortarFriction::new(zones, mesh, axis, dim)
        .map_err(|e| ExecError::new(format!("DEFI_CONT: {e}")))?;
    if let Some(r) = resi_geom {
        m.set_resi_geom(r);
    }
    Ok(m)
}

/// The material of a Nitsche contact: code_aster takes `ELAS` E and NU
/// of the CHAM_MATER's one material (`ContactComputation::contactData`
/// asserts there is one), whatever the behaviour.
pub(crate) fn nitsche_material(materials: &MaterialField) -> Result<NitscheMaterial, String> {
    let mut distinct: Vec<&Rc<Material>> = Vec::new();
    for m in materials.cells.values() {
        if !distinct.iter().any(|d| Rc::ptr_eq(d, m)) {
            distinct.push(m);
        }
    }
    match distinct.as_slice() {
        [m] if m.elastic && m.young.is_finite() && m.poisson.is_finite() => Ok(NitscheMaterial {
            young: m.young,
            poisson: m.poisson,
        }),
        [_] => Err("the material of a Nitsche contact (DEFI_CONT, ALGO_CONT='NITSCHE') has no constant ELAS E and NU: code_aster's Nitsche stress reads them".into()),
        _ => Err(format!(
            "{} materials in the CHAM_MATER of a Nitsche contact (DEFI_CONT, ALGO_CONT='NITSCHE'): code_aster's Nitsche stress takes ELAS E and NU of a single material",
            distinct.len()
        )),
    }
}

/// The force source of a penalised or Nitsche definition (`None` for the
/// Lagrangian method, whose source is [`source`]); `dim`: the model's
/// space dimension (Nitsche is 2D only, refused in 3D by [`defi_cont`]);
/// `resi_geom`: MECA_NON_LINE's `CONTACT/RESI_GEOM`,
/// code_aster 17's geometric criterion.
pub(crate) fn other_source(
    algo: MortarAlgo,
    zones: &[MortarZoneDef],
    mesh: &Mesh,
    axis: bool,
    dim: usize,
    materials: &MaterialField,
    resi_geom: Option<f64>,
) -> Result<Option<Box<dyn ForceSource>>, ExecError> {
    let fail = |e: aster_contact::ContactError| ExecError::new(format!("DEFI_CONT: {e}"));
    Ok(match algo {
        MortarAlgo::Lagrangian | MortarAlgo::Classique => None,
        MortarAlgo::Penalised if has_friction(zones) => {
            let mut source = MortarFrictionPenalty::new(zones, mesh, axis, dim).map_err(fail)?;
            if let Some(r) = resi_geom {
                source.set_resi_geom(r);
            }
            Some(Box::new(source))
        }
        MortarAlgo::Penalised => {
            let mut m = MortarPenalty::new(zones, mesh, axis, dim).map_err(fail)?;
            if let Some(r) = resi_geom {
                m.set_resi_geom(r);
            }
            Some(Box::new(m))
        }
        MortarAlgo::Nitsche => {
            let material = nitsche_material(materials)
                .map_err(|m| ExecError::new(format!("not supported yet: {m}")))?;
            let mut m = MortarNitsche::new(zones, mesh, axis, material).map_err(fail)?;
            if let Some(r) = resi_geom {
                m.set_resi_geom(r);
            }
            Some(Box::new(m))
        }
    })
}

/// The force source of a definition on the model's current mesh (`dim`:
/// the model's space dimension).
pub(crate) fn source(
    zones: &[MortarZoneDef],
    mesh: &Mesh,
    axis: bool,
    dim: usize,
    resi_geom: Option<f64>,
) -> Result<MortarLagrangian, ExecError> {
    let mut m = MortarLagrangian::new(zones, mesh, axis, dim)
        .map_err(|e| ExecError::new(format!("DEFI_CONT: {e}")))?;
    if let Some(r) = resi_geom {
        m.set_resi_geom(r);
    }
    Ok(m)
}

/// The force source of a CLASSIQUE definition on the model's current
/// mesh (`dim`: the model's space dimension): frictionless or with
/// friction in 2D, frictionless in 3D.
pub(crate) fn classique_source(
    zones: &[MortarZoneDef],
    mesh: &Mesh,
    axis: bool,
    dim: usize,
    resi_geom: Option<f64>,
) -> Result<MortarClassique, ExecError> {
    let mut m = MortarClassique::new(zones, mesh, axis, dim)
        .map_err(|e| ExecError::new(format!("DEFI_CONT: {e}")))?;
    if let Some(r) = resi_geom {
        m.set_resi_geom(r);
    }
    Ok(m)
}

pub fn defi_cont(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model_ref = ex.required("DEFI_CONT", kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    let dim = model.dim();
    let algos = algos(kw);
    let occs = kw.factor("ZONE");
    if dim != 2 {
        if let Some(occ) = occs.iter().zip(&algos).find_map(|(o, a)| {
            (*a == MortarAlgo::Classique && o.str("FROTTEMENT") == Some("OUI")).then_some(o)
        }) {
            return Err(ex.kw_error(
                "DEFI_CONT/ZONE",
                occ,
                "FROTTEMENT",
                "not supported yet: friction of code_aster 17's CLASSIQUE mortar contact in 3D (reproduced on 2D models: D_PLAN, C_PLAN, AXIS; frictionless CLASSIQUE and ROBUSTE with friction are reproduced in 3D)",
            ));
        }
    }
    // code_aster 2025 has no 3D Nitsche contact element: its list of
    // Nitsche contact cells (`contCellNits`, bibcxx/Contact/ContactPairing.h)
    // and `niElem` know the 2D volume cells only, so its MECA_NON_LINE stops
    // on an assertion (`getContCellIndx` finds no cell) at the first pairing.
    if let (true, Some(occ)) = (
        dim != 2,
        occs.iter()
            .zip(&algos)
            .find_map(|(o, a)| (*a == MortarAlgo::Nitsche).then_some(o)),
    ) {
        return Err(ex.kw_error(
            "DEFI_CONT/ZONE",
            occ,
            "ALGO_CONT",
            "not supported: ALGO_CONT='NITSCHE' in 3D has no contact element in code_aster 17 (its Nitsche cells, `contCellNits` and `niElem`, are the 2D ones: TRIA3, TRIA6, QUAD4, QUAD8, QUAD9 with SEG2/SEG3 masters; MECA_NON_LINE stops on an assertion at the pairing); reproduced on 2D models (D_PLAN, C_PLAN, AXIS)",
        ));
    }
    // Shells: code_aster 17's mortar contact cells (`contCellLagr`,
    // `contCellPena`: geometric pairs such as QUAD4/QUAD4) would act on
    // their mid-surfaces' DX DY DZ, the thickness of ZONE/CARA_ELEM being
    // stored and never read (`defi_cont_ops`, `PairingParameter`); not
    // validated here.
    if model.has_shells() {
        return Err(ex.kw_error(
            "DEFI_CONT",
            kw,
            "MODELE",
            "not supported yet: code_aster 17's mortar contact on a model with shells (DKT, COQUE_3D): reproduced on 2D models (D_PLAN, C_PLAN, AXIS) and 3D solids",
        ));
    }
    let axis = model
        .cells
        .values()
        .any(|m| *m == Modelisation::Axisymmetric);
    let mesh = ex.mesh_by_id(model.mesh)?;
    let zones = zones(kw);
    // Zones with and without friction in one definition: code_aster
    // builds one FrictionNew whose frictionless zones have frictionless
    // elements (CONT_LAG_SL_*: LAGS_C a pressure, no LAGS_F*; the
    // penalised elements with l_fric false), reproduced by the frictional
    // sources (`aster_contact::mortar_friction::split_zones`); the
    // CLASSIQUE variant's mixed zones are not.
    let classique_friction = zones
        .iter()
        .zip(&algos)
        .any(|(z, a)| *a == MortarAlgo::Classique && z.friction.is_some());
    for (i, occ) in occs.iter().enumerate() {
        if classique_friction && algos[i] == MortarAlgo::Classique && zones[i].friction.is_none() {
            return Err(ex.kw_error(
                "DEFI_CONT/ZONE",
                occ,
                "FROTTEMENT",
                "not supported yet: zones with and without friction in one DEFI_CONT with VARIANTE='CLASSIQUE' (reproduced with the ROBUSTE variant and the penalised method; with CLASSIQUE when every zone has FROTTEMENT='OUI')",
            ));
        }
    }
    // code_aster stops a definition whose zones share slave nodes, whatever
    // their methods (`ContactNew::build`, CONTACT1_1).
    let slave_nodes: Vec<std::collections::BTreeSet<u32>> = zones
        .iter()
        .map(|z| {
            mesh.group_ma(&z.slave_group)
                .map(|g| {
                    g.members
                        .iter()
                        .flat_map(|c| mesh.cell(*c).nodes.iter().map(|n| n.0))
                        .collect()
                })
                .unwrap_or_default()
        })
        .collect();
    for i in 0..zones.len() {
        if let Some(j) = (0..i).find(|&j| !slave_nodes[i].is_disjoint(&slave_nodes[j])) {
            return Err(ex
                .kw_error(
                    "DEFI_CONT/ZONE",
                    &occs[i],
                    "GROUP_MA_ESCL",
                    format!(
                        "the slave surface {} shares nodes with {} of zone {}: the slave nodes of the zones of one DEFI_CONT must be distinct (code_aster stops, ContactNew::build)",
                        zones[i].slave_group, zones[j].slave_group, j + 1
                    ),
                )
                .with_id("CONTACT1_1"));
        }
    }
    // The groups and cell kinds are checked now, located at the zone.
    for ((occ, z), algo) in occs.iter().zip(&zones).zip(&algos) {
        if let Err(e) = MortarLagrangian::new(std::slice::from_ref(z), &mesh, axis, dim) {
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
        // The Lagrangian friction in 3D: the faces it is reproduced on
        // (the penalised one takes every face kind of the pairing).
        if dim == 3 && z.friction.is_some() && algo.is_lagrangian() {
            if let Err(e) = MortarFriction::new(std::slice::from_ref(z), &mesh, axis, dim) {
                let at = if e.to_string().contains("GROUP_MA_MAIT") {
                    "GROUP_MA_MAIT"
                } else {
                    "GROUP_MA_ESCL"
                };
                return Err(ex.kw_error("DEFI_CONT/ZONE", occ, at, e.to_string()));
            }
        }
    }
    // Nitsche: the volume cell under every slave face.
    if algos.contains(&MortarAlgo::Nitsche) {
        let any = NitscheMaterial {
            young: 1.0,
            poisson: 0.0,
        };
        for (i, (occ, z)) in occs
            .iter()
            .zip(&zones)
            .enumerate()
            .filter(|(i, _)| algos[*i] == MortarAlgo::Nitsche)
        {
            match MortarNitsche::new(std::slice::from_ref(z), &mesh, axis, any) {
                Ok(_) => {}
                Err(aster_contact::ContactError::SlaveWithoutVolume { .. }) => {
                    // The zone alone was checked: name it by its occurrence.
                    let e = aster_contact::ContactError::SlaveWithoutVolume { zone: i + 1 };
                    return Err(ex
                        .kw_error("DEFI_CONT/ZONE", occ, "GROUP_MA_ESCL", e.to_string())
                        .with_id("CONTACT1_3"));
                }
                Err(e) => {
                    return Err(ex.kw_error("DEFI_CONT/ZONE", occ, "GROUP_MA_ESCL", e.to_string()))
                }
            }
        }
    }
    let def = ContactDef::Mortar {
        model: model_ref.id,
        zones,
        algos,
    };
    store_result(ex, call, Concept::Contact(Rc::new(def)))
}
