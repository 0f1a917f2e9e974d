//! The bridge to aster-fem: builds its model, loads and solver from a
//! [`SolveSetup`], runs it, and turns its results into stored fields.

use crate::concept::*;
use crate::executor::Executor;
use crate::field::{ElemField, ElemLocation, Field, NodalField};
use crate::function::Function;
use crate::solve::{BehaviourOcc, LoadRef, Relation, SolveSetup};
use crate::unil::LiaisonUnil;
use aster_eval::{CommandCall, ExecError};
use aster_fem::{
    post, CellValues, Comp, Convergence, Dof, Elastic, Element, ElementKind, Frame, Hypothesis,
    InitialState, Load, Loads, Model, Multiplier, NewtonOptions, NodalValues, NonLinearResult,
    StaticNonLinear, UnilateralSource,
};
use aster_mesh::{Mesh, NodeId};
use std::collections::BTreeMap;
use std::rc::Rc;
use std::sync::Arc;

/// What a result was computed with, kept for CALC_CHAMP.
#[derive(Debug)]
pub struct FemRun {
    pub model: Model,
    pub loads: Loads,
    /// The follower pressures (`TYPE_CHARGE='SUIV'`): external forces of
    /// the deformed configuration, which `REAC_NODA` subtracts as
    /// code_aster's `ccfnrn` (`vecgme` at the step's displacement).
    pub follower: aster_fem::follower::FollowerPressures,
    pub raw: NonLinearResult,
    /// Some cells were plastic or in finite strains: their stresses are not
    /// D B u, so nodal forces come from the stored SIEF_ELGA (on the
    /// deformed geometry for the finite-strain cells).
    pub plastic: bool,
    pub behaviours: aster_fem::Behaviours,
    /// The densities and discrete masses of the model (`None`: they could
    /// not be gathered), for the kinetic energy (`POST_ELEM/ENER_CIN`).
    pub mass: Option<aster_fem::MassData>,
    /// The element characteristics (the shells' frames of `EFGE_ELGA`).
    pub cara: Option<Rc<CaraElem>>,
    /// The joint cells (`PLAN_JOINT`) with their converged states: their
    /// forces are not in the model's elements (`FORC_NODA`, `REAC_NODA`
    /// add them).
    pub joints: Option<aster_fem::joint::JointCells>,
    /// The load items of each `EXCIT` occurrence given a `FONC_MULT`, with
    /// that multiplier (their own multipliers are it times the charge's
    /// functions): CALC_ERREUR takes the charges without it, as
    /// code_aster's estimator reads the load maps.
    pub excit: Vec<(std::ops::Range<usize>, Multiplier)>,
}

impl FemRun {
    /// The joint cells' nodal forces (`nmfifi`) at the converged step of
    /// time `t`, added to `forces` (indexed like the model's DOFs); none
    /// at a time without a converged joint state (the initial state).
    fn add_joint_forces(&self, t: f64, forces: &mut [f64]) -> Result<(), ExecError> {
        let Some(j) = &self.joints else {
            return Ok(());
        };
        let Some((_, points)) = j
            .history()
            .iter()
            .rev()
            .find(|(ti, _)| (ti - t).abs() <= 1e-12 * t.abs().max(1.0))
        else {
            return Ok(());
        };
        for (c, p) in j.cells().iter().zip(points) {
            let f = aster_fem::joint::forces(&c.geom, &p.traction);
            for (a, n) in c.nodes.iter().enumerate() {
                for (k, comp) in [Comp::DX, Comp::DY].into_iter().enumerate() {
                    let i = self
                        .model
                        .dofs()
                        .index(aster_fem::Dof::new(*n, comp))
                        .ok_or_else(|| ExecError::new("joint node without DOF"))?;
                    forces[i] += f[2 * a + k];
                }
            }
        }
        Ok(())
    }
}

impl FemRun {
    /// The computed state at a NUME_ORDRE, or an error naming `cmd`.
    pub fn state(&self, cmd: &str, nume_ordre: u32) -> Result<&aster_fem::Step, ExecError> {
        self.raw.by_order(nume_ordre as usize).ok_or_else(|| {
            ExecError::new(format!(
                "{cmd}: no computed state at NUME_ORDRE {nume_ordre}"
            ))
        })
    }
}

fn fem_err(cmd: &str, e: aster_fem::FemError) -> ExecError {
    with_fem_id(ExecError::new(format!("{cmd}: {e}")), &e)
}

/// The error with code_aster's message id for `e`'s cause, if any
/// (`crate::raised`).
fn with_fem_id(err: ExecError, e: &aster_fem::FemError) -> ExecError {
    match crate::raised::fem_error_id(e) {
        Some(id) => err.with_id(id),
        None => err,
    }
}

pub(crate) fn hypothesis(m: Modelisation) -> Option<Hypothesis> {
    match m {
        Modelisation::PlaneStrain => Some(Hypothesis::PlaneStrain),
        Modelisation::PlaneStress => Some(Hypothesis::PlaneStress),
        Modelisation::Axisymmetric => Some(Hypothesis::Axisymmetric),
        Modelisation::Solid3D => Some(Hypothesis::Solid3D),
        Modelisation::Discrete2D
        | Modelisation::Discrete3D
        | Modelisation::DiscreteRot3D
        | Modelisation::BeamEuler
        | Modelisation::BeamTimoshenko
        | Modelisation::Bar
        | Modelisation::Plate(_)
        | Modelisation::Coque3d
        | Modelisation::GridMembrane
        | Modelisation::GridExcentre
        | Modelisation::PlaneJoint => None,
    }
}

/// The fem model of an AFFE_MODELE + AFFE_MATERIAU + AFFE_CARA_ELEM.
pub fn build_model(
    mesh: &Arc<Mesh>,
    model: &ModelDef,
    materials: &MaterialField,
    cara: Option<&CaraElem>,
) -> Result<Model, ExecError> {
    let mut springs: BTreeMap<aster_mesh::CellId, &DiscreteStiffness> = BTreeMap::new();
    if let Some(c) = cara {
        for d in &c.discrete {
            for &cell in &d.cells {
                springs.insert(cell, d);
            }
        }
    }
    let mut shells: BTreeMap<aster_mesh::CellId, aster_fem::ShellSection> = BTreeMap::new();
    let mut coque3d: BTreeMap<aster_mesh::CellId, aster_fem::coque3d::Coque3dSection> =
        BTreeMap::new();
    if let Some(c) = cara {
        for s in &c.shells {
            for &cell in &s.cells {
                shells.insert(cell, s.section.clone());
                coque3d.insert(cell, s.coque3d_section());
            }
        }
    }
    let mut beams: BTreeMap<aster_mesh::CellId, aster_fem::BeamSection> = BTreeMap::new();
    if let Some(c) = cara {
        for b in &c.beams {
            for &cell in &b.cells {
                beams.insert(cell, b.section);
            }
        }
    }
    let mut bars: BTreeMap<aster_mesh::CellId, f64> = BTreeMap::new();
    if let Some(c) = cara {
        for b in &c.bars {
            for &cell in &b.cells {
                bars.insert(cell, b.area);
            }
        }
    }
    let mut grids: BTreeMap<aster_mesh::CellId, &crate::commands::cara_grille::GridCara> =
        BTreeMap::new();
    if let Some(c) = cara {
        for g in &c.grids {
            grids.insert(g.cell, g);
        }
    }
    // AFFE_CARA_ELEM/MASSIF: the material frames (a later occurrence
    // replaces an earlier one; the global frame elsewhere).
    let mut frames: BTreeMap<aster_mesh::CellId, [f64; 3]> = BTreeMap::new();
    if let Some(c) = cara {
        for f in &c.massif {
            for &cell in &f.cells {
                frames.insert(cell, f.angles);
            }
        }
    }
    let material_of = |cell: aster_mesh::CellId| -> Result<Elastic, ExecError> {
        let mat = materials.cells.get(&cell).ok_or_else(|| {
            ExecError::new(format!(
                "cell {} of the model has no material: assign one with AFFE_MATERIAU",
                crate::select::cell_name(mesh, cell)
            ))
        })?;
        if !mat.elastic {
            return Err(ExecError::new(format!(
                "the material of cell {} has no ELAS (a thermal material, THER alone): a mechanical model needs E and NU",
                crate::select::cell_name(mesh, cell)
            )));
        }
        if let Some(why) = &mat.unresolved {
            return Err(ExecError::new(why.clone()));
        }
        if mat.composite.is_some() {
            return Err(ExecError::new(format!(
                "the material of cell {} is a DEFI_COMPOSITE: it applies to the plate cells (DKT, DST, Q4G) only",
                crate::select::cell_name(mesh, cell)
            )));
        }
        if let Some(o) = mat.orthotropic {
            let angles = frames.get(&cell).copied().unwrap_or([0.0; 3]);
            return Elastic::orthotropic(aster_fem::orthotropic::Orthotropic { angles, ..o })
                .map_err(|e| {
                    ExecError::new(format!(
                        "DEFI_MATERIAU: the material of cell {}: {e}",
                        crate::select::cell_name(mesh, cell)
                    ))
                });
        }
        Elastic::new(mat.young, mat.poisson).map_err(|e| fem_err("DEFI_MATERIAU", e))
    };
    let mut elements = Vec::with_capacity(model.cells.len());
    for (&cell, &m) in &model.cells {
        let ty = mesh.cell(cell).ty;
        if let Modelisation::Plate(theory) = m {
            let section = shells.get(&cell).cloned().ok_or_else(|| {
                ExecError::new(format!(
                    "cell {} carries a {} shell element but no section: give AFFE_CARA_ELEM/COQUE with EPAIS (and CARA_ELEM to the solver)",
                    crate::select::cell_name(mesh, cell),
                    theory.name()
                ))
            })?;
            let (material, section) =
                match crate::commands::composite::layered(mesh, cell, materials, cara, &section)? {
                    Some(layered) => layered,
                    None => (material_of(cell)?, section),
                };
            elements.push(Element {
                cell,
                kind: ElementKind::Shell {
                    material,
                    section,
                    theory,
                },
            });
            continue;
        }
        if m == Modelisation::Coque3d {
            let section = coque3d.get(&cell).copied().ok_or_else(|| {
                ExecError::new(format!(
                    "cell {} carries a COQUE_3D shell element but no section: give AFFE_CARA_ELEM/COQUE with EPAIS (and CARA_ELEM to the solver)",
                    crate::select::cell_name(mesh, cell)
                ))
            })?;
            elements.push(Element {
                cell,
                kind: ElementKind::Coque3d {
                    material: material_of(cell)?,
                    section,
                },
            });
            continue;
        }
        if m.is_beam() {
            let name = if m == Modelisation::BeamEuler {
                "POU_D_E"
            } else {
                "POU_D_T"
            };
            let section = beams.get(&cell).copied().ok_or_else(|| {
                ExecError::new(format!(
                    "cell {} carries a {name} beam element but no section: give AFFE_CARA_ELEM/POUTRE (and CARA_ELEM to the solver)",
                    crate::select::cell_name(mesh, cell)
                ))
            })?;
            // POU_D_E: no shear strain (code_aster's `porigi`/`pomass` set
            // AY = AZ = 0); POU_D_T: the section's AY, AZ.
            let section = if m == Modelisation::BeamEuler {
                section.euler()
            } else if section.shear.is_none() {
                return Err(ExecError::new(format!(
                    "cell {} carries a POU_D_T beam element but its SECTION='GENERALE' gives no shear coefficients: give AFFE_CARA_ELEM/POUTRE/CARA 'AY' and 'AZ' (code_aster has no default for them)",
                    crate::select::cell_name(mesh, cell)
                )));
            } else {
                section
            };
            elements.push(Element {
                cell,
                kind: ElementKind::Beam {
                    material: material_of(cell)?,
                    section,
                },
            });
            continue;
        }
        if m == Modelisation::Bar {
            let area = bars.get(&cell).copied().ok_or_else(|| {
                ExecError::new(format!(
                    "cell {} carries a BARRE element but no section: give AFFE_CARA_ELEM/BARRE (and CARA_ELEM to the solver)",
                    crate::select::cell_name(mesh, cell)
                ))
            })?;
            elements.push(Element {
                cell,
                kind: ElementKind::Bar {
                    material: material_of(cell)?,
                    area,
                },
            });
            continue;
        }
        if matches!(m, Modelisation::GridMembrane | Modelisation::GridExcentre) {
            let g = grids.get(&cell).ok_or_else(|| {
                ExecError::new(format!(
                    "cell {} carries a grid element (GRILLE_*) but no section: give AFFE_CARA_ELEM/GRILLE (and CARA_ELEM to the solver)",
                    crate::select::cell_name(mesh, cell)
                ))
            })?;
            elements.push(Element {
                cell,
                kind: ElementKind::Grid {
                    material: material_of(cell)?,
                    section: g.section(m == Modelisation::GridExcentre),
                },
            });
            continue;
        }
        if m == Modelisation::PlaneJoint {
            // No stiffness of its own in K: its forces and tangent come
            // from the joint force source (`joint_source`); its nodes get
            // their DOFs.
            elements.push(Element {
                cell,
                kind: ElementKind::Boundary,
            });
            continue;
        }
        let rotational = m == Modelisation::DiscreteRot3D;
        if let Some(d) = springs.get(&cell) {
            if rotational != (d.values.len() == 6) {
                return Err(ExecError::new(format!(
                    "cell {} is {} but AFFE_CARA_ELEM/DISCRET gives it {} ({} values): DIS_TR takes K_TR_D_N/K_TR_D_L, DIS_T K_T_D_N/K_T_D_L",
                    crate::select::cell_name(mesh, cell),
                    if rotational { "DIS_TR" } else { "DIS_T" },
                    d.cara,
                    d.values.len()
                )));
            }
        }
        let kind = match hypothesis(m) {
            Some(h) if ty.dim() as usize == h.dim() => ElementKind::Continuum {
                hypothesis: h,
                material: material_of(cell)?,
            },
            Some(_) => ElementKind::Boundary,
            None => match springs.get(&cell) {
                Some(d) => ElementKind::Spring {
                    stiffness: d.values.clone(),
                    frame: if d.local { Frame::Local } else { Frame::Global },
                },
                // A discrete cell with only a mass (DYNA_NON_LINE).
                None if cara.is_some_and(|c| c.masses.iter().any(|m| m.cells.contains(&cell))) => {
                    ElementKind::Spring {
                        stiffness: vec![0.0; if rotational { 6 } else { m.dim() }],
                        frame: Frame::Global,
                    }
                }
                None => {
                    return Err(ExecError::new(format!(
                        "cell {} carries a discrete element but AFFE_CARA_ELEM gives it no stiffness (DISCRET/DISCRET_2D K_T_D_L or K_T_D_N)",
                        crate::select::cell_name(mesh, cell)
                    )))
                }
            },
        };
        elements.push(Element { cell, kind });
    }
    Model::new(mesh.clone(), elements)
        .and_then(|m| m.with_reduced_integration(model.reduced.iter().copied()))
        .and_then(|m| m.with_mixed(model.mixed.iter().copied()))
        .and_then(|m| m.with_edges(model.edges.iter().copied()))
        .map_err(|e| fem_err("AFFE_MODELE", e))
}

/// The fem behaviours of the COMPORTEMENT occurrences: each plastic cell
/// gets the law its material defines (ECRO_LINE for VMIS_ISOT_LINE,
/// TRACTION for VMIS_ISOT_TRAC). Cells outside the model are skipped.
pub fn build_behaviours(
    mesh: &Mesh,
    model: &Model,
    occurrences: &[BehaviourOcc],
    materials: &MaterialField,
    thermo: Option<&crate::thermo_mat::Prepared>,
) -> Result<aster_fem::Behaviours, ExecError> {
    let mut out = aster_fem::Behaviours::elastic();
    if let Some(t) = thermo {
        if let Some(h) = &t.history {
            out.set_temperature(h.clone());
        }
    }
    grid_behaviours(mesh, model, occurrences, materials, &mut out)?;
    let continuum: std::collections::BTreeSet<aster_mesh::CellId> = model
        .elements()
        .iter()
        .filter(|e| matches!(e.kind, ElementKind::Continuum { .. }))
        .map(|e| e.cell)
        .collect();
    let plane_stress: std::collections::BTreeSet<aster_mesh::CellId> = model
        .elements()
        .iter()
        .filter(|e| {
            matches!(
                e.kind,
                ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStress,
                    ..
                }
            )
        })
        .map(|e| e.cell)
        .collect();
    // The occurrence each cell ends with: a later occurrence replaces an
    // earlier one, whose law (and material requirement, e.g. ECRO_COOK
    // for VMIS_JOHN_COOK on TOUT='OUI' before a GROUP_MA with another
    // relation) then does not apply to that cell, as in code_aster.
    let mut last: std::collections::HashMap<aster_mesh::CellId, usize> =
        std::collections::HashMap::new();
    for (k, occ) in occurrences.iter().enumerate() {
        match &occ.cells {
            None => last.extend(continuum.iter().map(|&c| (c, k))),
            Some(c) => last.extend(c.iter().filter(|c| continuum.contains(c)).map(|&c| (c, k))),
        }
    }
    // One law per (material, relation), shared by its cells.
    let mut laws: Vec<(*const Material, Relation, Arc<aster_fem::VonMises>)> = Vec::new();
    for (k, occ) in occurrences.iter().enumerate() {
        // LEMAITRE: one law per material for this occurrence (its local
        // integration settings are the occurrence's).
        let mut viscous: Vec<(*const Material, Arc<aster_fem::Lemaitre>)> = Vec::new();
        let cells: Vec<aster_mesh::CellId> = match &occ.cells {
            None => continuum.iter().copied().collect(),
            Some(c) => c
                .iter()
                .copied()
                .filter(|c| continuum.contains(c))
                .collect(),
        };
        for cell in cells.into_iter().filter(|c| last.get(c) == Some(&k)) {
            if let Some(m) = thermo.and_then(|t| t.cells.get(&cell)) {
                out.assign_thermo(cell, m.clone());
                continue;
            }
            let orthotropic = materials
                .cells
                .get(&cell)
                .is_some_and(|m| m.orthotropic.is_some());
            if orthotropic
                && (occ.relation != Relation::Elas
                    || occ.kinematics != aster_fem::Kinematics::Small)
            {
                return Err(ExecError::new(format!(
                    "not supported yet: COMPORTEMENT RELATION='{}' DEFORMATION='{}' on cell {}, whose material is orthotropic (ELAS_ORTH): it is elastic in small strains only here (RELATION='ELAS', DEFORMATION='PETIT'); the other laws and kinematics are isotropic",
                    occ.relation.keyword(),
                    occ.kinematics.aster_name(),
                    crate::select::cell_name(mesh, cell)
                )));
            }
            if occ.relation == Relation::Elas {
                out.assign_with(cell, None, occ.kinematics);
                continue;
            }
            if matches!(occ.relation, Relation::CzmLinReg | Relation::CzmTuron) {
                if occ.cells.is_none() {
                    continue; // TOUT='OUI': the joint cells take it
                }
                return Err(ExecError::new(format!(
                    "STAT_NON_LINE/COMPORTEMENT: RELATION='{}' is a law of the joint elements (MODELISATION='PLAN_JOINT'); cell {} carries a continuum element",
                    occ.relation.keyword(),
                    crate::select::cell_name(mesh, cell)
                )));
            }
            let Some(mat) = materials.cells.get(&cell) else {
                continue; // reported by build_model
            };
            if occ.relation == Relation::Lemaitre {
                let law = match viscous.iter().find(|l| l.0 == Rc::as_ptr(mat)) {
                    Some(l) => l.1.clone(),
                    None => {
                        let c = mat.lemaitre.ok_or_else(|| {
                            ExecError::new(format!(
                                "STAT_NON_LINE/COMPORTEMENT: RELATION='LEMAITRE' on cell {} needs LEMAITRE=_F(N, UN_SUR_K) in its material's DEFI_MATERIAU",
                                crate::select::cell_name(mesh, cell)
                            ))
                        })?;
                        let law = aster_fem::Lemaitre::new(
                            c.n,
                            c.un_sur_k,
                            c.un_sur_m,
                            occ.local.theta,
                            occ.local.resi_inte,
                            occ.local.iter_inte_maxi,
                        )
                        .map_err(|e| fem_err("STAT_NON_LINE/COMPORTEMENT", e))?;
                        let law = Arc::new(law);
                        viscous.push((Rc::as_ptr(mat), law.clone()));
                        law
                    }
                };
                out.assign_viscous(cell, law);
                continue;
            }
            if occ.relation == Relation::VmisJohnCook {
                // nmtevp's thermal softening reads TEMP (AFFE_VARC), not
                // passed to the law here; its catalogue has no C_PLAN.
                if materials.temperature.is_some() {
                    return Err(ExecError::new(
                        "not supported yet: COMPORTEMENT/RELATION='VMIS_JOHN_COOK' with a temperature (AFFE_VARC): the thermal softening (1 − θ^M_PUIS) is not passed to the law",
                    ));
                }
                if plane_stress.contains(&cell) {
                    return Err(ExecError::new(format!(
                        "COMPORTEMENT/RELATION='VMIS_JOHN_COOK' on C_PLAN cell {}: code_aster's law has no plane-stress version (3D, AXIS, D_PLAN)",
                        crate::select::cell_name(mesh, cell)
                    )));
                }
            }
            let hencky = matches!(
                occ.relation,
                Relation::ElasVmisLine | Relation::ElasVmisTrac
            );
            if hencky && plane_stress.contains(&cell) {
                return Err(ExecError::new(format!(
                    "not supported yet: COMPORTEMENT/RELATION='{}' on C_PLAN cell {}: code_aster's plane-stress Hencky law (its own search of εzz, nmcri1) is not reproduced (3D, AXIS, D_PLAN are)",
                    occ.relation.keyword(),
                    crate::select::cell_name(mesh, cell)
                )));
            }
            let key = (Rc::as_ptr(mat), occ.relation);
            let law = match laws.iter().find(|l| (l.0, l.1) == key) {
                Some(l) => l.2.clone(),
                None => {
                    let law = Arc::new(plastic_law(mesh, cell, mat, occ.relation, &occ.local)?);
                    laws.push((key.0, key.1, law.clone()));
                    law
                }
            };
            if hencky {
                out.assign_hencky(cell, law);
            } else {
                out.assign_with(cell, Some(law), occ.kinematics);
            }
        }
    }
    // Temperature-dependent cells no occurrence names (ELAS by default).
    if let Some(t) = thermo {
        for (&cell, m) in &t.cells {
            if !last.contains_key(&cell) {
                out.assign_thermo(cell, m.clone());
            }
        }
    }
    Ok(out)
}

/// MECA_STATIQUE, MACRO_ELAS_MULT: a grid that expands (ELAS/ALPHA) under
/// a temperature other than the reference is refused — code_aster's
/// thermal strain of grids is reproduced in STAT_NON_LINE only (the
/// grids' behaviours), not as a load.
fn refuse_heated_grids(
    cmd: &str,
    mesh: &Mesh,
    model: &Model,
    materials: &MaterialField,
) -> Result<(), ExecError> {
    let Some(t) = materials.temperature.as_ref() else {
        return Ok(());
    };
    for el in model.elements() {
        if !matches!(el.kind, ElementKind::Grid { .. }) || !t.cells.contains(&el.cell) {
            continue;
        }
        let expands = materials
            .cells
            .get(&el.cell)
            .is_some_and(|m| m.alpha.is_some_and(|a| a != 0.) || m.alpha_fo.is_some());
        let heated = t.fields.iter().any(|(_, v)| {
            mesh.cell(el.cell)
                .nodes
                .iter()
                .any(|n| v[n.0 as usize] != t.tref)
        }) || t.shell.is_some();
        if expands && heated {
            return Err(ExecError::new(format!(
                "not supported yet: {cmd} with AFFE_MATERIAU/AFFE_VARC NOM_VARC='TEMP' on grid cell {}: the grids' thermal strain is reproduced in STAT_NON_LINE only ({})",
                mesh.cell_name(el.cell),
                t.at
            )));
        }
    }
    Ok(())
}

/// The reinforcement grids' behaviours (`te0431` → `nmco1d`): the uniaxial
/// law of each grid cell's last COMPORTEMENT occurrence — GRILLE_ISOT_LINE,
/// GRILLE_CINE_LINE from ELAS's E and ECRO_LINE — and, under a temperature
/// (AFFE_VARC) with ELAS/ALPHA, the thermal strain along the bars (an
/// ELAS grid then too); ELAS grids without one stay linear (K u). A GRILLE
/// relation on a cell that is not a grid is refused (code_aster's
/// catalogue gives these laws to GRILLE_MEMBRANE, GRILLE_EXCENTRE, 1D).
fn grid_behaviours(
    mesh: &Mesh,
    model: &Model,
    occurrences: &[BehaviourOcc],
    materials: &MaterialField,
    out: &mut aster_fem::Behaviours,
) -> Result<(), ExecError> {
    let grid_law = |r: Relation| matches!(r, Relation::GrilleIsotLine | Relation::GrilleCineLine);
    let mut last: std::collections::BTreeMap<aster_mesh::CellId, Relation> =
        std::collections::BTreeMap::new();
    let kinds: std::collections::HashMap<aster_mesh::CellId, &ElementKind> =
        model.elements().iter().map(|e| (e.cell, &e.kind)).collect();
    for occ in occurrences {
        let named: Vec<aster_mesh::CellId> = match &occ.cells {
            Some(c) => c.clone(),
            None => model.elements().iter().map(|e| e.cell).collect(),
        };
        for cell in named {
            let Some(kind) = kinds.get(&cell) else {
                continue;
            };
            match kind {
                ElementKind::Grid { .. } => {
                    last.insert(cell, occ.relation);
                }
                ElementKind::Boundary => {}
                _ if grid_law(occ.relation) => {
                    return Err(ExecError::new(format!(
                        "STAT_NON_LINE/COMPORTEMENT: RELATION='{}' is a law of the reinforcement grids (GRILLE_MEMBRANE, GRILLE_EXCENTRE); cell {} carries another element",
                        occ.relation.keyword(),
                        crate::select::cell_name(mesh, cell)
                    )));
                }
                _ => {}
            }
        }
    }
    if let Some(t) = materials.temperature.as_ref().filter(|t| t.shell.is_some()) {
        if let Some(el) = model.elements().iter().find(|e| {
            matches!(e.kind, ElementKind::Grid { .. })
                && t.cells.contains(&e.cell)
                && materials
                    .cells
                    .get(&e.cell)
                    .is_some_and(|m| m.alpha.is_some_and(|a| a != 0.) || m.alpha_fo.is_some())
        }) {
            return Err(ExecError::new(format!(
                "not supported yet: a temperature through the thickness of shells (CREA_RESU/PREP_VARC) on grid cell {}, which expands (ELAS/ALPHA) ({})",
                crate::select::cell_name(mesh, el.cell),
                t.at
            )));
        }
    }
    let temperature = materials
        .temperature
        .as_ref()
        .filter(|t| !t.fields.is_empty() && t.shell.is_none());
    let mut heated_any = false;
    for el in model.elements() {
        let ElementKind::Grid { material, .. } = &el.kind else {
            continue;
        };
        let cell = el.cell;
        let relation = last.get(&cell).copied().unwrap_or(Relation::Elas);
        let Some(mat) = materials.cells.get(&cell) else {
            continue; // reported by build_model
        };
        let name = crate::select::cell_name(mesh, cell);
        let heated = temperature.is_some_and(|t| {
            t.cells.contains(&cell)
                && t.fields.iter().any(|(_, v)| {
                    mesh.cell(cell)
                        .nodes
                        .iter()
                        .any(|n| v[n.0 as usize] != t.tref)
                })
        });
        if heated && mat.alpha_fo.is_some() {
            return Err(ExecError::new(format!(
                "not supported yet: ALPHA a function of the temperature (ELAS_FO) on grid cell {name} under AFFE_VARC: the grids' thermal strain is reproduced with a constant ALPHA"
            )));
        }
        let alpha = if heated {
            mat.alpha.unwrap_or(0.0)
        } else {
            0.0
        };
        let hardening = match relation {
            Relation::GrilleIsotLine => aster_fem::UniaxialHardening::Isotropic,
            Relation::GrilleCineLine => aster_fem::UniaxialHardening::Kinematic,
            Relation::Elas if alpha != 0.0 => aster_fem::UniaxialHardening::Elastic,
            _ => continue, // ELAS: K u; the others are refused by check_solve
        };
        let (et, sy) = match hardening {
            aster_fem::UniaxialHardening::Elastic => (0.0, 0.0),
            _ => {
                if mat.ecro_line.is_none() && mat.ecro_line_fo.is_some() {
                    return Err(ExecError::new(format!(
                        "not supported yet: DEFI_MATERIAU/ECRO_LINE_FO on grid cell {name} (RELATION='{}'): the grids' laws are reproduced with constant ECRO_LINE",
                        relation.keyword()
                    )));
                }
                let e = mat.ecro_line.ok_or_else(|| {
                    ExecError::new(format!(
                        "STAT_NON_LINE/COMPORTEMENT: RELATION='{}' on grid cell {name} needs ECRO_LINE=_F(D_SIGM_EPSI, SY) in its material's DEFI_MATERIAU",
                        relation.keyword()
                    ))
                })?;
                (e.d_sigm_epsi, e.sy)
            }
        };
        let law = aster_fem::Uniaxial {
            hardening,
            young: material.e,
            et,
            sy,
            alpha,
        };
        law.check().map_err(|m| {
            ExecError::new(format!(
                "STAT_NON_LINE/COMPORTEMENT: grid cell {name} (RELATION='{}'): {m}",
                relation.keyword()
            ))
        })?;
        heated_any |= alpha != 0.0;
        out.assign_uniaxial(cell, Arc::new(law));
    }
    if heated_any && !out.has_temperature() {
        if let Some(t) = temperature {
            out.set_temperature(Arc::new(aster_fem::NodalHistory {
                knots: t
                    .fields
                    .iter()
                    .map(|(t, v)| (*t, Arc::new(v.to_vec())))
                    .collect(),
                constant_before: t.constant_before,
                constant_after: t.constant_after,
            }));
        }
    }
    Ok(())
}

fn plastic_law(
    mesh: &Mesh,
    cell: aster_mesh::CellId,
    mat: &Material,
    relation: Relation,
    local: &crate::solve::LocalIntegration,
) -> Result<aster_fem::VonMises, ExecError> {
    let resi_inte = local.resi_inte;
    let missing = |what: &str| {
        ExecError::new(format!(
            "STAT_NON_LINE/COMPORTEMENT: RELATION='{}' on cell {} needs {what} in its material's DEFI_MATERIAU",
            relation.keyword(),
            crate::select::cell_name(mesh, cell)
        ))
    };
    let law = match relation {
        Relation::VmisIsotLine | Relation::ElasVmisLine => {
            if let (None, Some(fo)) = (&mat.ecro_line, &mat.ecro_line_fo) {
                return Err(ExecError::new(format!(
                    "not supported yet: DEFI_MATERIAU/ECRO_LINE_FO: `{}` or `{}` is a function of TEMP and cell {} has no temperature in STAT_NON_LINE (AFFE_MATERIAU/AFFE_VARC)",
                    fo.d_sigm_epsi.name,
                    fo.sy.name,
                    crate::select::cell_name(mesh, cell)
                )));
            }
            let e = mat
                .ecro_line
                .ok_or_else(|| missing("ECRO_LINE=_F(D_SIGM_EPSI, SY)"))?;
            aster_fem::VonMises::linear(mat.young, e.sy, e.d_sigm_epsi)
        }
        Relation::VmisIsotTrac | Relation::ElasVmisTrac => {
            if mat.traction_nappe.is_some() {
                return Err(ExecError::new(format!(
                    "not supported yet: DEFI_MATERIAU/TRACTION/SIGM is a nappe of TEMP and cell {} has no temperature in STAT_NON_LINE (AFFE_MATERIAU/AFFE_VARC): code_aster reads the curve at the point's temperature",
                    crate::select::cell_name(mesh, cell)
                )));
            }
            let t = mat
                .traction
                .as_ref()
                .ok_or_else(|| missing("TRACTION=_F(SIGM=...)"))?;
            let end = match t.right {
                crate::function::Extension::Linear => aster_fem::CurveEnd::Linear,
                crate::function::Extension::Constant => aster_fem::CurveEnd::Constant,
                crate::function::Extension::Excluded => aster_fem::CurveEnd::Excluded,
            };
            // code_aster reads Young's modulus from the curve (σ₁/ε₁).
            aster_fem::VonMises::traction_curve(t.abscissae(), t.values(), end)
        }
        Relation::VmisCineLine => {
            let e = mat
                .ecro_line
                .ok_or_else(|| missing("ECRO_LINE=_F(D_SIGM_EPSI, SY)"))?;
            aster_fem::VonMises::kinematic(mat.young, e.sy, e.d_sigm_epsi)
        }
        Relation::VmisIsotNl => {
            let c = mat.ecro_nl.ok_or_else(|| missing("ECRO_NL=_F(R0, ...)"))?;
            aster_fem::VonMises::nonlinear(aster_fem::EcroNl { resi_inte, ..c })
        }
        Relation::VmisJohnCook => {
            let c = mat
                .ecro_cook
                .ok_or_else(|| missing("ECRO_COOK=_F(A, B, N_PUIS, ...)"))?;
            aster_fem::VonMises::johnson_cook(aster_fem::JohnsonCook {
                resi_inte,
                iter_maxi: local.iter_inte_maxi,
                ..c
            })
        }
        Relation::Elas
        | Relation::Lemaitre
        | Relation::CzmLinReg
        | Relation::CzmTuron
        | Relation::GrilleIsotLine
        | Relation::GrilleCineLine => {
            return Err(ExecError::new(format!(
                "{} has no von Mises law",
                relation.keyword()
            )))
        }
    };
    law.map(|l| {
        l.with_search(aster_fem::LocalSearch {
            resi_inte,
            iter_maxi: local.iter_inte_maxi,
        })
    })
    .map_err(|e| fem_err("DEFI_MATERIAU", e))
}

/// The joint cells of the model (`PLAN_JOINT`) as a force source, each
/// with the cohesive law of its last `COMPORTEMENT` occurrence
/// (`CZM_LIN_REG` from the material's `RUPT_FRAG`, `CZM_TURON` from its
/// `RUPT_TURON`); `None` without joint cells.
pub fn joint_source(
    mesh: &Mesh,
    model: &ModelDef,
    occurrences: &[BehaviourOcc],
    materials: &MaterialField,
) -> Result<Option<aster_fem::joint::JointCells>, ExecError> {
    use aster_fem::cohesive::{CohesiveLaw, LinReg};
    let at = "STAT_NON_LINE/COMPORTEMENT";
    let mut cells = Vec::new();
    for (&cell, &m) in &model.cells {
        if m != Modelisation::PlaneJoint {
            continue;
        }
        let name = crate::select::cell_name(mesh, cell);
        let relation = occurrences
            .iter()
            .rev()
            .find(|o| o.cells.as_ref().is_none_or(|c| c.contains(&cell)))
            .map(|o| o.relation)
            .unwrap_or(Relation::Elas);
        let mat = materials.cells.get(&cell).ok_or_else(|| {
            ExecError::new(format!(
                "joint cell {name} has no material: assign one with AFFE_MATERIAU"
            ))
        })?;
        let law = match relation {
            Relation::CzmLinReg => {
                let r = mat.rupt_frag.ok_or_else(|| {
                    ExecError::new(format!(
                        "{at}: RELATION='CZM_LIN_REG' on joint cell {name} needs RUPT_FRAG=_F(GC, SIGM_C, PENA_ADHERENCE) in its material's DEFI_MATERIAU"
                    ))
                })?;
                let (Some(sigma_c), Some(pena_adherence)) = (r.sigm_c, r.pena_adherence) else {
                    return Err(ExecError::new(format!(
                        "{at}: RELATION='CZM_LIN_REG' on joint cell {name} needs SIGM_C and PENA_ADHERENCE in its material's RUPT_FRAG"
                    )));
                };
                CohesiveLaw::LinReg(LinReg {
                    gc: r.gc,
                    sigma_c,
                    pena_adherence,
                    pena_contact: r.pena_contact,
                })
            }
            Relation::CzmTuron => CohesiveLaw::Turon(mat.rupt_turon.ok_or_else(|| {
                ExecError::new(format!(
                    "{at}: RELATION='CZM_TURON' on joint cell {name} needs RUPT_TURON=_F(…) in its material's DEFI_MATERIAU"
                ))
            })?),
            other => {
                return Err(ExecError::new(format!(
                    "{at}: joint cell {name} (PLAN_JOINT) has RELATION='{}': aster runs its joint elements with CZM_LIN_REG or CZM_TURON",
                    other.keyword()
                )))
            }
        };
        let c = mesh.cell(cell);
        let nodes: [NodeId; 4] = c
            .nodes
            .as_slice()
            .try_into()
            .map_err(|_| ExecError::new(format!("joint cell {name} is not a QUAD4")))?;
        let geom = nodes.map(|n| {
            let x = mesh.coord(n);
            [x[0], x[1]]
        });
        cells.push(aster_fem::joint::JointCell {
            cell,
            nodes,
            geom,
            law,
        });
    }
    Ok((!cells.is_empty()).then(|| aster_fem::joint::JointCells::new(cells)))
}

fn comp(name: &str) -> Result<Comp, ExecError> {
    Comp::from_name(name).ok_or_else(|| ExecError::new(format!("unknown component {name}")))
}

/// A multiplier for fem. Tabulated functions and constants are plain data
/// and are moved into the closure; formulas are sampled at the instants
/// and at the times a step cut can reach (`cuts`, [`cut_instants`]).
fn multiplier(
    f: &Option<Rc<Function>>,
    instants: &[f64],
    cuts: &[f64],
) -> Result<Multiplier, ExecError> {
    let Some(f) = f else {
        return Ok(Multiplier::one());
    };
    match &**f {
        Function::Constant { value, .. } => Ok(Multiplier::constant(*value)),
        Function::Tabulated(t) => {
            let t = t.clone();
            Ok(Multiplier::from_fn(move |x| {
                t.eval(x).map_err(|e| e.to_string())
            }))
        }
        Function::Formula { .. } => {
            let mut samples: Vec<(f64, f64)> = instants
                .iter()
                .map(|&t| {
                    f.eval(t)
                        .map(|v| (t, v))
                        .map_err(|e| ExecError::new(format!("FONC_MULT: {e}")))
                })
                .collect::<Result<_, _>>()?;
            samples.extend(cuts.iter().filter_map(|&t| f.eval(t).ok().map(|v| (t, v))));
            Ok(Multiplier::from_fn(move |x| {
                samples
                    .iter()
                    .find(|(t, _)| (t - x).abs() <= 1e-9 * t.abs().max(1.0))
                    .map(|&(_, v)| v)
                    .ok_or_else(|| {
                        format!(
                            "formula multiplier asked at {x}, which is not an instant of the list"
                        )
                    })
            }))
        }
        Function::Nappe(n) => Err(ExecError::new(format!(
            "FONC_MULT: a nappe (DEFI_NAPPE) is a function of two parameters ({}, {}); a function of INST is expected",
            n.parameter, n.parameter_fonc
        ))),
    }
}

/// The multiplier of a value given by a function (`AFFE_CHAR_*_F`) at a
/// point: m(t)·f(INST=t, X, Y, Z). Tabulated functions of `INST` and
/// constants move into the closure; a function of the coordinates only is
/// evaluated once; formulas of `INST` are sampled at the instants.
fn function_multiplier(
    f: &LoadFunction,
    xyz: [f64; 3],
    m: &Multiplier,
    instants: &[f64],
    cuts: &[f64],
) -> Result<Multiplier, ExecError> {
    let named = |t: f64| [("INST", t), ("X", xyz[0]), ("Y", xyz[1]), ("Z", xyz[2])];
    let fun = &f.0;
    let depends_on_time = fun.parameters().contains(&"INST");
    let m = m.clone();
    let scaled = move |t: f64, v: f64| -> Result<f64, String> {
        Ok(m.eval(t).map_err(|e| e.to_string())? * v)
    };
    if !depends_on_time {
        let v = fun
            .eval_named(&named(0.0))
            .map_err(|e| ExecError::new(format!("load function: {e}")))?;
        return Ok(Multiplier::from_fn(move |t| scaled(t, v)));
    }
    if let Function::Tabulated(tab) = &**fun {
        let tab = tab.clone();
        return Ok(Multiplier::from_fn(move |t| {
            scaled(t, tab.eval(t).map_err(|e| e.to_string())?)
        }));
    }
    let mut samples: Vec<(f64, f64)> = instants
        .iter()
        .map(|&t| {
            fun.eval_named(&named(t))
                .map(|v| (t, v))
                .map_err(|e| ExecError::new(format!("load function at INST={t}: {e}")))
        })
        .collect::<Result<_, _>>()?;
    samples.extend(
        cuts.iter()
            .filter_map(|&t| fun.eval_named(&named(t)).ok().map(|v| (t, v))),
    );
    Ok(Multiplier::from_fn(move |x| {
        let v = samples
            .iter()
            .find(|(t, _)| (t - x).abs() <= 1e-9 * t.abs().max(1.0))
            .map(|&(_, v)| v)
            .ok_or_else(|| {
                format!("load formula asked at {x}, which is not an instant of the list")
            })?;
        scaled(x, v)
    }))
}

/// A distributed load given by a function of both `INST` and the
/// coordinates: code_aster evaluates it at the load's Gauss points at each
/// time. It is sampled at the solve's instants and the times step cutting
/// can reach ([`cut_instants`]): one load piece per sample time and cell,
/// with the function's values at the cell's `points` at that time, whose
/// multiplier is m(t) at its own sample and 0 at the others. A time that is
/// no sample stops with that time named (never a silent zero).
#[allow(clippy::too_many_arguments)]
fn space_time_pieces(
    loads: &mut Loads,
    f: &LoadFunction,
    cells: &[aster_mesh::CellId],
    points: impl Fn(aster_mesh::CellId) -> Vec<[f64; 3]>,
    make: impl Fn(aster_mesh::CellId, Vec<f64>) -> Load,
    m: &Multiplier,
    instants: &[f64],
    cuts: &[f64],
) -> Result<(), ExecError> {
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(1.0);
    let mut samples: Vec<f64> = Vec::new();
    for &t in instants.iter().chain(cuts) {
        if !samples.iter().any(|&s| close(s, t)) {
            samples.push(t);
        }
    }
    const MAX_PIECES: usize = 2_000_000;
    if samples.len().saturating_mul(cells.len()) > MAX_PIECES {
        return Err(ExecError::new(format!(
            "not supported yet: a distributed load function of both INST and the coordinates on {} cells over {} instants (and step-cut times): it is sampled per instant and cell, and more than {MAX_PIECES} pieces are refused",
            cells.len(),
            samples.len()
        )));
    }
    let samples = std::sync::Arc::new(samples);
    let points: Vec<(aster_mesh::CellId, Vec<[f64; 3]>)> =
        cells.iter().map(|&c| (c, points(c))).collect();
    for (k, &t) in samples.iter().enumerate() {
        let all = samples.clone();
        let m = m.clone();
        let mk = Multiplier::from_fn(move |x| {
            let j = all
                .iter()
                .position(|&s| (s - x).abs() <= 1e-9 * s.abs().max(1.0))
                .ok_or_else(|| {
                    format!("a load function of INST and the coordinates asked at {x}, which is not an instant of the list")
                })?;
            if j == k {
                m.eval(x).map_err(|e| e.to_string())
            } else {
                Ok(0.0)
            }
        });
        for (cell, pts) in &points {
            let values = pts
                .iter()
                .map(|x| {
                    f.0.eval_named(&[("INST", t), ("X", x[0]), ("Y", x[1]), ("Z", x[2])])
                        .map_err(|e| {
                            ExecError::new(format!(
                                "load function at INST={t}, ({}, {}, {}): {e}",
                                x[0], x[1], x[2]
                            ))
                        })
                })
                .collect::<Result<Vec<f64>, _>>()?;
            loads.add(make(*cell, values), mk.clone());
        }
    }
    Ok(())
}

/// A load function of both the time and the coordinates
/// ([`space_time_pieces`]).
fn of_time_and_coordinates(f: &LoadFunction) -> bool {
    of_coordinates(f) && f.0.parameters().contains(&"INST")
}

/// A load function of the coordinates, evaluated at the Gauss points of
/// each cell (with INST = 0 unless [`of_time_and_coordinates`]).
fn of_coordinates(f: &LoadFunction) -> bool {
    f.0.parameters().iter().any(|p| ["X", "Y", "Z"].contains(p))
}

/// A load function's values at points.
fn point_values(f: &LoadFunction, points: &[[f64; 3]]) -> Result<Vec<f64>, ExecError> {
    points
        .iter()
        .map(|x| {
            f.0.eval_named(&[("INST", 0.0), ("X", x[0]), ("Y", x[1]), ("Z", x[2])])
                .map_err(|e| {
                    ExecError::new(format!(
                        "load function at ({}, {}, {}): {e}",
                        x[0], x[1], x[2]
                    ))
                })
        })
        .collect()
}

/// Values of component `k` as vectors.
fn along(k: usize, values: Vec<f64>) -> Vec<[f64; 3]> {
    values
        .into_iter()
        .map(|v| {
            let mut f = [0.0; 3];
            f[k] = v;
            f
        })
        .collect()
}

/// The times between the list's instants that step cutting can reach:
/// SUBD_NIVEAU nested cuts into SUBD_PAS equal pieces put them at
/// tᵢ + k·(tᵢ₊₁ − tᵢ)/SUBD_PAS^SUBD_NIVEAU. Formulas of INST are sampled
/// there too (they cannot be evaluated inside the solver), up to 256
/// points per step and 4096 in all; beyond that a cut reaching an
/// unsampled time stops with the time named.
fn cut_instants(instants: &[f64], subdivision: Option<aster_fem::Subdivision>) -> Vec<f64> {
    let Some(sd) = subdivision else {
        return Vec::new();
    };
    let pieces = sd.pieces.max(2);
    let Some(n) = u32::try_from(sd.max_level)
        .ok()
        .and_then(|l| pieces.checked_pow(l))
        .filter(|&n| n > 1 && n <= 256)
    else {
        return Vec::new();
    };
    if instants.len().saturating_mul(n) > 4096 {
        return Vec::new();
    }
    instants
        .windows(2)
        .flat_map(|w| (1..n).map(move |k| w[0] + (w[1] - w[0]) * k as f64 / n as f64))
        .collect()
}

/// The follower pressures of the `TYPE_CHARGE='SUIV'` excitations
/// (`PRES_REP` only: `crate::solve::check_charge_type`), each with its
/// excitation's multiplier; a pressure function of one coordinate is
/// evaluated at each point of the current (`XF`, `YF`, `ZF`) or initial
/// (`X`, `Y`, `Z`) geometry, one of `INST` scales the multiplier.
fn follower_loads(
    setup: &SolveSetup,
    model: &Model,
) -> Result<aster_fem::follower::FollowerPressures, ExecError> {
    use aster_fem::follower::{FollowerPressures, FollowerValue};
    let cuts = cut_instants(&setup.instants, setup.subdivision);
    let mut items = Vec::new();
    for exc in &setup.excitations {
        if exc.kind != crate::solve::ChargeType::Suiv {
            continue;
        }
        let LoadRef::Mechanical(l) = &exc.load else {
            continue;
        };
        let m = multiplier(&exc.multiplier, &setup.instants, &cuts)?;
        for b in &l.boundary {
            if let BoundaryLoad::Pressure { cells, pressure } = b {
                for &cell in cells {
                    items.push((cell, FollowerValue::Constant(*pressure), m.clone()));
                }
            }
        }
        for b in &l.boundary_fn {
            let BoundaryFn::Pressure { cells, pressure } = b else {
                continue;
            };
            // evalPressure: the function at each point with X, Y, Z, XF,
            // YF, ZF and INST.
            let f = pressure.0.clone();
            let value = FollowerValue::At(Rc::new(move |x0: [f64; 3], x: [f64; 3], t: f64| {
                f.eval_named(&[
                    ("X", x0[0]),
                    ("Y", x0[1]),
                    ("Z", x0[2]),
                    ("XF", x[0]),
                    ("YF", x[1]),
                    ("ZF", x[2]),
                    ("INST", t),
                ])
                .map_err(|e| e.to_string())
            }));
            let mk = m.clone();
            for &cell in cells {
                items.push((cell, value.clone(), mk.clone()));
            }
        }
    }
    FollowerPressures::new(model, items)
        .map_err(|e| fem_err("STAT_NON_LINE/EXCIT/TYPE_CHARGE='SUIV'", e))
}

/// The load items of the `TYPE_CHARGE='DIDI'` excitations (ranges of
/// `Loads::items`, in the order [`build_loads`] adds them).
type DidiItems = Vec<std::ops::Range<usize>>;

/// The load items of the `EXCIT` occurrences with a `FONC_MULT`, and it
/// ([`FemRun::excit`]).
type ExcitItems = Vec<(std::ops::Range<usize>, Multiplier)>;

/// code_aster's differential Dirichlet conditions (`nmdidi`, `vecdid`):
/// the dualised conditions (and the eliminated ones, `vecdid_cine`) of a
/// `TYPE_CHARGE='DIDI'` load hold on u − u₀, u₀ the displacement of the
/// initial state (`ETAT_INIT`; zero without one): Σ cᵢ uᵢ = d·f(t) +
/// Σ cᵢ u₀ᵢ, the shift not scaled by the multiplier.
fn shift_didi(loads: &mut Loads, didi: &DidiItems, model: &Model, u0: Option<&[f64]>) {
    let Some(u0) = u0 else { return };
    let at = |dof: Dof| model.dofs().index(dof).map_or(0.0, |i| u0[i]);
    for range in didi {
        for item in &mut loads.items[range.clone()] {
            let (shift, value) = match &mut item.load {
                Load::Imposed { dof, value } | Load::Eliminated { dof, value } => (at(*dof), value),
                Load::Relation { terms, rhs } => {
                    (terms.iter().map(|(d, c)| c * at(*d)).sum::<f64>(), rhs)
                }
                _ => continue,
            };
            if shift == 0.0 {
                continue;
            }
            let (d, m) = (*value, item.mult.clone());
            *value = 1.0;
            item.mult =
                Multiplier::from_fn(move |t| Ok(d * m.eval(t).map_err(|e| e.to_string())? + shift));
        }
    }
}

fn build_loads(
    setup: &SolveSetup,
    mesh: &Mesh,
    model: &Model,
) -> Result<(Loads, DidiItems, ExcitItems), ExecError> {
    let cuts = cut_instants(&setup.instants, setup.subdivision);
    let mut loads = Loads::new();
    let mut didi = DidiItems::new();
    let mut excit = Vec::new();
    for exc in &setup.excitations {
        if exc.kind == crate::solve::ChargeType::Suiv {
            // `follower_loads`.
            continue;
        }
        let first_item = loads.items.len();
        let m = multiplier(&exc.multiplier, &setup.instants, &cuts)?;
        match &exc.load {
            LoadRef::Kinematic(k) => {
                for i in &k.imposed {
                    loads.add(
                        Load::Eliminated {
                            dof: Dof::new(i.node, comp(i.comp)?),
                            value: i.value,
                        },
                        m.clone(),
                    );
                }
                for i in &k.imposed_fn {
                    loads.add(
                        Load::Eliminated {
                            dof: Dof::new(i.node, comp(i.comp)?),
                            value: 1.0,
                        },
                        function_multiplier(&i.function, i.xyz, &m, &setup.instants, &cuts)?,
                    );
                }
            }
            LoadRef::Mechanical(l) => {
                for v in &l.volume {
                    for k in 0..3 {
                        let mut unit = [0.0; 3];
                        unit[k] = 1.0;
                        let mk = match &v.functions[k] {
                            Some(f) if of_time_and_coordinates(f) => {
                                space_time_pieces(
                                    &mut loads,
                                    f,
                                    &v.cells,
                                    |cell| Loads::model_volume_points(model, cell),
                                    |cell, values| Load::VolumeForceAt {
                                        cell,
                                        forces: along(k, values),
                                    },
                                    &m,
                                    &setup.instants,
                                    &cuts,
                                )?;
                                continue;
                            }
                            Some(f) if of_coordinates(f) => {
                                for &cell in &v.cells {
                                    let points = Loads::model_volume_points(model, cell);
                                    let forces = along(k, point_values(f, &points)?);
                                    loads.add(Load::VolumeForceAt { cell, forces }, m.clone());
                                }
                                continue;
                            }
                            Some(f) => {
                                function_multiplier(f, [0.0; 3], &m, &setup.instants, &cuts)?
                            }
                            None if v.force[k] != 0.0 => {
                                unit[k] = v.force[k];
                                m.clone()
                            }
                            None => continue,
                        };
                        for &cell in &v.cells {
                            loads.add(Load::VolumeForce { cell, force: unit }, mk.clone());
                        }
                    }
                }
                gravity_loads(&mut loads, &l.gravity, &m, setup, model)?;
                for e in &l.edges {
                    if e.functions.iter().all(Option::is_none) {
                        for &(cell, rule) in &e.cells {
                            loads.add(
                                Load::EdgeForce {
                                    cell,
                                    force: e.force,
                                    rule,
                                },
                                m.clone(),
                            );
                        }
                    }
                    for (k, f) in e.functions.iter().enumerate() {
                        let Some(f) = f else { continue };
                        let mut unit = [0.0; 6];
                        unit[k] = 1.0;
                        let mk = function_multiplier(f, [0.0; 3], &m, &setup.instants, &cuts)?;
                        for &(cell, rule) in &e.cells {
                            loads.add(
                                Load::EdgeForce {
                                    cell,
                                    force: unit,
                                    rule,
                                },
                                mk.clone(),
                            );
                        }
                    }
                }
                for sh in &l.shells {
                    shell_loads(&mut loads, sh, &m, setup, model, &cuts)?;
                }
                for i in &l.imposed_fn {
                    loads.add(
                        Load::Imposed {
                            dof: Dof::new(i.node, comp(i.comp)?),
                            value: 1.0,
                        },
                        function_multiplier(&i.function, i.xyz, &m, &setup.instants, &cuts)?,
                    );
                }
                for i in &l.nodal_forces_fn {
                    loads.add(
                        Load::NodalForce {
                            dof: Dof::new(i.node, comp(i.comp)?),
                            value: 1.0,
                        },
                        function_multiplier(&i.function, i.xyz, &m, &setup.instants, &cuts)?,
                    );
                }
                for b in &l.boundary_fn {
                    match b {
                        BoundaryFn::Force { cells, force } => {
                            for (k, f) in force.iter().enumerate() {
                                let Some(f) = f else { continue };
                                if of_time_and_coordinates(f) {
                                    space_time_pieces(
                                        &mut loads,
                                        f,
                                        cells,
                                        |cell| Loads::skin_points(mesh, cell),
                                        |cell, values| Load::SurfaceForceAt {
                                            cell,
                                            forces: along(k, values),
                                        },
                                        &m,
                                        &setup.instants,
                                        &cuts,
                                    )?;
                                    continue;
                                }
                                if of_coordinates(f) {
                                    for &cell in cells {
                                        let points = Loads::skin_points(mesh, cell);
                                        let forces = along(k, point_values(f, &points)?);
                                        loads.add(Load::SurfaceForceAt { cell, forces }, m.clone());
                                    }
                                    continue;
                                }
                                let mut unit = [0.0; 3];
                                unit[k] = 1.0;
                                let mk =
                                    function_multiplier(f, [0.0; 3], &m, &setup.instants, &cuts)?;
                                for &cell in cells {
                                    loads.add(Load::SurfaceForce { cell, force: unit }, mk.clone());
                                }
                            }
                        }
                        BoundaryFn::Pressure { pressure, .. }
                            if pressure
                                .0
                                .parameters()
                                .iter()
                                .any(|p| ["XF", "YF", "ZF"].contains(p)) =>
                        {
                            return Err(ExecError::new(
                                "not supported yet: a PRES_REP function of the current coordinates (XF, YF, ZF) in a load that is not TYPE_CHARGE='SUIV' (code_aster evaluates a dead pressure with XF = YF = ZF = 0)".to_string(),
                            ));
                        }
                        BoundaryFn::Pressure { cells, pressure }
                            if of_time_and_coordinates(pressure) =>
                        {
                            space_time_pieces(
                                &mut loads,
                                pressure,
                                cells,
                                |cell| Loads::skin_points(mesh, cell),
                                |cell, pressures| Load::PressureAt { cell, pressures },
                                &m,
                                &setup.instants,
                                &cuts,
                            )?;
                        }
                        BoundaryFn::Pressure { cells, pressure } if of_coordinates(pressure) => {
                            for &cell in cells {
                                let points = Loads::skin_points(mesh, cell);
                                let pressures = point_values(pressure, &points)?;
                                loads.add(Load::PressureAt { cell, pressures }, m.clone());
                            }
                        }
                        BoundaryFn::Pressure { cells, pressure } => {
                            let mk = function_multiplier(
                                pressure,
                                [0.0; 3],
                                &m,
                                &setup.instants,
                                &cuts,
                            )?;
                            for &cell in cells {
                                loads.add(
                                    Load::Pressure {
                                        cell,
                                        pressure: 1.0,
                                    },
                                    mk.clone(),
                                );
                            }
                        }
                    }
                }
                for i in &l.imposed {
                    loads.add(
                        Load::Imposed {
                            dof: Dof::new(i.node, comp(i.comp)?),
                            value: i.value,
                        },
                        m.clone(),
                    );
                }
                for r in &l.relations {
                    let terms = r
                        .terms
                        .iter()
                        .map(|(n, c, a)| Ok((Dof::new(*n, comp(c)?), *a)))
                        .collect::<Result<Vec<_>, ExecError>>()?;
                    loads.add(Load::Relation { terms, rhs: r.rhs }, m.clone());
                }
                for r in &l.relations_fn {
                    let terms = r
                        .relation
                        .terms
                        .iter()
                        .map(|(n, c, a)| Ok((Dof::new(*n, comp(c)?), *a)))
                        .collect::<Result<Vec<_>, ExecError>>()?;
                    loads.add(
                        Load::Relation {
                            terms,
                            rhs: r.relation.rhs,
                        },
                        function_multiplier(&r.function, [0.0; 3], &m, &setup.instants, &cuts)?,
                    );
                }
                for f in &l.nodal_forces {
                    loads.add(
                        Load::NodalForce {
                            dof: Dof::new(f.node, comp(f.comp)?),
                            value: f.value,
                        },
                        m.clone(),
                    );
                }
                for b in &l.boundary {
                    match b {
                        BoundaryLoad::Force { cells, force } => {
                            for &cell in cells {
                                loads.add(
                                    Load::SurfaceForce {
                                        cell,
                                        force: *force,
                                    },
                                    m.clone(),
                                );
                            }
                        }
                        BoundaryLoad::Pressure { cells, pressure } => {
                            for &cell in cells {
                                loads.add(
                                    Load::Pressure {
                                        cell,
                                        pressure: *pressure,
                                    },
                                    m.clone(),
                                );
                            }
                        }
                    }
                }
            }
        }
        if exc.kind == crate::solve::ChargeType::Didi {
            didi.push(first_item..loads.items.len());
        }
        if exc.multiplier.is_some() {
            excit.push((first_item..loads.items.len(), m.clone()));
        }
    }
    if let Some(temp) = &setup.materials.temperature {
        thermal_loads(
            &mut loads,
            temp,
            &setup.materials,
            mesh,
            model,
            &setup.instants,
        )?;
    }
    Ok((loads, didi, excit))
}

/// `PESANTEUR` as volume forces ρ g d on its continuum cells, ρ the
/// ELAS/RHO of each cell's material (an error located at the keyword when
/// it has none, as code_aster's `rcvalb` stops); in AXIS only the axial
/// component acts (te0085 loads DY alone, times r as every AXIS load).
fn gravity_loads(
    loads: &mut Loads,
    gravity: &[crate::concept::Gravity],
    m: &aster_fem::Multiplier,
    setup: &SolveSetup,
    model: &Model,
) -> Result<(), ExecError> {
    for g in gravity {
        for &cell in &g.cells {
            let (hypothesis, thickness) = match model.element_kind(cell) {
                Some(aster_fem::ElementKind::Continuum { hypothesis, .. }) => {
                    (Some(*hypothesis), None)
                }
                Some(aster_fem::ElementKind::Shell { section, .. }) => {
                    (None, Some(section.thickness))
                }
                _ => continue,
            };
            let rho = setup
                .materials
                .cells
                .get(&cell)
                .and_then(|mat| mat.density)
                .ok_or_else(|| {
                    ExecError::new(format!(
                        "AFFE_CHAR_MECA/PESANTEUR: the material of cell {} has no ELAS/RHO, which gravity needs (code_aster stops in rcvalb) ({})",
                        model.cell_name(cell),
                        g.at
                    ))
                })?;
            if let Some(h) = thickness {
                // te0032: ρ h g d per unit area of the facet (dxroep).
                let [x, y, z] = g.acceleration.map(|a| rho * h * a);
                let nodal =
                    vec![[x, y, z, 0.0, 0.0, 0.0, 0.0]; model.mesh().cell(cell).nodes.len()];
                loads.add(
                    Load::ShellForce {
                        cell,
                        nodal,
                        offset: 0.0,
                    },
                    m.clone(),
                );
                continue;
            }
            let mut force = g.acceleration.map(|a| rho * a);
            if hypothesis == Some(aster_fem::Hypothesis::Axisymmetric) {
                force[0] = 0.0;
                force[2] = 0.0;
            }
            if force.iter().any(|f| *f != 0.0) {
                loads.add(Load::VolumeForce { cell, force }, m.clone());
            }
        }
    }
    Ok(())
}

/// `FORCE_COQUE` as shell forces per cell: the constant values at every
/// node, each function of the coordinates at the cell's nodes (te0032,
/// te0403 evaluate them there), each function of `INST` as a multiplier;
/// PLAN's offset from a DKT's thickness (COQUE_3D: none, te0403).
fn shell_loads(
    loads: &mut Loads,
    sh: &crate::concept::ShellForce,
    m: &aster_fem::Multiplier,
    setup: &SolveSetup,
    model: &Model,
    cuts: &[f64],
) -> Result<(), ExecError> {
    let mesh = model.mesh();
    for &cell in &sh.cells {
        let offset = match model.element_kind(cell) {
            // te0032: dist = e ± h/2 (INF, SUP), e (MOY), 0 (MAIL).
            Some(aster_fem::ElementKind::Shell { section, .. }) if sh.section_plane => {
                section.offset + sh.plane * section.thickness / 2.0
            }
            _ => 0.0,
        };
        let nodes = &mesh.cell(cell).nodes;
        let mut values = sh.values;
        values[6] *= sh.normal_sign;
        if values.iter().any(|v| *v != 0.0) {
            let nodal = vec![values; nodes.len()];
            loads.add(
                Load::ShellForce {
                    cell,
                    nodal,
                    offset,
                },
                m.clone(),
            );
        }
        for (k, f) in sh.functions.iter().enumerate() {
            let Some(f) = f else { continue };
            if of_coordinates(f) {
                let points: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coord(n)).collect();
                let nodal = point_values(f, &points)?
                    .into_iter()
                    .map(|v| {
                        let mut x = [0.0; 7];
                        x[k] = if k == 6 { v * sh.normal_sign } else { v };
                        x
                    })
                    .collect();
                loads.add(
                    Load::ShellForce {
                        cell,
                        nodal,
                        offset,
                    },
                    m.clone(),
                );
            } else {
                let mut unit = [0.0; 7];
                unit[k] = if k == 6 { sh.normal_sign } else { 1.0 };
                let mk = function_multiplier(f, [0.0; 3], m, &setup.instants, cuts)?;
                let nodal = vec![unit; nodes.len()];
                loads.add(
                    Load::ShellForce {
                        cell,
                        nodal,
                        offset,
                    },
                    mk,
                );
            }
        }
    }
    Ok(())
}

/// The thermal strain α (T − T_ref) of `AFFE_VARC(NOM_VARC='TEMP')` as
/// free-strain loads: one per instant ("knot") and continuum cell,
/// weighted in time by linear interpolation between the knots (EXCLU
/// outside them unless PROL_GAUCHE/PROL_DROITE say CONSTANT). The knots
/// are the field's instants; when a cell's ALPHA is a function of the
/// temperature (ELAS_FO), the strain is not linear in time between them,
/// and the computed instants are knots too, so that the strain there is
/// the one of the temperature there, as code_aster computes it.
fn thermal_loads(
    loads: &mut Loads,
    temp: &crate::concept::Temperature,
    materials: &MaterialField,
    mesh: &Mesh,
    model: &Model,
    computed: &[f64],
) -> Result<(), ExecError> {
    let instants: Vec<f64> = temp.fields.iter().map(|f| f.0).collect();
    // Beams and bars expand too in code_aster (te0150, te0155): not
    // reproduced, refused rather than ignored.
    for el in model.elements() {
        if !temp.cells.contains(&el.cell)
            || !matches!(
                el.kind,
                aster_fem::ElementKind::Beam { .. } | aster_fem::ElementKind::Bar { .. }
            )
        {
            continue;
        }
        let expands = materials
            .cells
            .get(&el.cell)
            .is_some_and(|m| m.alpha.is_some_and(|a| a != 0.) || m.alpha_fo.is_some());
        let heated = temp.fields.iter().any(|(_, values)| {
            mesh.cell(el.cell)
                .nodes
                .iter()
                .any(|n| values[n.0 as usize] != temp.tref)
        });
        if expands && heated {
            return Err(ExecError::new(format!(
                "not supported yet: AFFE_MATERIAU/AFFE_VARC NOM_VARC='TEMP' on cell {}, a beam or bar (POU_D_E, POU_D_T, BARRE): their thermal strain is not reproduced ({})",
                mesh.cell_name(el.cell),
                temp.at
            )));
        }
    }
    shell_thermal_loads(loads, temp, materials, mesh, model)?;
    let heated = |el: &&aster_fem::Element| {
        matches!(el.kind, aster_fem::ElementKind::Continuum { .. }) && temp.cells.contains(&el.cell)
    };
    if temp.shell.is_some() {
        if let Some(el) = model.elements().iter().find(heated) {
            return Err(ExecError::new(format!(
                "AFFE_VARC gives cell {}, which is not a shell, a temperature through the thickness of shells (an EVOL of CREA_RESU/PREP_VARC: TEMP_MIL, TEMP_INF, TEMP_SUP, no TEMP) ({})",
                mesh.cell_name(el.cell),
                temp.at
            )));
        }
        return Ok(());
    }
    let nonlinear = instants.len() > 1
        && model.elements().iter().filter(heated).any(|el| {
            materials
                .cells
                .get(&el.cell)
                .is_some_and(|m| !m.linear_thermal_strain())
        });
    let (before, after) = (temp.constant_before, temp.constant_after);
    // Each knot with its nodal temperatures.
    let mut knots: Vec<(f64, Rc<Vec<f64>>)> = temp.fields.clone();
    if nonlinear {
        for &t in computed {
            let tol = 1e-12 * t.abs().max(1.0);
            if knots.iter().any(|(k, _)| (k - t).abs() <= tol) {
                continue;
            }
            let Ok(w) = crate::concept::temperature_weights(&instants, before, after, t) else {
                continue;
            };
            let n = temp.fields[0].1.len();
            let mut values = vec![0.0; n];
            for (wk, (_, f)) in w.iter().zip(&temp.fields) {
                if *wk != 0.0 {
                    for (v, x) in values.iter_mut().zip(f.iter()) {
                        *v += wk * x;
                    }
                }
            }
            knots.push((t, Rc::new(values)));
        }
        knots.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let times: Vec<f64> = knots.iter().map(|k| k.0).collect();
    for (k, (_, values)) in knots.iter().enumerate() {
        let times = times.clone();
        let mult = aster_fem::Multiplier::from_fn(move |t| {
            crate::concept::temperature_weights(&times, before, after, t).map(|w| w[k])
        });
        for el in model.elements().iter().filter(heated) {
            let mat = materials.cells.get(&el.cell);
            if mat.is_none_or(|m| m.alpha.is_none() && m.alpha_fo.is_none()) {
                return Err(ExecError::new(format!(
                    "AFFE_VARC gives a temperature to cell {}, whose material has no ELAS/ALPHA",
                    mesh.cell_name(el.cell)
                )));
            }
            let Some(mat) = mat else { continue };
            let mut nodal = Vec::new();
            for n in &mesh.cell(el.cell).nodes {
                let t = values[n.0 as usize];
                if t.is_nan() {
                    return Err(ExecError::new(format!(
                        "AFFE_VARC: the temperature field has no value at a node of cell {}",
                        mesh.cell_name(el.cell)
                    )));
                }
                let eps = mat
                    .thermal_strain(t, temp.tref)
                    .map_err(|e| {
                        ExecError::new(format!(
                            "DEFI_MATERIAU: the material of cell {}: {e}",
                            mesh.cell_name(el.cell)
                        ))
                    })?
                    .unwrap_or(0.0);
                nodal.push(eps);
            }
            if nodal.iter().any(|v| *v != 0.0) {
                loads.add(
                    Load::FreeStrain {
                        cell: el.cell,
                        nodal,
                    },
                    mult.clone(),
                );
            }
        }
    }
    Ok(())
}

/// The temperature through the thickness of the DKT, DST and Q4G plates
/// (an `EVOL` of `CREA_RESU/PREP_VARC`) as [`Load::ShellThermal`] free
/// strains, one per plate and field of the temperature with the
/// field's linear-interpolation weight as multiplier. code_aster's
/// `te0408` puts on each sub-point of a cell the parabola T(z) through the
/// means over its nodes of TEMP_INF, TEMP_MIL, TEMP_SUP at z = −h/2, 0,
/// h/2; its plates' thermal efforts (`dxefgt`), stresses (`dxsith`) and
/// efforts at the nodes (`dxefnt`) read that parabola, so the free strain
/// is ε_th(z) = α (T(z) − T_ref) with α of `ELAS` (`dxmath`: no ALPHA, or
/// 0, no thermal strain). Refused, located at AFFE_VARC: COQUE_3D cells,
/// ALPHA as a function (`dxmath` evaluates it at the mean of the cell's
/// sub-points: not done), a plate given a plain TEMP (not through
/// PREP_VARC).
fn shell_thermal_loads(
    loads: &mut Loads,
    temp: &crate::concept::Temperature,
    materials: &MaterialField,
    mesh: &Mesh,
    model: &Model,
) -> Result<(), ExecError> {
    let instants: Vec<f64> = temp.fields.iter().map(|f| f.0).collect();
    let (before, after) = (temp.constant_before, temp.constant_after);
    for el in model.elements() {
        if !temp.cells.contains(&el.cell) {
            continue;
        }
        let name = mesh.cell_name(el.cell);
        let refuse = |why: String| {
            Err(ExecError::new(format!(
                "not supported yet: AFFE_MATERIAU/AFFE_VARC NOM_VARC='TEMP' on cell {name}: {why} ({})",
                temp.at
            )))
        };
        let section = match &el.kind {
            aster_fem::ElementKind::Shell { section, .. } => section,
            aster_fem::ElementKind::Coque3d { .. } => {
                let expands = materials
                    .cells
                    .get(&el.cell)
                    .is_some_and(|m| m.alpha.is_some_and(|a| a != 0.) || m.alpha_fo.is_some());
                let heated = temp.shell.is_some()
                    || temp.fields.iter().any(|(_, values)| {
                        mesh.cell(el.cell)
                            .nodes
                            .iter()
                            .any(|n| values[n.0 as usize] != temp.tref)
                    });
                if expands && heated {
                    return refuse(
                        "a COQUE_3D shell: its thermal strain through the thickness is not reproduced"
                            .into(),
                    );
                }
                continue;
            }
            _ => continue,
        };
        let Some(mat) = materials.cells.get(&el.cell) else {
            continue;
        };
        if mat.alpha_fo.is_some() {
            return refuse(
                "ALPHA of ELAS_FO on a plate (code_aster's dxmath evaluates it at the mean temperature of the cell's sub-points: not reproduced)".into(),
            );
        }
        let Some(alpha) = mat.alpha.filter(|a| *a != 0.0) else {
            // dxmath: no ALPHA (or 0), no thermal strain.
            continue;
        };
        let Some(layers) = &temp.shell else {
            let heated = temp.fields.iter().any(|(_, values)| {
                mesh.cell(el.cell)
                    .nodes
                    .iter()
                    .any(|n| values[n.0 as usize] != temp.tref)
            });
            if heated {
                return refuse(
                    "a DKT/DST/Q4G plate given TEMP: a plate's temperature is TEMP_MIL, TEMP_INF, TEMP_SUP through CREA_RESU(OPERATION='PREP_VARC')".into(),
                );
            }
            continue;
        };
        let h = section.thickness;
        let nodes = &mesh.cell(el.cell).nodes;
        for (k, l) in layers.iter().enumerate() {
            // The cell's means of TEMP_MIL, TEMP_INF, TEMP_SUP (te0408).
            let mut mean = [0.0; 3];
            for (c, m) in mean.iter_mut().enumerate() {
                for n in nodes {
                    *m += l[c][n.0 as usize];
                }
                *m /= nodes.len() as f64;
            }
            if mean.iter().any(|v| v.is_nan()) {
                return Err(ExecError::new(format!(
                    "AFFE_VARC: the temperature (CREA_RESU/PREP_VARC) has no value at a node of cell {name}"
                )));
            }
            let [mil, inf, sup] = mean;
            let profile = [
                alpha * (mil - temp.tref),
                alpha * (sup - inf) / h,
                alpha * 2.0 * (inf + sup - 2.0 * mil) / (h * h),
            ];
            if profile.iter().all(|v| *v == 0.0) {
                continue;
            }
            let times = instants.clone();
            let mult = aster_fem::Multiplier::from_fn(move |t| {
                crate::concept::temperature_weights(&times, before, after, t).map(|w| w[k])
            });
            loads.add(
                Load::ShellThermal {
                    cell: el.cell,
                    profile,
                },
                mult,
            );
        }
    }
    Ok(())
}

/// A displacement vector of `model` from a stored DEPL field.
pub(crate) fn displacement_from(model: &Model, depl: &NodalField) -> Vec<f64> {
    model
        .dofs()
        .dofs()
        .iter()
        .map(|d| depl.get(d.node, d.comp.name()).unwrap_or(0.0))
        .collect()
}

/// A nodal field from a vector per DOF index.
pub fn nodal_from_dofs(model: &Model, values: &[f64]) -> NodalField {
    let comps: Vec<String> = model
        .dofs()
        .comps()
        .iter()
        .map(|c| c.name().to_string())
        .collect();
    let dofs = model.dofs().dofs();
    let node_count = dofs.iter().map(|d| d.node.0 as usize + 1).max();
    let mut f = NodalField::with_node_count(comps, node_count.unwrap_or(0));
    for (i, d) in dofs.iter().enumerate() {
        f.set(d.node, d.comp.name(), values[i]);
    }
    f
}

pub(crate) fn elem_field(location: ElemLocation, cells: &[CellValues]) -> ElemField {
    // Components: the union in order of appearance (continuum cells and
    // springs have different ones).
    let mut components: Vec<String> = Vec::new();
    for cv in cells {
        for n in &cv.names {
            if !components.iter().any(|c| c == n) {
                components.push(n.to_string());
            }
        }
    }
    // Where each component sits in a cell's own list, found once per
    // distinct list (cells of one kind share it).
    let mut index: Vec<(&[&str], Vec<Option<usize>>)> = Vec::new();
    let mut order: Vec<&CellValues> = cells.iter().collect();
    order.sort_by_key(|cv| cv.cell);
    let points = cells.iter().map(|cv| cv.points.len()).sum();
    let mut field = ElemField::with_capacity(location, components, cells.len(), points);
    for cv in order {
        let names: &[&str] = &cv.names;
        let k = match index.iter().position(|(n, _)| *n == names) {
            Some(k) => k,
            None => {
                let map = field
                    .components()
                    .iter()
                    .map(|c| names.iter().position(|n| n == c))
                    .collect();
                index.push((names, map));
                index.len() - 1
            }
        };
        let map = &index[k].1;
        if names.len() == field.components().len()
            && map.iter().enumerate().all(|(i, m)| *m == Some(i))
        {
            field.insert(cv.cell, &cv.points);
        } else {
            field.insert(
                cv.cell,
                cv.points.iter().map(|p| {
                    map.iter()
                        .map(|m| m.map(|i| p[i]).unwrap_or(f64::NAN))
                        .collect::<Vec<f64>>()
                }),
            );
        }
    }
    field
}

/// The nodal mean of element-node values whose cells carry different
/// component sets (beams' N VY VZ MT MFY MFZ beside shells' NXX … QY):
/// each family of cells averaged on its own, a node getting the
/// components of every family that reaches it, as code_aster's `*_NOEU`
/// of a model mixing such elements.
fn nodal_by_families(model: &aster_fem::Model, elno: &[CellValues]) -> NodalField {
    let mut families: Vec<&[&'static str]> = Vec::new();
    for cv in elno {
        if !families.contains(&cv.names.as_slice()) {
            families.push(&cv.names);
        }
    }
    let mut names: Vec<String> = Vec::new();
    for f in &families {
        for n in f.iter() {
            if !names.iter().any(|m| m == n) {
                names.push(n.to_string());
            }
        }
    }
    let mut out = NodalField::new(names);
    for f in &families {
        let part: Vec<CellValues> = elno.iter().filter(|cv| cv.names == *f).cloned().collect();
        write_nodal(&mut out, &post::noeu(model, &part));
    }
    out
}

fn nodal_from_values(v: &NodalValues) -> NodalField {
    let mut f = NodalField::new(v.names.iter().map(|s| s.to_string()).collect());
    write_nodal(&mut f, v);
    f
}

/// Writes every node's values of `v` into `out` (components by name).
fn write_nodal(out: &mut NodalField, v: &NodalValues) {
    for (n, vals) in v.values.iter().enumerate() {
        if let Some(vals) = vals {
            for (c, x) in v.names.iter().zip(vals) {
                out.set(NodeId(n as u32), c, *x);
            }
        }
    }
}

pub fn solve(
    ex: &mut Executor,
    setup: &SolveSetup,
    linear: bool,
) -> Result<(Vec<Step>, Rc<FemRun>), ExecError> {
    let cmd = if linear {
        "MECA_STATIQUE"
    } else if setup.dynamics.is_some() {
        "DYNA_NON_LINE"
    } else {
        "STAT_NON_LINE"
    };
    let mesh = ex.model_mesh(&setup.model)?;
    if linear
        && setup
            .model
            .cells
            .values()
            .any(|m| *m == Modelisation::PlaneJoint)
    {
        return Err(ExecError::new(format!(
            "{cmd}: the model has joint elements (PLAN_JOINT), which aster computes with their cohesive law in STAT_NON_LINE only"
        )));
    }
    // Parameters at each Gauss point's temperature (ELAS_FO varying,
    // ECRO_LINE_FO, plastic cells under AFFE_VARC): STAT_NON_LINE only.
    let thermo = if linear {
        None
    } else {
        let locate = |span| ex.location(span).unwrap_or_else(|| "DEFI_MATERIAU".into());
        crate::thermo_mat::prepare(
            &mesh,
            &setup.model,
            &setup.behaviours,
            &setup.materials,
            setup.dynamics.is_some(),
            &locate,
        )?
    };
    let thermo_setup;
    let setup = match &thermo {
        Some(t) => {
            thermo_setup = SolveSetup {
                materials: t.materials.clone(),
                ..setup.clone()
            };
            &thermo_setup
        }
        None => setup,
    };
    let mut model = build_model(&mesh, &setup.model, &setup.materials, setup.cara.as_deref())?;
    if linear {
        // code_aster's RIGI_MECA of COQUE_3D (te0401 → vdxrig): two Gauss
        // points through the thickness, not vdxnlr's Simpson.
        model.set_coque3d_rule(aster_fem::coque3d::ThicknessRule::Gauss2);
        // code_aster's RIGI_MECA of the mixed elements (te0592 → nirmtd).
        model.set_mixed_rigi_meca(true);
    }
    if linear {
        refuse_heated_grids(cmd, &mesh, &model, &setup.materials)?;
    }
    let (mut loads, didi, excit) = build_loads(setup, &mesh, &model)?;
    let follower = follower_loads(setup, &model)?;
    let behaviours = build_behaviours(
        &mesh,
        &model,
        &setup.behaviours,
        &setup.materials,
        thermo.as_ref(),
    )?;
    // A plastic cell under a temperature is a temperature-dependent one
    // (its thermal strain in its behaviour): the loads' thermal strains
    // are those of elastic cells, except with finite strains.
    let plastic = !behaviours.is_elastic();
    let finite = behaviours.has_finite_strains();
    if loads.has_free_strain() && (finite || setup.dynamics.is_some()) {
        return Err(ExecError::new(format!(
            "not supported yet: {cmd} with a temperature (AFFE_VARC) and {}: the thermal strain is implemented for linear elastic cells in small strains in MECA_STATIQUE and STAT_NON_LINE",
            if finite { "a non-linear behaviour or a large-strain kinematics (COMPORTEMENT)" } else { "dynamics" }
        )));
    }
    let mut post_zones: Option<Vec<aster_contact::ZoneContact>> = None;
    let mut post_friction: Option<aster_contact::friction::ContinuousFriction> = None;
    let mut post_discrete: Option<aster_contact::friction::DiscreteFriction> = None;
    let mut post_mortar: Option<aster_contact::mortar_lagrangian::MortarLagrangian> = None;
    let mut post_mortar_friction: Option<aster_contact::mortar_friction::MortarFriction> = None;
    let mut post_mortar_classique: Option<aster_contact::mortar_classique::MortarClassique> = None;
    let mut post_joints: Option<aster_fem::joint::JointCells> = None;
    let raw = if linear {
        aster_fem::meca_statique(&model, &loads, &setup.instants).map_err(|e| fem_err(cmd, e))?
    } else {
        // The contact zones are lent to the solver, so that what they record
        // during the solve (forces, last pairings) is there for CONT_NOEU.
        let mut contact_zones: Option<Vec<aster_contact::ZoneContact>> = None;
        let mut friction: Option<aster_contact::friction::ContinuousFriction> = None;
        let mut discrete: Option<aster_contact::friction::DiscreteFriction> = None;
        let mut mortar: Option<aster_contact::mortar_lagrangian::MortarLagrangian> = None;
        let mut mortar_friction: Option<aster_contact::mortar_friction::MortarFriction> = None;
        let mut mortar_classique: Option<aster_contact::mortar_classique::MortarClassique> = None;
        // DEFI_CONT's penalised and Nitsche methods: no unknowns, no fields.
        let mut mortar_other: Vec<Box<dyn aster_fem::ForceSource>> = Vec::new();
        let mut unil: Option<LiaisonUnil> = None;
        if let Some(c) = &setup.contact {
            match &**c {
                ContactDef::Mortar { zones, algos, .. } => {
                    let axis = setup
                        .model
                        .cells
                        .values()
                        .any(|m| *m == crate::concept::Modelisation::Axisymmetric);
                    // One force source per method (DEFI_CONT keeps the
                    // slave surfaces of different methods disjoint).
                    for (algo, zones) in crate::defi_cont::groups(zones, algos) {
                        let zones = &zones;
                        if let Some(s) = crate::defi_cont::other_source(
                            algo,
                            zones,
                            &mesh,
                            axis,
                            setup.model.dim(),
                            &setup.materials,
                            setup.contact_resi_geom,
                        )? {
                            mortar_other.push(s);
                            continue;
                        }
                        // The Lagrangian method (ROBUSTE/RAPIDE or
                        // CLASSIQUE): with or without friction (LAGS_C,
                        // LAGS_F1 fields).
                        let (dim, resi) = (setup.model.dim(), setup.contact_resi_geom);
                        if algo == crate::defi_cont::MortarAlgo::Classique {
                            mortar_classique = Some(crate::defi_cont::classique_source(
                                zones, &mesh, axis, dim, resi,
                            )?);
                        } else if crate::defi_cont::has_friction(zones) {
                            mortar_friction = Some(crate::defi_cont::friction_source(
                                zones, &mesh, axis, dim, resi,
                            )?);
                        } else {
                            mortar = Some(crate::defi_cont::source(zones, &mesh, axis, dim, resi)?);
                        }
                    }
                }
                ContactDef::Unilateral { zones, algo, .. } => {
                    unil = Some(LiaisonUnil {
                        zones: zones.clone(),
                        algo: *algo,
                    })
                }
                ContactDef::Zones { keywords, .. } => {
                    if crate::contactbridge::has_discrete_friction(keywords) {
                        discrete = Some(crate::contactbridge::discrete_friction_source(
                            ex, &mesh, keywords,
                        )?);
                    } else if crate::contactbridge::has_friction(keywords)
                        || crate::contactbridge::contact_elements(&mesh, keywords)
                    {
                        friction =
                            Some(crate::contactbridge::friction_source(ex, &mesh, keywords)?);
                    } else {
                        let zones = crate::contactbridge::zones(ex, &mesh, keywords)?;
                        // Discrete contact on QUAD8 faces: code_aster ties the
                        // middle nodes to their edges.
                        crate::contactbridge::add_middle_relations(&zones, &model, &mut loads);
                        contact_zones = Some(zones);
                    }
                }
            }
        }
        let mut joints = joint_source(&mesh, &setup.model, &setup.behaviours, &setup.materials)?;
        if joints.is_some() && (setup.initial.is_some() || setup.initial_fields.depl.is_some()) {
            // The joints' internal variables of the earlier result are not
            // carried over: continuing would restart them undamaged.
            return Err(ExecError::new(format!(
                "{cmd}/ETAT_INIT: not supported yet with joint elements (PLAN_JOINT): their internal variables are not carried from the initial state"
            )));
        }
        let mut sources: Vec<Box<dyn UnilateralSource + '_>> = Vec::new();
        if let Some(u) = unil {
            sources.push(Box::new(u));
        }
        for z in contact_zones.iter_mut().flatten() {
            sources.push(Box::new(z));
        }
        let mut forces: Vec<Box<dyn aster_fem::ForceSource + '_>> = Vec::new();
        if let Some(f) = friction.as_mut() {
            forces.push(Box::new(f));
        }
        if let Some(f) = discrete.as_mut() {
            forces.push(Box::new(f));
        }
        if let Some(f) = mortar.as_mut() {
            forces.push(Box::new(f));
        }
        if let Some(f) = mortar_friction.as_mut() {
            forces.push(Box::new(f));
        }
        if let Some(f) = mortar_classique.as_mut() {
            forces.push(Box::new(f));
        }
        for f in mortar_other.iter_mut() {
            forces.push(Box::new(f.as_mut()));
        }
        if let Some(j) = joints.as_mut() {
            forces.push(Box::new(j));
        }
        if !follower.is_empty() {
            forces.push(Box::new(aster_fem::follower::FollowerSource {
                loads: &follower,
            }));
        }
        let initial = match &setup.initial {
            Some((prev, t0)) => {
                let step = prev
                    .step_at(*t0, 1e-6, false)
                    .ok_or_else(|| ExecError::new(format!("{cmd}/ETAT_INIT: no state at {t0}")))?;
                let Some(Field::Nodal(depl)) = step.fields.get("DEPL") else {
                    return Err(ExecError::new(format!(
                        "{cmd}/ETAT_INIT: the initial result has no DEPL at {t0}"
                    )));
                };
                // Continuing a computation of this run from its last
                // step: the behaviour cells' state and the contact
                // unknowns there (same sources) come with the displacement.
                let raw = prev.fem.as_ref().map(|f| &f.raw);
                let behaviour = raw
                    .and_then(|r| r.final_state.as_ref())
                    .filter(|(t, _)| (t - t0).abs() <= 1e-6 * t0.abs().max(1e-300))
                    .map(|(_, s)| s.clone());
                let own_unknowns = raw
                    .and_then(|r| r.steps.last())
                    .filter(|st| (st.time - t0).abs() <= 1e-6 * t0.abs().max(1e-300))
                    .map(|st| st.own_unknowns.clone())
                    .filter(|o| {
                        o.len() == forces.len()
                            && o.iter().zip(&forces).all(|(a, f)| a.len() == f.unknowns())
                    });
                Some(InitialState {
                    time: Some(*t0),
                    displacement: displacement_from(&model, depl),
                    behaviour,
                    own_unknowns,
                })
            }
            None => crate::dyna::initial_displacement(ex, setup, &model)?.map(|u0| InitialState {
                time: None,
                displacement: u0,
                ..Default::default()
            }),
        };
        shift_didi(
            &mut loads,
            &didi,
            &model,
            initial.as_ref().map(|i| i.displacement.as_slice()),
        );
        let mut snl = StaticNonLinear {
            instants: setup.instants.clone(),
            init_time: setup.instants.first().copied(),
            final_time: setup.instants.last().copied(),
            initial,
            newton: NewtonOptions {
                reac_iter: setup.newton.reac_iter,
                matrix: setup.newton.matrix,
                prediction: setup.newton.prediction,
                symmetrize: setup.newton.symmetrize,
                line_search: setup.newton.line_search,
            },
            convergence: Convergence {
                resi_glob_rela: setup.newton.resi_glob_rela,
                resi_glob_maxi: setup.newton.resi_glob_maxi,
                iter_glob_maxi: setup.newton.iter_glob_maxi,
                at_least_one: setup.newton.at_least_one,
            },
            sources,
            forces,
            behaviours: behaviours.clone(),
            subdivision: setup.subdivision,
            cut_refused: setup.cut_refused.clone(),
            penalty_adaptation: setup.penalty_adaptation,
            ..StaticNonLinear::default()
        };
        let outcome = match &setup.dynamics {
            Some(d) => crate::dyna::solve(ex, d, setup, &mesh, &model, &loads, snl)?,
            None => {
                let out = snl.solve(&model, &loads);
                drop(snl);
                out
            }
        };
        let mut raw = outcome.map_err(|e| match (&e, &setup.time_list_at) {
            (aster_fem::FemError::StepCutting { .. }, Some(at)) => with_fem_id(
                ExecError::new(format!(
                    "{cmd}: {e} (cutting set by DEFI_LIST_INST/ECHEC at {at})"
                )),
                &e,
            ),
            (aster_fem::FemError::StepCutting { .. }, None) => with_fem_id(
                ExecError::new(format!(
                    "{cmd}: {e} (code_aster's default cutting of a list of reals: give INCREMENT/LIST_INST a DEFI_LIST_INST with ECHEC to change it)"
                )),
                &e,
            ),
            _ => fem_err(cmd, e),
        })?;
        setup.archive.apply(&mut raw);
        if setup.verbose {
            ex.write_report(&convergence_report(&raw))?;
        }
        if let Some(z) = contact_zones {
            post_zones = Some(z);
        }
        post_friction = friction;
        post_discrete = discrete;
        post_mortar = mortar;
        post_mortar_friction = mortar_friction;
        post_mortar_classique = mortar_classique;
        post_joints = joints;
        raw
    };
    let steps = raw
        .steps
        .iter()
        .map(|s| -> Result<Step, ExecError> {
            let mut fields = crate::field::StepFields::new();
            fields.insert(
                "DEPL".to_string(),
                Field::Nodal(nodal_from_dofs(&model, &s.displacement)),
            );
            // The DKTG/Q4GG facets' SIEF_ELGA: their generalised efforts.
            let plates = crate::shells::global_plate_sief(
                &model,
                setup.cara.as_deref(),
                &s.displacement,
                linear,
                (&loads, s.time),
            )
            .map_err(|e| fem_err(cmd, e))?;
            let sief = if plates.is_empty() {
                elem_field(ElemLocation::Gauss, &s.stress)
            } else {
                let mut all = s.stress.clone();
                all.extend(plates);
                elem_field(ElemLocation::Gauss, &all)
            };
            fields.insert("SIEF_ELGA".to_string(), Field::Elem(sief));
            fields.insert(
                "VARI_ELGA".to_string(),
                Field::Elem(elem_field(ElemLocation::Gauss, &s.internal_variables)),
            );
            if let Some(k) = &s.motion {
                fields.insert(
                    "VITE".to_string(),
                    Field::Nodal(nodal_from_dofs(&model, &k.velocity)),
                );
                fields.insert(
                    "ACCE".to_string(),
                    Field::Nodal(nodal_from_dofs(&model, &k.acceleration)),
                );
            }
            if let Some(f) = &post_friction {
                // Contact with friction: the multipliers are DOFs of DEPL on
                // the slave nodes, CONT_NOEU as recorded at convergence.
                if let Some(Field::Nodal(depl)) = fields.get_mut("DEPL") {
                    let own = s.own_unknowns.first().map(|v| v.as_slice()).unwrap_or(&[]);
                    let friction_dofs = f.has_friction_unknowns();
                    let dim = model
                        .dofs()
                        .comps()
                        .iter()
                        .filter(|c| matches!(c, aster_fem::Comp::DZ))
                        .count()
                        + 2;
                    for (n, v) in f.multipliers(own) {
                        depl.set(n, "LAGS_C", v[0]);
                        if friction_dofs {
                            depl.set(n, "LAGS_F1", v[1]);
                            if dim == 3 {
                                depl.set(n, "LAGS_F2", v[2]);
                            }
                        }
                    }
                }
                if let Some(cn) = f.cont_noeu_at(s.time) {
                    fields.insert("CONT_NOEU".to_string(), Field::Nodal(cont_noeu_field(cn)));
                }
            }
            if let Some(m) = &post_mortar {
                // DEFI_CONT: the contact pressures are DOFs of DEPL on the
                // slave nodes (LAGS_C).
                if let Some(Field::Nodal(depl)) = fields.get_mut("DEPL") {
                    let own = s.own_unknowns.first().map(|v| v.as_slice()).unwrap_or(&[]);
                    for (n, p) in m.multipliers(own) {
                        depl.set(n, "LAGS_C", p);
                    }
                }
            }
            if let Some(m) = &post_mortar_friction {
                // DEFI_CONT with friction: the multipliers are the global
                // components of the contact force (LAGS_C along x, LAGS_F1
                // along y, LAGS_F2 along z in 3D), DOFs of DEPL on the
                // slave nodes.
                if let Some(Field::Nodal(depl)) = fields.get_mut("DEPL") {
                    let own = s.own_unknowns.first().map(|v| v.as_slice()).unwrap_or(&[]);
                    for (n, [lx, ly, lz]) in m.multipliers(own) {
                        depl.set(n, "LAGS_C", lx);
                        depl.set(n, "LAGS_F1", ly);
                        if m.dim() == 3 {
                            depl.set(n, "LAGS_F2", lz);
                        }
                    }
                    // Zones without friction beside them: code_aster's
                    // frictionless elements, LAGS_C the pressure only.
                    for (n, p) in m.pressures(own) {
                        depl.set(n, "LAGS_C", p);
                    }
                }
            }
            if let Some(m) = &post_mortar_classique {
                // DEFI_CONT, VARIANTE='CLASSIQUE': the contact pressure
                // (LAGS_C) and, with friction, the tangential multiplier
                // along the slave tangent (LAGS_F1), DOFs of DEPL on the
                // slave nodes.
                if let Some(Field::Nodal(depl)) = fields.get_mut("DEPL") {
                    let own = s.own_unknowns.first().map(|v| v.as_slice()).unwrap_or(&[]);
                    for (n, [lc, lf]) in m.multipliers(own) {
                        depl.set(n, "LAGS_C", lc);
                        if m.has_friction() {
                            depl.set(n, "LAGS_F1", lf);
                        }
                    }
                }
            }
            if let Some(f) = post_discrete.as_ref() {
                // A step without a converged snapshot is the initial state:
                // code_aster's CONT_NOEU there is zero.
                let cn = match f.cont_noeu_at(s.time) {
                    Some(cn) => cont_noeu_field(cn),
                    None => cont_noeu_field(&f.cont_noeu_initial()),
                };
                fields.insert("CONT_NOEU".to_string(), Field::Nodal(cn));
            }
            if let Some(zones) = &mut post_zones {
                // CONT_NOEU: the zones re-paired on the step's geometry.
                let x = aster_contact::positions(&mesh, model.dofs(), &s.displacement);
                let cn =
                    aster_contact::ContNoeu::at_step_time(zones, &mesh, &x, &s.unilateral, s.time)
                        .map_err(|e| ExecError::new(format!("{cmd}: CONT_NOEU: {e}")))?;
                let mut f = NodalField::new(
                    aster_contact::CONT_NOEU_COMPONENTS
                        .iter()
                        .map(|c| c.to_string())
                        .collect(),
                );
                for (n, vals) in cn.nodes.iter().zip(&cn.values) {
                    for (c, v) in aster_contact::CONT_NOEU_COMPONENTS.iter().zip(vals) {
                        f.set(*n, c, *v);
                    }
                }
                fields.insert("CONT_NOEU".to_string(), Field::Nodal(f));
                // Continuous formulation: the contact pressure is a DOF of
                // DEPL on the slave nodes (LAGS_C).
                if let Some(Field::Nodal(depl)) = fields.get_mut("DEPL") {
                    for z in zones.iter() {
                        for (n, p) in z.lags_c().into_iter().flatten() {
                            depl.set(n, "LAGS_C", p);
                        }
                    }
                }
                if let Some(f) = crate::contactbridge::cont_elem(zones) {
                    fields.insert("CONT_ELEM".to_string(), f);
                }
            }
            Ok(Step {
                nume_ordre: s.nume_ordre as u32,
                inst: s.time,
                fields,
            })
        })
        .collect::<Result<Vec<_>, ExecError>>()?;
    Ok((
        steps,
        Rc::new(FemRun {
            model,
            loads,
            follower,
            raw,
            plastic,
            behaviours,
            mass: crate::dyna::mass_data(
                &mesh,
                &setup.model,
                &setup.materials,
                setup.cara.as_deref(),
            )
            .ok()
            .map(|(m, _)| m),
            cara: setup.cara.clone(),
            joints: post_joints,
            excit,
        }),
    ))
}

/// CONT_NOEU as a nodal field (with PROJ_X… when the formulation writes
/// them).
fn cont_noeu_field(cn: &aster_contact::ContNoeu) -> NodalField {
    let with_proj = !cn.proj.is_empty();
    let mut names: Vec<String> = aster_contact::CONT_NOEU_COMPONENTS
        .iter()
        .map(|c| c.to_string())
        .collect();
    if with_proj {
        names.extend(
            aster_contact::CONT_NOEU_PROJ_COMPONENTS
                .iter()
                .map(|c| c.to_string()),
        );
    }
    let mut nf = NodalField::new(names);
    for (k, (n, vals)) in cn.nodes.iter().zip(&cn.values).enumerate() {
        for (c, v) in aster_contact::CONT_NOEU_COMPONENTS.iter().zip(vals) {
            nf.set(*n, c, *v);
        }
        if let Some(p) = cn.proj.get(k) {
            // A component the formulation does not write there is NaN.
            for (c, v) in aster_contact::CONT_NOEU_PROJ_COMPONENTS.iter().zip(p) {
                if v.is_finite() {
                    nf.set(*n, c, *v);
                }
            }
        }
    }
    nf
}

/// `INFO=2`: one line per increment tried — Newton iterations and the
/// RESI_GLOB_RELA of each; for converged increments the active unilateral
/// rows and plastic Gauss points of the stored step; failed increments and
/// the pieces of cut ones with their outcome.
fn convergence_report(raw: &NonLinearResult) -> String {
    let mut out = String::from(
        "STAT_NON_LINE convergence (INFO=2)\n    INST        ITER  RESI_GLOB_RELA   ACTIVE ROWS  PLASTIC POINTS  RESIDUALS\n",
    );
    let stored = |t: f64| {
        raw.steps
            .iter()
            .skip(1)
            .find(|s| (s.time - t).abs() <= 1e-12 * t.abs().max(1.0))
    };
    for a in &raw.attempts {
        let history: Vec<String> = a.residuals.iter().map(|r| format!("{r:.2e}")).collect();
        let last = a.residuals.last().copied().unwrap_or(f64::NAN);
        let (active, plastic) = match stored(a.to).filter(|_| a.failure.is_none()) {
            Some(s) => (
                s.unilateral
                    .iter()
                    .map(|rows| rows.iter().filter(|r| r.active).count())
                    .sum::<usize>()
                    .to_string(),
                s.internal_variables
                    .iter()
                    .flat_map(|c| c.points.iter())
                    .filter(|p| p.get(1).is_some_and(|&v| v > 0.5))
                    .count()
                    .to_string(),
            ),
            None => ("-".to_string(), "-".to_string()),
        };
        let piece = if a.level > 0 {
            format!(" (piece from {} , level {})", a.from, a.level)
        } else {
            String::new()
        };
        out.push_str(&format!(
            "    {:<11.6} {:>4}  {:>14.6e}  {:>11}  {:>14}  {}{piece}\n",
            a.to,
            a.iterations,
            last,
            active,
            plastic,
            history.join(" ")
        ));
        if let Some(f) = &a.failure {
            let what = if a.cut { "failed, cut" } else { "failed" };
            out.push_str(&format!("      {what}: {f}\n"));
        }
    }
    out
}

/// CALC_CHAMP options on stored steps; with `only`, the element options on
/// those cells and the nodal averages over them (`GROUP_MA`, `MAILLE`).
pub fn calc_champ(
    ex: &mut Executor,
    call: &CommandCall,
    result: &EvolResult,
    options: &[String],
    steps: &[u32],
    only: Option<&std::collections::BTreeSet<aster_mesh::CellId>>,
) -> Result<EvolResult, ExecError> {
    let Some(run) = result.fem.clone() else {
        if result.modal.is_some() {
            return crate::commands::modal::modal_energies(ex, call, result, options, steps, only);
        }
        if !result.steps.is_empty() && result.tables.is_empty() {
            return calc_champ_from_fields(ex, call, result, options, steps, only);
        }
        return Err(ExecError::new(
            "CALC_CHAMP: this result was not computed by STAT_NON_LINE/MECA_STATIQUE in this run",
        ));
    };
    let keep = |c: aster_mesh::CellId| only.is_none_or(|s| s.contains(&c));
    fn on<'a>(
        only: Option<&std::collections::BTreeSet<aster_mesh::CellId>>,
        cells: &'a [CellValues],
    ) -> std::borrow::Cow<'a, [CellValues]> {
        match only {
            None => std::borrow::Cow::Borrowed(cells),
            Some(s) => std::borrow::Cow::Owned(
                cells
                    .iter()
                    .filter(|cv| s.contains(&cv.cell))
                    .cloned()
                    .collect(),
            ),
        }
    }
    let restrict = |cells| on(only, cells);
    let mut out = result.clone();
    for step in out
        .steps
        .iter_mut()
        .filter(|s| steps.contains(&s.nume_ordre))
    {
        let raw = run.state("CALC_CHAMP", step.nume_ordre)?;
        let u = &raw.displacement;
        let model = &run.model;
        let elno = || post::elno(model, &restrict(&raw.stress));
        // The plates' free strains through their thickness at this step
        // (CREA_RESU/PREP_VARC): their efforts, stresses and nodal forces
        // are the mechanical ones minus the thermal part.
        let heat =
            crate::shells::heat_at(&run.loads, raw.time).map_err(|e| fem_err("CALC_CHAMP", e))?;
        let shell_thermal = || {
            run.loads
                .shell_thermal_forces(model, raw.time)
                .map_err(|e| fem_err("CALC_CHAMP", e))
        };
        let forc_noda = || {
            let mut f = if run.plastic {
                aster_fem::behaviour::forc_noda_deformed(model, u, &raw.stress, &run.behaviours)
            } else {
                post::forc_noda(model, u)
            }
            .map_err(|e| fem_err("CALC_CHAMP", e))?;
            run.add_joint_forces(raw.time, &mut f)?;
            // te0031's FORC_NODA of a heated plate: ∫ Bᵀ (efforts − thermal
            // efforts) = K u − its CHAR_MECA_TEMP_R forces.
            if !heat.is_empty() {
                for (a, b) in f.iter_mut().zip(shell_thermal()?) {
                    *a -= b;
                }
            }
            Ok::<_, ExecError>(f)
        };
        let thermal = run
            .loads
            .items
            .iter()
            .any(|i| matches!(i.load, aster_fem::Load::FreeStrain { .. }));
        let plane_stress = model.elements().iter().any(|el| {
            matches!(
                el.kind,
                aster_fem::ElementKind::Continuum {
                    hypothesis: aster_fem::Hypothesis::PlaneStress,
                    ..
                }
            ) && keep(el.cell)
        });
        let epsi_elga = || {
            if plane_stress && thermal {
                return Err(ex.unsupported(
                    "CALC_CHAMP/DEFORMATION of plane stress (C_PLAN) cells with a thermal strain (code_aster's εzz then holds the thermal strain: not done)",
                    call.keywords.keyword("DEFORMATION").map(|k| k.span).unwrap_or(call.span),
                ));
            }
            if run.behaviours.has_finite_strains() {
                return Err(ex.unsupported(
                    "CALC_CHAMP/DEFORMATION of a result computed with DEFORMATION other than PETIT (EPSI_* are the small strains here)",
                    call.keywords.keyword("DEFORMATION").map(|k| k.span).unwrap_or(call.span),
                ));
            }
            post::epsi_elga_on(model, u, keep).map_err(|e| fem_err("CALC_CHAMP", e))
        };
        // EPSG_* (Green–Lagrange) and EPSL_* (logarithmic): kinematic
        // measures of the step's total displacement, whatever the
        // behaviour's DEFORMATION (code_aster's te0025/te0087 → epsvmc).
        let finite_elga = |measure: aster_fem::strain::StrainMeasure| {
            aster_fem::strain::finite_strain_elga_on(
                model,
                u,
                measure,
                run.loads.has_free_strain(),
                keep,
            )
            .map_err(|e| match e {
                // A crushed cell: the case's error, not a limit of aster.
                aster_fem::FemError::Integration(m) => {
                    ex.kw_error("CALC_CHAMP", &call.keywords, "DEFORMATION", m)
                }
                e => ex.unsupported(
                    &format!("CALC_CHAMP/DEFORMATION: {e}"),
                    call.keywords
                        .keyword("DEFORMATION")
                        .map(|k| k.span)
                        .unwrap_or(call.span),
                ),
            })
        };
        // EFGE_ELNO of the beams and of the shells, by code_aster's path
        // for a MECA_STATIQUE result (`ef0033`, `ef0410`) or a non-linear
        // one (`ef0031`, `ef0415`).
        let efge_elno = || {
            let mut v = post::beam_efge_elno(model, u).map_err(|e| fem_err("CALC_CHAMP", e))?;
            if model.has_shells() {
                let linear = matches!(result.typ.as_str(), "evol_elas" | "mult_elas");
                v.extend(
                    crate::shells::efge_elno(model, run.cara.as_deref(), u, linear, &heat)
                        .map_err(|e| fem_err("CALC_CHAMP", e))?,
                );
            }
            Ok::<_, ExecError>(on(only, &v).into_owned())
        };
        for opt in options {
            let field = match opt.as_str() {
                "EPSI_ELGA" => Field::Elem(elem_field(ElemLocation::Gauss, &epsi_elga()?)),
                "EPSI_ELNO" => Field::Elem(elem_field(
                    ElemLocation::Nodes,
                    &post::elno(model, &epsi_elga()?),
                )),
                "EPSI_NOEU" => {
                    let elno = post::elno(model, &epsi_elga()?);
                    refuse_grid_mix(ex, call, model, &elno, opt)?;
                    Field::Nodal(nodal_from_values(&post::noeu(model, &elno)))
                }
                "EPSG_ELGA" | "EPSG_ELNO" | "EPSG_NOEU" | "EPSL_ELGA" | "EPSL_ELNO"
                | "EPSL_NOEU" => {
                    let measure = if opt.starts_with("EPSG") {
                        aster_fem::strain::StrainMeasure::GreenLagrange
                    } else {
                        aster_fem::strain::StrainMeasure::Logarithmic
                    };
                    let elga = finite_elga(measure)?;
                    match &opt[5..] {
                        "ELGA" => Field::Elem(elem_field(ElemLocation::Gauss, &elga)),
                        "ELNO" => {
                            Field::Elem(elem_field(ElemLocation::Nodes, &post::elno(model, &elga)))
                        }
                        _ => Field::Nodal(nodal_from_values(&post::noeu(
                            model,
                            &post::elno(model, &elga),
                        ))),
                    }
                }
                "FORC_NODA" => Field::Nodal(nodal_from_dofs(model, &forc_noda()?)),
                "REAC_NODA" => {
                    // code_aster's REAC_NODA: FORC_NODA − the applied loads.
                    let mut r = forc_noda()?;
                    let fext = run
                        .loads
                        .external_forces(model, raw.time)
                        .map_err(|e| fem_err("CALC_CHAMP", e))?;
                    for (a, b) in r.iter_mut().zip(fext) {
                        *a -= b;
                    }
                    // The plates' thermal forces are in FORC_NODA (above)
                    // and in the loads' vector; once only in the reactions.
                    if !heat.is_empty() {
                        for (a, b) in r.iter_mut().zip(shell_thermal()?) {
                            *a += b;
                        }
                    }
                    if !run.follower.is_empty() {
                        let ff = run
                            .follower
                            .evaluate(model.mesh(), model.dofs(), u, raw.time, None)
                            .map_err(|e| fem_err("CALC_CHAMP", e))?;
                        for (a, b) in r.iter_mut().zip(ff) {
                            *a -= b;
                        }
                    }
                    Field::Nodal(nodal_from_dofs(model, &r))
                }
                "DEGE_ELGA" | "DEGE_ELNO" | "DEGE_NOEU" => {
                    // DKT/DKQ shells (te0033) and, at the nodes, POU_D_E
                    // beams (te0158: code_aster's beams have no DEGE_ELGA).
                    let gauss = opt == "DEGE_ELGA";
                    let why = if gauss && model.has_beams() {
                        Some(format!("CALC_CHAMP/DEFORMATION='{opt}' on a model with POU_D_E beams (code_aster's beams have DEGE_ELNO only, te0158: ask for DEGE_ELNO or DEGE_NOEU)"))
                    } else if model.has_coque3d() || !(model.has_shells() || model.has_beams()) {
                        Some(format!("CALC_CHAMP/DEFORMATION='{opt}' on a model whose elements are not DKT/DKQ shells or POU_D_E beams (the generalised strains of COQUE_3D and of the other elements are not computed)"))
                    } else {
                        None
                    };
                    if let Some(why) = why {
                        return Err(ex.unsupported(
                            &why,
                            call.keywords
                                .keyword("DEFORMATION")
                                .map(|k| k.span)
                                .unwrap_or(call.span),
                        ));
                    }
                    let mut v =
                        post::beam_dege_elno(model, u).map_err(|e| fem_err("CALC_CHAMP", e))?;
                    if model.has_shells() {
                        v.extend(
                            crate::shells::dege(model, run.cara.as_deref(), u, !gauss)
                                .map_err(|e| fem_err("CALC_CHAMP", e))?,
                        );
                    }
                    let v = on(only, &v).into_owned();
                    match opt.as_str() {
                        "DEGE_ELGA" => Field::Elem(elem_field(ElemLocation::Gauss, &v)),
                        "DEGE_ELNO" => Field::Elem(elem_field(ElemLocation::Nodes, &v)),
                        _ => Field::Nodal(nodal_by_families(model, &v)),
                    }
                }
                "EFGE_ELGA" if model.has_shells() => Field::Elem(elem_field(
                    ElemLocation::Gauss,
                    &crate::shells::efge_elga(
                        model,
                        run.cara.as_deref(),
                        u,
                        matches!(result.typ.as_str(), "evol_elas" | "mult_elas"),
                        &heat,
                    )
                    .map_err(|e| fem_err("CALC_CHAMP", e))?,
                )),
                "EFGE_ELNO" if model.has_beams() || model.has_bars() || model.has_shells() => {
                    Field::Elem(elem_field(ElemLocation::Nodes, &efge_elno()?))
                }
                "EFGE_NOEU" if model.has_beams() || model.has_bars() || model.has_shells() => {
                    Field::Nodal(nodal_by_families(model, &efge_elno()?))
                }
                // The stresses at the Gauss points as the solve computed
                // them (a MACRO_ELAS_MULT case with OPTION='SANS' has none
                // stored).
                "SIEF_ELGA" => Field::Elem(elem_field(ElemLocation::Gauss, &restrict(&raw.stress))),
                "SIEF_ELNO" | "SIGM_ELNO" => {
                    Field::Elem(elem_field(ElemLocation::Nodes, &continuum_only(elno())))
                }
                "SIEF_NOEU" | "SIGM_NOEU" => {
                    let elno = continuum_only(elno());
                    refuse_grid_mix(ex, call, model, &elno, opt)?;
                    Field::Nodal(nodal_from_values(&post::noeu(model, &elno)))
                }
                // Internal variables (none for ELAS: fields without components).
                "VARI_ELNO" => Field::Elem(elem_field(
                    ElemLocation::Nodes,
                    &post::elno(model, &restrict(&raw.internal_variables)),
                )),
                "VARI_NOEU" => Field::Nodal(nodal_from_values(&post::noeu(
                    model,
                    &post::elno(model, &restrict(&raw.internal_variables)),
                ))),
                "SIEQ_ELGA" => Field::Elem(elem_field(
                    ElemLocation::Gauss,
                    &post::sieq_field(&restrict(&raw.stress)),
                )),
                "EPSP_ELGA" | "EPSP_ELNO" => {
                    // ε − D⁻¹σ: the plastic strain where there is no
                    // thermal strain (a temperature's is refused).
                    if plane_stress {
                        return Err(ex.unsupported(
                            "CALC_CHAMP/DEFORMATION='EPSP_*' of plane stress (C_PLAN) cells (code_aster's te0334 is not reproduced)",
                            call.keywords.keyword("DEFORMATION").map(|k| k.span).unwrap_or(call.span),
                        ));
                    }
                    // LEMAITRE: code_aster's answer is the iterate its
                    // Newton accepts (RESI_GLOB_RELA) and ε − D⁻¹σ, a small
                    // difference, magnifies the gap to aster's: ssnp02a
                    // 1.4e-6 to 2.6e-5 off (docs/supported.md).
                    if run.behaviours.has_viscous() {
                        return Err(ex.unsupported(
                            "CALC_CHAMP/DEFORMATION='EPSP_*' of a result with LEMAITRE cells (its plastic strain differs from code_aster's by up to 2.6e-5: ε − D⁻¹σ magnifies the difference of the accepted Newton iterates)",
                            call.keywords.keyword("DEFORMATION").map(|k| k.span).unwrap_or(call.span),
                        ));
                    }
                    if thermal {
                        return Err(ex.unsupported(
                            "CALC_CHAMP/DEFORMATION='EPSP_*' of a result with a thermal strain (AFFE_VARC)",
                            call.keywords.keyword("DEFORMATION").map(|k| k.span).unwrap_or(call.span),
                        ));
                    }
                    let epsp =
                        post::inelastic_strain_elga(model, &epsi_elga()?, &restrict(&raw.stress))
                            .map_err(|e| fem_err("CALC_CHAMP", e))?;
                    if opt == "EPSP_ELGA" {
                        Field::Elem(elem_field(ElemLocation::Gauss, &epsp))
                    } else {
                        Field::Elem(elem_field(ElemLocation::Nodes, &post::elno(model, &epsp)))
                    }
                }
                "ENEL_ELGA" | "ENEL_ELNO" | "ENEL_ELEM" => {
                    if run.behaviours.has_finite_strains() {
                        return Err(ex.unsupported(
                            "CALC_CHAMP/ENERGIE of a result computed with DEFORMATION other than PETIT (code_aster's enelpg has its own formulas for SIMO_MIEHE and GDEF_LOG)",
                            call.keywords.keyword("ENERGIE").map(|k| k.span).unwrap_or(call.span),
                        ));
                    }
                    let energie = || {
                        call.keywords
                            .keyword("ENERGIE")
                            .map(|k| k.span)
                            .unwrap_or(call.span)
                    };
                    // The plates' energy (te0412) by the result's path;
                    // their ELNO (te0004's extrapolation) and a heated
                    // plate's are not done.
                    let (plates, plate_totals) = if model.has_shells() {
                        if opt == "ENEL_ELNO" {
                            return Err(ex.unsupported(
                                "CALC_CHAMP/ENERGIE='ENEL_ELNO' on plate cells (te0004's extrapolation of their energy is not reproduced: ask for ENEL_ELGA or ENEL_ELEM)",
                                energie(),
                            ));
                        }
                        if !heat.is_empty() {
                            return Err(ex.unsupported(
                                "CALC_CHAMP/ENERGIE of heated plates (a temperature through their thickness: te0412's thermal terms are not reproduced)",
                                energie(),
                            ));
                        }
                        aster_fem::energy::plate_elastic_energy(
                            model,
                            u,
                            matches!(result.typ.as_str(), "evol_elas" | "mult_elas"),
                        )
                        .map_err(|e| fem_err("CALC_CHAMP", e))?
                    } else {
                        (Vec::new(), Vec::new())
                    };
                    let mut density =
                        aster_fem::energy::elastic_energy_density(model, &restrict(&raw.stress))
                            .map_err(|e| fem_err("CALC_CHAMP", e))?;
                    match &opt[5..] {
                        "ELGA" => {
                            density.extend(plates);
                            Field::Elem(elem_field(ElemLocation::Gauss, &on(only, &density)))
                        }
                        "ELNO" => Field::Elem(elem_field(
                            ElemLocation::Nodes,
                            &post::elno(model, &density),
                        )),
                        _ => {
                            let mut cells = aster_fem::energy::cell_integrals(model, &density)
                                .map_err(|e| fem_err("CALC_CHAMP", e))?;
                            cells.extend(plate_totals);
                            Field::Elem(elem_field(ElemLocation::Cell, &on(only, &cells)))
                        }
                    }
                }
                "SIEQ_ELNO" => {
                    Field::Elem(elem_field(ElemLocation::Nodes, &post::sieq_field(&elno())))
                }
                "SIEQ_NOEU" => {
                    let noeu = post::noeu(model, &continuum_only(elno()));
                    Field::Nodal(nodal_from_values(&post::sieq_nodal(&noeu)))
                }
                // ½ uₑᵀ Kₑ uₑ per cell: code_aster's EPOT_ELEM (½ ∫ σ:ε
                // on the stiffness family) of a linear elastic result of
                // continuum cells without a thermal strain.
                "EPOT_ELEM"
                    if !run.plastic
                        && !thermal
                        && !run.behaviours.has_finite_strains()
                        && model.elements().iter().all(|el| {
                            matches!(
                                el.kind,
                                aster_fem::ElementKind::Continuum { .. }
                                    | aster_fem::ElementKind::Boundary
                            )
                        })
                        && !model.has_stabilised()
                        && !model.has_mixed() =>
                {
                    let cells: Vec<CellValues> =
                        aster_fem::energy::potential_energy_by_cell(model, u)
                            .map_err(|e| fem_err("CALC_CHAMP", e))?
                            .into_iter()
                            .filter(|(cell, _)| keep(*cell))
                            .map(|(cell, e)| CellValues {
                                cell,
                                names: vec!["TOTALE"],
                                points: vec![vec![e]],
                            })
                            .collect();
                    Field::Elem(elem_field(ElemLocation::Cell, &cells))
                }
                other => {
                    let span = ["FORCE", "CONTRAINTE", "CRITERES", "DEFORMATION", "ENERGIE"]
                        .iter()
                        .find_map(|k| {
                            call.keywords
                                .keyword(k)
                                .filter(|kw| kw.value != aster_eval::KwValue::Simple(vec![]))
                        })
                        .map(|k| k.span)
                        .unwrap_or(call.span);
                    return Err(ex.unsupported(&format!("CALC_CHAMP option {other}"), span));
                }
            };
            step.fields.insert(opt.clone(), field);
        }
    }
    Ok(out)
}

/// POST_CHAMP/EXTR_COQUE: a result holding, at each of `steps`, the
/// fields `names` (SIGM_ELNO, SIEF_ELNO) of the shells at one level
/// through their thickness. Each field must have been computed in `result`
/// (CALC_CHAMP), as code_aster requires. The new result cannot compute
/// further fields from a state (`fem: None`): CALC_CHAMP averages its ELNO
/// fields at the nodes.
pub fn extract_shell_level(
    result: &EvolResult,
    names: &[String],
    steps: &[u32],
    level: aster_fem::post::ShellLevel,
) -> Result<EvolResult, ExecError> {
    let Some(run) = result.fem.clone() else {
        return Err(ExecError::new(
            "POST_CHAMP: this result was not computed by STAT_NON_LINE/MECA_STATIQUE in this run",
        ));
    };
    if !run.model.has_shells() {
        return Err(ExecError::new(
            "POST_CHAMP/EXTR_COQUE: the result's model has no shell (DKT) cells",
        ));
    }
    let mut out = EvolResult::new(result.typ.clone(), result.mesh);
    for step in result
        .steps
        .iter()
        .filter(|s| steps.contains(&s.nume_ordre))
    {
        let raw = run.state("POST_CHAMP", step.nume_ordre)?;
        if let Some(name) = names.iter().find(|n| !step.fields.contains_key(n)) {
            return Err(ExecError::new(format!(
                "POST_CHAMP/EXTR_COQUE: the field {name} is not in the result at NUME_ORDRE {}: compute it first (CALC_CHAMP)",
                step.nume_ordre
            )));
        }
        // SIGM_ELNO and SIEF_ELNO of an elastic shell are the same stresses:
        // computed once, stored under each name asked.
        let cells = crate::shells::heat_at(&run.loads, raw.time)
            .and_then(|heat| {
                crate::shells::sigm_elno_at(
                    &run.model,
                    run.cara.as_deref(),
                    &raw.displacement,
                    level,
                    &heat,
                )
            })
            .map_err(|e| fem_err("POST_CHAMP", e))?;
        let field = Field::Elem(elem_field(ElemLocation::Nodes, &cells));
        let fields: crate::field::StepFields = names
            .iter()
            .map(|name| (name.clone(), field.clone()))
            .collect();
        out.steps.push(Step {
            nume_ordre: step.nume_ordre,
            inst: step.inst,
            fields,
        });
    }
    Ok(out)
}

/// POST_CHAMP/COQU_EXCENT: a result holding, at each of `steps`, the
/// shells' efforts `names` (EFGE_ELNO, EFGE_ELGA, which CALC_CHAMP must
/// have computed) of the cells `only` (all when `None`) moved from the
/// cells' plane to their section's mid-surface: MXX MYY MXY − e·(NXX NYY
/// NXY), e the offset of each cell's section (`EXCENTREMENT`; 0: the
/// efforts unchanged), as code_aster's `te0452` (`excent('MOY')`).
pub fn shell_efforts_to_mid_surface(
    result: &EvolResult,
    names: &[String],
    steps: &[u32],
    only: Option<&std::collections::BTreeSet<aster_mesh::CellId>>,
) -> Result<EvolResult, ExecError> {
    let Some(run) = result.fem.clone() else {
        return Err(ExecError::new(
            "POST_CHAMP/COQU_EXCENT: this result was not computed by STAT_NON_LINE/MECA_STATIQUE in this run",
        ));
    };
    let offset = |cell| match run.model.element_kind(cell) {
        Some(aster_fem::ElementKind::Shell { section, .. }) => Some(section.offset),
        _ => None,
    };
    let mut out = EvolResult::new(result.typ.clone(), result.mesh);
    for step in result
        .steps
        .iter()
        .filter(|s| steps.contains(&s.nume_ordre))
    {
        let mut fields = crate::field::StepFields::new();
        for name in names {
            let Some(Field::Elem(efge)) = step.fields.get(name) else {
                return Err(ExecError::new(format!(
                    "POST_CHAMP/COQU_EXCENT: the field {name} is not in the result at NUME_ORDRE {}: compute it first (CALC_CHAMP)",
                    step.nume_ordre
                )));
            };
            let comps = efge.components();
            let at = |c: &str| comps.iter().position(|n| n == c);
            let (Some(nxx), Some(nyy), Some(nxy), Some(mxx), Some(myy), Some(mxy)) = (
                at("NXX"),
                at("NYY"),
                at("NXY"),
                at("MXX"),
                at("MYY"),
                at("MXY"),
            ) else {
                return Err(ExecError::new(format!(
                    "POST_CHAMP/COQU_EXCENT: the field {name} has no NXX NYY NXY MXX MYY MXY components"
                )));
            };
            let mut moved = ElemField::new(efge.location, comps.to_vec());
            for (cell, points) in efge.iter() {
                if only.is_some_and(|o| !o.contains(&cell)) {
                    continue;
                }
                // te0452 is a shell option: cells of other elements are
                // left out of the new field.
                let Some(e) = offset(cell) else { continue };
                let pts: Vec<Vec<f64>> = points
                    .iter()
                    .map(|p| {
                        let mut v = p.to_vec();
                        v[mxx] -= e * p[nxx];
                        v[myy] -= e * p[nyy];
                        v[mxy] -= e * p[nxy];
                        v
                    })
                    .collect();
                moved.insert(cell, pts);
            }
            fields.insert(name.clone(), Field::Elem(moved));
        }
        out.steps.push(Step {
            nume_ordre: step.nume_ordre,
            inst: step.inst,
            fields,
        });
    }
    Ok(out)
}

/// CALC_CHAMP on a result that holds fields but no state to compute from
/// (POST_CHAMP's): the nodal averages of its stored ELNO stresses.
fn calc_champ_from_fields(
    ex: &Executor,
    call: &CommandCall,
    result: &EvolResult,
    options: &[String],
    steps: &[u32],
    only: Option<&std::collections::BTreeSet<aster_mesh::CellId>>,
) -> Result<EvolResult, ExecError> {
    let mesh = ex.mesh_by_id(result.mesh)?;
    let mut out = result.clone();
    for step in out
        .steps
        .iter_mut()
        .filter(|s| steps.contains(&s.nume_ordre))
    {
        for opt in options {
            let source = match opt.as_str() {
                "SIGM_NOEU" => "SIGM_ELNO",
                "SIEF_NOEU" => "SIEF_ELNO",
                other => {
                    return Err(ex.unsupported(
                        &format!("CALC_CHAMP option {other} on a result that holds fields but no computed state (POST_CHAMP, CREA_RESU): only the nodal averages SIGM_NOEU, SIEF_NOEU of its ELNO fields"),
                        call.span,
                    ))
                }
            };
            let Some(Field::Elem(elno)) = step.fields.get(source) else {
                return Err(ExecError::new(format!(
                    "CALC_CHAMP: {opt} needs {source}, which the result does not hold at NUME_ORDRE {}",
                    step.nume_ordre
                )));
            };
            // GROUP_MA / MAILLE: the average over those cells only.
            let on_cells;
            let elno = match only {
                None => elno,
                Some(cells) => {
                    on_cells = elno.on_cells(|c| cells.contains(&c));
                    &on_cells
                }
            };
            let Some(noeu) = elno.nodal_mean(&mesh) else {
                return Err(ExecError::new(format!(
                    "CALC_CHAMP: {source} is not a field at the nodes of the cells"
                )));
            };
            step.fields.insert(opt.clone(), Field::Nodal(noeu));
        }
    }
    Ok(out)
}

/// Stress fields without the springs' N/VY values (SIGM_* are continuum fields).
/// A nodal average (`*_NOEU`) over grid cells and other cells at once:
/// code_aster averages each component over the cells that have it (a
/// grid's SIXX with the solid's, its EXX alone), which `post::noeu` does
/// not (one component set per field): refused, located at the option.
fn refuse_grid_mix(
    ex: &Executor,
    call: &CommandCall,
    model: &Model,
    elno: &[CellValues],
    opt: &str,
) -> Result<(), ExecError> {
    if !model.has_grids() {
        return Ok(());
    }
    let grid = |c: &CellValues| {
        matches!(
            model.element_kind(c.cell),
            Some(aster_fem::ElementKind::Grid { .. })
        )
    };
    if elno.iter().any(grid) && !elno.iter().all(grid) {
        let at = ["DEFORMATION", "CONTRAINTE"]
            .iter()
            .find_map(|k| call.keywords.keyword(k))
            .map(|k| k.span)
            .unwrap_or(call.span);
        return Err(ex.unsupported(
            &format!(
                "CALC_CHAMP/{opt} over grid cells (GRILLE_*) and other cells at once (code_aster averages each component over the cells that have it; restrict it with GROUP_MA)"
            ),
            at,
        ));
    }
    Ok(())
}

fn continuum_only(cells: Vec<CellValues>) -> Vec<CellValues> {
    cells
        .into_iter()
        .filter(|c| c.names.first() == Some(&"SIXX"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::function::FormulaFn;

    #[test]
    fn cut_instants_are_the_nested_subdivisions_of_each_step() {
        let sd = aster_fem::Subdivision {
            pieces: 2,
            max_level: 2,
            min_step: 0.0,
        };
        assert_eq!(
            cut_instants(&[0.0, 1.0, 3.0], Some(sd)),
            vec![0.25, 0.5, 0.75, 1.5, 2.0, 2.5]
        );
        assert!(cut_instants(&[0.0, 1.0], None).is_empty());
        // SUBD_PAS^SUBD_NIVEAU beyond 256 points a step: not sampled.
        let deep = aster_fem::Subdivision {
            pieces: 5,
            max_level: 5,
            min_step: 0.0,
        };
        assert!(cut_instants(&[0.0, 1.0], Some(deep)).is_empty());
    }

    /// A formula of INST given as FONC_MULT is known at the times a cut
    /// reaches (code_aster's default cutting: 4 pieces, 3 levels), not only
    /// at the list's instants; elsewhere the time is named.
    #[test]
    fn a_formula_multiplier_is_known_where_steps_are_cut() {
        let f: Rc<FormulaFn> = Rc::new(|args: &[(String, f64)]| Ok(10.0 * args[0].1 * args[0].1));
        let formula = Some(Rc::new(Function::Formula {
            parameters: vec!["INST".into()],
            eval: f,
        }));
        let instants = [0.0, 0.4, 0.5];
        let cuts = cut_instants(&instants, Some(aster_fem::Subdivision::default()));
        let m = multiplier(&formula, &instants, &cuts).unwrap();
        let at = 0.4 + 0.1 * 3.0 / 64.0;
        assert!((m.eval(at).unwrap() - 10.0 * at * at).abs() < 1e-12);
        assert!((m.eval(0.5).unwrap() - 2.5).abs() < 1e-12);
        let without = multiplier(&formula, &instants, &[]).unwrap();
        let e = without.eval(at).unwrap_err().to_string();
        assert!(e.contains("not an instant of the list"), "{e}");
    }
}
