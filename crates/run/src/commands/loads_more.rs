//! PESANTEUR, FORCE_ARETE and LIAISON_OBLIQUE of AFFE_CHAR_MECA (and the
//! last two of AFFE_CHAR_MECA_F): the keywords read into a
//! [`MechanicalLoad`]'s gravity, edge forces and linear relations.
//!
//! - `PESANTEUR=_F(GRAVITE=g, DIRECTION=d, GROUP_MA)`: code_aster's
//!   `cbpesa` keeps g and d/|d| (CHARGES2_53 when |d| is zero) on the
//!   cells of GROUP_MA, every cell without it; te0015 (3D) and te0085
//!   (D_PLAN, C_PLAN, AXIS) integrate ρ g dᵢ Nᵢ with the RIGI family, ρ the
//!   ELAS RHO of the cell (`rcvalb`, which stops when it is missing), and
//!   in AXIS only the axial component g d_y, times r. On DKT/DKQ shells
//!   te0032 loads ρ h g d per unit area (dxroep) on the translations,
//!   weighted as a constant pressure (dxtfor, dxqfor). aster turns it into
//!   a volume force per continuum cell, or a shell force per facet, at the
//!   solve, when the material field and the thicknesses are known
//!   (`fembridge`). POU_D_E beams (te0150), COQUE_3D shells, discrete and
//!   joint elements are refused at the keyword.
//! - `FORCE_ARETE=_F(GROUP_MA, FX…MZ)`: force and moment per unit length
//!   on the segments of a 3D model (solid edges: te0469, DKT edges:
//!   te0034, the segment's RIGI family; COQUE_3D edges: te0418, FPG4 on
//!   their SEG3, a SEG2 there refused as code_aster has no element for
//!   it), ∫ Nᵢ f dl in global components; moments on the nodes that carry
//!   rotations only.
//! - `FORCE_COQUE=_F(TOUT/GROUP_MA, FX…MZ | PRES, PLAN)`: force and
//!   moment per unit area on the shell cells of the selection (the others
//!   take none: code_aster computes it on the elements that have the
//!   option), global components or a pressure along −n; DKT/DKQ te0032
//!   (dxtfor, dxqfor: the nodal values weighted by the facet's areas;
//!   PLAN INF/SUP add the moment ±h/2 n × F), COQUE_3D te0403 (fsurf:
//!   interpolated at the normal points; PLAN has no effect there, moments
//!   are refused: `forsrg` is not reproduced). The local normal force F3
//!   is −PRES (both elements read it along n); the local F1 F2 MF1 MF2
//!   are refused.
//! - `LIAISON_OBLIQUE=_F(ANGL_NAUT, DX…DRZ)`: code_aster's `caliob`: the
//!   rotation of the nautical angles (`matrot`, degrees), and per node and
//!   component given one relation Σₖ R[i][k] uₖ = value over the
//!   translations (DX) or rotations (DRX) of the model's dimension, i the
//!   component's axis of the oblique frame.

use super::loads::{check_dof, real_value};
use crate::concept::*;
use crate::executor::Executor;
use crate::select;
use aster_eval::{ExecError, Keywords};
use aster_fem::EdgeRule;
use aster_mesh::{CellType, Mesh};

/// `PESANTEUR` (one occurrence): the gravity on the continuum cells of
/// its GROUP_MA (every cell of the model without it).
pub(super) fn pesanteur(
    ex: &Executor,
    kw: &Keywords,
    occ: &Keywords,
    (model, mesh): (&ModelDef, &Mesh),
) -> Result<Gravity, ExecError> {
    let what = "AFFE_CHAR_MECA/PESANTEUR";
    let g = occ
        .f64("GRAVITE")
        .ok_or_else(|| ex.kw_error(what, occ, "GRAVITE", "a real value is required"))?;
    let d: Vec<f64> = occ
        .simple("DIRECTION")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    let [dx, dy, dz] = d[..] else {
        return Err(ex.kw_error(what, occ, "DIRECTION", "three real values are required"));
    };
    let norm = (dx * dx + dy * dy + dz * dz).sqrt();
    if !(norm > f64::MIN_POSITIVE && norm.is_finite()) {
        return Err(ex.kw_error(
            what,
            occ,
            "DIRECTION",
            "the direction is zero (code_aster CHARGES2_53)",
        ));
    }
    let selected = if occ.contains("GROUP_MA") {
        select::cells(occ, mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?
    } else {
        model.cells.keys().copied().collect()
    };
    let span = occ
        .keyword("GROUP_MA")
        .or_else(|| kw.keyword("PESANTEUR"))
        .map(|k| k.span)
        .unwrap_or_default();
    for &c in &selected {
        let Some(m) = model.cells.get(&c) else {
            continue;
        };
        let structural = match m {
            Modelisation::BeamEuler => Some("POU_D_E beam (a mass per length ρA)"),
            Modelisation::BeamTimoshenko => Some("POU_D_T beam (a mass per length ρA)"),
            Modelisation::Bar => Some("BARRE bar (a mass per length ρA)"),
            Modelisation::Coque3d => Some("COQUE_3D shell (te0403's mass per area)"),
            Modelisation::Discrete2D | Modelisation::Discrete3D | Modelisation::DiscreteRot3D => {
                Some("discrete element (its CARA_ELEM mass)")
            }
            Modelisation::PlaneJoint => Some("joint element"),
            Modelisation::GridMembrane | Modelisation::GridExcentre => {
                Some("reinforcement grid (te0430's ρ·SECTION per area)")
            }
            _ => None,
        };
        if let Some(kind) = structural {
            return Err(ex.unsupported(
                &format!(
                    "{what} on cell {}, a {kind}: gravity is applied to continuum cells (3D, D_PLAN, C_PLAN, AXIS) and DKT shells only",
                    select::cell_name(mesh, c)
                ),
                span,
            ));
        }
    }
    let shells: Vec<_> = selected
        .iter()
        .copied()
        .filter(|c| matches!(model.cells.get(c), Some(Modelisation::Plate(_))))
        .collect();
    let mut cells = super::loads::continuum_cells(model, mesh, selected);
    cells.extend(shells);
    let at = kw
        .keyword("PESANTEUR")
        .and_then(|k| ex.location(k.span))
        .unwrap_or_else(|| "PESANTEUR".into());
    Ok(Gravity {
        cells,
        acceleration: [g * dx / norm, g * dy / norm, g * dz / norm],
        at,
    })
}

/// The components of FORCE_COQUE, in [`ShellForce`]'s order; the last
/// slot holds PRES, or F3 (its opposite: the local normal force) when
/// given ([`shell_comps`]).
pub(super) const SHELL_COMPS: [&str; 7] = ["FX", "FY", "FZ", "MX", "MY", "MZ", "PRES"];

/// The keyword of each slot of a FORCE_COQUE occurrence and the sign of
/// the last: PRES (1), or F3 (−1) when the occurrence gives it.
pub(super) fn shell_comps(occ: &Keywords) -> ([&'static str; 7], f64) {
    let mut keys = SHELL_COMPS;
    if occ.contains("F3") {
        keys[6] = "F3";
        return (keys, -1.0);
    }
    (keys, 1.0)
}

/// A `FORCE_COQUE` occurrence whose components `read` gives (a constant
/// or a function each): its shell cells and PLAN, checked.
pub(super) fn force_coque(
    ex: &Executor,
    what: &str,
    occ: &Keywords,
    (model, mesh): (&ModelDef, &Mesh),
    values: [f64; 7],
    functions: [Option<crate::concept::LoadFunction>; 7],
    normal_sign: f64,
) -> Result<ShellForce, ExecError> {
    let selected =
        select::cells(occ, mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?;
    let cells: Vec<_> = selected
        .into_iter()
        .filter(|c| {
            matches!(
                model.cells.get(c),
                Some(Modelisation::Plate(_) | Modelisation::Coque3d)
            )
        })
        .collect();
    let at = if occ.contains("TOUT") {
        "TOUT"
    } else {
        "GROUP_MA"
    };
    if cells.is_empty() {
        return Err(ex.kw_error(
            what,
            occ,
            at,
            "the selection has no shell cell (DKT, COQUE_3D): FORCE_COQUE loads shells only",
        ));
    }
    let moment = (3..6).find(|&k| values[k] != 0.0 || functions[k].is_some());
    if let Some(k) = moment {
        if let Some(&c) = cells
            .iter()
            .find(|c| model.cells.get(c) == Some(&Modelisation::Coque3d))
        {
            let span = occ
                .keyword(SHELL_COMPS[k])
                .map(|k| k.span)
                .unwrap_or_default();
            return Err(ex.unsupported(
                &format!(
                    "{what}/{} on COQUE_3D cell {} (te0403's moments per unit area, forsrg, are not reproduced; forces and pressures are)",
                    SHELL_COMPS[k],
                    select::cell_name(mesh, c)
                ),
                span,
            ));
        }
    }
    let plan = occ.str("PLAN").unwrap_or("MAIL");
    let plane = match plan {
        "INF" => -1.0,
        "SUP" => 1.0,
        _ => 0.0,
    };
    Ok(ShellForce {
        cells,
        values,
        functions,
        plane,
        section_plane: plan != "MAIL",
        normal_sign,
    })
}

/// A cell of several FORCE_COQUE occurrences keeps the last one's
/// (code_aster's load map: the last zone given for a cell holds).
pub(super) fn last_per_cell(mut shells: Vec<ShellForce>) -> Vec<ShellForce> {
    let mut seen = std::collections::HashSet::new();
    for s in shells.iter_mut().rev() {
        s.cells.retain(|c| seen.insert(*c));
    }
    shells.retain(|s| !s.cells.is_empty());
    shells
}

/// The components of FORCE_ARETE and the DOFs they load.
pub(super) const EDGE_COMPS: [(&str, CompName); 6] = [
    ("FX", "DX"),
    ("FY", "DY"),
    ("FZ", "DZ"),
    ("MX", "DRX"),
    ("MY", "DRY"),
    ("MZ", "DRZ"),
];

/// The segments of a `FORCE_ARETE` occurrence, checked: SEG2/SEG3 cells of
/// a 3D model whose nodes carry the components given (`given[k]`), each
/// with the Gauss family of the element code_aster puts on it: a segment
/// on the nodes of COQUE_3D cells is their SEG3 edge `MEBOCQ3` (te0418,
/// FPG4; code_aster's COQUE_3D has no SEG2 element), the others the
/// edges of solids or plates (te0469, te0034: the segment's RIGI family).
pub(super) fn edge_cells(
    ex: &Executor,
    what: &str,
    occ: &Keywords,
    (model, mesh, carried): (&ModelDef, &Mesh, &[bool]),
    given: [bool; 6],
) -> Result<Vec<(aster_mesh::CellId, EdgeRule)>, ExecError> {
    let cells = select::cells(occ, mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?;
    if cells.is_empty() {
        return Err(ex.kw_error(
            what,
            occ,
            "GROUP_MA",
            "give the edges (GROUP_MA of SEG2/SEG3 cells)",
        ));
    }
    if model.dim() != 3 {
        return Err(ex.kw_error(
            what,
            occ,
            "GROUP_MA",
            "FORCE_ARETE loads the edges of a 3D model (FORCE_CONTOUR in 2D)",
        ));
    }
    let coque3d_nodes: std::collections::HashSet<aster_mesh::NodeId> = model
        .cells
        .iter()
        .filter(|(_, m)| **m == Modelisation::Coque3d)
        .flat_map(|(c, _)| mesh.cell(*c).nodes.iter().copied())
        .collect();
    let mut out = Vec::with_capacity(cells.len());
    for &c in &cells {
        let cell = mesh.cell(c);
        if !matches!(cell.ty, CellType::SEG2 | CellType::SEG3) {
            return Err(ex.kw_error(
                what,
                occ,
                "GROUP_MA",
                format!(
                    "cell {} is a {}; FORCE_ARETE needs segments (SEG2, SEG3)",
                    select::cell_name(mesh, c),
                    cell.ty.name()
                ),
            ));
        }
        let rule = if cell.nodes.iter().any(|n| coque3d_nodes.contains(n)) {
            if cell.ty != CellType::SEG3 {
                return Err(ex.kw_error(
                    what,
                    occ,
                    "GROUP_MA",
                    format!(
                        "cell {} is a SEG2 on the nodes of COQUE_3D cells; their edges are SEG3 cells (code_aster's MEBOCQ3)",
                        select::cell_name(mesh, c)
                    ),
                ));
            }
            EdgeRule::Gauss4
        } else {
            EdgeRule::Segment
        };
        for &n in &cell.nodes {
            for (k, (_, comp)) in EDGE_COMPS.iter().enumerate() {
                if given[k] {
                    check_dof(model, mesh, carried, n, comp, what)?;
                }
            }
        }
        out.push((c, rule));
    }
    Ok(out)
}

/// `AFFE_CHAR_MECA/FORCE_ARETE` (one occurrence).
pub(super) fn force_arete(
    ex: &Executor,
    occ: &Keywords,
    ctx: (&ModelDef, &Mesh, &[bool]),
) -> Result<EdgeForce, ExecError> {
    let what = "AFFE_CHAR_MECA/FORCE_ARETE";
    let mut force = [0.0; 6];
    for (k, (key, _)) in EDGE_COMPS.iter().enumerate() {
        if let Some(v) = real_value(ex, what, occ, key)? {
            force[k] = v;
        }
    }
    let given = force.map(|v| v != 0.0);
    let cells = edge_cells(ex, what, occ, ctx, given)?;
    Ok(EdgeForce {
        cells,
        force,
        functions: Default::default(),
    })
}

/// The rows of the rotation of `ANGL_NAUT` (degrees; missing angles 0):
/// the oblique frame's axes in global coordinates (code_aster's `matrot`).
fn oblique_frame(ex: &Executor, what: &str, occ: &Keywords) -> Result<[[f64; 3]; 3], ExecError> {
    let angles: Vec<f64> = occ
        .simple("ANGL_NAUT")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    if angles.is_empty() || angles.len() > 3 {
        return Err(ex.kw_error(what, occ, "ANGL_NAUT", "one to three angles (degrees)"));
    }
    let mut a = [0.0; 3];
    for (k, v) in angles.iter().enumerate() {
        a[k] = v.to_radians();
    }
    Ok(aster_fem::orthotropic::matrot(a))
}

/// One `LIAISON_OBLIQUE` occurrence: for each component given (its key
/// and value — the value of AFFE_CHAR_MECA, or 1 for AFFE_CHAR_MECA_F,
/// whose function then scales the right-hand side), one relation per node.
pub(super) fn liaison_oblique(
    ex: &Executor,
    what: &str,
    occ: &Keywords,
    (model, mesh, carried): (&ModelDef, &Mesh, &[bool]),
    components: &[(&str, f64)],
) -> Result<Vec<(String, LinearRelation)>, ExecError> {
    let frame = oblique_frame(ex, what, occ)?;
    let nodes =
        select::nodes_without(occ, mesh).map_err(|e| ExecError::new(format!("{what}: {e}")))?;
    let dim = model.dim();
    let mut out = Vec::new();
    for &(key, value) in components {
        let (axis, comps): (usize, [CompName; 3]) = match key {
            "DX" => (0, ["DX", "DY", "DZ"]),
            "DY" => (1, ["DX", "DY", "DZ"]),
            "DZ" => (2, ["DX", "DY", "DZ"]),
            "DRX" => (0, ["DRX", "DRY", "DRZ"]),
            "DRY" => (1, ["DRX", "DRY", "DRZ"]),
            "DRZ" => (2, ["DRX", "DRY", "DRZ"]),
            _ => continue,
        };
        let direction = frame[axis];
        for &n in &nodes {
            let mut terms = Vec::new();
            for (k, &comp) in comps.iter().enumerate().take(dim) {
                if direction[k] == 0.0 {
                    continue;
                }
                check_dof(model, mesh, carried, n, comp, what)?;
                terms.push((n, comp, direction[k]));
            }
            if terms.is_empty() {
                return Err(ex.kw_error(
                    what,
                    occ,
                    "ANGL_NAUT",
                    format!(
                        "the oblique axis of {key} has no component in the {dim}D model's plane"
                    ),
                ));
            }
            out.push((key.to_string(), LinearRelation { terms, rhs: value }));
        }
    }
    Ok(out)
}
