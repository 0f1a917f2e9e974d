//! The concepts a program creates, as the runner keeps them. Concepts that
//! belong to a mesh refer to it by concept id, so groups added later by
//! `DEFI_GROUP(reuse=…)` are seen by every concept built on that mesh (node
//! and cell numbering never change after reading).

use crate::field::Field;
use crate::function::Function;
use crate::table::Table;
use aster_mesh::{CellId, Mesh, NodeId};
use std::collections::BTreeMap;
use std::rc::Rc;
use std::sync::Arc;

/// A degree of freedom component name as the command language spells it.
pub type CompName = &'static str;

/// `AFFE_MODELE/AFFE/MODELISATION` values the runner knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Modelisation {
    /// `D_PLAN`: plane strain.
    PlaneStrain,
    /// `C_PLAN`: plane stress.
    PlaneStress,
    /// `AXIS`: axisymmetric.
    Axisymmetric,
    /// `3D`.
    Solid3D,
    /// `2D_DIS_T`: discrete translational elements in 2D.
    Discrete2D,
    /// `DIS_T`: discrete translational elements in 3D.
    Discrete3D,
    /// `DIS_TR`: discrete elements in 3D with the rotations DRX DRY DRZ
    /// on their nodes.
    DiscreteRot3D,
    /// `POU_D_E`: Euler–Bernoulli beams on SEG2, with the rotations.
    BeamEuler,
    /// `POU_D_T`: Timoshenko beams on SEG2 (`MECA_POU_D_T`: the shear
    /// coefficients AY, AZ of the section), with the rotations.
    BeamTimoshenko,
    /// `BARRE`: trusses on SEG2 (`MECA_BARRE`, the area of
    /// `AFFE_CARA_ELEM/BARRE`), DX DY DZ.
    Bar,
    /// `DKT`, `DST`, `Q4G`: plate facets on TRIA3 and QUAD4 (DKT/DKQ,
    /// DST/DSQ, T3G/Q4G: `aster_fem::plate`) with the rotations DRX DRY
    /// DRZ on their nodes.
    Plate(aster_fem::PlateTheory),
    /// `COQUE_3D`: code_aster's degenerated-solid shell on QUAD9 and TRIA7
    /// (`MEC3QU9H`, `MEC3TR7H`, `aster_fem::coque3d`); its centre node carries the
    /// rotations alone.
    Coque3d,
    /// `PLAN_JOINT`: plane joint elements on QUAD4 (`MFPLQU4`,
    /// `aster_fem::joint`) with a cohesive law.
    PlaneJoint,
    /// `GRILLE_MEMBRANE`: a reinforcement grid on TRIA3, TRIA6, QUAD4,
    /// QUAD8 (`MEGMTR3`…, `aster_fem::grid`), DX DY DZ.
    GridMembrane,
    /// `GRILLE_EXCENTRE`: a grid offset from its cell's surface, on TRIA3
    /// and QUAD4 (`MEGCTR3`, `MEGCQU4`), with the rotations DRX DRY DRZ.
    GridExcentre,
}

impl Modelisation {
    pub fn from_keyword(value: &str) -> Option<Modelisation> {
        Some(match value {
            "D_PLAN" => Modelisation::PlaneStrain,
            "C_PLAN" => Modelisation::PlaneStress,
            "AXIS" => Modelisation::Axisymmetric,
            "3D" => Modelisation::Solid3D,
            "2D_DIS_T" => Modelisation::Discrete2D,
            "DIS_T" => Modelisation::Discrete3D,
            "DIS_TR" => Modelisation::DiscreteRot3D,
            "POU_D_E" => Modelisation::BeamEuler,
            "POU_D_T" => Modelisation::BeamTimoshenko,
            "BARRE" => Modelisation::Bar,
            "DKT" => Modelisation::Plate(aster_fem::PlateTheory::Dkt),
            "DST" => Modelisation::Plate(aster_fem::PlateTheory::Dst),
            "Q4G" => Modelisation::Plate(aster_fem::PlateTheory::Q4g),
            "DKTG" => Modelisation::Plate(aster_fem::PlateTheory::Dktg),
            "Q4GG" => Modelisation::Plate(aster_fem::PlateTheory::Q4gg),
            "COQUE_3D" => Modelisation::Coque3d,
            "PLAN_JOINT" => Modelisation::PlaneJoint,
            "GRILLE_MEMBRANE" => Modelisation::GridMembrane,
            "GRILLE_EXCENTRE" => Modelisation::GridExcentre,
            _ => return None,
        })
    }

    /// A `MODELISATION` value: the modelisation, and whether it is one of
    /// code_aster's under-integrated ones (`D_PLAN_SI`, `C_PLAN_SI`,
    /// `AXIS_SI`, `3D_SI`: the same modelisation, its QUAD8, HEXA20 and
    /// TETRA10 cells integrated with a reduced family).
    pub fn from_keyword_si(value: &str) -> Option<(Modelisation, bool)> {
        if let Some(base @ ("D_PLAN" | "AXIS" | "3D")) = value.strip_suffix("_INCO_UPG") {
            return Modelisation::from_keyword(base).map(|m| (m, false));
        }
        match value.strip_suffix("_SI") {
            Some(base @ ("D_PLAN" | "C_PLAN" | "AXIS" | "3D")) => {
                Modelisation::from_keyword(base).map(|m| (m, true))
            }
            Some(_) => None,
            None => Modelisation::from_keyword(value).map(|m| (m, false)),
        }
    }

    /// Whether a `MODELISATION` value is one of code_aster's mixed
    /// incompressible ones (`D_PLAN_INCO_UPG`, `AXIS_INCO_UPG`,
    /// `3D_INCO_UPG`: displacement, pressure `PRES` and swelling `GONF`,
    /// aster-fem's `mixed_upg`).
    pub fn is_mixed_keyword(value: &str) -> bool {
        matches!(value, "D_PLAN_INCO_UPG" | "AXIS_INCO_UPG" | "3D_INCO_UPG")
    }

    pub const KEYWORDS: [&'static str; 26] = [
        "D_PLAN",
        "C_PLAN",
        "AXIS",
        "3D",
        "2D_DIS_T",
        "DIS_T",
        "D_PLAN_SI",
        "C_PLAN_SI",
        "AXIS_SI",
        "3D_SI",
        "DKT",
        "DST",
        "Q4G",
        "DKTG",
        "Q4GG",
        "DIS_TR",
        "POU_D_E",
        "POU_D_T",
        "BARRE",
        "PLAN_JOINT",
        "COQUE_3D",
        "D_PLAN_INCO_UPG",
        "AXIS_INCO_UPG",
        "3D_INCO_UPG",
        "GRILLE_MEMBRANE",
        "GRILLE_EXCENTRE",
    ];

    /// Space dimension of the displacement.
    pub fn dim(self) -> usize {
        match self {
            Modelisation::Solid3D
            | Modelisation::Discrete3D
            | Modelisation::DiscreteRot3D
            | Modelisation::BeamEuler
            | Modelisation::BeamTimoshenko
            | Modelisation::Bar
            | Modelisation::Plate(_)
            | Modelisation::Coque3d
            | Modelisation::GridMembrane
            | Modelisation::GridExcentre => 3,
            _ => 2,
        }
    }

    pub fn is_discrete(self) -> bool {
        matches!(
            self,
            Modelisation::Discrete2D | Modelisation::Discrete3D | Modelisation::DiscreteRot3D
        )
    }

    /// Whether its nodes carry the rotations DRX DRY DRZ.
    pub fn has_rotations(self) -> bool {
        matches!(
            self,
            Modelisation::Plate(_)
                | Modelisation::Coque3d
                | Modelisation::GridExcentre
                | Modelisation::DiscreteRot3D
                | Modelisation::BeamEuler
                | Modelisation::BeamTimoshenko
        )
    }

    /// Whether it is a straight beam on SEG2 (`POU_D_E`, `POU_D_T`).
    pub fn is_beam(self) -> bool {
        matches!(self, Modelisation::BeamEuler | Modelisation::BeamTimoshenko)
    }
}

/// `AFFE_MODELE`: which cells carry which modelisation.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelDef {
    pub mesh: u32,
    /// Per cell, its modelisation (the last `AFFE` occurrence wins, as in
    /// code_aster); cells of no occurrence are not in the model.
    pub cells: BTreeMap<CellId, Modelisation>,
    /// Cells of an under-integrated modelisation (`_SI`): QUAD8, HEXA20,
    /// TETRA10 integrated with code_aster's reduced stiffness family.
    pub reduced: std::collections::BTreeSet<CellId>,
    /// Cells of a mixed incompressible modelisation (`*_INCO_UPG`): TRIA6,
    /// QUAD8 (2D), HEXA20, PENTA15, TETRA10 (3D) with the unknowns PRES
    /// and GONF at their vertices.
    pub mixed: std::collections::BTreeSet<CellId>,
    /// Segments given MODELISATION='3D': code_aster's edge elements
    /// (`MECA_ARETE2`/`3`), without stiffness, which `POST_ELEM` integrates
    /// over; not in `cells`.
    pub edges: std::collections::BTreeSet<CellId>,
    /// Per mesh node, whether it carries the rotations DRX DRY DRZ (a
    /// node of a shell cell).
    pub rotations: Vec<bool>,
    /// `AFFE_SOUS_STRUC`: the super cells (static substructures) the
    /// model carries beside its elements.
    pub substructures: Vec<SuperCell>,
}

/// `MACR_ELEM_STAT`: a static substructure — a model's cells with their
/// materials, the Dirichlet conditions inside it (`CHAR_MACR_ELEM`), its
/// exterior nodes (`EXTERIEUR`) and its load cases (`CAS_CHARGE`).
#[derive(Clone, Debug)]
pub struct MacroElement {
    pub model: Rc<ModelDef>,
    pub materials: Rc<MaterialField>,
    /// `CHAR_MACR_ELEM`: the loads whose Dirichlet conditions hold inside.
    pub dirichlet: Vec<crate::solve::LoadRef>,
    pub exterior: Vec<NodeId>,
    pub cases: Vec<LoadCase>,
}

/// `MACR_ELEM_STAT/CAS_CHARGE`: a named load case of a macro element.
#[derive(Clone, Debug)]
pub struct LoadCase {
    pub name: String,
    pub loads: Vec<crate::solve::LoadRef>,
}

/// `DEFI_MAILLAGE`: super cells, each a macro element whose exterior
/// nodes are named by `DEFI_NOEUD`.
#[derive(Clone, Debug)]
pub struct SuperMesh {
    pub cells: Vec<SuperCell>,
}

/// One super cell of a [`SuperMesh`].
#[derive(Clone, Debug)]
pub struct SuperCell {
    pub name: String,
    pub macro_elem: Rc<MacroElement>,
    /// The names of the macro element's exterior nodes in the super mesh
    /// (in the order of [`MacroElement::exterior`]).
    pub node_names: Vec<String>,
}

impl PartialEq for SuperCell {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
            && self.node_names == other.node_names
            && Rc::ptr_eq(&self.macro_elem, &other.macro_elem)
    }
}

impl ModelDef {
    /// Whether the model has shell elements (`DKT`, `DST`, `Q4G`, `COQUE_3D`).
    pub fn has_shells(&self) -> bool {
        self.cells
            .values()
            .any(|&m| matches!(m, Modelisation::Plate(_) | Modelisation::Coque3d))
    }

    /// The cells carrying `COQUE_3D`.
    pub fn coque3d_cells(&self) -> std::collections::BTreeSet<CellId> {
        self.cells
            .iter()
            .filter(|(_, &m)| m == Modelisation::Coque3d)
            .map(|(&c, _)| c)
            .collect()
    }

    /// Whether some nodes carry rotations (`DKT`, `POU_D_E`, `DIS_TR`).
    pub fn has_rotations(&self) -> bool {
        self.rotations.iter().any(|&r| r)
    }

    /// Whether the model has beams (`POU_D_E`, `POU_D_T`).
    pub fn has_beams(&self) -> bool {
        self.cells.values().any(|&m| m.is_beam())
    }

    pub fn dim(&self) -> usize {
        self.cells.values().map(|m| m.dim()).max().unwrap_or(2)
    }
}

/// `DEFI_MATERIAU(ELAS=…)` or `DEFI_MATERIAU(ELAS_ORTH=…)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// `ELAS` given (a material with `THER` alone has no elasticity: its
    /// `young` and `poisson` are NaN).
    pub elastic: bool,
    pub young: f64,
    pub poisson: f64,
    pub density: Option<f64>,
    pub alpha: Option<f64>,
    /// Rayleigh damping `AMOR_ALPHA` (× stiffness) and `AMOR_BETA`
    /// (× mass), used by DYNA_NON_LINE.
    pub amor_alpha: Option<f64>,
    pub amor_beta: Option<f64>,
    /// `ECRO_LINE=_F(D_SIGM_EPSI, SY)` (for VMIS_ISOT_LINE); also
    /// `ECRO_LINE_FO`'s values when both its functions are constants.
    pub ecro_line: Option<EcroLine>,
    /// `ECRO_LINE_FO=_F(D_SIGM_EPSI, SY)`: functions of TEMP, evaluated at
    /// each Gauss point and instant in STAT_NON_LINE
    /// ([`crate::thermo_mat`]).
    pub ecro_line_fo: Option<Rc<EcroLineFo>>,
    /// `TRACTION=_F(SIGM=σ(EPSI))` (for VMIS_ISOT_TRAC): a tabulated
    /// function.
    pub traction: Option<crate::function::Tabulated>,
    /// `TRACTION=_F(SIGM=nappe of TEMP)`: one curve per temperature, the
    /// curve at a point's temperature built by `aster_fem`'s
    /// `behaviour::traction` (code_aster's `rctrac`).
    pub traction_nappe: Option<Rc<aster_fem::TractionNappe>>,
    /// `LEMAITRE=_F(N, UN_SUR_K, UN_SUR_M)` (for RELATION='LEMAITRE').
    pub lemaitre: Option<LemaitreCoefs>,
    /// `ECRO_NL=_F(R0, RH, R1, GAMMA_1, R2, GAMMA_2, RK, P0, GAMMA_M)`
    /// (for VMIS_ISOT_NL; its `resi_inte` is the COMPORTEMENT's).
    pub ecro_nl: Option<aster_fem::EcroNl>,
    /// `ECRO_COOK=_F(A, B, N_PUIS, C, EPSP0, M_PUIS, TROOM, TMELT)` (for
    /// VMIS_JOHN_COOK; its `resi_inte` and `iter_maxi` are the
    /// COMPORTEMENT's).
    pub ecro_cook: Option<aster_fem::JohnsonCook>,
    /// `THER=_F(LAMBDA, RHO_CP)`.
    pub thermal: Option<aster_fem::thermal::Conduction>,
    /// `THER_NL=_F(LAMBDA, BETA | RHO_CP)`: λ(T) and the enthalpy β(T)
    /// (from ρCp(T) as code_aster's `create_enthalpy` makes it).
    pub thermal_nl: Option<Rc<aster_fem::thermal_nl::NlConduction>>,
    /// `RUPT_FRAG=_F(GC, SIGM_C, PENA_ADHERENCE, PENA_CONTACT)` (for
    /// `CZM_LIN_REG`).
    pub rupt_frag: Option<RuptFrag>,
    /// `RUPT_TURON=_F(…)` (for `CZM_TURON`).
    pub rupt_turon: Option<aster_fem::cohesive::Turon>,
    /// `ELAS_ORTH=_F(…)` in place of `ELAS` (then `young` and `poisson`
    /// are NaN); its frame (`angles`) is the cells' AFFE_CARA_ELEM/MASSIF
    /// one, set by the model.
    pub orthotropic: Option<aster_fem::orthotropic::Orthotropic>,
    /// `DEFI_COMPOSITE`: a stack of `ELAS_ORTH` plies, homogenised
    /// (code_aster's `ELAS_COQMU`), for the plate cells only (then `young`
    /// and `poisson` are NaN; `density` is the stack's).
    pub composite: Option<std::sync::Arc<aster_fem::laminate::Laminate>>,
    /// `ELAS_FO=_F(…)` in place of `ELAS`: the functions, resolved per cell
    /// by AFFE_MATERIAU ([`crate::elas_fo`]); `young`, `poisson`,
    /// `density` and `alpha` hold their values when they are constants.
    pub elas_fo: Option<Rc<crate::elas_fo::ElasFo>>,
    /// ELAS_FO's ALPHA when it is not a constant: code_aster's α converted
    /// to the reference temperature (`alfint`), a function of TEMP; the
    /// thermal strain is α(T) (T − T_ref) ([`Material::thermal_strain`]).
    pub alpha_fo: Option<LoadFunction>,
    /// Why this cell's ELAS_FO has no constant E, NU (and RHO): set by
    /// AFFE_MATERIAU, raised (with the keyword's location) when a
    /// mechanical computation needs the material.
    pub unresolved: Option<String>,
}

impl Material {
    /// The thermal strain at temperature `temp` for the reference `tref`:
    /// ALPHA (T − T_ref), with ELAS_FO's α(T) converted as code_aster's
    /// `alfint` does; `None` without ALPHA.
    pub fn thermal_strain(&self, temp: f64, tref: f64) -> Result<Option<f64>, String> {
        if let Some(f) = &self.alpha_fo {
            let a =
                f.0.eval_named(&[("TEMP", temp)])
                    .map_err(|e| format!("ELAS_FO/ALPHA at TEMP={temp}: {e}"))?;
            return Ok(Some(a * (temp - tref)));
        }
        Ok(self.alpha.map(|a| a * (temp - tref)))
    }

    /// RHO, or why this cell's ELAS_FO did not resolve (the message,
    /// located at the keyword).
    pub fn resolved_density(&self) -> Result<Option<f64>, String> {
        match &self.unresolved {
            Some(why) => Err(why.clone()),
            None => Ok(self.density),
        }
    }

    /// Whether the thermal strain is linear in the temperature (a constant
    /// ALPHA).
    pub fn linear_thermal_strain(&self) -> bool {
        self.alpha_fo.is_none()
    }
}

/// `RUPT_FRAG`: the cohesive parameters of `CZM_LIN_REG` as given
/// (`SIGM_C` and `PENA_ADHERENCE` are optional in the catalog, required by
/// the law).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RuptFrag {
    pub gc: f64,
    pub sigm_c: Option<f64>,
    pub pena_adherence: Option<f64>,
    pub pena_contact: f64,
}

/// `LEMAITRE`: Lemaitre's viscoplastic coefficients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LemaitreCoefs {
    pub n: f64,
    pub un_sur_k: f64,
    pub un_sur_m: f64,
}

/// `ECRO_LINE`: the slope after yield of the uniaxial curve and the yield
/// stress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EcroLine {
    pub d_sigm_epsi: f64,
    pub sy: f64,
}

/// `ECRO_LINE_FO=_F(D_SIGM_EPSI, SY)`: the functions as given.
#[derive(Clone, Debug, PartialEq)]
pub struct EcroLineFo {
    pub d_sigm_epsi: crate::elas_fo::FoArg,
    pub sy: crate::elas_fo::FoArg,
}

/// `AFFE_MATERIAU`: the material of each cell.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialField {
    pub mesh: u32,
    pub cells: BTreeMap<CellId, Rc<Material>>,
    /// `AFFE_VARC(NOM_VARC='TEMP')`: the temperature of some cells.
    pub temperature: Option<Rc<Temperature>>,
}

/// A temperature given to cells by `AFFE_VARC(NOM_VARC='TEMP', EVOL=…
/// | CHAM_GD=…, VALE_REF=…)`: nodal temperatures at instants, linear in
/// time between them; the thermal strain is ALPHA (T − VALE_REF).
#[derive(Clone, Debug, PartialEq)]
pub struct Temperature {
    pub cells: std::collections::BTreeSet<CellId>,
    pub tref: f64,
    /// (instant, temperature per mesh node — NaN where the field has none),
    /// by increasing instant; one entry with a CHAM_GD (constant in time).
    pub fields: Vec<(f64, Rc<Vec<f64>>)>,
    /// Before the first and after the last instant: `PROL_GAUCHE`,
    /// `PROL_DROITE` (`true`: CONSTANT, `false`: EXCLU).
    pub constant_before: bool,
    pub constant_after: bool,
    /// `file:line:col` of the `AFFE_VARC` keyword, for the solve's
    /// refusals (a temperature on beams).
    pub at: String,
    /// A temperature through the thickness of shells (an `EVOL` of
    /// `CREA_RESU/PREP_VARC`): per field of `fields` (whose TEMP is then
    /// NaN everywhere), per node, TEMP_MIL, TEMP_INF, TEMP_SUP.
    pub shell: Option<Vec<Rc<[Vec<f64>; 3]>>>,
}

/// The weight of each of a [`Temperature`]'s fields, given by their
/// instants, at time t (linear interpolation), or why t is outside those
/// instants.
pub fn temperature_weights(
    instants: &[f64],
    constant_before: bool,
    constant_after: bool,
    t: f64,
) -> Result<Vec<f64>, String> {
    let n = instants.len();
    let mut w = vec![0.0; n];
    if n == 1 {
        w[0] = 1.0;
        return Ok(w);
    }
    let (first, last) = (instants[0], instants[n - 1]);
    let tol = 1e-9 * first.abs().max(last.abs()).max(1.0);
    if t < first - tol {
        if !constant_before {
            return Err(format!(
                "the temperature (AFFE_VARC/EVOL) is not defined at instant {t}, before its first instant {first} (PROL_GAUCHE='EXCLU')"
            ));
        }
        w[0] = 1.0;
        return Ok(w);
    }
    if t > last + tol {
        if !constant_after {
            return Err(format!(
                "the temperature (AFFE_VARC/EVOL) is not defined at instant {t}, after its last instant {last} (PROL_DROITE='EXCLU')"
            ));
        }
        w[n - 1] = 1.0;
        return Ok(w);
    }
    for k in 0..n - 1 {
        let (a, b) = (instants[k], instants[k + 1]);
        if t <= b + tol || k == n - 2 {
            let s = if b > a {
                ((t - a) / (b - a)).clamp(0.0, 1.0)
            } else {
                1.0
            };
            w[k] = 1.0 - s;
            w[k + 1] = s;
            return Ok(w);
        }
    }
    Ok(w)
}

/// `AFFE_CARA_ELEM/DISCRET(_2D)`: a stiffness on discrete cells.
#[derive(Clone, Debug, PartialEq)]
pub struct DiscreteStiffness {
    pub cells: Vec<CellId>,
    /// `K_T_D_L`, `K_TR_D_L` (segments) or `K_T_D_N`, `K_TR_D_N` (points).
    pub cara: String,
    /// Stiffness per direction (kx, ky[, kz]; `K_TR_*`: kx, ky, kz, krx,
    /// kry, krz).
    pub values: Vec<f64>,
    /// `REPERE='LOCAL'`: along the segment (x) and across; else global.
    pub local: bool,
}

/// `AFFE_CARA_ELEM/DISCRET(_2D)`: a mass on discrete cells (`M_T_D_N`:
/// one value; `M_T_N`, `M_T_L`: the upper triangle by columns).
#[derive(Clone, Debug, PartialEq)]
pub struct DiscreteMassDef {
    pub cells: Vec<CellId>,
    pub cara: String,
    pub values: Vec<f64>,
    pub local: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct CaraElem {
    pub model: u32,
    pub discrete: Vec<DiscreteStiffness>,
    /// `COQUE`: the shells' sections and frames.
    pub shells: Vec<crate::commands::cara_coque::ShellCara>,
    /// Discrete masses (DYNA_NON_LINE).
    pub masses: Vec<DiscreteMassDef>,
    /// `POUTRE`: the beams' sections.
    pub beams: Vec<crate::commands::cara_poutre::BeamCara>,
    /// `BARRE`: the bars' areas.
    pub bars: Vec<crate::commands::cara_poutre::BarCara>,
    /// `GRILLE`: the reinforcement grids' sections, cell by cell.
    pub grids: Vec<crate::commands::cara_grille::GridCara>,
    /// `MASSIF`: the material frames of continuum cells (orthotropic
    /// materials).
    pub massif: Vec<crate::commands::cara_massif::MassifFrame>,
}

/// An imposed component value on a node.
#[derive(Clone, Debug, PartialEq)]
pub struct Imposed {
    pub node: NodeId,
    pub comp: CompName,
    pub value: f64,
}

/// `LIAISON_DDL`: Σ coef·u = rhs.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearRelation {
    pub terms: Vec<(NodeId, CompName, f64)>,
    pub rhs: f64,
}

/// A distributed load on boundary cells.
#[derive(Clone, Debug, PartialEq)]
pub enum BoundaryLoad {
    /// `FORCE_CONTOUR`: force per unit length (FX, FY[, FZ]).
    Force { cells: Vec<CellId>, force: [f64; 3] },
    /// `PRES_REP`: pressure (positive pushes into the body).
    Pressure { cells: Vec<CellId>, pressure: f64 },
}

/// A value given as a function (`AFFE_CHAR_MECA_F`, `AFFE_CHAR_CINE_F`):
/// of `INST` and of the coordinates `X`, `Y`, `Z` where it applies.
#[derive(Clone, Debug)]
pub struct LoadFunction(pub Rc<Function>);

impl PartialEq for LoadFunction {
    fn eq(&self, other: &LoadFunction) -> bool {
        Rc::ptr_eq(&self.0, &other.0)
    }
}

/// An imposed value or nodal force given by a function, with the node's
/// coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct ImposedFn {
    pub node: NodeId,
    pub comp: CompName,
    pub function: LoadFunction,
    pub xyz: [f64; 3],
}

/// A distributed load given by functions of `INST` or of the coordinates
/// `X`, `Y`, `Z` (not both: checked when the load is defined).
#[derive(Clone, Debug, PartialEq)]
pub enum BoundaryFn {
    /// `FORCE_CONTOUR`/`FORCE_FACE`: per component, a function or nothing.
    Force {
        cells: Vec<CellId>,
        force: [Option<LoadFunction>; 3],
    },
    /// `PRES_REP`.
    Pressure {
        cells: Vec<CellId>,
        pressure: LoadFunction,
    },
}

/// `FORCE_INTERNE`: a force per unit volume (per unit area in 2D), each
/// component a constant or (AFFE_CHAR_MECA_F) a function of `INST` or of
/// the coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeForce {
    pub cells: Vec<CellId>,
    pub force: [f64; 3],
    pub functions: [Option<LoadFunction>; 3],
}

/// `PESANTEUR`: gravity, the force ρ·g·d per unit volume (per unit area
/// in 2D, ×r in AXIS where only its axial component acts: code_aster's
/// te0085) on continuum cells, ρ the `ELAS/RHO` of each cell's material
/// at the solve (code_aster's te0015/te0085 read it with `rcvalb`, which
/// stops when it is missing).
#[derive(Clone, Debug, PartialEq)]
pub struct Gravity {
    pub cells: Vec<CellId>,
    /// g·d/|d| (GRAVITE times the unit DIRECTION).
    pub acceleration: [f64; 3],
    /// `file:line:col` of the `PESANTEUR` keyword, for the solve's
    /// messages (a cell without RHO).
    pub at: String,
}

/// `FORCE_ARETE`: force and moment per unit length (FX FY FZ MX MY MZ) on
/// segments of a 3D model; `AFFE_CHAR_MECA_F`: functions of `INST`. Each
/// segment with the Gauss family of the element code_aster puts on it
/// (COQUE_3D edges: te0418's FPG4).
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeForce {
    pub cells: Vec<(CellId, aster_fem::EdgeRule)>,
    pub force: [f64; 6],
    pub functions: [Option<LoadFunction>; 6],
}

/// `FORCE_COQUE`: a force and moment per unit area on shell cells (DKT,
/// COQUE_3D): global FX FY FZ MX MY MZ, then a pressure PRES acting
/// along −n, each a constant (`values`) or, `AFFE_CHAR_MECA_F`, a function
/// of `INST` or of the coordinates (evaluated at the cell's nodes, as
/// te0032/te0403 do). A cell of several occurrences keeps the last one's
/// (code_aster's load map, `nocart`).
#[derive(Clone, Debug, PartialEq)]
pub struct ShellForce {
    pub cells: Vec<CellId>,
    pub values: [f64; 7],
    pub functions: [Option<LoadFunction>; 7],
    /// `PLAN`: the plane the load acts in, in half thicknesses from the
    /// mid-surface (INF −1, SUP +1, MOY and MAIL 0).
    pub plane: f64,
    /// Whether that plane is the section's (INF, SUP, MOY: moved by its
    /// `EXCENTREMENT` too, te0032's `dist`) rather than the mesh's (MAIL).
    pub section_plane: bool,
    /// The sign of the pressure slot: 1 for `PRES`, −1 when the local
    /// normal force `F3` was given there (te0032 and fsurf take F3 along
    /// the normal n, PRES along −n).
    pub normal_sign: f64,
}

/// `AFFE_CHAR_CINE(MECA_IMPO=…)`: eliminated imposed values
/// (`AFFE_CHAR_CINE_F`: `imposed_fn`).
#[derive(Clone, Debug, PartialEq)]
pub struct KinematicLoad {
    pub model: u32,
    pub imposed: Vec<Imposed>,
    pub imposed_fn: Vec<ImposedFn>,
}

/// `AFFE_CHAR_MECA`: dualised conditions and forces.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MechanicalLoad {
    pub model: u32,
    pub imposed: Vec<Imposed>,
    pub relations: Vec<LinearRelation>,
    pub nodal_forces: Vec<Imposed>,
    pub boundary: Vec<BoundaryLoad>,
    /// `FORCE_INTERNE`: force per unit volume on continuum cells.
    pub volume: Vec<VolumeForce>,
    /// `PESANTEUR`.
    pub gravity: Vec<Gravity>,
    /// `FORCE_ARETE` (constant or, `AFFE_CHAR_MECA_F`, functions of INST).
    pub edges: Vec<EdgeForce>,
    /// `FORCE_COQUE` (constant or, `AFFE_CHAR_MECA_F`, functions).
    pub shells: Vec<ShellForce>,
    /// `AFFE_CHAR_MECA_F`: the same loads given by functions.
    pub imposed_fn: Vec<ImposedFn>,
    pub nodal_forces_fn: Vec<ImposedFn>,
    pub boundary_fn: Vec<BoundaryFn>,
    /// `AFFE_CHAR_MECA_F/LIAISON_GROUP`: relations whose right-hand side
    /// is a function of `INST`.
    pub relations_fn: Vec<RelationFn>,
}

/// A linear relation Σ aᵢ·uᵢ = f(INST) (its `rhs` is 1, scaled by `function`).
#[derive(Clone, Debug, PartialEq)]
pub struct RelationFn {
    pub relation: LinearRelation,
    pub function: LoadFunction,
}

/// One `LIAISON_UNIL` zone: Σ COEF_MULT·u ≤ COEF_IMPO on each node.
#[derive(Clone, Debug)]
pub struct UnilateralZone {
    pub nodes: Vec<NodeId>,
    pub comps: Vec<CompName>,
    pub coef_mult: Vec<Rc<Function>>,
    pub coef_impo: Rc<Function>,
}

/// How LIAISON_UNIL rows are enforced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum UnilateralAlgo {
    Constraint,
    Penalty(f64),
}

/// `DEFI_CONTACT` and `DEFI_CONT`.
#[derive(Clone, Debug)]
pub enum ContactDef {
    Unilateral {
        model: u32,
        zones: Vec<UnilateralZone>,
        algo: UnilateralAlgo,
    },
    /// DISCRETE/CONTINUE zones, kept as keywords until the solve (the
    /// contact crate builds its zones from them).
    Zones {
        model: u32,
        keywords: aster_eval::Keywords,
    },
    /// `DEFI_CONT` (code_aster 17's mortar contact of MECA_NON_LINE).
    Mortar {
        model: u32,
        zones: Vec<aster_contact::mortar_lagrangian::MortarZoneDef>,
        /// Each zone's `ALGO_CONT` (and `VARIANTE`): one force source per
        /// method (`defi_cont::groups`).
        algos: Vec<crate::defi_cont::MortarAlgo>,
    },
}

/// One stored instant of a result.
#[derive(Clone, Debug)]
pub struct Step {
    pub nume_ordre: u32,
    pub inst: f64,
    pub fields: crate::field::StepFields,
}

/// `evol_noli` / `evol_elas`.
#[derive(Clone, Debug)]
pub struct EvolResult {
    pub typ: String,
    pub mesh: u32,
    pub steps: Vec<Step>,
    /// What produced it, to compute more fields on demand (`CALC_CHAMP`).
    pub fem: Option<Rc<crate::fembridge::FemRun>>,
    /// Tables the computation made (`OBSERVATION`), for `RECU_TABLE`.
    pub tables: Vec<(String, Rc<crate::table::Table>)>,
    /// A `mode_meca` (CALC_MODES): the modes' parameters.
    pub modal: Option<Rc<ModalInfo>>,
    /// A `mult_elas` (MACRO_ELAS_MULT): its load cases, named by NOM_CAS,
    /// the i-th stored at NUME_ORDRE i + 1.
    pub cases: Option<Rc<crate::commands::elas_mult::LoadCases>>,
    /// An `evol_ther`: what its fluxes need (`CALC_CHAMP/THERMIQUE`).
    pub thermal: Option<Rc<crate::commands::thermal_nl::ThermalRun>>,
    /// An `evol_ther` of `CREA_RESU(OPERATION='PREP_VARC')`: its `TEMP`
    /// fields hold TEMP_MIL, TEMP_INF, TEMP_SUP, the temperature through
    /// the thickness of the shells that AFFE_VARC gives it to.
    pub prep_varc: bool,
}

/// The parameters of the modes of a `mode_meca`, per NUME_ORDRE
/// (`NUME_MODE`, `FREQ`, `OMEGA2`, `MASS_GENE`, …), the modes whose
/// components code_aster's rules do not determine (why), every eigenvalue
/// of the problem and its matrices (for NORM_MODE).
#[derive(Clone, Debug, Default)]
pub struct ModalInfo {
    pub params: BTreeMap<u32, BTreeMap<String, f64>>,
    pub undetermined: BTreeMap<u32, String>,
    /// The modes of `undetermined` whose only indeterminacy is the sign
    /// (a tie of opposite components): their energies are determined.
    pub sign_only: std::collections::BTreeSet<u32>,
    /// `OPTION='AJUSTE'`: code_aster's frequencies are its secant
    /// iterates, converged to this relative precision (PREC_AJUSTE) on
    /// ω², not the eigenvalues aster computes.
    pub ajuste_prec: Option<f64>,
    pub lambdas: Vec<f64>,
    pub problem: Option<Rc<crate::commands::modal::Problem>>,
}

impl EvolResult {
    /// A result of type `typ` on mesh `mesh` with no step yet.
    pub fn new(typ: String, mesh: u32) -> EvolResult {
        EvolResult {
            typ,
            mesh,
            steps: Vec::new(),
            fem: None,
            tables: Vec::new(),
            modal: None,
            cases: None,
            thermal: None,
            prep_varc: false,
        }
    }

    /// The step at an instant, matched with a precision (relative unless
    /// `absolute`).
    pub fn step_at(&self, inst: f64, precision: f64, absolute: bool) -> Option<&Step> {
        self.steps.iter().find(|s| {
            let d = (s.inst - inst).abs();
            if absolute {
                d <= precision
            } else {
                d <= precision * inst.abs().max(1e-300) || d == 0.0
            }
        })
    }

    pub fn step_numbered(&self, nume_ordre: u32) -> Option<&Step> {
        self.steps.iter().find(|s| s.nume_ordre == nume_ordre)
    }

    /// The NUME_ORDRE of a `mult_elas`'s load case `NOM_CAS` (`None`: not
    /// a `mult_elas`, or no such case).
    pub fn case_named(&self, nom_cas: &str) -> Option<u32> {
        self.cases.as_ref()?.order_of(nom_cas)
    }

    /// The `NOM_CAS` of a `mult_elas`'s step.
    pub fn case_name(&self, nume_ordre: u32) -> Option<&str> {
        self.cases.as_ref()?.name_of(nume_ordre)
    }
}

/// `DEFI_LIST_INST`: the instants and what to do when an increment fails
/// (`ECHEC`).
#[derive(Clone, Debug, PartialEq)]
pub struct TimeList {
    pub instants: Rc<Vec<f64>>,
    /// `ECHEC/ACTION='DECOUPE'` (`None`: `ARRET`).
    pub subdivision: Option<aster_fem::Subdivision>,
    /// `ECHEC/EVENEMENT='INTERPENETRATION'`, `ACTION='ADAPT_COEF_PENA'`.
    pub penalty_adaptation: Option<aster_fem::PenaltyAdaptation>,
    /// Where the list was defined (`file:line:col`), for messages.
    pub location: Option<String>,
}

/// Any concept.
#[derive(Clone, Debug)]
pub enum Concept {
    Mesh(Arc<Mesh>),
    Model(Rc<ModelDef>),
    Material(Rc<Material>),
    MaterialField(Rc<MaterialField>),
    CaraElem(Rc<CaraElem>),
    KinematicLoad(Rc<KinematicLoad>),
    MechanicalLoad(Rc<MechanicalLoad>),
    Function(Rc<Function>),
    RealList(Rc<Vec<f64>>),
    TimeList(Rc<TimeList>),
    Contact(Rc<ContactDef>),
    Result(Rc<EvolResult>),
    Table(Rc<Table>),
    Field(Rc<Field>),
    /// Elementary vectors (`vect_elem`), kept assembled per node: every
    /// use in a program goes through ASSE_VECTEUR, which sums them.
    VectElem(Rc<crate::field::NodalField>),
    /// `NUME_DDL`: the numbering of a model's DOFs (the model's id).
    Numbering(u32),
    /// `CALC_MATR_ELEM`: elementary matrices (kept as their recipe).
    MatrElem(Rc<crate::commands::modal::MatrElem>),
    /// `ASSE_MATRICE`, `ASSEMBLAGE/MATR_ASSE`: an assembled matrix.
    MatrAsse(Rc<crate::commands::modal::MatrAsse>),
    /// A nodal field of functions (`CREA_CHAMP(OPERATION='AFFE',
    /// TYPE_CHAM='NOEU_*_F', AFFE=_F(VALE_F=…))`), evaluated by
    /// `CREA_CHAMP(OPERATION='EVAL')`.
    FunctionField(Rc<NodalFunctionField>),
    /// A field of functions at Gauss points (`CREA_CHAMP(OPERATION='AFFE',
    /// TYPE_CHAM='ELGA_NEUT_F')`), evaluated by `CREA_CHAMP(OPERATION=
    /// 'EVAL')` on an `ELGA` field of parameters.
    GaussFunctionField(Rc<GaussFunctionField>),
    /// `MACR_ELEM_STAT`.
    MacroElement(Rc<MacroElement>),
    /// `DEFI_MAILLAGE`.
    SuperMesh(Rc<SuperMesh>),
    /// `DEFI_FOND_FISS`: a crack front (`fond_fissure`).
    CrackFront(Rc<crate::commands::fracture::CrackFront>),
    /// `AFFE_MODELE(PHENOMENE='THERMIQUE')`.
    ThermalModel(Rc<crate::commands::thermal::ThermalModel>),
    /// `AFFE_CHAR_THER`.
    ThermalLoad(Rc<crate::commands::thermal::ThermalLoad>),
}

/// Per node, per component, a function (`NOEU_*_F`).
#[derive(Clone, Debug, Default)]
pub struct NodalFunctionField {
    pub components: Vec<String>,
    pub values: BTreeMap<NodeId, BTreeMap<String, Rc<Function>>>,
}

/// Per cell of a model, per component, a function shared by the cell's
/// Gauss points (`ELGA_NEUT_F`): `None` is code_aster's zero function
/// `&FOZERO` (`PROL_ZERO='OUI'` where no `AFFE` occurrence gave one).
#[derive(Clone, Debug, Default)]
pub struct GaussFunctionField {
    pub components: Vec<String>,
    /// Per cell: the number of Gauss points, and one function per
    /// component (in the order of `components`).
    pub values: BTreeMap<CellId, GaussFunctions>,
}

/// A cell's entry of a [`GaussFunctionField`]: its number of Gauss points
/// and one function per component (`None`: the zero function).
pub type GaussFunctions = (usize, Vec<Option<Rc<Function>>>);

impl Concept {
    /// What it is, for messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Concept::Mesh(_) => "a mesh",
            Concept::Model(_) => "a model",
            Concept::Material(_) => "a material",
            Concept::MaterialField(_) => "a material field",
            Concept::CaraElem(_) => "element characteristics",
            Concept::KinematicLoad(_) => "a kinematic load",
            Concept::MechanicalLoad(_) => "a mechanical load",
            Concept::Function(_) => "a function",
            Concept::RealList(_) => "a list of reals",
            Concept::TimeList(_) => "a time list",
            Concept::Contact(_) => "a contact definition",
            Concept::Result(_) => "a result",
            Concept::Table(_) => "a table",
            Concept::Field(_) => "a field",
            Concept::VectElem(_) => "elementary vectors",
            Concept::Numbering(_) => "a DOF numbering",
            Concept::MatrElem(_) => "elementary matrices (CALC_MATR_ELEM)",
            Concept::MatrAsse(_) => "an assembled matrix",
            Concept::FunctionField(_) => "a field of functions",
            Concept::GaussFunctionField(_) => "a field of functions at Gauss points",
            Concept::MacroElement(_) => "a static macro element (MACR_ELEM_STAT)",
            Concept::SuperMesh(_) => "a super mesh (DEFI_MAILLAGE)",
            Concept::CrackFront(_) => "a crack front",
            Concept::ThermalModel(_) => "a thermal model",
            Concept::ThermalLoad(_) => "a thermal load (AFFE_CHAR_THER)",
        }
    }
}
