//! MACR_LIGN_COUPE: a result's values along cut lines, as code_aster 17's
//! macro (`macr_lign_coupe_ops.py`) computes them: the lines' mesh,
//! PROJ_CHAMP onto it, POST_RELEVE_T along it. Step by step:
//!
//! 1. a mesh of SEG2 cells is written in ASTER text format
//!    (`crea_mail_lig_coup`: `NB_POINTS` nodes evenly spaced from
//!    `COOR_ORIG` to `COOR_EXTR`, the nodes of a `GROUP_NO` in its order, or
//!    the points of an `ARC`; coordinates printed `%21.14E` and read back),
//!    one cell group `LICOU<k>` per line (named after the group for
//!    `GROUP_NO`) and a node group of the same name;
//! 2. the fields are projected on its nodes by collocation
//!    (`PROJ_CHAMP(METHODE='COLLOCATION', DISTANCE_MAX=…)`, the smallest
//!    positive `DISTANCE_MAX` of the occurrences, else 0: a node outside the
//!    model's cells gets no value);
//! 3. for a `SEGMENT` or an `ARC`, only the nodes that got a value are kept,
//!    in their order (`crea_grp_matiere`: group `LICOF<k>`);
//! 4. `REPERE='LOCAL'` (a `SEGMENT`: x along the line, y from `VECT_Y`) and
//!    `'UTILISATEUR'` (`ANGL_NAUT`) turn `DEPL`, `SIGM_NOEU` and `FLUX_NOEU`
//!    into that frame (`MODI_REPERE`, through the nautical angles as the
//!    macro does); `'POLAIRE'` is `POST_RELEVE_T`'s own;
//! 5. `POST_RELEVE_T(ACTION=…)` on those nodes, one action per line, and the
//!    table without its `RESU` and `NOEUD` columns.
//!
//! Steps 2 and 5 run aster's own PROJ_CHAMP correspondence and POST_RELEVE_T
//! (the latter on a call built here, each keyword keeping the span of the
//! user's keyword it comes from, so that its messages point into the file).

use crate::commands::post::{select_steps, STEP_SELECTION};
use crate::commands::proj_champ::project_field;
use crate::concept::{Concept, EvolResult, Step};
use crate::executor::{result_of, store_result, Executor};
use crate::field::{Field, NodalField};
use crate::support::{joined, Refusal, Support, Values};
use aster_eval::{
    CommandCall, CommandOutput, ConceptRef, ExecError, Keyword, Keywords, KwValue, Scalar,
};
use aster_fem::projection::{case_of, Correspondence, Options};
use aster_mesh::{CellId, Group, Mesh, NodeId};
use aster_syntax::Span;
use std::rc::Rc;
use std::sync::Arc;

const KEYWORDS: &[&str] = &[
    "RESULTAT",
    "CHAM_GD",
    "NOM_CHAM",
    "MODELE",
    "UNITE_MAILLAGE",
    "VIS_A_VIS",
    "VIS_A_VIS/GROUP_MA_1",
    "VIS_A_VIS/MAILLE_1",
    "LIGN_COUPE",
    "LIGN_COUPE/INTITULE",
    "LIGN_COUPE/TYPE",
    "LIGN_COUPE/REPERE",
    "LIGN_COUPE/OPERATION",
    "LIGN_COUPE/NOM_CMP",
    "LIGN_COUPE/RESULTANTE",
    "LIGN_COUPE/GROUP_NO",
    "LIGN_COUPE/VECT_Y",
    "LIGN_COUPE/ANGL_NAUT",
    "LIGN_COUPE/NB_POINTS",
    "LIGN_COUPE/COOR_ORIG",
    "LIGN_COUPE/COOR_EXTR",
    "LIGN_COUPE/GROUP_NO_ORIG",
    "LIGN_COUPE/GROUP_NO_EXTR",
    "LIGN_COUPE/CENTRE",
    "LIGN_COUPE/ANGLE",
    "LIGN_COUPE/DNOR",
    "LIGN_COUPE/DISTANCE_MAX",
    "LIGN_COUPE/DISTANCE_ALARME",
];

/// What MACR_LIGN_COUPE reads (`crate::support`).
pub(crate) const MACR_LIGN_COUPE: Support = Support {
    values: &[
        Values::listed("LIGN_COUPE/TYPE", &["SEGMENT", "GROUP_NO", "ARC"]).why(
            "(TYPE='GROUP_MA' orders the cells' nodes by DEFI_GROUP's OPTION='NOEUD_ORDO', not implemented)",
        ),
        Values::listed(
            "LIGN_COUPE/REPERE",
            &["GLOBAL", "LOCAL", "POLAIRE", "UTILISATEUR"],
        )
        .why("(MODI_REPERE's cylindrical frame is not implemented)"),
        Values::new("LIGN_COUPE/OPERATION", &["EXTRACTION", "MOYENNE"]),
    ],
    hints: &[
        (
            "LIGN_COUPE/INVARIANT",
            "POST_RELEVE_T's invariants are not computed",
        ),
        (
            "LIGN_COUPE/ELEM_PRINCIPAUX",
            "POST_RELEVE_T's principal values are not computed",
        ),
        (
            "LIGN_COUPE/TRAC_NOR",
            "POST_RELEVE_T's tractions are not computed",
        ),
        (
            "LIGN_COUPE/TRAC_DIR",
            "POST_RELEVE_T's tractions are not computed",
        ),
        (
            "LIGN_COUPE/MOMENT",
            "POST_RELEVE_T's moments of a resultant are not computed",
        ),
        ("NUME_MODE", "modal results are not read here"),
    ],
    reuse: false,
    rules: Some(rules),
    ..Support::keywords(&joined::<_, { KEYWORDS.len() + STEP_SELECTION.len() }>(
        KEYWORDS,
        STEP_SELECTION,
    ))
};

/// Whether a field name is an element field (`SIGM_ELNO`, `EPSI_ELGA`…).
fn element_field(name: &str) -> bool {
    ["_ELNO", "_ELGA", "_ELEM"]
        .iter()
        .any(|s| name.ends_with(s))
}

/// The combinations the tables cannot say.
fn rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    if let Some(name) = kw.str("NOM_CHAM").filter(|n| element_field(n)) {
        out.push(Refusal::at(
            format!("MACR_LIGN_COUPE/NOM_CHAM='{name}' (an element field: its projection on the cut line, PROJ_CHAMP of a cham_elem, is not implemented; the nodal field, e.g. SIGM_NOEU from CALC_CHAMP, is)"),
            kw,
            "NOM_CHAM",
            call.span,
        ));
    }
    for occ in kw.factor("LIGN_COUPE") {
        let repere = occ.str("REPERE").unwrap_or("GLOBAL");
        if occ.str("OPERATION") == Some("MOYENNE") && repere == "POLAIRE" {
            out.push(Refusal::at(
                "MACR_LIGN_COUPE/LIGN_COUPE/REPERE='POLAIRE' with OPERATION='MOYENNE'".into(),
                occ,
                "REPERE",
                call.span,
            ));
        }
    }
}

/// One cut line, as the macro reads it.
enum Path {
    Segment {
        orig: Vec<f64>,
        extr: Vec<f64>,
        points: usize,
    },
    /// The group's name and its nodes' coordinates, in its order.
    Group { name: String, points: Vec<[f64; 3]> },
    Arc {
        orig: Vec<f64>,
        centre: Vec<f64>,
        points: usize,
        angle: f64,
        dnor: Vec<f64>,
    },
}

/// `%21.14E`, as the macro writes coordinates.
fn e14(x: f64) -> String {
    crate::pyfmt::c_exp(x, 21, 14)
}

/// `crea_noeu_lig_coup`: the point of an arc at `angle` degrees.
fn arc_point(dim: usize, orig: &[f64], centre: &[f64], angle: f64, dnor: &[f64]) -> Vec<f64> {
    let a = orig[0] - centre[0];
    let b = orig[1] - centre[1];
    let r = angle * std::f64::consts::PI / 180.0;
    if dim == 2 {
        return vec![
            centre[0] + a * r.cos() - b * r.sin(),
            centre[1] + b * r.cos() + a * r.sin(),
        ];
    }
    let c = orig[2] - centre[2];
    let (d1, d2, d3) = (dnor[0], dnor[1], dnor[2]);
    let d = (d1 * d1 + d2 * d2 + d3 * d3).sqrt();
    vec![
        centre[0] + a * r.cos() + r.sin() * (c * d2 - b * d3) / d,
        centre[1] + b * r.cos() + r.sin() * (a * d3 - c * d1) / d,
        centre[2] + c * r.cos() + r.sin() * (b * d1 - a * d2) / d,
    ]
}

/// The line mesh's text (`crea_mail_lig_coup`), and per arc its angles.
/// Lines come first, then groups, then arcs, as the macro numbers them; the
/// cell groups are `LICOU<k>` (lines and arcs, counted together) and the
/// groups' own names.
fn line_mesh_text(dim: usize, paths: &[Path]) -> (String, Vec<Vec<f64>>) {
    let mut out = vec!["TITRE".to_string(), "FINSF".into(), format!("COOR_{dim}D")];
    let coords = |p: &[f64]| -> String {
        p[..dim]
            .iter()
            .map(|&x| e14(x))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut nbno = 0;
    let mut counts = Vec::new();
    let mut angles = Vec::new();
    let order = |p: &Path| match p {
        Path::Segment { .. } => 0,
        Path::Group { .. } => 1,
        Path::Arc { .. } => 2,
    };
    let mut sorted: Vec<&Path> = paths.iter().collect();
    sorted.sort_by_key(|p| order(p));
    for p in &sorted {
        let pts: Vec<Vec<f64>> = match p {
            Path::Segment { orig, extr, points } => (0..*points)
                .map(|j| {
                    (0..dim)
                        .map(|k| orig[k] + j as f64 * (extr[k] - orig[k]) / (*points - 1) as f64)
                        .collect()
                })
                .collect(),
            Path::Group { points, .. } => points.iter().map(|p| p.to_vec()).collect(),
            Path::Arc {
                orig,
                centre,
                points,
                angle,
                dnor,
            } => {
                let full = (angle - 360.0).abs() < 1e-8;
                let nbpt = if full { points + 1 } else { *points };
                let list: Vec<f64> = (0..*points)
                    .map(|j| j as f64 * angle / (nbpt - 1) as f64)
                    .collect();
                let pts = list
                    .iter()
                    .map(|&a| arc_point(dim, orig, centre, a, dnor))
                    .collect();
                angles.push(list);
                pts
            }
        };
        for q in &pts {
            nbno += 1;
            out.push(format!("N{nbno} {}", coords(q)));
        }
        counts.push(pts.len());
    }
    out.push("FINSF".into());
    // Cells: consecutive nodes; a full circle closes on its first node.
    let mut nbma = 0;
    let mut first = 1;
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    let mut licou = 0;
    for (p, &n) in sorted.iter().zip(&counts) {
        out.push("SEG2".into());
        let mut cells = Vec::new();
        for j in 0..n.saturating_sub(1) {
            nbma += 1;
            out.push(format!("M{nbma} N{} N{}", first + j, first + j + 1));
            cells.push(nbma);
        }
        if let Path::Arc { angle, .. } = p {
            if (angle - 360.0).abs() < 1e-8 {
                nbma += 1;
                out.push(format!("M{nbma} N{} N{first}", first + n - 1));
                cells.push(nbma);
            }
        }
        out.push("FINSF".into());
        let name = match p {
            Path::Group { name, .. } => name.clone(),
            _ => {
                licou += 1;
                format!("LICOU{licou}")
            }
        };
        groups.push((name, cells));
        first += n;
    }
    for (name, cells) in &groups {
        out.push("GROUP_MA".into());
        out.push(format!("  {name}"));
        for c in cells {
            out.push(format!("  M{c}"));
        }
        out.push(String::new());
        out.push("FINSF".into());
    }
    out.push("FIN".into());
    out.push(String::new());
    (out.join("\n"), angles)
}

/// DEFI_GROUP(CREA_GROUP_NO=_F(GROUP_MA=name)) on the line mesh: the nodes
/// of the group's cells, in the cells' order.
fn node_group_of_cells(mesh: &mut Mesh, name: &str, new_name: &str) {
    let Some(cells) = mesh.group_ma(name).map(|g| g.members.clone()) else {
        return;
    };
    let mut members: Vec<NodeId> = Vec::new();
    for c in cells {
        for &n in &mesh.cell(c).nodes {
            if !members.contains(&n) {
                members.push(n);
            }
        }
    }
    mesh.groups_no.retain(|g| g.name != new_name);
    mesh.groups_no.push(Group {
        name: new_name.to_string(),
        members,
    });
}

/// code_aster's `matrot`: the rotation from the global frame to the one of
/// nautical angles (degrees) α, β, γ; rows are the local axes.
fn matrot(angles: [f64; 3]) -> [[f64; 3]; 3] {
    aster_fem::orthotropic::matrot(angles.map(|d| d * std::f64::consts::PI / 180.0))
}

/// The nautical angles of a SEGMENT's local frame (`crea_resu_local`):
/// x along the line, y from `VECT_Y` (made orthogonal when it is not).
fn local_angles(
    dim: usize,
    orig: &[f64],
    extr: &[f64],
    vect_y: &[f64],
) -> Result<[f64; 3], String> {
    let epsi = 1e-8;
    let comp = |v: &[f64], k: usize| {
        if k < dim {
            v.get(k).copied().unwrap_or(0.0)
        } else {
            0.0
        }
    };
    let mut cx = [0.0; 3];
    for (k, c) in cx.iter_mut().enumerate() {
        *c = comp(extr, k) - comp(orig, k);
    }
    let nx = (cx[0] * cx[0] + cx[1] * cx[1] + cx[2] * cx[2]).sqrt();
    if nx.abs() < epsi {
        return Err("the line's ends coincide (POST0_1)".into());
    }
    cx = cx.map(|c| c / nx);
    if vect_y.is_empty() {
        return Err("REPERE='LOCAL' needs VECT_Y (POST0_50)".into());
    }
    let mut cy = [comp(vect_y, 0), comp(vect_y, 1), comp(vect_y, 2)];
    let ny = (cy[0] * cy[0] + cy[1] * cy[1] + cy[2] * cy[2]).sqrt();
    if ny.abs() < epsi {
        return Err("VECT_Y is zero (POST0_2)".into());
    }
    cy = cy.map(|c| c / ny);
    let same = (0..3).all(|k| (cx[k] - cy[k]).abs() < epsi);
    let opposite = (0..3).all(|k| (cx[k] + cy[k]).abs() < epsi);
    if same || opposite {
        return Err("VECT_Y is along the line (POST0_3)".into());
    }
    let cross = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let mut cz = cross(cx, cy);
    if (cx[0] * cy[0] + cx[1] * cy[1] + cx[2] * cy[2]).abs() > epsi {
        let nz = (cz[0] * cz[0] + cz[1] * cz[1] + cz[2] * cz[2]).sqrt();
        cz = cz.map(|c| c / nz);
        cy = cross(cz, cx);
        let ny = (cy[0] * cy[0] + cy[1] * cy[1] + cy[2] * cy[2]).sqrt();
        cy = cy.map(|c| c / ny);
    }
    Ok(nautical(dim, cx, cy, cz))
}

/// The nautical angles (degrees) of the frame (x, y, z), as the macro
/// computes them before `MODI_REPERE`.
fn nautical(dim: usize, cx: [f64; 3], cy: [f64; 3], cz: [f64; 3]) -> [f64; 3] {
    let epsi = 1e-8;
    let (alpha, beta, gamma) = if dim == 2 {
        (cx[1].atan2(cx[0]), 0.0, 0.0)
    } else if cx[0] * cx[0] + cx[1] * cx[1] > epsi {
        (cx[1].atan2(cx[0]), -cx[2].asin(), cy[2].atan2(cz[2]))
    } else {
        ((-cy[0]).atan2(cy[1]), -cx[2].asin(), 0.0)
    };
    let deg = 180.0 / std::f64::consts::PI;
    [alpha * deg, beta * deg, gamma * deg]
}

/// `crea_resu_local` for a group with `REPERE='LOCAL'`: at each node of the
/// path's cells, x along the path (the sum of its cells' vectors, then
/// normalised; in 3D the macro takes each vector's z as z2 − z2, i.e. 0,
/// reproduced), y normal to it (2D: x turned by 90 degrees; 3D: `VECT_Y`
/// made orthogonal to x by two cross products).
fn group_frames(
    line: &Mesh,
    group: &str,
    dim: usize,
    vect_y: &[f64],
) -> Result<std::collections::BTreeMap<NodeId, [f64; 3]>, String> {
    let cells = crate::select::group_ma(line, group)?;
    let mut tangent: std::collections::BTreeMap<NodeId, Vec<[f64; 3]>> = Default::default();
    for &c in cells {
        let nodes = &line.cell(c).nodes;
        let (a, b) = (line.coord(nodes[0]), line.coord(nodes[1]));
        let u = [b[0] - a[0], b[1] - a[1], 0.0];
        for n in [nodes[0], nodes[1]] {
            tangent.entry(n).or_default().push(u);
        }
    }
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let mut out = std::collections::BTreeMap::new();
    for (n, vs) in tangent {
        let mut t = vs[0];
        if vs.len() == 2 {
            t = [t[0] + vs[1][0], t[1] + vs[1][1], t[2] + vs[1][2]];
        }
        let nt = norm(t);
        if nt == 0.0 {
            return Err(format!(
                "the path folds back on itself at node {}",
                line.node_name(n)
            ));
        }
        let t = t.map(|c| c / nt);
        let angles = if dim == 2 {
            nautical(2, t, [-t[1], t[0], 0.0], [0.0, 0.0, 1.0])
        } else {
            if vect_y.len() < 3 {
                return Err("REPERE='LOCAL' on a group in 3D needs VECT_Y".into());
            }
            let ny = norm([vect_y[0], vect_y[1], vect_y[2]]);
            let y0 = [vect_y[0] / ny, vect_y[1] / ny, vect_y[2] / ny];
            let mut z = [
                t[1] * y0[2] - t[2] * y0[1],
                t[2] * y0[0] - t[0] * y0[2],
                t[0] * y0[1] - t[1] * y0[0],
            ];
            let nz = norm(z);
            if nz == 0.0 {
                return Err("VECT_Y is along the path".into());
            }
            z = z.map(|c| c / nz);
            let mut y = [
                z[1] * t[2] - z[2] * t[1],
                z[2] * t[0] - z[0] * t[2],
                z[0] * t[1] - z[1] * t[0],
            ];
            let ny = norm(y);
            y = y.map(|c| c / ny);
            nautical(3, t, y, z)
        };
        out.insert(n, angles);
    }
    Ok(out)
}

/// `MODI_REPERE(REPERE='UTILISATEUR')` of a nodal field with the rotation
/// `p` (rows: local axes): the vector components (DX DY DZ or FLUX FLUY
/// FLUZ) and the symmetric tensor ones (SIXX … SIYZ); in 2D only the
/// in-plane ones turn (SIZZ stays).
fn rotated(
    f: &NodalField,
    frame: impl Fn(NodeId) -> Option<[[f64; 3]; 3]>,
    dim: usize,
) -> NodalField {
    let mut out = f.clone();
    let idx = |c: &str| f.component_index(c);
    let vectors = [["DX", "DY", "DZ"], ["FLUX", "FLUY", "FLUZ"]];
    let tensor = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"].map(idx);
    for (node, orig) in f.iter() {
        let Some(p) = frame(node) else {
            continue;
        };
        let get = |i: Option<usize>| i.and_then(|i| orig.get(i)).unwrap_or(0.0);
        for names in &vectors {
            let ids = names.map(idx);
            if ids[0].is_none() || ids[1].is_none() {
                continue;
            }
            let u = ids.map(get);
            for (r, id) in ids.iter().enumerate().take(dim) {
                if let Some(i) = id {
                    out.set_at(node, *i, Some((0..dim).map(|k| p[r][k] * u[k]).sum()));
                }
            }
        }
        if tensor[0].is_some() && tensor[1].is_some() {
            let [xx, yy, zz, xy, xz, yz] = tensor.map(get);
            let s = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
            let n = dim;
            let rot = |a: usize, b: usize| -> f64 {
                let mut v = 0.0;
                for i in 0..n {
                    for j in 0..n {
                        v += p[a][i] * s[i][j] * p[b][j];
                    }
                }
                v
            };
            let new = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
            for (slot, (a, b)) in tensor.iter().zip(new) {
                if let Some(i) = slot {
                    if a < n && b < n {
                        out.set_at(node, *i, Some(rot(a, b)));
                    }
                }
            }
        }
    }
    out
}

/// The rotation of each node (`None`: the global frame there).
type FrameOf = Box<dyn Fn(NodeId) -> Option<[[f64; 3]; 3]>>;

/// Temporary concepts of one macro call: ids above those the program uses.
const TEMP_MESH: u32 = u32::MAX - 1;
const TEMP_RESULT_BASE: u32 = u32::MAX - 64;
const TEMP_TABLE: u32 = u32::MAX - 2;

fn simple(name: &str, values: Vec<Scalar>, span: Span) -> Keyword {
    Keyword {
        name: name.into(),
        value: KwValue::Simple(values),
        span,
        defaulted: false,
    }
}

fn reals(kw: &Keywords, name: &str) -> Vec<f64> {
    kw.simple(name).iter().filter_map(|s| s.as_f64()).collect()
}

pub fn macr_lign_coupe(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    const CMD: &str = "MACR_LIGN_COUPE";
    let kw = &call.keywords;
    let name = result_of(call)?.name.clone();
    // The result and the field's name; a CHAM_GD becomes a one-step result
    // (CREA_RESU(OPERATION='AFFE', INST=0) in the macro).
    let (result, nom_cham, source_name) = if let Some(r) = kw.concept("RESULTAT") {
        let result = ex.result(r)?;
        let nom = kw.str("NOM_CHAM").unwrap_or("SIGM_NOEU").to_string();
        (result, nom, r.name.clone())
    } else if let Some(c) = kw.concept("CHAM_GD") {
        let model = kw.concept("MODELE").ok_or_else(|| {
            ex.kw_error(
                CMD,
                kw,
                "CHAM_GD",
                "MODELE is required with CHAM_GD (POST0_10)",
            )
        })?;
        let mesh_id = match ex.concept(model)? {
            Concept::Model(d) => d.mesh,
            Concept::ThermalModel(t) => t.mesh,
            _ => return Err(ex.kw_error(CMD, kw, "MODELE", "a model is expected")),
        };
        let field = ex.field(c)?;
        let quantity = ex.field_quantity.get(&c.id).cloned().unwrap_or_default();
        let default = match quantity.get(..6).unwrap_or("") {
            "TEMP_R" => Some("TEMP"),
            "DEPL_R" | "SIEF_R" => Some("DEPL"),
            "NEUT_R" => Some("NEUT"),
            _ => None,
        };
        let nom = kw.str("NOM_CHAM").or(default).ok_or_else(|| {
            ex.kw_error(
                CMD,
                kw,
                "CHAM_GD",
                "give NOM_CHAM: the field's quantity is not known",
            )
        })?;
        let typ = if quantity.starts_with("TEMP") {
            "EVOL_THER"
        } else {
            "EVOL_ELAS"
        };
        let step = Step {
            nume_ordre: 1,
            inst: 0.0,
            fields: [(nom.to_string(), (*field).clone())].into_iter().collect(),
        };
        let result = Rc::new(EvolResult {
            prep_varc: false,
            typ: typ.to_string(),
            mesh: mesh_id,
            steps: vec![step],
            fem: None,
            tables: Vec::new(),
            modal: None,
            cases: None,
            thermal: None,
        });
        (result, nom.to_string(), c.name.clone())
    } else {
        return Err(ExecError::new(format!("{CMD}: give RESULTAT or CHAM_GD")));
    };
    if element_field(&nom_cham) {
        let span = kw.keyword("NOM_CHAM").map(|k| k.span).unwrap_or(call.span);
        return Err(ex.unsupported(
            &format!("{CMD}/NOM_CHAM='{nom_cham}' (an element field: PROJ_CHAMP of a cham_elem is not implemented)"),
            span,
        ));
    }
    let mesh = ex.mesh_by_id(result.mesh)?;
    let dim = mesh.dim as usize;
    // The cells projected from: the model's (MODELE, else the result's), else
    // every cell; VIS_A_VIS keeps those of its groups.
    let mut cells1: Vec<CellId> = if let Some(m) = kw.concept("MODELE") {
        match ex.concept(m)? {
            Concept::Model(d) => d.cells.keys().copied().collect(),
            Concept::ThermalModel(t) => t.cells.iter().copied().collect(),
            _ => return Err(ex.kw_error(CMD, kw, "MODELE", "a model is expected")),
        }
    } else if let Some(fem) = &result.fem {
        let mut c: Vec<CellId> = fem.model.elements().iter().map(|e| e.cell).collect();
        c.sort();
        c.dedup();
        c
    } else {
        (0..mesh.cells.len() as u32).map(CellId).collect()
    };
    let vav = kw.factor("VIS_A_VIS");
    if !vav.is_empty() {
        let mut keep = std::collections::BTreeSet::new();
        for occ in vav {
            for g in occ.simple("GROUP_MA_1").iter().filter_map(|s| s.as_str()) {
                let cells = crate::select::group_ma(&mesh, g)
                    .map_err(|e| ex.kw_error("MACR_LIGN_COUPE/VIS_A_VIS", occ, "GROUP_MA_1", e))?;
                keep.extend(cells.iter().copied());
            }
            for m in occ.simple("MAILLE_1").iter().filter_map(|s| s.as_str()) {
                let c = crate::select::cell_named(&mesh, m)
                    .map_err(|e| ex.kw_error("MACR_LIGN_COUPE/VIS_A_VIS", occ, "MAILLE_1", e))?;
                keep.insert(c);
            }
        }
        cells1.retain(|c| keep.contains(c));
    }

    // The paths.
    let lines = kw.factor("LIGN_COUPE");
    let mut paths = Vec::new();
    let coor = |occ: &Keywords, end: &str| -> Result<Vec<f64>, ExecError> {
        let gkw = format!("GROUP_NO_{end}");
        if let Some(g) = occ.str(&gkw) {
            let nodes = crate::select::group_no(&mesh, g)
                .map_err(|e| ex.kw_error("MACR_LIGN_COUPE/LIGN_COUPE", occ, &gkw, e))?;
            let [n] = nodes else {
                return Err(ex.kw_error(
                    "MACR_LIGN_COUPE/LIGN_COUPE",
                    occ,
                    &gkw,
                    format!(
                        "the group `{g}` has {} nodes, one is expected (POST0_27)",
                        nodes.len()
                    ),
                ));
            };
            return Ok(mesh.coord(*n).to_vec());
        }
        Ok(reals(occ, &format!("COOR_{end}")))
    };
    for occ in lines {
        let ty = occ.str("TYPE").unwrap_or("SEGMENT");
        let path = match ty {
            "SEGMENT" => {
                let orig = coor(occ, "ORIG")?;
                let extr = coor(occ, "EXTR")?;
                if orig.len().min(extr.len()) < dim {
                    return Err(ex.kw_error(
                        "MACR_LIGN_COUPE/LIGN_COUPE",
                        occ,
                        "COOR_ORIG",
                        format!("the coordinates must have the mesh's {dim} components (POST0_11)"),
                    ));
                }
                let points = occ
                    .first("NB_POINTS")
                    .and_then(|v| v.as_i64())
                    .unwrap_or(2)
                    .max(2) as usize;
                Path::Segment { orig, extr, points }
            }
            "ARC" => {
                let orig = reals(occ, "COOR_ORIG");
                let centre = reals(occ, "CENTRE");
                if orig.len().min(centre.len()) < dim {
                    return Err(ex.kw_error(
                        "MACR_LIGN_COUPE/LIGN_COUPE",
                        occ,
                        "COOR_ORIG",
                        format!("the coordinates must have the mesh's {dim} components (POST0_11)"),
                    ));
                }
                let dnor = reals(occ, "DNOR");
                if dim == 3 && dnor.len() < 3 {
                    return Err(ex.kw_error(
                        "MACR_LIGN_COUPE/LIGN_COUPE",
                        occ,
                        "DNOR",
                        "an ARC in 3D needs DNOR (POST0_12)",
                    ));
                }
                let r2: f64 = (0..dim).map(|k| (orig[k] - centre[k]).powi(2)).sum();
                if r2.sqrt() < 1e-8 {
                    return Err(ex.kw_error(
                        "MACR_LIGN_COUPE/LIGN_COUPE",
                        occ,
                        "CENTRE",
                        "the arc's radius is zero (POST0_6)",
                    ));
                }
                let points = occ
                    .first("NB_POINTS")
                    .and_then(|v| v.as_i64())
                    .unwrap_or(2)
                    .max(2) as usize;
                let angle = occ.f64("ANGLE").unwrap_or(0.0);
                Path::Arc {
                    orig,
                    centre,
                    points,
                    angle,
                    dnor,
                }
            }
            "GROUP_NO" => {
                let g = occ.str("GROUP_NO").unwrap_or("");
                let nodes = crate::select::group_no(&mesh, g)
                    .map_err(|e| ex.kw_error("MACR_LIGN_COUPE/LIGN_COUPE", occ, "GROUP_NO", e))?;
                Path::Group {
                    name: g.to_string(),
                    points: nodes.iter().map(|&n| mesh.coord(n)).collect(),
                }
            }
            other => {
                let span = occ.keyword("TYPE").map(|k| k.span).unwrap_or(call.span);
                return Err(ex.unsupported(&format!("{CMD}/LIGN_COUPE/TYPE='{other}'"), span));
            }
        };
        paths.push(path);
    }
    let arcs = paths.iter().any(|p| matches!(p, Path::Arc { .. }));
    if arcs && paths.iter().any(|p| !matches!(p, Path::Arc { .. })) {
        return Err(ex.kw_error(
            CMD,
            kw,
            "LIGN_COUPE",
            "arcs cannot be mixed with segments or groups (POST0_16)",
        ));
    }

    // 1. The line mesh, written and read back as the macro does.
    let (text, angles) = line_mesh_text(dim, &paths);
    if let Some(unit) = kw.first("UNITE_MAILLAGE").and_then(|v| v.as_i64()) {
        let path = ex.output_path(unit);
        std::fs::write(&path, &text)
            .map_err(|e| ExecError::new(format!("{CMD}: cannot write {}: {e}", path.display())))?;
    }
    let mut line = aster_mesh::parse_mail(&text, std::path::Path::new("macr_lign_coupe.mail"))
        .map_err(|e| ExecError::new(format!("{CMD}: the cut-line mesh: {e}")))?;
    let group_names: Vec<String> = line.groups_ma.iter().map(|g| g.name.clone()).collect();
    for g in &group_names {
        node_group_of_cells(&mut line, g, g);
    }

    // 2. The projection (PROJ_CHAMP by collocation on the line's nodes).
    // The macro's rule: the smallest value given (a zero counts as not
    // given, Python's truthiness), else 0.
    let smallest_given = |k: &str| -> f64 {
        lines
            .iter()
            .filter_map(|o| o.f64(k))
            .filter(|&d| d != 0.0)
            .reduce(f64::min)
            .unwrap_or(0.0)
    };
    let options = Options {
        distance_max: Some(smallest_given("DISTANCE_MAX")),
        distance_alarme: Some(smallest_given("DISTANCE_ALARME")),
    };
    let case = case_of(&mesh, &cells1)
        .ok_or_else(|| ex.kw_error(CMD, kw, "RESULTAT", "the model has no cell to project from"))?;
    let nodes2: Vec<NodeId> = (0..line.node_count() as u32).map(NodeId).collect();
    let mut corr = Correspondence::new(&line, options);
    corr.add(&mesh, &cells1, &line, &nodes2, case)
        .map_err(|e| ExecError::new(format!("{CMD}: {}", e.message)).with_id(e.id))?;
    let steps = select_steps(ex, CMD, kw, &result)?;
    if steps.is_empty() {
        return Err(ex.kw_error(CMD, kw, "RESULTAT", "no step selected"));
    }
    if !steps.iter().any(|s| s.fields.contains_key(&nom_cham)) {
        return Err(ex.kw_error(
            CMD,
            kw,
            if kw.contains("NOM_CHAM") {
                "NOM_CHAM"
            } else {
                "RESULTAT"
            },
            format!("the result `{source_name}` has no field {nom_cham} at the selected steps"),
        ));
    }
    let n2 = line.node_count();
    let projected_steps: Vec<Step> = steps
        .iter()
        .filter_map(|s| {
            let f = s.fields.get(&nom_cham)?;
            let Field::Nodal(f) = f else {
                return None;
            };
            Some(Step {
                nume_ordre: s.nume_ordre,
                inst: s.inst,
                fields: [(
                    nom_cham.clone(),
                    Field::Nodal(project_field(f, &corr, n2, None)),
                )]
                .into_iter()
                .collect(),
            })
        })
        .collect();
    if projected_steps.is_empty() {
        return Err(ex.unsupported(
            &format!("{CMD}/NOM_CHAM='{nom_cham}' (an element field in this result)"),
            kw.keyword("NOM_CHAM").map(|k| k.span).unwrap_or(call.span),
        ));
    }

    // 3. The nodes in the matter, per SEGMENT/ARC (LICOF<k>).
    let mut licof = 0;
    let mut action_groups = Vec::new();
    for (occ, p) in lines.iter().zip(&paths) {
        match p {
            Path::Group { name, .. } => action_groups.push(name.clone()),
            _ => {
                licof += 1;
                let from = format!("LICOU{licof}");
                let to = format!("LICOF{licof}");
                let members = crate::select::group_no(&line, &from)
                    .unwrap_or(&[])
                    .to_vec();
                let Some(first) = projected_steps[0].fields.get(&nom_cham) else {
                    continue;
                };
                let Field::Nodal(f) = first else {
                    continue;
                };
                let wanted: Vec<usize> =
                    match occ.simple("NOM_CMP").first().and_then(|s| s.as_str()) {
                        Some(c) => f.component_index(c).into_iter().collect(),
                        None => (0..f.components().len()).collect(),
                    };
                let kept: Vec<NodeId> = members
                    .into_iter()
                    .filter(|n| wanted.iter().any(|&i| f.get_at(*n, i).is_some()))
                    .collect();
                if kept.is_empty() {
                    let span = occ
                        .keyword("COOR_ORIG")
                        .or(occ.keyword("CENTRE"))
                        .map(|k| k.span)
                        .unwrap_or(call.span);
                    let loc = ex
                        .location(span)
                        .map(|l| format!(" ({l})"))
                        .unwrap_or_default();
                    return Err(ExecError::new(format!(
                        "{CMD}/LIGN_COUPE: no point of cut line {licof} lies in the model's cells{loc}"
                    )));
                }
                line.groups_no.push(Group {
                    name: to.clone(),
                    members: kept,
                });
                action_groups.push(to);
            }
        }
    }

    // 4. Frames, and the temporary concepts.
    let line = Arc::new(line);
    ex.insert(
        &ConceptRef {
            name: "__macou".into(),
            id: TEMP_MESH,
            typ: "maillage_sdaster".into(),
        },
        Concept::Mesh(line.clone()),
    );
    let mut temps = vec![TEMP_MESH, TEMP_TABLE];
    let rotating = ["DEPL", "SIGM_NOEU", "FLUX_NOEU"].contains(&nom_cham.as_str());
    let mut actions = Vec::new();
    let mut ioc2 = 0;
    for (k, (occ, p)) in lines.iter().zip(&paths).enumerate() {
        let repere = occ.str("REPERE").unwrap_or("GLOBAL");
        let mut steps = projected_steps.clone();
        // The frame of each node (None: the global one).
        let flat = |mut a: [f64; 3]| {
            if dim == 2 {
                a[1] = 0.0;
                a[2] = 0.0;
            }
            matrot(a)
        };
        let frames: Option<FrameOf> = match (repere, p) {
            (_, Path::Arc { .. }) if ["LOCAL", "UTILISATEUR"].contains(&repere) => {
                return Err(ex.kw_error(
                    "MACR_LIGN_COUPE/LIGN_COUPE",
                    occ,
                    "REPERE",
                    format!("an ARC takes REPERE='GLOBAL', 'POLAIRE' or 'CYLINDRIQUE', not '{repere}' (POST0_5)"),
                ));
            }
            _ if !rotating => None,
            ("LOCAL", Path::Segment { orig, extr, .. }) => {
                let a = local_angles(dim, orig, extr, &reals(occ, "VECT_Y"))
                    .map_err(|e| ex.kw_error("MACR_LIGN_COUPE/LIGN_COUPE", occ, "REPERE", e))?;
                let p = flat(a);
                Some(Box::new(move |_| Some(p)))
            }
            ("LOCAL", Path::Group { name, .. }) => {
                let angles = group_frames(&line, name, dim, &reals(occ, "VECT_Y"))
                    .map_err(|e| ex.kw_error("MACR_LIGN_COUPE/LIGN_COUPE", occ, "REPERE", e))?;
                let per_node: std::collections::BTreeMap<NodeId, [[f64; 3]; 3]> =
                    angles.into_iter().map(|(n, a)| (n, flat(a))).collect();
                Some(Box::new(move |n| per_node.get(&n).copied()))
            }
            ("UTILISATEUR", _) => {
                let a = reals(occ, "ANGL_NAUT");
                let p = flat([
                    a.first().copied().unwrap_or(0.0),
                    a.get(1).copied().unwrap_or(0.0),
                    a.get(2).copied().unwrap_or(0.0),
                ]);
                Some(Box::new(move |_| Some(p)))
            }
            _ => None,
        };
        if let Some(frame) = &frames {
            for s in steps.iter_mut() {
                for f in s.fields.values_mut() {
                    if let Field::Nodal(n) = f {
                        *n = rotated(n, frame, dim);
                    }
                }
            }
        }
        let id = TEMP_RESULT_BASE + k as u32;
        temps.push(id);
        let res_ref = ConceptRef {
            name: "__recou".into(),
            id,
            typ: result.typ.to_lowercase(),
        };
        ex.insert(
            &res_ref,
            Concept::Result(Rc::new(EvolResult {
                prep_varc: false,
                typ: result.typ.clone(),
                mesh: TEMP_MESH,
                steps,
                fem: None,
                tables: Vec::new(),
                modal: None,
                cases: None,
                thermal: None,
            })),
        );
        // The action, each keyword at the span of the user's one.
        let at = |name: &str| occ.keyword(name).map(|k| k.span).unwrap_or(call.span);
        if !matches!(p, Path::Group { .. }) {
            ioc2 += 1;
        }
        let intitule = match (occ.str("INTITULE"), p) {
            (Some(t), _) => t.to_string(),
            (None, Path::Group { name, .. }) => name.clone(),
            (None, _) => format!("l.coupe{ioc2}"),
        };
        let mut e = vec![
            simple("INTITULE", vec![Scalar::Str(intitule)], at("INTITULE")),
            simple("RESULTAT", vec![Scalar::Concept(res_ref)], call.span),
            simple("NOM_CHAM", vec![Scalar::Str(nom_cham.clone())], at("TYPE")),
            simple(
                "GROUP_NO",
                vec![Scalar::Str(action_groups[k].clone())],
                at("TYPE"),
            ),
            simple(
                "OPERATION",
                vec![Scalar::Str(
                    occ.str("OPERATION").unwrap_or("EXTRACTION").into(),
                )],
                at("OPERATION"),
            ),
        ];
        if occ.contains("NOM_CMP") {
            e.push(simple(
                "NOM_CMP",
                occ.simple("NOM_CMP").to_vec(),
                at("NOM_CMP"),
            ));
        } else if occ.contains("RESULTANTE") {
            e.push(simple(
                "RESULTANTE",
                occ.simple("RESULTANTE").to_vec(),
                at("RESULTANTE"),
            ));
        } else {
            e.push(simple(
                "TOUT_CMP",
                vec![Scalar::Str("OUI".into())],
                call.span,
            ));
        }
        if repere == "POLAIRE" {
            e.push(simple(
                "REPERE",
                vec![Scalar::Str("POLAIRE".into())],
                at("REPERE"),
            ));
        }
        actions.push(Keywords { entries: e });
    }
    let table_ref = ConceptRef {
        name: "__tabitm".into(),
        id: TEMP_TABLE,
        typ: "table_sdaster".into(),
    };
    let post = CommandCall {
        command: "POST_RELEVE_T".into(),
        result: Some(table_ref.clone()),
        reuse: None,
        keywords: Keywords {
            entries: vec![Keyword {
                name: "ACTION".into(),
                value: KwValue::Factor(actions),
                span: call.span,
                defaulted: false,
            }],
        },
        span: call.span,
    };
    let ran = crate::commands::post::post_releve_t(ex, &post);
    let table = ran.and_then(|_| ex.table(&table_ref));
    for id in temps {
        ex.remove(id);
    }
    let mut table = (*table?).clone();

    // 5. The table without RESU and NOEUD; arcs get their angles.
    let keep: Vec<usize> = (0..table.columns.len())
        .filter(|&c| !["RESU", "NOEUD"].contains(&table.columns[c].name.as_str()))
        .collect();
    table.keep_columns(&keep);
    if !angles.is_empty() && table.column_index("ABSC_CURV").is_some() {
        // The macro's ANGLE column: the arcs' angles repeated per step.
        let mut column = Vec::new();
        let per_arc: usize = angles.iter().map(Vec::len).sum();
        let steps = table.rows.len().checked_div(per_arc).unwrap_or(0);
        for a in &angles {
            for _ in 0..steps {
                column.extend(a.iter().copied());
            }
        }
        let c = table.ensure_column("ANGLE", crate::table::ColumnType::Real);
        for (row, v) in table.rows.iter_mut().zip(column) {
            row[c] = Some(crate::table::Value::Real(v));
        }
    }
    table.title = crate::commands::post::table_title(&name);
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_segment_mesh_is_written_as_the_macro_writes_it() {
        let (text, angles) = line_mesh_text(
            2,
            &[Path::Segment {
                orig: vec![0.0, 0.0],
                extr: vec![1.0, 0.5],
                points: 3,
            }],
        );
        assert!(angles.is_empty());
        let expected = "TITRE\nFINSF\nCOOR_2D\n\
N1  0.00000000000000E+00  0.00000000000000E+00\n\
N2  5.00000000000000E-01  2.50000000000000E-01\n\
N3  1.00000000000000E+00  5.00000000000000E-01\n\
FINSF\nSEG2\nM1 N1 N2\nM2 N2 N3\nFINSF\nGROUP_MA\n  LICOU1\n  M1\n  M2\n\nFINSF\nFIN\n";
        assert_eq!(text, expected);
        let mut mesh = aster_mesh::parse_mail(&text, std::path::Path::new("t.mail")).unwrap();
        node_group_of_cells(&mut mesh, "LICOU1", "LICOU1");
        let g = mesh.group_no("LICOU1").unwrap();
        assert_eq!(g.members, vec![NodeId(0), NodeId(1), NodeId(2)]);
    }

    #[test]
    fn a_full_circle_closes_on_its_first_node() {
        let (text, angles) = line_mesh_text(
            2,
            &[Path::Arc {
                orig: vec![1.0, 0.0],
                centre: vec![0.0, 0.0],
                points: 4,
                angle: 360.0,
                dnor: vec![],
            }],
        );
        assert_eq!(angles, vec![vec![0.0, 90.0, 180.0, 270.0]]);
        let mesh = aster_mesh::parse_mail(&text, std::path::Path::new("t.mail")).unwrap();
        assert_eq!(mesh.cells.len(), 4);
        assert_eq!(mesh.cell(CellId(3)).nodes, vec![NodeId(3), NodeId(0)]);
        let p = mesh.coord(NodeId(1));
        assert!((p[0] - 0.0).abs() < 1e-14 && (p[1] - 1.0).abs() < 1e-14);
    }

    #[test]
    fn the_local_frame_of_a_segment_turns_x_onto_the_line() {
        // 2D: a line at 30 degrees.
        let a = local_angles(2, &[0.0, 0.0], &[3f64.sqrt(), 1.0], &[0.0, 1.0]).unwrap();
        assert!((a[0] - 30.0).abs() < 1e-12);
        // 3D: x along (1, 1, 1)/√3, y from VECT_Y = z made orthogonal.
        let a = local_angles(3, &[0.0; 3], &[1.0, 1.0, 1.0], &[0.0, 0.0, 1.0]).unwrap();
        let p = matrot(a);
        let s = 1.0 / 3f64.sqrt();
        for k in 0..3 {
            assert!((p[0][k] - s).abs() < 1e-12, "{p:?}");
        }
        // y is orthogonal to x and in the plane of x and z.
        let dot: f64 = (0..3).map(|k| p[0][k] * p[1][k]).sum();
        assert!(dot.abs() < 1e-12);
        assert!((p[1][0] - p[1][1]).abs() < 1e-12 && p[1][2] > 0.0);
        assert!(local_angles(2, &[0.0, 0.0], &[1.0, 0.0], &[2.0, 0.0]).is_err());
    }

    #[test]
    fn a_rotation_turns_vectors_and_tensors() {
        let mut f = NodalField::new(
            ["DX", "DY", "SIXX", "SIYY", "SIZZ", "SIXY"]
                .map(String::from)
                .to_vec(),
        );
        f.insert(
            NodeId(0),
            vec![
                Some(1.0),
                Some(0.0),
                Some(1.0),
                Some(0.0),
                Some(5.0),
                Some(0.0),
            ],
        );
        let p = matrot([90.0, 0.0, 0.0]);
        let r = rotated(&f, |_| Some(p), 2);
        let v: Vec<Option<f64>> = r.node(NodeId(0)).unwrap().iter().collect();
        // x' = y: the global x vector has components (0, -1) in the turned frame.
        assert!(v[0].unwrap().abs() < 1e-15 && (v[1].unwrap() + 1.0).abs() < 1e-15);
        // σ = e_x ⊗ e_x becomes e_y' ⊗ e_y'; σzz stays.
        assert!(v[2].unwrap().abs() < 1e-15 && (v[3].unwrap() - 1.0).abs() < 1e-15);
        assert_eq!(v[4], Some(5.0));
        assert!(v[5].unwrap().abs() < 1e-15);
    }
}
