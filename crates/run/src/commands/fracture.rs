//! Fracture mechanics: `DEFI_FOND_FISS` (a crack front) and `CALC_G`
//! (G and K1, K2 by the theta method), in 2D, as code_aster computes them
//! (aster-fem `fracture`).
//!
//! - `DEFI_FOND_FISS` in 2D: the crack tip is the one node of
//!   `FOND_FISS/GROUP_NO`; the crack direction (code_aster's `BASEFOND`)
//!   is the unit vector from the other corner of the `LEVRE_SUP` segment
//!   that holds the tip to the tip (code_aster derives it from the cells
//!   around the tip; the two agree for a crack whose lip is straight at the
//!   tip); the cell size at the tip (`FOND.TAILLE_R`) as `fonno7`, for the
//!   default crown R_INF = 2 h, R_SUP = 4 h. 3D fronts (`GROUP_MA`, several
//!   nodes) are refused.
//! - `CALC_G(RESULTAT, THETA=_F(FISSURE, R_INF, R_SUP), OPTION='G'|'K')`:
//!   per stored instant, a row of `NUME_ORDRE`, `INST`, `NOEUD`,
//!   `COOR_X`, `COOR_Y` and `G` (option `G`) or `K1`, `K2`, `G_IRWIN`
//!   (option `K`), doubled (K2 = 0) for a symmetric crack (`SYME='OUI'`).
//!   Linear elastic plane models (`D_PLAN`, `C_PLAN`) only; loads applied
//!   where theta is not zero, plastic results, 3D and axisymmetric models
//!   are refused before the integral is computed.

use crate::concept::{Concept, EvolResult};
use crate::executor::{store_result, Executor};
use crate::support::{Support, Values};
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_fem::dof::{Comp, Dof};
use aster_fem::fracture::{self, CrackTip, PlaneCell};
use aster_fem::loads::Load;
use aster_fem::{ElementKind, Model};
use aster_mesh::{Mesh, NodeId};
use std::rc::Rc;

/// A 2D crack front as `DEFI_FOND_FISS` defines it.
#[derive(Clone, Debug)]
pub struct CrackFront {
    /// The mesh's concept id.
    pub mesh: u32,
    pub node: NodeId,
    pub node_name: String,
    pub tip: CrackTip,
    /// `SYME='OUI'`: only one half of a symmetric crack is meshed.
    pub symmetric: bool,
    /// The cell size at the tip (`fonno7`).
    pub size: f64,
}

/// What DEFI_FOND_FISS reads (`crate::support`).
pub(crate) const DEFI_FOND_FISS: Support = Support {
    values: &[Values::new("CONFIG_INIT", &["COLLEE"])
        .why("(a crack open in the initial state, NORMALE): only cracks whose lips touch")],
    ..Support::keywords(&[
        "MAILLAGE",
        "INFO",
        "FOND_FISS",
        "FOND_FISS/GROUP_NO",
        "FOND_FISS/TYPE_FOND",
        "SYME",
        "LEVRE_SUP",
        "LEVRE_SUP/GROUP_MA",
        "LEVRE_INF",
        "LEVRE_INF/GROUP_MA",
        "CONFIG_INIT",
        "PREC_NORM",
    ])
};

pub fn defi_fond_fiss(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let cmd = "DEFI_FOND_FISS";
    let mesh_ref = ex.required(cmd, kw, "MAILLAGE")?;
    let mesh = ex.mesh(mesh_ref)?;
    let mesh_id = mesh_ref.id;
    if mesh.dim != 2 {
        return Err(ex.unsupported(
            "DEFI_FOND_FISS of a 3D crack front (aster computes G and K in 2D only)",
            call.span,
        ));
    }
    let fronts = kw.factor("FOND_FISS");
    let [front] = fronts else {
        return Err(ex.unsupported(
            "DEFI_FOND_FISS with two FOND_FISS occurrences (one 2D crack tip only)",
            call.span,
        ));
    };
    let nodes = crate::select::nodes(front, &mesh, "")
        .map_err(|e| ex.kw_error(cmd, front, "GROUP_NO", e))?;
    let [node] = nodes[..] else {
        return Err(ex.kw_error(
            cmd,
            front,
            "GROUP_NO",
            format!(
                "a 2D crack front is one node; the groups give {}",
                nodes.len()
            ),
        ));
    };
    let p = mesh.coord(node);
    let tip = [p[0], p[1]];
    let Some(sup) = kw.factor("LEVRE_SUP").first() else {
        return Err(ExecError::new(format!("{cmd}: LEVRE_SUP is required")));
    };
    let mut lip_cells = Vec::new();
    for g in sup.simple("GROUP_MA").iter().filter_map(|s| s.as_str()) {
        let cells =
            crate::select::group_ma(&mesh, g).map_err(|e| ex.kw_error(cmd, sup, "GROUP_MA", e))?;
        lip_cells.extend_from_slice(cells);
    }
    // The lip segment at the tip: its other corner.
    let mut dir = None;
    for &c in &lip_cells {
        let cell = mesh.cell(c);
        if cell.ty.dim() != 1 || !cell.nodes.contains(&node) {
            continue;
        }
        let corners = &cell.nodes[..2];
        let other = if corners[0] == node {
            corners[1]
        } else if corners[1] == node {
            corners[0]
        } else {
            continue;
        };
        let q = mesh.coord(other);
        let v = [tip[0] - q[0], tip[1] - q[1]];
        let n = (v[0] * v[0] + v[1] * v[1]).sqrt();
        if n > 0.0 {
            dir = Some([v[0] / n, v[1] / n]);
        }
        break;
    }
    let Some(dir) = dir else {
        return Err(ex.kw_error(
            cmd,
            sup,
            "GROUP_MA",
            format!(
                "no segment of the upper lip ends at the crack tip `{}`: aster takes the crack direction from it",
                node_name(&mesh, node)
            ),
        ));
    };
    let size = tip_size(&mesh, node, dir);
    let front = CrackFront {
        mesh: mesh_id,
        node,
        node_name: node_name(&mesh, node),
        tip: CrackTip { tip, dir },
        symmetric: kw.str("SYME") == Some("OUI"),
        size,
    };
    store_result(ex, call, Concept::CrackFront(Rc::new(front)))
}

fn node_name(mesh: &Mesh, n: NodeId) -> String {
    mesh.node_names
        .get(n.0 as usize)
        .cloned()
        .unwrap_or_else(|| format!("N{}", n.0 + 1))
}

/// `fonno7`: the vectors from the tip along the corner edges of the 2D
/// cells that hold it.
fn tip_size(mesh: &Mesh, node: NodeId, dir: [f64; 2]) -> f64 {
    let p = mesh.coord(node);
    let mut edges = Vec::new();
    for cell in &mesh.cells {
        if cell.ty.dim() != 2 || !cell.nodes.contains(&node) {
            continue;
        }
        let nc = aster_fem::shape::corner_count(cell.ty);
        let corners = &cell.nodes[..nc.min(cell.nodes.len())];
        for (i, &a) in corners.iter().enumerate() {
            let b = corners[(i + 1) % corners.len()];
            let other = if a == node {
                b
            } else if b == node {
                a
            } else {
                continue;
            };
            let q = mesh.coord(other);
            edges.push([q[0] - p[0], q[1] - p[1]]);
        }
    }
    fracture::tip_cell_size(&edges, dir)
}

const CALC_G_OWN: &[&str] = &[
    "RESULTAT",
    "THETA",
    "THETA/FISSURE",
    "THETA/R_INF",
    "THETA/R_SUP",
    "OPTION",
    "INFO",
    "TITRE",
];

/// What CALC_G reads (`crate::support`): its own keywords and the step
/// selection ([`super::post::STEP_SELECTION`]).
pub(crate) const CALC_G: Support = Support {
    values: &[Values::listed("OPTION", &["G", "K"])],
    ..Support::keywords(&crate::support::joined::<
        _,
        { super::post::STEP_SELECTION.len() + CALC_G_OWN.len() },
    >(super::post::STEP_SELECTION, CALC_G_OWN))
};

pub fn calc_g(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let cmd = "CALC_G";
    let Some(theta_kw) = kw.factor("THETA").first() else {
        return Err(ExecError::new("CALC_G: THETA is required"));
    };
    let front = ex.crack_front(ex.required(cmd, theta_kw, "FISSURE")?)?;
    let r = ex.required(cmd, kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let Some(run) = result.fem.clone() else {
        return Err(ex.unsupported(
            "CALC_G on a result not computed in this run (its model and materials are needed)",
            kw.keyword("RESULTAT").map(|k| k.span).unwrap_or(call.span),
        ));
    };
    let model = &run.model;
    let here = kw.keyword("RESULTAT").map(|k| k.span).unwrap_or(call.span);
    if run.plastic {
        return Err(ex.unsupported(
            "CALC_G on a result with plastic cells (aster computes G of linear elastic results only)",
            here,
        ));
    }
    if model.mesh().dim != 2 || ex.mesh_by_id(front.mesh)?.node_count() != model.mesh().node_count()
    {
        return Err(ex.unsupported(
            "CALC_G: the crack front and the result are not on the same 2D mesh",
            here,
        ));
    }
    let (r_inf, r_sup) = match (theta_kw.f64("R_INF"), theta_kw.f64("R_SUP")) {
        (Some(a), Some(b)) => {
            if a < 0.0 || a >= b {
                return Err(ex.kw_error(
                    cmd,
                    theta_kw,
                    "R_INF",
                    format!("R_INF = {a} and R_SUP = {b}: give 0 ≤ R_INF < R_SUP"),
                ));
            }
            (a, b)
        }
        _ => (2.0 * front.size, 4.0 * front.size),
    };
    let mesh = model.mesh();
    let nodes: Vec<[f64; 2]> = mesh.coords.iter().map(|p| [p[0], p[1]]).collect();
    let mut theta = fracture::theta_field(&front.tip, &nodes, r_inf, r_sup);
    theta[front.node.0 as usize] = front.tip.dir;
    check_loads(ex, &run, &theta, here)?;
    let options: Vec<String> = kw
        .simple("OPTION")
        .iter()
        .filter_map(|s| s.as_str().map(str::to_string))
        .collect();
    let steps = super::post::select_steps(ex, cmd, kw, &result)?;
    let mut columns = vec![
        col("NUME_ORDRE", ColumnType::Int),
        col("INST", ColumnType::Real),
        col("NOEUD", ColumnType::Text(8)),
        col("COOR_X", ColumnType::Real),
        col("COOR_Y", ColumnType::Real),
    ];
    if options.iter().any(|o| o == "G") {
        columns.push(col("G", ColumnType::Real));
    }
    if options.iter().any(|o| o == "K") {
        for c in ["K1", "K2", "G_IRWIN"] {
            columns.push(col(c, ColumnType::Real));
        }
    }
    let mut table = Table::new(columns);
    for step in steps {
        let u = displacement(&result, &run, step.nume_ordre, &r.name)?;
        let disp = nodal_displacement(model, &u);
        let with_k = options.iter().any(|o| o == "K");
        let mut cells = plane_cells(model, &nodes, &disp, &theta, with_k)
            .map_err(|e| ex.unsupported(&format!("CALC_G: {e}"), here))?;
        for (cell, c) in &mut cells {
            c.free_strain = run
                .loads
                .free_strain_at(*cell, step.inst)
                .map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
        }
        let cells: Vec<OwnedCell> = cells.into_iter().map(|(_, c)| c).collect();
        let views: Vec<PlaneCell> = cells
            .iter()
            .map(|c| PlaneCell {
                ty: c.ty,
                coords: &c.coords,
                disp: &c.disp,
                theta: &c.theta,
                material: c.material,
                hyp: c.hyp,
                free_strain: c.free_strain.as_deref(),
            })
            .collect();
        let mut row = vec![
            ("NUME_ORDRE", Value::Int(step.nume_ordre as i64)),
            ("INST", Value::Real(step.inst)),
            ("NOEUD", Value::Text(front.node_name.clone())),
            ("COOR_X", Value::Real(front.tip.tip[0])),
            ("COOR_Y", Value::Real(front.tip.tip[1])),
        ];
        let factor = if front.symmetric { 2.0 } else { 1.0 };
        if options.iter().any(|o| o == "G") {
            let g = fracture::g_theta(&views).map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
            row.push(("G", Value::Real(factor * g)));
        }
        if options.iter().any(|o| o == "K") {
            let k = fracture::k_theta(&views, &front.tip)
                .map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
            let (fic1, fic2, k1, k2) = if front.symmetric {
                (2.0 * k.fic1, 0.0, 2.0 * k.k1, 0.0)
            } else {
                (k.fic1, k.fic2, k.k1, k.k2)
            };
            row.push(("K1", Value::Real(k1)));
            row.push(("K2", Value::Real(k2)));
            row.push(("G_IRWIN", Value::Real(fic1 * fic1 + fic2 * fic2)));
        }
        table.push_row(row);
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

fn col(name: &str, ty: ColumnType) -> Column {
    Column {
        name: name.to_string(),
        ty,
    }
}

fn nonzero(t: [f64; 2]) -> bool {
    t[0].abs() + t[1].abs() >= f64::EPSILON
}

/// Loads where theta is not zero enter code_aster's G (`te0096`'s force
/// terms, `te0282` on edges) and are not computed here: refused.
fn check_loads(
    ex: &Executor,
    run: &crate::fembridge::FemRun,
    theta: &[[f64; 2]],
    here: aster_syntax::Span,
) -> Result<(), ExecError> {
    let mesh = run.model.mesh();
    let on_cell = |c: aster_mesh::CellId| {
        mesh.cell(c)
            .nodes
            .iter()
            .any(|n| nonzero(theta[n.0 as usize]))
    };
    for item in &run.loads.items {
        let hit = match &item.load {
            Load::SurfaceForce { cell, .. }
            | Load::Pressure { cell, .. }
            | Load::VolumeForce { cell, .. }
            | Load::SurfaceForceAt { cell, .. }
            | Load::PressureAt { cell, .. }
            | Load::VolumeForceAt { cell, .. } => on_cell(*cell).then(|| mesh.cell_name(*cell)),
            Load::NodalForce { dof, .. } => nonzero(theta[dof.node.0 as usize])
                .then(|| format!("node {}", node_name(mesh, dof.node))),
            _ => None,
        };
        if let Some(place) = hit {
            return Err(ex.unsupported(
                &format!(
                    "CALC_G with a load inside the theta crown (on {place}): the terms of the loads in G are not computed, narrow R_SUP"
                ),
                here,
            ));
        }
    }
    Ok(())
}

struct OwnedCell {
    free_strain: Option<Vec<f64>>,
    ty: aster_mesh::CellType,
    coords: Vec<[f64; 2]>,
    disp: Vec<[f64; 2]>,
    theta: Vec<[f64; 2]>,
    material: aster_fem::Elastic,
    hyp: aster_fem::Hypothesis,
}

fn plane_cells(
    model: &Model,
    nodes: &[[f64; 2]],
    disp: &[[f64; 2]],
    theta: &[[f64; 2]],
    with_k: bool,
) -> Result<Vec<(aster_mesh::CellId, OwnedCell)>, String> {
    let mesh = model.mesh();
    let mut out = Vec::new();
    for el in model.elements() {
        let cell = mesh.cell(el.cell);
        let reached = cell.nodes.iter().any(|n| nonzero(theta[n.0 as usize]));
        match &el.kind {
            ElementKind::Continuum {
                hypothesis,
                material,
            } => {
                if !reached {
                    continue;
                }
                let axis = *hypothesis == aster_fem::Hypothesis::Axisymmetric;
                if !(matches!(
                    hypothesis,
                    aster_fem::Hypothesis::PlaneStrain | aster_fem::Hypothesis::PlaneStress
                ) || axis && !with_k)
                {
                    return Err(format!(
                        "OPTION='K' of {} cells (G in D_PLAN, C_PLAN and AXIS; K in D_PLAN and C_PLAN only)",
                        hypothesis.aster_name()
                    ));
                }
                if model.is_reduced(el.cell) || model.is_stabilised(el.cell) {
                    return Err(format!(
                        "cell {} is under-integrated: G with the full stiffness family only",
                        mesh.cell_name(el.cell)
                    ));
                }
                let idx = |f: &[[f64; 2]]| cell.nodes.iter().map(|n| f[n.0 as usize]).collect();
                out.push((
                    el.cell,
                    OwnedCell {
                        free_strain: None,
                        ty: cell.ty,
                        coords: idx(nodes),
                        disp: idx(disp),
                        theta: idx(theta),
                        material: *material,
                        hyp: *hypothesis,
                    },
                ));
            }
            ElementKind::Boundary => {}
            _ if reached => {
                return Err(format!(
                    "cell {} is not a continuum cell and theta reaches it",
                    mesh.cell_name(el.cell)
                ))
            }
            _ => {}
        }
    }
    Ok(out)
}

fn nodal_displacement(model: &Model, u: &[f64]) -> Vec<[f64; 2]> {
    let dofs = model.dofs();
    (0..model.mesh().node_count())
        .map(|i| {
            let n = NodeId(i as u32);
            [
                dofs.value(u, Dof::new(n, Comp::DX)).unwrap_or(0.0),
                dofs.value(u, Dof::new(n, Comp::DY)).unwrap_or(0.0),
            ]
        })
        .collect()
}

/// The displacement (per DOF of the model) of a result at a NUME_ORDRE.
fn displacement(
    result: &EvolResult,
    run: &crate::fembridge::FemRun,
    order: u32,
    name: &str,
) -> Result<Vec<f64>, ExecError> {
    if let Some(step) = run.raw.by_order(order as usize) {
        return Ok(step.displacement.clone());
    }
    let step = result
        .step_numbered(order)
        .ok_or_else(|| ExecError::new(format!("CALC_G: no NUME_ORDRE {order} in `{name}`")))?;
    match super::post::step_field(step, "DEPL", name)? {
        crate::field::Field::Nodal(depl) => {
            Ok(crate::fembridge::displacement_from(&run.model, depl))
        }
        _ => Err(ExecError::new(format!(
            "CALC_G: DEPL of `{name}` is not a nodal field"
        ))),
    }
}
