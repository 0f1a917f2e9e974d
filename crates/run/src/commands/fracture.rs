//! Fracture mechanics: `DEFI_FOND_FISS` (a crack front), `CALC_G`
//! (G and K1, K2 by the theta method, in 2D) and `POST_K1_K2_K3` (K1, K2,
//! K3 along a 3D front from the lips' displacement jump), as code_aster
//! computes them (aster-fem `fracture`, `fracture::front3d`,
//! `fracture::post_k`).
//!
//! - `DEFI_FOND_FISS` in 2D: the crack tip is the one node of
//!   `FOND_FISS/GROUP_NO`; the crack direction (code_aster's `BASEFOND`)
//!   is the unit vector from the other corner of the `LEVRE_SUP` segment
//!   that holds the tip to the tip (code_aster derives it from the cells
//!   around the tip; the two agree for a crack whose lip is straight at the
//!   tip); the cell size at the tip (`FOND.TAILLE_R`) as `fonno7`, for the
//!   default crown R_INF = 2 h, R_SUP = 4 h.
//! - `DEFI_FOND_FISS` in 3D: a front of SEG2 or SEG3 segments
//!   (`FOND_FISS/GROUP_MA`) from `GROUP_NO_ORIG`, both lips given
//!   (`SYME='NON'`): its nodes, basis, sizes and normal lip nodes
//!   (`fracture::front3d`).
//! - `CALC_G(RESULTAT, THETA=_F(FISSURE, R_INF, R_SUP), OPTION='G'|'K')`:
//!   per stored instant, a row of `NUME_ORDRE`, `INST`, `NOEUD`,
//!   `COOR_X`, `COOR_Y` and `G` (option `G`) or `K1`, `K2`, `G_IRWIN`
//!   (option `K`), doubled (K2 = 0) for a symmetric crack (`SYME='OUI'`).
//!   Linear elastic plane models (`D_PLAN`, `C_PLAN`) only; loads applied
//!   where theta is not zero, plastic results, 3D fronts and axisymmetric
//!   models are refused before the integral is computed.
//! - `POST_K1_K2_K3(FOND_FISS, RESULTAT)` on a 3D front, regular mesh
//!   (`TYPE_MAILLAGE='REGLE'`): one row per front node and instant
//!   (`fracture::post_k`), every other front node on a mesh with quadratic
//!   cells.

use crate::concept::{Concept, EvolResult};
use crate::executor::{store_result, Executor};
use crate::support::{Support, Values};
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_fem::dof::{Comp, Dof};
use aster_fem::fracture::front3d::{define_front, Front3d, FrontInput};
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
    /// A 3D front (`FOND_FISS/GROUP_MA`): its nodes, bases, sizes and
    /// normal lip nodes; the 2D fields above then hold its first node.
    pub line: Option<Rc<Front3d>>,
}

/// What DEFI_FOND_FISS reads (`crate::support`).
pub(crate) const DEFI_FOND_FISS: Support = Support {
    values: &[
        Values::new("CONFIG_INIT", &["COLLEE"])
            .why("(a crack open in the initial state, NORMALE): only cracks whose lips touch"),
        Values::new("FOND_FISS/TYPE_FOND", &["OUVERT"])
            .why("(a closed 3D front, FERME): open fronts only"),
    ],
    ..Support::keywords(&[
        "MAILLAGE",
        "INFO",
        "FOND_FISS",
        "FOND_FISS/GROUP_NO",
        "FOND_FISS/GROUP_MA",
        "FOND_FISS/GROUP_NO_ORIG",
        "FOND_FISS/GROUP_NO_EXTR",
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
    if mesh.dim == 3 {
        return defi_fond_fiss_3d(ex, call, &mesh, mesh_id);
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
                mesh.node_name(node)
            ),
        ));
    };
    let size = tip_size(&mesh, node, dir);
    let front = CrackFront {
        mesh: mesh_id,
        node,
        node_name: mesh.node_name(node),
        tip: CrackTip { tip, dir },
        symmetric: kw.str("SYME") == Some("OUI"),
        size,
        line: None,
    };
    store_result(ex, call, Concept::CrackFront(Rc::new(front)))
}

/// The cells of the `GROUP_MA` groups of an occurrence.
fn occurrence_cells(
    ex: &Executor,
    cmd: &str,
    occ: &aster_eval::Keywords,
    mesh: &Mesh,
) -> Result<Vec<aster_mesh::CellId>, ExecError> {
    let mut cells = Vec::new();
    for g in occ.simple("GROUP_MA").iter().filter_map(|s| s.as_str()) {
        let c =
            crate::select::group_ma(mesh, g).map_err(|e| ex.kw_error(cmd, occ, "GROUP_MA", e))?;
        cells.extend_from_slice(c);
    }
    Ok(cells)
}

/// The one node of a node-group keyword.
fn one_node(
    ex: &Executor,
    cmd: &str,
    occ: &aster_eval::Keywords,
    key: &str,
    mesh: &Mesh,
) -> Result<Option<NodeId>, ExecError> {
    let Some(g) = occ.str(key) else {
        return Ok(None);
    };
    let nodes = crate::select::group_no(mesh, g).map_err(|e| ex.kw_error(cmd, occ, key, e))?;
    match nodes {
        [n] => Ok(Some(*n)),
        _ => Err(ex.kw_error(
            cmd,
            occ,
            key,
            format!("the group `{g}` has {} nodes, one expected", nodes.len()),
        )),
    }
}

/// DEFI_FOND_FISS on a 3D mesh: a front of segments (`FOND_FISS/GROUP_MA`)
/// from `GROUP_NO_ORIG`, both lips meshed (aster-fem `fracture::front3d`).
fn defi_fond_fiss_3d(
    ex: &mut Executor,
    call: &CommandCall,
    mesh: &Mesh,
    mesh_id: u32,
) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let cmd = "DEFI_FOND_FISS";
    let fronts = kw.factor("FOND_FISS");
    let [front] = fronts else {
        return Err(ex.unsupported(
            "DEFI_FOND_FISS with two FOND_FISS occurrences (one front only)",
            call.span,
        ));
    };
    if !front.contains("GROUP_MA") {
        return Err(ex.unsupported(
            "DEFI_FOND_FISS of a 3D front given by its nodes (GROUP_NO): aster reads a front of segments (GROUP_MA)",
            call.span,
        ));
    }
    if kw.str("SYME") == Some("OUI") {
        return Err(ex.unsupported(
            "DEFI_FOND_FISS of a 3D front with SYME='OUI' (both lips meshed only)",
            call.span,
        ));
    }
    let segments = occurrence_cells(ex, cmd, front, mesh)?;
    let Some(origin) = one_node(ex, cmd, front, "GROUP_NO_ORIG", mesh)? else {
        return Err(ex.unsupported(
            "DEFI_FOND_FISS of a 3D front without GROUP_NO_ORIG (aster does not pick the origin itself)",
            call.span,
        ));
    };
    let end = one_node(ex, cmd, front, "GROUP_NO_EXTR", mesh)?;
    let (Some(sup), Some(inf)) = (
        kw.factor("LEVRE_SUP").first(),
        kw.factor("LEVRE_INF").first(),
    ) else {
        return Err(ex.unsupported(
            "DEFI_FOND_FISS of a 3D front without both lips (LEVRE_SUP, LEVRE_INF): aster builds the front's basis from them",
            call.span,
        ));
    };
    let lip_sup = occurrence_cells(ex, cmd, sup, mesh)?;
    let lip_inf = occurrence_cells(ex, cmd, inf, mesh)?;
    let input = FrontInput {
        mesh,
        segments: &segments,
        origin,
        end,
        lip_sup: &lip_sup,
        lip_inf: &lip_inf,
        prec_norm: kw.f64("PREC_NORM").unwrap_or(0.1),
    };
    let line =
        define_front(&input).map_err(|e| ex.unsupported(&format!("{cmd}: {e}"), call.span))?;
    let first = line.nodes[0];
    let p = mesh.coord(first);
    let crack = CrackFront {
        mesh: mesh_id,
        node: first,
        node_name: mesh.node_name(first),
        tip: CrackTip {
            tip: [p[0], p[1]],
            dir: [line.dir[0][0], line.dir[0][1]],
        },
        symmetric: false,
        size: line.size[0],
        line: Some(Rc::new(line)),
    };
    store_result(ex, call, Concept::CrackFront(Rc::new(crack)))
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
    "THETA/DISCRETISATION",
    "THETA/DEGRE",
    "THETA/NB_POINT_FOND",
    "OPTION",
    "INFO",
    "TITRE",
];

/// What CALC_G reads (`crate::support`): its own keywords and the step
/// selection ([`super::post::STEP_SELECTION`]).
pub(crate) const CALC_G: Support = Support {
    values: &[
        Values::listed("OPTION", &["G", "K"]),
        Values::listed("THETA/DISCRETISATION", &["LINEAIRE", "LEGENDRE"]),
    ],
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
    if let Some(line) = front.line.clone() {
        return calc_g_3d(ex, call, theta_kw, &line);
    }
    if let Some(k) = theta_kw.keyword("NB_POINT_FOND") {
        return Err(ex.unsupported(
            "CALC_G THETA/NB_POINT_FOND on a 2D crack tip (points along a 3D front only)",
            k.span,
        ));
    }
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
    let (r_inf, r_sup) = crown(ex, theta_kw, front.size)?;
    let mesh = model.mesh();
    let nodes: Vec<[f64; 2]> = mesh.coords.iter().map(|p| [p[0], p[1]]).collect();
    let mut theta = fracture::theta_field(&front.tip, &nodes, r_inf, r_sup);
    theta[front.node.0 as usize] = front.tip.dir;
    check_loads(ex, &run, &|n: NodeId| nonzero(theta[n.0 as usize]), here)?;
    let options = options(kw);
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
    // G doubled for SYME='OUI' (K below). AXIS: the integral is per radian;
    // code_aster 17 divides it by the front's radius (`cgComputeGtheta`:
    // "Cas axis, on normalise par 1/R", R the first coordinate of the front
    // point in BASLOC).
    let mut factor = if front.symmetric { 2.0 } else { 1.0 };
    if model.hypothesis() == Some(aster_fem::Hypothesis::Axisymmetric) {
        let r = front.tip.tip[0];
        if r.abs() < f64::EPSILON {
            return Err(ex.unsupported(
                "CALC_G on an AXIS model with the crack tip on the axis (code_aster divides G by the tip's radius, here 0)",
                here,
            ));
        }
        factor /= r;
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

/// The theta crown (`THETA/R_INF`, `R_SUP`), by default 2 h and 4 h of
/// the cell size `h` at the front (code_aster's largest `FOND.TAILLE_R`).
fn crown(ex: &Executor, theta_kw: &aster_eval::Keywords, h: f64) -> Result<(f64, f64), ExecError> {
    match (theta_kw.f64("R_INF"), theta_kw.f64("R_SUP")) {
        (Some(a), Some(b)) => {
            if a < 0.0 || a >= b {
                return Err(ex.kw_error(
                    "CALC_G",
                    theta_kw,
                    "R_INF",
                    format!("R_INF = {a} and R_SUP = {b}: give 0 ≤ R_INF < R_SUP"),
                ));
            }
            Ok((a, b))
        }
        _ => Ok((2.0 * h, 4.0 * h)),
    }
}

/// The options of CALC_G, in the order given.
fn options(kw: &aster_eval::Keywords) -> Vec<String> {
    kw.simple("OPTION")
        .iter()
        .filter_map(|s| s.as_str().map(str::to_string))
        .collect()
}

/// CALC_G on a 3D front (aster-fem `fracture::theta3d`): OPTION='K' with
/// one theta field per front node (`DISCRETISATION='LINEAIRE'`), a row per
/// front node and step: `NUME_ORDRE`, `INST`, `NOEUD`, `NUM_PT`, `COOR_X`,
/// `COOR_Y`, `COOR_Z`, `ABSC_CURV`, `ABSC_CURV_NORM`, `COMPORTEMENT`, `K1`,
/// `K2`, `K3`, `G_IRWIN` (code_aster 17's `cgTable`).
fn calc_g_3d(
    ex: &mut Executor,
    call: &CommandCall,
    theta_kw: &aster_eval::Keywords,
    line: &Front3d,
) -> Result<CommandOutput, ExecError> {
    use aster_fem::fracture::theta3d::{
        front_abscissa, k_theta_fields, k_theta_legendre, legendre_nodal, node_bases,
        smooth_linear, theta0, virtual_front, FaceLoad, Front, KTheta, NodalData, SolidCell,
        Wanted,
    };
    let kw = &call.keywords;
    let cmd = "CALC_G";
    let theta_here = kw.keyword("THETA").map(|k| k.span).unwrap_or(call.span);
    // The options in the order given, once each (code_aster computes and
    // writes them in that order).
    let mut opts = options(kw);
    opts.dedup();
    let wanted = Wanted {
        g: opts.iter().any(|o| o == "G"),
        k: opts.iter().any(|o| o == "K"),
    };
    // DISCRETISATION='LEGENDRE': the degree (code_aster's default 5).
    let legendre = match theta_kw.str("DISCRETISATION") {
        Some("LEGENDRE") => Some(
            theta_kw
                .first("DEGRE")
                .and_then(|v| v.as_i64())
                .unwrap_or(5),
        ),
        _ => None,
    };
    if let Some(d) = legendre {
        if !(0..=7).contains(&d) {
            return Err(ex.kw_error(
                cmd,
                theta_kw,
                "DEGRE",
                format!("DEGRE = {d}: code_aster's Legendre polynomials are of degree 0 to 7"),
            ));
        }
    }
    // NB_POINT_FOND (`create_npf`): theta fields on a front of that many
    // points at equal abscissae; 0 is code_aster's default (the front's
    // nodes). The catalog allows it with DISCRETISATION='LINEAIRE' only.
    let npf = match theta_kw.first("NB_POINT_FOND").and_then(|v| v.as_i64()) {
        None | Some(0) => None,
        Some(n) if n < 2 => {
            return Err(ex.kw_error(
                cmd,
                theta_kw,
                "NB_POINT_FOND",
                format!("NB_POINT_FOND = {n}: two points at least"),
            ))
        }
        Some(n) => Some(n as usize),
    };
    let r = ex.required(cmd, kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let here = kw.keyword("RESULTAT").map(|k| k.span).unwrap_or(call.span);
    let Some(run) = result.fem.clone() else {
        return Err(ex.unsupported(
            "CALC_G on a result not computed in this run (its model and materials are needed)",
            here,
        ));
    };
    if run.plastic {
        return Err(ex.unsupported(
            "CALC_G on a result with plastic cells (aster computes K of linear elastic results only)",
            here,
        ));
    }
    let model = &run.model;
    let mesh = model.mesh();
    if mesh.dim != 3
        || mesh.node_count()
            < line
                .nodes
                .iter()
                .map(|n| n.0 as usize + 1)
                .max()
                .unwrap_or(0)
    {
        return Err(ex.unsupported(
            "CALC_G: the crack front and the result are not on the same 3D mesh",
            here,
        ));
    }
    // code_aster's `milieu`: quadratic lips give the middle nodes theta
    // fields of their own (SEG3 smoothing), unless NB_POINT_FOND.
    let milieu = line.quadratic_lips && npf.is_none() && legendre.is_none();
    if milieu && !line.quadratic {
        return Err(ex.unsupported(
            "CALC_G on a front of SEG2 cells between quadratic lips (code_aster's SEG3 smoothing reads a middle node per segment)",
            theta_here,
        ));
    }
    let nnof = npf.unwrap_or(line.nodes.len());
    if nnof == 3 && legendre.is_none() && !milieu {
        return Err(ex.unsupported(
            "CALC_G on a front of 3 points (code_aster's end correction of the theta fields reads the abscissa before the first point)",
            theta_here,
        ));
    }
    let hmax = line.size.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (r_inf, r_sup) = crown(ex, theta_kw, hmax)?;
    let coords: Vec<[f64; 3]> = line.nodes.iter().map(|&n| mesh.coord(n)).collect();
    let absfon = front_abscissa(&coords);
    let lonfis = absfon.last().copied().unwrap_or(0.0);
    let front = Front {
        coords: &coords,
        normal: &line.normal,
        dir: &line.dir,
        absc: &absfon,
        quadratic: line.quadratic,
    };
    let bases = node_bases(&front, &mesh.coords);
    // The points of the table and the bases theta is built from: the
    // front's nodes, or the NB_POINT_FOND points (named XXXXXXXX between
    // the ends, as code_aster).
    let virt = npf
        .map(|n| virtual_front(&front, n))
        .transpose()
        .map_err(|e| ex.unsupported(&format!("{cmd}: {e}"), theta_here))?;
    let (points, names, absfon, theta_bases) = match &virt {
        Some(v) => {
            let vf = Front {
                coords: &v.coords,
                normal: &v.normal,
                dir: &v.dir,
                absc: &v.absc,
                quadratic: false,
            };
            let names: Vec<Option<NodeId>> = (0..v.coords.len())
                .map(|i| match i {
                    0 => Some(line.nodes[0]),
                    i if i + 1 == v.coords.len() => line.nodes.last().copied(),
                    _ => None,
                })
                .collect();
            (
                v.coords.clone(),
                names,
                v.absc.clone(),
                node_bases(&vf, &mesh.coords),
            )
        }
        None => (
            coords.clone(),
            line.nodes.iter().map(|&n| Some(n)).collect(),
            absfon.clone(),
            bases.clone(),
        ),
    };
    let th0: Vec<f64> = mesh
        .coords
        .iter()
        .zip(&theta_bases)
        .map(|(&x, b)| theta0(b, x, r_inf, r_sup))
        .collect();
    let reached = |n: NodeId| th0[n.0 as usize] >= f64::EPSILON;
    // A pressure or a face force of real values on a face (te0147's term
    // of G) is computed; any other load theta reaches is refused.
    let on_face = |l: &Load| match l {
        Load::Pressure { cell, .. } | Load::SurfaceForce { cell, .. } => {
            mesh.cell(*cell).ty.dim() == 2 && !model.is_coque3d(*cell)
        }
        _ => false,
    };
    check_loads_but(ex, &run, &reached, &on_face, here)?;
    let mut cells = Vec::new();
    for el in model.elements() {
        let cell = mesh.cell(el.cell);
        let hit = cell.nodes.iter().any(|&n| reached(n));
        match &el.kind {
            ElementKind::Continuum {
                hypothesis,
                material,
            } if *hypothesis == aster_fem::Hypothesis::Solid3D => {
                if !hit {
                    continue;
                }
                if model.is_reduced(el.cell) || model.is_stabilised(el.cell) {
                    return Err(ex.unsupported(
                        &format!(
                            "CALC_G: cell {} is under-integrated (K with the full stiffness family only)",
                            mesh.cell_name(el.cell)
                        ),
                        here,
                    ));
                }
                cells.push(SolidCell {
                    cell: el.cell,
                    material: *material,
                });
            }
            // Skin cells without loads and discrete springs have no term.
            ElementKind::Boundary | ElementKind::Spring { .. } => {}
            _ if hit => {
                return Err(ex.unsupported(
                    &format!(
                        "CALC_G: theta reaches cell {}, not a 3D continuum cell",
                        mesh.cell_name(el.cell)
                    ),
                    here,
                ))
            }
            _ => {}
        }
    }
    let steps = super::post::select_steps(ex, cmd, kw, &result)?;
    for step in &steps {
        for c in &cells {
            if run
                .loads
                .free_strain_at(c.cell, step.inst)
                .map_err(|e| ExecError::new(format!("{cmd}: {e}")))?
                .is_some()
            {
                return Err(ex.unsupported(
                    &format!(
                        "CALC_G on a 3D front with a thermal strain on cell {} (te0222's thermal terms are not reproduced)",
                        mesh.cell_name(c.cell)
                    ),
                    here,
                ));
            }
        }
    }
    let mut columns = vec![
        col("NUME_ORDRE", ColumnType::Int),
        col("INST", ColumnType::Real),
        col("NOEUD", ColumnType::Text(8)),
        col("NUM_PT", ColumnType::Int),
    ];
    for c in ["COOR_X", "COOR_Y", "COOR_Z", "ABSC_CURV", "ABSC_CURV_NORM"] {
        columns.push(col(c, ColumnType::Real));
    }
    columns.push(col("COMPORTEMENT", ColumnType::Text(8)));
    for o in &opts {
        let names: &[&str] = if o == "G" {
            &["G"]
        } else {
            &["K1", "K2", "K3", "G_IRWIN"]
        };
        for c in names {
            columns.push(col(c, ColumnType::Real));
        }
    }
    // cgComporNodes: a result without a behaviour map (MECA_STATIQUE) is
    // ELAS at every point; otherwise the NB_POINT_FOND points between the
    // ends are XXXXXXXX (aster's results are elastic).
    let behaviour_map = result.typ != "evol_elas";
    let mut table = Table::new(columns);
    for step in steps {
        let u = displacement(&result, &run, step.nume_ordre, &r.name)?;
        let disp = nodal_displacement_3d(model, &u);
        let nodal = NodalData {
            bases: &bases,
            theta: &theta_bases,
            theta0: &th0,
            disp: &disp,
        };
        let mut faces = Vec::new();
        for item in &run.loads.items {
            let (cell, pressure, force) = match &item.load {
                l @ Load::Pressure { cell, pressure } if on_face(l) => (*cell, *pressure, [0.0; 3]),
                l @ Load::SurfaceForce { cell, force } if on_face(l) => (*cell, 0.0, *force),
                _ => continue,
            };
            if !mesh.cell(cell).nodes.iter().any(|&n| reached(n)) {
                continue;
            }
            let m = item
                .mult
                .eval(step.inst)
                .map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
            faces.push(FaceLoad {
                cell,
                pressure: pressure * m,
                force: force.map(|f| f * m),
            });
        }
        let values: Vec<KTheta> = match legendre {
            None => {
                let fields = k_theta_fields(mesh, &cells, &faces, &nodal, &absfon, wanted)
                    .map_err(|e| ex.unsupported(&format!("{cmd}: {e}"), here))?;
                smooth_linear(&absfon, &fields, milieu)
            }
            Some(d) => {
                let fields =
                    k_theta_legendre(mesh, &cells, &faces, &nodal, lonfis, d as usize, wanted)
                        .map_err(|e| ex.unsupported(&format!("{cmd}: {e}"), here))?;
                legendre_nodal(&absfon, lonfis, &fields)
            }
        }
        .map_err(|e| ex.unsupported(&format!("{cmd}: {e}"), theta_here))?;
        for (i, ki) in values.iter().enumerate() {
            let p = points[i];
            let (name, behaviour) = match names[i] {
                Some(n) => (mesh.node_name(n), "ELAS"),
                None if behaviour_map => ("XXXXXXXX".to_string(), "XXXXXXXX"),
                None => ("XXXXXXXX".to_string(), "ELAS"),
            };
            let mut row = vec![
                ("NUME_ORDRE", Value::Int(step.nume_ordre as i64)),
                ("INST", Value::Real(step.inst)),
                ("NOEUD", Value::Text(name)),
                ("NUM_PT", Value::Int(i as i64 + 1)),
                ("COOR_X", Value::Real(p[0])),
                ("COOR_Y", Value::Real(p[1])),
                ("COOR_Z", Value::Real(p[2])),
                ("ABSC_CURV", Value::Real(absfon[i])),
                ("ABSC_CURV_NORM", Value::Real(absfon[i] / lonfis)),
                ("COMPORTEMENT", Value::Text(behaviour.into())),
            ];
            for o in &opts {
                if o == "G" {
                    row.push(("G", Value::Real(ki.gth)));
                } else {
                    row.push(("K1", Value::Real(ki.k[0])));
                    row.push(("K2", Value::Real(ki.k[1])));
                    row.push(("K3", Value::Real(ki.k[2])));
                    row.push((
                        "G_IRWIN",
                        Value::Real(ki.g[0] * ki.g[0] + ki.g[1] * ki.g[1] + ki.g[2] * ki.g[2]),
                    ));
                }
            }
            table.push_row(row);
        }
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

/// Loads where theta is not zero enter code_aster's G and K (`te0096`,
/// `te0222`'s force terms, `te0282` on edges) and are not computed here:
/// refused. `reached`: whether theta is not zero at a node.
fn check_loads(
    ex: &Executor,
    run: &crate::fembridge::FemRun,
    reached: &dyn Fn(NodeId) -> bool,
    here: aster_syntax::Span,
) -> Result<(), ExecError> {
    check_loads_but(ex, run, reached, &|_| false, here)
}

/// [`check_loads`] but for the loads `computed` (their term of G is).
fn check_loads_but(
    ex: &Executor,
    run: &crate::fembridge::FemRun,
    reached: &dyn Fn(NodeId) -> bool,
    computed: &dyn Fn(&Load) -> bool,
    here: aster_syntax::Span,
) -> Result<(), ExecError> {
    let mesh = run.model.mesh();
    let on_cell = |c: aster_mesh::CellId| mesh.cell(c).nodes.iter().any(|&n| reached(n));
    for item in &run.loads.items {
        if computed(&item.load) {
            continue;
        }
        let hit = match &item.load {
            Load::SurfaceForce { cell, .. }
            | Load::Pressure { cell, .. }
            | Load::VolumeForce { cell, .. }
            | Load::SurfaceForceAt { cell, .. }
            | Load::PressureAt { cell, .. }
            | Load::VolumeForceAt { cell, .. }
            | Load::EdgeForce { cell, .. }
            | Load::ShellForce { cell, .. } => on_cell(*cell).then(|| mesh.cell_name(*cell)),
            Load::NodalForce { dof, .. } => {
                reached(dof.node).then(|| format!("node {}", mesh.node_name(dof.node)))
            }
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

const POST_K_OWN: &[&str] = &[
    "FOND_FISS",
    "RESULTAT",
    "ABSC_CURV_MAXI",
    "PREC_VIS_A_VIS",
    "NB_NOEUD_COUPE",
    "TYPE_MAILLAGE",
    "INFO",
    "TITRE",
];

/// What POST_K1_K2_K3 reads (`crate::support`): a meshed 3D crack
/// (`FOND_FISS`) on a regular mesh, and the step selection.
pub(crate) const POST_K1_K2_K3: Support = Support {
    values: &[Values::new("TYPE_MAILLAGE", &["REGLE"])
        .why("(LIBRE: the jumps read along cut lines by MACR_LIGN_COUPE): the lip nodes normal to the front only")],
    ..Support::keywords(&crate::support::joined::<
        _,
        { super::post::STEP_SELECTION.len() + POST_K_OWN.len() },
    >(super::post::STEP_SELECTION, POST_K_OWN))
};

/// `POST_K1_K2_K3(FOND_FISS, RESULTAT)` on a 3D front (aster-fem
/// `fracture::post_k`): one row per front node with enough lip nodes and
/// per instant, `FOND_FISS`, `NUME_FOND`, `INST`, `NUME_ORDRE`, `NOEUD`,
/// `NUM_PT`, `ABSC_CURV`, `K1`, `ERR_K1`, `K2`, `ERR_K2`, `K3`, `ERR_K3`,
/// `G`.
pub fn post_k1_k2_k3(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    use aster_fem::fracture::post_k::{k_at_node, keep_lip_nodes, LipPoint};
    let kw = &call.keywords;
    let cmd = "POST_K1_K2_K3";
    let front_ref = ex.required(cmd, kw, "FOND_FISS")?;
    let front = ex.crack_front(front_ref)?;
    let here = kw.keyword("FOND_FISS").map(|k| k.span).unwrap_or(call.span);
    let Some(line) = front.line.clone() else {
        return Err(ex.unsupported(
            "POST_K1_K2_K3 on a 2D crack tip (aster computes it on 3D fronts; CALC_G gives K in 2D)",
            here,
        ));
    };
    let r = ex.required(cmd, kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let Some(run) = result.fem.clone() else {
        return Err(ex.unsupported(
            "POST_K1_K2_K3 on a result not computed in this run (its model and materials are needed)",
            kw.keyword("RESULTAT").map(|k| k.span).unwrap_or(call.span),
        ));
    };
    let model = &run.model;
    let mesh = model.mesh();
    if ex.mesh_by_id(front.mesh)?.node_count() != mesh.node_count() {
        return Err(ex.unsupported(
            "POST_K1_K2_K3: the crack front and the result are not on the same mesh",
            here,
        ));
    }
    // The material at the front (code_aster's postkutil: the cells there).
    let mut material = None;
    for el in model.elements() {
        let cell = mesh.cell(el.cell);
        if !line.nodes.iter().any(|n| cell.nodes.contains(n)) {
            continue;
        }
        if let ElementKind::Continuum {
            hypothesis,
            material: m,
        } = &el.kind
        {
            if *hypothesis != aster_fem::Hypothesis::Solid3D {
                continue;
            }
            match material {
                None => material = Some(*m),
                Some(prev) if prev != *m => {
                    return Err(ex.unsupported(
                        "POST_K1_K2_K3: two materials along the crack front (aster reads one)",
                        here,
                    ))
                }
                _ => {}
            }
        }
    }
    let Some(material) = material else {
        return Err(ex.unsupported("POST_K1_K2_K3: no 3D elastic cell at the crack front", here));
    };
    let hmax = match kw.f64("ABSC_CURV_MAXI") {
        Some(h) => h,
        None => 4.0 * line.size.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    };
    let pvv = kw.f64("PREC_VIS_A_VIS").unwrap_or(0.1);
    // ABSC_CURV along the front (get_absfon).
    let mut absc = vec![0.0; line.nodes.len()];
    for i in 1..line.nodes.len() {
        let (a, b) = (mesh.coord(line.nodes[i - 1]), mesh.coord(line.nodes[i]));
        let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
        absc[i] = absc[i - 1] + d;
    }
    // The front nodes computed (get_noeud_a_calculer): on a mesh with a
    // quadratic cell (code_aster's `Mesh.isQuadratic`), every other one
    // from the first (the ends of a quadratic front's cells).
    let quadratic = mesh
        .cells
        .iter()
        .any(|c| c.nodes.len() > aster_fem::shape::corner_count(c.ty));
    let every = if quadratic { 2 } else { 1 };
    // The front nodes with enough lip nodes (get_noeuds_perp_regle).
    let coords = |ns: &[NodeId]| ns.iter().map(|&n| mesh.coord(n)).collect::<Vec<_>>();
    let mut kept = Vec::new();
    for (i, &n) in line.nodes.iter().enumerate().step_by(every) {
        let sup = &line.sup_normal[i];
        let inf = &line.inf_normal[i];
        if let Some((ks, ki)) = keep_lip_nodes(mesh.coord(n), &coords(sup), &coords(inf), hmax, pvv)
        {
            let pick = |l: &[NodeId], k: &[usize]| k.iter().map(|&j| l[j]).collect::<Vec<_>>();
            kept.push((i, pick(sup, &ks), pick(inf, &ki)));
        }
    }
    if kept.is_empty() {
        return Err(ExecError::new(format!(
            "{cmd}: no front node has 3 lip nodes on each lip within {hmax} (code_aster's RUPTURE0_30)"
        )));
    }
    let steps = super::post::select_steps(ex, cmd, kw, &result)?;
    let columns = vec![
        col("FOND_FISS", ColumnType::Text(8)),
        col("NUME_FOND", ColumnType::Int),
        col("INST", ColumnType::Real),
        col("NUME_ORDRE", ColumnType::Int),
        col("NOEUD", ColumnType::Text(8)),
        col("NUM_PT", ColumnType::Int),
        col("ABSC_CURV", ColumnType::Real),
        col("K1", ColumnType::Real),
        col("ERR_K1", ColumnType::Real),
        col("K2", ColumnType::Real),
        col("ERR_K2", ColumnType::Real),
        col("K3", ColumnType::Real),
        col("ERR_K3", ColumnType::Real),
        col("G", ColumnType::Real),
    ];
    let mut disps = Vec::new();
    for step in &steps {
        let u = displacement(&result, &run, step.nume_ordre, &r.name)?;
        disps.push(nodal_displacement_3d(model, &u));
    }
    let mut rows = Vec::new();
    for (num, (i, sup, inf)) in kept.iter().enumerate() {
        let node = line.nodes[*i];
        let pf = mesh.coord(node);
        for (step, disp) in steps.iter().zip(&disps) {
            let points = |ns: &[NodeId]| {
                let mut v: Vec<LipPoint> = ns
                    .iter()
                    .map(|&n| {
                        let p = mesh.coord(n);
                        let d = ((p[0] - pf[0]).powi(2)
                            + (p[1] - pf[1]).powi(2)
                            + (p[2] - pf[2]).powi(2))
                        .sqrt();
                        LipPoint {
                            r: d,
                            u: disp[n.0 as usize],
                        }
                    })
                    .collect();
                v.sort_by(|a, b| a.r.total_cmp(&b.r));
                v
            };
            let k = k_at_node(
                &points(sup),
                &points(inf),
                line.normal[*i],
                line.dir[*i],
                material,
            )
            .map_err(|e| ExecError::new(format!("{cmd}: node {}: {e}", mesh.node_name(node))))?;
            rows.push(vec![
                ("FOND_FISS", Value::Text(front_ref.name.clone())),
                ("NUME_FOND", Value::Int(1)),
                ("INST", Value::Real(step.inst)),
                ("NUME_ORDRE", Value::Int(step.nume_ordre as i64)),
                ("NOEUD", Value::Text(mesh.node_name(node))),
                ("NUM_PT", Value::Int(num as i64 + 1)),
                ("ABSC_CURV", Value::Real(absc[*i])),
                ("K1", Value::Real(k.k1)),
                ("ERR_K1", Value::Real(k.err[0])),
                ("K2", Value::Real(k.k2)),
                ("ERR_K2", Value::Real(k.err[1])),
                ("K3", Value::Real(k.k3)),
                ("ERR_K3", Value::Real(k.err[2])),
                ("G", Value::Real(k.g)),
            ]);
        }
    }
    if steps.len() != 1 {
        // CALC_TABLE TRI on (INST, ABSC_CURV), stable.
        let key = |row: &Vec<(&str, Value)>, name: &str| match row.iter().find(|(n, _)| *n == name)
        {
            Some((_, Value::Real(x))) => *x,
            _ => 0.0,
        };
        rows.sort_by(|a, b| {
            key(a, "INST")
                .total_cmp(&key(b, "INST"))
                .then(key(a, "ABSC_CURV").total_cmp(&key(b, "ABSC_CURV")))
        });
    }
    let mut table = Table::new(columns);
    for row in rows {
        table.push_row(row);
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

fn nodal_displacement_3d(model: &Model, u: &[f64]) -> Vec<[f64; 3]> {
    let dofs = model.dofs();
    (0..model.mesh().node_count())
        .map(|i| {
            let n = NodeId(i as u32);
            [
                dofs.value(u, Dof::new(n, Comp::DX)).unwrap_or(0.0),
                dofs.value(u, Dof::new(n, Comp::DY)).unwrap_or(0.0),
                dofs.value(u, Dof::new(n, Comp::DZ)).unwrap_or(0.0),
            ]
        })
        .collect()
}
