//! Shell elements (`MODELISATION='DKT'`, `'COQUE_3D'`) in the solvers and
//! CALC_CHAMP: what a model with shells can run, refused where it cannot
//! (located at the keyword), and the shells' efforts `EFGE_ELGA` in the
//! frame of `AFFE_CARA_ELEM/COQUE` (`ANGL_REP`/`VECTEUR`).
//!
//! The shells are linear elastic facets ([`aster_fem::ElementKind::Shell`])
//! and COQUE_3D QUAD9 / TRIA7 cells ([`aster_fem::ElementKind::Coque3d`], whose
//! stresses by layer come from `aster_fem::coque3d::sigm_elno`).
//! Contact zones on shell cells pair their mid-surfaces, as code_aster does
//! (`DIST_COQUE='OUI'` subtracts half the slave shell's thickness from the
//! gap: `crate::contactbridge`, aster-contact's `structural_gap`); a constant
//! `PRES_REP` loads them along their normal. The stresses through the
//! thickness are computed at one level at a time from the efforts
//! (`sigm_elno_at`, for `POST_CHAMP/EXTR_COQUE`); CALC_CHAMP's own
//! `SIGM_ELNO` holds the continuum cells only. Refused with shells:
//! behaviours other than `ELAS` in small strains and dynamics on DKT
//! quadrangles and COQUE_3D (no mass yet; DKT triangles have theirs).

use crate::concept::{CaraElem, ModelDef, Modelisation};
use crate::executor::Executor;
use crate::solve::{BehaviourOcc, Relation};
use aster_eval::{CommandCall, ExecError, Keywords};
use aster_fem::post::EffortsAt;
use aster_fem::{CellValues, Kinematics, Model};
use aster_mesh::{CellId, Mesh};
use std::collections::BTreeMap;

fn is_shell(model: &ModelDef, cell: CellId) -> bool {
    matches!(
        model.cells.get(&cell),
        Some(Modelisation::Plate(_) | Modelisation::Coque3d)
    )
}

fn is_grid(model: &ModelDef, cell: CellId) -> bool {
    matches!(
        model.cells.get(&cell),
        Some(Modelisation::GridMembrane | Modelisation::GridExcentre)
    )
}

/// A shell or a beam: a linear elastic structural element here.
fn is_structural(model: &ModelDef, cell: CellId) -> bool {
    matches!(
        model.cells.get(&cell),
        Some(
            Modelisation::Plate(_)
                | Modelisation::Coque3d
                | Modelisation::BeamEuler
                | Modelisation::BeamTimoshenko
                | Modelisation::Bar
                | Modelisation::GridMembrane
                | Modelisation::GridExcentre
        )
    )
}

/// AFFE_CHAR_MECA: a distributed force (`FORCE_FACE`, `FORCE_CONTOUR`) on
/// shell cells is refused at its factor keyword (code_aster loads shells
/// with `FORCE_COQUE` or `PRES_REP`: aster-fem's `Load::ShellForce`).
pub(crate) fn refuse_loads_on_shells(
    ex: &Executor,
    key: &str,
    occ: &Keywords,
    model: &ModelDef,
    mesh: &Mesh,
    cells: &[CellId],
) -> Result<(), ExecError> {
    let Some(&c) = cells.iter().find(|&&c| is_shell(model, c)) else {
        return Ok(());
    };
    let span = ["GROUP_MA", "MAILLE", "TOUT"]
        .iter()
        .find_map(|k| occ.keyword(k))
        .map(|k| k.span)
        .unwrap_or_default();
    Err(ex.unsupported(
        &format!(
            "AFFE_CHAR_MECA/{key} on shell cells (cell {} is DKT): distributed loads on shells are not implemented",
            crate::select::cell_name(mesh, c)
        ),
        span,
    ))
}

/// STAT_NON_LINE, MECA_STATIQUE, DYNA_NON_LINE: with shells or beams,
/// only `ELAS` in small strains (`COMPORTEMENT` occurrences covering shell
/// or beam cells) (every structural element has its mass in dynamics,
/// aster-fem's `mass`).
pub(crate) fn check_solve(
    ex: &Executor,
    call: &CommandCall,
    model: &ModelDef,
    behaviours: &[BehaviourOcc],
) -> Result<(), ExecError> {
    if !model.cells.keys().any(|&c| is_structural(model, c)) {
        return Ok(());
    }
    let cmd = call.command.as_str();
    let kw = &call.keywords;
    // code_aster's DST and Q4G elements (MEDSTR3, MEDSQU4, MET3TR3,
    // MEQ4QU4) have no RAPH_MECA / FULL_MECA (`te=-1` in their catalogue):
    // only the linear solvers (MECA_STATIQUE, MACRO_ELAS_MULT) run them.
    if !matches!(cmd, "MECA_STATIQUE" | "MACRO_ELAS_MULT") {
        if let Some(Modelisation::Plate(theory)) = model
            .cells
            .values()
            .find(|m| matches!(m, Modelisation::Plate(t) if t.has_shear_strain() && !t.is_global()))
        {
            let at = kw.keyword("MODELE").map(|k| k.span).unwrap_or(call.span);
            let name = theory.name();
            return Err(ex.unsupported(
                &format!(
                    "{cmd} on a model with MODELISATION='{name}': code_aster's {name} plates have no non-linear options (RAPH_MECA, FULL_MECA); MECA_STATIQUE, MACRO_ELAS_MULT and the modal commands run them"
                ),
                at,
            ));
        }
    }
    let occurrences = kw.factor("COMPORTEMENT");
    for (k, b) in behaviours.iter().enumerate() {
        let on_shell = match &b.cells {
            None => model.cells.keys().any(|&c| is_structural(model, c)),
            Some(cells) => cells.iter().any(|&c| is_structural(model, c)),
        };
        if !on_shell {
            continue;
        }
        let occ = occurrences.get(k);
        let at = |key: &str| {
            occ.and_then(|o| o.keyword(key))
                .map(|k| k.span)
                .unwrap_or(call.span)
        };
        // The grids' own laws (GRILLE_ISOT_LINE, GRILLE_CINE_LINE) on grid
        // cells: `crate::fembridge`'s grid behaviours.
        let grid_law = matches!(
            b.relation,
            Relation::GrilleIsotLine | Relation::GrilleCineLine
        );
        let on_other = match &b.cells {
            None => model
                .cells
                .keys()
                .any(|&c| is_structural(model, c) && !is_grid(model, c)),
            Some(cells) => cells
                .iter()
                .any(|&c| is_structural(model, c) && !is_grid(model, c)),
        };
        if grid_law && on_other {
            return Err(ex.unsupported(
                &format!(
                    "{cmd}/COMPORTEMENT/RELATION='{}' on shell, beam or bar cells: it is a law of the reinforcement grids (GRILLE_MEMBRANE, GRILLE_EXCENTRE)",
                    b.relation.keyword()
                ),
                at("RELATION"),
            ));
        }
        if b.relation != Relation::Elas && !grid_law {
            return Err(ex.unsupported(
                &format!(
                    "{cmd}/COMPORTEMENT/RELATION other than ELAS on shell, beam, bar or grid cells (DKT, POU_D_E, POU_D_T, BARRE; GRILLE_* take GRILLE_ISOT_LINE and GRILLE_CINE_LINE too): they are linear elastic here"
                ),
                at("RELATION"),
            ));
        }
        if b.kinematics != Kinematics::Small {
            return Err(ex.unsupported(
                &format!(
                    "{cmd}/COMPORTEMENT/DEFORMATION other than PETIT on shell, beam or bar cells (DKT, POU_D_E, POU_D_T, BARRE): they are in small strains here"
                ),
                at("DEFORMATION"),
            ));
        }
    }
    Ok(())
}

/// The reference direction of each shell cell (`ANGL_REP`/`VECTEUR` of
/// `AFFE_CARA_ELEM/COQUE`; global X when absent).
fn directions(cara: Option<&CaraElem>) -> impl Fn(CellId) -> [f64; 3] {
    let mut direction: BTreeMap<CellId, [f64; 3]> = BTreeMap::new();
    if let Some(c) = cara {
        for s in &c.shells {
            for &cell in &s.cells {
                direction.insert(cell, s.direction);
            }
        }
    }
    move |cell| direction.get(&cell).copied().unwrap_or([1., 0., 0.])
}

/// `EFGE_ELGA` of the shells of `model`: NXX NYY NXY MXX MYY MXY QX QY at
/// the Gauss points, in the frame of each
/// cell's `AFFE_CARA_ELEM/COQUE` (global X projected on the facet by
/// default; on a COQUE_3D cell, on its plane at the first reduced point,
/// as code_aster stores its `SIEF_ELGA`).
pub(crate) fn efge_elga(
    model: &Model,
    cara: Option<&CaraElem>,
    u: &[f64],
    linear: bool,
    heat: &Heat,
) -> Result<Vec<CellValues>, aster_fem::FemError> {
    let direction = directions(cara);
    let at = if linear {
        EffortsAt::GaussLinear
    } else {
        EffortsAt::Gauss
    };
    let mut out = aster_fem::post::shell_efforts(model, u, &direction, at)?;
    subtract_thermal_efforts(model, heat, &mut out);
    out.extend(aster_fem::post::coque3d_efge(
        model,
        u,
        &direction,
        EffortsAt::Gauss,
    )?);
    Ok(out)
}

/// `SIEF_ELGA` of the `DKTG`/`Q4GG` facets of `model` (none without
/// them): their generalised efforts NXX … QY at the Gauss points in the
/// user's frame — `te0409`'s for a non-linear result (a DKTG's without
/// shear forces), `te0422`'s (`dxefgv`) for a linear one.
pub(crate) fn global_plate_sief(
    model: &Model,
    cara: Option<&CaraElem>,
    u: &[f64],
    linear: bool,
    (loads, t): (&aster_fem::Loads, f64),
) -> Result<Vec<CellValues>, aster_fem::FemError> {
    let global: std::collections::BTreeSet<CellId> = model
        .elements()
        .iter()
        .filter(|el| {
            matches!(&el.kind, aster_fem::ElementKind::Shell { theory, .. } if theory.is_global())
        })
        .map(|el| el.cell)
        .collect();
    if global.is_empty() {
        return Ok(Vec::new());
    }
    let mut v = efge_elga(model, cara, u, linear, &heat_at(loads, t)?)?;
    v.retain(|cv| global.contains(&cv.cell));
    Ok(v)
}

/// `DEGE_ELGA` (at the Gauss points) or `DEGE_ELNO` (`at_nodes`) of the
/// DKT/DKQ shells of `model`: EXX EYY EXY KXX KYY KXY GAX GAY in the user's
/// frame of each facet (`te0033`).
pub(crate) fn dege(
    model: &Model,
    cara: Option<&CaraElem>,
    u: &[f64],
    at_nodes: bool,
) -> Result<Vec<CellValues>, aster_fem::FemError> {
    aster_fem::post::shell_strains(model, u, &directions(cara), at_nodes)
}

/// `EFGE_ELNO` of the shells of `model` (DKT/DKQ facets and COQUE_3D
/// cells) at their nodes, in the user's frame of each cell (each node's on
/// a COQUE_3D), by code_aster's path for a linear (`MECA_STATIQUE`) or a
/// non-linear result ([`EffortsAt`]).
pub(crate) fn efge_elno(
    model: &Model,
    cara: Option<&CaraElem>,
    u: &[f64],
    linear: bool,
    heat: &Heat,
) -> Result<Vec<CellValues>, aster_fem::FemError> {
    let at = if linear {
        EffortsAt::NodesLinear
    } else {
        EffortsAt::NodesNonLinear
    };
    let direction = directions(cara);
    let mut out = aster_fem::post::shell_efforts(model, u, &direction, at)?;
    subtract_thermal_efforts(model, heat, &mut out);
    out.extend(aster_fem::post::coque3d_efge(model, u, &direction, at)?);
    Ok(out)
}

/// The stresses of the shells of `model` at one level through their
/// thickness, at their nodes (`SIGM_ELNO` of a sub-point, what
/// `POST_CHAMP/EXTR_COQUE` extracts), in the frame of `efge_elga`.
pub(crate) fn sigm_elno_at(
    model: &Model,
    cara: Option<&CaraElem>,
    u: &[f64],
    level: aster_fem::post::ShellLevel,
    heat: &Heat,
) -> Result<Vec<CellValues>, aster_fem::FemError> {
    let mut layers: BTreeMap<CellId, u32> = BTreeMap::new();
    if let Some(c) = cara {
        for s in &c.shells {
            for &cell in &s.cells {
                layers.insert(cell, s.layers);
            }
        }
    }
    let layers_of = |cell| layers.get(&cell).copied().unwrap_or(1);
    let mut out = aster_fem::post::shell_sigm_elno(model, u, &directions(cara), &layers_of, level)?;
    // dxsith: σ − E/(1 − ν) ε_th(z) on SIXX and SIYY at the level's height
    // (the sub-point of `layer` of COQUE_NCOU equal layers, as
    // `shell_sigm_elno` places it); isotropic, so in any frame.
    for cv in &mut out {
        let Some(p) = heat.get(&cv.cell) else {
            continue;
        };
        let Some(aster_fem::ElementKind::Shell {
            material, section, ..
        }) = model.element_kind(cv.cell)
        else {
            continue;
        };
        let h = section.thickness;
        let n = f64::from(layers_of(cv.cell).max(1));
        let z = -0.5 * h + h * (f64::from(level.layer - 1) + level.position) / n;
        let s = aster_fem::plate::thermal_stress(material, *p, z);
        for point in &mut cv.points {
            point[0] -= s;
            point[1] -= s;
        }
    }
    Ok(out)
}

/// The free strain through the thickness of each heated plate at one
/// instant ([`aster_fem::Load::ShellThermal`], a temperature of
/// `CREA_RESU/PREP_VARC`).
pub(crate) type Heat = BTreeMap<CellId, aster_fem::plate::ThicknessProfile>;

/// The [`Heat`] of `loads` at time t (empty without a temperature).
pub(crate) fn heat_at(loads: &aster_fem::Loads, t: f64) -> Result<Heat, aster_fem::FemError> {
    let mut out = Heat::new();
    for item in &loads.items {
        if let aster_fem::Load::ShellThermal { cell, .. } = item.load {
            if let std::collections::btree_map::Entry::Vacant(e) = out.entry(cell) {
                if let Some(p) = loads.shell_thermal_at(cell, t)? {
                    e.insert(p);
                }
            }
        }
    }
    Ok(out)
}

/// The efforts of heated plates without their thermal part (`dxefgv`:
/// EFFGT − `dxefgt`/`dxefnt`): N and M of [`aster_fem::plate::thermal_efforts`]
/// off NXX, NYY and MXX, MYY (isotropic in the plane, so in any frame).
fn subtract_thermal_efforts(model: &Model, heat: &Heat, out: &mut [CellValues]) {
    if heat.is_empty() {
        return;
    }
    for cv in out.iter_mut() {
        let Some(p) = heat.get(&cv.cell) else {
            continue;
        };
        let Some(aster_fem::ElementKind::Shell {
            material, section, ..
        }) = model.element_kind(cv.cell)
        else {
            continue;
        };
        let (n, m) = aster_fem::plate::thermal_efforts(material, section, *p);
        for point in &mut cv.points {
            point[0] -= n;
            point[1] -= n;
            point[3] -= m;
            point[4] -= m;
        }
    }
}
