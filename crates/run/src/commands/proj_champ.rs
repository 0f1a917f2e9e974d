//! PROJ_CHAMP: nodal fields and results projected from one mesh onto
//! another by collocation (`METHODE='COLLOCATION'`, or `'AUTO'` which is
//! collocation for nodal fields), as code_aster's `op0166`/`pjefco`/`cnsprj`:
//! the keywords turned into the cells of mesh 1 and nodes of mesh 2 of each
//! `VIS_A_VIS` occurrence, handed to `aster_fem::projection`.

use crate::concept::{Concept, EvolResult, Step};
use crate::executor::{result_of, store_result, Executor};
use crate::field::{Field, NodalField};
use crate::support::{joined, Refusal, Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_fem::projection::{case_of, interpolate, Case, Correspondence, Options};
use aster_mesh::{CellId, Mesh, NodeId};
use std::collections::BTreeSet;
use std::rc::Rc;
use std::sync::Arc;

const KEYWORDS: &[&str] = &[
    "PROJECTION",
    "METHODE",
    "CHAM_GD",
    "RESULTAT",
    "MODELE_1",
    "MAILLAGE_1",
    "MODELE_2",
    "MAILLAGE_2",
    "CAS_FIGURE",
    "DISTANCE_MAX",
    "DISTANCE_ALARME",
    "ALARME",
    "PROL_VALE",
    "INFO",
    "TITRE",
    "TRANSF_GEOM_1",
    "TRANSF_GEOM_2",
    "NOM_CHAM",
    "TOUT_CHAM",
    "VIS_A_VIS",
    "VIS_A_VIS/TOUT_1",
    "VIS_A_VIS/GROUP_MA_1",
    "VIS_A_VIS/MAILLE_1",
    "VIS_A_VIS/TOUT_2",
    "VIS_A_VIS/GROUP_MA_2",
    "VIS_A_VIS/MAILLE_2",
    "VIS_A_VIS/GROUP_NO_2",
    "VIS_A_VIS/NOEUD_2",
    "VIS_A_VIS/CAS_FIGURE",
    "VIS_A_VIS/TRANSF_GEOM_1",
    "VIS_A_VIS/TRANSF_GEOM_2",
];

/// What PROJ_CHAMP reads (`crate::support`).
pub(crate) const PROJ_CHAMP: Support = Support {
    values: &[
        Values::listed("METHODE", &["AUTO", "COLLOCATION"])
            .why("(nodal fields by collocation only; ECLA_PG, SOUS_POINT and NUAGE_DEG_* are not implemented)"),
        Values::new("PROJECTION", &["OUI"]),
        Values::listed("CAS_FIGURE", &["2D", "3D", "2.5D"])
            .why("(1.5D, segments, is not implemented)"),
        Values::listed("VIS_A_VIS/CAS_FIGURE", &["2D", "3D", "2.5D"])
            .why("(1.5D and 0D are not implemented)"),
    ],
    hints: &[
        (
            "VIS_A_VIS/GROUP_NO_1",
            "code_aster locates the nodes in the cells of GROUP_MA_1/MAILLE_1/TOUT_1 only",
        ),
        (
            "TYPE_CHAM",
            "it converts element fields, which are not projected yet",
        ),
        (
            "NUME_DDL",
            "the projected fields are numbered by their own values",
        ),
    ],
    reuse: false,
    rules: Some(rules),
    ..Support::keywords(&joined::<_, { KEYWORDS.len() + crate::commands::post::STEP_SELECTION.len() }>(
        KEYWORDS,
        crate::commands::post::STEP_SELECTION,
    ))
};

/// Without RESULTAT nor CHAM_GD, PROJ_CHAMP only makes a correspondence
/// (`corresp_2_mailla`), which nothing reads yet.
fn rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    if !kw.contains("RESULTAT") && !kw.contains("CHAM_GD") {
        out.push(Refusal {
            what: "PROJ_CHAMP without RESULTAT or CHAM_GD (a correspondence concept, corresp_2_mailla)".into(),
            span: call.span,
        });
    }
}

/// One side of the projection: a mesh and, with a model, its cells.
struct Side {
    mesh_id: u32,
    mesh: Arc<Mesh>,
    /// The model's cells (`None`: a mesh, every cell).
    cells: Option<BTreeSet<CellId>>,
}

fn side(ex: &Executor, kw: &Keywords, n: u8) -> Result<Side, ExecError> {
    if let Some(m) = kw.concept(&format!("MAILLAGE_{n}")) {
        return Ok(Side {
            mesh_id: m.id,
            mesh: ex.mesh(m)?,
            cells: None,
        });
    }
    let name = format!("MODELE_{n}");
    let Some(m) = kw.concept(&name) else {
        return Err(ExecError::new(format!(
            "PROJ_CHAMP: give MAILLAGE_{n} or MODELE_{n}"
        )));
    };
    let (mesh_id, cells) = match ex.concept(m)? {
        Concept::Model(d) => (d.mesh, d.cells.keys().copied().collect()),
        Concept::ThermalModel(t) => (t.mesh, t.cells.clone()),
        _ => return Err(ex.kw_error("PROJ_CHAMP", kw, &name, "a model is expected")),
    };
    Ok(Side {
        mesh_id,
        mesh: ex.mesh_by_id(mesh_id)?,
        cells: Some(cells),
    })
}

impl Side {
    fn has(&self, c: CellId) -> bool {
        self.cells.as_ref().is_none_or(|s| s.contains(&c))
    }

    /// The nodes of the model's cells (code_aster's `NOEUD_UTIL`); every
    /// node for a mesh.
    fn used_nodes(&self) -> Vec<bool> {
        match &self.cells {
            None => vec![true; self.mesh.node_count()],
            Some(cells) => {
                let mut used = vec![false; self.mesh.node_count()];
                for &c in cells {
                    for n in &self.mesh.cell(c).nodes {
                        used[n.0 as usize] = true;
                    }
                }
                used
            }
        }
    }
}

/// The cells of `GROUP_MA_<n>`/`MAILLE_<n>`/`TOUT_<n>` of an occurrence.
fn occurrence_cells(
    ex: &Executor,
    occ: &Keywords,
    mesh: &Mesh,
    n: u8,
) -> Result<Vec<CellId>, ExecError> {
    if occ.str(&format!("TOUT_{n}")) == Some("OUI") {
        return Ok((0..mesh.cells.len() as u32).map(CellId).collect());
    }
    let mut out = Vec::new();
    let mut seen = BTreeSet::new();
    let cmd = "PROJ_CHAMP/VIS_A_VIS";
    let group_kw = format!("GROUP_MA_{n}");
    for g in occ.simple(&group_kw).iter().filter_map(|s| s.as_str()) {
        let cells =
            crate::select::group_ma(mesh, g).map_err(|e| ex.kw_error(cmd, occ, &group_kw, e))?;
        for &c in cells {
            if seen.insert(c) {
                out.push(c);
            }
        }
    }
    let cell_kw = format!("MAILLE_{n}");
    for m in occ.simple(&cell_kw).iter().filter_map(|s| s.as_str()) {
        let c =
            crate::select::cell_named(mesh, m).map_err(|e| ex.kw_error(cmd, occ, &cell_kw, e))?;
        if seen.insert(c) {
            out.push(c);
        }
    }
    Ok(out)
}

/// `pjeftg`: the mesh with its coordinates mapped by `TRANSF_GEOM_<n>` of
/// `kw` (2 or 3 functions of X, Y, Z; 2 only in the 2D case, z then 0).
/// The mesh itself without the keyword.
fn transformed(
    ex: &Executor,
    kw: &Keywords,
    n: u8,
    mesh: &Arc<Mesh>,
    case: Case,
) -> Result<Arc<Mesh>, ExecError> {
    let name = format!("TRANSF_GEOM_{n}");
    let funcs: Vec<_> = kw
        .simple(&name)
        .iter()
        .filter_map(|s| s.as_concept())
        .map(|c| ex.function(c))
        .collect::<Result<_, _>>()?;
    if funcs.is_empty() {
        return Ok(mesh.clone());
    }
    if funcs.len() == 2 && case != Case::Plane {
        return Err(ex
            .kw_error(
                "PROJ_CHAMP",
                kw,
                &name,
                format!("2 functions are for the 2D case only, here {}", case.name()),
            )
            .with_id("PROJECTION4_4"));
    }
    let mut out = (**mesh).clone();
    for c in out.coords.iter_mut() {
        let args = [("X", c[0]), ("Y", c[1]), ("Z", c[2])];
        let mut v = [0.0; 3];
        for (k, f) in funcs.iter().enumerate() {
            v[k] = f
                .eval_named(&args)
                .map_err(|e| ex.kw_error("PROJ_CHAMP", kw, &name, e.to_string()))?;
        }
        *c = v;
    }
    Ok(Arc::new(out))
}

fn parse_case(s: &str) -> Option<Case> {
    match s {
        "2D" => Some(Case::Plane),
        "3D" => Some(Case::Volume),
        "2.5D" => Some(Case::Surface),
        _ => None,
    }
}

/// The case of a set of cells (`pjefca`), or a refusal located at `name`.
fn case_or_refuse(
    ex: &Executor,
    kw: &Keywords,
    name: &str,
    forced: Option<&str>,
    mesh: &Mesh,
    cells: &[CellId],
) -> Result<Case, ExecError> {
    if let Some(c) = forced.and_then(parse_case) {
        return Ok(c);
    }
    case_of(mesh, cells).ok_or_else(|| {
        let span = kw.keyword(name).map(|k| k.span).unwrap_or_default();
        ex.unsupported(
            "PROJ_CHAMP from segments or points only (CAS_FIGURE='1.5D')",
            span,
        )
    })
}

/// The correspondence of the whole command (`pjefco`).
fn correspondence(
    ex: &Executor,
    call: &CommandCall,
    one: &Side,
    two: &Side,
) -> Result<Correspondence, ExecError> {
    let kw = &call.keywords;
    let options = Options {
        distance_max: kw.f64("DISTANCE_MAX"),
        distance_alarme: kw.f64("DISTANCE_ALARME"),
    };
    let mut corr = Correspondence::new(&two.mesh, options);
    let used2 = two.used_nodes();
    let proj_err = |e: aster_fem::projection::ProjectionError| {
        ExecError::new(format!("PROJ_CHAMP: {}", e.message)).with_id(e.id)
    };
    let occurrences = kw.factor("VIS_A_VIS");
    if occurrences.is_empty() {
        let cells1: Vec<CellId> = (0..one.mesh.cells.len() as u32)
            .map(CellId)
            .filter(|&c| one.has(c))
            .collect();
        let case = case_or_refuse(
            ex,
            kw,
            "CAS_FIGURE",
            kw.str("CAS_FIGURE"),
            &one.mesh,
            &cells1,
        )?;
        let nodes2: Vec<NodeId> = (0..two.mesh.node_count() as u32)
            .map(NodeId)
            .filter(|n| used2[n.0 as usize])
            .collect();
        if nodes2.is_empty() {
            return Err(
                ExecError::new("PROJ_CHAMP: no node of mesh 2 to project onto")
                    .with_id("PROJECTION4_54"),
            );
        }
        let m1 = transformed(ex, kw, 1, &one.mesh, case)?;
        let m2 = transformed(ex, kw, 2, &two.mesh, case)?;
        corr.add(&m1, &cells1, &m2, &nodes2, case)
            .map_err(proj_err)?;
        return Ok(corr);
    }
    for n in ["TRANSF_GEOM_1", "TRANSF_GEOM_2"] {
        if kw.contains(n) {
            return Err(ex
                .kw_error(
                    "PROJ_CHAMP",
                    kw,
                    n,
                    "with VIS_A_VIS, give the transformation in each occurrence",
                )
                .with_id("PROJECTION4_3"));
        }
    }
    for occ in occurrences {
        // pjefca takes the case from the occurrence's cells; pjxxut then
        // keeps those of the model.
        let named1 = occurrence_cells(ex, occ, &one.mesh, 1)?;
        let cells1: Vec<CellId> = named1.iter().copied().filter(|&c| one.has(c)).collect();
        let cells2 = occurrence_cells(ex, occ, &two.mesh, 2)?;
        // The nodes of mesh 2: those of the GROUP_MA_2 cells of their own
        // dimension (pjxxu2), and GROUP_NO_2/NOEUD_2.
        let mut nodes2 = vec![false; two.mesh.node_count()];
        if !cells2.is_empty() {
            let case2 = case_or_refuse(ex, occ, "GROUP_MA_2", None, &two.mesh, &cells2)?;
            for &c in &cells2 {
                let cell = two.mesh.cell(c);
                if case2.accepts(cell.ty) {
                    for n in &cell.nodes {
                        nodes2[n.0 as usize] = true;
                    }
                }
            }
        }
        for g in occ.simple("GROUP_NO_2").iter().filter_map(|s| s.as_str()) {
            let members = crate::select::group_no(&two.mesh, g)
                .map_err(|e| ex.kw_error("PROJ_CHAMP/VIS_A_VIS", occ, "GROUP_NO_2", e))?;
            for n in members {
                nodes2[n.0 as usize] = true;
            }
        }
        for name in occ.simple("NOEUD_2").iter().filter_map(|s| s.as_str()) {
            let n = crate::select::node_named(&two.mesh, name)
                .map_err(|e| ex.kw_error("PROJ_CHAMP/VIS_A_VIS", occ, "NOEUD_2", e))?;
            nodes2[n.0 as usize] = true;
        }
        let nodes2: Vec<NodeId> = (0..two.mesh.node_count() as u32)
            .map(NodeId)
            .filter(|n| nodes2[n.0 as usize] && used2[n.0 as usize])
            .collect();
        if nodes2.is_empty() {
            return Err(ex
                .kw_error(
                    "PROJ_CHAMP",
                    kw,
                    "VIS_A_VIS",
                    "an occurrence selects no node of mesh 2",
                )
                .with_id("PROJECTION4_54"));
        }
        let case1 = case_or_refuse(
            ex,
            occ,
            "GROUP_MA_1",
            occ.str("CAS_FIGURE"),
            &one.mesh,
            &named1,
        )?;
        // pjeftg: mesh 1 moved in its own case, mesh 2 in that of its cells.
        let case2 = case_of(&two.mesh, &cells2).unwrap_or(case1);
        let m1 = transformed(ex, occ, 1, &one.mesh, case1)?;
        let m2 = transformed(ex, occ, 2, &two.mesh, case2)?;
        corr.add(&m1, &cells1, &m2, &nodes2, case1)
            .map_err(proj_err)?;
    }
    Ok(corr)
}

/// A nodal field of mesh 1 projected on mesh 2 (`cnsprj`, then `cnscno`
/// with `PROL_VALE`: every node of mesh 2 gets the value for each component
/// it lacks).
pub(crate) fn project_field(
    f: &NodalField,
    corr: &Correspondence,
    node_count2: usize,
    prol: Option<f64>,
) -> NodalField {
    let mut out = NodalField::new(f.components().to_vec());
    let nc = f.components().len();
    for i in 0..node_count2 {
        let mut vals = vec![None; nc];
        if let Some(link) = &corr.links[i] {
            for (c, v) in vals.iter_mut().enumerate() {
                *v = interpolate(link, |n| f.get_at(n, c));
            }
        }
        if let Some(p) = prol {
            for v in vals.iter_mut() {
                v.get_or_insert(p);
            }
        }
        if vals.iter().any(|v| v.is_some()) {
            out.insert(NodeId(i as u32), vals);
        }
    }
    out
}

fn refuse_element_field(ex: &Executor, kw: &Keywords, name: &str, what: &str) -> ExecError {
    let span = kw.keyword(name).map(|k| k.span).unwrap_or_default();
    ex.unsupported(
        &format!(
            "PROJ_CHAMP of an element field ({what}: METHODE='ECLA_PG'/'COLLOCATION' on cham_elem)"
        ),
        span,
    )
}

pub fn proj_champ(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let one = side(ex, kw, 1)?;
    let two = side(ex, kw, 2)?;
    let prol = kw.f64("PROL_VALE");
    if let Some(c) = kw.concept("CHAM_GD") {
        let field = ex.field(c)?;
        let Field::Nodal(f) = &*field else {
            return Err(refuse_element_field(ex, kw, "CHAM_GD", &c.name));
        };
        if let Some(&m) = ex.field_meshes.get(&c.id) {
            if m != one.mesh_id {
                return Err(ex.kw_error(
                    "PROJ_CHAMP",
                    kw,
                    "CHAM_GD",
                    "the field does not live on MAILLAGE_1/MODELE_1's mesh (CALCULEL4_59)",
                ));
            }
        }
        let corr = correspondence(ex, call, &one, &two)?;
        let out = project_field(f, &corr, two.mesh.node_count(), prol);
        let id = result_of(call)?.id;
        ex.field_meshes.insert(id, two.mesh_id);
        ex.field_origin.remove(&id);
        match ex.field_quantity.get(&c.id).cloned() {
            Some(q) => ex.field_quantity.insert(id, q),
            None => ex.field_quantity.remove(&id),
        };
        return store_result(ex, call, Concept::Field(Rc::new(Field::Nodal(out))));
    }
    let r = ex.required("PROJ_CHAMP", kw, "RESULTAT")?.clone();
    let result = ex.result(&r)?;
    if result.mesh != one.mesh_id {
        return Err(ex.kw_error(
            "PROJ_CHAMP",
            kw,
            "RESULTAT",
            "the result does not live on MAILLAGE_1/MODELE_1's mesh",
        ));
    }
    let names: Vec<&str> = kw
        .simple("NOM_CHAM")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let steps = crate::commands::post::select_steps(ex, "PROJ_CHAMP", kw, &result)?;
    if steps.is_empty() {
        return Err(ex
            .kw_error("PROJ_CHAMP", kw, "RESULTAT", "no step selected")
            .with_id("CALCULEL4_62"));
    }
    // Every field to project must be nodal (checked before any work).
    for s in &steps {
        for (name, f) in s.fields.iter() {
            let wanted = names.is_empty() || names.contains(&name.as_str());
            if wanted && !matches!(f, Field::Nodal(_)) {
                let at = if names.is_empty() {
                    "RESULTAT"
                } else {
                    "NOM_CHAM"
                };
                return Err(refuse_element_field(ex, kw, at, name));
            }
        }
    }
    for n in &names {
        if !steps.iter().any(|s| s.fields.contains_key(n)) {
            return Err(ex.kw_error(
                "PROJ_CHAMP",
                kw,
                "NOM_CHAM",
                format!("the result has no field {n} at the selected steps (CALCULEL4_64)"),
            ));
        }
    }
    let corr = correspondence(ex, call, &one, &two)?;
    let n2 = two.mesh.node_count();
    let out_steps: Vec<Step> = steps
        .iter()
        .map(|s| Step {
            nume_ordre: s.nume_ordre,
            inst: s.inst,
            fields: s
                .fields
                .iter()
                .filter(|(name, _)| names.is_empty() || names.contains(&name.as_str()))
                .filter_map(|(name, f)| match f {
                    Field::Nodal(f) => Some((
                        name.clone(),
                        Field::Nodal(project_field(f, &corr, n2, prol)),
                    )),
                    Field::Elem(_) => None,
                })
                .collect(),
        })
        .collect();
    let projected = EvolResult {
        prep_varc: false,
        typ: result.typ.clone(),
        mesh: two.mesh_id,
        steps: out_steps,
        fem: None,
        tables: Vec::new(),
        modal: None,
        cases: None,
        thermal: None,
    };
    store_result(ex, call, Concept::Result(Rc::new(projected)))
}
