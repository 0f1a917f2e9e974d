//! STAT_NON_LINE, MECA_STATIQUE and CALC_CHAMP: keywords → a plain
//! [`SolveSetup`], handed to aster-fem (see `fembridge`).

use crate::concept::*;
use crate::executor::{store_result, Executor};
use crate::function::Function;
use crate::list;
use crate::support::{Refusal, Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use std::rc::Rc;

/// A load of `EXCIT`.
#[derive(Clone, Debug)]
pub enum LoadRef {
    Kinematic(Rc<KinematicLoad>),
    Mechanical(Rc<MechanicalLoad>),
}

/// One `EXCIT` occurrence: a load and its time multiplier (`FONC_MULT`,
/// 1 when absent).
#[derive(Clone, Debug)]
pub struct Excitation {
    pub load: LoadRef,
    pub multiplier: Option<Rc<Function>>,
    /// `TYPE_CHARGE` (STAT_NON_LINE: `SUIV`, `DIDI`).
    pub kind: ChargeType,
}

/// `EXCIT/TYPE_CHARGE`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ChargeType {
    /// `FIXE_CSTE`: a dead load, imposed values as given.
    #[default]
    FixeCste,
    /// `SUIV`: the pressures follow the current configuration
    /// (`aster_fem::follower`).
    Suiv,
    /// `DIDI`: the dualised imposed values are relative to the
    /// displacement of the initial state (code_aster's `nmdidi`, `vecdid`).
    Didi,
}

/// `COMPORTEMENT/RELATION`, as far as supported.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    Elas,
    /// Von Mises, linear isotropic hardening (material's ECRO_LINE).
    VmisIsotLine,
    /// Von Mises, isotropic hardening by a traction curve (TRACTION).
    VmisIsotTrac,
    /// Lemaitre's viscoplasticity (material's LEMAITRE), small strains.
    Lemaitre,
    /// Von Mises, non-linear isotropic hardening (material's ECRO_NL).
    VmisIsotNl,
    /// Cohesive law of the joint elements (material's RUPT_FRAG).
    CzmLinReg,
    /// Turon's cohesive law of the joint elements (material's RUPT_TURON).
    CzmTuron,
    /// Von Mises, Johnson–Cook rate-dependent hardening (material's
    /// ECRO_COOK), code_aster's `nmtevp`.
    VmisJohnCook,
    /// Von Mises, linear kinematic hardening (material's ECRO_LINE),
    /// code_aster's `nmcine`.
    VmisCineLine,
    /// Reinforcement grids, uniaxial plasticity along the bars with linear
    /// isotropic hardening (material's ECRO_LINE), code_aster's `nm1dis`.
    GrilleIsotLine,
    /// The same with linear kinematic hardening, code_aster's `nm1dci`.
    GrilleCineLine,
    /// Hencky's non-linear elasticity with a linear hardening curve
    /// (material's ECRO_LINE), code_aster's `lcelnl`.
    ElasVmisLine,
    /// Hencky's non-linear elasticity with a traction curve (TRACTION),
    /// code_aster's `lcelnl`.
    ElasVmisTrac,
}

impl Relation {
    pub fn keyword(self) -> &'static str {
        match self {
            Relation::Elas => "ELAS",
            Relation::VmisIsotLine => "VMIS_ISOT_LINE",
            Relation::VmisIsotTrac => "VMIS_ISOT_TRAC",
            Relation::Lemaitre => "LEMAITRE",
            Relation::VmisIsotNl => "VMIS_ISOT_NL",
            Relation::CzmLinReg => "CZM_LIN_REG",
            Relation::CzmTuron => "CZM_TURON",
            Relation::VmisJohnCook => "VMIS_JOHN_COOK",
            Relation::VmisCineLine => "VMIS_CINE_LINE",
            Relation::GrilleIsotLine => "GRILLE_ISOT_LINE",
            Relation::GrilleCineLine => "GRILLE_CINE_LINE",
            Relation::ElasVmisLine => "ELAS_VMIS_LINE",
            Relation::ElasVmisTrac => "ELAS_VMIS_TRAC",
        }
    }
}

/// One `COMPORTEMENT` occurrence: a relation under a kinematics
/// (`DEFORMATION`) on cells (`None`: all, the default TOUT='OUI').
#[derive(Clone, Debug, PartialEq)]
pub struct BehaviourOcc {
    pub relation: Relation,
    pub kinematics: aster_fem::Kinematics,
    pub cells: Option<Vec<aster_mesh::CellId>>,
    /// The local integration settings the viscous laws use.
    pub local: LocalIntegration,
}

/// `PARM_THETA`, `RESI_INTE_RELA`, `ITER_INTE_MAXI` of a `COMPORTEMENT`
/// occurrence (code_aster's defaults 1, 1e-6, 20).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalIntegration {
    pub theta: f64,
    pub resi_inte: f64,
    pub iter_inte_maxi: usize,
}

/// Newton and convergence settings (`NEWTON`, `CONVERGENCE`).
#[derive(Clone, Debug, PartialEq)]
pub struct NewtonSettings {
    /// `RESI_GLOB_RELA`; code_aster's default 1e-6 applies when neither
    /// criterion is given.
    pub resi_glob_rela: Option<f64>,
    pub resi_glob_maxi: Option<f64>,
    pub iter_glob_maxi: usize,
    /// `REAC_ITER`: re-assemble the tangent every n iterations (0: never).
    pub reac_iter: usize,
    /// `MATRICE`.
    pub matrix: aster_fem::MatrixKind,
    /// `PREDICTION`.
    pub prediction: aster_fem::Prediction,
    /// `CONVERGENCE/VERIF='AU_MOINS_UN'`: one criterion met is enough.
    pub at_least_one: bool,
    /// `MATR_RIGI_SYME='OUI'`.
    pub symmetrize: bool,
    /// `RECH_LINEAIRE` (`crate::line_search`).
    pub line_search: Option<aster_fem::LineSearch>,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            resi_glob_rela: Some(1e-6),
            resi_glob_maxi: None,
            iter_glob_maxi: 10,
            reac_iter: 1,
            matrix: aster_fem::MatrixKind::Tangente,
            prediction: aster_fem::Prediction::Tangente,
            at_least_one: false,
            symmetrize: false,
            line_search: None,
        }
    }
}

/// Everything a static computation needs, with no keyword left.
#[derive(Clone, Debug)]
pub struct SolveSetup {
    pub model: Rc<ModelDef>,
    pub materials: Rc<MaterialField>,
    pub cara: Option<Rc<CaraElem>>,
    pub excitations: Vec<Excitation>,
    pub contact: Option<Rc<ContactDef>>,
    /// `COMPORTEMENT`, in order (a later occurrence wins on a cell).
    pub behaviours: Vec<BehaviourOcc>,
    /// The instants: the first is the initial state, each next one a step.
    pub instants: Vec<f64>,
    pub newton: NewtonSettings,
    /// `ETAT_INIT/EVOL_NOLI` and the instant taken from it.
    pub initial: Option<(Rc<EvolResult>, f64)>,
    /// `INFO=2`: print the iterations.
    pub verbose: bool,
    /// What to do with a failed increment (`DEFI_LIST_INST/ECHEC`; a
    /// plain list of reals gets code_aster's default cutting).
    pub subdivision: Option<aster_fem::Subdivision>,
    /// Where the DEFI_LIST_INST was defined, for messages.
    pub time_list_at: Option<String>,
    /// `ETAT_INIT/DEPL`, `VITE`, `ACCE` fields (without EVOL_NOLI).
    pub initial_fields: InitialFields,
    /// DYNA_NON_LINE's time scheme and mass (`None`: statics).
    pub dynamics: Option<crate::dyna::DynamicSetup>,
    /// `ARCHIVAGE`: the steps stored.
    pub archive: crate::archive::Archive,
    /// Why a failed increment may not be cut here (aster-fem's
    /// `StaticNonLinear::cut_refused`), with where it was decided.
    pub cut_refused: Option<String>,
    /// `DEFI_LIST_INST/ECHEC/EVENEMENT='INTERPENETRATION'`.
    pub penalty_adaptation: Option<aster_fem::PenaltyAdaptation>,
    /// MECA_NON_LINE's `CONTACT/RESI_GEOM` (code_aster 17's geometric
    /// criterion of a DEFI_CONT contact; `None` elsewhere).
    pub contact_resi_geom: Option<f64>,
}

/// Initial fields given one by one in `ETAT_INIT` (`DEPL`, and in
/// dynamics `VITE`, `ACCE`), each with where its keyword is written.
#[derive(Clone, Debug, Default)]
pub struct InitialFields {
    pub depl: Option<(Rc<crate::field::Field>, aster_syntax::Span)>,
    pub vite: Option<(Rc<crate::field::Field>, aster_syntax::Span)>,
    pub acce: Option<(Rc<crate::field::Field>, aster_syntax::Span)>,
}

/// The keywords STAT_NON_LINE reads (also DYNA_NON_LINE's and
/// MECA_NON_LINE's: the same set-up).
pub(crate) const SNL_KEYWORDS: &[&str] = &[
    "MODELE",
    "CHAM_MATER",
    "CARA_ELEM",
    "EXCIT",
    "EXCIT/CHARGE",
    "EXCIT/FONC_MULT",
    "EXCIT/TYPE_CHARGE",
    "CONTACT",
    "COMPORTEMENT",
    "COMPORTEMENT/RELATION",
    "COMPORTEMENT/DEFORMATION",
    "COMPORTEMENT/TOUT",
    "COMPORTEMENT/GROUP_MA",
    "COMPORTEMENT/MAILLE",
    // Local (Gauss-point) integration settings: the radial return of the
    // von Mises laws is exact, so they change nothing; LEMAITRE's scalar
    // equation uses RESI_INTE_RELA, ITER_INTE_MAXI and its θ-scheme
    // PARM_THETA (refused with the other relations but at its default 1);
    // VMIS_JOHN_COOK's search stops at RESI_INTE within ITER_INTE_MAXI
    // (ALGO_INTE='BRENT' only).
    "COMPORTEMENT/PARM_THETA",
    "COMPORTEMENT/RESI_INTE_RELA",
    "COMPORTEMENT/RESI_INTE",
    "COMPORTEMENT/ITER_INTE_MAXI",
    "COMPORTEMENT/ITER_INTE_PAS",
    "COMPORTEMENT/ALGO_INTE",
    "INCREMENT",
    "INCREMENT/LIST_INST",
    "INCREMENT/INST_INIT",
    "INCREMENT/INST_FIN",
    "INCREMENT/NUME_INST_INIT",
    "INCREMENT/NUME_INST_FIN",
    "INCREMENT/PRECISION",
    "METHODE",
    "NEWTON",
    "NEWTON/PREDICTION",
    "NEWTON/MATRICE",
    "NEWTON/REAC_ITER",
    "NEWTON/REAC_INCR",
    "NEWTON/MATR_RIGI_SYME",
    "NEWTON/REAC_ITER_ELAS",
    "NEWTON/PAS_MINI_ELAS",
    // The prediction from a previous result only changes the first
    // iterate; the converged steps are the same.
    "NEWTON/EVOL_NOLI",
    "CONVERGENCE",
    "CONVERGENCE/RESI_GLOB_RELA",
    "CONVERGENCE/RESI_GLOB_MAXI",
    "CONVERGENCE/ITER_GLOB_MAXI",
    "CONVERGENCE/ITER_GLOB_ELAS",
    "CONVERGENCE/ARRET",
    // 'AU_MOINS_UN': one of RESI_GLOB_RELA/MAXI met is enough.
    "CONVERGENCE/VERIF",
    // Module `line_search`.
    "RECH_LINEAIRE",
    "RECH_LINEAIRE/METHODE",
    "RECH_LINEAIRE/RESI_LINE_RELA",
    "RECH_LINEAIRE/ITER_LINE_MAXI",
    "RECH_LINEAIRE/RHO_MIN",
    "RECH_LINEAIRE/RHO_MAX",
    "RECH_LINEAIRE/RHO_EXCL",
    "SOLVEUR",
    "SOLVEUR/*",
    "ETAT_INIT",
    "ETAT_INIT/EVOL_NOLI",
    "ETAT_INIT/DEPL",
    "ETAT_INIT/INST",
    "ETAT_INIT/NUME_ORDRE",
    "ETAT_INIT/PRECISION",
    "ETAT_INIT/CRITERE",
    "INFO",
    // Debugging output of code_aster's internals: nothing to print here.
    "INFO_DBG",
    "TITRE",
    "AFFICHAGE",
    "AFFICHAGE/*",
    "ARCHIVAGE",
    "ARCHIVAGE/*",
    "MESURE",
    "MESURE/*",
    // Columns of the convergence table code_aster prints (the values of
    // chosen components at each Newton iteration): nothing to print here.
    "SUIVI_DDL",
    "SUIVI_DDL/*",
    // Module `observation`.
    "OBSERVATION",
    "OBSERVATION/NOM_CHAM",
    "OBSERVATION/NOM_CMP",
    "OBSERVATION/EVAL_CMP",
    "OBSERVATION/EVAL_CHAM",
    "OBSERVATION/EVAL_ELGA",
    "OBSERVATION/TITRE",
    "OBSERVATION/OBSE_ETAT_INIT",
    "OBSERVATION/INST",
    "OBSERVATION/LIST_INST",
    "OBSERVATION/PAS_OBSE",
    "OBSERVATION/CRITERE",
    "OBSERVATION/PRECISION",
    "OBSERVATION/TOUT",
    "OBSERVATION/NOEUD",
    "OBSERVATION/GROUP_NO",
    "OBSERVATION/MAILLE",
    "OBSERVATION/GROUP_MA",
    "OBSERVATION/POINT",
    "OBSERVATION/SOUS_POINT",
];

/// The values DYNA_NON_LINE and MECA_NON_LINE handle (STAT_NON_LINE's
/// but the follower and differential loads).
pub(crate) const SNL_VALUES: &[Values] =
    &crate::support::joined::<_, { SNL_COMMON_VALUES.len() + 1 }>(
        &[Values::new("EXCIT/TYPE_CHARGE", &["FIXE_CSTE"])],
        SNL_COMMON_VALUES,
    );

/// The values STAT_NON_LINE handles: `TYPE_CHARGE='SUIV'` on pressures
/// (`aster_fem::follower`) and `'DIDI'` besides the common ones.
const STAT_VALUES: &[Values] = &crate::support::joined::<_, { SNL_COMMON_VALUES.len() + 1 }>(
    &[Values::new(
        "EXCIT/TYPE_CHARGE",
        &["FIXE_CSTE", "SUIV", "DIDI"],
    )],
    SNL_COMMON_VALUES,
);

/// The values STAT_NON_LINE, DYNA_NON_LINE and MECA_NON_LINE share.
const SNL_COMMON_VALUES: &[Values] = &[
    crate::line_search::VALUES,
    // NEWTON_KRYLOV is Newton with inexact iterative linear solves: with
    // the direct solver here it is Newton.
    Values::new("METHODE", &["NEWTON", "NEWTON_KRYLOV"]),
    Values::new("CONVERGENCE/ARRET", &["OUI"]),
    Values::new(
        "NEWTON/PREDICTION",
        &["ELASTIQUE", "TANGENTE", "DEPL_CALCULE", "EXTRAPOLE"],
    ),
    Values::new("NEWTON/MATRICE", &["TANGENTE", "ELASTIQUE"]),
    Values::listed(
        "COMPORTEMENT/RELATION",
        &[
            "ELAS",
            "VMIS_ISOT_LINE",
            "VMIS_ISOT_TRAC",
            "VMIS_ISOT_NL",
            "VMIS_JOHN_COOK",
            "VMIS_CINE_LINE",
            "LEMAITRE",
            "CZM_LIN_REG",
            "CZM_TURON",
            "GRILLE_ISOT_LINE",
            "GRILLE_CINE_LINE",
            "ELAS_VMIS_LINE",
            "ELAS_VMIS_TRAC",
        ],
    ),
    Values::listed(
        "COMPORTEMENT/DEFORMATION",
        &[
            "PETIT",
            "PETIT_REAC",
            "GREEN_LAGRANGE",
            "GROT_GDEP",
            "GDEF_LOG",
            "SIMO_MIEHE",
        ],
    ),
];

/// The static substructures' load cases (`crate::commands::substructure`):
/// STAT_NON_LINE's only (DYNA_NON_LINE shares the rest of its keywords).
const SOUS_STRUC_KEYWORDS: &[&str] = &[
    "SOUS_STRUC",
    "SOUS_STRUC/CAS_CHARGE",
    "SOUS_STRUC/TOUT",
    "SOUS_STRUC/SUPER_MAILLE",
    "SOUS_STRUC/FONC_MULT",
];

/// What STAT_NON_LINE reads (`crate::support`).
pub(crate) const STAT_NON_LINE: Support = Support {
    keywords: &crate::support::joined::<_, { SNL_KEYWORDS.len() + SOUS_STRUC_KEYWORDS.len() }>(
        SNL_KEYWORDS,
        SOUS_STRUC_KEYWORDS,
    ),
    values: STAT_VALUES,
    hints: &[],
    reuse: true,
    rules: Some(snl_rules),
};

/// The rules STAT_NON_LINE, DYNA_NON_LINE and MECA_NON_LINE share: the
/// kinematics and `RECH_LINEAIRE` (`crate::line_search`).
pub(crate) fn snl_rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    kinematics_rules(call, out);
    crate::line_search::rules(call, out);
}

/// The DEFORMATION a relation cannot take: GROT_GDEP on continuum
/// elements is code_aster's hyperelastic kinematics (with ELAS it is Saint
/// Venant-Kirchhoff, the same as GREEN_LAGRANGE), SIMO_MIEHE is for the
/// plastic laws.
pub(crate) fn kinematics_rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    for occ in call.keywords.factor("COMPORTEMENT") {
        let relation = occ.str("RELATION").unwrap_or("ELAS");
        let why = match (occ.str("DEFORMATION"), relation) {
            (Some("GROT_GDEP"), r) if r != "ELAS" => format!(
                "with RELATION='{r}' (GROT_GDEP on continuum elements is for hyperelastic laws; GREEN_LAGRANGE carries small-strain laws)"
            ),
            (Some("SIMO_MIEHE"), "ELAS") => {
                "with RELATION='ELAS' (code_aster's SIMO_MIEHE is for the plastic laws)".into()
            }
            (Some(d), "LEMAITRE") if d != "PETIT" => {
                "with RELATION='LEMAITRE' (its viscoplastic integration is implemented in small strains only)".into()
            }
            _ => {
                if relation != "LEMAITRE" && occ.f64("PARM_THETA").is_some_and(|t| t != 1.0) {
                    out.push(Refusal::at(
                        format!(
                            "{}/COMPORTEMENT/PARM_THETA other than 1 with RELATION='{relation}' (the θ-scheme is implemented for LEMAITRE only)",
                            call.command
                        ),
                        occ,
                        "PARM_THETA",
                        call.span,
                    ));
                }
                continue;
            }
        };
        let d = occ.str("DEFORMATION").unwrap_or_default();
        out.push(Refusal::at(
            format!("{}/COMPORTEMENT/DEFORMATION='{d}' {why}", call.command),
            occ,
            "DEFORMATION",
            call.span,
        ));
    }
}

/// A load concept (`char_meca`, `char_cine_meca`) as `at` names it.
pub(crate) fn load_ref(
    ex: &Executor,
    at: &str,
    c: &aster_eval::ConceptRef,
) -> Result<LoadRef, ExecError> {
    match ex.concept(c)? {
        Concept::KinematicLoad(l) => Ok(LoadRef::Kinematic(l.clone())),
        Concept::MechanicalLoad(l) => Ok(LoadRef::Mechanical(l.clone())),
        other => Err(ExecError::new(format!(
            "{at}: `{}` is {}, expected a load",
            c.name,
            other.kind()
        ))),
    }
}

fn parse_excitations(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
) -> Result<Vec<Excitation>, ExecError> {
    let mut out = Vec::new();
    for occ in kw.factor("EXCIT") {
        let c = ex.required(&format!("{cmd}/EXCIT"), occ, "CHARGE")?;
        let load = load_ref(ex, &format!("{cmd}/EXCIT/CHARGE"), c)?;
        let multiplier = match occ.concept("FONC_MULT") {
            Some(f) => Some(ex.function(f)?),
            None => None,
        };
        let kind = match occ.str("TYPE_CHARGE") {
            Some("SUIV") => ChargeType::Suiv,
            Some("DIDI") => ChargeType::Didi,
            _ => ChargeType::FixeCste,
        };
        if kind != ChargeType::FixeCste {
            check_charge_type(ex, cmd, occ, &load, kind)?;
        }
        if kind != ChargeType::Suiv {
            check_dead_pressures(ex, cmd, occ, &load)?;
        }
        out.push(Excitation {
            load,
            multiplier,
            kind,
        });
    }
    Ok(out)
}

/// A dead load's pressures (`PRES_REP` of AFFE_CHAR_MECA_F) take
/// functions of INST and of the initial coordinates, not of the current
/// coordinates `XF`, `YF`, `ZF`, which only a follower load knows.
fn check_dead_pressures(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    load: &LoadRef,
) -> Result<(), ExecError> {
    let LoadRef::Mechanical(l) = load else {
        return Ok(());
    };
    for b in &l.boundary_fn {
        let crate::concept::BoundaryFn::Pressure { pressure, .. } = b else {
            continue;
        };
        let params = pressure.0.parameters();
        let current = params.iter().any(|p| ["XF", "YF", "ZF"].contains(p));
        if current {
            let span = occ.keyword("CHARGE").map(|k| k.span).unwrap_or_default();
            return Err(ex.unsupported(
                &format!(
                    "{cmd}/EXCIT/CHARGE: a PRES_REP function of the current coordinates XF, YF, ZF in a load that is not TYPE_CHARGE='SUIV' (XF, YF, ZF are the current coordinates of a follower load)"
                ),
                span,
            ));
        }
    }
    Ok(())
}

/// What `TYPE_CHARGE='SUIV'`/`'DIDI'` is executed on: STAT_NON_LINE
/// only; a follower load made of pressures (`PRES_REP`) alone, constant
/// or functions of INST and of the initial (`X`, `Y`, `Z`) or current
/// (`XF`, `YF`, `ZF`) coordinates.
fn check_charge_type(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    load: &LoadRef,
    kind: ChargeType,
) -> Result<(), ExecError> {
    let value = if kind == ChargeType::Suiv {
        "SUIV"
    } else {
        "DIDI"
    };
    let refuse = |why: &str| {
        let span = occ
            .keyword("TYPE_CHARGE")
            .map(|k| k.span)
            .unwrap_or_default();
        Err(ex.unsupported(&format!("{cmd}/EXCIT/TYPE_CHARGE='{value}' {why}"), span))
    };
    if cmd != "STAT_NON_LINE" {
        return refuse("outside STAT_NON_LINE (implemented for STAT_NON_LINE only)");
    }
    if kind == ChargeType::Didi {
        return Ok(());
    }
    let LoadRef::Mechanical(l) = load else {
        return refuse(
            "on an AFFE_CHAR_CINE load (code_aster refuses it: a follower load is a force)",
        );
    };
    let others = !l.imposed.is_empty()
        || !l.relations.is_empty()
        || !l.nodal_forces.is_empty()
        || !l.volume.is_empty()
        || !l.gravity.is_empty()
        || !l.edges.is_empty()
        || !l.shells.is_empty()
        || !l.imposed_fn.is_empty()
        || !l.nodal_forces_fn.is_empty()
        || !l.relations_fn.is_empty()
        || l.boundary
            .iter()
            .any(|b| !matches!(b, crate::concept::BoundaryLoad::Pressure { .. }))
        || l.boundary_fn
            .iter()
            .any(|b| !matches!(b, crate::concept::BoundaryFn::Pressure { .. }));
    if others {
        return refuse("on a load with other things than PRES_REP (the follower load is implemented for pressures on continuum faces and edges: FORCE_COQUE, FORCE_FACE, PESANTEUR… are not)");
    }
    Ok(())
}

pub(crate) fn parse_setup(
    ex: &Executor,
    call: &CommandCall,
    linear: bool,
) -> Result<SolveSetup, ExecError> {
    let cmd = call.command.as_str();
    let kw = &call.keywords;
    let own_model = ex.model(ex.required(cmd, kw, "MODELE")?)?;
    let materials = ex.material_field(ex.required(cmd, kw, "CHAM_MATER")?)?;
    let cara = match kw.concept("CARA_ELEM") {
        Some(c) => Some(ex.cara_elem(c)?),
        None => None,
    };
    let mut excitations = parse_excitations(ex, cmd, kw)?;
    // Super cells: their macro elements' cells and loads join the solve.
    let (model, materials) = crate::commands::substructure::expand(
        ex,
        call,
        own_model.clone(),
        materials,
        &mut excitations,
    )?;
    // STAT_NON_LINE/DYNA_NON_LINE: CONTACT=DEFI_CONTACT; MECA_NON_LINE:
    // CONTACT=_F(DEFINITION=DEFI_CONT, …) (crate::meca_non_line).
    let contact_factor = kw.factor("CONTACT");
    let contact_ref = kw
        .concept("CONTACT")
        .or_else(|| contact_factor.first().and_then(|o| o.concept("DEFINITION")));
    let contact = match contact_ref {
        Some(c) => Some(ex.contact(c)?),
        None => None,
    };
    let behaviours = parse_behaviours(ex, cmd, kw, &model)?;
    crate::commands::substructure::check_behaviours(ex, call, &own_model, &behaviours)?;
    crate::shells::check_solve(ex, call, &model, &behaviours)?;
    let mut newton = NewtonSettings::default();
    if let Some(conv) = kw.factor("CONVERGENCE").first() {
        let rela = conv.f64("RESI_GLOB_RELA");
        let maxi = conv.f64("RESI_GLOB_MAXI");
        // code_aster: RESI_GLOB_RELA=1e-6 unless only RESI_GLOB_MAXI is given.
        newton.resi_glob_rela = if rela.is_none() && maxi.is_some() {
            None
        } else {
            Some(rela.unwrap_or(1e-6))
        };
        newton.resi_glob_maxi = maxi;
        if let Some(n) = conv.first("ITER_GLOB_MAXI").and_then(|s| s.as_i64()) {
            newton.iter_glob_maxi = n.max(1) as usize;
        }
        newton.at_least_one = conv.str("VERIF") == Some("AU_MOINS_UN");
    }
    if let Some(nw) = kw.factor("NEWTON").first() {
        if let Some(n) = nw.first("REAC_ITER").and_then(|s| s.as_i64()) {
            newton.reac_iter = n.max(0) as usize;
        }
        newton.prediction = match nw.str("PREDICTION") {
            Some("ELASTIQUE") => aster_fem::Prediction::Elastique,
            Some("DEPL_CALCULE") => aster_fem::Prediction::DeplCalcule,
            Some("EXTRAPOLE") => aster_fem::Prediction::Extrapole,
            _ => aster_fem::Prediction::Tangente,
        };
        if nw.str("MATRICE") == Some("ELASTIQUE") {
            newton.matrix = aster_fem::MatrixKind::Elastique;
        }
        newton.symmetrize = nw.str("MATR_RIGI_SYME") == Some("OUI");
    }
    newton.line_search = crate::line_search::parse(call);
    let mut subdivision = None;
    let mut time_list_at = None;
    let mut penalty_adaptation = None;
    let mut initial_fields = InitialFields::default();
    let (instants, initial) = if linear {
        instants_linear(ex, kw)?
    } else {
        let Some(inc) = kw.factor("INCREMENT").first() else {
            return Err(ExecError::new(format!("{cmd}: INCREMENT is required")));
        };
        let l = ex.required(&format!("{cmd}/INCREMENT"), inc, "LIST_INST")?;
        let list = ex.real_list(l)?;
        (subdivision, time_list_at) = ex.time_stepping(l)?;
        penalty_adaptation = ex.penalty_adaptation(l)?;
        if penalty_adaptation.is_some() {
            let discrete_friction = contact.as_deref().is_some_and(|c| match c {
                ContactDef::Zones { keywords, .. } => {
                    keywords.str("FORMULATION").unwrap_or("DISCRETE") == "DISCRETE"
                        && keywords.str("FROTTEMENT") == Some("COULOMB")
                }
                _ => false,
            });
            if !discrete_friction {
                return Err(ex.unsupported(
                    &format!(
                        "{cmd}/INCREMENT/LIST_INST with ECHEC/EVENEMENT='INTERPENETRATION'{} without a discrete penalised friction contact (FORMULATION='DISCRETE', FROTTEMENT='COULOMB'): the penalty adaptation is done for that contact only",
                        time_list_at.as_ref().map(|l| format!(" (defined at {l})")).unwrap_or_default()
                    ),
                    inc.keyword("LIST_INST").map_or(call.span, |k| k.span),
                ));
            }
        }
        let mut init = inc.f64("INST_INIT");
        let mut fin = inc.f64("INST_FIN");
        if let Some(n) = inc.first("NUME_INST_INIT").and_then(|s| s.as_i64()) {
            init = Some(*list.get(n as usize).ok_or_else(|| {
                ExecError::new(format!(
                    "{cmd}/INCREMENT/NUME_INST_INIT={n}: the list has {} instants",
                    list.len()
                ))
            })?);
        }
        if let Some(n) = inc.first("NUME_INST_FIN").and_then(|s| s.as_i64()) {
            fin = Some(*list.get(n as usize).ok_or_else(|| {
                ExecError::new(format!(
                    "{cmd}/INCREMENT/NUME_INST_FIN={n}: the list has {} instants",
                    list.len()
                ))
            })?);
        }
        let mut initial = None;
        if let Some(ei) = kw.factor("ETAT_INIT").first() {
            if let Some(r) = ei.concept("EVOL_NOLI") {
                // code_aster's DEPL would replace the result's displacement.
                for name in ["DEPL", "VITE", "ACCE"] {
                    if let Some(k) = ei.keyword(name) {
                        return Err(ex.unsupported(
                            &format!("{cmd}/ETAT_INIT/{name} together with EVOL_NOLI (a field replacing the initial result's)"),
                            k.span,
                        ));
                    }
                }
                let prev = ex.result(r)?;
                let step = if let Some(t) = ei.f64("INST") {
                    prev.step_at(t, 1e-6, false)
                } else if let Some(n) = ei.first("NUME_ORDRE").and_then(|s| s.as_i64()) {
                    prev.step_numbered(n as u32)
                } else {
                    prev.steps.last()
                }
                .ok_or_else(|| {
                    ExecError::new(format!(
                        "{cmd}/ETAT_INIT: the instant asked is not in `{}`",
                        r.name
                    ))
                })?;
                let t0 = step.inst;
                if init.is_none() {
                    init = Some(t0);
                }
                initial = Some((prev.clone(), t0));
            } else {
                // Fields one by one (the keywords a command accepts are
                // checked by its list).
                for (name, slot) in [
                    ("DEPL", &mut initial_fields.depl),
                    ("VITE", &mut initial_fields.vite),
                    ("ACCE", &mut initial_fields.acce),
                ] {
                    if let (Some(c), Some(k)) = (ei.concept(name), ei.keyword(name)) {
                        *slot = Some((ex.field(c)?, k.span));
                    }
                }
                if initial_fields.depl.is_none()
                    && initial_fields.vite.is_none()
                    && initial_fields.acce.is_none()
                {
                    let span = ei.entries.first().map(|k| k.span).unwrap_or(call.span);
                    return Err(ex.unsupported(
                        &format!("{cmd}/ETAT_INIT without EVOL_NOLI, DEPL, VITE or ACCE"),
                        span,
                    ));
                }
            }
        }
        let instants = list::select_instants(&list, init, fin)
            .map_err(|e| ExecError::new(format!("{cmd}/INCREMENT: {e}")))?;
        (instants, initial)
    };
    // NEWTON/PAS_MINI_ELAS: code_aster iterates a step shorter than it on
    // the elastic matrix (`swapMatrToSecant`, ITER_GLOB_ELAS iterations);
    // not reproduced, so refused where it changes the iterations (a step
    // below it with a non-elastic behaviour).
    if let Some(nw) = kw.factor("NEWTON").first() {
        if let Some(pme) = nw.f64("PAS_MINI_ELAS") {
            let short = instants.windows(2).any(|w| (w[1] - w[0]).abs() < pme);
            if short && behaviours.iter().any(|b| b.relation != Relation::Elas) {
                let span = nw
                    .keyword("PAS_MINI_ELAS")
                    .map(|k| k.span)
                    .unwrap_or(call.span);
                return Err(ex.unsupported(
                    &format!(
                        "{cmd}/NEWTON/PAS_MINI_ELAS={pme} with a step shorter than it and a non-elastic COMPORTEMENT: code_aster's elastic-matrix iterations of those steps (swapMatrToSecant, ITER_GLOB_ELAS) are not reproduced"
                    ),
                    span,
                ));
            }
        }
    }
    Ok(SolveSetup {
        model,
        materials,
        cara,
        excitations,
        contact,
        behaviours,
        instants,
        newton,
        initial,
        verbose: kw.first("INFO").and_then(|s| s.as_i64()) == Some(2),
        subdivision,
        time_list_at,
        initial_fields,
        dynamics: None,
        archive: parse_archive(ex, kw)?,
        cut_refused: None,
        penalty_adaptation,
        // code_aster 17's default with ALGO_RESO_GEOM='NEWTON': 1e-6.
        contact_resi_geom: contact_factor
            .first()
            .map(|o| o.f64("RESI_GEOM").unwrap_or(1e-6)),
    })
}

/// `ARCHIVAGE`: `LIST_INST`/`INST` (with `PRECISION`, `CRITERE`) or
/// `PAS_ARCH`.
pub(crate) fn parse_archive(
    ex: &Executor,
    kw: &Keywords,
) -> Result<crate::archive::Archive, ExecError> {
    let mut archive = crate::archive::Archive::default();
    let Some(occ) = kw.factor("ARCHIVAGE").first() else {
        return Ok(archive);
    };
    let list: Option<Vec<f64>> = match occ.concept("LIST_INST") {
        Some(l) => Some((*ex.real_list(l)?).clone()),
        None if occ.contains("INST") => Some(
            occ.simple("INST")
                .iter()
                .filter_map(|v| v.as_f64())
                .collect(),
        ),
        None => None,
    };
    if let Some(list) = list {
        archive.instants = Some((
            list,
            occ.f64("PRECISION").unwrap_or(1e-6),
            occ.str("CRITERE") == Some("ABSOLU"),
        ));
    }
    archive.every = occ
        .first("PAS_ARCH")
        .and_then(|v| v.as_i64())
        .map(|k| k.max(1) as usize);
    Ok(archive)
}

/// The `COMPORTEMENT` occurrences: ELAS and the von Mises laws with
/// isotropic hardening, in small strains (PETIT, PETIT_REAC) or finite
/// strains (GREEN_LAGRANGE, GDEF_LOG, SIMO_MIEHE; GROT_GDEP with ELAS,
/// which is then Saint Venant–Kirchhoff hyperelasticity, the same as
/// GREEN_LAGRANGE with ELAS).
fn parse_behaviours(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    model: &ModelDef,
) -> Result<Vec<BehaviourOcc>, ExecError> {
    use aster_fem::Kinematics;
    let mut out = Vec::new();
    let occs = kw.factor("COMPORTEMENT");
    if occs.is_empty() {
        return Ok(out);
    }
    let mesh = ex.mesh_by_id(model.mesh)?;
    let at = format!("{cmd}/COMPORTEMENT");
    for occ in occs {
        let relation = match occ.str("RELATION").unwrap_or("ELAS") {
            "ELAS" => Relation::Elas,
            "VMIS_ISOT_LINE" => Relation::VmisIsotLine,
            "VMIS_ISOT_TRAC" => Relation::VmisIsotTrac,
            "LEMAITRE" => Relation::Lemaitre,
            "VMIS_ISOT_NL" => Relation::VmisIsotNl,
            "CZM_LIN_REG" => Relation::CzmLinReg,
            "CZM_TURON" => Relation::CzmTuron,
            "VMIS_JOHN_COOK" => Relation::VmisJohnCook,
            "VMIS_CINE_LINE" => Relation::VmisCineLine,
            "GRILLE_ISOT_LINE" => Relation::GrilleIsotLine,
            "GRILLE_CINE_LINE" => Relation::GrilleCineLine,
            "ELAS_VMIS_LINE" => Relation::ElasVmisLine,
            "ELAS_VMIS_TRAC" => Relation::ElasVmisTrac,
            other => {
                let span = occ.keyword("RELATION").map(|k| k.span).unwrap_or_default();
                return Err(ex.unsupported(
                    &format!(
                        "{at}/RELATION='{other}' (supported: ELAS, VMIS_ISOT_LINE, VMIS_ISOT_TRAC, VMIS_ISOT_NL, VMIS_JOHN_COOK, VMIS_CINE_LINE, LEMAITRE, CZM_LIN_REG, CZM_TURON, GRILLE_ISOT_LINE, GRILLE_CINE_LINE, ELAS_VMIS_LINE, ELAS_VMIS_TRAC)"
                    ),
                    span,
                ));
            }
        };
        let deformation = occ.str("DEFORMATION").unwrap_or("PETIT");
        let span = occ
            .keyword("DEFORMATION")
            .map(|k| k.span)
            .unwrap_or_default();
        let refuse =
            |why: &str| ex.unsupported(&format!("{at}/DEFORMATION='{deformation}' {why}"), span);
        let kinematics = match (deformation, relation) {
            ("PETIT", _) => Kinematics::Small,
            ("PETIT_REAC", _) => Kinematics::SmallUpdated,
            // The combinations `kinematics_rules` refuses never get here.
            ("GREEN_LAGRANGE" | "GROT_GDEP", _) => Kinematics::GreenLagrange,
            ("GDEF_LOG", _) => Kinematics::Logarithmic,
            ("SIMO_MIEHE", _) => Kinematics::SimoMiehe,
            (other, _) => return Err(refuse(&format!("(got {other})"))),
        };
        // code_aster's catalogue of the GRILLE_* laws: PETIT only.
        if matches!(
            relation,
            Relation::GrilleIsotLine | Relation::GrilleCineLine
        ) && kinematics != Kinematics::Small
        {
            return Err(refuse(&format!(
                "with RELATION='{}' (code_aster's law takes PETIT only)",
                relation.keyword()
            )));
        }
        // ELAS_VMIS_*: code_aster's catalogue has PETIT, GDEF_LOG and
        // GREEN_LAGRANGE; the Hencky law is integrated in small strains
        // only here.
        if matches!(relation, Relation::ElasVmisLine | Relation::ElasVmisTrac)
            && kinematics != Kinematics::Small
        {
            return Err(refuse(&format!(
                "with RELATION='{}' (the Hencky law is integrated in small strains, DEFORMATION='PETIT', here)",
                relation.keyword()
            )));
        }
        // code_aster's catalogue of VMIS_ISOT_NL: PETIT and GDEF_LOG only.
        if relation == Relation::VmisIsotNl
            && !matches!(kinematics, Kinematics::Small | Kinematics::Logarithmic)
        {
            return Err(refuse(
                "with RELATION='VMIS_ISOT_NL' (code_aster's law takes PETIT and GDEF_LOG only)",
            ));
        }
        // code_aster's catalogue of VMIS_JOHN_COOK: PETIT, PETIT_REAC,
        // GROT_GDEP and GDEF_LOG; GROT_GDEP with a plastic law is not
        // done here.
        if relation == Relation::VmisJohnCook
            && !matches!(
                kinematics,
                Kinematics::Small | Kinematics::SmallUpdated | Kinematics::Logarithmic
            )
        {
            return Err(refuse(
                "with RELATION='VMIS_JOHN_COOK' (supported: PETIT, PETIT_REAC and GDEF_LOG)",
            ));
        }
        // code_aster's catalogue of VMIS_CINE_LINE: PETIT, PETIT_REAC,
        // GROT_GDEP and GDEF_LOG; GROT_GDEP with a plastic law is not
        // done here.
        if relation == Relation::VmisCineLine
            && !matches!(
                kinematics,
                Kinematics::Small | Kinematics::SmallUpdated | Kinematics::Logarithmic
            )
        {
            return Err(refuse(
                "with RELATION='VMIS_CINE_LINE' (supported: PETIT, PETIT_REAC and GDEF_LOG)",
            ));
        }
        if relation == Relation::VmisJohnCook {
            // nmtevp through zerofr: BRENT (the catalogue's default) is
            // reproduced, DEKKER and SECANTE are not.
            if let Some(a) = occ.str("ALGO_INTE").filter(|a| *a != "BRENT") {
                let span = occ.keyword("ALGO_INTE").map(|k| k.span).unwrap_or_default();
                return Err(ex.unsupported(
                    &format!("{at}/ALGO_INTE='{a}' with RELATION='VMIS_JOHN_COOK' (code_aster's zerofr is reproduced with BRENT only)"),
                    span,
                ));
            }
        }
        let named = ["TOUT", "GROUP_MA", "MAILLE"]
            .iter()
            .any(|k| occ.keyword(k).is_some_and(|e| !e.defaulted));
        let cells = if named && occ.str("TOUT") != Some("OUI") {
            Some(
                crate::select::cells(occ, &mesh, "")
                    .map_err(|e| ExecError::new(format!("{at}: {e}")))?,
            )
        } else {
            None
        };
        if kinematics == Kinematics::SimoMiehe {
            let plane_stress =
                |c: &aster_mesh::CellId| model.cells.get(c) == Some(&Modelisation::PlaneStress);
            let any = match &cells {
                Some(cs) => cs.iter().any(plane_stress),
                None => model.cells.keys().any(plane_stress),
            };
            if any {
                return Err(refuse(
                    "on C_PLAN cells (code_aster has no plane-stress SIMO_MIEHE element)",
                ));
            }
        }
        let local = LocalIntegration {
            theta: occ.f64("PARM_THETA").unwrap_or(1.0),
            resi_inte: occ
                .f64("RESI_INTE_RELA")
                .or_else(|| occ.f64("RESI_INTE"))
                .unwrap_or(1e-6),
            iter_inte_maxi: occ
                .first("ITER_INTE_MAXI")
                .and_then(|v| v.as_i64())
                .map(|k| k.max(1) as usize)
                .unwrap_or(20),
        };
        out.push(BehaviourOcc {
            relation,
            kinematics,
            cells,
            local,
        });
    }
    Ok(out)
}

/// MECA_STATIQUE: one step at INST (default 0), or the instants of LIST_INST.
/// Instants and the initial state they start from.
type Instants = (Vec<f64>, Option<(Rc<EvolResult>, f64)>);

fn instants_linear(ex: &Executor, kw: &Keywords) -> Result<Instants, ExecError> {
    if let Some(l) = kw.concept("LIST_INST") {
        let list = ex.real_list(l)?;
        let mut instants = (*list).clone();
        // INST_FIN: the instants of the list up to it (one of them).
        if let Some(end) = kw.f64("INST_FIN") {
            let tol = 1e-6 * end.abs().max(1e-300);
            if !instants.iter().any(|t| (t - end).abs() <= tol) {
                return Err(ex.kw_error(
                    "MECA_STATIQUE",
                    kw,
                    "INST_FIN",
                    format!("INST_FIN = {end} is not an instant of LIST_INST"),
                ));
            }
            instants.retain(|t| *t <= end + tol);
        }
        return Ok((instants, None));
    }
    let t = kw.f64("INST").unwrap_or(0.0);
    Ok((vec![t], None))
}

pub fn stat_non_line(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    solve_and_store(ex, call, false)
}

/// What MECA_STATIQUE reads (`crate::support`).
pub(crate) const MECA_STATIQUE: Support = Support {
    values: &[Values::new("EXCIT/TYPE_CHARGE", &["FIXE_CSTE"])],
    ..Support::keywords(&[
        "MODELE",
        "CHAM_MATER",
        "CARA_ELEM",
        "EXCIT",
        "EXCIT/CHARGE",
        "EXCIT/FONC_MULT",
        "EXCIT/TYPE_CHARGE",
        "INST",
        "LIST_INST",
        "INST_FIN",
        "SOLVEUR",
        "SOLVEUR/*",
        "INFO",
        "TITRE",
        "OPTION",
    ])
};

pub fn meca_statique(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    solve_and_store(ex, call, true)
}

/// The common tail of STAT_NON_LINE (`linear` false: an evol_noli) and
/// MECA_STATIQUE (`linear` true: an evol_elas): set-up, solve, store.
fn solve_and_store(
    ex: &mut Executor,
    call: &CommandCall,
    linear: bool,
) -> Result<CommandOutput, ExecError> {
    let setup = parse_setup(ex, call, linear)?;
    store_solution(ex, call, &setup, linear)
}

/// Solves a set-up and stores the result (`linear`: an evol_elas).
pub(crate) fn store_solution(
    ex: &mut Executor,
    call: &CommandCall,
    setup: &SolveSetup,
    linear: bool,
) -> Result<CommandOutput, ExecError> {
    let mesh_id = setup.model.mesh;
    let mesh = ex.mesh_by_id(mesh_id)?;
    let observations = crate::observation::parse(ex, &call.keywords, &mesh)?;
    let continued = match linear {
        // MECA_STATIQUE's reuse= replaces the result.
        true => None,
        false => continued_result(ex, call, setup, !observations.is_empty())?,
    };
    let (mut steps, mut fem) = crate::fembridge::solve(ex, setup, linear)?;
    if let Some((prev, t0)) = continued {
        (steps, fem) = continue_steps(&prev, t0, steps, fem)?;
    }
    let mut tables = Vec::new();
    if !fem.raw.energy.is_empty() {
        tables.push((
            "PARA_CALC".to_string(),
            Rc::new(crate::table::energy_table(&fem.raw.energy)),
        ));
    }
    if !observations.is_empty() {
        let t = crate::observation::table(&observations, &steps, &mesh);
        tables.push(("OBSERVATION".to_string(), Rc::new(t)));
    }
    if call
        .keywords
        .factor("MESURE")
        .first()
        .is_some_and(|o| o.str("TABLE") == Some("OUI"))
    {
        let counted = setup.contact.as_deref().is_some_and(contact_counted);
        tables.push(("STAT".to_string(), Rc::new(stat_table(&steps, counted))));
    }
    let evol = EvolResult {
        prep_varc: false,
        typ: if linear { "evol_elas" } else { "evol_noli" }.into(),
        mesh: mesh_id,
        steps,
        fem: Some(fem),
        tables,
        modal: None,
        cases: None,
        thermal: None,
    };
    store_result(ex, call, Concept::Result(Rc::new(evol)))
}

/// `reuse=R`: the computation continues `R` from its state named by
/// `ETAT_INIT/EVOL_NOLI=R` (the one continuation code_aster's tests make);
/// returns that result and the initial instant. Refused: a `reuse` whose
/// `ETAT_INIT` names another result or none, and observations (their table
/// would have to be continued too).
fn continued_result(
    ex: &Executor,
    call: &CommandCall,
    setup: &SolveSetup,
    observed: bool,
) -> Result<Option<(Rc<EvolResult>, f64)>, ExecError> {
    let Some(r) = call.reuse.as_ref() else {
        return Ok(None);
    };
    let cmd = &call.command;
    let reused = ex.result(r)?;
    let Some((prev, t0)) = setup
        .initial
        .as_ref()
        .filter(|(p, _)| Rc::ptr_eq(p, &reused))
    else {
        return Err(ex.unsupported(
            &format!("{cmd} with reuse= whose ETAT_INIT/EVOL_NOLI is not the reused result (only continuing a result from one of its own states)"),
            call.span,
        ));
    };
    if observed || !prev.tables.is_empty() {
        return Err(ex.unsupported(
            &format!(
                "{cmd} with reuse= and OBSERVATION or ENERGIE (their tables are not continued)"
            ),
            call.span,
        ));
    }
    if prev.mesh != setup.model.mesh || prev.typ != "evol_noli" {
        return Err(ex.unsupported(
            &format!("{cmd} with reuse= of a result on another mesh or of another type"),
            call.span,
        ));
    }
    Ok(Some((prev.clone(), *t0)))
}

/// The steps of a continued result, as code_aster's `reuse` keeps them:
/// those of `prev` up to the initial state (at `t0`, NUME_ORDRE k₀; later
/// ones are dropped), then the new ones numbered from k₀ + 1. The new
/// run's own copy of the initial state is not stored. The computation kept
/// for CALC_CHAMP is the new one, renumbered the same way, with the
/// previous computation's states before k₀ in front when both describe
/// the same problem (same DOF numbering, behaviours and loads: a field at
/// an earlier step is then computed as the first run would have); when
/// they differ a step before k₀ is not in it, so a field asked there is
/// an error, never another step's values.
fn continue_steps(
    prev: &EvolResult,
    t0: f64,
    steps: Vec<Step>,
    mut fem: Rc<crate::fembridge::FemRun>,
) -> Result<(Vec<Step>, Rc<crate::fembridge::FemRun>), ExecError> {
    let k0 = prev
        .step_at(t0, 1e-6, false)
        .map(|s| s.nume_ordre)
        .ok_or_else(|| ExecError::new(format!("reuse=: no state at {t0} in the reused result")))?;
    let mut merged: Vec<Step> = prev
        .steps
        .iter()
        .filter(|s| s.nume_ordre <= k0)
        .cloned()
        .collect();
    let first = steps.first().map(|s| s.nume_ordre).unwrap_or(0);
    merged.extend(steps.into_iter().skip(1).map(|mut s| {
        s.nume_ordre = s.nume_ordre - first + k0;
        s
    }));
    let run =
        Rc::get_mut(&mut fem).ok_or_else(|| ExecError::new("reuse=: the computation is shared"))?;
    for s in &mut run.raw.steps {
        s.nume_ordre = s.nume_ordre - first as usize + k0 as usize;
    }
    if let Some(before) = prev.fem.as_deref().filter(|p| same_problem(p, run)) {
        let earlier = before
            .raw
            .steps
            .iter()
            .filter(|s| s.nume_ordre < k0 as usize)
            .cloned();
        run.raw.steps.splice(0..0, earlier);
    }
    Ok((merged, fem))
}

/// Whether two computations describe the same problem, so that the states
/// of one are read with the other's model, behaviours and loads.
fn same_problem(a: &crate::fembridge::FemRun, b: &crate::fembridge::FemRun) -> bool {
    a.model.dofs() == b.model.dofs()
        && a.behaviours == b.behaviours
        && a.plastic == b.plastic
        && format!("{:?}", a.loads) == format!("{:?}", b.loads)
}

const CALC_CHAMP_OWN: &[&str] = &[
    "RESULTAT",
    "MODELE",
    "CHAM_MATER",
    "CARA_ELEM",
    "EXCIT",
    "EXCIT/CHARGE",
    "EXCIT/FONC_MULT",
    "FORCE",
    "CONTRAINTE",
    "CRITERES",
    "DEFORMATION",
    "VARI_INTERNE",
    "ENERGIE",
    "THERMIQUE",
    "TOUT",
    "GROUP_MA",
    "INFO",
    "TITRE",
];

/// What CALC_CHAMP reads (`crate::support`): its own keywords and the step
/// selection ([`crate::commands::post::STEP_SELECTION`]).
pub(crate) const CALC_CHAMP: Support = Support {
    rules: Some(calc_champ_rules),
    // The elastic energy (`enelpg`, PETIT); ETOT_* (the work of the
    // stresses over the history), EPOT_ELEM/ECIN_ELEM and the others not.
    values: &[
        Values::listed(
            "ENERGIE",
            &[
                "ENEL_ELGA",
                "ENEL_ELNO",
                "ENEL_ELEM",
                "EPOT_ELEM",
                "ECIN_ELEM",
            ],
        ),
        Values::new("THERMIQUE", &["FLUX_ELGA", "FLUX_ELNO", "FLUX_NOEU"]),
    ],
    ..Support::keywords(&crate::support::joined::<
        _,
        { crate::commands::post::STEP_SELECTION.len() + CALC_CHAMP_OWN.len() },
    >(crate::commands::post::STEP_SELECTION, CALC_CHAMP_OWN))
};

/// `GROUP_MA`/`MAILLE` restrict the element options and the nodal averages
/// to those cells; the nodal forces of some cells only are not computed.
fn calc_champ_rules(call: &CommandCall, out: &mut Vec<crate::support::Refusal>) {
    let kw = &call.keywords;
    let Some(key) = ["GROUP_MA", "MAILLE"]
        .into_iter()
        .find(|k| kw.keyword(k).is_some_and(|k| !k.defaulted))
    else {
        return;
    };
    for opt in kw.simple("FORCE").iter().filter_map(|s| s.as_str()) {
        if matches!(opt, "FORC_NODA" | "REAC_NODA") {
            out.push(crate::support::Refusal::at(
                format!(
                    "CALC_CHAMP/{key} with FORCE='{opt}' (the nodal forces of some cells only)"
                ),
                kw,
                key,
                call.span,
            ));
        }
    }
}

pub fn calc_champ(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let r = ex.required("CALC_CHAMP", kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let mut options: Vec<String> = Vec::new();
    for key in [
        "FORCE",
        "CONTRAINTE",
        "CRITERES",
        "DEFORMATION",
        "VARI_INTERNE",
        "ENERGIE",
    ] {
        options.extend(
            kw.simple(key)
                .iter()
                .filter_map(|s| s.as_str().map(str::to_string)),
        );
    }
    let steps: Vec<u32> = crate::commands::select_steps_pub(ex, "CALC_CHAMP", kw, &result)?;
    // GROUP_MA / MAILLE: the element options on those cells only, the
    // nodal averages (`*_NOEU`) over them, as code_aster computes them
    // (FORC_NODA/REAC_NODA with them are refused: `calc_champ_rules`).
    let only: Option<std::collections::BTreeSet<aster_mesh::CellId>> = if kw.str("TOUT")
        == Some("OUI")
        || ["GROUP_MA", "MAILLE"]
            .iter()
            .all(|k| kw.keyword(k).is_none())
    {
        None
    } else {
        let mesh = ex.mesh_by_id(result.mesh)?;
        let cells = crate::select::cells(kw, &mesh, "")
            .map_err(|m| ExecError::new(format!("CALC_CHAMP: {m}")))?;
        Some(cells.into_iter().collect())
    };
    let thermique: Vec<String> = kw
        .simple("THERMIQUE")
        .iter()
        .filter_map(|s| s.as_str().map(str::to_string))
        .collect();
    let mut result = result;
    if !thermique.is_empty() {
        result = Rc::new(crate::commands::thermal_nl::calc_champ_thermique(
            ex,
            &result,
            &thermique,
            &steps,
            only.as_ref(),
        )?);
        if options.is_empty() {
            return store_result(ex, call, Concept::Result(result));
        }
    }
    let updated = crate::fembridge::calc_champ(ex, call, &result, &options, &steps, only.as_ref())?;
    store_result(ex, call, Concept::Result(Rc::new(updated)))
}

/// Whether code_aster counts a definition's contact points per node from
/// CONT_NOEU (`cfmxre` → `mmmcpt`): the continuous formulation (not LAC)
/// integrated at the slave nodes.
fn contact_counted(def: &ContactDef) -> bool {
    let ContactDef::Zones { keywords, .. } = def else {
        return false;
    };
    keywords.str("FORMULATION") == Some("CONTINUE")
        && keywords.factor("ZONE").iter().all(|o| {
            o.str("ALGO_CONT") != Some("LAC")
                && matches!(o.str("INTEGRATION").unwrap_or("AUTO"), "AUTO" | "NOEUD")
        })
}

/// `MESURE=_F(TABLE='OUI')`: code_aster's table 'STAT', one row per
/// stored step, with its contact counts when `counted` (`mmmcpt`: the slave
/// nodes whose CONT_NOEU CONT is ≥ 1, in contact, `Count_Cont_NCont`, and
/// = 1, sticking, `Count_Cont_NFric`). Its timers and iteration counts are
/// not kept, so a test of them finds no column.
pub(crate) fn stat_table(steps: &[Step], counted: bool) -> crate::table::Table {
    use crate::table::{Column, ColumnType, Table, Value};
    let mut columns = vec![
        Column {
            name: "NUME_ORDRE".into(),
            ty: ColumnType::Int,
        },
        Column {
            name: "INST".into(),
            ty: ColumnType::Real,
        },
    ];
    if counted {
        for name in ["Count_Cont_NCont", "Count_Cont_NFric"] {
            columns.push(Column {
                name: name.into(),
                ty: ColumnType::Int,
            });
        }
    }
    let mut t = Table::new(columns);
    for s in steps.iter().filter(|s| s.nume_ordre > 0) {
        let mut row = vec![
            ("NUME_ORDRE", Value::Int(s.nume_ordre as i64)),
            ("INST", Value::Real(s.inst)),
        ];
        if counted {
            let (mut cont, mut stick) = (0_i64, 0_i64);
            if let Some(crate::field::Field::Nodal(f)) = s.fields.get("CONT_NOEU") {
                if let Some(k) = f.component_index("CONT") {
                    for (_, v) in f.iter() {
                        let c = v.get(k).unwrap_or(0.0).round();
                        if c >= 1.0 {
                            cont += 1;
                            if c == 1.0 {
                                stick += 1;
                            }
                        }
                    }
                }
            }
            row.push(("Count_Cont_NCont", Value::Int(cont)));
            row.push(("Count_Cont_NFric", Value::Int(stick)));
        }
        t.push_row(row);
    }
    t
}
