//! Modal analysis: `CALC_MATR_ELEM` (`RIGI_MECA`, `MASS_MECA`,
//! `MASS_MECA_DIAG`), `NUME_DDL(MATR_RIGI=…)`, `ASSE_MATRICE`, the
//! `ASSEMBLAGE` macro (`MATR_ASSE`), `CALC_MODES` (`TYPE_RESU=
//! 'DYNAMIQUE'`) and `NORM_MODE`, turned into aster-fem's
//! [`aster_fem::modal`] eigenproblem: the matrices are the element
//! routines' (stiffness, mass of DYNA_NON_LINE), the conditions of the
//! stiffness's loads (`DDL_IMPO`, `LIAISON_*`, `CHAR_CINE`) the
//! homogeneous constraints of the eigenproblem. The result is a
//! `mode_meca`: NUME_ORDRE 1.. in ascending frequency, the parameters of
//! code_aster's `vppara` (NUME_MODE, FREQ, OMEGA2, MASS_GENE, RIGI_GENE,
//! FACT_PARTICI_D*, MASS_EFFE_D*) and the field DEPL normalised as
//! code_aster's `vpnorx` does (largest component +1), or by `NORM_MODE`.

use crate::concept::{CaraElem, Concept, EvolResult, KinematicLoad, MaterialField, MechanicalLoad};
use crate::concept::{ModalInfo, ModelDef, Step};
use crate::executor::{result_of, store_result, Executor};
use crate::fembridge;
use crate::field::{Field, StepFields};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ConceptRef, ExecError, Keywords};
use aster_fem::modal::{self, Selection};
use aster_fem::{Comp, Dof, Load, Loads, Lumping, Model};
use std::collections::BTreeMap;
use std::rc::Rc;

/// What an elementary matrix is (`CALC_MATR_ELEM/OPTION`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatrixOption {
    Rigi,
    Mass,
    MassDiag,
}

impl MatrixOption {
    fn name(self) -> &'static str {
        match self {
            MatrixOption::Rigi => "RIGI_MECA",
            MatrixOption::Mass => "MASS_MECA",
            MatrixOption::MassDiag => "MASS_MECA_DIAG",
        }
    }
}

/// `matr_elem_depl_r`: kept as its recipe, assembled when used.
#[derive(Clone, Debug)]
pub struct MatrElem {
    pub option: MatrixOption,
    /// The model's concept id (`NUME_DDL(MATR_RIGI=…)`'s numbering).
    pub model_id: u32,
    pub model: Rc<ModelDef>,
    pub materials: Option<Rc<MaterialField>>,
    pub cara: Option<Rc<CaraElem>>,
    /// `CHARGE`: their conditions (dualised by code_aster) constrain
    /// the eigenproblem.
    pub loads: Vec<Rc<MechanicalLoad>>,
}

/// `matr_asse_depl_r`: elementary matrices and the eliminated conditions.
#[derive(Clone, Debug)]
pub struct MatrAsse {
    pub elem: Rc<MatrElem>,
    pub kinematic: Vec<Rc<KinematicLoad>>,
}

const OPTIONS: &[&str] = &["RIGI_MECA", "MASS_MECA", "MASS_MECA_DIAG"];

/// What CALC_MATR_ELEM reads (`crate::support`).
pub(crate) const CALC_MATR_ELEM: Support = Support {
    values: &[Values::new("OPTION", OPTIONS)
        .why("(the mechanical stiffness and mass: damping, geometric stiffness and the other physics are not implemented)")],
    ..Support::keywords(&[
        "OPTION",
        "MODELE",
        "CHAM_MATER",
        "CARA_ELEM",
        "CHARGE",
        "INST",
        "CALC_ELEM_MODELE",
        "MODE_FOURIER",
        "INFO",
    ])
};

fn parse_option(s: &str) -> Option<MatrixOption> {
    match s {
        "RIGI_MECA" => Some(MatrixOption::Rigi),
        "MASS_MECA" => Some(MatrixOption::Mass),
        "MASS_MECA_DIAG" => Some(MatrixOption::MassDiag),
        _ => None,
    }
}

fn mechanical_loads(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
) -> Result<Vec<Rc<MechanicalLoad>>, ExecError> {
    let mut out = Vec::new();
    for s in kw.simple("CHARGE") {
        let Some(c) = s.as_concept() else { continue };
        match ex.concept(c)? {
            Concept::MechanicalLoad(l) => out.push(l.clone()),
            other => {
                return Err(ex.kw_error(
                    cmd,
                    kw,
                    "CHARGE",
                    format!(
                        "`{}` is {}, expected a mechanical load",
                        c.name,
                        other.kind()
                    ),
                ))
            }
        }
    }
    Ok(out)
}

fn matr_elem(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    option: MatrixOption,
) -> Result<MatrElem, ExecError> {
    let m = ex.required(cmd, kw, "MODELE")?;
    let model = ex.model(m)?;
    let materials = match kw.concept("CHAM_MATER") {
        Some(c) => Some(ex.material_field(c)?),
        None => None,
    };
    let cara = match kw.concept("CARA_ELEM") {
        Some(c) => Some(ex.cara_elem(c)?),
        None => None,
    };
    if !model.substructures.is_empty() {
        return Err(ex.kw_error(
            cmd,
            kw,
            "MODELE",
            "a model with super cells (AFFE_SOUS_STRUC) is not supported here",
        ));
    }
    Ok(MatrElem {
        option,
        model_id: m.id,
        model,
        materials,
        cara,
        loads: mechanical_loads(ex, cmd, kw)?,
    })
}

pub fn calc_matr_elem(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let opt = kw.str("OPTION").unwrap_or("RIGI_MECA");
    let option = parse_option(opt)
        .ok_or_else(|| ex.kw_error("CALC_MATR_ELEM", kw, "OPTION", format!("'{opt}'")))?;
    let m = matr_elem(ex, "CALC_MATR_ELEM", kw, option)?;
    store_result(ex, call, Concept::MatrElem(Rc::new(m)))
}

/// NUME_DDL's `MATR_RIGI`: the numbering of the matrix's model.
pub(crate) fn numbering_of(ex: &Executor, c: &ConceptRef) -> Result<u32, ExecError> {
    match ex.concept(c)? {
        Concept::MatrElem(m) => Ok(m.model_id),
        other => Err(ExecError::new(format!(
            "NUME_DDL/MATR_RIGI: `{}` is {}, expected elementary matrices (CALC_MATR_ELEM)",
            c.name,
            other.kind()
        ))),
    }
}

/// What ASSE_MATRICE reads (`crate::support`).
pub(crate) const ASSE_MATRICE: Support =
    Support::keywords(&["MATR_ELEM", "NUME_DDL", "CHAR_CINE", "SYME", "INFO"]);

fn kinematic_loads(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
) -> Result<Vec<Rc<KinematicLoad>>, ExecError> {
    let mut out = Vec::new();
    for s in kw.simple("CHAR_CINE") {
        let Some(c) = s.as_concept() else { continue };
        match ex.concept(c)? {
            Concept::KinematicLoad(l) => out.push(l.clone()),
            other => {
                return Err(ex.kw_error(
                    cmd,
                    kw,
                    "CHAR_CINE",
                    format!("`{}` is {}, expected AFFE_CHAR_CINE", c.name, other.kind()),
                ))
            }
        }
    }
    Ok(out)
}

pub fn asse_matrice(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let elems: Vec<&ConceptRef> = kw
        .simple("MATR_ELEM")
        .iter()
        .filter_map(|s| s.as_concept())
        .collect();
    let [e] = elems.as_slice() else {
        return Err(ex.kw_error(
            "ASSE_MATRICE",
            kw,
            "MATR_ELEM",
            "one elementary matrix is supported (a sum of several is not)",
        ));
    };
    let Concept::MatrElem(elem) = ex.concept(e)? else {
        return Err(ex.kw_error(
            "ASSE_MATRICE",
            kw,
            "MATR_ELEM",
            format!("`{}` is not an elementary matrix (CALC_MATR_ELEM)", e.name),
        ));
    };
    let elem = elem.clone();
    let kinematic = kinematic_loads(ex, "ASSE_MATRICE", kw)?;
    store_result(
        ex,
        call,
        Concept::MatrAsse(Rc::new(MatrAsse { elem, kinematic })),
    )
}

/// What ASSEMBLAGE reads (`crate::support`).
pub(crate) const ASSEMBLAGE: Support = Support {
    values: &[Values::new("MATR_ASSE/OPTION", OPTIONS)
        .why("(the mechanical stiffness and mass: damping, geometric stiffness and the other physics are not implemented)")],
    ..Support::keywords(&[
        "MODELE",
        "CHAM_MATER",
        "CARA_ELEM",
        "CHARGE",
        "CHAR_CINE",
        "NUME_DDL",
        "INST",
        "INFO",
        "SOLVEUR",
        "SOLVEUR/*",
        "MATR_ASSE",
        "MATR_ASSE/MATRICE",
        "MATR_ASSE/OPTION",
        "MATR_ASSE/MODE_FOURIER",
    ])
};

/// The `ASSEMBLAGE` macro: CALC_MATR_ELEM + NUME_DDL + ASSE_MATRICE for
/// each `MATR_ASSE` occurrence, into the concepts `CO(…)` names.
pub fn assemblage(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let cmd = "ASSEMBLAGE";
    let kinematic = kinematic_loads(ex, cmd, kw)?;
    let mut model_id = None;
    for occ in kw.factor("MATR_ASSE") {
        let opt = occ.str("OPTION").unwrap_or("RIGI_MECA");
        let option =
            parse_option(opt).ok_or_else(|| ex.kw_error(cmd, occ, "OPTION", format!("'{opt}'")))?;
        let elem = Rc::new(matr_elem(ex, cmd, kw, option)?);
        model_id = Some(elem.model_id);
        let target = ex.required(cmd, occ, "MATRICE")?.clone();
        ex.insert(
            &target,
            Concept::MatrAsse(Rc::new(MatrAsse {
                elem,
                kinematic: kinematic.clone(),
            })),
        );
    }
    if let Some(n) = kw.concept("NUME_DDL") {
        let id = match model_id {
            Some(id) => id,
            None => ex.required(cmd, kw, "MODELE")?.id,
        };
        if !matches!(ex.concept(n), Ok(Concept::Numbering(_))) {
            let n = n.clone();
            ex.insert(&n, Concept::Numbering(id));
        }
    }
    Ok(CommandOutput::Nothing)
}

fn matr_asse(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    name: &str,
) -> Result<Rc<MatrAsse>, ExecError> {
    let c = ex.required(cmd, kw, name)?;
    match ex.concept(c)? {
        Concept::MatrAsse(m) => Ok(m.clone()),
        other => Err(ex.kw_error(
            cmd,
            kw,
            name,
            format!(
                "`{}` is {}, expected an assembled matrix",
                c.name,
                other.kind()
            ),
        )),
    }
}

/// What CALC_MODES reads (`crate::support`).
pub(crate) const CALC_MODES: Support = Support {
    values: &[
        Values::new("TYPE_RESU", &["DYNAMIQUE"])
            .why("(buckling and general eigenproblems are not implemented)"),
        Values::new(
            "OPTION",
            &["PLUS_PETITE", "CENTRE", "BANDE", "TOUT", "PROCHE", "AJUSTE"],
        ),
        Values::new("FILTRE_MODE/CRIT_EXTR", &["MASS_EFFE_UN", "MASS_GENE"]),
        Values::new(
            "NORM_MODE/NORME",
            &[
                "MASS_GENE",
                "RIGI_GENE",
                "TRAN_ROTA",
                "TRAN",
                "SANS_CMP=LAGR",
            ],
        ),
    ],
    ..Support::keywords(&[
        "TYPE_RESU",
        "OPTION",
        "MATR_RIGI",
        "MATR_MASS",
        "CALC_FREQ",
        "CALC_FREQ/NMAX_FREQ",
        "CALC_FREQ/FREQ",
        "CALC_FREQ/SEUIL_FREQ",
        "CALC_FREQ/NMAX_ITER_SHIFT",
        "CALC_FREQ/PREC_SHIFT",
        "CALC_FREQ/NMAX_ITER",
        "CALC_FREQ/PREC",
        "CALC_FREQ/NPREC_SOLVEUR",
        "CALC_FREQ/NMAX_ITER_SEPARE",
        "CALC_FREQ/PREC_SEPARE",
        "CALC_FREQ/NMAX_ITER_AJUSTE",
        "CALC_FREQ/PREC_AJUSTE",
        "SOLVEUR_MODAL",
        "SOLVEUR_MODAL/*",
        "SOLVEUR",
        "SOLVEUR/*",
        "VERI_MODE",
        "VERI_MODE/*",
        "NORM_MODE",
        "NORM_MODE/NORME",
        "NORM_MODE/INFO",
        "FILTRE_MODE",
        "FILTRE_MODE/CRIT_EXTR",
        "FILTRE_MODE/SEUIL",
        "IMPRESSION",
        "IMPRESSION/*",
        "AMELIORATION",
        "STOP_BANDE_VIDE",
        "TITRE",
        "INFO",
        "PARALLELISME_MACRO",
        "PARALLELISME_MACRO/*",
        // Stored with the modes by code_aster; the matrices already carry them.
        "CHAM_MATER",
        "CARA_ELEM",
    ])
};

/// The matrices, constraints and model of an eigenproblem (kept with the
/// modes for NORM_MODE).
pub struct Problem {
    model: Model,
    k: aster_fem::linalg::Csc,
    m: aster_fem::linalg::Csc,
    constraints: Vec<Vec<(usize, f64)>>,
    /// The densities and discrete masses of the mass matrix (ECIN_ELEM).
    mass_data: aster_fem::mass::MassData,
}

impl std::fmt::Debug for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Problem({} DOFs, {} constraints)",
            self.k.n,
            self.constraints.len()
        )
    }
}

fn comp(name: &str) -> Result<Comp, ExecError> {
    Comp::from_name(name).ok_or_else(|| ExecError::new(format!("unknown component {name}")))
}

fn problem(ex: &Executor, cmd: &str, k: &MatrAsse, m: &MatrAsse) -> Result<Problem, ExecError> {
    let err = |e: aster_fem::FemError| ExecError::new(format!("{cmd}: {e}"));
    if k.elem.option != MatrixOption::Rigi {
        return Err(ExecError::new(format!(
            "{cmd}/MATR_RIGI: the matrix is {}, expected RIGI_MECA",
            k.elem.option.name()
        )));
    }
    if m.elem.option == MatrixOption::Rigi {
        return Err(ExecError::new(format!(
            "{cmd}/MATR_MASS: the matrix is RIGI_MECA, expected MASS_MECA or MASS_MECA_DIAG"
        )));
    }
    if k.elem.model_id != m.elem.model_id {
        return Err(ExecError::new(format!(
            "{cmd}: MATR_RIGI and MATR_MASS are built on different models"
        )));
    }
    let def = &k.elem.model;
    let mesh = ex.mesh_by_id(def.mesh)?;
    let empty = MaterialField {
        mesh: def.mesh,
        cells: BTreeMap::new(),
        temperature: None,
    };
    let materials = k.elem.materials.as_deref().unwrap_or(&empty);
    let model = fembridge::build_model(&mesh, def, materials, k.elem.cara.as_deref())?;
    let stiffness = aster_fem::assembly::assemble_stiffness(&model).map_err(err)?;
    let mass_materials = m.elem.materials.as_deref().unwrap_or(&empty);
    let mass_cara = m.elem.cara.as_deref().or(k.elem.cara.as_deref());
    let data = crate::dyna::mass_data(&mesh, def, mass_materials, mass_cara)?.0;
    let lumping = if m.elem.option == MatrixOption::MassDiag {
        Lumping::Diagonal
    } else {
        Lumping::Consistent
    };
    let mass = aster_fem::mass::assemble_mass(&model, &data, lumping).map_err(err)?;
    let mass_data = data;
    // The homogeneous conditions of the stiffness's loads.
    let mut loads = Loads::new();
    for l in &k.elem.loads {
        for i in &l.imposed {
            loads.push(Load::Imposed {
                dof: Dof::new(i.node, comp(i.comp)?),
                value: 0.0,
            });
        }
        for i in &l.imposed_fn {
            loads.push(Load::Imposed {
                dof: Dof::new(i.node, comp(i.comp)?),
                value: 0.0,
            });
        }
        for r in l
            .relations
            .iter()
            .chain(l.relations_fn.iter().map(|r| &r.relation))
        {
            let terms = r
                .terms
                .iter()
                .map(|(n, c, a)| Ok((Dof::new(*n, comp(c)?), *a)))
                .collect::<Result<Vec<_>, ExecError>>()?;
            loads.push(Load::Relation { terms, rhs: 0.0 });
        }
    }
    for kl in &k.kinematic {
        for i in &kl.imposed {
            loads.push(Load::Eliminated {
                dof: Dof::new(i.node, comp(i.comp)?),
                value: 0.0,
            });
        }
        for i in &kl.imposed_fn {
            loads.push(Load::Eliminated {
                dof: Dof::new(i.node, comp(i.comp)?),
                value: 0.0,
            });
        }
    }
    loads.validate(&model).map_err(err)?;
    let mut constraints: Vec<Vec<(usize, f64)>> = loads
        .equality_rows(&model, 0.0)
        .map_err(err)?
        .into_iter()
        .map(|r| r.terms)
        .collect();
    let mut elim: Vec<usize> = loads
        .eliminated(&model, 0.0)
        .map_err(err)?
        .into_keys()
        .collect();
    elim.sort_unstable();
    constraints.extend(elim.into_iter().map(|i| vec![(i, 1.0)]));
    Ok(Problem {
        model,
        k: stiffness,
        m: mass,
        constraints,
        mass_data,
    })
}

fn two_pi() -> f64 {
    2.0 * std::f64::consts::PI
}

/// code_aster's frequency of an eigenvalue: √λ / 2π, negative for λ < 0
/// (`freqom`).
fn freq(lambda: f64) -> f64 {
    lambda.signum() * lambda.abs().sqrt() / two_pi()
}

fn omega2(f: f64) -> f64 {
    let w = two_pi() * f;
    f.signum() * w * w
}

/// How a mode's vector is scaled (`NORM_MODE/NORME`).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Norm {
    /// `SANS_CMP=LAGR` (code_aster's default `vpnorx`).
    MaxComponent,
    /// `TRAN_ROTA`, `TRAN`: the largest of the named components becomes 1
    /// (sign kept as `vpnorm` does: divided by the signed component).
    MaxOf(&'static [Comp]),
    MassGene,
    RigiGene,
}

fn parse_norm(s: &str) -> Option<Norm> {
    Some(match s {
        "SANS_CMP=LAGR" => Norm::MaxComponent,
        "TRAN_ROTA" => Norm::MaxOf(&[
            Comp::DX,
            Comp::DY,
            Comp::DZ,
            Comp::DRX,
            Comp::DRY,
            Comp::DRZ,
        ]),
        "TRAN" => Norm::MaxOf(&[Comp::DX, Comp::DY, Comp::DZ]),
        "MASS_GENE" => Norm::MassGene,
        "RIGI_GENE" => Norm::RigiGene,
        _ => return None,
    })
}

/// The parameters of one mode and its scaled vector.
fn mode_params(
    p: &Problem,
    u: &[f64],
    lambda: f64,
    nume_mode: usize,
    total_mass: &[f64; 3],
) -> BTreeMap<String, f64> {
    let mu = p.m.mul(u);
    let ku = p.k.mul(u);
    let mass_gene: f64 = u.iter().zip(&mu).map(|(a, b)| a * b).sum();
    let rigi_gene: f64 = u.iter().zip(&ku).map(|(a, b)| a * b).sum();
    let f = freq(lambda);
    let mut out = BTreeMap::new();
    out.insert("NUME_MODE".to_string(), nume_mode as f64);
    out.insert("FREQ".to_string(), f);
    out.insert("OMEGA2".to_string(), omega2(f));
    out.insert("MASS_GENE".to_string(), mass_gene);
    out.insert("RIGI_GENE".to_string(), rigi_gene);
    out.insert("AMOR_GENE".to_string(), 0.0);
    out.insert("AMOR_REDUIT".to_string(), 0.0);
    let dofs = p.model.dofs().dofs();
    for (k, (c, name)) in [(Comp::DX, "DX"), (Comp::DY, "DY"), (Comp::DZ, "DZ")]
        .into_iter()
        .enumerate()
    {
        // xᵀ M d, d = 1 on every DOF of the component (vppfac).
        let r: f64 = dofs
            .iter()
            .enumerate()
            .filter(|(_, d)| d.comp == c)
            .map(|(i, _)| mu[i])
            .sum();
        let fact = r / mass_gene;
        out.insert(format!("FACT_PARTICI_{name}"), fact);
        out.insert(format!("MASS_EFFE_{name}"), r * fact);
        if total_mass[k] > 0.0 {
            out.insert(format!("MASS_EFFE_UN_{name}"), r * fact / total_mass[k]);
        }
    }
    out
}

/// Scales a mode by a norm; returns false when the norm is zero.
fn scale(p: &Problem, u: &mut [f64], norm: Norm) -> bool {
    let d = match norm {
        Norm::MaxComponent => return modal::normalise_max_component(u) != 0.0,
        Norm::MaxOf(comps) => {
            let dofs = p.model.dofs().dofs();
            let mut best = 0.0f64;
            for (i, v) in u.iter().enumerate() {
                if comps.contains(&dofs[i].comp) && best.abs() < v.abs() {
                    best = *v;
                }
            }
            best
        }
        Norm::MassGene | Norm::RigiGene => {
            let a = if norm == Norm::MassGene { &p.m } else { &p.k };
            let au = a.mul(u);
            let g: f64 = u.iter().zip(&au).map(|(x, y)| x * y).sum();
            if g <= 0.0 {
                return false;
            }
            g.sqrt()
        }
    };
    if d == 0.0 {
        return false;
    }
    u.iter_mut().for_each(|v| *v /= d);
    true
}

/// Why a mode's components cannot be compared with code_aster's: a
/// repeated eigenvalue (its basis is the solver's choice) or a sign set by
/// a tie between components of opposite signs.
fn undetermined(all: &[f64], lambda: f64, u: &[f64], norm: Norm) -> Option<String> {
    let near = all
        .iter()
        .filter(|&&l| (l - lambda).abs() <= 1e-5 * lambda.abs().max(1e-300))
        .count();
    if near > 1 {
        return Some(format!(
            "its eigenvalue is repeated ({near} eigenvalues within 1e-5 of {lambda:.6e}): the basis of the eigenspace is the solver's choice, not code_aster's"
        ));
    }
    if matches!(norm, Norm::MaxComponent | Norm::MaxOf(_)) && modal::sign_ambiguous(u, 1e-6) {
        return Some(
            "its largest components are equal with opposite signs: code_aster's sign (vpnorx: the first of them in its DOF numbering) cannot be reproduced".into(),
        );
    }
    if matches!(norm, Norm::MassGene | Norm::RigiGene) {
        // The sign is the one of vpnorx before the scaling.
        let mut v = u.to_vec();
        modal::normalise_max_component(&mut v);
        if modal::sign_ambiguous(&v, 1e-6) {
            return Some(
                "its largest components are equal with opposite signs: code_aster's sign cannot be reproduced".into(),
            );
        }
    }
    None
}

pub fn calc_modes(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "CALC_MODES";
    let kw = &call.keywords;
    for k in ["MATR_AMOR", "MATR_RIGI_GEOM", "MATR_A", "MATR_B"] {
        if kw.contains(k) {
            return Err(ex.unsupported(
                &format!("{cmd}/{k}"),
                kw.keyword(k).map(|k| k.span).unwrap_or(call.span),
            ));
        }
    }
    let k = matr_asse(ex, cmd, kw, "MATR_RIGI")?;
    let m = matr_asse(ex, cmd, kw, "MATR_MASS")?;
    let option = kw.str("OPTION").unwrap_or("PLUS_PETITE");
    let cf = kw.factor("CALC_FREQ").first().cloned().unwrap_or_default();
    if cf.f64("AMOR_REDUIT").is_some() {
        return Err(ex.unsupported(
            "CALC_MODES/CALC_FREQ/AMOR_REDUIT",
            cf.keyword("AMOR_REDUIT")
                .map(|k| k.span)
                .unwrap_or(call.span),
        ));
    }
    let nmax = cf
        .first("NMAX_FREQ")
        .and_then(|s| s.as_i64())
        .unwrap_or(10)
        .max(0) as usize;
    let freqs: Vec<f64> = cf
        .simple("FREQ")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    // AJUSTE (MODE_ITER_INV, op0044): the eigenvalues between the first
    // and the last FREQ (Sturm counts at both ends, vpfopr 'STURMAD'; a
    // bound within SEUIL_FREQ of 0 moves to −SEUIL_FREQ's ω² so that rigid
    // modes are kept), isolated by bisection and converged by the secant
    // method and inverse iteration (vpdich, vpinte, vp1pro): the exact
    // eigenpairs of the band, the first NMAX_FREQ of them when NMAX_FREQ > 0.
    let ajuste_nmax = if option == "AJUSTE" {
        cf.first("NMAX_FREQ")
            .and_then(|s| s.as_i64())
            .unwrap_or(0)
            .max(0) as usize
    } else {
        0
    };
    let omecor = omega2(cf.f64("SEUIL_FREQ").unwrap_or(1e-2));
    let ajuste_lo = match freqs.first() {
        Some(&f) if omega2(f).abs() <= omecor => -omecor,
        Some(&f) => omega2(f),
        None => f64::NEG_INFINITY,
    };
    if option == "AJUSTE" && freqs.len() < 2 {
        return Err(ex.kw_error(
            cmd,
            &cf,
            "FREQ",
            "AJUSTE needs at least two frequencies (the band's bounds)",
        ));
    }
    let p = problem(ex, cmd, &k, &m)?;
    let err = |e: aster_fem::FemError| ExecError::new(format!("{cmd}: {e}"));
    // The spectrum from its bottom: every eigenpair when the dense solver
    // takes the problem, else the lowest ones (sparse Lanczos) as far as
    // the option needs, one more for the repeated-eigenvalue check. The
    // mode numbers (NUME_MODE) are the ranks in it.
    let nr = modal::unknowns(p.k.n, &p.constraints).map_err(err)?;
    let all = if nr <= modal::MAX_DENSE {
        modal::modes(&p.k, &p.m, &p.constraints, Selection::All).map_err(err)?
    } else {
        let reach = |modes: &[modal::Mode]| -> bool {
            let Some(last) = modes.last().map(|m| m.lambda) else {
                return true;
            };
            match option {
                "PLUS_PETITE" => modes.len() > nmax,
                "BANDE" => freqs.last().is_none_or(|&hi| last > omega2(hi)),
                "AJUSTE" => {
                    let hi = freqs.last().copied().unwrap_or(f64::INFINITY);
                    last > omega2(hi)
                        || (ajuste_nmax > 0
                            && modes.iter().filter(|m| m.lambda >= ajuste_lo).count() > ajuste_nmax)
                }
                "CENTRE" | "PROCHE" => {
                    let c = freqs.iter().copied().fold(f64::MIN, f64::max);
                    let c = omega2(c);
                    let mut d: Vec<f64> = modes.iter().map(|m| (m.lambda - c).abs()).collect();
                    d.sort_by(f64::total_cmp);
                    last > c && d.get(nmax.max(1) - 1).is_some_and(|&x| x < last - c)
                }
                _ => true,
            }
        };
        if option == "TOUT" {
            return Err(ex.unsupported(
                &format!("CALC_MODES/OPTION='TOUT' on {nr} unknowns (all the modes of a problem larger than the dense solver's {})", modal::MAX_DENSE),
                kw.keyword("OPTION").map(|k| k.span).unwrap_or(call.span),
            ));
        }
        let mut count = if option == "PLUS_PETITE" {
            nmax + 1
        } else {
            20
        };
        loop {
            let modes =
                modal::lowest_modes(&p.k, &p.m, &p.constraints, count.min(nr)).map_err(err)?;
            if reach(&modes) || count >= nr {
                break modes;
            }
            if count >= 400 {
                return Err(ex.unsupported(
                    &format!("CALC_MODES/CALC_FREQ on {nr} unknowns: more than 400 modes below the requested frequencies (the sparse solver computes the spectrum from its bottom)"),
                    kw.keyword("CALC_FREQ").map(|k| k.span).unwrap_or(call.span),
                ));
            }
            count *= 2;
        }
    };
    let lambdas: Vec<f64> = all.iter().map(|md| md.lambda).collect();
    rigid_rotations_check(ex, call, &p, &lambdas)?;
    let mut chosen: Vec<usize> = match option {
        "PLUS_PETITE" => (0..nmax.min(all.len())).collect(),
        "TOUT" => (0..all.len()).collect(),
        "CENTRE" => {
            let Some(&f) = freqs.first() else {
                return Err(ex.kw_error(cmd, &cf, "FREQ", "CENTRE needs FREQ"));
            };
            let c = omega2(f);
            let mut idx: Vec<usize> = (0..all.len()).collect();
            idx.sort_by(|&a, &b| (lambdas[a] - c).abs().total_cmp(&(lambdas[b] - c).abs()));
            idx.truncate(nmax);
            idx
        }
        "BANDE" => {
            // More than two frequencies: code_aster's
            // calc_modes_multi_bandes computes each band [fᵢ, fᵢ₊₁] and
            // joins them (EXTR_MODE), NUME_MODE their ranks in the whole
            // spectrum: the modes of [f₁, fₙ].
            let (Some(lo), Some(hi), true) = (freqs.first(), freqs.last(), freqs.len() >= 2) else {
                return Err(ex.kw_error(cmd, &cf, "FREQ", "BANDE needs two frequencies"));
            };
            let (lo, hi) = (omega2(*lo), omega2(*hi));
            // `vpfopr`: a band from 0 of a free structure (K singular
            // there, the Sturm count fails) starts at −OMECOR, so its
            // rigid-body modes (ω² ≈ 0 either side) are in it.
            let lo = if lo.abs() < omecor { -omecor } else { lo };
            (0..all.len())
                .filter(|&i| lambdas[i] >= lo && lambdas[i] <= hi)
                .collect()
        }
        "AJUSTE" => {
            let hi = freqs.last().copied().map(omega2).unwrap_or(f64::INFINITY);
            let hi = if hi.abs() <= omecor { omecor } else { hi };
            let mut idx: Vec<usize> = (0..all.len())
                .filter(|&i| lambdas[i] >= ajuste_lo && lambdas[i] <= hi)
                .collect();
            if ajuste_nmax > 0 {
                idx.truncate(ajuste_nmax);
            }
            idx
        }
        "PROCHE" => {
            let mut idx = Vec::new();
            for f in &freqs {
                let c = omega2(*f);
                if let Some(i) = (0..all.len())
                    .min_by(|&a, &b| (lambdas[a] - c).abs().total_cmp(&(lambdas[b] - c).abs()))
                {
                    idx.push(i);
                }
            }
            idx
        }
        other => {
            return Err(ex.unsupported(
                &format!("CALC_MODES/OPTION='{other}'"),
                kw.keyword("OPTION").map(|k| k.span).unwrap_or(call.span),
            ))
        }
    };
    chosen.sort_unstable();
    if option != "PROCHE" {
        chosen.dedup();
    }
    if chosen.is_empty() {
        return Err(ExecError::new(format!(
            "{cmd}: no eigenvalue in the requested range ({} eigenvalues in all)",
            all.len()
        )));
    }
    let norm = match kw.factor("NORM_MODE").first().and_then(|o| o.str("NORME")) {
        Some(s) => parse_norm(s).ok_or_else(|| {
            ex.unsupported(
                &format!("CALC_MODES/NORM_MODE/NORME='{s}'"),
                kw.factor("NORM_MODE")[0]
                    .keyword("NORME")
                    .map(|k| k.span)
                    .unwrap_or(call.span),
            )
        })?,
        None => Norm::MaxComponent,
    };
    let total_mass = total_mass(&p);
    let mut steps = Vec::new();
    let mut info = ModalInfo {
        lambdas: lambdas.clone(),
        ajuste_prec: (option == "AJUSTE").then(|| {
            kw.factor("SOLVEUR_MODAL")
                .first()
                .and_then(|o| o.f64("PREC_AJUSTE"))
                .or_else(|| cf.f64("PREC_AJUSTE"))
                .unwrap_or(1e-4)
        }),
        ..ModalInfo::default()
    };
    let mut scaled = Vec::with_capacity(chosen.len());
    for (n, &i) in chosen.iter().enumerate() {
        let mut u = all[i].vector.clone();
        // vpnorx first (the sign), then NORM_MODE.
        modal::normalise_max_component(&mut u);
        if norm != Norm::MaxComponent && !scale(&p, &mut u, norm) {
            return Err(ExecError::new(format!(
                "{cmd}/NORM_MODE: mode {} has a zero norm",
                n + 1
            )));
        }
        let params = mode_params(&p, &u, all[i].lambda, i + 1, &total_mass);
        scaled.push((i, u, params));
    }
    // FILTRE_MODE (calc_modes_post → EXTR_MODE, op0168): the modes whose
    // criterion reaches SEUIL, renumbered (NUME_ORDRE), NUME_MODE kept.
    if let Some(f) = kw.factor("FILTRE_MODE").first() {
        let seuil = f.f64("SEUIL").unwrap_or(1e-3);
        let crit = f.str("CRIT_EXTR").unwrap_or("MASS_EFFE_UN");
        let keep = filtre_mode(crit, seuil, scaled.iter().map(|s| &s.2)).ok_or_else(|| {
            ex.unsupported(
                &format!("CALC_MODES/FILTRE_MODE/CRIT_EXTR='{crit}'"),
                f.keyword("CRIT_EXTR").map(|k| k.span).unwrap_or(call.span),
            )
        })?;
        let mut it = keep.into_iter();
        scaled.retain(|_| it.next().unwrap_or(false));
        if scaled.is_empty() {
            return Err(ex.kw_error(
                cmd,
                f,
                "SEUIL",
                format!(
                    "no mode passes the filter {crit} ≥ {seuil} (code_aster stops: ALGELINE3_11)"
                ),
            ));
        }
    }
    for (n, (i, u, params)) in scaled.into_iter().enumerate() {
        let nume = n as u32 + 1;
        if let Some(why) = undetermined(&lambdas, all[i].lambda, &u, norm) {
            if !why.contains("repeated") {
                info.sign_only.insert(nume);
            }
            info.undetermined.insert(nume, why);
        }
        info.params.insert(nume, params);
        let mut fields = StepFields::new();
        fields.insert(
            "DEPL".into(),
            Field::Nodal(fembridge::nodal_from_dofs(&p.model, &u)),
        );
        steps.push(Step {
            nume_ordre: nume,
            inst: 0.0,
            fields,
        });
    }
    let (p_dofs, p_conditions) = (p.k.n, p.constraints.len());
    info.problem = Some(Rc::new(p));
    let result = EvolResult {
        prep_varc: false,
        typ: "mode_meca".into(),
        mesh: k.elem.model.mesh,
        steps,
        fem: None,
        tables: Vec::new(),
        modal: Some(Rc::new(info)),
        cases: None,
        thermal: None,
    };
    let name = result_of(call)?.name.clone();
    let mut report = format!(
        "{cmd} `{name}`: {} modes of {} ({} DOFs, {} conditions; mass along DX DY DZ {:.6e} {:.6e} {:.6e})\n",
        result.steps.len(),
        lambdas.len(),
        p_dofs,
        p_conditions,
        total_mass[0],
        total_mass[1],
        total_mass[2]
    );
    if let Some(info) = &result.modal {
        for (n, p) in &info.params {
            report.push_str(&format!(
                "  {n:>4}  FREQ = {:.10e}  MASS_GENE = {:.6e}\n",
                p["FREQ"], p["MASS_GENE"]
            ));
        }
    }
    ex.write_report(&report)?;
    store_result(ex, call, Concept::Result(Rc::new(result)))
}

/// A COQUE_3D structure without any condition (a free shell: no discrete
/// spring of the model holds it either) must have its rigid rotations as
/// zero-energy modes. aster's COQUE_3D drilling stiffness resists them on
/// curved shells (sdls109d: two rigid modes at 0.65 Hz, its elastic modes
/// then 0.15 % above code_aster's): such a problem is refused rather than
/// solved with a wrong spectrum.
fn rigid_rotations_check(
    ex: &Executor,
    call: &CommandCall,
    p: &Problem,
    lambdas: &[f64],
) -> Result<(), ExecError> {
    if !p.constraints.is_empty() || p.model.dim() != 3 || !p.model.has_coque3d() {
        return Ok(());
    }
    let mesh = p.model.mesh();
    let dofs = p.model.dofs().dofs();
    let n = dofs.len().max(1) as f64;
    let mut c = [0.0; 3];
    for d in dofs {
        let x = mesh.coord(d.node);
        for k in 0..3 {
            c[k] += x[k] / n;
        }
    }
    // A connected free body has six rigid modes: the seventh eigenvalue
    // is its first elastic one.
    let first_elastic = lambdas.get(6).or(lambdas.last()).copied().unwrap_or(0.0);
    for axis in 0..3 {
        let mut w = [0.0; 3];
        w[axis] = 1.0;
        let u: Vec<f64> = dofs
            .iter()
            .map(|d| {
                let x = mesh.coord(d.node);
                let r = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
                let t = [
                    w[1] * r[2] - w[2] * r[1],
                    w[2] * r[0] - w[0] * r[2],
                    w[0] * r[1] - w[1] * r[0],
                ];
                match d.comp {
                    Comp::DX => t[0],
                    Comp::DY => t[1],
                    Comp::DZ => t[2],
                    Comp::DRX => w[0],
                    Comp::DRY => w[1],
                    Comp::DRZ => w[2],
                    Comp::PRES | Comp::GONF => 0.0,
                }
            })
            .collect();
        let ku = p.k.mul(&u);
        let mu = p.m.mul(&u);
        let a: f64 = u.iter().zip(&ku).map(|(x, y)| x * y).sum();
        let b: f64 = u.iter().zip(&mu).map(|(x, y)| x * y).sum();
        if b > 0.0 && a / b > 1e-8 * first_elastic {
            return Err(ex.unsupported(
                &format!(
                    "CALC_MODES on a free structure whose stiffness resists a rigid rotation (about axis {}: ω² = {:.3e}, the seventh eigenvalue ω² = {:.3e}): aster's drilling stiffness of curved COQUE_3D shells is not code_aster's, whose rigid modes are free; its elastic modes would be off",
                    ["X", "Y", "Z"][axis],
                    a / b,
                    first_elastic
                ),
                call.keywords.keyword("MATR_RIGI").map(|k| k.span).unwrap_or(call.span),
            ));
        }
    }
    Ok(())
}

/// Which modes EXTR_MODE's FILTRE_MODE keeps (op0168): `MASS_EFFE_UN`,
/// those with one of MASS_EFFE_UN_DX, _DY, _DZ ≥ `seuil`; `MASS_GENE`,
/// those whose MASS_GENE is ≥ `seuil` × the sum of the modes' MASS_GENE.
/// `None` for another criterion.
fn filtre_mode<'a>(
    crit: &str,
    seuil: f64,
    params: impl Iterator<Item = &'a BTreeMap<String, f64>> + Clone,
) -> Option<Vec<bool>> {
    let get = |p: &BTreeMap<String, f64>, k: &str| p.get(k).copied().unwrap_or(0.0);
    match crit {
        "MASS_EFFE_UN" => Some(
            params
                .map(|p| {
                    ["MASS_EFFE_UN_DX", "MASS_EFFE_UN_DY", "MASS_EFFE_UN_DZ"]
                        .iter()
                        .any(|k| get(p, k) >= seuil)
                })
                .collect(),
        ),
        "MASS_GENE" => {
            let total: f64 = params.clone().map(|p| get(p, "MASS_GENE")).sum();
            Some(
                params
                    .map(|p| get(p, "MASS_GENE") / total >= seuil)
                    .collect(),
            )
        }
        _ => None,
    }
}

/// The total mass along DX, DY, DZ: dᵀ M d (d = 1 on the component).
fn total_mass(p: &Problem) -> [f64; 3] {
    let dofs = p.model.dofs().dofs();
    let mut out = [0.0; 3];
    for (k, c) in [Comp::DX, Comp::DY, Comp::DZ].into_iter().enumerate() {
        let d: Vec<f64> = dofs
            .iter()
            .map(|x| if x.comp == c { 1.0 } else { 0.0 })
            .collect();
        let md = p.m.mul(&d);
        out[k] = d.iter().zip(&md).map(|(a, b)| a * b).sum();
    }
    out
}

/// What NORM_MODE reads (`crate::support`).
pub(crate) const NORM_MODE: Support = Support {
    values: &[Values::new(
        "NORME",
        &[
            "MASS_GENE",
            "RIGI_GENE",
            "TRAN_ROTA",
            "TRAN",
            "SANS_CMP=LAGR",
        ],
    )],
    ..Support::keywords(&["MODE", "NORME", "INFO", "TITRE", "MASSE", "RAIDE"])
};

/// `NORM_MODE(reuse=modes, MODE=modes, NORME=…)`: the modes rescaled (the
/// parameters MASS_GENE, RIGI_GENE, FACT_PARTICI_*, MASS_EFFE_* follow).
/// Only a result of CALC_MODES of this run (its matrices are needed).
pub fn norm_mode(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let cmd = "NORM_MODE";
    let r = ex.required(cmd, kw, "MODE")?;
    let result = ex.result(r)?;
    let Some(info) = result.modal.clone() else {
        return Err(ex.kw_error(cmd, kw, "MODE", "not a result of CALC_MODES"));
    };
    let Some(p) = info.problem.clone() else {
        return Err(ex.kw_error(
            cmd,
            kw,
            "MODE",
            "the modes' matrices are not kept (a result not computed by CALC_MODES in this run)",
        ));
    };
    let name = kw.str("NORME").unwrap_or("SANS_CMP=LAGR");
    let norm = parse_norm(name).ok_or_else(|| {
        ex.unsupported(
            &format!("NORM_MODE/NORME='{name}'"),
            kw.keyword("NORME").map(|k| k.span).unwrap_or(call.span),
        )
    })?;
    let total_mass = total_mass(&p);
    let mut out = (*result).clone();
    let mut new_info = (*info).clone();
    for step in out.steps.iter_mut() {
        let Some(Field::Nodal(depl)) = step.fields.get("DEPL") else {
            continue;
        };
        let mut u = fembridge::displacement_from(&p.model, depl);
        if !scale(&p, &mut u, norm) {
            return Err(ExecError::new(format!(
                "{cmd}: mode {} has a zero norm",
                step.nume_ordre
            )));
        }
        let old = info
            .params
            .get(&step.nume_ordre)
            .cloned()
            .unwrap_or_default();
        let lambda = omega2(old.get("FREQ").copied().unwrap_or(0.0));
        let nume_mode = old.get("NUME_MODE").copied().unwrap_or(0.0) as usize;
        let params = mode_params(&p, &u, lambda, nume_mode, &total_mass);
        new_info.params.insert(step.nume_ordre, params);
        if let Some(why) = undetermined(&info.lambdas, lambda, &u, norm) {
            if !why.contains("repeated") && !info.undetermined.contains_key(&step.nume_ordre) {
                new_info.sign_only.insert(step.nume_ordre);
            }
            new_info.undetermined.entry(step.nume_ordre).or_insert(why);
        }
        step.fields.insert(
            "DEPL".into(),
            Field::Nodal(fembridge::nodal_from_dofs(&p.model, &u)),
        );
    }
    out.modal = Some(Rc::new(new_info));
    store_result(ex, call, Concept::Result(Rc::new(out)))
}

/// `CALC_CHAMP(RESULTAT=modes, ENERGIE=('EPOT_ELEM', 'ECIN_ELEM'))` on the
/// modes of a CALC_CHAMP of this run: per cell, `EPOT_ELEM` = ½ uₑᵀ Kₑ uₑ
/// (component `TOTALE`) and `ECIN_ELEM` = ½ ω² uₑᵀ Mₑ uₑ with the
/// components of code_aster's elements (aster-fem
/// `mass::modal_kinetic_energy_by_cell`), ω² the mode's `OMEGA2`. Any
/// other option on modes is refused.
pub(crate) fn modal_energies(
    ex: &Executor,
    call: &CommandCall,
    result: &EvolResult,
    options: &[String],
    steps: &[u32],
    only: Option<&std::collections::BTreeSet<aster_mesh::CellId>>,
) -> Result<EvolResult, ExecError> {
    let cmd = "CALC_CHAMP";
    let span = |key: &str| {
        call.keywords
            .keyword(key)
            .map(|k| k.span)
            .unwrap_or(call.span)
    };
    for opt in options {
        if !matches!(opt.as_str(), "EPOT_ELEM" | "ECIN_ELEM") {
            // The keyword that asks for it.
            let family = [
                "FORCE",
                "CONTRAINTE",
                "CRITERES",
                "DEFORMATION",
                "ENERGIE",
                "VARI_INTERNE",
            ]
            .into_iter()
            .find(|k| {
                call.keywords
                    .simple(k)
                    .iter()
                    .any(|v| v.as_str() == Some(opt.as_str()))
            })
            .unwrap_or("RESULTAT");
            return Err(ex.unsupported(
                &format!("CALC_CHAMP option {opt} on modes (of a MODE_MECA: EPOT_ELEM and ECIN_ELEM only)"),
                span(family),
            ));
        }
    }
    let Some(info) = result.modal.clone() else {
        return Err(ExecError::new(format!("{cmd}: not a result of CALC_MODES")));
    };
    let Some(p) = info.problem.clone() else {
        return Err(ex.unsupported(
            "CALC_CHAMP/ENERGIE on modes whose matrices are not kept (not computed by CALC_MODES in this run)",
            span("RESULTAT"),
        ));
    };
    let err = |e: aster_fem::FemError| ExecError::new(format!("{cmd}: {e}"));
    let keep = |c: &aster_fem::post::CellValues| only.is_none_or(|s| s.contains(&c.cell));
    let mut out = result.clone();
    for step in out
        .steps
        .iter_mut()
        .filter(|s| steps.contains(&s.nume_ordre))
    {
        let Some(Field::Nodal(depl)) = step.fields.get("DEPL") else {
            return Err(ExecError::new(format!(
                "{cmd}: mode {} has no DEPL",
                step.nume_ordre
            )));
        };
        let u = fembridge::displacement_from(&p.model, depl);
        let omega2 = info
            .params
            .get(&step.nume_ordre)
            .and_then(|m| m.get("OMEGA2"))
            .copied()
            .ok_or_else(|| {
                ExecError::new(format!("{cmd}: mode {} has no OMEGA2", step.nume_ordre))
            })?;
        for opt in options {
            let cells: Vec<aster_fem::post::CellValues> = if opt == "EPOT_ELEM" {
                aster_fem::energy::potential_energy_by_cell(&p.model, &u)
                    .map_err(err)?
                    .into_iter()
                    .map(|(cell, e)| aster_fem::post::CellValues {
                        cell,
                        names: vec!["TOTALE"],
                        points: vec![vec![e]],
                    })
                    .collect()
            } else {
                aster_fem::mass::modal_kinetic_energy_by_cell(&p.model, &p.mass_data, &u, omega2)
                    .map_err(err)?
            };
            let cells: Vec<_> = cells.into_iter().filter(|c| keep(c)).collect();
            step.fields.insert(
                opt.clone(),
                Field::Elem(fembridge::elem_field(
                    crate::field::ElemLocation::Cell,
                    &cells,
                )),
            );
        }
    }
    Ok(out)
}
